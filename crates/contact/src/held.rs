//! Where a held driven gear may be let go, solved exactly.
//!
//! A held gear at θ has no free position ahead: the obstacles at φ, swept in order of their lower
//! ends (`cover_from` in `solver/cover.rs`, as at the jam that held it: one joins the cover when its
//! lower end is within the side tolerance `tol` of the top so far, so that a driver tooth
//! touching the gear from ahead holds it), close up from θ past a threshold more than
//! a turn on. Take the **chain** c_1 … c_m of obstacles that lifted the top, and these **joints**:
//!
//! - joint 0: lo_1 ≤ θ + tol;
//! - joint i (0 < i < m): lo_{i+1} ≤ hi_i + tol and hi_i > θ;
//! - joint m: hi_m ≥ the threshold.
//!
//! Wherever every link's teeth touch and every joint holds, the sweep closes up past the
//! threshold. By induction over the links in order of their lower ends: a link at or below
//! θ + tol joins whatever the top is. Any other c_i has an earlier link c_k with lo_k < lo_i (c_1 is
//! one); take the last. It was swept before c_i, so the top is at least hi_k > θ, and the links
//! between have lower ends at or above lo_i, so lo_i ≤ lo_{k+1} ≤ hi_k + tol: c_i joins, and the
//! top reaches hi_i. Hence the top reaches hi_m, past the threshold; more obstacles only cover
//! more.
//!
//! So the gear stays held until a joint fails or a link's teeth part, and each of these happens
//! at a root of the links' contact conditions (`meet.rs`): an end of a link crossing a fixed
//! driven angle (θ + tol, θ, the threshold: closed form), the upper end of a link crossing the
//! lower end of the next less the tolerance (two conditions met, one shifted by `tol`), or a
//! link's two ends meeting (its teeth parting). [`first_change`] gives the first of these over a
//! range of driver angles; there the solver sweeps the turn again, and either lets the gear go or
//! takes the new chain.

use smallvec::SmallVec;

use crate::meet::{Condition, meetings};
use crate::mesh::{End, Mesh, Obstacle};

/// How near (radians, relative to 1 + |angle|) an obstacle's end must be to a root for the root
/// to be that end's: a root of a condition that is not the end (a flank's line beyond the tooth,
/// the other branch of a circle) lies far off it.
const AT_ROOT: f64 = 1e-9;

/// How close (radians of driver angle, relative to 1 + |φ|) roots of a held gear's chain are
/// taken as one change. Teeth alike (a driven gear without errors of its own) open joints a
/// whole number of pitches apart at the same driver angle but for rounding and small
/// eccentricities, 1e-13 to 1e-11 rad apart; which opens first, and so where the gear goes,
/// would be decided by the roots' rounding. Far below the events' accuracy (1e-9 rad).
const SIMULTANEOUS: f64 = 1e-10;

/// The conditions of one end of one link.
type Conditions = SmallVec<[Condition; 8]>;

/// What a root found by [`first_change`] may change, to be checked where it lies.
#[derive(Debug, Clone, Copy)]
enum Change {
    /// An end of link `link` (its upper end if `upper`) reaching the fixed driven angle `at`.
    End { link: usize, upper: bool, at: f64 },
    /// The upper end of link `below` plus the tolerance reaching the lower end of the next link,
    /// both at `theta`.
    Joint { below: usize, theta: f64 },
    /// The two ends of link `link` meeting: its teeth part.
    Parting { link: usize },
}

