//! A typed experiment: settings in, results out (saved as data), a report drawn from them; and
//! the entry `inventory` collects for it.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::{Mutex, PoisonError};

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::{Value, json};

use crate::{ConfigFile, Context, Param, Report, RunError, Settings, TrialEngine, TrialMode};

/// Where an experiment's section stands in the report: the paper's items in the order the paper
/// presents them, then the studies beyond it (each plugin declares its own place, so that adding
/// one edits no list).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Place {
    /// An item of the paper; the number orders the items as the paper presents them (section 2's
    /// figures first, Appendix II's last), with room between for items added later.
    Paper(u32),
    /// A study beyond the paper, after every item of it, in the order the README discusses them.
    Beyond(u32),
}

/// An experiment: a table or figure of the paper, or a study beyond it.
///
/// [`Experiment::compute`] turns typed settings into typed results - every simulation - and
/// [`Experiment::report`] draws the tables and figures from them, touching no simulation, so that
/// a report is drawn again from stored results without recomputing them (`cargo xtask report`)
/// and a later experiment (the claims ledger) reads the results themselves rather than text
/// read back out of a table. A plugin file implements it on a unit struct and registers it with
/// [`crate::register!`].
pub trait Experiment: 'static {
    /// Short unique id used on the command line, e.g. "fig2".
    const ID: &'static str;
    /// One-line title.
    const TITLE: &'static str;
    /// The item of the paper it reproduces, e.g. "Figure 2 (section 2)".
    const PAPER_ITEM: &'static str;
    /// Where its section stands in the report.
    const PLACE: Place;
    /// `None`: the experiment takes no `--config FILE`; `Some(text)`: what the RON config file
    /// describes.
    const CONFIG: Option<&'static str> = None;

    /// Its settings: its own parameters and the groups it shares.
    type Settings: Settings;
    /// What it computes, stored as `results.json` beside its tables.
    type Results: Serialize + DeserializeOwned;

    /// Every simulation of the experiment.
    ///
    /// # Errors
    /// Bad input found against data (a gearing's mesh, a grid's end below its start), or a
    /// failure of the simulation.
    fn compute(settings: &Self::Settings, run: &Run) -> Result<Self::Results, RunError>;

    /// The tables and figures drawn from `results` (no simulation).
    ///
    /// # Errors
    /// Results that cannot be drawn (an internal error).
    fn report(settings: &Self::Settings, results: &Self::Results) -> Result<Report, RunError>;
}

/// What [`Experiment::compute`] is handed beside its settings: the trial engine (one RNG stream
/// per trial, shards, replays), the run's seed and threads, the `--config` file, and the
/// results of other experiments (the claims ledger reads them). It offers no parameter: those
/// are the settings, read once.
#[derive(Clone, Copy)]
pub struct Run<'a> {
    ctx: &'a Context,
    engine: &'a TrialEngine,
}

