//! Experiment registry: experiments join with `inventory`, the runner reads them as a sorted map.
//!
//! An experiment is a type implementing [`Experiment`] - typed [`Settings`] in, typed results
//! out, a [`Report`] drawn from them - registered once with [`register!`]:
//!
//! ```ignore
//! struct Fig2;
//! impl registry::Experiment for Fig2 {
//!     const ID: &'static str = "fig2";
//!     const TITLE: &'static str = "Transmission error of a triangular-tooth pair";
//!     const PAPER_ITEM: &'static str = "Figure 2 (section 2)";
//!     const PLACE: registry::Place = registry::Place::Paper(10);
//!     type Settings = Settings;
//!     type Results = Results;
//!     fn compute(s: &Settings, run: &registry::Run) -> Result<Results, registry::RunError> { ... }
//!     fn report(s: &Settings, r: &Results) -> Result<registry::Report, registry::RunError> { ... }
//! }
//! registry::register!(Fig2);
//! ```
//!
//! The runner (`cargo xtask`) looks experiments up with [`experiments`], builds a [`Context`]
//! from the command line (every value checked against its parameter's kind), calls
//! [`Entry::run`] (settings read once, results computed, the report drawn from them), prints
//! [`Report::text`] and stores the tables and the results with [`write_results`].
//!
//! Experiments run their Monte-Carlo trials with [`Context::trials`] (or
//! [`Context::trials_whole`]), so that the runner can split a run into shards
//! (`cargo xtask run <id> --shard K/N`, [`Context::with_shard`]), join the shards' records
//! ([`merge_records`]) and replay the experiment from them (`cargo xtask merge`,
//! [`Context::with_replay`]) with the same results, bit for bit.

use std::collections::BTreeMap;

// `#[derive(Settings)]` names `::registry`, also inside this crate.
extern crate self as registry;

pub use inventory;

mod context;
mod csv_file;
mod engine;
mod error;
mod experiment;
mod finite;
mod lock;
mod output;
mod progress;
mod report;
mod settings;
pub mod streams;
mod table;
mod trials;
mod values;

pub use context::{
    ConfigFile, Context, Declared, FromParam, MAX_COUNT, MAX_TRIALS, MIN_PER_ENGAGEMENT,
    MIN_PER_ENGAGEMENT_WHY, MIN_SAMPLES, MIN_SAMPLES_WHY, SAMPLES_PER_TOOTH, interval_trials,
    samples, samples_cover,
};
pub use csv_file::{Csv, csv_line};
pub use engine::{TrialEngine, TrialMode};
pub use error::RunError;
pub use experiment::{
    Entry, Experiment, Outcome, Place, RESULTS_JSON, Run, Source, forget_computed,
};
pub use lock::{lock_path, lock_writing, release_locks};
pub use output::{
    Agreement, DEPARTURE, FileKind, MAX_ANGLE_DEG, MAX_DATA_ROWS, OutputFile, RECOGNISED_BYTES,
    Report, WriteError, abandon_writes, check_replace, read_one_version, results_replaceable,
    stopping, tidy, write_file, write_results,
};
pub use progress::{BatchProgress, Progress};
pub use settings::{NoSettings, ParamValue, Settings, changed_from_default};
pub use settings_derive::Settings;
pub use streams::{Identity, Streams, TrialRng, fnv1a64};
// Shared with crates below `registry` (`train`), and kept here for every crate above it.
pub use stdx::{fmt_f64, fmt_number};
pub use table::{Table, terminal_text};
pub use trials::{Batch, Records, Shard, ShardRecords, f64_bits, merge_records};
pub use values::{ValueError, Values};

