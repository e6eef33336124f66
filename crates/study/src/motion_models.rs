//! Every measure of `motion-models` under each registered motion model (`motion`): the jams and
//! disengagements of the per-mesh tables' cells (on the cells' own gears and initial angles),
//! Figure 2's pair against Thorndike's closed form, Table 1's five pointers composed mesh by
//! mesh, and Figure IV's σ against the clearance.
//!
//! A model is handed the trial as the tables build it (`cell::draw_trial`, the listed driver
//! driving: `Drawn::driven_by`), and, for the models that place the driven gear at an angle of
//! its own, that angle drawn from a stream of its own ([`driven_angle`], the
//! [`Part::DrivenAngle`] of the tables' draws), so that every other draw is the tables'.

use std::f64::consts::TAU;

use mechanism::Mechanism;
use motion::{Model, Outcome, Path, Trial, Want};
use rand::Rng;
use registry::{RunError, Streams, TrialEngine, fnv1a64};
use rules::Rule;
use serde::{Deserialize, Serialize};
use train::Gearing;

use crate::cell::{CellSpec, Counts, draw_trial};
use crate::draws::{Draws, Part};
use crate::drive::Driver;
use crate::gearing::GearingId;
use crate::limits::IdealPair;

/// The driven gear's own initial angle in trial `t` of `draws`: uniform over its pitch `pitch`,
/// from the draws' [`Part::DrivenAngle`] (the tables' own draws are untouched).
pub fn driven_angle(streams: Streams, draws: Draws<'_>, t: u64, pitch: f64) -> f64 {
    let mut rng = streams.stream(draws.part(Part::DrivenAngle), t);
    rng.random::<f64>() * pitch
}

/// The (jammed, disengaged) of a model's events under `rule`.
fn tally(rule: &Rule, events: &[motion::Event]) -> (bool, bool) {
    rule.tally(events)
}

/// Trial `t` of `cell` under every model: bit `2m` "jammed at least once under model m",
/// bit `2m + 1` "disengaged at least once", counted by `rule`.
fn cell_trial(
    g: &Gearing,
    cell: &CellSpec,
    seed: u64,
    t: u64,
    models: &[Model],
    rule: &Rule,
) -> Result<u64, RunError> {
    let drawn = draw_trial(g, cell, seed, t)?;
    let run = drawn.driven_by(Driver::Listed);
    let Some(mesh) = run.mesh.as_ref() else {
        // Bodies that overlap at every angle cannot turn under any model: a jam.
        return Ok((0..models.len()).fold(0, |acc, m| acc | 1 << (2 * m)));
    };
    let pitch = TAU / mesh.driven().teeth() as f64;
    let trial = Trial {
        mesh,
        phi0: run.phi0,
        turn: run.turn,
        drawn: Some(driven_angle(
            Streams::new(seed),
            Draws::Cell(&cell.canonical()),
            t,
            pitch,
        )),
        tooth_height: cell.tooth_height,
    };
    let answered = |events: &[motion::Event]| tally(rule, events) == (true, true);
    let mut bits = 0;
    for (m, model) in models.iter().enumerate() {
        let out = model.run(&trial, Want::Events(&answered));
        let (jam, dis) = tally(rule, &out.events);
        bits |= u64::from(jam) << (2 * m) | u64::from(dis) << (2 * m + 1);
    }
    Ok(bits)
}

