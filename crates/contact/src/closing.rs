//! Where a driver tooth ahead first closes on the driven gear along its planned path: at a root
//! where a contact condition of the pair ahead holds together with one of the path's.
//!
//! Along a stretch of a step the driven angle is known in closed form: at rest, a constant;
//! pushed, the largest upper end of the pushing pairs' obstacles (held between the stretch's
//! first and last driven angles), each such end a root of one of the pair's contact conditions
//! ([`Mesh::conditions_of_both_sides`]: a just-met obstacle may have both ends on one side). The
//! backlash ahead - the lowest lower end of the pairs ahead, less the driven angle - can change
//! sign only where a condition of a pair ahead holds at the same (φ, θ) as one of the path: two conditions meeting (`meet::meetings`), or, where
//! the driven angle is constant, one condition at that angle (`Condition::roots_at_theta`). So
//! between two consecutive roots the backlash keeps one sign: one evaluation inside each, in
//! order, finds the first closing, and it lies exactly at a root. No sampling, no step is
//! passed over on a bound: a closing however brief (a tip grazing a tip) has its two roots.
//! A driver tooth reaching the driven gear at rest from behind is found alike ([`first_reach`]).

use smallvec::SmallVec;

use crate::meet::{Condition, meetings};
use crate::mesh::{ConditionSet, Mesh};

/// How the driven gear moves over one stretch of a planned step.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Path<'a> {
    /// At rest at this driven angle.
    Rest(f64),
    /// Pushed by these pairs from the first driven angle of `levels` to the second.
    Push {
        pairs: &'a [(i64, i64)],
        levels: [f64; 2],
    },
}

/// A stretch of driver angles `(phi.0, phi.1]` and how the driven gear moves over it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Stretch<'a> {
    pub(crate) phi: (f64, f64),
    pub(crate) path: Path<'a>,
}

