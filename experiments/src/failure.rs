//! `failure`: the paper's 30-run study (section 5, after Figure 6): whole mechanisms with
//! manufacturing errors at G = 40 %, each run until its trains jam; per train the day of the
//! first jam, the share of runs jamming within a year, and survival curves.
//!
//! One run is one mechanism: every gear manufactured once (a gear in two meshes carries the same
//! errors in both), every one of the gearing's meshes given one random initial angle, and every
//! mesh simulated once over the horizon, up to its first jam. Trains that share meshes (b2-l1 and
//! l2-m1 are in both the Metonic/Games and the Saros/Exeligmos trains) share their motion.
//!
//! `Report::engagements` counts, for every mesh simulated in every run, the driver's turns over
//! the simulated stretch (to the horizon or the mesh's first jam) times its teeth: the teeth that
//! passed through the mesh.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use contact::Start;
use hypotheses::{Hypothesis, MeasuredHypothesis, Params};
use mechanism::{Mechanism, PointerRun, Stage, StageRun, trial_rng};
use plotters::prelude::*;
use rand::Rng;
use registry::{
    Agreement, Context, Experiment, OutputFile, Param, Report, RunError, Table, fmt_f64,
};
use serde::{Deserialize, Serialize};
use stats::{DAYS_PER_YEAR, Proportion, clopper_pearson95, mean_ci95};

use crate::errors;
use crate::gearing;
use crate::table2::CASES;

/// The `days` parameter: the horizon of each whole-mechanism run.
pub(crate) const DAYS: Param = Param {
    name: "days",
    default: "365.25",
    unit: "days of b",
    help: "horizon of each run (365.25 d per turn of b); at least one year",
};

/// The `cases` parameter: which of Edmunds' cases to run.
pub(crate) const CASES_PARAM: Param = Param {
    name: "cases",
    default: "A,B,C,D",
    unit: "",
    help: "Edmunds' cases to run, comma-separated (empty: none)",
};

/// Whole-mechanism runs per input at the defaults (the paper: 30).
pub(crate) const RUNS_DEFAULT: &str = "30";

const PARAMS: &[Param] = &[
    Param {
        name: "trials",
        default: RUNS_DEFAULT,
        unit: "",
        help: "whole-mechanism runs per input (the paper: 30)",
    },
    DAYS,
    CASES_PARAM,
    Param {
        name: "measured",
        default: "",
        unit: "",
        help: "per-gear error table (RON, as crates/hypotheses/data/measured-example.ron), run with the measured hypothesis; empty: not run",
    },
    gearing::CLEARANCE,
    gearing::TOOTH_HEIGHT,
    errors::SPLIT,
    errors::PARAM,
    errors::PARAMS_PARAM,
    gearing::PARAM,
    gearing::PIN_AND_SLOT,
    crate::events::PARAM,
];

registry::inventory::submit! {
    Experiment {
        id: "failure",
        title: "Days to the first jam of each train, whole mechanisms with Edmunds' errors at G = 40 %",
        paper_item: "Section 5, the 30-run study",
        params: PARAMS,
        config: None,
        run,
    }
}

/// The trains the paper reports: (name, the pointers whose meshes make it up).
pub(crate) const TRAINS: [(&str, &[&str]); 3] = [
    ("Lunar", &["Lunar"]),
    ("Metonic/Games", &["Metonic", "Games"]),
    ("Saros/Exeligmos", &["Saros", "Exeligmos"]),
];

/// Name of the row that combines every train (a jam anywhere stops the mechanism).
const MECHANISM: &str = "mechanism (any train)";

/// Stream index of the measured table (the cases use their index in `CASES`).
const MEASURED_INDEX: u64 = CASES.len() as u64;

/// Points of b at which the survival table is read: degrees of the solar (b) pointer.
const READ_AT_DEG: [f64; 5] = [30.0, 60.0, 120.0, 180.0, 360.0];

/// The clearance of each mesh of a whole mechanism.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Clearances {
    /// One clearance (% of h) for every mesh, as in the paper.
    Uniform(f64),
    /// A clearance per mesh label; meshes not listed get `default`.
    PerMesh {
        /// Clearance of the meshes not in `meshes` (% of h).
        default: f64,
        /// Clearance by mesh label (% of h).
        meshes: BTreeMap<String, f64>,
    },
}

impl Clearances {
    /// The clearance of mesh `label` (% of h).
    pub(crate) fn of(&self, label: &str) -> f64 {
        match self {
            Clearances::Uniform(g) => *g,
            Clearances::PerMesh { default, meshes } => {
                meshes.get(label).copied().unwrap_or(*default)
            }
        }
    }
}