impl<'a> Run<'a> {
    /// The run of context `ctx`, its trials through `engine` (the context's own, or the engine
    /// of the run that asked for this experiment's results).
    pub fn new(ctx: &'a Context, engine: &'a TrialEngine) -> Run<'a> {
        Run { ctx, engine }
    }

    /// The trial engine with the run's seed: what `study`'s trial loops take.
    pub fn engine(&self) -> &'a TrialEngine {
        self.engine
    }

    /// The seed of every random stream of the run (`--seed`).
    pub fn seed(&self) -> u64 {
        self.ctx.seed()
    }

    /// Threads of the pool the experiment runs in (`--threads`).
    pub fn threads(&self) -> usize {
        self.ctx.threads()
    }

    /// The config file given with `--config`, if any.
    pub fn config(&self) -> Option<&'a ConfigFile> {
        self.ctx.config()
    }

    /// The results of experiment `id` run with its parameters at their defaults but for `sets`
    /// (declaration, value as typed), read typed: from `<results folder>/<id>/results.json` when
    /// a run there was made with exactly these settings and this seed, else computed now
    /// (through the same trial engine, so a shard or a replay of this run holds them too).
    /// Returns the results and where they came from.
    ///
    /// `T` must be the type experiment `id` declares as its results (checked by name: a
    /// mismatch is an internal error, never a misread).
    ///
    /// # Errors
    /// An unregistered id, a value its parameters refuse, a failure of its computation.
    pub fn results_of<T: DeserializeOwned>(
        &self,
        id: &str,
        sets: &[(&Param, String)],
    ) -> Result<(T, Source), RunError> {
        let entry = crate::experiments()
            .map_err(|e| RunError::Internal(e.to_string()))?
            .get(id)
            .copied()
            .ok_or_else(|| RunError::Internal(format!("no experiment `{id}` is registered")))?;
        if (entry.results_type)() != std::any::type_name::<T>() {
            return Err(RunError::Internal(format!(
                "experiment `{id}` stores {}, not {}",
                (entry.results_type)(),
                std::any::type_name::<T>()
            )));
        }
        let overrides: Vec<(String, String)> = sets
            .iter()
            .map(|(p, v)| (p.name.to_owned(), v.clone()))
            .collect();
        let ctx = Context::new(entry, self.seed(), self.threads(), &overrides, None)?;
        let settings = (entry.settings_of)(&ctx)?;
        if let Some(dir) = self.ctx.results_dir()
            && let Some(stored) = stored_results(&dir.join(id), id, self.seed(), &settings)
        {
            return Ok((decode(id, stored)?, Source::Stored(dir.join(id))));
        }
        if let Some(data) = cached(id, self.seed(), &settings)
            && let Some(results) = data.get("results")
        {
            return Ok((decode(id, results.clone())?, Source::Computed));
        }
        // Through this run's engine: a shard of this run computes (and records) its share of
        // the other experiment's trials too, and a merge replays them.
        let outcome = (entry.run)(&ctx, self.engine)?;
        let results = outcome
            .data
            .get("results")
            .cloned()
            .ok_or_else(|| RunError::Internal(format!("`{id}` stored no results")))?;
        Ok((decode(id, results)?, Source::Computed))
    }
}

/// Where [`Run::results_of`] took another experiment's results from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source {
    /// A results folder of an earlier run with the same settings and seed.
    Stored(PathBuf),
    /// Computed in this run.
    Computed,
}

/// The name of the stored results in an experiment's results folder.
pub const RESULTS_JSON: &str = "results.json";

/// The largest `results.json` read back: 256 MiB, as the report reads results files.
const MAX_RESULTS_JSON_BYTES: u64 = 256 * 1024 * 1024;

/// The results stored in `dir` if they are experiment `id`'s with exactly `settings` and `seed`.
/// Read with a size limit (a FIFO or a device named `results.json` is no stored result, never
/// waited on), one version of the folder should a run replace it meanwhile.
fn stored_results(dir: &Path, id: &str, seed: u64, settings: &Value) -> Option<Value> {
    let path = dir.join(RESULTS_JSON);
    let text = crate::read_one_version(dir, || {
        input_file::read_to_string(&path, MAX_RESULTS_JSON_BYTES)
    })
    .ok()?;
    let stored: Value = serde_json::from_str(&text).ok()?;
    let same = stored.get("experiment")?.as_str()? == id
        && stored.get("seed")?.as_u64()? == seed
        && stored.get("settings")? == settings;
    same.then(|| stored.get("results").cloned()).flatten()
}

fn decode<T: DeserializeOwned>(id: &str, value: Value) -> Result<T, RunError> {
    serde_json::from_value(value)
        .map_err(|e| RunError::Internal(format!("the results of `{id}` do not read back: {e}")))
}

/// What running an experiment gives: its report and its data (`results.json`: the experiment's
/// id, the seed, its settings and its results, as JSON).
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The tables and files, drawn from the results.
    pub report: Report,
    /// `{"experiment", "seed", "settings", "results"}`.
    pub data: Value,
}

