//! The speed layer, on top of the exact core: proofs that let a run skip work of the core without
//! changing any result. Built per run from the mesh ([`Certifier::new`], straight flanks only),
//! it holds the certificates of the mesh's teeth and what it keeps from step to step, and takes
//! what the core offers it through `Shortcut` (`solver/shortcut.rs`):
//!
//! - a pushed gear's step, taken on a certificate ([`Certifier::try_certified`] in
//!   `certified.rs`, on the bounds of `certify.rs`) where every tooth pair near the driven gear
//!   is proved either to stay clear of it or, behind it, only to push it forwards;
//! - a held gear's joints, each proved to hold over stretches of driver angle by a driven angle
//!   that moves with its links' overlap, kept in a queue ordered by where each proof ends, so
//!   that a step leaves to the core's search only the joints whose proofs end inside it
//!   ([`Certifier::proved_held_joints`] in `held.rs`);
//! - a closing's search, left only the contact conditions that may hold in the box of the
//!   step's driver angles and the driven angles its path covers ([`Certifier::conditions_in`]).
//!
//! Everything here may be left out (the crate's `speed` feature) without changing a result:
//! `tests/differential.rs` holds runs with and without it to the same events, bit for bit.

use crate::held::Chain;
use crate::mesh::{ConditionSet, Mesh, Placed};
use crate::solver::{Pairs, Run, Shortcut, Stand};

mod certified;
mod certify;
mod held;
mod stats;

use certify::{CertTooth, ConfigBox};
use held::HeldJoints;
pub use stats::{SpeedStats, speed_stats};

/// The speed layer of one run: the certificates of both gears' teeth, and the pairs the last
/// certified step proved ahead of the driven gear.
pub(crate) struct Certifier {
    driver: Vec<CertTooth>,
    driven: Vec<CertTooth>,
    /// Untracked tooth pairs known to be ahead of the driven gear, or gone, at (φ, θ): the
    /// suspects the last certified step ending there proved clear of its path, so the next
    /// step need not evaluate them to find where they start.
    clear_ahead: (f64, f64, Pairs),
    /// The proofs about a held gear's joints, and the queue of its chain's joints.
    held: HeldJoints,
}

impl Certifier {
    /// The speed layer for a run on `mesh`, or None where it has none (curved flanks, which the
    /// certificates do not cover).
    pub(crate) fn new(mesh: &Mesh) -> Option<Self> {
        if mesh.curved {
            return None;
        }
        let certs = |gear: &Placed| gear.teeth.iter().map(CertTooth::new).collect();
        Some(Self {
            driver: certs(&mesh.driver),
            driven: certs(&mesh.driven),
            clear_ahead: (f64::NAN, f64::NAN, Pairs::new()),
            held: HeldJoints::default(),
        })
    }

    /// Driver tooth `j`'s certificate (any unwrapped index).
    fn driver_tooth(&self, j: i64) -> &CertTooth {
        &self.driver[j.rem_euclid(self.driver.len() as i64) as usize]
    }

    /// Driven tooth `k`'s certificate (any unwrapped index).
    fn driven_tooth(&self, k: i64) -> &CertTooth {
        &self.driven[k.rem_euclid(self.driven.len() as i64) as usize]
    }

    /// Whether the last certified step proved `pair` ahead of the driven gear (or gone) where
    /// the run now is.
    fn known_clear_ahead(&self, at: &Stand<'_, '_>, pair: (i64, i64)) -> bool {
        let (phi, theta, pairs) = &self.clear_ahead;
        (*phi, *theta) == at.at() && pairs.contains(&pair)
    }

    /// Where two vertices of tooth pair (j, k) first meet (or, with `last`, meet last) while the
    /// driver turns over `range` (`certify::vertex_meeting`).
    fn vertex_meeting(
        &self,
        mesh: &Mesh,
        (j, k): (i64, i64),
        (phi0, phi1): (f64, f64),
        last: bool,
    ) -> Option<(f64, f64)> {
        certify::vertex_meeting(
            self.driver_tooth(j),
            self.driven_tooth(k),
            phi0,
            phi1,
            mesh.centre_distance,
            last,
        )
    }

    /// The contact conditions of `pair` that may hold in the box of driver angles `phi` and
    /// driven angles `theta` (`ConfigBox::conditions_in_box`).
    pub(super) fn conditions_in(
        &self,
        mesh: &Mesh,
        (j, k): (i64, i64),
        phi: (f64, f64),
        theta: (f64, f64),
    ) -> ConditionSet {
        let cell = ConfigBox::new(phi.0, phi.1, theta.0, theta.1, mesh.centre_distance);
        let (a, b) = (
            cell.place_driver(self.driver_tooth(j)),
            cell.place_driven(self.driven_tooth(k)),
        );
        ConditionSet(cell.conditions_in_box(&a, &b))
    }
}

impl Shortcut for Certifier {
    fn pushed_step(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        self.try_certified(run, phi1, pushers)
    }

    fn held_joints(&mut self, chain: &mut Chain<'_>, theta: f64, phi1: f64) -> Option<Vec<usize>> {
        Some(self.proved_held_joints(chain, theta, phi1))
    }

    fn conditions_in_box(
        &mut self,
        mesh: &Mesh,
        pair: (i64, i64),
        phi: (f64, f64),
        theta: (f64, f64),
    ) -> ConditionSet {
        self.conditions_in(mesh, pair, phi, theta)
    }
}