/// The first driver angle of `stretches` (in order, end to end) at which the backlash of the
/// pairs `ahead` stops being positive - `backlash(φ)`, their lowest lower end less the driven
/// angle on the path - or None if it stays positive. The first stretch's start counts (a
/// backlash that closes from exactly zero there closes at it) unless `after_start`. Of each
/// pair's conditions (ahead, or on the path) only those of `sets` are taken: the others must
/// hold nowhere in the stretches' driver angles and the driven angles of the path (a closing is
/// a root of two conditions at once on the path, so no closing is lost).
pub(crate) fn first_closing(
    mesh: &Mesh,
    stretches: &[Stretch<'_>],
    ahead: &[(i64, i64)],
    (after_start, sets): (bool, &mut dyn FnMut((i64, i64)) -> ConditionSet),
    backlash: impl Fn(f64) -> f64,
) -> Option<f64> {
    let first = stretches.first()?;
    let lower: SmallVec<[Condition; 32]> = ahead
        .iter()
        .flat_map(|&pair| mesh.conditions_in(pair, sets(pair)))
        .collect();
    let mut roots: Vec<f64> = Vec::new();
    for s in stretches {
        let (a, b) = s.phi;
        if b <= a {
            continue;
        }
        roots.push(b);
        roots_in_stretch(mesh, s, &lower, sets, &mut roots);
    }
    if after_start {
        // The search starts at the first root: whatever the backlash does before it (a pair
        // just found holding nothing at the start), no sign change lies there.
        let start = roots.iter().copied().fold(f64::INFINITY, f64::min);
        roots.retain(|r| *r > start);
        return first_sign_change(start, roots, backlash);
    }
    first_sign_change(first.phi.0, roots, backlash)
}

/// The first driver angle in `(phi.0, phi.1]` at which a driver tooth of the pairs `behind`
/// reaches the driven gear resting at θ - `reach(φ)`, θ less the highest upper end of their
/// obstacles, stops being positive - or None. Resting, θ is constant: the upper end of a pair
/// reaches it only where one of its conditions holds at θ, in closed form.
pub(crate) fn first_reach(
    mesh: &Mesh,
    behind: &[(i64, i64)],
    theta: f64,
    phi: (f64, f64),
    reach: impl Fn(f64) -> f64,
) -> Option<f64> {
    let mut roots = vec![phi.1];
    for &(j, k) in behind {
        for c in mesh.conditions_of_both_sides(j, k) {
            roots.extend(c.roots_at_theta(theta, phi.0, phi.1));
        }
    }
    first_sign_change(phi.0, roots, reach)
}

/// The first driver angle from `start` at which `gap` stops being positive, where its sign can
/// change only at `roots` (any order, any past the range too: the last root ends the search), or
/// None if it stays positive up to the last root. Between two consecutive roots the sign is the
/// sign at their middle; a change is recorded on its open side ([`open_side`]).
pub(crate) fn first_sign_change(
    start: f64,
    mut roots: Vec<f64>,
    gap: impl Fn(f64) -> f64,
) -> Option<f64> {
    roots.sort_by(f64::total_cmp);
    roots.dedup();
    let (mut from, mut open) = (start, start);
    for r in roots {
        if r <= from {
            continue;
        }
        let mid = 0.5 * (from + r);
        if gap(mid) < 0.0 {
            return Some(open_side(from, open, &gap));
        }
        (from, open) = (r, mid);
    }
    None
}

/// How small a positive gap is at the open side of a closing (radians of driven angle): well
/// inside the solver's side tolerance (1e-10 rad), within which a tooth ahead counts as touching
/// the gear and holds it, so that the tooth that closes is judged touching there however steeply
/// it closes.
pub(crate) const TOUCHING: f64 = 2.5e-11;

/// Where a sign change at the root `root` is recorded: the last angle before it, within about
/// 1e-13 rad, at which the gap is still positive (the teeth touch, not yet overlap), but not
/// before `open`, where it is known to be positive. At the root itself the gap is zero only to
/// rounding, of either sign; on the open side the driven gear is where the push model leaves it
/// at a jam, and a release tested there sees the closing tooth ahead of it, touching: where
/// the gap closes so steeply (hundreds of radians of driven angle a radian of driver angle, a
/// tooth met just after it appeared) that 1e-13 rad back it is already wider than
/// [`TOUCHING`], the angle is bisected towards the root until it is not.
fn open_side(root: f64, open: f64, gap: &impl Fn(f64) -> f64) -> f64 {
    let mut back = 1e-13 * (1.0 + root.abs());
    let (mut x, mut closed) = (root, root);
    while x > open && gap(x) <= 0.0 {
        closed = x;
        x = root - back;
        back *= 2.0;
    }
    let x = x.max(open);
    let (mut wide, mut shut) = (x, closed);
    while gap(wide) > TOUCHING {
        let mid = 0.5 * (wide + shut);
        if mid <= wide || mid >= shut {
            break;
        }
        if gap(mid) > 0.0 {
            wide = mid;
        } else {
            shut = mid;
        }
    }
    wide
}

/// Every driver angle in the stretch where a lower-end condition of `lower` holds together with
/// a condition of the path (of those in `sets`), into `out`.
fn roots_in_stretch(
    mesh: &Mesh,
    s: &Stretch<'_>,
    lower: &[Condition],
    sets: &mut dyn FnMut((i64, i64)) -> ConditionSet,
    out: &mut Vec<f64>,
) {
    let (a, b) = s.phi;
    let at_level = |theta: f64, out: &mut Vec<f64>| {
        for c in lower {
            out.extend(c.roots_at_theta(theta, a, b));
        }
    };
    match s.path {
        Path::Rest(theta) => at_level(theta, out),
        Path::Push { pairs, levels } => {
            for theta in levels {
                at_level(theta, out);
            }
            for &pair in pairs {
                for up in mesh.conditions_in(pair, sets(pair)) {
                    for c in lower {
                        out.extend(meetings(&up, c, a, b, levels[0]).iter().map(|m| m.0));
                    }
                }
            }
        }
    }
}
