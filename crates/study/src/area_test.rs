//! The paper's kind of contact test run on the ideal pairs of Figure IV (`contact-tolerance`): an
//! overlap area ignored up to a tolerance, or tips cut flat, in place of the exact solver's
//! contact (`polycheck::area`, which shares nothing with the solver), σ against G for each mesh;
//! and the stepped area test on the per-mesh tables' manufactured gears beside the exact solver
//! (`jam-readings`, `polycheck::stepped`), trial by trial on the cells' own streams.

use contact::{Event, Solve, Start};
use geometry::{Gear, centre_distance};
use polycheck::area::AreaPair;
use polycheck::stepped::{GearOutline, SteppedPair, Stepping};
use registry::{RunError, TrialEngine, fnv1a64};
use serde::{Deserialize, Serialize};

use train::Gearing;

use crate::cell::{CellSpec, Drawn, Rebuilt, draw_trial};
use crate::drive::{Drive, Driver};
use crate::limits::IdealPair;

/// One contact test: an overlap area ignored (mm²) and a tip cut (% of h); a ladder of tests
/// sets at most one of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Test {
    /// Overlap area ignored (mm²); 0 is the exact test.
    pub tolerance: f64,
    /// Depth cut flat off every tip (% of h).
    pub blunt: f64,
}

/// One point of a σ(G) curve, as recorded by the trial engine (NaN bits survive).
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct Point {
    /// Clearance G (% of h).
    #[serde(with = "registry::f64_bits")]
    pub g: f64,
    /// σ of the driven gear's Theoretical Difference, degrees; NaN when the pair does not run
    /// (jams, or never touches).
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Whether the driven gear stood still at some sample (contact lost).
    pub lost: bool,
}

/// The clearance grid, % of h: 10 to 100 by 5.
pub fn grid() -> Vec<f64> {
    (2..=20).map(|i| 5.0 * f64::from(i)).collect()
}

/// σ(G) of one mesh under one test over the grid, `samples` driver angles per driver pitch.
pub fn curve(pair: &IdealPair, test: Test, samples: usize) -> Vec<Point> {
    grid()
        .into_iter()
        .map(|g| {
            let area = AreaPair {
                n1: pair.n1,
                n2: pair.n2,
                r1: pair.r1,
                r2: pair.r2,
                h: pair.h,
                centre_distance: centre_distance(pair.r1, pair.r2, pair.h, g),
                tolerance: test.tolerance,
                blunt: test.blunt * pair.h / 100.0,
            };
            match area.run_pitch(samples) {
                Some(run) => Point {
                    g,
                    sigma: run.sigma_deg,
                    lost: run.lost_contact,
                },
                None => Point {
                    g,
                    sigma: f64::NAN,
                    lost: true,
                },
            }
        })
        .collect()
}

/// Every (test, mesh) curve, test by test, each test's meshes in order: one whole batch of the
/// trial engine (job j is test j / meshes, mesh j % meshes), the same bits for any thread count
/// or shard.
pub fn curves(
    engine: &TrialEngine,
    tests: &[Test],
    meshes: &[IdealPair],
    samples: usize,
) -> Result<Vec<Vec<Point>>, RunError> {
    let key = format!(
        "contact-tolerance curves: tests {tests:?}, grid {:?}, {samples} samples per driver pitch",
        grid()
    );
    engine.trials_whole(&key, (tests.len() * meshes.len()) as u64, |j| {
        let (ti, mi) = (j as usize / meshes.len(), j as usize % meshes.len());
        Ok(curve(&meshes[mi], tests[ti], samples))
    })
}

/// One contact test of `jam-readings`, applied to every cell alike.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reading {
    /// Our exact solver with the gear `drive` names driving (the same manufactured gears): a jam
    /// is a contact stop (lock, strike, blocked start).
    Exact(Drive),
    /// The stepped area test ignoring overlaps up to this area (mm²), with the gear `drive` names
    /// driving.
    Area(f64, Drive),
}

/// A gear's outline as plain numbers for the area test (straight flanks only).
fn outline(g: &Gear) -> Result<GearOutline, RunError> {
    if g.flank_sagitta() != 0.0 {
        return Err(RunError::bad(
            "--hypothesis",
            "flank_sagitta",
            "the area test takes straight flanks only",
        ));
    }
    let n = g.teeth() as i64;
    let e = g.rotation_centre();
    Ok(GearOutline {
        tips: g.tip_angles().to_vec(),
        valleys: g.valley_angles().to_vec(),
        tip_radii: (0..n).map(|k| g.tip_radius_of(k)).collect(),
        root_radii: (0..n).map(|k| g.root_radius_of(k)).collect(),
        rotation_centre: [e.x, e.y],
    })
}

