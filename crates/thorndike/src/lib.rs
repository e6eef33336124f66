//! Thorndike's closed-form transmission `theta(phi)` for ideal triangular-tooth gear pairs (paper, Appendix I).
//!
//! # Frames
//!
//! The driver's rotation centre is at the origin and the driven's at `(D, 0)` (`D` is the
//! paper's `Y`). Driver tip `j` is at angle `t_j + phi'` from the line of centres, measured
//! counter-clockwise about the origin; driven tip `k` is at angle `theta' - t_k` from the line
//! of centres, measured clockwise about `(D, 0)` (`t_k = 2 pi k / N`). These are the primed
//! angles of Appendix I ("Figure III frame"). The main-text angles are
//! `phi = phi' - phi'_o`, `theta = theta' - theta'_o` with `theta'_o = theta'(phi'_o)`.
//! All angles are radians.
//!
//! # Tooth pairs
//!
//! Expressions \[I\] ([`expr_i`], Phase 2: driver tip on the driven flank) and \[II\]
//! ([`expr_ii`], Phase 1: driver flank on the driven tip) describe the contact of the driver
//! tooth whose tip is at `phi'` with the driven tooth whose tip is at `theta'`: the driver's
//! leading flank (from its tip towards the next valley, counter-clockwise) against the driven's
//! trailing flank (from its tip towards the driven valley nearer the line of centres).
//! Tooth pair `m` is the driver tooth at `phi' - m p1` (driver tooth `-m mod N1`) with the
//! driven tooth at `theta' - m p2` (driven tooth `m mod N2`), `p_i = 2 pi / N_i`. In the push
//! model the driven angle is the largest of the valid constraints of all tooth pairs
//! ([`theta_prime`]); the model ignores the driven's other flanks, so it does not detect
//! jamming (contact of the driven's leading flank with the next driver tooth).
//!
//! # Paper example
//!
//! `N1 = N2 = 8`, `R = 200`, `r = 100`, `D = 310`: `theta'(0) = 17.955 387 66 deg` (the paper's
//! 17.96 deg), Phase 1 hands over to Phase 2 at `phi' = -6.0396 deg`, and tooth pair 1 takes
//! over at `phi' = 11.5558 deg`.

use std::f64::consts::{PI, TAU};

/// Relative tolerance on the flank parameter when deciding whether a contact point lies on
/// a flank segment (keeps exact tip-to-tip contacts valid despite rounding).
const FLANK_TOL: f64 = 1e-12;

/// Bracket width at which bisections stop, radians (they also stop when the midpoint no
/// longer moves).
const BISECT_TOL: f64 = 1e-15;

/// Tip half-angle of an ideal triangular tooth: the angle at the tip between the radius and a
/// flank, `atan2(r sin(pi/N), R - r cos(pi/N))`.
#[must_use]
pub fn tip_half_angle(n: u32, r_tip: f64, r_root: f64) -> f64 {
    let h = PI / f64::from(n);
    (r_root * h.sin()).atan2(r_tip - r_root * h.cos())
}

/// Length of a flank of an ideal triangular tooth (from tip to valley).
#[must_use]
pub fn flank_length(n: u32, r_tip: f64, r_root: f64) -> f64 {
    let h = PI / f64::from(n);
    (r_tip * r_tip + r_root * r_root - 2.0 * r_tip * r_root * h.cos()).sqrt()
}

/// Why a [`Pair`] could not be built. Each variant names the offending field.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum PairError {
    /// A tooth count below 3.
    #[error("{field}: need at least 3 teeth, got {value}")]
    TooFewTeeth {
        /// `"n1"` or `"n2"`.
        field: &'static str,
        /// The rejected tooth count.
        value: u32,
    },
    /// A radius or the centre distance that is not finite and positive.
    #[error("{field}: must be finite and positive, got {value}")]
    NotPositive {
        /// The field name, e.g. `"r_tip1"`.
        field: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// A root (valley) radius not below the tip radius of the same gear.
    #[error("{field}: must be below the tip radius {r_tip}, got {value}")]
    RootNotBelowTip {
        /// `"r_root1"` or `"r_root2"`.
        field: &'static str,
        /// The rejected root radius.
        value: f64,
        /// The tip radius of the same gear.
        r_tip: f64,
    },
    /// Centre distance so small that a tip reaches the other gear's root circle
    /// (`D <= max(R1 + r2, R2 + r1)`).
    #[error("{field}: {value} lets a tip reach the other gear's root circle (need > {min})")]
    TooClose {
        /// Always `"centre_distance"`.
        field: &'static str,
        /// The rejected centre distance.
        value: f64,
        /// The exclusive lower bound.
        min: f64,
    },
    /// Centre distance so large that the tip circles do not overlap (`D >= R1 + R2`).
    #[error("{field}: {value} leaves the gears out of mesh (need < {max})")]
    TooFar {
        /// Always `"centre_distance"`.
        field: &'static str,
        /// The rejected centre distance.
        value: f64,
        /// The exclusive upper bound.
        max: f64,
    },
    /// The push-model `theta'(phi')` would not be continuous: one tooth pair releases the
    /// driven before the next one engages (contact ratio below one), the next pair engages
    /// above the current one (the driven is struck and jumps, as with teeth too tall for
    /// their pitch), or a tooth pair has no Phase 1 to Phase 2 switch.
    #[error("{field}: {value} gives no continuous tooth contact ({reason})")]
    ContactInterrupted {
        /// Always `"centre_distance"`.
        field: &'static str,
        /// The centre distance of the rejected pair.
        value: f64,
        /// What was missing.
        reason: &'static str,
    },
}