/// The first driver angle in `(phi0, phi1]` at which the held gear's `chain` (at `phi0`, see the
/// module's docs) may stop holding it at θ, or None if every joint holds throughout.
pub(crate) fn first_change(
    mesh: &Mesh,
    chain: &[Obstacle],
    theta: f64,
    threshold: f64,
    tol: f64,
    (phi0, phi1): (f64, f64),
) -> Option<ChainBreak> {
    let m = chain.iter().position(|c| c.hi >= threshold)? + 1;
    let chain = &chain[..m];
    let of = |end: End| -> Vec<Conditions> {
        chain
            .iter()
            .map(|c| mesh.conditions(c.driver_tooth, c.driven_tooth, end))
            .collect()
    };
    let (lower, upper) = (of(End::Lower), of(End::Upper));
    let mut found: Vec<(f64, Change)> = Vec::new();
    ends_at_fixed_angles(
        (&lower, &upper),
        theta,
        threshold,
        tol,
        (phi0, phi1),
        &mut found,
    );
    joints_roots(
        mesh,
        chain,
        (&lower, &upper),
        (theta, tol),
        (phi0, phi1),
        &mut found,
    );
    if m == 1 {
        partings(
            (&lower[0], &upper[0]),
            0,
            &chain[0],
            (phi0, phi1),
            &mut found,
        );
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let i = found
        .iter()
        .position(|&(phi, change)| changes(mesh, chain, phi, change, tol))?;
    Some(break_at(&found[i..], phi1))
}

/// The roots where a joint between two links of `chain` (at `phi0`) may fail over the range, or
/// where either link's teeth may part, into `found`: for each joint (the same teeth a turn apart
/// are taken once), after the stretch it is proved to hold by points.
fn joints_roots(
    mesh: &Mesh,
    chain: &[Obstacle],
    (lower, upper): (&[Conditions], &[Conditions]),
    (theta, tol): (f64, f64),
    (phi0, phi1): (f64, f64),
    found: &mut Vec<(f64, Change)>,
) {
    // A cover longer than a turn meets the same teeth again a turn on: the same roots.
    let n2 = mesh.driven.tips.len() as i64;
    let mut seen: Vec<(i64, i64, i64, i64)> = Vec::new();
    let mut parted = vec![false; chain.len()];
    for (i, pair) in chain.windows(2).enumerate() {
        let (link, next) = (pair[0], pair[1]);
        let key = (
            link.driver_tooth,
            link.driven_tooth.rem_euclid(n2),
            next.driver_tooth,
            next.driven_tooth - link.driven_tooth,
        );
        if seen.contains(&key) {
            continue;
        }
        seen.push(key);
        // Most joints overlap by far more than their links move: a driven angle inside both
        // that no end of either crosses proves the joint held (closed form), and only what is
        // left of the range after a few such proofs is searched for meetings.
        let ends = [&lower[i], &upper[i], &lower[i + 1], &upper[i + 1]];
        let from = held_by_points(mesh, (link, next), ends, theta, (phi0, phi1));
        if from >= phi1 {
            continue;
        }
        for l in [i, i + 1] {
            if !std::mem::replace(&mut parted[l], true) {
                partings((&lower[l], &upper[l]), l, &chain[l], (from, phi1), found);
            }
        }
        let below: Conditions = upper[i].iter().map(|c| c.shifted(tol)).collect();
        for above in &lower[i + 1] {
            for below in &below {
                for (phi, theta) in meetings(above, below, from, phi1, next.lo) {
                    found.push((phi, Change::Joint { below: i, theta }));
                }
            }
        }
    }
}

/// The chain break whose first root is `roots[0]` (`roots` sorted, the rest after it): roots
/// within `SIMULTANEOUS` of the first are one change (see there), and the turn is swept again
/// past the last of them, halfway to the next root or `SIMULTANEOUS` on, whichever is nearer.
fn break_at(roots: &[(f64, Change)], phi1: f64) -> ChainBreak {
    let root = roots[0].0;
    let scale = 1.0 + root.abs();
    let last = roots
        .iter()
        .map(|&(phi, _)| phi)
        .take_while(|&phi| phi <= root + SIMULTANEOUS * scale)
        .last()
        .unwrap_or(root);
    let next = roots
        .iter()
        .map(|&(phi, _)| phi)
        .find(|&phi| phi > last)
        .unwrap_or(phi1);
    let look_at = last + (SIMULTANEOUS * scale).min(0.5 * (next - last));
    ChainBreak { root, look_at }
}

/// Where a held gear's chain may break: the first root of the change, and the driver angle
/// just past it where the turn is to be swept again. Not at the root itself: there a joint's
/// gap equals the side tolerance, and the ends' rounding (about 1e-14 rad) would decide whether
/// the gear is free, differently for roots found over different ranges. A little past it (but
/// short of the chain's next root) the gap has opened by its slope times that, far above the
/// rounding and far below the events' accuracy.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChainBreak {
    pub root: f64,
    pub look_at: f64,
}