/// One parameter of an experiment, settable from the command line with `--set name=value`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Param {
    /// Name used with `--set name=value`.
    pub name: &'static str,
    /// Value used when the command line does not set it (as it would be typed).
    pub default: &'static str,
    /// Unit of the value, e.g. "mm" or "deg"; empty when it has none.
    pub unit: &'static str,
    /// One line telling what the parameter does.
    pub help: &'static str,
    /// What values it takes: checked by [`Context::new`] before anything runs, so that an
    /// experiment reads a value already known to fit.
    pub kind: Kind,
    /// A reading of the paper rather than an input of it: it chooses how the paper is read, not
    /// what is simulated (the event rule, which gear drives, where a trial's counting ends, the
    /// paper's own E. max row). A run that changes only readings still runs on the paper's
    /// inputs and is compared with it ([`Settings::departures`]).
    pub reading: bool,
    /// A clearance G (or a list of them) in % of the tooth height h, where a value below 1 is
    /// more likely a fraction typed for a percentage (the runner warns); not a step or margin
    /// between clearances, which are differences.
    pub clearance: bool,
    /// Recorded with every run's results whatever its value (what the numbers depend on beyond
    /// counts: the gearing, the hypothesis, the rule, G, h, trials); every other parameter is
    /// recorded where it departs from its default.
    pub recorded: bool,
}

impl Param {
    /// A parameter with no unit: `name`, its `default` (as it would be typed), one line of
    /// `help` and the values it takes; [`Param::unit`] adds a unit. One line where a plugin
    /// declares one of its own, e.g.
    /// `Param::new("teeth", "50", "teeth of both gears", Kind::count(3, 500, ""))`.
    pub const fn new(
        name: &'static str,
        default: &'static str,
        help: &'static str,
        kind: Kind,
    ) -> Param {
        Param {
            name,
            default,
            unit: "",
            help,
            kind,
            reading: false,
            clearance: false,
            recorded: false,
        }
    }

    /// The same parameter with `unit`, e.g. "mm" or "% of h".
    pub const fn unit(self, unit: &'static str) -> Param {
        Param { unit, ..self }
    }

    /// The same parameter as a reading of the paper ([`Param::reading`]).
    pub const fn reading(self) -> Param {
        Param {
            reading: true,
            ..self
        }
    }

    /// Whether it counts trials: a count bounded by [`MAX_TRIALS`], the limit on trials.
    pub fn counts_trials(&self) -> bool {
        matches!(self.kind, Kind::Count { max, .. } if max == MAX_TRIALS)
    }

    /// The same parameter as a clearance in % of h ([`Param::clearance`]).
    pub const fn a_clearance(self) -> Param {
        Param {
            clearance: true,
            ..self
        }
    }

    /// The same parameter recorded with every run whatever its value ([`Param::recorded`]).
    pub const fn recorded(self) -> Param {
        Param {
            recorded: true,
            ..self
        }
    }
}