/// Two ideal triangular-tooth gears in mesh, validated. Construct with [`Pair::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pair {
    n1: u32,
    n2: u32,
    r_tip1: f64,
    r_root1: f64,
    r_tip2: f64,
    r_root2: f64,
    centre_distance: f64,
    alpha1: f64,
    alpha2: f64,
    switch: f64,
    handoff: f64,
}

impl Pair {
    /// Validate and build: `N >= 3`, `0 < r < R`, all finite, and
    /// `max(R1 + r2, R2 + r1) < D < R1 + R2`; also requires a continuous `theta'(phi')`: a
    /// Phase 1 to Phase 2 switch, and the next tooth pair taking over (engaging below the
    /// current constraint and overtaking it) before the current one lets go.
    ///
    /// # Errors
    ///
    /// A [`PairError`] naming the first offending field.
    pub fn new(
        n1: u32,
        n2: u32,
        r_tip1: f64,
        r_root1: f64,
        r_tip2: f64,
        r_root2: f64,
        centre_distance: f64,
    ) -> Result<Self, PairError> {
        for (field, value) in [("n1", n1), ("n2", n2)] {
            if value < 3 {
                return Err(PairError::TooFewTeeth { field, value });
            }
        }
        for (field, value) in [
            ("r_tip1", r_tip1),
            ("r_root1", r_root1),
            ("r_tip2", r_tip2),
            ("r_root2", r_root2),
            ("centre_distance", centre_distance),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(PairError::NotPositive { field, value });
            }
        }
        for (field, value, r_tip) in [("r_root1", r_root1, r_tip1), ("r_root2", r_root2, r_tip2)] {
            if value >= r_tip {
                return Err(PairError::RootNotBelowTip {
                    field,
                    value,
                    r_tip,
                });
            }
        }
        let field = "centre_distance";
        let min = (r_tip1 + r_root2).max(r_tip2 + r_root1);
        if centre_distance <= min {
            return Err(PairError::TooClose {
                field,
                value: centre_distance,
                min,
            });
        }
        let max = r_tip1 + r_tip2;
        if centre_distance >= max {
            return Err(PairError::TooFar {
                field,
                value: centre_distance,
                max,
            });
        }
        let mut g = Self {
            n1,
            n2,
            r_tip1,
            r_root1,
            r_tip2,
            r_root2,
            centre_distance,
            alpha1: tip_half_angle(n1, r_tip1, r_root1),
            alpha2: tip_half_angle(n2, r_tip2, r_root2),
            switch: f64::NAN,
            handoff: f64::NAN,
        };
        let interrupted = |reason| PairError::ContactInterrupted {
            field,
            value: centre_distance,
            reason,
        };
        g.switch = find_switch(&g).ok_or_else(|| interrupted("no Phase 1 to Phase 2 switch"))?;
        g.handoff = find_handoff(&g).map_err(interrupted)?;
        Ok(g)
    }

    /// Number of driver teeth `N1`.
    #[must_use]
    pub fn n1(&self) -> u32 {
        self.n1
    }

    /// Number of driven teeth `N2`.
    #[must_use]
    pub fn n2(&self) -> u32 {
        self.n2
    }

    /// Driver tip radius `R1`.
    #[must_use]
    pub fn r_tip1(&self) -> f64 {
        self.r_tip1
    }

    /// Driver root (valley) radius `r1`.
    #[must_use]
    pub fn r_root1(&self) -> f64 {
        self.r_root1
    }

    /// Driven tip radius `R2`.
    #[must_use]
    pub fn r_tip2(&self) -> f64 {
        self.r_tip2
    }

    /// Driven root (valley) radius `r2`.
    #[must_use]
    pub fn r_root2(&self) -> f64 {
        self.r_root2
    }

    /// Centre distance `D` (the paper's `Y`).
    #[must_use]
    pub fn centre_distance(&self) -> f64 {
        self.centre_distance
    }

    /// Driver tip half-angle `alpha1` (see [`tip_half_angle`]).
    #[must_use]
    pub fn alpha1(&self) -> f64 {
        self.alpha1
    }

    /// Driven tip half-angle `alpha2` (see [`tip_half_angle`]).
    #[must_use]
    pub fn alpha2(&self) -> f64 {
        self.alpha2
    }

    /// Driver angular pitch `p1 = 2 pi / N1`.
    #[must_use]
    pub fn pitch1(&self) -> f64 {
        TAU / f64::from(self.n1)
    }

    /// Driven angular pitch `p2 = 2 pi / N2`.
    #[must_use]
    pub fn pitch2(&self) -> f64 {
        TAU / f64::from(self.n2)
    }

    /// Gear ratio `N1 / N2` (driven turns per driver turn).
    #[must_use]
    pub fn ratio(&self) -> f64 {
        f64::from(self.n1) / f64::from(self.n2)
    }

    /// Clearance `G = D - (R1 + R2 - h)` with `h` the mean tooth height `((R1 - r1) + (R2 - r2)) / 2`.
    #[must_use]
    pub fn clearance(&self) -> f64 {
        let h = 0.5 * ((self.r_tip1 - self.r_root1) + (self.r_tip2 - self.r_root2));
        self.centre_distance - (self.r_tip1 + self.r_tip2 - h)
    }
}

