//! The whole-mechanism study (the paper's 30-run study, section 5): whole mechanisms with
//! manufacturing errors, each run until its trains jam; per train the day of the first jam.
//!
//! One run is one mechanism: every gear manufactured once (a gear in two meshes carries the same
//! errors in both), every one of the gearing's meshes given one random initial angle, and every
//! mesh simulated once over the horizon, up to its first jam. Trains that share meshes (b2-l1 and
//! l2-m1 are in both the Metonic/Games and the Saros/Exeligmos trains) share their motion.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use contact::{Solve, Start};
use hypotheses::{Hypothesis, MeasuredHypothesis, Params};
use mechanism::{Mechanism, PointerRun, Stage, StageRun};
use rand::Rng;
use registry::{Param, RunError, Streams, TrialEngine};
use serde::{Deserialize, Serialize};
use stats::{DAYS_PER_YEAR, Proportion, clopper_pearson95, mean_ci95};

use crate::draws::{Draws, Part};
use crate::grids::CASES;

/// The `days` parameter: the horizon of each whole-mechanism run.
pub const DAYS: Param = Param {
    name: "days",
    default: "365.25",
    unit: "days of b",
    help: "horizon of each run (365.25 d per turn of b); at least one year",
    kind: registry::Kind::number(
        stats::DAYS_PER_YEAR,
        100.0 * stats::DAYS_PER_YEAR,
        "one year of b: jams are counted within a year",
    ),
    reading: false,
    clearance: false,
    recorded: false,
};

/// The `cases` parameter: which of Edmunds' cases to run.
pub const CASES_PARAM: Param = Param {
    name: "cases",
    default: "A,B,C,D",
    unit: "",
    help: "Edmunds' cases to run, comma-separated (empty: none)",
    kind: registry::Kind::Text,
    reading: false,
    clearance: false,
    recorded: false,
};

/// Whole-mechanism runs per input at the defaults (the paper: 30).
pub const RUNS_DEFAULT: &str = "30";

/// A train of the study: (name, the pointers whose meshes make it up).
pub type Train = (&'static str, &'static [&'static str]);

/// The trains the paper reports: (name, the pointers whose meshes make it up).
pub const TRAINS: [Train; 3] = [
    ("Lunar", &["Lunar"]),
    ("Metonic/Games", &["Metonic", "Games"]),
    ("Saros/Exeligmos", &["Saros", "Exeligmos"]),
];

/// Name of the row that combines every train (a jam anywhere stops the mechanism).
pub const MECHANISM: &str = "mechanism (any train)";

/// Gears index of the measured table ([`Input::index`]; the cases use their index in `CASES`).
pub const MEASURED_INDEX: u64 = CASES.len() as u64;

/// The clearance of each mesh of a whole mechanism.
#[derive(Debug, Clone, PartialEq)]
pub enum Clearances {
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
    pub fn of(&self, label: &str) -> f64 {
        match self {
            Clearances::Uniform(g) => *g,
            Clearances::PerMesh { default, meshes } => {
                meshes.get(label).copied().unwrap_or(*default)
            }
        }
    }
}

/// One set of error inputs: a case or the measured table, at its clearances.
pub struct Input<'a> {
    /// "A".."D" or "measured".
    pub label: String,
    /// Legend text.
    pub legend: String,
    /// Which gears it draws ([`Draws::WholeMechanism`]): inputs with the same index run the
    /// same gears and initial angles (only the clearances may differ).
    pub index: u64,
    /// Where its hypothesis came from, for errors: `--hypothesis` or `--set measured`.
    pub source: &'static str,
    /// The hypothesis that makes its gears.
    pub hypothesis: &'a dyn Hypothesis,
    /// The hypothesis's parameter values.
    pub params: Params,
    /// The clearance of each mesh.
    pub clearances: Clearances,
    /// The Lunar train includes the pin-and-slot (beyond the paper; off in the paper's study).
    pub pin_and_slot: bool,
    /// A second hypothesis applied to each gear after the first (a shape change on top of
    /// Edmunds' errors), drawing from a stream of its own ([`Part::ExtraErrors`]): the first
    /// one's draws and the initial angles stay those of the run without it, so the two runs
    /// differ by it alone.
    pub extra: Option<(&'a dyn Hypothesis, Params)>,
}

/// The first jam of a train within the horizon.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Jam {
    /// Day of the b arbor.
    pub day: f64,
    /// The mesh that jammed.
    pub mesh: String,
}

/// One whole-mechanism run. The default (a run of another shard, see `TrialEngine::trials`) has
/// no trains: it reads as a run that never jammed.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct MechanismRun {
    /// First jam per train of `TRAINS` (None: none within the horizon).
    pub trains: Vec<Option<Jam>>,
    /// Driver turns times driver teeth, summed over every simulated mesh.
    pub engagements: f64,
    /// The gears could not be placed (bodies overlapping at every angle): the mesh and rule.
    pub unplaceable: Option<String>,
    /// σ of the Lunar pointer's Theoretical Difference (degrees) over the run up to its first jam
    /// (None: it jammed at once, or the gears could not be placed).
    #[serde(default)]
    pub lunar_sigma: Option<f64>,
}

