//! The trial engine behind [`crate::Context::trials`]: runs a batch of trials on the rayon pool,
//! or one shard of it (recording each value), or replays it from merged records; tells the
//! progress hook; refuses a batch key used twice.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Mutex, MutexGuard, PoisonError};
use std::time::Instant;

use rayon::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value as Json;

use crate::RunError;
use crate::progress::{BatchProgress, Hook};
use crate::streams::{Identity, Streams, TrialRng};
use crate::trials::{Batch, Records, Shard};

/// How [`crate::Context::trials`] runs its trials.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TrialMode {
    /// Every trial is computed (`cargo xtask run`).
    Normal,
    /// Only this shard's trials are computed and recorded; the others are `T::default()`, and
    /// the report is discarded (`cargo xtask run <id> --shard K/N`).
    Shard(Shard),
    /// Every trial's value is read from the merged records (`cargo xtask merge`).
    Replay,
}

/// Trial batches of one run: the keys asked for so far, and in shard mode what was recorded.
#[derive(Debug, Default)]
struct Ledger {
    /// Batch keys asked for, to refuse a key used twice.
    claimed: BTreeSet<String>,
    /// Shard mode: the recorded batches.
    recorded: Records,
}

/// Runs, records or replays the trial batches of one experiment run: what `study`'s trial loops
/// take ([`crate::Context::engine`]), with the run's seed, instead of the whole context.
#[derive(Debug)]
pub struct TrialEngine {
    /// The experiment, for messages and progress.
    pub(crate) id: &'static str,
    /// Seed for every random number generator of the run (`--seed`).
    pub(crate) seed: u64,
    pub(crate) mode: TrialMode,
    /// Replay mode: the merged records of every shard.
    pub(crate) replay: Records,
    ledger: Mutex<Ledger>,
    /// Told about every batch of trials (the runner's progress bars); never changes results.
    pub(crate) progress: Option<Hook>,
}

impl Clone for TrialEngine {
    /// A copy with the same settings and a copy of the batches claimed and recorded so far.
    fn clone(&self) -> Self {
        let ledger = self.ledger();
        TrialEngine {
            id: self.id,
            seed: self.seed,
            mode: self.mode,
            replay: self.replay.clone(),
            ledger: Mutex::new(Ledger {
                claimed: ledger.claimed.clone(),
                recorded: ledger.recorded.clone(),
            }),
            progress: self.progress.clone(),
        }
    }
}

impl TrialEngine {
    /// An engine in normal mode with nothing claimed.
    pub(crate) fn new(id: &'static str, seed: u64) -> Self {
        TrialEngine {
            id,
            seed,
            mode: TrialMode::Normal,
            replay: Records::new(),
            ledger: Mutex::new(Ledger::default()),
            progress: None,
        }
    }

    /// Seed for every random number generator of the run (`--seed`).
    pub fn seed(&self) -> u64 {
        self.seed
    }

    /// The run's random streams ([`Streams`]), for a study that hands the seed on.
    pub fn streams(&self) -> Streams {
        Streams::new(self.seed)
    }

    /// The generator of trial `trial` of the draws `identity` under the run's seed: the one
    /// scheme every study draws through (see [`crate::streams`]).
    pub fn stream(&self, identity: Identity, trial: u64) -> TrialRng {
        self.streams().stream(identity, trial)
    }

    /// How trials are run: normally, as one shard, or replayed from records.
    pub fn mode(&self) -> TrialMode {
        self.mode
    }