/// Expression \[I\] of Appendix I, literally (Phase 2, driver tip on the driven flank):
/// `theta' = asin(R1 sin phi' / q) + asin(R2 sin alpha2 / q) - alpha2` with
/// `q = sqrt(R1^2 + D^2 - 2 R1 D cos phi')`. NaN where an `asin` argument exceeds 1. No
/// validity check: see [`phase2_theta`].
#[must_use]
pub fn expr_i(g: &Pair, phi_prime: f64) -> f64 {
    let (r1, d, r2, a2) = (g.r_tip1, g.centre_distance, g.r_tip2, g.alpha2);
    let q = (r1 * r1 + d * d - 2.0 * r1 * d * phi_prime.cos()).sqrt();
    (r1 * phi_prime.sin() / q).asin() + (r2 * a2.sin() / q).asin() - a2
}

/// Expression \[II\] (Phase 1, driver flank on the driven tip), in the frame of \[I\]:
/// `theta' = asin((D sin(phi' - alpha1) + R1 sin alpha1) / R2) - phi' + alpha1`.
///
/// Derivation: the driver's leading flank lies on the line `x . n = R1 sin alpha1` with unit
/// normal `n` at angle `phi' + pi/2 - alpha1`; the driven tip is at
/// `(D - R2 cos theta', R2 sin theta')`; substituting gives
/// `D sin(alpha1 - phi') + R2 sin(theta' + phi' - alpha1) = R1 sin alpha1`. The principal
/// `asin` branch (`|theta' + phi' - alpha1| <= pi/2`) is the one at which the driven tip
/// leaves the driver tooth as `theta'` grows. NaN where the `asin` argument exceeds 1. No
/// validity check: see [`phase1_theta`].
#[must_use]
pub fn expr_ii(g: &Pair, phi_prime: f64) -> f64 {
    let (r1, d, r2, a1) = (g.r_tip1, g.centre_distance, g.r_tip2, g.alpha1);
    ((d * (phi_prime - a1).sin() + r1 * a1.sin()) / r2).asin() - phi_prime + a1
}

/// \[I\] where it is valid: the driver tip lies on the driven's trailing flank segment, i.e.
/// its distance `q` from the driven centre gives a flank parameter
/// `s2 = R2 cos alpha2 - sqrt(q^2 - R2^2 sin^2 alpha2)` (distance from the driven tip) in
/// `[0, L2]`, `L2` the flank length. `None` otherwise.
#[must_use]
pub fn phase2_theta(g: &Pair, phi_prime: f64) -> Option<f64> {
    let (r1, d, r2, a2) = (g.r_tip1, g.centre_distance, g.r_tip2, g.alpha2);
    let q2 = r1 * r1 + d * d - 2.0 * r1 * d * phi_prime.cos();
    let disc = q2 - (r2 * a2.sin()).powi(2);
    if disc < 0.0 {
        return None;
    }
    let s2 = r2 * a2.cos() - disc.sqrt();
    let l2 = flank_length(g.n2, g.r_tip2, g.r_root2);
    on_segment(s2, l2).then(|| expr_i(g, phi_prime))
}

