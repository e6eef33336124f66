//! What the runner hands an experiment: seed, thread count, parameters and config file, and
//! the way to run trials ([`Context::trials`]) that the runner can shard and replay.

use std::path::{Path, PathBuf};
use std::str::FromStr;
use std::sync::Arc;

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::engine::{TrialEngine, TrialMode};
use crate::progress::{Hook, Progress};
use crate::trials::{Records, Shard};
use crate::{Param, RunError};

/// The most trials a `trials` parameter may ask for: 10^6 (per cell, case or input, as the
/// experiment counts them). By convention an experiment's `trials` parameter is its number of
/// Monte-Carlo trials; [`Context::new`] refuses a larger value (or one that is not a
/// non-negative integer) before anything runs, naming this limit. The paper's largest count is
/// 200. Experiments hold a small record per trial of every cell in memory (table3: 60 cells, some
/// 24 bytes each), so 10^6 keeps even the largest grids within a few gigabytes, and is already
/// far beyond what one machine computes in a day; split a larger study into runs with different
/// seeds.
pub const MAX_TRIALS: u64 = 1_000_000;

/// The largest count [`Context::get`] accepts as a `usize`: 10^7. Integer parameters read that way are
/// counts that size the work and its memory (samples, pitches, teeth, trials...); a larger one
/// is refused, naming this limit, rather than attempted.
pub const MAX_COUNT: usize = 10_000_000;

/// The fewest samples of a Theoretical Difference curve a `samples` parameter may ask for: σ,
/// Dm and P of fewer points say nothing about the pointer (two points have σ 0, and a ratio of
/// two such σ is NaN). [`MIN_SAMPLES_WHY`] says so in `help` and in a refusal.
pub const MIN_SAMPLES: u64 = 100;

/// Why [`MIN_SAMPLES`]: shown after the range.
pub const MIN_SAMPLES_WHY: &str = "sigma, Dm and P need the curve sampled through its teeth";

/// A count of trials whose results are given with a 95 % interval: parameter `trials` with
/// `default` and `help`, at least two.
pub const fn interval_trials(default: &'static str, help: &'static str) -> Param {
    Param {
        name: "trials",
        default,
        unit: "",
        help,
        kind: crate::Kind::count(2, MAX_TRIALS, "an interval needs two trials"),
        reading: false,
        clearance: false,
        recorded: true,
    }
}

/// A count of Theoretical-Difference samples: parameter `samples` with `default` and `help`, at
/// least [`MIN_SAMPLES`].
pub const fn samples(default: &'static str, help: &'static str) -> Param {
    Param {
        name: "samples",
        default,
        unit: "",
        help,
        kind: crate::Kind::count(MIN_SAMPLES, MAX_COUNT as u64, MIN_SAMPLES_WHY),
        reading: false,
        clearance: false,
        recorded: false,
    }
}

/// The fewest samples per tooth engagement a `samples_per_engagement` parameter may ask for:
/// one sample per engagement sees every engagement at the same phase, so its σ misses the error
/// within it.
pub const MIN_PER_ENGAGEMENT: u64 = 2;

/// Why [`MIN_PER_ENGAGEMENT`]: shown after the range.
pub const MIN_PER_ENGAGEMENT_WHY: &str =
    "fewer cannot follow the pointer's error within a tooth engagement";

/// Samples a curve needs per tooth engagement it spans, for [`samples_cover`].
pub const SAMPLES_PER_TOOTH: usize = 4;

/// Checks that `samples` points of a curve spanning `engagements` tooth engagements (set by the
/// parameter `of`) give each at least [`SAMPLES_PER_TOOTH`]; the error names the parameter
/// `name` and the rule, e.g. `--set: samples: must be at least 400 for 100 pitches (4 per tooth
/// engagement)`.
///
/// # Errors
/// [`RunError::BadInput`] as above.
pub fn samples_cover(
    name: &str,
    samples: usize,
    engagements: usize,
    of: &str,
) -> Result<(), RunError> {
    let need = engagements.saturating_mul(SAMPLES_PER_TOOTH);
    if samples < need {
        return Err(RunError::bad(
            "--set",
            name,
            format!(
                "must be at least {need} for {of} = {engagements} ({SAMPLES_PER_TOOTH} per tooth engagement; got {samples})"
            ),
        ));
    }
    Ok(())
}

