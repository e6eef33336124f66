//! The speed layer, on top of the exact core: proofs that let a run skip work of the core without
//! changing any result. Built per run from the mesh ([`Certifier::new`], straight flanks only),
//! it holds the certificates of the mesh's teeth and what it keeps from step to step, and takes
//! what the core offers it through `Shortcut` (`solver/shortcut.rs`):
//!
//! - a pushed gear's step, taken on a certificate ([`Certifier::try_certified`] in
//!   `certified.rs`, on the bounds of `certify.rs`) where every tooth pair near the driven gear
//!   is proved either to stay clear of it or, behind it, only to push it forwards.
//!
//! Everything here may be left out (the crate's `speed` feature) without changing a result:
//! `tests/differential.rs` holds runs with and without it to the same events, bit for bit.

use crate::mesh::{Mesh, Placed};
use crate::solver::{Pairs, Run, Shortcut};

mod certified;
mod certify;

use certify::CertTooth;

/// The speed layer of one run: the certificates of both gears' teeth, and the pairs the last
/// certified step proved ahead of the driven gear.
pub(crate) struct Certifier {
    driver: Vec<CertTooth>,
    driven: Vec<CertTooth>,
    /// Untracked tooth pairs known to be ahead of the driven gear, or gone, at (φ, θ): the
    /// suspects the last certified step ending there proved clear of its path, so the next
    /// step need not evaluate them to find where they start.
    clear_ahead: (f64, f64, Pairs),
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
    fn known_clear_ahead(&self, run: &Run<'_>, pair: (i64, i64)) -> bool {
        let (phi, theta, pairs) = &self.clear_ahead;
        (*phi, *theta) == run.at() && pairs.contains(&pair)
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
}

impl Shortcut for Certifier {
    fn pushed_step(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        self.try_certified(run, phi1, pushers)
    }
}