/// One set of error inputs: a case or the measured table, at its clearances.
pub(crate) struct Input<'a> {
    /// "A".."D" or "measured".
    pub(crate) label: String,
    /// Legend text.
    pub(crate) legend: String,
    /// Index selecting its RNG streams: inputs with the same index run the same gears and
    /// initial angles (only the clearances may differ).
    pub(crate) index: u64,
    /// Where its hypothesis came from, for errors: `--hypothesis` or `--set measured`.
    pub(crate) source: &'static str,
    pub(crate) hypothesis: &'a dyn Hypothesis,
    pub(crate) params: Params,
    /// The clearance of each mesh.
    pub(crate) clearances: Clearances,
    /// The Lunar train includes the pin-and-slot (beyond the paper; off in the paper's study).
    pub(crate) pin_and_slot: bool,
    /// A second hypothesis applied to each gear after the first (a shape change on top of
    /// Edmunds' errors), drawing from its own stream ([`EXTRA_STREAM`]): the first one's draws
    /// and the initial angles stay those of the run without it, so the two runs differ by it
    /// alone.
    pub(crate) extra: Option<(&'a dyn Hypothesis, Params)>,
}

/// Stream flag of an input's [`Input::extra`] hypothesis: trial t of input i draws its extra
/// errors from stream `EXTRA_STREAM | i << 32 | t`, apart from stream `i << 32 | t`.
pub(crate) const EXTRA_STREAM: u64 = 1 << 63;

/// The first jam of a train within the horizon.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Jam {
    /// Day of the b arbor.
    pub(crate) day: f64,
    /// The mesh that jammed.
    pub(crate) mesh: String,
}

/// One whole-mechanism run. The default (a run of another shard, see `Context::trials`) has
/// no trains: it reads as a run that never jammed.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub(crate) struct Outcome {
    /// First jam per train of `TRAINS` (None: none within the horizon).
    trains: Vec<Option<Jam>>,
    /// Driver turns times driver teeth, summed over every simulated mesh.
    pub(crate) engagements: f64,
    /// The gears could not be placed (bodies overlapping at every angle): the mesh and rule.
    unplaceable: Option<String>,
    /// σ of the Lunar pointer's Theoretical Difference [deg] over the run up to its first jam
    /// (None: it jammed at once, or the gears could not be placed).
    #[serde(default)]
    pub(crate) lunar_sigma: Option<f64>,
}

impl Outcome {
    /// First jam anywhere.
    pub(crate) fn mechanism(&self) -> Option<&Jam> {
        self.trains
            .iter()
            .flatten()
            .min_by(|a, b| a.day.total_cmp(&b.day))
    }
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::events::label(ctx, counted(ctx)?)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let g = gearing::load(ctx)?;
    let trials = ctx.u64("trials")?;
    if trials == 0 {
        return Err(RunError::bad("--set", "trials", "must be at least 1"));
    }
    let days = days(ctx)?;
    let (h, clearance) = (ctx.f64("tooth_height")?, ctx.f64("clearance")?);
    // Read here, before the gearing's checks, as each case reads it again.
    ctx.f64("split")?;
    check_study(&g, h, &Clearances::Uniform(clearance))?;
    let pin_and_slot = gearing::pin_and_slot(ctx)?;
    let ideal = Mechanism::ideal(&g, h, clearance).map_err(crate::gearing::mechanism_error)?;
    gearing::with_pin_and_slot(ctx, ideal, pin_and_slot)?;

    let hyp = errors::chosen(ctx)?;
    let measured = measured_table(ctx.param("measured")?)?;
    let mut inputs: Vec<Input<'_>> = Vec::new();
    for ci in parse_cases(ctx.param("cases")?)? {
        inputs.push(case_input(ctx, hyp, ci, Clearances::Uniform(clearance))?);
    }
    if let Some((file, m)) = &measured {
        inputs.push(Input {
            label: "measured".into(),
            legend: format!("measured table {file}"),
            index: MEASURED_INDEX,
            source: "--set measured",
            hypothesis: m,
            params: Params::new(m, &[])
                .map_err(|e| RunError::bad("--set measured", e.what, e.rule))?,
            clearances: Clearances::Uniform(clearance),
            pin_and_slot: false,
            extra: None,
        });
    }
    for inp in &mut inputs {
        inp.pin_and_slot = pin_and_slot;
    }
    if inputs.is_empty() {
        return Err(RunError::bad(
            "--set",
            "cases",
            "no case and no measured table: nothing to run",
        ));
    }

    let outcomes = run_study(
        ctx,
        &g,
        &inputs,
        trials,
        h,
        days,
        &batch_key(ctx, &inputs, trials, h, clearance, days)?,
    )?;
    let per_input: Vec<&[Outcome]> = outcomes.chunks(trials as usize).collect();

