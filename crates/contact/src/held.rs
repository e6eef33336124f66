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
//!
//! Each joint's roots are its own: those of joint i (0 < i < m) are the upper end of c_i at θ,
//! the meetings of c_i's upper end with c_{i+1}'s lower end, and the partings of both links, found
//! from the links alone; a root counts only where the change it stands for is there, and where
//! several changes come together only they are taken together. So a joint that the speed layer
//! proves to hold over a range (`Shortcut::held_joints`) may be left out of the search without
//! changing its answer.

use smallvec::SmallVec;

use crate::meet::{Condition, meetings};
use crate::mesh::{End, Mesh, Obstacle};
use crate::stats::count;

/// How near (radians, relative to 1 + |angle|) an obstacle's end must be to a root for the root
/// to be that end's: a root of a condition that is not the end (a flank's line beyond the tooth,
/// the other branch of a circle) lies far off it.
pub(crate) const AT_ROOT: f64 = 1e-9;

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

/// A held gear's chain at one driver angle: its links' tooth pairs, in the order the sweep took
/// them, up to the first that reaches the threshold, and each link's obstacle there, evaluated
/// when first asked for (a chain carried from the step before is not evaluated again where a
/// joint is proved to hold).
pub(crate) struct Chain<'m> {
    mesh: &'m Mesh,
    phi: f64,
    pairs: Vec<(i64, i64)>,
    at: Vec<Option<Option<Obstacle>>>,
}

impl<'m> Chain<'m> {
    /// The chain a sweep of the turn at `phi` took (`links`, its obstacles there), up to the
    /// first link that reaches `threshold` (none if none does).
    pub(crate) fn swept(mesh: &'m Mesh, phi: f64, links: &[Obstacle], threshold: f64) -> Self {
        let m = links
            .iter()
            .position(|c| c.hi >= threshold)
            .map_or(0, |i| i + 1);
        Self {
            mesh,
            phi,
            pairs: links[..m]
                .iter()
                .map(|o| (o.driver_tooth, o.driven_tooth))
                .collect(),
            at: links[..m].iter().map(|&o| Some(Some(o))).collect(),
        }
    }

    /// The chain of tooth pairs `pairs` that held the gear through the step before, at `phi`.
    pub(crate) fn carried(mesh: &'m Mesh, phi: f64, pairs: Vec<(i64, i64)>) -> Self {
        let at = vec![None; pairs.len()];
        Self {
            mesh,
            phi,
            pairs,
            at,
        }
    }

    /// The mesh the chain is on.
    #[cfg_attr(
        not(feature = "speed"),
        expect(dead_code, reason = "the speed layer's proofs read the chain")
    )]
    pub(crate) fn mesh(&self) -> &'m Mesh {
        self.mesh
    }

    /// The driver angle the chain is at.
    #[cfg_attr(
        not(feature = "speed"),
        expect(dead_code, reason = "the speed layer's proofs read the chain")
    )]
    pub(crate) fn phi(&self) -> f64 {
        self.phi
    }

    /// The links' tooth pairs, in order.
    #[cfg_attr(
        not(feature = "speed"),
        expect(dead_code, reason = "the speed layer's proofs read the chain")
    )]
    pub(crate) fn pairs(&self) -> &[(i64, i64)] {
        &self.pairs
    }

    /// Link `i`'s obstacle at the chain's driver angle (None where its teeth no longer touch).
    pub(crate) fn link(&mut self, i: usize) -> Option<Obstacle> {
        let (mesh, phi, (j, k)) = (self.mesh, self.phi, self.pairs[i]);
        *self.at[i].get_or_insert_with(|| mesh.obstacle(phi, j, k))
    }

    /// The links' tooth pairs, to carry to the next step.
    pub(crate) fn into_pairs(self) -> Vec<(i64, i64)> {
        self.pairs
    }
}