/// Roots where an end of a link reaches a fixed driven angle: the first link's lower end
/// θ + tol (joint 0), any link's upper end θ (joints 1 to m − 1), the last link's upper end the
/// threshold (joint m).
fn ends_at_fixed_angles(
    (lower, upper): (&[Conditions], &[Conditions]),
    theta: f64,
    threshold: f64,
    tol: f64,
    (phi0, phi1): (f64, f64),
    found: &mut Vec<(f64, Change)>,
) {
    let m = lower.len();
    let mut at = |link: usize, is_upper: bool, at: f64| {
        let conditions = if is_upper { &upper[link] } else { &lower[link] };
        for c in conditions {
            for phi in c.roots_at_theta(at, phi0, phi1) {
                found.push((
                    phi,
                    Change::End {
                        link,
                        upper: is_upper,
                        at,
                    },
                ));
            }
        }
    };
    at(0, false, theta + tol);
    for link in 0..m.saturating_sub(1) {
        at(link, true, theta);
    }
    at(m - 1, true, threshold);
}

/// How far past `phi0` (up to `phi1`) the joint of `link` and `next` (the obstacles at `phi0`)
/// is proved to hold by points: a driven angle u above θ inside both, held there until an end of
/// either reaches it (the first root of their conditions `ends` at u that is that end), then a
/// new point there, a few times over.
fn held_by_points(
    mesh: &Mesh,
    (link, next): (Obstacle, Obstacle),
    ends: [&Conditions; 4],
    theta: f64,
    (phi0, phi1): (f64, f64),
) -> f64 {
    let (mut t, mut link, mut next) = (phi0, link, next);
    for _ in 0..8 {
        let (low, high) = (next.lo.max(theta), link.hi);
        let u = 0.5 * (low + high);
        if !(low < u && u < high) {
            return t;
        }
        // Each root with the link whose end it may be (0: `link`, 1: `next`).
        let mut roots: SmallVec<[(f64, usize); 16]> = SmallVec::new();
        for (e, conditions) in ends.iter().enumerate() {
            for c in conditions.iter() {
                roots.extend(c.roots_at_theta(u, t, phi1).into_iter().map(|r| (r, e / 2)));
            }
        }
        roots.sort_by(|a, b| a.0.total_cmp(&b.0));
        let near = |x: f64| (x - u).abs() <= AT_ROOT * (1.0 + u.abs());
        let crossing = roots.into_iter().find_map(|(phi, which)| {
            let o = [link, next][which];
            let inside = mesh
                .obstacle(phi, o.driver_tooth, o.driven_tooth)
                .is_some_and(|o| o.lo < u && u < o.hi && !near(o.lo) && !near(o.hi));
            (!inside).then_some(phi)
        });
        let Some(c) = crossing else {
            return phi1;
        };
        t = c;
        match (
            mesh.obstacle(t, link.driver_tooth, link.driven_tooth),
            mesh.obstacle(t, next.driver_tooth, next.driven_tooth),
        ) {
            (Some(a), Some(b)) => (link, next) = (a, b),
            _ => return t,
        }
    }
    t
}

/// Roots where link `i`'s teeth may part: its two ends met, a condition of its lower end with
/// one of its upper end.
fn partings(
    (lower, upper): (&Conditions, &Conditions),
    i: usize,
    link: &Obstacle,
    (phi0, phi1): (f64, f64),
    found: &mut Vec<(f64, Change)>,
) {
    for first in lower {
        for second in upper {
            for (phi, _) in meetings(first, second, phi0, phi1, link.hi) {
                found.push((phi, Change::Parting { link: i }));
            }
        }
    }
}

/// Whether the root at φ is the change it stands for: the ends it names are there (or the
/// link's teeth no longer touch at all, which changes the chain too).
fn changes(mesh: &Mesh, chain: &[Obstacle], phi: f64, change: Change, tol: f64) -> bool {
    let near = |x: f64, y: f64| (x - y).abs() <= AT_ROOT * (1.0 + y.abs());
    let at = |i: usize| mesh.obstacle(phi, chain[i].driver_tooth, chain[i].driven_tooth);
    match change {
        Change::End { link, upper, at: a } => at(link).is_none_or(|o| {
            let end = if upper { o.hi } else { o.lo };
            near(end, a)
        }),
        Change::Joint { below, theta } => match (at(below), at(below + 1)) {
            (Some(c), Some(next)) => near(c.hi + tol, theta) && near(next.lo, theta),
            _ => true,
        },
        Change::Parting { link } => at(link).is_none_or(|o| near(o.lo, o.hi)),
    }
}

#[cfg(test)]
#[path = "../tests/unit/held.rs"]
mod tests;
