//! The candidate readings of the paper's inputs and method that `sigma-causes` runs side by
//! side on the same draws: the gears and centre distances each reading gives, Table 1's σ per
//! trial under each, and Figure IV's minimum of each mesh under each.

use std::collections::BTreeMap;

use geometry::Gear;
use mechanism::{Mechanism, PointerRun};
use registry::{RunError, Streams, TrialEngine};
use serde::{Deserialize, Serialize};
use train::Gearing;

use crate::draws::Draws;
use crate::limits::IdealPair;
use crate::pointers::samples_for;

/// How the tip radii are chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Radii {
    /// `crates/train`: one least-squares scale per group of meshed gears, R = mu N (ours).
    LeastSquares,
    /// The same fit, to the Freeth 2006 radius plus h/2: his radius (the mean of the best-fit
    /// inner and outer radius) read as mid-height, so the tip lies h/2 beyond it.
    MidHeight,
    /// The gear with most teeth (of those measured) in each group keeps its Freeth 2006 radius
    /// exactly; its partners follow by the tooth ratio.
    LargestKept,
    /// Freeth et al. 2021, Table S8 outer radii (the embedded `freeth2021`), least squares.
    Freeth2021,
}

/// One candidate reading: what differs from ours.
#[derive(Debug, Clone, Copy)]
pub struct Reading {
    /// Short name, as printed.
    pub name: &'static str,
    /// Whether it keeps to the paper's stated inputs (a reading of them) or departs from them.
    pub stated: &'static str,
    /// How the tip radii are chosen.
    pub radii: Radii,
    /// Tooth height h of every gear, mm.
    pub tooth_height: f64,
    /// Centre distance added to every mesh, % of h (D = R1 + R2 - h + (G + extra) h / 100).
    pub extra_clearance: f64,
    /// G is a percentage of the flank length (the slant height of a tooth, tip to valley; the
    /// mean of the two gears') instead of the radial height h.
    pub per_flank: bool,
}

impl Reading {
    /// The clearance in % of h (the paper's formula, ours) that this reading's `g_percent`
    /// amounts to on a mesh of teeth `n1`, `n2` and tip radii `r1`, `r2`.
    pub fn clearance(&self, g_percent: f64, n1: usize, n2: usize, r1: f64, r2: f64) -> f64 {
        let h = self.tooth_height;
        let flank = |tip: f64, n: usize| {
            let root = tip - h;
            (tip * tip + root * root - 2.0 * tip * root * (std::f64::consts::PI / n as f64).cos())
                .sqrt()
        };
        let scale = if self.per_flank {
            0.5 * (flank(r1, n1) + flank(r2, n2)) / h
        } else {
            1.0
        };
        g_percent * scale + self.extra_clearance
    }
}

/// The readings that change the gears or their centre distances: they move both Figure IV and
/// Table 1. (Readings of the sampling, the statistic, the span and the initial angles change
/// Table 1 only and are run on the first reading's gears.)
pub const GEOMETRY: [Reading; 7] = [
    Reading {
        name: "as built: least-squares radii, h = 1.1 mm, D = R1 + R2 - h + G",
        stated: "yes (ours)",
        radii: Radii::LeastSquares,
        tooth_height: 1.1,
        extra_clearance: 0.0,
        per_flank: false,
    },
    Reading {
        name: "radii: tip = Freeth 2006 radius + h/2 (his radius read as mid-height)",
        stated: "another reading",
        radii: Radii::MidHeight,
        tooth_height: 1.1,
        extra_clearance: 0.0,
        per_flank: false,
    },
    Reading {
        name: "radii: largest gear of each group keeps its Freeth 2006 radius",
        stated: "another reading",
        radii: Radii::LargestKept,
        tooth_height: 1.1,
        extra_clearance: 0.0,
        per_flank: false,
    },
    Reading {
        name: "radii: Freeth 2021 outer radii (Table S8)",
        stated: "no: other data",
        radii: Radii::Freeth2021,
        tooth_height: 1.1,
        extra_clearance: 0.0,
        per_flank: false,
    },
    Reading {
        name: "tooth height 0.85 mm",
        stated: "no: paper says 1.1 mm",
        radii: Radii::LeastSquares,
        tooth_height: 0.85,
        extra_clearance: 0.0,
        per_flank: false,
    },
    Reading {
        name: "D larger by 5 % of h (0.055 mm) on every mesh",
        stated: "no: not the paper's D",
        radii: Radii::LeastSquares,
        tooth_height: 1.1,
        extra_clearance: 5.0,
        per_flank: false,
    },
    Reading {
        name: "G as a percentage of the flank length (tip to valley), not of h",
        stated: "another reading",
        radii: Radii::LeastSquares,
        tooth_height: 1.1,
        extra_clearance: 0.0,
        per_flank: true,
    },
];