/// A config file given with `--config FILE`, already read.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConfigFile {
    /// The path as given on the command line; use it in error messages.
    pub path: PathBuf,
    /// The file's contents.
    pub text: String,
}

/// One declared parameter and its value.
#[derive(Debug, Clone)]
struct Value {
    name: &'static str,
    /// The declaration it was made from, so that a typed read ([`Context::get`]) of another
    /// declaration with the same name is caught rather than read.
    decl: &'static Param,
    value: String,
    /// Set with `--set` (a parse failure is the user's), rather than the default (a bug).
    overridden: bool,
}

/// What the runner hands an experiment: the parameter side (seed, threads, parameters, config
/// file), read here, and the trial engine behind [`Context::trials`] (`engine.rs`).
///
/// An experiment reads a parameter by its declaration (`ctx.get(&CLEARANCE)`, checked against
/// the one it declares); no reader takes a name, so a literal key does not compile:
///
/// ```compile_fail
/// const NAME: &str = "clearance";
/// fn clearance(ctx: &registry::Context) -> f64 {
///     ctx.f64(NAME).unwrap_or(40.0)
/// }
/// ```
///
/// ```compile_fail
/// const NAME: &str = "clearance";
/// fn clearance(ctx: &registry::Context) -> String {
///     ctx.param(NAME).unwrap_or_default().to_owned()
/// }
/// ```
///
/// ```
/// fn clearance(ctx: &registry::Context, p: &registry::Param) -> f64 {
///     ctx.get(p).unwrap_or(40.0)
/// }
/// ```
#[derive(Debug, Clone)]
pub struct Context {
    id: &'static str,
    seed: u64,
    threads: usize,
    params: Vec<Value>,
    config: Option<ConfigFile>,
    /// Each parameter's default, in declaration order.
    defaults: Vec<&'static str>,
    /// Runs, records or replays the trial batches.
    engine: TrialEngine,
    /// The folder the run's results go to (`--out`), where [`crate::Run::results_of`] looks
    /// for another experiment's stored results before computing them.
    results_dir: Option<PathBuf>,
}

/// What a context is built from: an experiment's id, its declared parameters and the
/// configuration file it takes (the registered [`crate::Entry`] says these; a context needs no
/// more of it, which keeps the context below the experiment that reads it).
pub trait Declared {
    /// The experiment's id.
    fn id(&self) -> &'static str;
    /// Every parameter the experiment declares, in its settings' order.
    fn params(&self) -> Vec<&'static Param>;
    /// What its `--config` file holds, or None if it takes none.
    fn config(&self) -> Option<&'static str>;
}

impl<T: Declared + ?Sized> Declared for &T {
    fn id(&self) -> &'static str {
        (**self).id()
    }

    fn params(&self) -> Vec<&'static Param> {
        (**self).params()
    }

    fn config(&self) -> Option<&'static str> {
        (**self).config()
    }
}