/// Trial `t` of `spec` under every reading: bit r set when reading r jams.
fn trial(
    g: &Gearing,
    spec: &CellSpec,
    seed: u64,
    t: u64,
    readings: &[Reading],
    stepping: &Stepping,
) -> Result<u64, RunError> {
    let drawn = draw_trial(g, spec, seed, t)?;
    // The exact solver's verdict with each gear driving, run at most once each.
    let mut exact: [Option<bool>; 2] = [None, None];
    let mut bits = 0;
    for (r, reading) in readings.iter().enumerate() {
        let jam = match *reading {
            Reading::Exact(drive) => {
                let driver = drive.driver(drawn.coin());
                let i = usize::from(driver == Driver::Other);
                match exact[i] {
                    Some(jam) => jam,
                    None => *exact[i].insert(exact_jams(&drawn, driver)),
                }
            }
            Reading::Area(tol, drive) => area_jams(
                &drawn.driven_by(drive.driver(drawn.coin())),
                spec,
                tol,
                stepping,
            )?,
        };
        bits |= u64::from(jam) << r;
    }
    Ok(bits)
}

/// Whether the exact solver finds a contact stop in the trial with `driver` driving; gears
/// whose bodies overlap at every angle cannot turn, a jam.
fn exact_jams(drawn: &Drawn, driver: Driver) -> bool {
    let run = drawn.driven_by(driver);
    let Some(mesh) = run.mesh.as_ref() else {
        return true;
    };
    let stop = |events: &[Event]| events.iter().any(|e| e.kind.is_contact_stop());
    let end = run.phi0 + run.turn;
    stop(&mesh.solve(
        run.phi0..=end,
        Start::Touching(0.0),
        Solve::events().until_answered(&stop),
    ))
}

/// Whether the stepped area test at tolerance `tol` finds a jam in the trial `run`.
fn area_jams(
    run: &Rebuilt,
    spec: &CellSpec,
    tol: f64,
    stepping: &Stepping,
) -> Result<bool, RunError> {
    let Some(mesh) = run.mesh.as_ref() else {
        // Bodies that overlap at every angle cannot turn under any contact test.
        return Ok(true);
    };
    let (driver, driven) = (outline(mesh.driver())?, outline(mesh.driven())?);
    let pair = SteppedPair::new(
        &driver,
        &driven,
        mesh.centre_distance(),
        tol,
        spec.tooth_height,
    );
    Ok(pair.run(run.phi0, run.turn, 0.0, stepping).jam.is_some())
}

/// Every run cell's jam count under every reading: `jams[run][reading]`.
pub fn run_all(
    engine: &TrialEngine,
    g: &Gearing,
    runs: &[CellSpec],
    readings: &[Reading],
    stepping: &Stepping,
    trials: u64,
) -> Result<Vec<Vec<u64>>, RunError> {
    // The batch key names everything its trials depend on: the cells' contents, the readings
    // and the stepping (hashed, as the text is long).
    let mut text: String = runs.iter().map(|c| c.canonical() + "\n").collect();
    text.push_str(&format!("{readings:?};{stepping:?};{trials}"));
    let key = format!("jam-readings:{:016x}", fnv1a64(text.as_bytes()));
    // One flat batch (cell-major), so every thread has work however few trials a cell has;
    // each trial's stream is its cell's and its index's, so the thread count changes nothing.
    let bits = engine.trials(&key, runs.len() as u64 * trials, |i| {
        let spec = &runs[(i / trials) as usize];
        trial(g, spec, engine.seed(), i % trials, readings, stepping)
    })?;
    Ok(runs
        .iter()
        .enumerate()
        .map(|(c, _)| {
            let cell = &bits[c * trials as usize..(c + 1) * trials as usize];
            (0..readings.len())
                .map(|r| cell.iter().filter(|b| *b >> r & 1 == 1).count() as u64)
                .collect()
        })
        .collect())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use train::Gearing;

    /// The polygon model's exact test is our contact solver's Figure IV: the same σ at 40 and
    /// 60 % for every mesh, within 1 % (sampling: one pitch here, a full turn there).
    #[test]
    fn the_exact_area_test_is_the_contact_solvers_figure_iv() {
        let g = Gearing::freeth2006();
        let h = crate::gearing::TOOTH_HEIGHT.default.parse().unwrap();
        for m in g.meshes() {
            let pair = IdealPair::of_mesh(&g, &m.label, h).unwrap();
            let exact = Test {
                tolerance: 0.0,
                blunt: 0.0,
            };
            let ours = curve(&pair, exact, 200);
            for gp in [40.0, 60.0] {
                let run = pair.run(gp).unwrap().unwrap();
                let want = pair.td_sigma(&run, 2000).sigma;
                let got = ours.iter().find(|p| p.g == gp).unwrap();
                assert!(!got.lost, "{} at {gp}", m.label);
                assert!(
                    (got.sigma / want - 1.0).abs() < 0.01,
                    "{} at {gp}: {} vs {want}",
                    m.label,
                    got.sigma
                );
            }
        }
    }
}