    /// Runs trials `0..n` of a batch: see [`crate::Context::trials`].
    pub fn trials<T, F>(&self, batch: &str, n: u64, f: F) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        self.batch(batch, n, false, f)
    }

    /// Runs a batch never sharded: see [`crate::Context::trials_whole`].
    pub fn trials_whole<T, F>(&self, batch: &str, n: u64, f: F) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        self.batch(batch, n, true, f)
    }

    /// The batches recorded so far in shard mode (empty in the other modes).
    pub(crate) fn recorded(&self) -> Records {
        self.ledger().recorded.clone()
    }

    /// Replay mode: the batches of the records that the run never asked for.
    pub(crate) fn unclaimed(&self) -> Vec<String> {
        let ledger = self.ledger();
        self.replay
            .keys()
            .filter(|k| !ledger.claimed.contains(*k))
            .cloned()
            .collect()
    }

    fn ledger(&self) -> MutexGuard<'_, Ledger> {
        // A panic while the lock was held cannot leave the ledger half-updated (each update is
        // one insert), so a poisoned lock is still usable.
        self.ledger.lock().unwrap_or_else(PoisonError::into_inner)
    }

    pub(crate) fn batch<T, F>(
        &self,
        batch: &str,
        n: u64,
        whole: bool,
        f: F,
    ) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        let index = {
            let mut ledger = self.ledger();
            if !ledger.claimed.insert(batch.to_owned()) {
                return Err(RunError::Internal(format!(
                    "experiment `{}` ran the trial batch `{batch}` twice: batch keys must be unique within a run",
                    self.id
                )));
            }
            ledger.claimed.len() - 1
        };
        tracing::debug!(
            experiment = self.id,
            index,
            trials = n,
            whole,
            mode = ?self.mode,
            "trial batch `{batch}`"
        );
        let start = Instant::now();
        let result = self.run_batch(batch, index, n, whole, &f);
        tracing::debug!(
            experiment = self.id,
            index,
            trials = n,
            seconds = start.elapsed().as_secs_f64(),
            ok = result.is_ok(),
            "trial batch done"
        );
        result
    }

    /// [`TrialEngine::batch`] after the key is claimed: runs, records or replays the trials.
    fn run_batch<T, F>(
        &self,
        batch: &str,
        index: usize,
        n: u64,
        whole: bool,
        f: &F,
    ) -> Result<Vec<T>, RunError>
    where
        T: Serialize + DeserializeOwned + Send + Clone + Default,
        F: Fn(u64) -> Result<T, RunError> + Sync + Send,
    {
        // Replayed values are read, not computed: nothing to watch.
        let watch: Option<Box<dyn BatchProgress>> = match (&self.progress, self.mode) {
            (Some(hook), TrialMode::Normal | TrialMode::Shard(_)) => {
                Some(hook.0.batch(self.id, batch, index, n))
            }
            _ => None,
        };
        // Runs trial `t` and tells the hook; the value is returned untouched.
        let tick = |t: u64| {
            let value = f(t);
            if let Some(w) = &watch {
                w.done();
            }
            value
        };
        match self.mode {
            TrialMode::Normal => (0..n).into_par_iter().map(tick).collect(),
            TrialMode::Shard(shard) => {
                let owns = |t: u64| whole || shard.owns(t);
                let done: Vec<Option<(T, Json)>> = (0..n)
                    .into_par_iter()
                    .map(|t| {
                        if !owns(t) {
                            if let Some(w) = &watch {
                                w.done();
                            }
                            return Ok(None);
                        }
                        let value = tick(t)?;
                        let json = encode(batch, t, &value)?;
                        Ok(Some((value, json)))
                    })
                    .collect::<Result<_, RunError>>()?;
                let mut values = BTreeMap::new();
                let mut out = Vec::with_capacity(done.len());
                for (t, d) in (0..n).zip(done) {
                    match d {
                        Some((value, json)) => {
                            values.insert(t, json);
                            out.push(value);
                        }
                        None => out.push(T::default()),
                    }
                }
                self.ledger().recorded.insert(
                    batch.to_owned(),
                    Batch {
                        trials: n,
                        whole,
                        values,
                    },
                );
                Ok(out)
            }
            TrialMode::Replay => self.replayed(batch, n, whole),
        }
    }

    /// The values of `batch` from the merged records.
    fn replayed<T: DeserializeOwned>(
        &self,
        batch: &str,
        n: u64,
        whole: bool,
    ) -> Result<Vec<T>, RunError> {
        let uncovered = |what: String| RunError::bad("merge", format!("batch `{batch}`"), what);
        let Some(rec) = self.replay.get(batch) else {
            return Err(uncovered(format!(
                "shards do not cover this batch of {n} trials: no shard recorded it (were the shards run with the same build and inputs?)"
            )));
        };
        if rec.trials != n || rec.whole != whole {
            return Err(uncovered(format!(
                "shards do not cover this batch: they recorded {} trials{}, the merge asks for {n}{}",
                rec.trials,
                if rec.whole { " (whole)" } else { "" },
                if whole { " (whole)" } else { "" }
            )));
        }
        (0..n)
            .map(|t| {
                let json = rec.values.get(&t).ok_or_else(|| {
                    RunError::bad(
                        "merge",
                        format!("batch `{batch}` trial {t}"),
                        format!("shards do not cover trial {t} of {n}"),
                    )
                })?;
                T::deserialize(json).map_err(|e| {
                    RunError::bad(
                        "merge",
                        format!("batch `{batch}` trial {t}"),
                        format!("the recorded value does not fit this build: {e}"),
                    )
                })
            })
            .collect()
    }
}

/// `value` as JSON, checked to come back as it went: no non-finite float, and deserializing it
/// and serializing the result again gives the same JSON.
fn encode<T: Serialize + DeserializeOwned>(
    batch: &str,
    t: u64,
    value: &T,
) -> Result<Json, RunError> {
    let fail = |what: String| {
        RunError::Internal(format!(
            "trial {t} of batch `{batch}` cannot be recorded: {what}"
        ))
    };
    crate::finite::check(value).map_err(|e| {
        fail(format!(
            "it {e}, which JSON cannot carry (store such a field with registry::f64_bits)"
        ))
    })?;
    let json = serde_json::to_value(value).map_err(|e| fail(e.to_string()))?;
    let back = T::deserialize(&json).map_err(|e| fail(format!("it does not read back: {e}")))?;
    let again = serde_json::to_value(&back).map_err(|e| fail(e.to_string()))?;
    if again != json {
        return Err(fail(
            "it does not read back to the same value (a field skipped or renamed one way only?)"
                .into(),
        ));
    }
    Ok(json)
}