/// Tip radius of every gear in a mesh under `rule` (mm).
pub fn tip_radii(
    g: &Gearing,
    g2021: &Gearing,
    rule: Radii,
    h: f64,
) -> Result<BTreeMap<String, f64>, RunError> {
    let teeth = |name: &str| g.gear(name).map_or(0.0, |x| f64::from(x.teeth));
    let mut out = BTreeMap::new();
    for c in g.components() {
        if c.meshes.is_empty() {
            continue;
        }
        let measured: Vec<(f64, f64)> = c
            .gears
            .iter()
            .filter_map(|n| Some((teeth(n), g.gear(n)?.measured_radius?)))
            .collect();
        let mu = match rule {
            Radii::LeastSquares => c.mu,
            Radii::MidHeight => {
                let na: f64 = measured.iter().map(|(n, a)| n * (a + 0.5 * h)).sum();
                let nn: f64 = measured.iter().map(|(n, _)| n * n).sum();
                na / nn
            }
            Radii::LargestKept => {
                measured
                    .iter()
                    .copied()
                    .fold(
                        (0.0, c.mu),
                        |best, (n, a)| {
                            if n > best.0 { (n, a / n) } else { best }
                        },
                    )
                    .1
            }
            Radii::Freeth2021 => {
                let first = c.gears.first().map_or("", String::as_str);
                g2021.tip_radius(first).unwrap_or(f64::NAN) / teeth(first)
            }
        };
        if !(mu.is_finite() && mu > 0.0) {
            return Err(RunError::bad(
                "gearing",
                format!("group of {}", c.gears.join(", ")),
                "cannot be sized under this reading",
            ));
        }
        for n in &c.gears {
            out.insert(n.clone(), mu * teeth(n));
        }
    }
    Ok(out)
}

/// The ideal mechanism of a reading: its radii and tooth height, and every centre distance
/// D = R1 + R2 - h + (G + extra) h / 100.
pub fn mechanism(
    g: &Gearing,
    radii: &BTreeMap<String, f64>,
    r: &Reading,
    clearance: f64,
) -> Result<Mechanism, RunError> {
    let h = r.tooth_height;
    let radius = |name: &str| radii.get(name).copied().unwrap_or(f64::NAN);
    // `Mechanism` places each mesh at train's D for a clearance; ask for the clearance that
    // gives this reading's D on train's radii.
    let teeth = |name: &str| g.gear(name).map_or(0, |x| x.teeth as usize);
    let equivalent = |label: &str| {
        let (Some(m), Some(base)) = (g.mesh(label), g.mesh_geometry(label, h, 0.0)) else {
            return f64::NAN;
        };
        let (r1, r2) = (radius(&m.driver), radius(&m.driven));
        let c = r.clearance(clearance, teeth(&m.driver), teeth(&m.driven), r1, r2);
        let d = r1 + r2 - h + h * c / 100.0;
        (d - base.centre_distance) / h * 100.0
    };
    Mechanism::build_with_clearances(g, h, equivalent, |name, gear| {
        let tip = radius(name);
        Gear::ideal(gear.teeth(), tip, tip - h).map_err(|e| e.to_string())
    })
    .map_err(crate::gearing::mechanism_error)
}

/// σ and mean of one pointer's Theoretical Difference in one trial (degrees), under the
/// sampling readings: σ and mean at the default density, σ at one sample per engagement and at
/// twice the default. NaN bits survive the shard records.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct PointerSigma {
    /// σ at the default density (degrees).
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Mean at the default density (degrees).
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
    /// σ at one sample per engagement.
    #[serde(with = "registry::f64_bits")]
    pub sigma_coarse: f64,
    /// σ at twice the default density.
    #[serde(with = "registry::f64_bits")]
    pub sigma_fine: f64,
}

/// A pointer's σ under the three sampling densities (`per`, 1 and `2 per` per engagement).
fn sigmas(
    g: &Gearing,
    run: Option<PointerRun>,
    name: &str,
    turns: f64,
    per: usize,
) -> PointerSigma {
    let Some(run) = run else {
        return PointerSigma {
            sigma: f64::NAN,
            mean: f64::NAN,
            sigma_coarse: f64::NAN,
            sigma_fine: f64::NAN,
        };
    };
    let s = run.stats(samples_for(g, name, turns, per));
    PointerSigma {
        sigma: s.sigma,
        mean: s.mean,
        sigma_coarse: run.stats(samples_for(g, name, turns, 1)).sigma,
        sigma_fine: run.stats(samples_for(g, name, turns, 2 * per)).sigma,
    }
}

