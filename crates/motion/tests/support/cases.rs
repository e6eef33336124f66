//! Random manufactured meshes for the motion models' property tests: each tip moved by a
//! random share of the pitch, each gear turning about an offset centre, at a random clearance;
//! the solver's mesh and the independent polygon oracle's of each.

use std::f64::consts::TAU;
use std::ops::Range;

use contact::Mesh;
use geometry::{Gear, Vec2};
use proptest::prelude::*;

/// One gear as plain numbers.
#[derive(Debug, Clone)]
pub struct GearSpec {
    pub r_tip: f64,
    pub r_root: f64,
    pub tips: Vec<f64>,
    pub ecc: [f64; 2],
}

impl GearSpec {
    fn gear(&self) -> Option<Gear> {
        Gear::new(
            self.r_tip,
            self.r_root,
            self.tips.clone(),
            Vec2::new(self.ecc[0], self.ecc[1]),
        )
        .ok()
    }

    fn shape(&self) -> Option<polycheck::GearShape> {
        let g = self.gear()?;
        Some(polycheck::GearShape {
            outline: g.outline().iter().map(|v| [v.x, v.y]).collect(),
            rotation_centre_offset: self.ecc,
        })
    }
}

/// A mesh and the driver range a property runs over.
#[derive(Debug, Clone)]
pub struct Case {
    pub driver: GearSpec,
    pub driven: GearSpec,
    /// Clearance, % of h.
    pub g: f64,
    pub h: f64,
    pub phi0: f64,
    /// Driver pitches run.
    pub pitches: f64,
}

impl Case {
    pub fn centre_distance(&self) -> f64 {
        geometry::centre_distance(self.driver.r_tip, self.driven.r_tip, self.h, self.g)
    }

    pub fn mesh(&self) -> Option<Mesh> {
        Mesh::new(
            self.driver.gear()?,
            self.driven.gear()?,
            self.centre_distance(),
        )
        .ok()
    }

    #[allow(
        clippy::unwrap_used,
        reason = "tests: a case whose mesh exists has gears"
    )]
    pub fn oracle(&self) -> polycheck::Mesh {
        polycheck::Mesh {
            driver: self.driver.shape().unwrap(),
            driven: self.driven.shape().unwrap(),
            centre_distance: self.centre_distance(),
        }
    }

    #[allow(dead_code, reason = "not every test file asks for it")]
    pub fn ratio(&self) -> f64 {
        self.driver.tips.len() as f64 / self.driven.tips.len() as f64
    }

    pub fn phi_end(&self) -> f64 {
        self.phi0 + self.pitches * TAU / self.driver.tips.len() as f64
    }
}

/// A gear of `n` teeth of module 0.5 (tip radius n / 4 mm), h = 1.1 mm, each tip moved by up to
/// `sigma` of the pitch (`u` in [-1, 1]), its centre offset by `e` mm at angle `a`.
fn spec(n: usize, sigma: f64, u: &[f64], e: f64, a: f64) -> GearSpec {
    let r_tip = n as f64 * 0.25;
    let pitch = TAU / n as f64;
    GearSpec {
        r_tip,
        r_root: r_tip - 1.1,
        tips: (0..n).map(|k| pitch * (k as f64 + sigma * u[k])).collect(),
        ecc: [e * a.cos(), e * a.sin()],
    }
}

/// Cases of 12-60 teeth a gear, tip errors up to 0.12 of the pitch, offsets up to 0.15 mm, at a
/// clearance drawn from `g`, run over 3-6 driver pitches.
pub fn case(g: Range<f64>) -> impl Strategy<Value = Case> {
    (12usize..60, 12usize..60)
        .prop_flat_map(move |(n1, n2)| {
            (
                Just((n1, n2)),
                prop::collection::vec(-1.0..1.0f64, n1),
                prop::collection::vec(-1.0..1.0f64, n2),
                0.0..0.12f64,
                (0.0..0.15f64, 0.0..TAU, 0.0..0.15f64, 0.0..TAU),
                g.clone(),
                (0.0..TAU, 3.0..6.0f64),
            )
        })
        .prop_map(
            |((n1, n2), u1, u2, sigma, (e1, a1, e2, a2), g, (phi0, pitches))| Case {
                driver: spec(n1, sigma, &u1, e1, a1),
                driven: spec(n2, sigma, &u2, e2, a2),
                g,
                h: 1.1,
                phi0,
                pitches,
            },
        )
}
