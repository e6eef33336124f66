//! Experiment registry: experiments join with `inventory`, the runner reads them as a sorted map.
//!
//! An experiment crate registers each experiment once:
//!
//! ```ignore
//! registry::inventory::submit! {
//!     registry::Experiment {
//!         id: "fig2",
//!         title: "Transmission error of a triangular-tooth pair",
//!         paper_item: "Figure 2 (section 2)",
//!         params: &[registry::Param { name: "samples", default: "1000", unit: "", help: "angles sampled",
//!             kind: registry::Kind::count(2, 1_000_000, "") }],
//!         groups: &[],
//!         config: None,
//!         run: fig2,
//!     }
//! }
//! ```
//!
//! The runner (`cargo xtask`) looks experiments up with [`experiments`], builds a [`Context`]
//! from the command line, calls [`Experiment::run`], prints [`Report::text`] and stores the
//! results with [`write_results`].
//!
//! Experiments run their Monte-Carlo trials with [`Context::trials`] (or
//! [`Context::trials_whole`]), so that the runner can split a run into shards
//! (`cargo xtask run <id> --shard K/N`, [`Context::with_shard`]), join the shards' records
//! ([`merge_records`]) and replay the experiment from them (`cargo xtask merge`,
//! [`Context::with_replay`]) with the same results, bit for bit.

use std::collections::BTreeMap;

pub use inventory;

mod context;
mod csv_file;
mod engine;
mod error;
mod finite;
mod lock;
mod output;
mod progress;
mod table;
mod trials;
mod values;

pub use context::{
    ConfigFile, Context, FromParam, MAX_COUNT, MAX_TRIALS, MIN_PER_ENGAGEMENT,
    MIN_PER_ENGAGEMENT_WHY, MIN_SAMPLES, MIN_SAMPLES_WHY, READINGS, SAMPLES_PER_TOOTH,
    interval_trials, samples, samples_cover,
};
pub use csv_file::{Csv, csv_line};
pub use engine::{TrialEngine, TrialMode};
pub use error::{DuplicateId, RunError};
pub use lock::{lock_path, lock_writing, release_locks};
pub use output::{
    Agreement, FileKind, MAX_ANGLE_DEG, MAX_DATA_ROWS, OutputFile, RECOGNISED_BYTES, Report,
    WriteError, abandon_writes, check_replace, read_one_version, results_replaceable, stopping,
    tidy, write_file, write_results,
};
pub use progress::{BatchProgress, Progress};
pub use table::{Table, fmt_f64, fmt_number, terminal_text};
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
        }
    }

    /// The same parameter with `unit`, e.g. "mm" or "% of h".
    pub const fn unit(self, unit: &'static str) -> Param {
        Param { unit, ..self }
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
                    let limit = if max as usize == MAX_COUNT {
                        ", the limit on counts"
                    } else {
                        ""
                    };
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

/// A registered experiment: what it reproduces, what it accepts, and the function that runs it.
#[derive(Debug)]
pub struct Experiment {
    /// Short unique id used on the command line, e.g. "fig2".
    pub id: &'static str,
    /// One-line title.
    pub title: &'static str,
    /// The item of the paper it reproduces, e.g. "Figure 2 (section 2)".
    pub paper_item: &'static str,
    /// Its own parameters, settable with `--set name=value`.
    pub params: &'static [Param],
    /// Setting groups it shares with other experiments (a gearing with h and G, an error
    /// hypothesis, an event rule, a grid...), declared once where the group is read; settable
    /// like its own parameters, listed after them.
    pub groups: &'static [&'static [Param]],
    /// `None`: the experiment takes no `--config FILE`; `Some(text)`: what the RON config file describes.
    pub config: Option<&'static str>,
    /// Runs the experiment.
    pub run: fn(&Context) -> Result<Report, RunError>,
}

inventory::collect!(Experiment);

impl Experiment {
    /// Every parameter: its own, then those of its setting groups, in declaration order.
    pub fn all_params(&self) -> impl Iterator<Item = &'static Param> + Clone {
        self.params
            .iter()
            .chain(self.groups.iter().flat_map(|g| g.iter()))
    }
}

/// All registered experiments sorted by id; a duplicate id is an error naming it.
pub fn experiments() -> Result<BTreeMap<&'static str, &'static Experiment>, DuplicateId> {
    collect(inventory::iter::<Experiment>.into_iter())
}

/// Sorts `items` by id, refusing a duplicate id.
fn collect(
    items: impl Iterator<Item = &'static Experiment>,
) -> Result<BTreeMap<&'static str, &'static Experiment>, DuplicateId> {
    let mut map = BTreeMap::new();
    for exp in items {
        if map.insert(exp.id, exp).is_some() {
            return Err(DuplicateId(exp.id));
        }
    }
    Ok(map)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    fn nothing(_: &Context) -> Result<Report, RunError> {
        Ok(Report::default())
    }

    static A: Experiment = Experiment {
        id: "a",
        title: "A",
        paper_item: "Figure 1",
        params: &[],
        groups: &[],
        config: None,
        run: nothing,
    };
    static B: Experiment = Experiment {
        id: "b",
        title: "B",
        paper_item: "Figure 2",
        params: &[],
        groups: &[],
        config: None,
        run: nothing,
    };
    static A2: Experiment = Experiment {
        id: "a",
        title: "A again",
        paper_item: "Table 1",
        params: &[],
        groups: &[],
        config: None,
        run: nothing,
    };

    #[test]
    fn collect_sorts_by_id() {
        let map = collect([&B, &A].into_iter()).unwrap();
        assert_eq!(map.keys().copied().collect::<Vec<_>>(), ["a", "b"]);
    }

    #[test]
    fn collect_refuses_duplicate_id() {
        let err = collect([&A, &B, &A2].into_iter()).unwrap_err();
        assert_eq!(err.0, "a");
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

    fn nothing(_: &Context) -> Result<Report, RunError> {
        Ok(Report::default())
    }

    static RANGED: Experiment = Experiment {
        id: "ranged",
        title: "a ranged parameter",
        paper_item: "Table 0",
        params: &[Param {
            name: "clearance",
            default: "40",
            unit: "% of h",
            help: "clearance",
            kind: Kind::positive(100.0, "% of h"),
        }],
        groups: &[],
        config: None,
        run: nothing,
    };

    static BAD_DEFAULT: Experiment = Experiment {
        id: "bad-default",
        title: "a default outside its range",
        paper_item: "Table 0",
        params: &[Param {
            name: "split",
            default: "2",
            unit: "",
            help: "split",
            kind: Kind::number(0.0, 1.0, ""),
        }],
        groups: &[],
        config: None,
        run: nothing,
    };

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
