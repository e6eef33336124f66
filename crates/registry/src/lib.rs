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
//!         params: &[registry::Param { name: "samples", default: "1000", unit: "", help: "angles sampled" }],
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
mod engine;
mod error;
mod finite;
mod output;
mod progress;
mod table;
mod trials;

pub use context::{ConfigFile, Context, MAX_COUNT, MAX_TRIALS};
pub use engine::TrialMode;
pub use error::{DuplicateId, RunError};
pub use output::{Agreement, MAX_DATA_ROWS, OutputFile, Report, tidy, write_results};
pub use progress::{BatchProgress, Progress};
pub use table::{Table, fmt_f64, fmt_number};
pub use trials::{Batch, Records, Shard, ShardRecords, f64_bits, merge_records};

/// One parameter of an experiment, settable from the command line with `--set name=value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Param {
    /// Name used with `--set name=value`.
    pub name: &'static str,
    /// Value used when the command line does not set it (as it would be typed).
    pub default: &'static str,
    /// Unit of the value, e.g. "mm" or "deg"; empty when it has none.
    pub unit: &'static str,
    /// One line telling what the parameter does.
    pub help: &'static str,
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
    /// Parameters, settable with `--set name=value`.
    pub params: &'static [Param],
    /// `None`: the experiment takes no `--config FILE`; `Some(text)`: what the RON config file describes.
    pub config: Option<&'static str>,
    /// Runs the experiment.
    pub run: fn(&Context) -> Result<Report, RunError>,
}

inventory::collect!(Experiment);

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
        config: None,
        run: nothing,
    };
    static B: Experiment = Experiment {
        id: "b",
        title: "B",
        paper_item: "Figure 2",
        params: &[],
        config: None,
        run: nothing,
    };
    static A2: Experiment = Experiment {
        id: "a",
        title: "A again",
        paper_item: "Table 1",
        params: &[],
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