    let mut report = Report {
        trials: outcomes.len() as u64,
        engagements: outcomes.iter().map(|o| o.engagements).sum::<f64>().round() as u64,
        ..Default::default()
    };
    let summaries: Vec<Vec<Summary>> = per_input.iter().map(|runs| summarise(runs, days)).collect();
    let (mut paper_table, agreement) = paper_table(&inputs, &summaries, trials, days, clearance);
    if pin_and_slot {
        paper_table.note("The Lunar train includes the pin-and-slot (--set pin_and_slot=true), beyond the paper: e5-k1 and k2-e6 turn in the frame of the e3 turntable, which turns at its mean rate.");
    }
    report.tables.push(paper_table);
    report
        .tables
        .push(detail_table(&inputs, &summaries, trials, days));
    report
        .tables
        .push(survival_table(&inputs, per_input.as_slice(), days));
    report.agreement = agreement;
    report.files.push(OutputFile::new(
        "failure-runs.csv",
        runs_csv(&inputs, &per_input, days),
    ));
    for (ti, name) in train_names().enumerate() {
        let curves: Vec<(String, Vec<(f64, f64)>)> = inputs
            .iter()
            .zip(&per_input)
            .map(|(inp, runs)| {
                let times: Vec<Option<f64>> =
                    runs.iter().map(|o| jam_of(o, ti).map(|j| j.day)).collect();
                (
                    inp.legend.clone(),
                    stats::step_points(&stats::kaplan_meier(&times, days), days),
                )
            })
            .collect();
        let svg = survival_plot(
            &format!("Section 5, the 30-run study: {name}, runs not yet jammed (Kaplan-Meier)"),
            days,
            &curves,
        )?;
        report.files.push(OutputFile::new(
            format!("failure-{}.svg", file_stem(name)),
            svg,
        ));
    }
    Ok(report)
}

/// The `days` parameter, checked: at least one year (jams are counted within a year), at most
/// 100 years.
pub(crate) fn days(ctx: &Context) -> Result<f64, RunError> {
    let days = ctx.f64(DAYS.name)?;
    if !(DAYS_PER_YEAR..=100.0 * DAYS_PER_YEAR).contains(&days) {
        return Err(RunError::bad(
            "--set",
            DAYS.name,
            format!(
                "must be between {DAYS_PER_YEAR} (one year of b: jams are counted within a year) and {} (got {days})",
                100.0 * DAYS_PER_YEAR
            ),
        ));
    }
    Ok(days)
}

/// Checks that the study can run on `g`: ideal gears fit at `clearances` and tooth height `h` (a
/// clearance or tooth height that breaks a mesh is bad input), and every train's pointers are in
/// the gearing.
pub(crate) fn check_study(
    g: &train::Gearing,
    h: f64,
    clearances: &Clearances,
) -> Result<(), RunError> {
    Mechanism::build_with_clearances(g, h, |m| clearances.of(m), |_name, gear| Ok(gear))
        .map_err(crate::gearing::mechanism_error)?;
    for (_, pointers) in TRAINS {
        for p in pointers {
            if g.pointer(p).is_none() || g.pointer_ratio(p).is_none() {
                return Err(RunError::bad(
                    "gearing",
                    format!("pointer {p}"),
                    "is missing from the gearing (the failure study runs every train)",
                ));
            }
        }
    }
    Ok(())
}

/// Case `CASES[ci]` under hypothesis `hyp` (its random and systematic errors, the `split`
/// parameter) at `clearances`; its RNG streams are selected by `ci`.
pub(crate) fn case_input<'a>(
    ctx: &Context,
    hyp: &'a dyn Hypothesis,
    ci: usize,
    clearances: Clearances,
) -> Result<Input<'a>, RunError> {
    let (case, systematic, random) = CASES[ci];
    let split = ctx.f64("split")?;
    Ok(Input {
        label: case.to_string(),
        legend: format!("Case {case} (systematic {systematic} deg, random {random})"),
        index: ci as u64,
        source: "--hypothesis",
        hypothesis: hyp,
        params: errors::params(
            ctx,
            hyp,
            &[
                ("random", random),
                ("systematic", systematic),
                ("split", split),
            ],
        )?,
        clearances,
        pin_and_slot: false,
        extra: None,
    })
}