impl MechanismRun {
    /// First jam anywhere.
    pub fn mechanism(&self) -> Option<&Jam> {
        self.trains
            .iter()
            .flatten()
            .min_by(|a, b| a.day.total_cmp(&b.day))
    }
}

/// Checks that the study can run on `g`: ideal gears fit at `clearances` and tooth height `h` (a
/// clearance or tooth height that breaks a mesh is bad input), and every train's pointers are in
/// the gearing.
pub fn check_study(g: &train::Gearing, h: f64, clearances: &Clearances) -> Result<(), RunError> {
    check_trains(g, h, clearances, &TRAINS)
}

/// [`check_study`] for the trains `trains`.
pub fn check_trains(
    g: &train::Gearing,
    h: f64,
    clearances: &Clearances,
    trains: &[Train],
) -> Result<(), RunError> {
    Mechanism::build_with_clearances(g, h, |m| clearances.of(m), |_name, gear| Ok(gear))
        .map_err(crate::gearing::mechanism_error)?;
    for &(_, pointers) in trains {
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

/// Case `CASES[ci]` under the hypothesis of `errors` (its random and systematic errors, the
/// split) at `clearances`; its RNG streams are selected by `ci`.
pub fn case_input(
    errors: &crate::errors::Settings,
    ci: usize,
    clearances: Clearances,
) -> Result<Input<'static>, RunError> {
    let hyp = errors.hypothesis;
    let (case, systematic, random) = CASES[ci];
    Ok(Input {
        label: case.to_string(),
        legend: format!("Case {case} (systematic {systematic} deg, random {random})"),
        index: ci as u64,
        source: "--hypothesis",
        hypothesis: hyp,
        params: errors.case_params((systematic, random))?,
        clearances,
        pin_and_slot: false,
        extra: None,
    })
}

/// Runs `trials` whole mechanisms of every input over `days` of b, all in one batch named
/// `batch` of [`TrialEngine::trials`] (flattened so that every run shares the pool), and returns
/// the outcomes input by input, each input's in trial order. Run `t` of an input draws from
/// trial t of [`Draws::WholeMechanism`] of `input.index`: the gears' errors, then the meshes'
/// initial angles, whatever the clearances. Jams are counted by `events`.
#[allow(
    clippy::too_many_arguments,
    reason = "the study's inputs, each a value of its own"
)]
pub fn run_study(
    engine: &TrialEngine,
    g: &train::Gearing,
    inputs: &[Input<'_>],
    trials: u64,
    h: f64,
    days: f64,
    events: &rules::Rule,
    batch: &str,
) -> Result<Vec<MechanismRun>, RunError> {
    let study = Study {
        gearing: g,
        trains: &TRAINS,
        h,
        days,
        events,
    };
    run_study_of(engine, &study, inputs, trials, batch)
}

/// What a whole-mechanism study runs: the gearing, its trains (each a run's [`MechanismRun`]
/// entry, in order), h, the horizon in days of b and the event rule that stops a train.
pub struct Study<'a> {
    /// The gearing.
    pub gearing: &'a train::Gearing,
    /// The trains whose first jams a run records.
    pub trains: &'a [Train],
    /// Tooth height h (mm).
    pub h: f64,
    /// Horizon of each run, days of b.
    pub days: f64,
    /// The event rule that counts a jam.
    pub events: &'a rules::Rule,
}

