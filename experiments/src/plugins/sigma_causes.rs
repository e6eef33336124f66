//! `sigma-causes`: why our σ differs from the paper's, by experiment. Two open differences:
//! Figure IV's σ has its minimum at 55-75 % clearance for every mesh where the paper
//! sees it "around 40% to 50%", and Table 1's σ is 1.21-1.27 times the paper's. Each candidate
//! reading of the paper's inputs and method (radii, tooth height, centre distance, how the
//! Theoretical Difference is sampled and summarised, the initial angles) is run side by side on
//! the same draws, so the table shows which one moves ours onto the paper's.

use std::collections::BTreeMap;

use geometry::Gear;
use mechanism::{Mechanism, PointerRun, trial_rng};
use registry::{Context, Experiment, Param, Report, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use train::Gearing;

use study::limits::IdealPair;
use study::pointers::{POINTERS, samples_for};

/// `trials`: Table 1 trials per reading (random initial angles; the same draws for every reading).
const TRIALS: Param = Param {
    name: "trials",
    default: "2",
    unit: "",
    help: "Table 1 trials per reading (random initial angles; the same draws for every reading)",
    kind: registry::Kind::count(2, registry::MAX_TRIALS, "a pooled sigma needs two trials"),
};

/// `clearance`: Table 1's clearance G of every mesh (before a reading's extra centre distance).
/// Not the gearing group's `clearance` ([`study::gearing::CLEARANCE`]): this experiment runs the
/// embedded gearings only, so its clearance is Table 1's input alone, under the same name.
const TABLE1_CLEARANCE: Param = Param {
    name: "clearance",
    default: "40",
    unit: "% of h",
    help: "Table 1's clearance G of every mesh (before a reading's extra centre distance)",
    kind: registry::Kind::positive(100.0, "% of the tooth height h"),
};

/// `samples_per_engagement`: TD samples per tooth engagement of the busiest mesh (Table 1's default).
const SAMPLES_PER_ENGAGEMENT: Param = Param {
    name: "samples_per_engagement",
    default: "16",
    unit: "",
    help: "TD samples per tooth engagement of the busiest mesh (Table 1's default)",
    kind: registry::Kind::count(
        registry::MIN_PER_ENGAGEMENT,
        registry::MAX_COUNT as u64,
        registry::MIN_PER_ENGAGEMENT_WHY,
    ),
};

/// `draws`: Figure IV with Case A errors: manufactured pairs per mesh (each swept over every G).
const DRAWS: Param = Param {
    name: "draws",
    default: "3",
    unit: "",
    help: "Figure IV with Case A errors: manufactured pairs per mesh (each swept over every G)",
    kind: registry::Kind::count(1, registry::MAX_COUNT as u64, "a mean needs one draw"),
};

/// `samples`: TD samples per pair run of the Figure IV sweep (figIV's default).
const SAMPLES: Param = Param {
    name: "samples",
    default: "2000",
    unit: "",
    help: "TD samples per pair run of the Figure IV sweep (figIV's default)",
    kind: registry::Kind::count(
        registry::MIN_SAMPLES,
        registry::MAX_COUNT as u64,
        registry::MIN_SAMPLES_WHY,
    ),
};

const PARAMS: &[Param] = &[
    TRIALS,
    TABLE1_CLEARANCE,
    SAMPLES_PER_ENGAGEMENT,
    DRAWS,
    SAMPLES,
];

registry::inventory::submit! {
    Experiment {
        id: "sigma-causes",
        title: "Why our sigma differs from the paper's: Figure IV's minimum and Table 1's sigma under each candidate reading",
        paper_item: "Table 1 and Figure IV (beyond the paper)",
        params: PARAMS,
        groups: &[],
        config: None,
        run,
    }
}

/// How the tip radii are chosen.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Radii {
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
struct Reading {
    /// Short name, as printed.
    name: &'static str,
    /// Whether it keeps to the paper's stated inputs (a reading of them) or departs from them.
    stated: &'static str,
    radii: Radii,
    /// Tooth height h of every gear, mm.
    tooth_height: f64,
    /// Centre distance added to every mesh, % of h (D = R1 + R2 - h + (G + extra) h / 100).
    extra_clearance: f64,
    /// G is a percentage of the flank length (the slant height of a tooth, tip to valley; the
    /// mean of the two gears') instead of the radial height h.
    per_flank: bool,
}

impl Reading {
    /// The clearance in % of h (the paper's formula, ours) that this reading's `g_percent`
    /// amounts to on a mesh of teeth `n1`, `n2` and tip radii `r1`, `r2`.
    fn clearance(&self, g_percent: f64, n1: usize, n2: usize, r1: f64, r2: f64) -> f64 {
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
const GEOMETRY: [Reading; 7] = [
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
fn tip_radii(
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
fn mechanism(
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
    .map_err(study::gearing::mechanism_error)
}

/// σ and mean of one pointer's Theoretical Difference in one trial (degrees), under the
/// sampling readings: σ and mean at the default density, σ at one sample per engagement and at
/// twice the default. NaN bits survive the shard records.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
struct PointerSigma {
    #[serde(with = "registry::f64_bits")]
    sigma: f64,
    #[serde(with = "registry::f64_bits")]
    mean: f64,
    #[serde(with = "registry::f64_bits")]
    sigma_coarse: f64,
    #[serde(with = "registry::f64_bits")]
    sigma_fine: f64,
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
enum Starts {
    /// Each mesh's initial driver angle uniform within its driver's pitch (the paper, ours).
    Random,
    /// Every mesh starts at driver angle 0.
    Zero,
}

/// Table 1's σ per trial and pointer for one mechanism, one start rule and a span factor.
fn table1_trials(
    ctx: &Context,
    key: &str,
    g: &Gearing,
    mech: &Mechanism,
    start: Starts,
    span: f64,
    per: usize,
) -> Result<Vec<Vec<PointerSigma>>, RunError> {
    let trials: usize = ctx.get(&TRIALS)?;
    let seed = ctx.seed();
    let turns: Vec<(&str, f64)> = POINTERS
        .iter()
        .map(|&(name, param)| Ok((name, caption_turns(param)? * span)))
        .collect::<Result<_, RunError>>()?;
    ctx.trials(key, trials as u64, |t| {
        let mut rng = trial_rng(seed, t);
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

/// The run length of a pointer as `table1` runs it by default (the caption's turns of b).
fn caption_turns(p: &Param) -> Result<f64, RunError> {
    p.default
        .parse()
        .map_err(|_| RunError::Internal(format!("run length {} is not a number", p.name)))
}

/// Mean over trials of one field, for pointer `i`.
fn mean_of(trials: &[Vec<PointerSigma>], i: usize, f: impl Fn(&PointerSigma) -> f64) -> f64 {
    let v: Vec<f64> = trials
        .iter()
        .map(|t| t.get(i).map_or(f64::NAN, &f))
        .collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// σ of every trial's samples pooled into one series: (1/T) Σ σ_t² + (1/T) Σ (m_t - m̄)², exact
/// because every trial has the same number of samples.
fn pooled(trials: &[Vec<PointerSigma>], i: usize) -> f64 {
    let m = mean_of(trials, i, |p| p.mean);
    let v = mean_of(trials, i, |p| {
        p.sigma * p.sigma + (p.mean - m) * (p.mean - m)
    });
    v.sqrt()
}

/// Where a σ(G) curve is smallest, and how deep that minimum is. Recorded per (reading, mesh)
/// through `Context::trials_whole` (NaN fields as bits).
#[derive(Debug, Clone, Copy, Default, serde::Serialize, serde::Deserialize)]
struct Minimum {
    /// The clearance of the smallest σ, % of h.
    #[serde(with = "registry::f64_bits")]
    at: f64,
    /// σ at 40 % over the smallest σ (NaN when 40 % is not on the curve).
    #[serde(with = "registry::f64_bits")]
    depth: f64,
    /// The largest clearance on the curve (for ideal gears: the largest that runs a full turn
    /// without a jam or disengagement).
    #[serde(with = "registry::f64_bits")]
    last: f64,
}

impl Minimum {
    /// The minimum of (G, σ) points; None for no points.
    fn of(curve: &[(f64, f64)]) -> Option<Minimum> {
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
/// the mean σ over the draws. Draw d of mesh i uses stream `1000 i + d` of `seed`.
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
    for d in 0..draws {
        let mut rng = trial_rng(seed, 1000 * index as u64 + d as u64);
        let (ideal1, ideal2) = pair.ideal_gears()?;
        let a = study::errors::make(hyp, &ideal1, &m.driver, &params, &mut rng)?;
        let b = study::errors::make(hyp, &ideal2, &m.driven, &params, &mut rng)?;
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

fn run(ctx: &Context) -> Result<Report, RunError> {
    let g = Gearing::freeth2006();
    let g2021 = Gearing::builtin("freeth2021")
        .ok_or_else(|| RunError::Internal("the embedded freeth2021 gearing is missing".into()))?;
    let trials: usize = ctx.get(&TRIALS)?;
    let clearance: f64 = ctx.get(&TABLE1_CLEARANCE)?;
    let per: usize = ctx.get(&SAMPLES_PER_ENGAGEMENT)?;
    let samples: usize = ctx.get(&SAMPLES)?;
    let paper_from = crate::paper::get("sigma-causes", "figIV.minimum_from").map(|r| r.value);
    let paper_to = crate::paper::get("sigma-causes", "figIV.minimum_to").map(|r| r.value);

    // ---- Figure IV: σ against G for each mesh under each geometry reading. ----
    let grid: Vec<f64> = (0..=16).map(|i| 20.0 + 5.0 * f64::from(i)).collect();
    let radii: Vec<BTreeMap<String, f64>> = GEOMETRY
        .iter()
        .map(|r| tip_radii(&g, &g2021, r.radii, r.tooth_height))
        .collect::<Result<_, _>>()?;
    let draws: usize = ctx.get(&DRAWS)?;
    let seed = ctx.seed();
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
    let minima: Vec<Option<Minimum>> = ctx.trials_whole(&key, jobs.len() as u64, |j| {
        let &(ri, mi, ref pair) = &jobs[j as usize];
        {
            if ri == case_a {
                return case_a_minimum(&g, mi, pair, &grid, draws, samples, seed);
            }
            let reading = &GEOMETRY[if ri == in_backlash { 0 } else { ri }];
            let mut curve = Vec::new();
            for &c in &grid {
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
    let columns = in_backlash + 1;

    let mut header = vec!["mesh".to_string()];
    header.extend((1..=columns).map(|i| format!("({i})")));
    let mut fig = Table::new(
        "Figure IV: the clearance G [% of h] of the smallest sigma of each mesh under each reading (G = 20-100 % by 5)",
        header,
    );
    for (mi, m) in g.meshes().iter().enumerate() {
        let mut row = vec![m.label.clone()];
        for ri in 0..columns {
            row.push(
                at.get(&(ri, mi))
                    .copied()
                    .flatten()
                    .map_or_else(|| "-".into(), |m| fmt_f64(m.at, 0)),
            );
        }
        fig.row(row);
    }
    let mut inside = vec![format!(
        "minimum within the paper's {}-{} %",
        paper_from.map_or_else(|| "?".into(), |v| fmt_f64(v, 0)),
        paper_to.map_or_else(|| "?".into(), |v| fmt_f64(v, 0))
    )];
    let mut range = vec!["range of the minima".to_string()];
    let mut depth = vec!["sigma at 40 % / smallest sigma: median (range)".to_string()];
    let mut runs = vec![format!(
        "largest G that runs without a jam or disengagement: median (range) [paper: none above {}]",
        crate::paper::get("clearance", "disengage_above")
            .map_or_else(|| "?".into(), |r| fmt_f64(r.value, 0))
    )];
    for ri in 0..columns {
        let found: Vec<Minimum> = (0..g.meshes().len())
            .filter_map(|mi| at.get(&(ri, mi)).copied().flatten())
            .collect();
        let cs: Vec<f64> = found.iter().map(|m| m.at).collect();
        let mut lasts: Vec<f64> = found.iter().map(|m| m.last).collect();
        lasts.sort_by(f64::total_cmp);
        runs.push(match (ri == case_a, lasts.first(), lasts.last()) {
            (false, Some(lo), Some(hi)) => format!(
                "{} ({}-{})",
                fmt_f64(lasts[lasts.len() / 2], 0),
                fmt_f64(*lo, 0),
                fmt_f64(*hi, 0)
            ),
            _ => "-".into(),
        });
        let mut ds: Vec<f64> = found
            .iter()
            .map(|m| m.depth)
            .filter(|d| d.is_finite())
            .collect();
        ds.sort_by(f64::total_cmp);
        depth.push(match (ds.first(), ds.last()) {
            (Some(lo), Some(hi)) => format!(
                "{} ({}-{})",
                fmt_f64(ds[ds.len() / 2], 2),
                fmt_f64(*lo, 2),
                fmt_f64(*hi, 2)
            ),
            _ => "-".into(),
        });
        let n_in = match (paper_from, paper_to) {
            (Some(a), Some(b)) => cs.iter().filter(|&&c| a <= c && c <= b).count().to_string(),
            _ => "-".into(),
        };
        inside.push(format!("{n_in} of {}", g.meshes().len()));
        let lo = cs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = cs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        range.push(format!("{}-{}", fmt_f64(lo, 0), fmt_f64(hi, 0)));
    }
    fig.row(inside);
    fig.row(range);
    fig.row(depth);
    fig.row(runs);
    for (i, r) in GEOMETRY.iter().enumerate() {
        fig.note(format!(
            "({}) {} [paper's inputs: {}]",
            i + 1,
            r.name,
            r.stated
        ));
    }
    fig.note(format!(
        "({}) the gears of (1) with Case A errors (edmunds-split: random 0.04 of the pitch, no systematic error): mean sigma of {draws} manufactured pairs per mesh, each swept over every G from one random initial angle, through jams [paper's inputs: no: Figure IV is read as ideal]",
        case_a + 1
    ));
    fig.note(format!(
        "({}) the gears of (1), ideal, with the driven gear at rest half-way through the backlash at the start (not touching): it waits until a driver tooth takes it up, and that lost motion is part of the run [paper's inputs: another reading (the paper's initial angles are drawn; this one puts the driven gear mid-way)]",
        in_backlash + 1
    ));
    fig.note("G is the clearance of the paper's formula, D = R1 + R2 - h + G (reading (6) adds its extra centre distance to it; reading (7) reads G in % of the flank length); a mesh's minimum is the grid point of its smallest sigma of the driven gear's Theoretical Difference over one turn of the larger gear (ideal gears: figIV's runs, from driver angle 0, at grid points that run without a jam or disengagement; '-': none does).");

    // ---- Table 1: σ of the five pointers under every reading. ----
    let mut rows: Vec<(String, &'static str, Vec<f64>)> = Vec::new();
    let mut baseline: Option<Vec<Vec<PointerSigma>>> = None;
    for (ri, r) in GEOMETRY.iter().enumerate() {
        let mech = mechanism(&g, &radii[ri], r, clearance)?;
        let key = format!(
            "sigma-causes: table1 trials, reading ({}) {}, G = {clearance} %, {per} samples per engagement, random starts",
            ri + 1,
            r.name
        );
        let t = table1_trials(ctx, &key, &g, &mech, Starts::Random, 1.0, per)?;
        rows.push((
            format!("({}) {}", ri + 1, r.name),
            r.stated,
            (0..POINTERS.len())
                .map(|i| mean_of(&t, i, |p| p.sigma))
                .collect(),
        ));
        if ri == 0 {
            baseline = Some(t);
        }
    }
    let base = baseline.ok_or_else(|| RunError::Internal("no baseline reading".into()))?;
    // (GEOMETRY.len() + 1) and (+ 2) are Figure IV's Case A and backlash columns, not run here.
    let next = GEOMETRY.len() + 3;
    rows.push((
        format!("({next}) TD sampled once per engagement of the busiest mesh (on (1))"),
        "another reading (paper silent)",
        (0..POINTERS.len())
            .map(|i| mean_of(&base, i, |p| p.sigma_coarse))
            .collect(),
    ));
    rows.push((
        format!(
            "({}) TD sampled {} times per engagement (on (1))",
            next + 1,
            2 * per
        ),
        "another reading (paper silent)",
        (0..POINTERS.len())
            .map(|i| mean_of(&base, i, |p| p.sigma_fine))
            .collect(),
    ));
    rows.push((
        format!(
            "({}) sigma of all trials' samples pooled, not averaged per trial (on (1))",
            next + 2
        ),
        "another reading",
        (0..POINTERS.len()).map(|i| pooled(&base, i)).collect(),
    ));
    let mech = mechanism(&g, &radii[0], &GEOMETRY[0], clearance)?;
    let halved = table1_trials(
        ctx,
        &format!(
            "sigma-causes: table1 trials, reading (1) with every run half as long, G = {clearance} %, {per} samples per engagement, random starts"
        ),
        &g,
        &mech,
        Starts::Random,
        0.5,
        per,
    )?;
    rows.push((
        format!(
            "({}) every run half the caption's length (on (1))",
            next + 3
        ),
        "no: caption's lengths",
        (0..POINTERS.len())
            .map(|i| mean_of(&halved, i, |p| p.sigma))
            .collect(),
    ));
    let zero = table1_trials(
        ctx,
        &format!(
            "sigma-causes: table1 trials, reading (1) with every mesh from driver angle 0, G = {clearance} %, {per} samples per engagement"
        ),
        &g,
        &mech,
        Starts::Zero,
        1.0,
        per,
    )?;
    rows.push((
        format!(
            "({}) every mesh starts at driver angle 0 (on (1))",
            next + 4
        ),
        "no: paper draws them",
        (0..POINTERS.len())
            .map(|i| mean_of(&zero, i, |p| p.sigma))
            .collect(),
    ));

    let mut header = vec!["reading".to_string(), "paper's inputs".to_string()];
    header.extend(
        POINTERS
            .iter()
            .map(|(n, _)| format!("{n} sigma [deg] (ours/paper)")),
    );
    header.push("ours/paper, Lunar to Games".into());
    let mut t1 = Table::new(
        format!(
            "Table 1: sigma of each pointer [deg], mean of {trials} trials (the same draws for every reading), and ours/paper"
        ),
        header,
    );
    let paper: Vec<Option<f64>> = POINTERS
        .iter()
        .map(|(n, _)| crate::paper::get("table1", &format!("{n}.sigma")).map(|r| r.value))
        .collect();
    let mut paper_row = vec!["paper (Table 1)".to_string(), "-".to_string()];
    paper_row.extend(
        paper
            .iter()
            .map(|p| p.map_or_else(|| "-".into(), |v| fmt_f64(v, 3))),
    );
    paper_row.push("-".into());
    for (name, stated, sig) in rows {
        let mut row = vec![name, stated.to_string()];
        let mut ratios = Vec::new();
        for (i, s) in sig.iter().enumerate() {
            let ratio = paper[i].map(|p| s / p);
            if i < 4
                && let Some(q) = ratio
            {
                ratios.push(q);
            }
            row.push(format!(
                "{} ({})",
                fmt_f64(*s, 4),
                ratio.map_or_else(|| "-".into(), |q| fmt_f64(q, 2))
            ));
        }
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &q| {
                (a.min(q), b.max(q))
            });
        row.push(format!("{}-{}", fmt_f64(lo, 2), fmt_f64(hi, 2)));
        t1.row(row);
    }
    t1.row(paper_row);
    t1.note(format!(
        "Ideal gears, G = {clearance} % (plus the reading's extra centre distance), runs of the caption's length (Lunar 1, Metonic and Games 3.8, Saros and Exeligmos 4.5 turns of b), {per} TD samples per engagement of the busiest mesh unless the reading says otherwise; sigma per trial, then the mean over trials, as table1."
    ));
    t1.note("Ours/paper, Lunar to Games: the smallest and largest ours/paper of the Lunar, Metonic, Saros and Games pointers (the 1.21-1.27 that first prompted this study; Exeligmos, 1.8, has a cause of its own: see table1's note).");
    Ok(Report {
        tables: vec![fig, t1],
        trials: (trials * (GEOMETRY.len() + 2)) as u64,
        ..Default::default()
    })
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

    #[test]
    fn pooled_sigma_is_the_sigma_of_all_samples_together() {
        let a = [0.1, -0.3, 0.25, 0.05];
        let b = [1.0, 1.2, 0.7, 0.9];
        let trial = |x: &[f64]| {
            let s = stats::pointer_stats(x);
            vec![PointerSigma {
                sigma: s.sigma,
                mean: s.mean,
                ..Default::default()
            }]
        };
        let all: Vec<f64> = a.iter().chain(&b).copied().collect();
        let want = stats::pointer_stats(&all).sigma;
        let got = pooled(&[trial(&a), trial(&b)], 0);
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}