/// The parameters a run sets away from the paper's inputs, each with its value as typed.
pub type Departures = Vec<(&'static Param, String)>;

/// A registered experiment, as `inventory` collects it: what it is, what it accepts, and its
/// typed functions behind plain function pointers. Made by [`Entry::of`] (through
/// [`crate::register!`]).
#[derive(Debug)]
pub struct Entry {
    /// Short unique id used on the command line, e.g. "fig2".
    pub id: &'static str,
    /// One-line title.
    pub title: &'static str,
    /// The item of the paper it reproduces.
    pub paper_item: &'static str,
    /// Where its section stands in the report.
    pub place: Place,
    /// `None`: the experiment takes no `--config FILE`; `Some(text)`: what the file describes.
    pub config: Option<&'static str>,
    params: fn(&mut Vec<&'static Param>),
    /// Reads the settings and computes the results (trials through the engine given) and the report.
    pub run: fn(&Context, &TrialEngine) -> Result<Outcome, RunError>,
    /// Draws the report again from stored data (`results.json`), computing nothing.
    pub render: fn(&Value) -> Result<Report, RunError>,
    settings_of: fn(&Context) -> Result<Value, RunError>,
    departures_of: fn(&Value) -> Result<Departures, RunError>,
    results_type: fn() -> &'static str,
}

impl crate::context::Declared for Entry {
    fn id(&self) -> &'static str {
        self.id
    }

    fn params(&self) -> Vec<&'static Param> {
        self.all_params().collect()
    }

    fn config(&self) -> Option<&'static str> {
        self.config
    }
}

impl Entry {
    /// The entry of experiment `E`.
    pub const fn of<E: Experiment>() -> Entry {
        Entry {
            id: E::ID,
            title: E::TITLE,
            paper_item: E::PAPER_ITEM,
            place: E::PLACE,
            config: E::CONFIG,
            params: <E::Settings as Settings>::params,
            run: run::<E>,
            render: render::<E>,
            settings_of: settings_of::<E>,
            departures_of: departures_of::<E>,
            results_type: std::any::type_name::<E::Results>,
        }
    }

    /// Every parameter, in declaration order (its own, then its groups', as its settings list them).
    pub fn all_params(&self) -> impl Iterator<Item = &'static Param> + Clone + use<> {
        let mut out = Vec::new();
        (self.params)(&mut out);
        out.into_iter()
    }

    /// Whether the experiment declares `p` itself (the same declaration, not only its name).
    pub fn declares(&self, p: &Param) -> bool {
        self.all_params().any(|q| q == p)
    }

    /// The inputs in which the run stored as `data` (`results.json`) departs from the paper's:
    /// its settings' [`Settings::departures`], read typed from the stored settings.
    ///
    /// # Errors
    /// Stored data whose settings do not read as this experiment's.
    pub fn departures(&self, data: &Value) -> Result<Departures, RunError> {
        (self.departures_of)(data)
    }

    /// The report of the run stored as `data` (`results.json`), drawn again from it and computing
    /// nothing, as the runner printed it: [`Entry::render`], then labelled where the run's
    /// inputs depart from the paper's ([`Report::label_departures`]).
    ///
    /// # Errors
    /// Stored data that does not read as this experiment's, or does not draw.
    pub fn redraw(&self, data: &Value) -> Result<Report, RunError> {
        let mut report = (self.render)(data)?;
        report.label_departures(&self.departures(data)?);
        Ok(report)
    }

    /// The name of the type it stores as its results (`std::any::type_name`).
    pub fn results_type(&self) -> &'static str {
        (self.results_type)()
    }

    /// Reads its settings under `ctx`, running their checks across fields, and keeps nothing:
    /// what the runner asks of every experiment before any computes, so that a setting one of
    /// them refuses stops the command before another has run.
    ///
    /// # Errors
    /// The refusal of the settings' reader or check, naming the parameter and its rule.
    pub fn check_settings(&self, ctx: &Context) -> Result<(), RunError> {
        (self.settings_of)(ctx).map(|_| ())
    }

    /// Its outcome under `ctx` if this process has already computed it (as the run of another
    /// experiment's results, [`Run::results_of`]): the stored data and the report drawn from
    /// them, computing nothing; `None` if it has not.
    ///
    /// # Errors
    /// Settings `ctx` refuses, or stored data that does not draw.
    pub fn computed_outcome(&self, ctx: &Context) -> Result<Option<Outcome>, RunError> {
        let settings = (self.settings_of)(ctx)?;
        match cached(self.id, ctx.seed(), &settings) {
            Some(data) => Ok(Some(Outcome {
                report: (self.render)(&data)?,
                data,
            })),
            None => Ok(None),
        }
    }
}