/// \[II\] where it is valid: the driven tip lies on the driver's leading flank segment, i.e.
/// its projection on that flank is at distance `s1` from the driver tip with `s1` in
/// `[0, L1]`. `None` otherwise (including where the `asin` argument exceeds 1).
#[must_use]
pub fn phase1_theta(g: &Pair, phi_prime: f64) -> Option<f64> {
    let theta = expr_ii(g, phi_prime);
    if !theta.is_finite() {
        return None;
    }
    let (r1, d, r2) = (g.r_tip1, g.centre_distance, g.r_tip2);
    let tip1 = [r1 * phi_prime.cos(), r1 * phi_prime.sin()];
    let va = phi_prime + PI / f64::from(g.n1);
    let valley1 = [g.r_root1 * va.cos(), g.r_root1 * va.sin()];
    let l1 = flank_length(g.n1, g.r_tip1, g.r_root1);
    let u = [(valley1[0] - tip1[0]) / l1, (valley1[1] - tip1[1]) / l1];
    let tip2 = [d - r2 * theta.cos(), r2 * theta.sin()];
    let s1 = (tip2[0] - tip1[0]) * u[0] + (tip2[1] - tip1[1]) * u[1];
    on_segment(s1, l1).then_some(theta)
}

fn on_segment(s: f64, len: f64) -> bool {
    let tol = FLANK_TOL * len;
    s >= -tol && s <= len + tol
}

/// Contact phase of a tooth pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// Phase 1, expression \[II\]: driver flank on the driven tip.
    One,
    /// Phase 2, expression \[I\]: driver tip on the driven flank.
    Two,
}

/// The constraint of one tooth pair (driver tooth at `phi'`, driven tooth at `theta'`):
/// the larger of the valid [`phase1_theta`] and [`phase2_theta`], with its phase. `None` if
/// the teeth cannot touch at this `phi'`.
#[must_use]
pub fn tooth_pair_theta(g: &Pair, phi_prime: f64) -> Option<(f64, Phase)> {
    match (phase1_theta(g, phi_prime), phase2_theta(g, phi_prime)) {
        (Some(a), Some(b)) if a > b => Some((a, Phase::One)),
        (_, Some(b)) => Some((b, Phase::Two)),
        (Some(a), None) => Some((a, Phase::One)),
        (None, None) => None,
    }
}

/// The binding contact of the push model at some `phi'`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Tooth pair `m`: driver tooth at `phi' - m p1` against driven tooth at `theta' - m p2`.
    pub pair: i64,
    /// Its phase.
    pub phase: Phase,
    /// The driven angle `theta'` (Figure III frame).
    pub theta_prime: f64,
}

/// The binding contact of the push model at `phi_prime`: the tooth pair whose constraint is
/// highest (ties go to the lower pair index). Valid for any finite `phi_prime`.
#[must_use]
pub fn contact(g: &Pair, phi_prime: f64) -> Contact {
    let p1 = g.pitch1();
    let p2 = g.pitch2();
    let m0 = (phi_prime / p1).round();
    let base = phi_prime - m0 * p1;
    let span = (PI / p1).ceil() as i64 + 1;
    let mut best = Contact {
        pair: 0,
        phase: Phase::Two,
        theta_prime: f64::NEG_INFINITY,
    };
    for dm in -span..=span {
        let a = base - dm as f64 * p1;
        if let Some((t, phase)) = tooth_pair_theta(g, a) {
            let t = t + (m0 + dm as f64) * p2;
            if t > best.theta_prime {
                best = Contact {
                    pair: m0 as i64 + dm,
                    phase,
                    theta_prime: t,
                };
            }
        }
    }
    best
}

/// Push-model driven angle `theta'(phi')` in the Figure III frame, for any `phi'`: the
/// maximum over tooth pairs `m` of the valid \[I\]/\[II\] values of pair `m`
/// (`tooth_pair_theta(phi' - m p1) + m p2`). Periodic:
/// `theta'(phi' + p1) = theta'(phi') + p2`.
#[must_use]
pub fn theta_prime(g: &Pair, phi_prime: f64) -> f64 {
    contact(g, phi_prime).theta_prime
}

/// The `phi'` at which, for one tooth pair, Phase 1 (\[II\]) hands over to Phase 2 (\[I\]):
/// the intersection of the two curves (Figure III_A), found by bisection to about 1e-15 rad.
#[must_use]
pub fn phase_switch(g: &Pair) -> f64 {
    g.switch
}

