//! θ(φ) of a run under any model: the exact push model's trajectory, the carried motion's
//! pieces (each one closed-form rule on the exact obstacles), or a stepped program's driven
//! angle at each step.

use contact::{Mesh, Trajectory};

/// How the driven gear followed the driver over one stretch of the carried motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rule {
    /// Carried at the nominal ratio from (φ, θ): θ + (N1/N2)(φ' − φ).
    Carried {
        /// Driver angle the carrying started at.
        phi: f64,
        /// Driven angle there.
        theta: f64,
    },
    /// Pushed by a driver tooth behind: θ is the upper end of the (driver, driven) pair's
    /// obstacle.
    Pushed(i64, i64),
    /// Held back by a driver tooth ahead: θ is the lower end of the pair's obstacle.
    HeldBack(i64, i64),
    /// Jammed with no free position: θ stays.
    Stuck(f64),
}

/// One stretch of the carried motion, `phi_start` to `phi_end`, under one rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// First driver angle.
    pub phi_start: f64,
    /// Last driver angle.
    pub phi_end: f64,
    /// The rule.
    pub rule: Rule,
}

/// The driven angle along a run.
#[derive(Debug, Clone)]
pub enum Path {
    /// The exact push model's trajectory.
    Exact(Box<Trajectory>),
    /// The exact push model's trajectory of the other gear driving, read back in the listed
    /// driver's terms: the listed driven gear's angle turned by the run is that trajectory's
    /// driver angle, and the listed driver's its driven angle. θ(φ) is the largest input angle
    /// at which the trajectory has reached φ (bisection on a non-decreasing function).
    Inverse(Box<Trajectory>),
    /// The carried motion: its pieces, each exact on the mesh's obstacles.
    Carried {
        /// The mesh, whose obstacles the pieces read.
        mesh: Box<Mesh>,
        /// The pieces, in order of driver angle.
        pieces: Vec<Piece>,
    },
    /// A stepped program: (driver angle, driven angle) after each step, from the start, joined
    /// by straight lines (the program knows nothing between its steps).
    Steps(Vec<(f64, f64)>),
    /// One path up to a driver angle, another after it.
    Joined {
        /// The path before `until`.
        first: Box<Path>,
        /// Where the second takes over.
        until: f64,
        /// The path from `until` on.
        then: Box<Path>,
    },
}

impl Path {
    /// Driven angle at driver angle φ (clamped to the run).
    pub fn theta_at(&self, phi: f64) -> f64 {
        match self {
            Path::Exact(t) => t.theta_at(phi),
            Path::Inverse(t) => inverse_at(t, phi),
            Path::Carried { mesh, pieces } => carried_at(mesh, pieces, phi),
            Path::Steps(steps) => steps_at(steps, phi),
            Path::Joined { first, until, then } => {
                if phi < *until {
                    first.theta_at(phi)
                } else {
                    then.theta_at(phi)
                }
            }
        }
    }

    /// First and last driver angle of the run.
    pub fn phi_range(&self) -> (f64, f64) {
        match self {
            Path::Exact(t) => (t.phi_start(), t.phi_end()),
            Path::Inverse(t) => (t.theta_at(t.phi_start()), t.theta_at(t.phi_end())),
            Path::Carried { pieces, .. } => (
                pieces.first().map_or(0.0, |p| p.phi_start),
                pieces.last().map_or(0.0, |p| p.phi_end),
            ),
            Path::Steps(steps) => (
                steps.first().map_or(0.0, |s| s.0),
                steps.last().map_or(0.0, |s| s.0),
            ),
            Path::Joined { first, then, .. } => (first.phi_range().0, then.phi_range().1),
        }
    }
}

/// θ of `rule` at φ on `mesh`, or None where its pair has no obstacle.
pub(crate) fn rule_at(mesh: &Mesh, rule: Rule, phi: f64, ratio: f64) -> Option<f64> {
    match rule {
        Rule::Carried { phi: p, theta } => Some(theta + ratio * (phi - p)),
        Rule::Pushed(j, k) => mesh.obstacle(phi, j, k).map(|o| o.hi),
        Rule::HeldBack(j, k) => mesh.obstacle(phi, j, k).map(|o| o.lo),
        Rule::Stuck(theta) => Some(theta),
    }
}

fn carried_at(mesh: &Mesh, pieces: &[Piece], phi: f64) -> f64 {
    let Some(last) = pieces.last() else {
        return 0.0;
    };
    let phi = phi.clamp(pieces[0].phi_start, last.phi_end);
    let i = pieces
        .partition_point(|p| p.phi_end < phi)
        .min(pieces.len() - 1);
    let ratio = mesh.driver().teeth() as f64 / mesh.driven().teeth() as f64;
    let piece = &pieces[i];
    rule_at(mesh, piece.rule, phi, ratio)
        // A pair's obstacle ends exactly where its piece ends (a push let go as the teeth
        // part): the piece's last driven angle is its value at its end, just inside.
        .or_else(|| rule_at(mesh, piece.rule, piece.phi_start, ratio))
        .unwrap_or(f64::NAN)
}

fn steps_at(steps: &[(f64, f64)], phi: f64) -> f64 {
    let Some(&(p_last, t_last)) = steps.last() else {
        return 0.0;
    };
    if phi >= p_last {
        return t_last;
    }
    let i = steps.partition_point(|s| s.0 <= phi);
    if i == 0 {
        return steps[0].1;
    }
    let ((p0, t0), (p1, t1)) = (steps[i - 1], steps[i]);
    t0 + (t1 - t0) * (phi - p0) / (p1 - p0)
}

fn inverse_at(t: &Trajectory, phi: f64) -> f64 {
    let (mut lo, mut hi) = (t.phi_start(), t.phi_end());
    if t.theta_at(lo) >= phi {
        return lo;
    }
    if t.theta_at(hi) <= phi {
        return hi;
    }
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if t.theta_at(mid) <= phi {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn steps_are_joined_by_straight_lines_and_clamped() {
        let steps = vec![(0.0, 1.0), (1.0, 2.0), (2.0, 2.0)];
        let path = Path::Steps(steps);
        assert_eq!(path.theta_at(-1.0), 1.0);
        assert_eq!(path.theta_at(0.5), 1.5);
        assert_eq!(path.theta_at(1.5), 2.0);
        assert_eq!(path.theta_at(3.0), 2.0);
        assert_eq!(path.phi_range(), (0.0, 2.0));
    }
}