/// Runs `trials` whole mechanisms of every input over `days` of b, all in one batch named
/// `batch` of [`Context::trials`] (flattened so that every run shares the pool), and returns
/// the outcomes input by input, each input's in trial order. Run `t` of an input draws from
/// `trial_rng(seed, (input.index << 32) | t)`: the gears' errors, then the meshes' initial
/// angles, whatever the clearances.
pub(crate) fn run_study(
    ctx: &Context,
    g: &train::Gearing,
    inputs: &[Input<'_>],
    trials: u64,
    h: f64,
    days: f64,
    batch: &str,
) -> Result<Vec<Outcome>, RunError> {
    let horizon = days / DAYS_PER_YEAR * TAU;
    let seed = ctx.seed();
    let events = crate::events::chosen(ctx)?;
    // The rule decides where a train stops, so it names the batch too.
    let batch = format!("{batch}|events={}", events.label());
    let jobs: Vec<(usize, u64)> = (0..inputs.len())
        .flat_map(|i| (0..trials).map(move |t| (i, t)))
        .collect();
    ctx.trials(&batch, jobs.len() as u64, |j| {
        let &(i, t) = jobs
            .get(j as usize)
            .ok_or_else(|| RunError::Internal(format!("run {j} of {}", jobs.len())))?;
        one_run(g, &inputs[i], h, seed, t, horizon, &events)
    })
}

/// The key of the batch of runs: everything that determines them. An input with its own
/// clearances (not `clearance` for every mesh) lists them.
pub(crate) fn batch_key(
    ctx: &Context,
    inputs: &[Input<'_>],
    trials: u64,
    h: f64,
    clearance: f64,
    days: f64,
) -> Result<String, RunError> {
    let inputs: Vec<String> = inputs
        .iter()
        .map(|inp| {
            let p: Vec<String> = inp.params.iter().map(|(k, v)| format!("{k}={v}")).collect();
            let extra = inp
                .extra
                .as_ref()
                .map(|(h, params)| {
                    let q: Vec<String> = params.iter().map(|(k, v)| format!("{k}={v}")).collect();
                    format!(" then {}({})", h.name(), q.join(","))
                })
                .unwrap_or_default();
            let own = match &inp.clearances {
                Clearances::Uniform(g) if *g == clearance => String::new(),
                Clearances::Uniform(g) => format!(" G = {g} %"),
                Clearances::PerMesh { default, meshes } => {
                    let m: Vec<String> = meshes.iter().map(|(k, v)| format!("{k}={v}")).collect();
                    format!(" G = {default} % except {}", m.join(","))
                }
            };
            // With the pin-and-slot left out (the paper) the key is what it always was.
            let pin = if inp.pin_and_slot {
                ", with the pin-and-slot"
            } else {
                ""
            };
            format!(
                "{} [{}] stream {} {}({}){extra}{own}{pin}",
                inp.label,
                inp.legend,
                inp.index,
                inp.hypothesis.name(),
                p.join(",")
            )
        })
        .collect();
    Ok(format!(
        "failure: {trials} runs per input over {days} d, h = {h} mm, G = {clearance} %, gearing {}, inputs: {}",
        ctx.param("gearing")?,
        inputs.join("; ")
    ))
}

/// Indices into `CASES` of a comma-separated list of case names.
pub(crate) fn parse_cases(text: &str) -> Result<Vec<usize>, RunError> {
    let mut out = Vec::new();
    for name in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some(i) = CASES.iter().position(|c| c.0.eq_ignore_ascii_case(name)) else {
            return Err(RunError::bad(
                "--set",
                "cases",
                format!("unknown case `{name}` (known: A, B, C, D)"),
            ));
        };
        if !out.contains(&i) {
            out.push(i);
        }
    }
    Ok(out)
}

/// The measured table named by the `measured` parameter, if any: (file as given, hypothesis).
fn measured_table(file: &str) -> Result<Option<(String, MeasuredHypothesis)>, RunError> {
    let Some(file) = hypotheses::measured_file_given(file) else {
        return Ok(None);
    };
    let text = input_file::read_to_string(std::path::Path::new(file), input_file::MAX_INPUT_BYTES)
        .map_err(|e| RunError::bad("--set measured", file, format!("cannot read: {e}")))?;
    let table = hypotheses::measured_from_ron(file, &text)
        .map_err(|e| RunError::bad("--set measured", e.what, e.rule))?;
    Ok(Some((file.to_string(), table.hypothesis())))
}

/// Train names, then the mechanism row.
pub(crate) fn train_names() -> impl Iterator<Item = &'static str> {
    TRAINS.iter().map(|t| t.0).chain(std::iter::once(MECHANISM))
}

/// The jam of train `ti` (`TRAINS.len()`: the mechanism).
pub(crate) fn jam_of(o: &Outcome, ti: usize) -> Option<&Jam> {
    if ti < TRAINS.len() {
        o.trains.get(ti).and_then(Option::as_ref)
    } else {
        o.mechanism()
    }
}

fn file_stem(train: &str) -> String {
    let first = train.split(' ').next().unwrap_or(train);
    first.to_lowercase().replace('/', "-")
}