/// How a Table 1 trial sets each mesh's initial angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Starts {
    /// Each mesh's initial driver angle uniform within its driver's pitch (the paper, ours).
    Random,
    /// Every mesh starts at driver angle 0.
    Zero,
}

/// Table 1's σ per trial and pointer for one mechanism and one start rule: `trials` trials,
/// trial t on Table 1's stream (trial t of [`Draws::IdealMechanism`], on purpose: each reading
/// is compared with Table 1 on the same initial angles), each pointer of `turns` (pointer,
/// input turns) in turn; in trial order, as the batch `key` of [`TrialEngine::trials`].
#[allow(
    clippy::too_many_arguments,
    reason = "the runs' inputs, each a value of its own"
)]
pub fn table1_trials(
    engine: &TrialEngine,
    key: &str,
    g: &Gearing,
    mech: &Mechanism,
    start: Starts,
    turns: &[(&str, f64)],
    per: usize,
    trials: u64,
) -> Result<Vec<Vec<PointerSigma>>, RunError> {
    engine.trials(key, trials, |t| {
        let mut rng = engine.stream(Draws::IdealMechanism.identity(), t);
        Ok(turns
            .iter()
            .map(|&(name, turns)| {
                let run = match start {
                    Starts::Random => mech.run_pointer(name, turns, &mut rng),
                    Starts::Zero => mech.run_pointer_from(name, turns, |_| Some(0.0)),
                };
                sigmas(g, run, name, turns, per)
            })
            .collect())
    })
}

/// Where a σ(G) curve is smallest, and how deep that minimum is. Recorded per (reading, mesh)
/// through `TrialEngine::trials_whole` (NaN fields as bits).
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
pub struct Minimum {
    /// The clearance of the smallest σ, % of h.
    #[serde(with = "registry::f64_bits")]
    pub at: f64,
    /// σ at 40 % over the smallest σ (NaN when 40 % is not on the curve).
    #[serde(with = "registry::f64_bits")]
    pub depth: f64,
    /// The largest clearance on the curve (for ideal gears: the largest that runs a full turn
    /// without a jam or disengagement).
    #[serde(with = "registry::f64_bits")]
    pub last: f64,
}

impl Minimum {
    /// The minimum of (G, σ) points; None for no points.
    pub fn of(curve: &[(f64, f64)]) -> Option<Minimum> {
        let (at, smallest) =
            curve
                .iter()
                .copied()
                .fold(None, |best: Option<(f64, f64)>, (c, s)| match best {
                    Some((_, b)) if b <= s => best,
                    _ => Some((c, s)),
                })?;
        let at40 = curve
            .iter()
            .find(|(c, _)| (c - 40.0).abs() < 1e-9)
            .map_or(f64::NAN, |&(_, s)| s);
        let last = curve.iter().map(|&(c, _)| c).fold(f64::NAN, f64::max);
        Some(Minimum {
            at,
            depth: at40 / smallest,
            last,
        })
    }
}