/// A joint's teeth with its driven teeth taken within the turn: joints a whole turn apart, which
/// a chain longer than a turn meets twice, have the same teeth and the same roots.
pub(crate) fn joint_key(n2: i64, link: (i64, i64), next: (i64, i64)) -> (i64, i64, i64, i64) {
    (link.0, link.1.rem_euclid(n2), next.0, next.1 - link.1)
}

/// Where a held gear's chain can no longer be read at its driver angle: a link's teeth no longer
/// touch there.
#[derive(Debug)]
pub(crate) struct LinkGone;

/// The first driver angle in `(phi0, phi1]` (`phi0` the chain's angle) at which the held gear's
/// `chain` (see the module's docs) may stop holding it at θ, or None if every joint holds
/// throughout. Of the joints between links, the first of those a turn apart are searched, or,
/// given `joints`, only those (the rest proved to hold: see the module's docs).
pub(crate) fn first_change(
    chain: &mut Chain<'_>,
    (theta, threshold, tol): (f64, f64, f64),
    phi1: f64,
    joints: Option<&[usize]>,
) -> Result<Option<ChainBreak>, LinkGone> {
    let (mesh, phi0) = (chain.mesh, chain.phi);
    let m = chain.pairs.len();
    if m == 0 {
        return Ok(None);
    }
    let cond = |(j, k): (i64, i64), end: End| mesh.conditions(j, k, end);
    let mut found: Vec<(f64, Change)> = Vec::new();
    // Joint 0 and joint m.
    let (first, last) = (chain.pairs[0], chain.pairs[m - 1]);
    let range = (phi0, phi1);
    end_roots(
        &cond(first, End::Lower),
        (0, false, theta + tol),
        range,
        &mut found,
    );
    end_roots(
        &cond(last, End::Upper),
        (m - 1, true, threshold),
        range,
        &mut found,
    );
    if m == 1 {
        let link = chain.link(0).ok_or(LinkGone)?;
        let ends = (&cond(first, End::Lower), &cond(first, End::Upper));
        partings(ends, 0, &link, range, &mut found);
    }
    let joints = joints_to_search(chain, joints);
    count(|st| {
        st.held_searches += 1;
        st.joints_searched += joints.len() as u64;
    });
    for i in joints {
        joint_roots(chain, i, (theta, tol), phi1, &mut found)?;
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    let is_change = |&(phi, change): &(f64, Change)| changes(chain, phi, change, tol);
    let Some(i) = found.iter().position(is_change) else {
        return Ok(None);
    };
    Ok(Some(break_at(&found[i..], is_change, phi1)))
}

/// The joints (each by the index of its lower link) [`first_change`] searches: `joints` if
/// given, else the first of each that a turn apart share their teeth.
fn joints_to_search(chain: &Chain<'_>, joints: Option<&[usize]>) -> Vec<usize> {
    if let Some(joints) = joints {
        return joints.to_vec();
    }
    let n2 = chain.mesh.driven.tips.len() as i64;
    let mut keyed: Vec<_> = chain
        .pairs
        .windows(2)
        .enumerate()
        .map(|(i, w)| (joint_key(n2, w[0], w[1]), i))
        .collect();
    keyed.sort_unstable();
    keyed.dedup_by_key(|(key, _)| *key);
    let mut first: Vec<usize> = keyed.into_iter().map(|(_, i)| i).collect();
    first.sort_unstable();
    first
}

/// The roots of joint `i` (between links i and i + 1) over the range from the chain's angle to
/// `phi1`, into `found`: the upper end of link i at θ, and, after the stretch the joint is proved
/// to hold by points, the meetings of link i's upper end (plus the tolerance) with link i + 1's
/// lower end and the partings of both links.
fn joint_roots(
    chain: &mut Chain<'_>,
    i: usize,
    (theta, tol): (f64, f64),
    phi1: f64,
    found: &mut Vec<(f64, Change)>,
) -> Result<(), LinkGone> {
    let (mesh, phi0) = (chain.mesh, chain.phi);
    let (link, next) = (
        chain.link(i).ok_or(LinkGone)?,
        chain.link(i + 1).ok_or(LinkGone)?,
    );
    let of = |o: &Obstacle, end: End| mesh.conditions(o.driver_tooth, o.driven_tooth, end);
    let lower = [of(&link, End::Lower), of(&next, End::Lower)];
    let upper = [of(&link, End::Upper), of(&next, End::Upper)];
    end_roots(&upper[0], (i, true, theta), (phi0, phi1), found);
    // Most joints overlap by far more than their links move: a driven angle inside both that no
    // end of either crosses proves the joint held (closed form), and only what is left of the
    // range after a few such proofs is searched for meetings.
    let ends = [&lower[0], &upper[0], &lower[1], &upper[1]];
    let from = held_by_points(mesh, (link, next), ends, theta, (phi0, phi1));
    if from >= phi1 {
        return Ok(());
    }
    for (l, o) in [link, next].iter().enumerate() {
        partings((&lower[l], &upper[l]), i + l, o, (from, phi1), found);
    }
    let below: Conditions = upper[0].iter().map(|c| c.shifted(tol)).collect();
    for above in &lower[1] {
        for below in &below {
            for (phi, theta) in meetings(above, below, from, phi1, next.lo) {
                found.push((phi, Change::Joint { below: i, theta }));
            }
        }
    }
    Ok(())
}

/// The chain break whose first change is at `roots[0]` (`roots` sorted, the candidates after
/// it, `is_change` telling a change): changes within `SIMULTANEOUS` of the first are one change
/// (see there), and the turn is swept again past the last of them, halfway to the next change
/// or `SIMULTANEOUS` on, whichever is nearer. Only changes count: a root where nothing changes,
/// of any joint, moves nothing.
fn break_at(
    roots: &[(f64, Change)],
    is_change: impl Fn(&(f64, Change)) -> bool,
    phi1: f64,
) -> ChainBreak {
    let root = roots[0].0;
    let scale = 1.0 + root.abs();
    let last = roots
        .iter()
        .take_while(|r| r.0 <= root + SIMULTANEOUS * scale)
        .filter(|r| is_change(r))
        .last()
        .map_or(root, |r| r.0);
    // Past twice `SIMULTANEOUS`, the next change no longer moves where the turn is swept.
    let next = roots
        .iter()
        .filter(|r| r.0 > last)
        .take_while(|r| r.0 < last + 2.0 * SIMULTANEOUS * scale)
        .find(|r| is_change(r))
        .map_or(phi1, |r| r.0);
    let look_at = last + (SIMULTANEOUS * scale).min(0.5 * (next - last));
    ChainBreak { root, look_at }
}

/// Where a held gear's chain may break: the first root of the change, and the driver angle
/// just past it where the turn is to be swept again. Not at the root itself: there a joint's
/// gap equals the side tolerance, and the ends' rounding (about 1e-14 rad) would decide whether
/// the gear is free, differently for roots found over different ranges. A little past it (but
/// short of the chain's next change) the gap has opened by its slope times that, far above the
/// rounding and far below the events' accuracy.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ChainBreak {
    pub root: f64,
    pub look_at: f64,
}

/// Roots where an end of link `link` (its upper end if `upper`), with conditions `conditions`,
/// reaches the fixed driven angle `at`: θ + tol for the first link's lower end (joint 0), θ for
/// a link's upper end (joints 1 to m − 1), the threshold for the last link's (joint m).
fn end_roots(
    conditions: &Conditions,
    (link, upper, at): (usize, bool, f64),
    (phi0, phi1): (f64, f64),
    found: &mut Vec<(f64, Change)>,
) {
    for c in conditions {
        for phi in c.roots_at_theta(at, phi0, phi1) {
            found.push((phi, Change::End { link, upper, at }));
        }
    }
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
fn changes(chain: &Chain<'_>, phi: f64, change: Change, tol: f64) -> bool {
    let near = |x: f64, y: f64| (x - y).abs() <= AT_ROOT * (1.0 + y.abs());
    let at = |i: usize| {
        let (j, k) = chain.pairs[i];
        chain.mesh.obstacle(phi, j, k)
    };
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