/// One whole-mechanism run: trial `t` of `input`, at the input's clearances.
fn one_run(
    g: &train::Gearing,
    input: &Input<'_>,
    h: f64,
    seed: u64,
    t: u64,
    horizon: f64,
    events: &rules::Rule,
) -> Result<Outcome, RunError> {
    // One stream per (input, trial): every gear's errors, then every mesh's initial angle.
    let mut rng = trial_rng(seed, (input.index << 32) | t);
    let mut extra_rng = trial_rng(seed, EXTRA_STREAM | (input.index << 32) | t);
    let mut failure = None;
    let clearances = &input.clearances;
    let mech = Mechanism::build_with_clearances(
        g,
        h,
        |m| clearances.of(m),
        |name, gear| {
            let made = input.hypothesis.apply(&gear, name, &input.params, &mut rng);
            let made = match (&input.extra, made) {
                (Some((extra, params)), Ok(gear)) => {
                    extra.apply(&gear, name, params, &mut extra_rng)
                }
                (_, made) => made,
            };
            made.map_err(|e| {
                let text = e.to_string();
                failure = Some(RunError::bad(input.source, e.what, e.rule));
                text
            })
        },
    );
    let mech = match (mech, failure) {
        (_, Some(e)) => return Err(e),
        // The ideal gears fit (checked before), so the errors moved the bodies into each other:
        // this mechanism cannot turn at all.
        (Err(e), None) => {
            return Ok(Outcome {
                trains: vec![
                    Some(Jam {
                        day: 0.0,
                        mesh: e.mesh.clone(),
                    });
                    TRAINS.len()
                ],
                engagements: 0.0,
                unplaceable: Some(e.to_string()),
                lunar_sigma: None,
            });
        }
        (Ok(m), None) => m
            .with_rule(events.clone())
            .with_pin_and_slot(input.pin_and_slot)
            .map_err(|e| RunError::Internal(format!("the pin-and-slot was checked: {e}")))?,
    };
    let mut phi0s: BTreeMap<&str, f64> = BTreeMap::new();
    for m in g.meshes() {
        let mesh = mech
            .mesh(&m.label)
            .ok_or_else(|| RunError::Internal(format!("mesh {} was not built", m.label)))?;
        let pitch = TAU / mesh.driver().teeth() as f64;
        phi0s.insert(m.label.as_str(), rng.random::<f64>() * pitch);
    }
    // Stages by the chain of meshes leading to them: each mesh is simulated once per run.
    let mut memo: BTreeMap<String, Stage> = BTreeMap::new();
    let mut engagements = 0.0;
    let mut trains = Vec::with_capacity(TRAINS.len());
    let mut lunar_sigma = None;
    for (_, pointers) in TRAINS {
        let mut first: Option<Jam> = None;
        for &p in pointers {
            let missing = || RunError::Internal(format!("pointer {p} vanished from the gearing"));
            let chain = g.pointer(p).ok_or_else(missing)?;
            let ratio = g.pointer_ratio(p).ok_or_else(missing)?.to_f64();
            if mech.pin_slot_for(p).is_some() {
                // With the pin-and-slot the pointer's meshes on the turntable turn in its frame:
                // its train is run on its own (no other train shares its meshes).
                let run = mech
                    .run_pointer_from(p, horizon / TAU, |label| phi0s.get(label).copied())
                    .ok_or_else(missing)?;
                for s in &run.stages {
                    if let Some(traj) = s.run.trajectory() {
                        engagements += (traj.phi_end() - traj.phi_start()) / TAU
                            * traj.mesh().driver().teeth() as f64;
                    }
                }
                if p == "Lunar" {
                    lunar_sigma = lunar_spread(g, &run, horizon);
                }
                if let Some(stop) = run.first_stop()
                    && first.as_ref().is_none_or(|f| stop.day < f.day)
                {
                    first = Some(Jam {
                        day: stop.day,
                        mesh: stop.mesh,
                    });
                }
                continue;
            }
            let mut range = horizon;
            let mut key = String::new();
            let mut stages = Vec::with_capacity(chain.meshes.len());
            for label in &chain.meshes {
                key.push_str(label);
                key.push('>');
                let stage = match memo.get(&key) {
                    Some(s) => s.clone(),
                    None => {
                        let (Some(mesh), Some(&phi0)) =
                            (mech.mesh(label), phi0s.get(label.as_str()))
                        else {
                            return Err(RunError::Internal(format!("mesh {label} was not built")));
                        };
                        let is_jam = |e: &contact::Event| mech.rule().is_jam(e);
                        let traj =
                            mesh.run_until(phi0, phi0 + range, Start::Touching(0.0), Some(&is_jam));
                        engagements += (traj.phi_end() - traj.phi_start()) / TAU
                            * mesh.driver().teeth() as f64;
                        let s = Stage {
                            label: label.clone(),
                            phi0,
                            theta0: traj.theta_at(phi0),
                            run: StageRun::Triangular(Box::new(traj)),
                        };
                        memo.insert(key.clone(), s.clone());
                        s
                    }
                };
                range = stage.run.theta_at(stage.phi0 + range) - stage.theta0;
                stages.push(stage);
            }
            let run = PointerRun {
                pointer: p.to_string(),
                ratio,
                input_range: horizon,
                stages,
                pin_slot: None,
                rule: mech.rule().clone(),
            };
            if p == "Lunar" {
                lunar_sigma = lunar_spread(g, &run, horizon);
            }
            if let Some(stop) = run.first_stop()
                && first.as_ref().is_none_or(|f| stop.day < f.day)
            {
                first = Some(Jam {
                    day: stop.day,
                    mesh: stop.mesh,
                });
            }
        }
        trains.push(first);
    }
    Ok(Outcome {
        trains,
        engagements,
        unplaceable: None,
        lunar_sigma,
    })
}

/// σ of a pointer run's Theoretical Difference up to its first jam, sampled as table1 samples
/// (8 per tooth engagement of the busiest mesh); None for a run that jams at once, which has no
/// spread to speak of.
fn lunar_spread(g: &train::Gearing, run: &PointerRun, horizon: f64) -> Option<f64> {
    let samples = crate::table1::samples_for(g, &run.pointer, horizon / TAU, 8);
    run.first_stop()
        .is_none_or(|s| s.input_angle > 0.0)
        .then(|| run.stats(samples).sigma)
}

/// What is reported of one train (or the mechanism) under one input.
pub(crate) struct Summary {
    /// Runs jammed within a year, with the 95 % Clopper-Pearson interval.
    pub(crate) year: Proportion,
    /// Days of the first jam of the runs that jammed within the horizon, in trial order.
    pub(crate) days: Vec<f64>,
    /// Meshes that jammed first, with their counts, most frequent first.
    pub(crate) meshes: Vec<(String, usize)>,
}