/// Each cell's counts under each model, counted by `rule`: `counts[cell][model]`. One flat
/// batch of (cell, trial) jobs through the trial engine, collected in order, so the counts
/// are the same for any thread count or shard.
///
/// Errors: `trials == 0`; more than 32 models; those of [`crate::cell::rebuild`].
pub fn cell_counts(
    engine: &TrialEngine,
    g: &Gearing,
    cells: &[CellSpec],
    models: &[Model],
    rule: &Rule,
    trials: u64,
) -> Result<Vec<Vec<Counts>>, RunError> {
    if trials == 0 {
        return Err(RunError::bad("--set", "trials", "must be at least 1"));
    }
    if models.is_empty() || models.len() > 32 {
        return Err(RunError::Internal(
            "cells are counted under 1 to 32 motion models at once".into(),
        ));
    }
    let mut names: String = cells.iter().map(|c| c.canonical() + "\n").collect();
    names.push_str(&format!(
        "{:?};{};{trials};{:016x}",
        models,
        rule.label(),
        GearingId::of(g)?
    ));
    let key = format!("motion-models cells:{:016x}", fnv1a64(names.as_bytes()));
    let seed = engine.seed();
    let bits = engine.trials(&key, cells.len() as u64 * trials, |i| {
        cell_trial(
            g,
            &cells[(i / trials) as usize],
            seed,
            i % trials,
            models,
            rule,
        )
    })?;
    Ok(cells
        .iter()
        .enumerate()
        .map(|(c, cell)| {
            let larger = g
                .mesh_geometry(&cell.mesh, cell.tooth_height, cell.clearance)
                .map_or(0, |m| u64::from(m.driver_teeth.max(m.driven_teeth)));
            let outcomes = &bits[c * trials as usize..(c + 1) * trials as usize];
            (0..models.len())
                .map(|m| {
                    let mut counts = Counts {
                        trials,
                        engagements: trials * larger,
                        ..Counts::default()
                    };
                    for &o in outcomes {
                        let (jam, dis) = (o >> (2 * m) & 1 == 1, o >> (2 * m + 1) & 1 == 1);
                        counts.jams += u64::from(jam);
                        counts.disengagements += u64::from(dis);
                        counts.failures += u64::from(jam || dis);
                    }
                    counts
                })
                .collect()
        })
        .collect())
}

/// Figure 2 under one model: the largest difference from Thorndike's closed form and the
/// Theoretical Difference's σ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Figure2 {
    /// Largest |θ(φ) − θ'(φ)| over the samples (degrees).
    pub max_diff: f64,
    /// The same at the model's own points only (a stepped program's steps), where it has some.
    pub max_diff_own: Option<f64>,
    /// σ of the Theoretical Difference over the samples (degrees).
    pub sigma: f64,
    /// The closed form's σ over the same samples (degrees).
    pub closed_sigma: f64,
}

/// Figure 2's pair (two N = 8 gears, R = 200, r = 100, D = 310) under `model`, one driver turn
/// from φ' = 0 with the driven gear touching (θ'o = θ'(0), the paper's Figure III frame), sampled
/// every `step_deg` degrees against expressions \[I\] and \[II\].
///
/// Errors: the pair refused by the solver or the closed forms (never, for these sizes).
pub fn figure2(model: &Model, step_deg: f64) -> Result<Figure2, RunError> {
    let (n, big_r, small_r, d) = (8, 200.0, 100.0, 310.0);
    let pair = crate::equal_pair::build(n, big_r, small_r, d)?;
    let closed = thorndike::Pair::new(8, 8, big_r, small_r, big_r, small_r, d)
        .map_err(|e| RunError::Internal(format!("Figure 2's pair: {e}")))?;
    let trial = Trial {
        mesh: &pair.mesh,
        phi0: 0.0,
        turn: TAU,
        drawn: None,
        tooth_height: big_r - small_r,
    };
    let Outcome { path, .. } = model.run(&trial, Want::Path);
    let path = path.ok_or_else(|| RunError::Internal("a model gave no path".into()))?;
    let samples = (360.0 / step_deg).round() as usize;
    let th0 = path.theta_at(0.0);
    let closed0 = thorndike::theta_prime(&closed, 0.0);
    let (mut max_diff, mut td, mut closed_td) = (0.0_f64, Vec::new(), Vec::new());
    for i in 0..=samples {
        let phi = (i as f64 * step_deg).to_radians().min(TAU);
        let (sim, exact) = (path.theta_at(phi), thorndike::theta_prime(&closed, phi));
        max_diff = max_diff.max((sim - exact).abs());
        td.push((sim - th0 - phi).to_degrees());
        closed_td.push((exact - closed0 - phi).to_degrees());
    }
    let max_diff_own = match &path {
        Path::Steps(steps) => Some(
            steps
                .iter()
                .map(|&(phi, theta)| (theta - thorndike::theta_prime(&closed, phi)).abs())
                .fold(0.0, f64::max)
                .to_degrees(),
        ),
        _ => None,
    };
    Ok(Figure2 {
        max_diff: max_diff.to_degrees(),
        max_diff_own,
        sigma: stats::pointer_stats(&td).sigma,
        closed_sigma: stats::pointer_stats(&closed_td).sigma,
    })
}