impl Context {
    /// Builds a context: params start at the experiment's defaults, then `overrides`
    /// (from `--set key=value`, later ones winning) replace them.
    ///
    /// Errors ([`RunError::BadInput`]): an unknown key (naming it and listing the known ones);
    /// `threads == 0`; a config file for an experiment that takes none; a value its parameter's
    /// kind refuses (a count of trials above [`MAX_TRIALS`] among them).
    pub fn new(
        exp: &impl Declared,
        seed: u64,
        threads: usize,
        overrides: &[(String, String)],
        config: Option<ConfigFile>,
    ) -> Result<Context, RunError> {
        if threads == 0 {
            return Err(RunError::bad("--threads", "threads", "must be at least 1"));
        }
        let mut params: Vec<Value> = exp
            .params()
            .into_iter()
            .map(|p| Value {
                name: p.name,
                decl: p,
                value: p.default.to_owned(),
                overridden: false,
            })
            .collect();
        for (key, value) in overrides {
            match params.iter_mut().find(|p| p.name == key) {
                Some(p) => {
                    p.value.clone_from(value);
                    p.overridden = true;
                }
                None => {
                    let known = if exp.params().is_empty() {
                        format!("experiment `{}` has no parameters", exp.id())
                    } else {
                        let names: Vec<&str> = exp.params().into_iter().map(|p| p.name).collect();
                        format!(
                            "unknown parameter of experiment `{}`; known: {}",
                            exp.id(),
                            names.join(", ")
                        )
                    };
                    return Err(RunError::bad("--set", key.as_str(), known));
                }
            }
        }
        // Every value against its parameter's kind, before anything runs.
        for (v, p) in params.iter().zip(exp.params()) {
            if let Err(rule) = p.kind.check(&v.value) {
                return Err(if v.overridden {
                    RunError::bad(
                        "--set",
                        v.name,
                        format!("{rule} (got `{}`)", v.value.trim()),
                    )
                } else {
                    RunError::Internal(format!(
                        "experiment `{}`: default of parameter `{}` ({:?}) {rule}",
                        exp.id(),
                        v.name,
                        v.value
                    ))
                });
            }
        }
        if let (Some(file), None) = (&config, exp.config()) {
            return Err(RunError::bad(
                "--config",
                file.path.display().to_string(),
                format!("experiment `{}` takes no --config", exp.id()),
            ));
        }
        Ok(Context {
            id: exp.id(),
            seed,
            threads,
            params,
            config,
            defaults: exp.params().into_iter().map(|p| p.default).collect(),
            engine: TrialEngine::new(exp.id(), seed),
            results_dir: None,
        })
    }

    /// This context with its results going to folder `dir` (`--out`): another experiment's
    /// results stored there are read rather than computed again ([`crate::Run::results_of`]).
    #[must_use]
    pub fn with_results_dir(mut self, dir: PathBuf) -> Context {
        self.results_dir = Some(dir);
        self
    }

    /// The folder the run's results go to, if the runner said.
    pub fn results_dir(&self) -> Option<&Path> {
        self.results_dir.as_deref()
    }

    /// This context with `progress` told about every batch of trials as it runs (see
    /// [`crate::Progress`]). Results do not depend on it.
    #[must_use]
    pub fn with_progress(mut self, progress: Arc<dyn Progress>) -> Context {
        self.engine.progress = Some(Hook(progress));
        self
    }

    /// The parameters set (with `--set` or a shorthand) to something other than their default,
    /// as (name, value), in declaration order: how this run's inputs differ from the defaults,
    /// which are the paper's.
    pub fn changed(&self) -> Vec<(&'static str, &str)> {
        self.params
            .iter()
            .zip(&self.defaults)
            .filter(|(p, default)| p.overridden && p.value.trim() != default.trim())
            .map(|(p, _)| (p.name, p.value.as_str()))
            .collect()
    }

    /// [`Context::changed`] without the readings of the paper ([`Param::reading`]): the inputs in
    /// which this run departs from the paper's, so that the paper's numbers beside ours come from
    /// other inputs and are not compared with them.
    pub fn departures(&self) -> Vec<(&'static str, &str)> {
        let mut changed = self.changed();
        changed.retain(|(k, _)| !self.params.iter().any(|p| p.name == *k && p.decl.reading));
        changed
    }

    /// The parameters given (with `--set` or a shorthand), whatever their value, as (name,
    /// value), in declaration order: what the user typed, where [`Context::changed`] is what
    /// differs from the defaults.
    pub fn given(&self) -> Vec<(&'static str, &str)> {
        self.params
            .iter()
            .filter(|p| p.overridden)
            .map(|p| (p.name, p.value.as_str()))
            .collect()
    }