/// Per train, then the mechanism.
pub(crate) fn summarise(runs: &[Outcome], horizon_days: f64) -> Vec<Summary> {
    (0..=TRAINS.len())
        .map(|ti| {
            let jams: Vec<&Jam> = runs
                .iter()
                .filter_map(|o| jam_of(o, ti))
                .filter(|j| j.day <= horizon_days)
                .collect();
            let in_year = jams.iter().filter(|j| j.day <= DAYS_PER_YEAR).count() as u64;
            let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
            for j in &jams {
                *counts.entry(j.mesh.as_str()).or_default() += 1;
            }
            let mut meshes: Vec<(String, usize)> = counts
                .into_iter()
                .map(|(m, c)| (m.to_string(), c))
                .collect();
            meshes.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
            Summary {
                year: clopper_pearson95(in_year, runs.len() as u64),
                days: jams.iter().map(|j| j.day).collect(),
                meshes,
            }
        })
        .collect()
}

/// Mean of days with its 95 % Student-t interval, clipped to the days a jam can have
/// (0 to the horizon): with few jams the t interval reaches below day 0.
fn mean_days(days: &[f64], horizon: f64) -> stats::Estimate {
    let mut e = mean_ci95(days);
    e.lo = e.lo.max(0.0);
    e.hi = e.hi.min(horizon);
    e
}

/// "mean [lo .. hi]" of days (no interval for one value, "-" for none).
pub(crate) fn mean_cell(days: &[f64], horizon: f64) -> String {
    let e = mean_days(days, horizon);
    match days.len() {
        0 => "-".into(),
        1 => format!("{} (n = 1)", fmt_f64(e.mean, 0)),
        _ => format!(
            "{} [{} .. {}]",
            fmt_f64(e.mean, 0),
            fmt_f64(e.lo, 0),
            fmt_f64(e.hi, 0)
        ),
    }
}

/// "rate [lo .. hi]" of a proportion, in whole percent.
pub(crate) fn percent_cell(p: &Proportion) -> String {
    format!(
        "{} [{} .. {}]",
        fmt_f64(100.0 * p.rate(), 0),
        fmt_f64(100.0 * p.lo, 0),
        fmt_f64(100.0 * p.hi, 0)
    )
}