/// [`run_study`] for any trains: `trials` runs of every input, as the batch `batch`.
pub fn run_study_of(
    engine: &TrialEngine,
    study: &Study<'_>,
    inputs: &[Input<'_>],
    trials: u64,
    batch: &str,
) -> Result<Vec<MechanismRun>, RunError> {
    let (g, days, events) = (study.gearing, study.days, study.events);
    let h = study.h;
    let horizon = days / DAYS_PER_YEAR * TAU;
    let streams = engine.streams();
    // The rule decides where a train stops, so it names the batch too.
    let batch = format!("{batch}|events={}", events.label());
    // Run j is run j % trials of input j / trials (arithmetic, not a vector of every pair).
    let jobs = inputs.len() as u64 * trials;
    engine.trials(&batch, jobs, |j| {
        let input = inputs
            .get((j / trials) as usize)
            .ok_or_else(|| RunError::Internal(format!("run {j} of {jobs}")))?;
        one_run(
            g,
            input,
            h,
            streams,
            j % trials,
            horizon,
            events,
            study.trains,
        )
    })
}

/// The key of the batch of runs: everything that determines them. An input with its own
/// clearances (not `clearance` for every mesh) lists them. `gearing` is the gearing as typed.
pub fn batch_key(
    gearing: &str,
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
        gearing,
        inputs.join("; ")
    ))
}

/// Indices into `CASES` of a comma-separated list of case names.
pub fn parse_cases(text: &str) -> Result<Vec<usize>, RunError> {
    let mut out = Vec::new();
    for name in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        let Some(i) = CASES.iter().position(|c| c.0.eq_ignore_ascii_case(name)) else {
            return Err(RunError::bad(
                "--set",
                "cases",
                format!("unknown case `{name}` (known: A, B, C, D)"),
            ));
        };
        // Named twice: refused, as every list a run takes refuses a repeat (the runs of a
        // Case would be one row twice over).
        if out.contains(&i) {
            return Err(RunError::bad(
                "--set",
                "cases",
                format!("names the case `{name}` twice: give each once (got `{text}`)"),
            ));
        }
        out.push(i);
    }
    Ok(out)
}

/// The measured table named by the `measured` parameter, if any: (file as given, hypothesis).
pub fn measured_table(file: &str) -> Result<Option<(String, MeasuredHypothesis)>, RunError> {
    let Some(file) = hypotheses::measured_file_given(file) else {
        return Ok(None);
    };
    let text = input_file::read_to_string(std::path::Path::new(file), input_file::MAX_INPUT_BYTES)
        .map_err(|e| RunError::bad("--set", "measured", format!("{file}: cannot read: {e}")))?;
    let table = hypotheses::measured_from_ron(file, &text)
        .map_err(|e| RunError::bad("--set", "measured", format!("{}: {}", e.what, e.rule)))?;
    Ok(Some((file.to_string(), table.hypothesis())))
}

/// Train names, then the mechanism row.
pub fn train_names() -> impl Iterator<Item = &'static str> {
    TRAINS.iter().map(|t| t.0).chain(std::iter::once(MECHANISM))
}

/// The jam of train `ti` (`TRAINS.len()`: the mechanism).
pub fn jam_of(o: &MechanismRun, ti: usize) -> Option<&Jam> {
    jam_of_in(o, ti, TRAINS.len())
}

/// The jam of train `ti` of a study of `trains` trains (`trains`: the mechanism).
pub fn jam_of_in(o: &MechanismRun, ti: usize, trains: usize) -> Option<&Jam> {
    if ti < trains {
        o.trains.get(ti).and_then(Option::as_ref)
    } else {
        o.mechanism()
    }
}

/// A run of a mechanism whose gears, as made, cannot be placed: the errors moved the bodies into
/// each other (the ideal gears fit, checked before), so it cannot turn at all.
fn unplaceable(e: &mechanism::MechanismError, trains: usize) -> MechanismRun {
    MechanismRun {
        trains: vec![
            Some(Jam {
                day: 0.0,
                mesh: e.mesh.clone(),
            });
            trains
        ],
        engagements: 0.0,
        unplaceable: Some(e.to_string()),
        lunar_sigma: None,
    }
}