fn settings_of<E: Experiment>(ctx: &Context) -> Result<Value, RunError> {
    to_value(&E::Settings::read(ctx)?)
}

fn to_value<T: Serialize>(x: &T) -> Result<Value, RunError> {
    serde_json::to_value(x).map_err(|e| RunError::Internal(format!("results as JSON: {e}")))
}

fn run<E: Experiment>(ctx: &Context, engine: &TrialEngine) -> Result<Outcome, RunError> {
    let settings = E::Settings::read(ctx)?;
    let results = E::compute(&settings, &Run::new(ctx, engine))?;
    let report = E::report(&settings, &results)?;
    let settings = to_value(&settings)?;
    let data = json!({
        "experiment": E::ID,
        "seed": ctx.seed(),
        "settings": settings,
        "results": to_value(&results)?,
    });
    // A shard's results hold only its share of the trials: kept for no one else.
    if engine.mode() == TrialMode::Normal {
        remember(E::ID, ctx.seed(), &settings, &data);
    }
    Ok(Outcome { report, data })
}

/// The results this process has computed, by experiment, seed and settings: an experiment whose
/// results another asks for ([`Run::results_of`]) is computed once per process (the claims
/// ledger reads a dozen experiments' results, under several readings, that the same test run
/// or `run all` computes too). Results depend only on these three, so a hit is the same bits.
static COMPUTED: Mutex<BTreeMap<String, Value>> = Mutex::new(BTreeMap::new());

fn cache_key(id: &str, seed: u64, settings: &Value) -> String {
    format!("{id}\n{seed}\n{settings}")
}

fn remember(id: &str, seed: u64, settings: &Value, data: &Value) {
    COMPUTED
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .insert(cache_key(id, seed, settings), data.clone());
}

fn cached(id: &str, seed: u64, settings: &Value) -> Option<Value> {
    COMPUTED
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .get(&cache_key(id, seed, settings))
        .cloned()
}

/// Forgets every result this process has computed (benchmarks time the work itself).
pub fn forget_computed() {
    COMPUTED
        .lock()
        .unwrap_or_else(PoisonError::into_inner)
        .clear();
}

fn departures_of<E: Experiment>(data: &Value) -> Result<Departures, RunError> {
    let settings: E::Settings = stored::<E, _>(data, "settings")?;
    Ok(settings.departures())
}

/// Part `name` (`settings` or `results`) of experiment `E`'s stored data, read typed.
fn stored<E: Experiment, T: serde::de::DeserializeOwned>(
    data: &Value,
    name: &str,
) -> Result<T, RunError> {
    let part = data.get(name).cloned().ok_or_else(|| {
        RunError::bad(
            RESULTS_JSON,
            name,
            format!("is missing (`{}`'s stored data)", E::ID),
        )
    })?;
    serde_json::from_value(part).map_err(|e| RunError::bad(RESULTS_JSON, name, e.to_string()))
}

fn render<E: Experiment>(data: &Value) -> Result<Report, RunError> {
    let settings: E::Settings = stored::<E, _>(data, "settings")?;
    let results: E::Results = stored::<E, _>(data, "results")?;
    E::report(&settings, &results)
}

/// Registers experiment `$ty` (a type implementing [`Experiment`]) with `inventory`:
/// `registry::register!(Table3);`.
#[macro_export]
macro_rules! register {
    ($ty:ty) => {
        $crate::inventory::submit! { $crate::Entry::of::<$ty>() }
    };
}