/// The paper's numbers beside ours, per input; the agreement counts the measured input only.
fn paper_table(
    inputs: &[Input<'_>],
    summaries: &[Vec<Summary>],
    trials: u64,
    days: f64,
    clearance: f64,
) -> (Table, Option<Agreement>) {
    let mut header = vec!["quantity".to_string(), "paper".to_string()];
    header.extend(inputs.iter().map(|i| match i.index {
        MEASURED_INDEX => "measured table".to_string(),
        _ => format!("Case {}", i.label),
    }));
    let mut table = Table::new(
        format!(
            "Section 5, the 30-run study: the paper beside ours (G = {clearance} %, {trials} runs per input, {} days of b): ours [95 % interval]; * where the paper's value is outside it",
            fmt_f64(days, 2)
        ),
        header,
    );
    let paper = |q: &str| crate::paper::get("failure", q).map(|r| r.value);
    let mut agreement = Agreement::default();
    let mut judged = false;
    // (label, paper quantity, train index, is the share row)
    let mut rows: Vec<(String, String, usize, bool)> = vec![(
        "mechanisms jammed within a year [%]".into(),
        "mechanisms_jammed".into(),
        TRAINS.len(),
        true,
    )];
    for (ti, (name, _)) in TRAINS.iter().enumerate() {
        rows.push((
            format!("{name}: mean day of the first jam"),
            format!("{name}.mean_days"),
            ti,
            false,
        ));
    }
    for (label, quantity, ti, share) in rows {
        let p = paper(&quantity);
        let mut row = vec![label, p.map_or_else(|| "-".into(), |v| fmt_f64(v, 0))];
        for (inp, s) in inputs.iter().zip(summaries) {
            let s = &s[ti];
            let (cell, inside) = if share {
                let inside = p.map(|v| {
                    let r = v / 100.0;
                    s.year.lo <= r && r <= s.year.hi
                });
                (percent_cell(&s.year), inside)
            } else {
                let e = mean_days(&s.days, days);
                let inside = p.filter(|_| s.days.len() >= 2).map(|v| e.contains(v));
                (mean_cell(&s.days, days), inside)
            };
            let mark = if inside == Some(false) { " *" } else { "" };
            row.push(format!("{cell}{mark}"));
            if inp.index == MEASURED_INDEX
                && let Some(inside) = inside
            {
                judged = true;
                if inside {
                    agreement.consistent += 1;
                } else {
                    agreement.differ += 1;
                }
            }
        }
        table.row(row);
    }
    // The conclusion's "one-third (120 deg)": the median day the mechanism stopped.
    let third = paper("stop_angle").map(|deg| deg / 360.0 * DAYS_PER_YEAR);
    let mut row = vec![
        "median day the mechanism stopped (of the runs that did)".to_string(),
        third.map_or_else(|| "-".into(), |d| format!("about {}", fmt_f64(d, 0))),
    ];
    for s in summaries {
        row.push(
            stats::median(&s[TRAINS.len()].days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
        );
    }
    table.row(row);
    table.note("The paper ran Edmunds' measured per-gear errors (its Figure 6), which are not available here: our inputs are Edmunds' Cases A-D until a measured table is given with --set measured=FILE. Only that column is counted as agreement with the paper; the cases are for orientation.");
    table.note("Shares: runs whose mechanism (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed within the horizon, 95 % Student-t interval clipped to 0 .. horizon (none for fewer than two).");
    table.note("The paper's horizon is not stated (Table 1 ran 1, 3.8 and 4.5 turns of b); ours is the days parameter. The last row compares with the conclusions: a mechanism with Edmunds' errors 'would generally stop after the solar pointer completed one-third (120 deg)'.");
    (table, judged.then_some(agreement))
}

fn detail_table(inputs: &[Input<'_>], summaries: &[Vec<Summary>], trials: u64, days: f64) -> Table {
    let mut table = Table::new(
        format!(
            "Days to the first jam per input and train ({trials} runs each, horizon {} days of b)",
            fmt_f64(days, 2)
        ),
        [
            "input",
            "train",
            "jammed within a year",
            "95 % interval [%]",
            "jammed within the horizon",
            "mean day [95 % interval]",
            "median day",
            "meshes that jammed first (runs)",
        ],
    );
    for (inp, s) in inputs.iter().zip(summaries) {
        for (name, s) in train_names().zip(s) {
            let meshes: Vec<String> = s
                .meshes
                .iter()
                .take(4)
                .map(|(m, c)| format!("{m} ({c})"))
                .collect();
            table.row(vec![
                inp.label.clone(),
                name.into(),
                format!("{}/{}", s.year.k, s.year.n),
                format!(
                    "{} .. {}",
                    fmt_f64(100.0 * s.year.lo, 0),
                    fmt_f64(100.0 * s.year.hi, 0)
                ),
                format!("{}/{}", s.days.len(), s.year.n),
                mean_cell(&s.days, days),
                stats::median(&s.days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                if meshes.is_empty() {
                    "-".into()
                } else {
                    meshes.join(", ")
                },
            ]);
        }
    }
    for inp in inputs {
        let p: Vec<String> = inp
            .params
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        table.note(format!(
            "{}: hypothesis {} with {}.",
            inp.label,
            inp.hypothesis.name(),
            if p.is_empty() {
                "no parameters".into()
            } else {
                p.join(", ")
            }
        ));
    }
    table.note("One run is one mechanism: every gear manufactured once, each mesh given one random initial angle, each mesh run once up to its first jam; trains sharing meshes (b2-l1, l2-m1) share their motion. A train's first jam is the earliest jam on any of its pointers' meshes, dated on the b arbor. Trains are counted separately, as the paper did; in the real mechanism any jam stops every train (the mechanism row).");
    table
}

/// Share of runs not yet jammed at fixed angles of b.
fn survival_table(inputs: &[Input<'_>], per_input: &[&[Outcome]], days: f64) -> Table {
    let mut header = vec!["input".to_string(), "train".to_string()];
    for deg in READ_AT_DEG {
        header.push(format!(
            "{deg} deg of b ({} d)",
            fmt_f64(deg / 360.0 * DAYS_PER_YEAR, 1)
        ));
    }
    let mut table = Table::new(
        "Runs not yet jammed [%] at angles of the solar pointer (b arbor)",
        header,
    );
    let mut unplaceable = 0;
    for (inp, runs) in inputs.iter().zip(per_input) {
        unplaceable += runs.iter().filter(|o| o.unplaceable.is_some()).count();
        for (ti, name) in train_names().enumerate() {
            let times: Vec<Option<f64>> =
                runs.iter().map(|o| jam_of(o, ti).map(|j| j.day)).collect();
            let steps = stats::kaplan_meier(&times, days);
            let mut row = vec![inp.label.clone(), name.to_string()];
            for deg in READ_AT_DEG {
                row.push(survival_cell(&steps, deg / 360.0 * DAYS_PER_YEAR));
            }
            table.row(row);
        }
    }
    table.note("Kaplan-Meier estimate [95 % band]; every run is observed to the same horizon, so it is the share of runs whose first jam came later, and the band is that share's exact (Clopper-Pearson) interval.");
    if unplaceable > 0 {
        table.note(format!(
            "{unplaceable} runs had gears whose bodies overlapped at every angle (errors too large for the clearance): counted as jammed at day 0."
        ));
    }
    table
}

/// A survival share [%] at `day` with its 95 % band: `50 [33 .. 70]`.
fn survival_cell(steps: &[stats::Step], day: f64) -> String {
    let at = steps
        .iter()
        .take_while(|p| p.day <= day)
        .last()
        .copied()
        .unwrap_or(stats::Step {
            day: 0.0,
            survival: 100.0,
            lo: 100.0,
            hi: 100.0,
        });
    format!(
        "{} [{} .. {}]",
        fmt_f64(at.survival, 0),
        fmt_f64(at.lo, 0),
        fmt_f64(at.hi, 0)
    )
}

fn survival_plot(
    title: &str,
    horizon: f64,
    curves: &[(String, Vec<(f64, f64)>)],
) -> Result<String, RunError> {
    let colours = [BLUE, RED, BLACK, GREEN, MAGENTA, CYAN];
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 480)).into_drawing_area();
        let plot_err = |e: &dyn std::fmt::Display| RunError::Internal(format!("plot {title}: {e}"));
        root.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(0.0..horizon, 0.0..102.0)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc("days of the b arbor (solar pointer; 365.25 d per turn)")
            .y_desc("runs not yet jammed [%]")
            .x_label_formatter(&|v: &f64| format!("{v:.0}"))
            .y_label_formatter(&|v: &f64| format!("{v:.0}"))
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (i, (label, points)) in curves.iter().enumerate() {
            let colour = colours[i % colours.len()];
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(|e| plot_err(&e))?
                .label(label.as_str())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::MiddleRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| plot_err(&e))?;
        root.present().map_err(|e| plot_err(&e))?;
    }
    Ok(svg)
}

/// Per run and train: the day of the first jam, or the horizon and "censored".
pub(crate) fn runs_csv(inputs: &[Input<'_>], per_input: &[&[Outcome]], days: f64) -> String {
    let mut csv = String::from("input,trial,train,first_jam_day,status,mesh\n");
    for (inp, runs) in inputs.iter().zip(per_input) {
        for (t, o) in runs.iter().enumerate() {
            for (ti, name) in train_names().enumerate() {
                let line = match jam_of(o, ti).filter(|j| j.day <= days) {
                    Some(j) => format!("{},{t},{name},{},jammed,{}\n", inp.label, j.day, j.mesh),
                    None => format!("{},{t},{name},{days},censored,\n", inp.label),
                };
                csv.push_str(&line);
            }
        }
    }
    csv
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn survival_cells_carry_their_band() {
        let steps = stats::kaplan_meier(&[Some(30.0), None, Some(10.0), Some(10.0)], 100.0);
        // 4 of 4 not yet jammed: the exact interval still reaches down to 40 %.
        assert_eq!(survival_cell(&steps, 5.0), "100 [40 .. 100]");
        let at_10 = survival_cell(&steps, 10.0);
        assert!(at_10.starts_with("50 ["), "{at_10}");
        assert_eq!(
            stats::survival_at(&steps, 99.0),
            25.0,
            "the cell reads the same curve"
        );
    }

    #[test]
    fn cases_parse_and_refuse_unknown_names() {
        assert_eq!(parse_cases("A, c,D,a").unwrap(), [0, 2, 3]);
        assert!(parse_cases("").unwrap().is_empty());
        let e = parse_cases("A,E").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("`E`"), "{e}");
    }

    fn run_with(threads: usize, sets: &[(&str, &str)]) -> Result<Report, RunError> {
        crate::link();
        let map = registry::experiments().unwrap();
        let overrides: Vec<(String, String)> = sets
            .iter()
            .map(|(k, v)| ((*k).to_string(), (*v).to_string()))
            .collect();
        let ctx = Context::new(map["failure"], 11, threads, &overrides, None)?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| run(&ctx))
    }

    #[test]
    fn bad_parameters_are_refused_as_bad_input() {
        for sets in [
            &[("days", "100")][..],
            &[("trials", "0")],
            &[("cases", "X")],
            &[("cases", "")],
            &[("measured", "/no/such/file.ron")],
        ] {
            let e = run_with(1, sets).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{sets:?}: {e}");
        }
    }

    #[test]
    fn case_d_is_identical_with_one_and_two_threads() {
        // Case D jams early in almost every run, so this is quick.
        let sets = [("cases", "D"), ("trials", "3")];
        let one = run_with(1, &sets).unwrap();
        let two = run_with(2, &sets).unwrap();
        assert_eq!(one, two);
        assert_eq!(one.trials, 3);
        assert!(one.engagements > 0);
        assert_eq!(
            one.agreement, None,
            "cases are not judged against the paper"
        );
        let csv = &one.files[0];
        assert_eq!(csv.name, "failure-runs.csv");
        // 3 runs x (3 trains + mechanism) + header.
        assert_eq!(String::from_utf8_lossy(&csv.contents).lines().count(), 13);
    }

    #[test]
    fn a_measured_table_is_run_and_judged() {
        let path =
            std::env::temp_dir().join(format!("failure-measured-{}.ron", std::process::id()));
        // Every gear with Case D's errors: quick, and a judged column.
        let mut text = String::from("(gears: [\n");
        for g in train::Gearing::freeth2006().gears() {
            text.push_str(&format!(
                "(gear: \"{}\", random: 0.08, systematic: 2.0),\n",
                g.name
            ));
        }
        text.push_str("])\n");
        std::fs::write(&path, text).unwrap();
        let r = run_with(
            2,
            &[
                ("cases", ""),
                ("trials", "2"),
                ("measured", path.to_str().unwrap()),
            ],
        );
        let _ = std::fs::remove_file(&path);
        let r = r.unwrap();
        assert_eq!(r.trials, 2);
        let a = r.agreement.unwrap();
        assert!(a.consistent + a.differ >= 1, "{a:?}");
        assert!(r.tables[0].columns.iter().any(|c| c == "measured table"));
    }
}