    /// Every declared parameter with its value as typed (or its default), in declaration
    /// order: how the runner, which knows no experiment's declarations, reads what a run was
    /// given. An experiment reads its own parameters by declaration ([`Context::get`],
    /// [`Context::text`]).
    pub fn values(&self) -> impl Iterator<Item = (&'static Param, &str)> + '_ {
        self.params.iter().map(|v| (v.decl, v.value.as_str()))
    }

    /// This context in shard mode: [`Context::trials`] computes and records only `shard`'s
    /// trials ([`Context::recorded`] returns them after the run).
    #[must_use]
    pub fn with_shard(mut self, shard: Shard) -> Context {
        self.engine.mode = TrialMode::Shard(shard);
        self
    }

    /// This context in replay mode: [`Context::trials`] and [`Context::trials_whole`] take every
    /// value from `records` (the shards' records joined by [`crate::merge_records`]).
    #[must_use]
    pub fn with_replay(mut self, records: Records) -> Context {
        self.engine.mode = TrialMode::Replay;
        self.engine.replay = records;
        self
    }

    /// How trials are run: normally, as one shard, or replayed from records.
    pub fn trial_mode(&self) -> TrialMode {
        self.engine.mode
    }

    /// Seed for every random number generator of the run (`--seed`).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The trial engine with the run's seed: what `study`'s trial loops take.
    pub fn engine(&self) -> &TrialEngine {
        &self.engine
    }

    /// Number of threads of the pool the experiment runs in (`--threads`).
    pub fn threads(&self) -> usize {
        self.threads
    }

    /// The value of parameter `p` as type `T` (a number, a count, a switch): how experiments and
    /// `study` read their settings, named by the parameter's declaration rather than a string.
    /// A declaration the experiment does not hold - another parameter that only shares the name
    /// (fig5's own `clearance` is not the gearing's) - is a bug ([`RunError::Internal`]).
    pub fn get<T: FromParam>(&self, p: &Param) -> Result<T, RunError> {
        self.declared(p)?;
        T::from_param(self, p)
    }

    /// The text of parameter `p` as typed (a name, a list, a file), by its declaration as for
    /// [`Context::get`].
    pub fn text(&self, p: &Param) -> Result<&str, RunError> {
        Ok(self.declared(p)?.value.as_str())
    }

    /// Whether the experiment declares `p` itself (the same declaration, not just its name).
    pub fn holds(&self, p: &Param) -> bool {
        self.params.iter().any(|v| v.decl == p)
    }

    /// The names of every declared parameter, in declaration order.
    pub fn names(&self) -> Vec<&'static str> {
        self.params.iter().map(|v| v.name).collect()
    }

    fn declared(&self, p: &Param) -> Result<&Value, RunError> {
        let v = self.value(p.name)?;
        if v.decl != p {
            return Err(RunError::Internal(format!(
                "experiment `{}` read parameter `{}` by a declaration other than the one it declares",
                self.id, p.name
            )));
        }
        Ok(v)
    }

    fn value(&self, name: &str) -> Result<&Value, RunError> {
        self.params.iter().find(|p| p.name == name).ok_or_else(|| {
            RunError::Internal(format!(
                "experiment `{}` asked for parameter `{name}`, which it does not declare",
                self.id
            ))
        })
    }

    /// Parses a param; a value set with `--set` that does not parse is
    /// `RunError::BadInput { source: "--set", field: name, rule }`; a default that does not
    /// parse is a bug ([`RunError::Internal`]).
    fn parse<T: FromStr>(&self, name: &str, rule: &str) -> Result<T, RunError> {
        let v = self.value(name)?;
        v.value
            .trim()
            .parse::<T>()
            .map_err(|_| self.reject(v, rule))
    }

    fn reject(&self, v: &Value, rule: &str) -> RunError {
        if v.overridden {
            RunError::bad("--set", v.name, format!("{rule} (got `{}`)", v.value))
        } else {
            RunError::Internal(format!(
                "experiment `{}`: default of parameter `{}` ({:?}) {rule}",
                self.id, v.name, v.value
            ))
        }
    }

    /// A param as a finite number (`NaN` and infinities are refused).
    fn finite(&self, name: &str) -> Result<f64, RunError> {
        let rule = "must be a finite number";
        let x: f64 = self.parse(name, rule)?;
        if x.is_finite() {
            Ok(x)
        } else {
            Err(self.reject(self.value(name)?, rule))
        }
    }