/// Figure IV with manufacturing errors: `draws` pairs of mesh `label` manufactured under Case A
/// (`edmunds-split`, random 0.04 of the pitch, no systematic error), each swept over every
/// clearance of `grid` with the same gears and initial angle; through jams (the driven gear
/// released to its next free position, as the paper's program did). Returns the minimum of
/// the mean σ over the draws. Draw d of the mesh is trial d of [`Draws::FigureIvCaseA`].
fn case_a_minimum(
    g: &Gearing,
    index: usize,
    pair: &IdealPair,
    grid: &[f64],
    draws: usize,
    samples: usize,
    seed: u64,
) -> Result<Option<Minimum>, RunError> {
    use rand::Rng;
    let Some(m) = g.meshes().get(index) else {
        return Ok(None);
    };
    let hyp = hypotheses::lookup("edmunds-split")
        .map_err(|e| RunError::Internal(format!("edmunds-split: {}", e.rule)))?;
    let params = hypotheses::Params::new(
        hyp,
        &[
            ("random".into(), "0.04".into()),
            ("systematic".into(), "0".into()),
        ],
    )
    .map_err(|e| RunError::Internal(format!("edmunds-split: {}", e.rule)))?;
    let turn = std::f64::consts::TAU * pair.n1.max(pair.n2) as f64 / pair.n1 as f64;
    let ratio = pair.n1 as f64 / pair.n2 as f64;
    let mut sums = vec![0.0; grid.len()];
    let mut counts = vec![0_usize; grid.len()];
    let pairs = Draws::FigureIvCaseA { mesh: &m.label };
    for d in 0..draws {
        let mut rng = pairs.stream(Streams::new(seed), d as u64);
        let (ideal1, ideal2) = pair.ideal_gears()?;
        let a = crate::errors::make(hyp, &ideal1, &m.driver, &params, &mut rng)?;
        let b = crate::errors::make(hyp, &ideal2, &m.driven, &params, &mut rng)?;
        let phi0 = rng.random::<f64>() * std::f64::consts::TAU / pair.n1 as f64;
        for (k, &c) in grid.iter().enumerate() {
            let Ok(t) = pair.run_made((&a, &b), c, phi0) else {
                continue;
            };
            let th0 = t.theta_at(phi0);
            let acc: stats::Accumulator = (0..samples)
                .map(|j| {
                    let phi = turn * j as f64 / samples as f64;
                    (t.theta_at(phi0 + phi) - th0 - ratio * phi).to_degrees()
                })
                .collect();
            sums[k] += acc.sigma();
            counts[k] += 1;
        }
    }
    let curve: Vec<(f64, f64)> = grid
        .iter()
        .zip(sums.iter().zip(&counts))
        .filter(|(_, (_, n))| **n == draws)
        .map(|(&c, (s, n))| (c, s / *n as f64))
        .collect();
    Ok(Minimum::of(&curve))
}