/// Every mesh's initial driver angle, drawn from the run's stream in the gearing's order: a
/// share of the driver's pitch.
fn initial_angles<'g>(
    g: &'g train::Gearing,
    mech: &Mechanism,
    rng: &mut impl Rng,
) -> Result<BTreeMap<&'g str, f64>, RunError> {
    let mut phi0s: BTreeMap<&str, f64> = BTreeMap::new();
    for m in g.meshes() {
        let mesh = mech
            .mesh(&m.label)
            .ok_or_else(|| RunError::Internal(format!("mesh {} was not built", m.label)))?;
        let pitch = TAU / mesh.driver().teeth() as f64;
        phi0s.insert(m.label.as_str(), rng.random::<f64>() * pitch);
    }
    Ok(phi0s)
}

/// The stages of a pointer's chain of `meshes` over `horizon` of its input, each mesh run to its
/// first jam from its initial angle; a chain's stage already run (`memo`, by the chain of meshes
/// leading to it) is reused, so each mesh is simulated once per run. Adds the driver teeth that
/// engaged to `engagements`.
fn chain_stages(
    mech: &Mechanism,
    meshes: &[String],
    phi0s: &BTreeMap<&str, f64>,
    horizon: f64,
    memo: &mut BTreeMap<String, Stage>,
    engagements: &mut f64,
) -> Result<Vec<Stage>, RunError> {
    let mut range = horizon;
    let mut key = String::new();
    let mut stages = Vec::with_capacity(meshes.len());
    for label in meshes {
        key.push_str(label);
        key.push('>');
        let stage = match memo.get(&key) {
            Some(s) => s.clone(),
            None => {
                let (Some(mesh), Some(&phi0)) = (mech.mesh(label), phi0s.get(label.as_str()))
                else {
                    return Err(RunError::Internal(format!("mesh {label} was not built")));
                };
                let is_jam = |e: &contact::Event| mech.rule().is_jam(e);
                let traj = mesh.solve(
                    phi0..=phi0 + range,
                    Start::Touching(0.0),
                    Solve::path().stop_at(&is_jam),
                );
                *engagements +=
                    (traj.phi_end() - traj.phi_start()) / TAU * mesh.driver().teeth() as f64;
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
    Ok(stages)
}

/// One whole-mechanism run: trial `t` of `input`, at the input's clearances.
#[allow(
    clippy::too_many_arguments,
    reason = "the run's inputs, each a value of its own"
)]
fn one_run(
    g: &train::Gearing,
    input: &Input<'_>,
    h: f64,
    streams: Streams,
    t: u64,
    horizon: f64,
    events: &rules::Rule,
    trains_run: &[Train],
) -> Result<MechanismRun, RunError> {
    // One stream per (gears, trial): every gear's errors, then every mesh's initial angle; the
    // extra hypothesis's errors from a part of their own.
    let draws = Draws::WholeMechanism { gears: input.index };
    let mut rng = streams.stream(draws.identity(), t);
    let mut extra_rng = streams.stream(draws.part(Part::ExtraErrors), t);
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
        (Err(e), None) => return Ok(unplaceable(&e, trains_run.len())),
        (Ok(m), None) => m
            .with_rule(events.clone())
            .with_pin_and_slot(input.pin_and_slot)
            .map_err(|e| RunError::Internal(format!("the pin-and-slot was checked: {e}")))?,
    };
    let phi0s = initial_angles(g, &mech, &mut rng)?;
    // Stages by the chain of meshes leading to them: each mesh is simulated once per run.
    let mut memo: BTreeMap<String, Stage> = BTreeMap::new();
    let mut engagements = 0.0;
    let mut trains = Vec::with_capacity(trains_run.len());
    let mut lunar_sigma = None;
    for &(_, pointers) in trains_run {
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
                note_pointer(g, &run, horizon, &mut first, &mut lunar_sigma);
                continue;
            }
            let stages = chain_stages(
                &mech,
                &chain.meshes,
                &phi0s,
                horizon,
                &mut memo,
                &mut engagements,
            )?;
            let run = PointerRun {
                pointer: p.to_string(),
                ratio,
                input_range: horizon,
                stages,
                pin_slot: None,
                rule: mech.rule().clone(),
            };
            note_pointer(g, &run, horizon, &mut first, &mut lunar_sigma);
        }
        trains.push(first);
    }
    Ok(MechanismRun {
        trains,
        engagements,
        unplaceable: None,
        lunar_sigma,
    })
}