    /// A param as a non-negative integer count, at most [`MAX_COUNT`].
    fn usize(&self, name: &str) -> Result<usize, RunError> {
        let n: usize = self.parse(
            name,
            &format!("must be a non-negative integer, at most {MAX_COUNT} (the limit on counts)"),
        )?;
        if n > MAX_COUNT {
            return Err(self.reject(
                self.value(name)?,
                &format!("must be at most {MAX_COUNT}, the limit on counts"),
            ));
        }
        Ok(n)
    }

    /// A param as a non-negative 64-bit integer.
    fn u64(&self, name: &str) -> Result<u64, RunError> {
        self.parse(name, "must be a non-negative integer")
    }

    /// The config file given with `--config`, if any.
    pub fn config(&self) -> Option<&ConfigFile> {
        self.config.as_ref()
    }

    /// Runs trials `0..n` of a batch: `f(t)` for each `t`, in parallel on the caller's rayon
    /// pool, collected in trial order. This is how an experiment runs its Monte-Carlo trials,
    /// so that the runner can split them across machines and join them again.
    ///
    /// `f(t)` must depend only on the experiment's inputs, the seed and `t` (draw its random
    /// numbers from [`TrialEngine::stream`]`(identity, t)`), never on other
    /// trials or on the thread it runs on.
    ///
    /// `batch` names the batch. It must be unique within the run (a key asked for twice is a
    /// [`RunError::Internal`]) and should spell out everything that determines its trials: the
    /// cell's parameters (mesh, case, clearance...), not just a counter, so that records of
    /// different inputs can never be mistaken for each other.
    ///
    /// By [`TrialMode`]:
    /// - normal: every trial is computed;
    /// - shard `K/N`: only trials with `t % N == K` are computed; each value is recorded (see
    ///   [`Context::recorded`]) and the others are `T::default()`, so that the experiment can
    ///   finish (its report is discarded). The rest of the experiment must therefore not fail
    ///   or panic on default values, and nothing it decides - which later batches it runs, or
    ///   their keys or sizes - may depend on this batch's values: use
    ///   [`Context::trials_whole`] for a stage whose results feed the parameters of later
    ///   stages;
    /// - replay: every value is read from the merged records; a batch or trial they do not
    ///   hold is a [`RunError::BadInput`] ("shards do not cover ..."), never a default.
    ///
    /// Recorded values go through JSON: finite floats round-trip bit for bit, but NaN and the
    /// infinities cannot be carried - a field that can hold one must be stored with
    /// [`crate::f64_bits`]. A value that holds one, or that does not deserialize back to the
    /// same JSON, is refused when it is recorded ([`RunError::Internal`]).
    ///
    /// Errors: the first error of `f` (in normal and shard mode), or the errors above.
    pub fn trials<T, F>(&self, batch: &str, n: u64, f: F) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        self.engine.batch(batch, n, false, f)
    }

    /// Like [`Context::trials`], but never sharded: every shard computes (and records) the
    /// whole batch, and a replay takes it from the records (checked identical across shards).
    ///
    /// Use it for a stage whose results decide what runs next - which cells a later stage
    /// runs, their parameters, their batch keys or sizes (e.g. rows of one table chosen from
    /// another's counts) - so that every shard and the merge run the same later batches. Its
    /// cost is paid by every shard, so keep such stages small; everything else uses
    /// [`Context::trials`].
    pub fn trials_whole<T, F>(&self, batch: &str, n: u64, f: F) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        self.engine.batch(batch, n, true, f)
    }

    /// The batches recorded so far in shard mode (empty in the other modes).
    pub fn recorded(&self) -> Records {
        self.engine.recorded()
    }

    /// Replay mode: the batches of the records that the run never asked for (a merge whose
    /// records came from a different build or different inputs).
    pub fn unclaimed(&self) -> Vec<String> {
        self.engine.unclaimed()
    }
}

/// A type a parameter's value is read as with [`Context::get`]; the parameter's [`crate::Kind`]
/// has already checked it fits.
pub trait FromParam: Sized {
    /// The value of the declared parameter `p`.
    fn from_param(ctx: &Context, p: &Param) -> Result<Self, RunError>;
}

impl FromParam for f64 {
    fn from_param(ctx: &Context, p: &Param) -> Result<f64, RunError> {
        ctx.finite(p.name)
    }
}