/// One pointer of one trial under one model (degrees); NaN bits survive the trial records.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct PointerSigma {
    /// σ of the pointer's Theoretical Difference.
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Dm, its largest deviation from the mean.
    #[serde(with = "registry::f64_bits")]
    pub dm: f64,
    /// Its mean.
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
}

/// One pointer's train run mesh by mesh under `model`: each mesh's path, its start and the
/// driven angle there.
struct Chain {
    stages: Vec<(f64, f64, Path)>,
}

impl Chain {
    /// The output arbor's rotation after the input has turned ψ: each mesh's driven rotation is
    /// the next mesh's driver rotation.
    fn angle(&self, psi: f64) -> f64 {
        self.stages.iter().fold(psi, |x, (phi0, theta0, path)| {
            path.theta_at(phi0 + x) - theta0
        })
    }
}

/// Runs `pointer`'s train of `mech` for `turns` input turns under `model`, each mesh's initial
/// driver angle drawn from `rng` in chain order exactly as `Mechanism::run_pointer` draws it
/// (so the push model gives Table 1's runs bit for bit), the driven gear's own angle from
/// `extra`; `None` for a pointer the gearing lacks.
fn chain(
    mech: &Mechanism,
    pointer: &str,
    turns: f64,
    model: &Model,
    rng: &mut impl Rng,
    extra: &mut impl Rng,
    h: f64,
) -> Option<Chain> {
    let p = mech.gearing().pointer(pointer)?;
    let mut range = turns * TAU;
    let mut stages = Vec::with_capacity(p.meshes.len());
    for label in &p.meshes {
        let mesh = mech.mesh(label)?;
        let phi0 = rng.random::<f64>() * TAU / mesh.driver().teeth() as f64;
        let drawn = extra.random::<f64>() * TAU / mesh.driven().teeth() as f64;
        let trial = Trial {
            mesh,
            phi0,
            turn: range,
            drawn: Some(drawn),
            tooth_height: h,
        };
        let path = model.run(&trial, Want::Path).path?;
        let theta0 = path.theta_at(phi0);
        range = path.theta_at(phi0 + range) - theta0;
        stages.push((phi0, theta0, path));
    }
    Some(Chain { stages })
}

/// Table 1 under each model: `trials` trials of the ideal mechanism `mech`, trial t from Table
/// 1's stream ([`Draws::IdealMechanism`], every pointer of `runs` in turn, as Table 1 draws
/// them) and the driven gears' own angles from its [`Part::DrivenAngle`], the
/// Theoretical Difference of each pointer sampled `samples` times evenly over its run (through
/// any jam, as the paper's program went on): `result[model][trial][pointer]`.
pub fn pointer_sigmas(
    engine: &TrialEngine,
    mech: &Mechanism,
    runs: &[(&str, f64, usize)],
    models: &[Model],
    trials: u64,
    h: f64,
) -> Result<Vec<Vec<Vec<PointerSigma>>>, RunError> {
    let key = format!("motion-models table 1: {models:?} {runs:?} {trials} trials, h = {h}");
    let g = mech.gearing();
    let per_trial = engine.trials(&key, trials, |t| {
        Ok(models
            .iter()
            .map(|model| {
                // Every model from the same streams, on purpose: a paired comparison, each model
                // run on the same initial angles (and the push model's are Table 1's runs).
                let mut rng = engine.stream(Draws::IdealMechanism.identity(), t);
                let extra_id = Draws::IdealMechanism.part(Part::DrivenAngle);
                let mut extra = engine.stream(extra_id, t);
                runs.iter()
                    .map(|&(name, turns, samples)| {
                        let ratio = g.pointer_ratio(name).map_or(f64::NAN, |r| r.to_f64());
                        let Some(c) = chain(mech, name, turns, model, &mut rng, &mut extra, h)
                        else {
                            return PointerSigma {
                                sigma: f64::NAN,
                                dm: f64::NAN,
                                mean: f64::NAN,
                            };
                        };
                        let end = turns * TAU;
                        let n = samples.max(2);
                        let s = (0..n)
                            .map(|i| {
                                let psi = end * i as f64 / (n - 1) as f64;
                                (c.angle(psi) - ratio * psi).to_degrees()
                            })
                            .collect::<stats::Accumulator>()
                            .stats();
                        PointerSigma {
                            sigma: s.sigma,
                            dm: s.dm,
                            mean: s.mean,
                        }
                    })
                    .collect::<Vec<_>>()
            })
            .collect::<Vec<_>>())
    })?;
    Ok((0..models.len())
        .map(|m| per_trial.iter().map(|t| t[m].clone()).collect())
        .collect())
}