/// What one pointer's run tells its train: its first stop, if earlier than the train's first so
/// far, and for the Lunar pointer the σ of its TD.
fn note_pointer(
    g: &train::Gearing,
    run: &PointerRun,
    horizon: f64,
    first: &mut Option<Jam>,
    lunar_sigma: &mut Option<f64>,
) {
    if run.pointer == "Lunar" {
        *lunar_sigma = lunar_spread(g, run, horizon);
    }
    if let Some(stop) = run.first_stop()
        && first.as_ref().is_none_or(|f| stop.day < f.day)
    {
        *first = Some(Jam {
            day: stop.day,
            mesh: stop.mesh,
        });
    }
}

/// σ of a pointer run's Theoretical Difference up to its first jam, sampled as table1 samples
/// (8 per tooth engagement of the busiest mesh); None for a run that jams at once, which has no
/// spread to speak of.
fn lunar_spread(g: &train::Gearing, run: &PointerRun, horizon: f64) -> Option<f64> {
    let samples = crate::pointers::samples_for(g, &run.pointer, horizon / TAU, 8);
    run.first_stop()
        .is_none_or(|s| s.input_angle > 0.0)
        .then(|| run.stats(samples).sigma)
}

/// What is reported of one train (or the mechanism) under one input.
pub struct Summary {
    /// Runs jammed within a year, with the 95 % Clopper-Pearson interval.
    pub year: Proportion,
    /// Days of the first jam of the runs that jammed within the horizon, in trial order.
    pub days: Vec<f64>,
    /// Meshes that jammed first, with their counts, most frequent first.
    pub meshes: Vec<(String, usize)>,
}

/// Per train, then the mechanism.
pub fn summarise(runs: &[MechanismRun], horizon_days: f64) -> Vec<Summary> {
    summarise_trains(runs, horizon_days, TRAINS.len())
}

/// [`summarise`] for a study of `trains` trains.
pub fn summarise_trains(runs: &[MechanismRun], horizon_days: f64, trains: usize) -> Vec<Summary> {
    (0..=trains)
        .map(|ti| {
            let jams: Vec<&Jam> = runs
                .iter()
                .filter_map(|o| jam_of_in(o, ti, trains))
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
pub fn mean_days(days: &[f64], horizon: f64) -> stats::Estimate {
    let mut e = mean_ci95(days);
    e.lo = e.lo.max(0.0);
    e.hi = e.hi.min(horizon);
    e
}

/// Per run and train: the day of the first jam, or the horizon and "censored".
pub fn runs_csv(inputs: &[Input<'_>], per_input: &[&[MechanismRun]], days: f64) -> String {
    labelled_runs_csv(inputs.iter().map(|i| i.label.as_str()), per_input, days)
}

/// [`runs_csv`] of runs stored with their inputs' labels (`labels`, one per input) rather than
/// the inputs themselves.
pub fn labelled_runs_csv<'a>(
    labels: impl IntoIterator<Item = &'a str>,
    per_input: &[&[MechanismRun]],
    days: f64,
) -> String {
    let mut csv = String::from("input,trial,train,first_jam_day,status,mesh\n");
    for (label, runs) in labels.into_iter().zip(per_input) {
        for (t, o) in runs.iter().enumerate() {
            for (ti, name) in train_names().enumerate() {
                let line = match jam_of(o, ti).filter(|j| j.day <= days) {
                    Some(j) => registry::csv_row!(label, t, name, j.day, "jammed", j.mesh),
                    None => registry::csv_row!(label, t, name, days, "censored", ""),
                };
                csv.push_str(&line);
            }
        }
    }
    csv
}
