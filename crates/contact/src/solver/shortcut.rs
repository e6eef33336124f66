//! The boundary between the exact core and the speed layer on top of it. The core offers the
//! speed layer, passed to each step, the work it may take over - a pushed gear's step, where the
//! layer proves that no event lies in it; the joints of a held gear's chain it proves to hold; the
//! contact conditions a closing's search need not take - and lets it read where the run stands
//! ([`Stand`]) and move it on a proved step ([`Run::take_proved_step`]). The core never names the
//! layer (`entry.rs` builds it for a run); [`ExactOnly`], which proves nothing, is the exact core
//! alone, and no result depends on which: `tests/differential.rs` holds the two to the same
//! events, bit for bit.

// Without the speed layer nothing reads or moves the run through this boundary.
#![cfg_attr(
    not(feature = "speed"),
    allow(dead_code, reason = "the speed layer's side of the boundary")
)]

use super::{Motion, Pairs, Run, Segment, Side, Tracked};
use crate::held::Chain;
use crate::mesh::{ConditionSet, Mesh};

/// What the speed layer may do for the exact core, one run at a time. Each method may prove that
/// part of an exact search would find nothing, so that the core leaves it out; or prove nothing
/// (the defaults), so that the core searches it all.
pub(crate) trait Shortcut {
    /// Takes the pushed step from the run's (φ, θ) to `phi1` (`pushers` push the driven gear
    /// there) on a proof that no event lies in it, moving the run on exactly as the exact step
    /// would ([`Run::take_proved_step`]), and returns whether it did; if not, the run is as it
    /// was.
    fn pushed_step(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        let _ = (run, phi1, pushers);
        false
    }

    /// The joints of a held gear's `chain` (each by the index of its lower link, the first of
    /// those a turn apart) that the core must search from the chain's driver angle to `phi1`,
    /// the gear held at `theta`: every other joint is proved to hold throughout, by a margin that
    /// no root of its search could come within (`held.rs`). None: every joint is searched.
    fn held_joints(&mut self, chain: &mut Chain<'_>, theta: f64, phi1: f64) -> Option<Vec<usize>> {
        let _ = (chain, theta, phi1);
        None
    }

    /// Of the contact conditions of tooth pair `pair` (those of both sides), the ones that may
    /// hold somewhere in the box of driver angles `phi` and driven angles `theta`: a search for
    /// roots in the box may leave the others out. All, unless proved otherwise.
    fn conditions_in_box(
        &mut self,
        mesh: &Mesh,
        pair: (i64, i64),
        phi: (f64, f64),
        theta: (f64, f64),
    ) -> ConditionSet {
        let _ = (mesh, pair, phi, theta);
        ConditionSet::ALL
    }
}

/// The exact core alone: proves nothing, so every step is exact and every search whole.
pub(crate) struct ExactOnly;

impl Shortcut for ExactOnly {}

/// A tooth pair as a proved step leaves it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairAtEnd {
    pub(crate) pair: (i64, i64),
    /// Upper end of its obstacle at the step's end (−∞ if gone, or not needed).
    pub(crate) hi: f64,
    /// Whether its contacts rose through the step (it may carry the driven gear), else fell.
    pub(crate) rising: bool,
}

/// Where a run stands between steps, as the speed layer reads it: the mesh, the driver and
/// driven angles, and the tooth pairs near the driven gear with their sides and upper ends. The
/// run's own ([`Run::stand`]), or where proved steps would leave it ([`Moved`]).
#[derive(Clone, Copy)]
pub(crate) struct Stand<'r, 'm> {
    mesh: &'m Mesh,
    phi: f64,
    theta: f64,
    sides: &'r [Tracked],
}

/// Where a proved step would leave a run ([`Stand::after_proved`]), the run itself not moved:
/// the speed layer proves a step's second half from there before it moves the run over both.
pub(crate) struct Moved<'m> {
    mesh: &'m Mesh,
    phi: f64,
    theta: f64,
    sides: Vec<Tracked>,
}