/// Declares parameters, each on one line as its author wrote it:
///
/// ```
/// use registry::Param;
/// registry::params! {
///     /// `step`: driver angle between samples.
///     const STEP = Param::new("step", "0.01", "driver angle between samples", registry::Kind::positive(10.0, "degrees")).unit("deg");
/// }
/// ```
///
/// expands to `const STEP: Param = ...;`. An experiment's parameters are a table - a name, a
/// default, a help text, a kind - and read best as one: rustfmt, which leaves a macro's body as
/// written, would otherwise spread each over seven lines of the same shape in every plugin.
#[macro_export]
macro_rules! params {
    ($($(#[$meta:meta])* $vis:vis const $name:ident = $param:expr;)*) => {
        $($(#[$meta])* $vis const $name: $crate::Param = $param;)*
    };
}

/// What values a parameter takes. [`Context::new`] checks the default and any `--set` value
/// against it, so that a refused value names the flag, the value and the range before anything
/// runs, and experiments do not each write the same check.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Kind {
    /// Text: a name, a list or a file, read and checked where it is used (a gearing, a
    /// hypothesis, an event rule, a list of cases).
    Text,
    /// A finite number from `min` to `max` (both included; an infinite bound is no bound);
    /// `why` (may be empty) says in a few words what the range protects.
    Number {
        /// Smallest value allowed.
        min: f64,
        /// Largest value allowed.
        max: f64,
        /// Why, shown after the range when a value falls outside it.
        why: &'static str,
    },
    /// A finite number above 0 and at most `max` (an infinite `max` is no bound): a length, a
    /// step, a clearance; `why` as for [`Kind::Number`].
    Positive {
        /// Largest value allowed.
        max: f64,
        /// Why, or the unit, shown after the range when a value falls outside it.
        why: &'static str,
    },
    /// A whole number from `min` to `max` (both included); `why` as for [`Kind::Number`].
    Count {
        /// Smallest value allowed.
        min: u64,
        /// Largest value allowed.
        max: u64,
        /// Why, shown after the range when a value falls outside it.
        why: &'static str,
    },
    /// `true` or `false`.
    Switch,
    /// One of these words.
    Choice(&'static [&'static str]),
}

impl Kind {
    /// A number with no range beyond being finite.
    pub const ANY_NUMBER: Kind = Kind::Number {
        min: f64::NEG_INFINITY,
        max: f64::INFINITY,
        why: "",
    };

    /// [`Kind::Count`] from `min` to `max`; `why` may be empty.
    pub const fn count(min: u64, max: u64, why: &'static str) -> Kind {
        Kind::Count { min, max, why }
    }

    /// [`Kind::Number`] from `min` to `max`; `why` may be empty.
    pub const fn number(min: f64, max: f64, why: &'static str) -> Kind {
        Kind::Number { min, max, why }
    }

    /// [`Kind::Positive`] up to `max`; `why` may be empty.
    pub const fn positive(max: f64, why: &'static str) -> Kind {
        Kind::Positive { max, why }
    }

    /// Checks `value` (as typed); the error is the rule broken, e.g. "must be at least 1".
    pub fn check(&self, value: &str) -> Result<(), String> {
        let value = value.trim();
        let because = |rule: String, why: &str| {
            if why.is_empty() {
                rule
            } else {
                format!("{rule} ({why})")
            }
        };
        match *self {
            Kind::Text => Ok(()),
            Kind::Number { min, max, why } => {
                let x: f64 = value
                    .parse()
                    .ok()
                    .filter(|x: &f64| x.is_finite())
                    .ok_or_else(|| "must be a finite number".to_string())?;
                if x >= min && x <= max {
                    return Ok(());
                }
                let rule = match (min.is_finite(), max.is_finite()) {
                    (true, true) => format!("must be between {min} and {max}"),
                    (true, false) => format!("must be at least {min}"),
                    _ => format!("must be at most {max}"),
                };
                Err(because(rule, why))
            }
            Kind::Positive { max, why } => {
                let x: f64 = value
                    .parse()
                    .ok()
                    .filter(|x: &f64| x.is_finite())
                    .ok_or_else(|| "must be a finite number".to_string())?;
                if x > 0.0 && x <= max {
                    return Ok(());
                }
                let rule = if max.is_finite() {
                    format!("must be greater than 0 and at most {max}")
                } else {
                    "must be greater than 0".to_string()
                };
                Err(because(rule, why))
            }
            Kind::Count { min, max, why } => {
                let limit = if max as usize == MAX_COUNT {
                    ", the limit on counts"
                } else if max == MAX_TRIALS {
                    ", the limit on trials"
                } else {
                    ""
                };
                // Not a whole number, or one beyond 64 bits (`1e300`): the range says what is.
                let n: u64 = value.parse().map_err(|_| {
                    because(
                        format!("must be a non-negative integer, from {min} to {max}{limit}"),
                        why,
                    )
                })?;
                if n < min {
                    Err(because(format!("must be at least {min}"), why))
                } else if n > max {
                    Err(because(format!("must be at most {max}{limit}"), why))
                } else {
                    Ok(())
                }
            }
            Kind::Switch => match value {
                "true" | "false" => Ok(()),
                _ => Err("must be true or false".into()),
            },
            Kind::Choice(words) => {
                if words.contains(&value) {
                    Ok(())
                } else {
                    Err(format!("must be one of {}", words.join(", ")))
                }
            }
        }
    }

    /// The values it takes, in words, for `cargo xtask help` (empty for text).
    pub fn describe(&self) -> String {
        match *self {
            Kind::Text => String::new(),
            Kind::Number { min, max, .. } => match (min.is_finite(), max.is_finite()) {
                (true, true) => format!("{min} to {max}"),
                (true, false) => format!("at least {min}"),
                (false, true) => format!("at most {max}"),
                (false, false) => "a number".into(),
            },
            Kind::Positive { max, .. } if max.is_finite() => format!("above 0, at most {max}"),
            Kind::Positive { .. } => "above 0".into(),
            Kind::Count { min, max, .. } => format!("integer {min} to {max}"),
            Kind::Switch => "true or false".into(),
            Kind::Choice(words) => words.join(" | "),
        }
    }
}

inventory::collect!(Entry);

/// A test experiment that computes nothing: `test_experiment!(Name, "id", "paper item", Settings)`
/// (and `, title: "..."`, `, config: Some("what the file holds")`), for tests of the registry
/// and the runner.
#[doc(hidden)]
#[macro_export]
macro_rules! test_experiment {
    ($name:ident, $id:literal, $item:literal, $settings:ty $(, config: $config:expr)? $(,)?) => {
        $crate::test_experiment!($name, $id, $item, $settings, title: $id $(, config: $config)?);
    };
    ($name:ident, $id:literal, $item:literal, $settings:ty, title: $title:literal $(, config: $config:expr)? $(,)?) => {
        struct $name;
        impl $crate::Experiment for $name {
            const ID: &'static str = $id;
            const TITLE: &'static str = $title;
            const PAPER_ITEM: &'static str = $item;
            const PLACE: $crate::Place = $crate::Place::Beyond(u32::MAX);
            $(const CONFIG: Option<&'static str> = $config;)?
            type Settings = $settings;
            type Results = ();
            fn compute(_: &$settings, _: &$crate::Run) -> Result<(), $crate::RunError> {
                Ok(())
            }
            fn report(_: &$settings, _: &()) -> Result<$crate::Report, $crate::RunError> {
                Ok($crate::Report::default())
            }
        }
    };
}

/// All registered experiments sorted by id; a duplicate id is an error naming it.
pub fn experiments() -> Result<BTreeMap<&'static str, &'static Entry>, stdx::Duplicate> {
    collect(inventory::iter::<Entry>.into_iter())
}

/// Sorts `items` by id, refusing a duplicate id.
fn collect(
    items: impl Iterator<Item = &'static Entry>,
) -> Result<BTreeMap<&'static str, &'static Entry>, stdx::Duplicate> {
    stdx::by_name("experiment id", items, |e| e.id)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    crate::test_experiment!(ExpA, "a", "Figure 1", NoSettings);
    crate::test_experiment!(ExpB, "b", "Figure 2", NoSettings);
    crate::test_experiment!(ExpA2, "a", "Table 1", NoSettings);
    static A: Entry = Entry::of::<ExpA>();
    static B: Entry = Entry::of::<ExpB>();
    static A2: Entry = Entry::of::<ExpA2>();

    #[test]
    fn collect_sorts_by_id() {
        let map = collect([&B, &A].into_iter()).unwrap();
        assert_eq!(map.keys().copied().collect::<Vec<_>>(), ["a", "b"]);
    }

    #[test]
    fn collect_refuses_duplicate_id() {
        let err = collect([&A, &B, &A2].into_iter()).unwrap_err();
        assert_eq!(err.name, "a");
        assert_eq!(err.to_string(), "experiment id `a` is registered twice");
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod kind_tests {
    use super::*;

    #[test]
    fn every_kind_says_the_rule_it_breaks() {
        let count = Kind::Count {
            min: 2,
            max: 10,
            why: "an interval needs two trials",
        };
        assert_eq!(count.check(" 2 "), Ok(()));
        assert_eq!(count.check("10"), Ok(()));
        assert_eq!(
            count.check("1").unwrap_err(),
            "must be at least 2 (an interval needs two trials)"
        );
        assert_eq!(
            count.check("11").unwrap_err(),
            "must be at most 10 (an interval needs two trials)"
        );
        assert_eq!(
            count.check("-1").unwrap_err(),
            "must be a non-negative integer, from 2 to 10 (an interval needs two trials)"
        );
        let trials = Kind::count(2, MAX_TRIALS, "");
        assert_eq!(
            trials.check("1e300").unwrap_err(),
            "must be a non-negative integer, from 2 to 1000000, the limit on trials"
        );
        let counts = Kind::Count {
            min: 0,
            max: MAX_COUNT as u64,
            why: "",
        };
        assert_eq!(
            counts.check("10000001").unwrap_err(),
            "must be at most 10000000, the limit on counts"
        );
        let split = Kind::Number {
            min: 0.0,
            max: 1.0,
            why: "",
        };
        assert_eq!(split.check("0"), Ok(()));
        assert_eq!(split.check("1.5").unwrap_err(), "must be between 0 and 1");
        assert_eq!(split.check("NaN").unwrap_err(), "must be a finite number");
        assert_eq!(split.check("inf").unwrap_err(), "must be a finite number");
        let from = Kind::Number {
            min: 0.0,
            max: f64::INFINITY,
            why: "",
        };
        assert_eq!(from.check("-0.1").unwrap_err(), "must be at least 0");
        let g = Kind::Positive {
            max: 100.0,
            why: "% of h",
        };
        assert_eq!(g.check("100"), Ok(()));
        assert_eq!(
            g.check("0").unwrap_err(),
            "must be greater than 0 and at most 100 (% of h)"
        );
        assert_eq!(
            Kind::Positive {
                max: f64::INFINITY,
                why: ""
            }
            .check("-1")
            .unwrap_err(),
            "must be greater than 0"
        );
        assert_eq!(
            Kind::Switch.check("yes").unwrap_err(),
            "must be true or false"
        );
        assert_eq!(
            Kind::Choice(&["derived", "paper"])
                .check("both")
                .unwrap_err(),
            "must be one of derived, paper"
        );
        assert_eq!(Kind::Text.check("anything"), Ok(()));
        assert_eq!(Kind::ANY_NUMBER.check("-1e300"), Ok(()));
    }

    const CLEARANCE: Param = Param::new(
        "clearance",
        "40",
        "clearance",
        Kind::positive(100.0, "% of h"),
    )
    .unit("% of h");
    const SPLIT: Param = Param::new("split", "2", "split", Kind::number(0.0, 1.0, ""));

    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, Settings)]
    struct Ranged {
        #[param(CLEARANCE)]
        clearance: f64,
    }

    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, Settings)]
    struct BadDefault {
        #[param(SPLIT)]
        split: f64,
    }

    crate::test_experiment!(RangedExp, "ranged", "Table 0", Ranged);
    crate::test_experiment!(BadDefaultExp, "bad-default", "Table 0", BadDefault);
    static RANGED: Entry = Entry::of::<RangedExp>();
    static BAD_DEFAULT: Entry = Entry::of::<BadDefaultExp>();

    #[test]
    fn a_context_refuses_a_value_outside_its_kind_before_anything_runs() {
        let set = |v: &str| vec![("clearance".to_string(), v.to_string())];
        assert!(Context::new(&RANGED, 1, 1, &set("70"), None).is_ok());
        let e = Context::new(&RANGED, 1, 1, &set("120"), None).unwrap_err();
        assert_eq!(
            e.to_string(),
            "--set: clearance: must be greater than 0 and at most 100 (% of h) (got `120`)"
        );
        // A default outside its own range is a bug, not the user's.
        let e = Context::new(&BAD_DEFAULT, 1, 1, &[], None).unwrap_err();
        assert!(matches!(e, RunError::Internal(_)), "{e}");
    }
}