impl FromParam for usize {
    fn from_param(ctx: &Context, p: &Param) -> Result<usize, RunError> {
        ctx.usize(p.name)
    }
}

impl FromParam for u64 {
    fn from_param(ctx: &Context, p: &Param) -> Result<u64, RunError> {
        ctx.u64(p.name)
    }
}

impl FromParam for String {
    fn from_param(ctx: &Context, p: &Param) -> Result<String, RunError> {
        Ok(ctx.text(p)?.trim().to_owned())
    }
}

impl FromParam for bool {
    fn from_param(ctx: &Context, p: &Param) -> Result<bool, RunError> {
        ctx.parse(p.name, "must be true or false")
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use crate::{Entry, Kind, Param};
    // The parameters here are `Kind::Text`: these tests read values the kinds would refuse, to
    // check the reading functions themselves (kinds are tested in lib.rs).

    const TEETH: Param = Param::new("teeth", "24", "number of teeth", Kind::Text);
    const MODULE: Param = Param::new("module", "0.5", "tooth size", Kind::Text).unit("mm");
    const BROKEN: Param = Param::new(
        "broken",
        "lots",
        "a default that does not parse",
        Kind::Text,
    );

    /// Three text parameters, read here by name to test the readers themselves.
    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, crate::Settings)]
    struct Three {
        #[param(TEETH)]
        teeth: String,
        #[param(MODULE)]
        module: String,
        #[param(BROKEN)]
        broken: String,
    }

    crate::test_experiment!(ExpT, "t", "Figure 0", Three, config: Some("a mesh"));
    crate::test_experiment!(ExpBare, "bare", "Table 0", crate::NoSettings);
    static EXP: Entry = Entry::of::<ExpT>();
    static BARE: Entry = Entry::of::<ExpBare>();

    fn set(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect()
    }

    fn field_of(e: &RunError) -> (&str, &str, &str) {
        match e {
            RunError::BadInput {
                source,
                field,
                rule,
            } => (source, field, rule),
            RunError::Internal(m) => panic!("expected BadInput, got Internal({m})"),
        }
    }

    #[test]
    fn defaults_then_overrides() {
        let ctx = Context::new(&EXP, 7, 3, &[], None).unwrap();
        assert_eq!(ctx.seed(), 7);
        assert_eq!(ctx.threads(), 3);
        assert_eq!(
            ctx.values().find(|(p, _)| p.name == "teeth").unwrap().1,
            "24"
        );
        assert_eq!(ctx.usize("teeth").unwrap(), 24);
        assert_eq!(ctx.u64("teeth").unwrap(), 24);
        assert!((ctx.finite("module").unwrap() - 0.5).abs() < 1e-15);
        assert!(ctx.config().is_none());

        let ctx =
            Context::new(&EXP, 7, 1, &set(&[("teeth", "30"), ("teeth", "31")]), None).unwrap();
        assert_eq!(ctx.usize("teeth").unwrap(), 31, "later --set wins");
        assert!((ctx.finite("module").unwrap() - 0.5).abs() < 1e-15);
    }

    #[test]
    fn unknown_key_is_named_with_known_ones() {
        let e = Context::new(&EXP, 0, 1, &set(&[("nonsense", "1")]), None).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let (source, field, rule) = field_of(&e);
        assert_eq!(source, "--set");
        assert_eq!(field, "nonsense");
        assert!(rule.contains("teeth, module, broken"), "{rule}");

        let e = Context::new(&BARE, 0, 1, &set(&[("x", "1")]), None).unwrap_err();
        assert!(e.to_string().contains("has no parameters"), "{e}");
    }

    #[test]
    fn parse_errors_are_bad_input() {
        let ctx = Context::new(
            &EXP,
            0,
            1,
            &set(&[("teeth", "-3"), ("module", "NaN")]),
            None,
        )
        .unwrap();
        let e = ctx.usize("teeth").unwrap_err();
        assert_eq!(field_of(&e).0, "--set");
        assert_eq!(field_of(&e).1, "teeth");
        assert!(!e.to_string().contains('\n'));
        assert!(ctx.u64("teeth").is_err());
        let e = ctx.finite("module").unwrap_err();
        assert_eq!(field_of(&e).1, "module");
        assert!(field_of(&e).2.contains("finite"));

        let ctx = Context::new(&EXP, 0, 1, &set(&[("module", "inf")]), None).unwrap();
        assert!(ctx.finite("module").is_err());
        let ctx = Context::new(&EXP, 0, 1, &set(&[("module", "abc")]), None).unwrap();
        assert_eq!(ctx.finite("module").unwrap_err().exit_code(), 2);
    }

    #[test]
    fn bad_default_and_undeclared_name_are_internal() {
        let ctx = Context::new(&EXP, 0, 1, &[], None).unwrap();
        assert!(matches!(ctx.usize("broken"), Err(RunError::Internal(_))));
        assert!(ctx.values().all(|(p, _)| p.name != "nope"));
        assert!(matches!(ctx.finite("nope"), Err(RunError::Internal(_))));
    }

    const TRIALS: Param = Param::new("trials", "30", "trials", Kind::count(0, MAX_TRIALS, ""));
    const SAMPLES: Param = Param::new("samples", "100", "samples", Kind::Text);

    /// A `trials` and a `samples` parameter, as text.
    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, crate::Settings)]
    struct Counted {
        #[param(TRIALS)]
        trials: String,
        #[param(SAMPLES)]
        samples: String,
    }

    crate::test_experiment!(ExpCounted, "counted", "Table 0", Counted);
    static COUNTED: Entry = Entry::of::<ExpCounted>();

    #[test]
    fn trials_are_limited_before_anything_runs() {
        let ok = Context::new(&COUNTED, 0, 1, &set(&[("trials", "1000000")]), None).unwrap();
        assert_eq!(ok.u64("trials").unwrap(), MAX_TRIALS);
        for (value, words) in [
            ("1000001", "at most 1000000, the limit on trials"),
            ("18446744073709551615", "the limit on trials"),
            ("99999999999999999999999", "non-negative integer"),
            ("-1", "non-negative integer"),
            ("1e3", "non-negative integer"),
        ] {
            let e = Context::new(&COUNTED, 0, 1, &set(&[("trials", value)]), None).unwrap_err();
            let (source, field, rule) = field_of(&e);
            assert_eq!((source, field), ("--set", "trials"), "{value}");
            assert!(rule.contains(words), "{value}: {rule}");
        }
        // A text parameter is checked where it is read, not up front.
        assert!(Context::new(&EXP, 0, 1, &set(&[("teeth", "99999999999")]), None).is_ok());
    }

    #[test]
    fn counts_are_limited() {
        let ctx = Context::new(&COUNTED, 0, 1, &set(&[("samples", "10000001")]), None).unwrap();
        let e = ctx.usize("samples").unwrap_err();
        assert_eq!(field_of(&e).1, "samples");
        assert!(field_of(&e).2.contains("at most 10000000"), "{e}");
        let ctx = Context::new(&COUNTED, 0, 1, &set(&[("samples", "10000000")]), None).unwrap();
        assert_eq!(ctx.usize("samples").unwrap(), MAX_COUNT);
    }

    #[test]
    fn declares_names_the_declared_parameters() {
        let ctx = Context::new(&COUNTED, 0, 1, &[], None).unwrap();
        let declares = |name: &str| ctx.values().any(|(p, _)| p.name == name);
        assert!(declares("trials") && declares("samples"));
        assert!(!declares("teeth"));
    }

    #[test]
    fn zero_threads_and_unwanted_config_are_refused() {
        assert_eq!(
            Context::new(&EXP, 0, 0, &[], None).unwrap_err().exit_code(),
            2
        );
        let file = ConfigFile {
            path: "mesh.ron".into(),
            text: "()".into(),
        };
        let e = Context::new(&BARE, 0, 1, &[], Some(file.clone())).unwrap_err();
        assert!(e.to_string().contains("takes no --config"), "{e}");
        let ctx = Context::new(&EXP, 0, 1, &[], Some(file.clone())).unwrap();
        assert_eq!(ctx.config(), Some(&file));
    }
}
