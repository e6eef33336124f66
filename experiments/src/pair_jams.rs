//! The paper's jam protocol for one mesh on its own: each trial draws both gears' errors and an
//! initial angle, runs one full turn of the gear with more teeth, and notes whether it jammed and
//! whether it disengaged at least once.

use std::f64::consts::TAU;

use contact::{Mesh, Start};
use geometry::Gear;
use hypotheses::{Hypothesis, Params};
use mechanism::trial_rng;
use rand::Rng;
use registry::RunError;
use train::Gearing;

use crate::errors;

/// One mesh under one set of errors: what a cell of Tables 3-5 and I needs.
pub struct Cell<'a> {
    /// Mesh label.
    pub mesh: &'a str,
    /// Error hypothesis and its parameters.
    pub hypothesis: &'a dyn Hypothesis,
    /// Parameters of the hypothesis.
    pub params: &'a Params,
    /// Tooth height h (mm).
    pub tooth_height: f64,
    /// Clearance G (% of h).
    pub clearance: f64,
    /// Index of the cell, which selects its RNG streams.
    pub index: u64,
}

/// (jammed at least once, disengaged at least once) for trial `t` of `cell`. Gears whose bodies
/// would overlap at every angle (a large eccentricity at a small clearance) cannot turn: a jam.
pub fn trial(g: &Gearing, cell: &Cell<'_>, seed: u64, t: u64) -> Result<(bool, bool), RunError> {
    let m = g.mesh(cell.mesh).ok_or_else(|| {
        RunError::bad(
            "--set",
            "mesh",
            format!("no mesh `{}` in the gearing", cell.mesh),
        )
    })?;
    let geo = g
        .mesh_geometry(cell.mesh, cell.tooth_height, cell.clearance)
        .ok_or_else(|| {
            RunError::bad("gearing", format!("mesh {}", cell.mesh), "cannot be sized")
        })?;
    let h = cell.tooth_height;
    let bad = |e: geometry::GeometryError| {
        RunError::bad("gearing", format!("mesh {}", cell.mesh), e.to_string())
    };
    let ideal_driver = Gear::ideal(
        geo.driver_teeth as usize,
        geo.driver_tip_radius,
        geo.driver_tip_radius - h,
    )
    .map_err(bad)?;
    let ideal_driven = Gear::ideal(
        geo.driven_teeth as usize,
        geo.driven_tip_radius,
        geo.driven_tip_radius - h,
    )
    .map_err(bad)?;
    // One stream per (cell, trial): both gears' errors, then the initial angle.
    let mut rng = trial_rng(seed, (cell.index << 32) | t);
    let driver = errors::make(
        cell.hypothesis,
        &ideal_driver,
        &m.driver,
        cell.params,
        &mut rng,
    )?;
    let driven = errors::make(
        cell.hypothesis,
        &ideal_driven,
        &m.driven,
        cell.params,
        &mut rng,
    )?;
    let phi0 = rng.random::<f64>() * TAU / driver.teeth() as f64;
    let Ok(mesh) = Mesh::new(driver, driven, geo.centre_distance) else {
        return Ok((true, false));
    };
    let turn = TAU * (geo.driver_teeth.max(geo.driven_teeth) as f64) / geo.driver_teeth as f64;
    let run = mesh.run(phi0, phi0 + turn, Start::Touching(0.0));
    Ok((run.jams() > 0, run.disengagements() > 0))
}
