//! Watching trial batches as they run: the hook behind the runner's progress bars.
//!
//! The registry knows nothing of terminals. A runner that wants progress bars gives the context
//! a [`Progress`] ([`crate::Context::with_progress`]); [`crate::Context::trials`] then asks it
//! for a [`BatchProgress`] when a batch starts and calls [`BatchProgress::done`] once per
//! finished trial, from whichever worker thread ran it. The hook only watches: it sees no trial
//! value and cannot change which trials run, their order or their results.

use std::fmt;
use std::sync::Arc;

/// Told when a batch of trials starts; hands out the handle its trials report to.
pub trait Progress: Send + Sync {
    /// A batch of `n` trials of experiment `experiment` starts; `batch` is its key and `index`
    /// its place among the run's batches (from 0). The handle is dropped when the batch ends.
    fn batch(&self, experiment: &str, batch: &str, index: usize, n: u64) -> Box<dyn BatchProgress>;
}

/// One running batch: told once per finished trial.
pub trait BatchProgress: Send + Sync {
    /// One more trial of the batch is done (called from worker threads, in no particular order).
    fn done(&self);
}

/// A [`Progress`] shared by a context and its clones.
#[derive(Clone)]
pub(crate) struct Hook(pub(crate) Arc<dyn Progress>);

impl fmt::Debug for Hook {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("Progress")
    }
}