/// The `phi'` at which tooth pair 1 takes over from tooth pair 0:
/// `f(phi') = f(phi' - p1) + p2` with `f` = [`tooth_pair_theta`], found by bisection to
/// about 1e-15 rad. Tooth pair 0 is binding on `[handoff - p1, handoff]`.
#[must_use]
pub fn handoff(g: &Pair) -> f64 {
    g.handoff
}

/// Main-text driven angle `theta(phi) = theta'(phi'_o + phi) - theta'(phi'_o)` for the
/// initial driver angle `phi_o_prime` (`phi'_o`).
#[must_use]
pub fn theta_from(g: &Pair, phi_o_prime: f64, phi: f64) -> f64 {
    theta_prime(g, phi_o_prime + phi) - theta_prime(g, phi_o_prime)
}

/// Main-text driven angle with `phi'_o = 0` (as in Figure III): `theta'(phi) - theta'(0)`.
#[must_use]
pub fn theta(g: &Pair, phi: f64) -> f64 {
    theta_from(g, 0.0, phi)
}

/// Theoretical Difference `theta(phi) - (N1/N2) phi` for the initial driver angle
/// `phi_o_prime`. (The paper's \[2\] prints `N2/N1`; the ratio of \[1\] is `N1/N2`.)
#[must_use]
pub fn td_from(g: &Pair, phi_o_prime: f64, phi: f64) -> f64 {
    theta_from(g, phi_o_prime, phi) - g.ratio() * phi
}

/// Theoretical Difference `theta(phi) - (N1/N2) phi` with `phi'_o = 0` (Figure III).
#[must_use]
pub fn td(g: &Pair, phi: f64) -> f64 {
    td_from(g, 0.0, phi)
}

/// Samples for the scans that bracket the switch and the handoff, per driver pitch.
const SCAN_PER_PITCH: f64 = 512.0;

/// Bisect a predicate that is false at `lo` and true at `hi`.
fn bisect(mut lo: f64, mut hi: f64, pred: impl Fn(f64) -> bool) -> f64 {
    while (hi - lo).abs() > BISECT_TOL {
        let mid = 0.5 * (lo + hi);
        if mid == lo || mid == hi {
            break;
        }
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// Scan points over `[-pi, pi]` for one tooth pair.
fn scan(g: &Pair) -> impl Iterator<Item = f64> {
    let step = g.pitch1() / SCAN_PER_PITCH;
    let n = (TAU / step).ceil() as i64;
    (0..=n).map(move |i| -PI + i as f64 * step)
}

fn find_switch(g: &Pair) -> Option<f64> {
    // d > 0: Phase 1 above Phase 2; the switch is where it becomes <= 0.
    let d = |a: f64| Some(phase1_theta(g, a)? - phase2_theta(g, a)?);
    let mut prev: Option<f64> = None;
    for a in scan(g) {
        match d(a) {
            Some(v) if v <= 0.0 => {
                if let Some(lo) = prev {
                    return Some(bisect(lo, a, |x| d(x).is_none_or(|v| v <= 0.0)));
                }
                prev = None;
            }
            Some(_) => prev = Some(a),
            None => prev = None,
        }
    }
    None
}

/// Why no handoff exists: the next pair starts above the current one (the driven would be
/// struck and jump), or the current pair lets go before the next one engages.
fn find_handoff(g: &Pair) -> Result<f64, &'static str> {
    let (p1, p2) = (g.pitch1(), g.pitch2());
    let f = |a: f64| tooth_pair_theta(g, a).map(|t| t.0);
    // h >= 0: the next pair (driver tooth at a - p1) is at least as high as pair 0.
    let h = |a: f64| Some(f(a - p1)? + p2 - f(a)?);
    let mut prev: Option<f64> = None;
    let mut seen_pair0 = false;
    for a in scan(g) {
        let pair0 = f(a).is_some();
        match h(a) {
            Some(v) if v >= 0.0 => {
                return prev
                    .map(|lo| bisect(lo, a, |x| h(x).is_none_or(|v| v >= 0.0)))
                    .ok_or("the next tooth pair engages above the current one (the driven jumps)");
            }
            Some(_) => prev = Some(a),
            None if seen_pair0 && !pair0 => {
                return Err("a tooth pair lets go before the next one engages");
            }
            None => prev = None,
        }
        seen_pair0 |= pair0;
    }
    Err("a tooth pair lets go before the next one engages")
}

#[cfg(test)]
mod tests;
