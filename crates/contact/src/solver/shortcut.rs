//! The boundary between the exact core and the speed layer on top of it. The core offers the
//! speed layer one thing to take over - a pushed gear's step, where the layer proves that no event
//! lies in it - and lets it read and move the run through the few methods below. The core never
//! names the layer (`entry.rs` builds it for a run); a run without it is the exact core alone,
//! and no result depends on which: `tests/differential.rs` holds the two to the same events, bit
//! for bit.

// Without the speed layer nothing reads or moves the run through this boundary.
#![cfg_attr(
    not(feature = "speed"),
    allow(dead_code, reason = "the speed layer's side of the boundary")
)]

use smallvec::SmallVec;

use super::{Motion, Run, Segment, Side, Tracked};
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
    fn pushed_step(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool;

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

/// A tooth pair as a proved step leaves it.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairAtEnd {
    pub(crate) pair: (i64, i64),
    /// Upper end of its obstacle at the step's end (−∞ if gone, or not needed).
    pub(crate) hi: f64,
    /// Whether its contacts rose through the step (it may carry the driven gear), else fell.
    pub(crate) rising: bool,
}

/// The run as it was before steps the speed layer may yet take back ([`Run::checkpoint`]).
pub(crate) struct Checkpoint {
    phi: f64,
    theta: f64,
    sides: SmallVec<[Tracked; 16]>,
    segments: usize,
    /// The last segment, set aside where only the last is kept (a step replaces it).
    last: Option<Segment>,
}

impl<'m> Run<'m> {
    /// The mesh the run is on.
    pub(crate) fn mesh(&self) -> &'m Mesh {
        self.mesh
    }

    /// The driver and driven angles the run has reached.
    pub(crate) fn at(&self) -> (f64, f64) {
        (self.phi, self.theta)
    }

    /// The tooth pairs near the driven gear, with their sides and upper ends at the current φ.
    pub(crate) fn tracked(&self) -> &[Tracked] {
        &self.sides
    }

    /// Whether an event waits for the drive to resume to be sized: a proved push would size it.
    pub(crate) fn sizing_waits(&self) -> bool {
        !self.pending.is_empty()
    }

    /// Moves the run to (`phi1`, `theta1`) along a step proved free of events: pushed by the
    /// rising pairs of `pairs`, each of `pairs` with its upper end at `phi1`; the sides stay
    /// (nothing crossed θ), and a pair behind that `pairs` does not hold stayed clear of the
    /// path, so it is no pusher at `phi1`.
    pub(crate) fn take_proved_step(&mut self, phi1: f64, theta1: f64, pairs: &[PairAtEnd]) {
        let mut rising = self.spare_pairs();
        rising.extend(pairs.iter().filter(|m| m.rising).map(|m| m.pair));
        self.push_segment(phi1, theta1, Motion::Push(rising));
        // Pairs whose driver tooth has left the window (teeth enter it at lower indices as the
        // driver turns, and leave it at higher ones) are done with.
        let last = *self.mesh.driver_teeth(phi1).end();
        self.sides.retain(|t| t.pair.0 <= last);
        for t in &mut self.sides {
            match pairs.iter().find(|m| m.pair == t.pair) {
                Some(m) => t.hi = m.hi,
                None if t.side == Side::Behind => t.hi = f64::NEG_INFINITY,
                None => {}
            }
        }
        for m in pairs {
            if self.side_of(m.pair).is_none() {
                self.sides.push(Tracked {
                    pair: m.pair,
                    side: Side::Behind,
                    hi: m.hi,
                });
            }
        }
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

    /// The run as it is, to be restored if the proved steps taken after this do not stand
    /// ([`Run::restore`]); where only the last segment is kept, it is set aside until then.
    pub(crate) fn checkpoint(&mut self) -> Checkpoint {
        Checkpoint {
            phi: self.phi,
            theta: self.theta,
            sides: SmallVec::from_slice(&self.sides),
            segments: self.segments.len(),
            last: if self.keep_segments {
                None
            } else {
                self.segments.pop()
            },
        }
    }

    /// The run as it was at `checkpoint`.
    pub(crate) fn restore(&mut self, checkpoint: Checkpoint) {
        (self.phi, self.theta) = (checkpoint.phi, checkpoint.theta);
        self.sides.clear();
        self.sides.extend_from_slice(&checkpoint.sides);
        if self.keep_segments {
            self.segments.truncate(checkpoint.segments);
        } else {
            self.segments.clear();
            self.segments.extend(checkpoint.last);
        }
    }
}