/// One point of a model's σ(G) curve (degrees); NaN where the run jams or no tooth ever moves
/// the driven gear.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct SigmaPoint {
    /// σ of the driven gear's Theoretical Difference.
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Whether the run jammed under the rule (no σ is read from it).
    pub jammed: bool,
    /// Whether the run disengaged under the rule (σ is read from it all the same).
    pub disengaged: bool,
}

/// Figure IV under each model: for each ideal pair, σ of the driven gear's Theoretical
/// Difference (`samples` samples over a turn of the larger gear from φ = 0, the driven gear
/// touching) at each clearance: `result[model][pair][clearance]`. One whole batch of the trial
/// engine (job j: model, pair and clearance in that order).
pub fn sigma_sweep(
    engine: &TrialEngine,
    pairs: &[IdealPair],
    clearances: &[f64],
    models: &[Model],
    rule: &Rule,
    samples: usize,
) -> Result<Vec<Vec<Vec<SigmaPoint>>>, RunError> {
    let key = format!(
        "motion-models figure IV: {models:?} {pairs:?} {clearances:?} {} {samples}",
        rule.label()
    );
    let (np, nc) = (pairs.len(), clearances.len());
    let points = engine.trials_whole(&key, (models.len() * np * nc) as u64, |j| {
        let j = j as usize;
        let (m, p, c) = (j / (np * nc), j / nc % np, j % nc);
        sigma_point(&models[m], &pairs[p], clearances[c], rule, samples)
    })?;
    Ok((0..models.len())
        .map(|m| {
            (0..np)
                .map(|p| points[(m * np + p) * nc..(m * np + p + 1) * nc].to_vec())
                .collect()
        })
        .collect())
}

/// One point of [`sigma_sweep`].
fn sigma_point(
    model: &Model,
    pair: &IdealPair,
    g: f64,
    rule: &Rule,
    samples: usize,
) -> Result<SigmaPoint, RunError> {
    let (driver, driven) = pair.ideal_gears()?;
    let Ok(mesh) = motion::Mesh::new(driver, driven, pair.centre_distance(g)) else {
        return Ok(SigmaPoint {
            sigma: f64::NAN,
            jammed: true,
            disengaged: false,
        });
    };
    let turn = TAU * pair.n1.max(pair.n2) as f64 / pair.n1 as f64;
    let trial = Trial {
        mesh: &mesh,
        phi0: 0.0,
        turn,
        drawn: None,
        tooth_height: pair.h,
    };
    let out = model.run(&trial, Want::Path);
    let (jammed, disengaged) = rule.tally(&out.events);
    let never_moved = out.events.iter().any(|e| e.idle_start && !e.resumed);
    let sigma = match out.path {
        Some(path) if !jammed && !never_moved => {
            let ratio = pair.n1 as f64 / pair.n2 as f64;
            let th0 = path.theta_at(0.0);
            let n = samples.max(2);
            (0..n)
                .map(|k| {
                    let phi = turn * k as f64 / (n - 1) as f64;
                    (path.theta_at(phi) - th0 - ratio * phi).to_degrees()
                })
                .collect::<stats::Accumulator>()
                .stats()
                .sigma
        }
        _ => f64::NAN,
    };
    Ok(SigmaPoint {
        sigma,
        jammed,
        disengaged,
    })
}