impl<'m> Stand<'_, 'm> {
    /// The mesh the run is on.
    pub(crate) fn mesh(&self) -> &'m Mesh {
        self.mesh
    }

    /// The driver and driven angles the run stands at.
    pub(crate) fn at(&self) -> (f64, f64) {
        (self.phi, self.theta)
    }

    /// The tooth pairs near the driven gear, with their sides and upper ends at φ.
    pub(crate) fn tracked(&self) -> &[Tracked] {
        self.sides
    }

    /// The side of the driven gear `pair` is known to lie on, if it is tracked.
    pub(crate) fn side_of(&self, pair: (i64, i64)) -> Option<Side> {
        self.sides.iter().find(|t| t.pair == pair).map(|t| t.side)
    }

    /// The pushing pairs: those behind the driven gear whose upper end is at θ.
    pub(crate) fn pushers(&self) -> Pairs {
        self.sides
            .iter()
            .filter(|t| t.pushes(self.theta))
            .map(|t| t.pair)
            .collect()
    }

    /// Where the step to (`phi1`, `theta1`) proved free of events would leave the run, pushed by
    /// the rising pairs of `pairs` ([`Run::take_proved_step`]), without moving it.
    pub(crate) fn after_proved(&self, phi1: f64, theta1: f64, pairs: &[PairAtEnd]) -> Moved<'m> {
        let mut sides = self.sides.to_vec();
        proved_sides(&mut sides, self.mesh, phi1, pairs);
        Moved {
            mesh: self.mesh,
            phi: phi1,
            theta: theta1,
            sides,
        }
    }
}

impl<'m> Moved<'m> {
    /// Where the run would stand.
    pub(crate) fn stand(&self) -> Stand<'_, 'm> {
        Stand {
            mesh: self.mesh,
            phi: self.phi,
            theta: self.theta,
            sides: &self.sides,
        }
    }
}

/// The tooth pairs near the driven gear as a step proved free of events leaves them, at its end
/// `phi1`: each of `pairs` with its upper end there; the sides stay (nothing crossed θ), and a
/// pair behind that `pairs` does not hold stayed clear of the path, so it is no pusher at `phi1`.
// Inlined into the proved step, which takes it at every certified step.
#[inline(always)]
fn proved_sides(sides: &mut Vec<Tracked>, mesh: &Mesh, phi1: f64, pairs: &[PairAtEnd]) {
    // Pairs whose driver tooth has left the window (teeth enter it at lower indices as the
    // driver turns, and leave it at higher ones) are done with.
    let last = *mesh.driver_teeth(phi1).end();
    sides.retain(|t| t.pair.0 <= last);
    for t in sides.iter_mut() {
        match pairs.iter().find(|m| m.pair == t.pair) {
            Some(m) => t.hi = m.hi,
            None if t.side == Side::Behind => t.hi = f64::NEG_INFINITY,
            None => {}
        }
    }
    for m in pairs {
        if !sides.iter().any(|t| t.pair == m.pair) {
            sides.push(Tracked {
                pair: m.pair,
                side: Side::Behind,
                hi: m.hi,
            });
        }
    }
}

impl<'m> Run<'m> {
    /// Where the run stands.
    pub(crate) fn stand(&self) -> Stand<'_, 'm> {
        Stand {
            mesh: self.mesh,
            phi: self.phi,
            theta: self.theta,
            sides: &self.sides,
        }
    }

    /// Whether an event waits for the drive to resume to be sized: a proved push would size it.
    pub(crate) fn sizing_waits(&self) -> bool {
        !self.sizing.pending.is_empty()
    }

    /// Moves the run to (`phi1`, `theta1`) along a step proved free of events: pushed by the
    /// rising pairs of `pairs`, each of `pairs` with its upper end at `phi1` (`proved_sides`).
    pub(crate) fn take_proved_step(&mut self, phi1: f64, theta1: f64, pairs: &[PairAtEnd]) {
        let mut rising = self.spare_pairs();
        rising.extend(pairs.iter().filter(|m| m.rising).map(|m| m.pair));
        self.push_segment(phi1, theta1, Motion::Push(rising));
        proved_sides(&mut self.sides, self.mesh, phi1, pairs);
    }

    /// An empty list for the pairs of the next segment: the last segment's own when only the last
    /// is kept (it is about to be replaced), so that a step allocates nothing for it.
    fn spare_pairs(&mut self) -> Vec<(i64, i64)> {
        match self.segments.last_mut() {
            Some(Segment {
                motion: Motion::Push(pairs),
                ..
            }) if !self.keep_segments => {
                let mut spare = std::mem::take(pairs);
                spare.clear();
                spare
            }
            _ => Vec::new(),
        }
    }
}
