//! The paper's kind of contact test run on the ideal pairs of Figure IV (`contact-tolerance`): an
//! overlap area ignored up to a tolerance, or tips cut flat, in place of the exact solver's
//! contact (`polycheck::area`, which shares nothing with the solver), σ against G for each mesh.

use geometry::centre_distance;
use polycheck::area::AreaPair;
use registry::{Context, RunError};
use serde::{Deserialize, Serialize};

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
    ctx: &Context,
    tests: &[Test],
    meshes: &[IdealPair],
    samples: usize,
) -> Result<Vec<Vec<Point>>, RunError> {
    let key = format!(
        "contact-tolerance curves: tests {tests:?}, grid {:?}, {samples} samples per driver pitch",
        grid()
    );
    ctx.trials_whole(&key, (tests.len() * meshes.len()) as u64, |j| {
        let (ti, mi) = (j as usize / meshes.len(), j as usize % meshes.len());
        Ok(curve(&meshes[mi], tests[ti], samples))
    })
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