/// Figure IV's minimum of every (column, mesh): the columns are the readings of [`GEOMETRY`]
/// (their tip radii `radii`), then the first one's gears with Case A errors (`draws` pairs
/// each), then its ideal gears started at rest half-way through the backlash; σ over the
/// clearances `grid`, `samples` samples a run. One whole batch of the trial engine (job j is
/// (column, mesh)); the Case A column draws its gears from streams of the seed.
pub fn figure_iv_minima(
    engine: &TrialEngine,
    g: &Gearing,
    radii: &[BTreeMap<String, f64>],
    grid: &[f64],
    (draws, samples): (usize, usize),
) -> Result<BTreeMap<(usize, usize), Option<Minimum>>, RunError> {
    let seed = engine.seed();
    // Columns: the geometry readings, then (CASE_A) the first one's gears with Case A errors,
    // then (IN_BACKLASH) its ideal gears started at rest half-way through the backlash.
    let case_a = GEOMETRY.len();
    let in_backlash = case_a + 1;
    let mut jobs = Vec::new();
    for ri in 0..=in_backlash {
        let geometry = if ri >= case_a { 0 } else { ri };
        let r = &GEOMETRY[geometry];
        let radii = &radii[geometry];
        for (mi, m) in g.meshes().iter().enumerate() {
            let radius = |n: &str| radii.get(n).copied().unwrap_or(f64::NAN);
            let teeth = |n: &str| g.gear(n).map_or(0, |x| x.teeth as usize);
            jobs.push((
                ri,
                mi,
                IdealPair {
                    n1: teeth(&m.driver),
                    n2: teeth(&m.driven),
                    r1: radius(&m.driver),
                    r2: radius(&m.driven),
                    h: r.tooth_height,
                },
            ));
        }
    }
    // (column, mesh) -> G of the smallest σ; pairs of identical geometry (b2-c1 and b2-l1) are
    // run twice, which keeps the code plain.
    // Through the trial engine like every trial loop: job j is (reading, mesh); the Case A column
    // draws its gears from streams of the seed.
    let key = format!(
        "sigma-causes Figure IV minima: {} jobs, grid {grid:?}, draws {draws}, samples {samples}",
        jobs.len()
    );
    let minima: Vec<Option<Minimum>> = engine.trials_whole(&key, jobs.len() as u64, |j| {
        let &(ri, mi, ref pair) = &jobs[j as usize];
        {
            if ri == case_a {
                return case_a_minimum(g, mi, pair, grid, draws, samples, seed);
            }
            let reading = &GEOMETRY[if ri == in_backlash { 0 } else { ri }];
            let mut curve = Vec::new();
            for &c in grid {
                let ours = reading.clearance(c, pair.n1, pair.n2, pair.r1, pair.r2);
                let run = if ri == in_backlash {
                    pair.run_in_backlash(ours, 0.5)?
                } else {
                    pair.run(ours)?
                };
                let Some(t) = run else {
                    continue;
                };
                // A run counts when it turns the driven gear as the tooth ratio says (tip
                // circles that do not overlap leave it still, with no event to report).
                let ratio = pair.n1 as f64 / pair.n2 as f64;
                let moved = t.theta_at(t.phi_end()) - t.theta_at(t.phi_start());
                let expected = ratio * (t.phi_end() - t.phi_start());
                let pitch = std::f64::consts::TAU / pair.n2 as f64;
                if t.jams() > 0 || t.disengagements() > 0 || (moved - expected).abs() > pitch {
                    continue;
                }
                curve.push((c, pair.td_sigma(&t, samples).sigma));
            }
            Ok(Minimum::of(&curve))
        }
    })?;
    let mut at: BTreeMap<(usize, usize), Option<Minimum>> = BTreeMap::new();
    for ((ri, mi, _), m) in jobs.iter().zip(minima) {
        at.insert((*ri, *mi), m);
    }
    Ok(at)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn the_first_reading_is_the_trains_own_geometry() {
        let g = Gearing::freeth2006();
        let g2021 = Gearing::builtin("freeth2021").unwrap();
        let r = &GEOMETRY[0];
        let radii = tip_radii(&g, &g2021, r.radii, r.tooth_height).unwrap();
        let mech = mechanism(&g, &radii, r, 40.0).unwrap();
        for m in g.meshes() {
            let want = g.mesh_geometry(&m.label, 1.1, 40.0).unwrap();
            let got = mech.mesh(&m.label).unwrap();
            assert!(
                (got.centre_distance() - want.centre_distance).abs() < 1e-12,
                "{}",
                m.label
            );
            assert_eq!(
                got.driver().tip_radius(),
                want.driver_tip_radius,
                "{}",
                m.label
            );
        }
    }

    #[test]
    fn five_percent_more_centre_distance_is_0_055_mm() {
        let g = Gearing::freeth2006();
        let g2021 = Gearing::builtin("freeth2021").unwrap();
        let shifted = GEOMETRY.iter().find(|r| r.extra_clearance == 5.0).unwrap();
        let radii = tip_radii(&g, &g2021, shifted.radii, shifted.tooth_height).unwrap();
        let mech = mechanism(&g, &radii, shifted, 40.0).unwrap();
        let base = g.mesh_geometry("b2-c1", 1.1, 40.0).unwrap();
        let d = mech.mesh("b2-c1").unwrap().centre_distance();
        assert!((d - base.centre_distance - 0.055).abs() < 1e-12, "{d}");
    }

    #[test]
    fn radii_readings_follow_their_rules() {
        let g = Gearing::freeth2006();
        let g2021 = Gearing::builtin("freeth2021").unwrap();
        let lsq = tip_radii(&g, &g2021, Radii::LeastSquares, 1.1).unwrap();
        let mid = tip_radii(&g, &g2021, Radii::MidHeight, 1.1).unwrap();
        let kept = tip_radii(&g, &g2021, Radii::LargestKept, 1.1).unwrap();
        // c2 (48) and d1 (24), both measured: the fitted scale grows by (h/2) ΣN / ΣN².
        let grow = 0.55 * (48.0 + 24.0) / (48.0 * 48.0 + 24.0 * 24.0);
        assert!((mid["c2"] - lsq["c2"] - 48.0 * grow).abs() < 1e-12);
        // b2 (64) is the largest of b2, c1, l1: it keeps its 15.30 mm, its partners follow.
        assert!((kept["b2"] - 15.30).abs() < 1e-12);
        assert!((kept["c1"] - 15.30 * 38.0 / 64.0).abs() < 1e-12);
        assert_eq!(kept["c1"], kept["l1"]);
    }

    #[test]
    fn flank_reading_scales_g_by_the_flank_over_h() {
        // N = 8, R = 200, h = 100 (Figure 2's gears): tip (200, 0), valley at radius 100 and
        // half a pitch, 22.5 degrees.
        let r = Reading {
            name: "",
            stated: "",
            radii: Radii::LeastSquares,
            tooth_height: 100.0,
            extra_clearance: 0.0,
            per_flank: true,
        };
        let a = 22.5_f64.to_radians();
        let flank = (200.0 - 100.0 * a.cos()).hypot(100.0 * a.sin());
        assert!((r.clearance(40.0, 8, 8, 200.0, 200.0) - 40.0 * flank / 100.0).abs() < 1e-9);
        let plain = Reading {
            per_flank: false,
            extra_clearance: 5.0,
            ..r
        };
        assert_eq!(plain.clearance(40.0, 8, 8, 200.0, 200.0), 45.0);
    }
}
