//! Trials the runner can shard across machines and replay: what [`Context::trials`] records.
//!
//! A run is split into `N` shards (`cargo xtask run <id> --shard K/N`). Shard `K` computes the
//! trials `t` of each batch with `t % N == K` and records their values, keyed by batch name and
//! trial index; `cargo xtask merge` checks the shards' records with [`merge_records`] and runs
//! the experiment once more with every value taken from them ([`Context::with_replay`]). As
//! every trial depends only on its inputs, the seed and its index, the merged report is the one
//! a single run gives, bit for bit.
//!
//! [`Context::trials`]: crate::Context::trials
//! [`Context::with_replay`]: crate::Context::with_replay

use std::collections::BTreeMap;
use std::fmt;

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::RunError;

/// One shard of a run: `index` of `count` (`K/N` on the command line).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Shard {
    index: u64,
    count: u64,
}

impl Shard {
    /// Shard `index` of `count`: `count >= 1` and `index < count`, else
    /// [`RunError::BadInput`] from `--shard`.
    pub fn new(index: u64, count: u64) -> Result<Shard, RunError> {
        if count == 0 {
            return Err(RunError::bad(
                "--shard",
                format!("{index}/{count}"),
                "N (the number of shards) must be at least 1",
            ));
        }
        if index >= count {
            return Err(RunError::bad(
                "--shard",
                format!("{index}/{count}"),
                format!(
                    "K must be from 0 to N-1 = {} (shards are numbered from 0)",
                    count - 1
                ),
            ));
        }
        Ok(Shard { index, count })
    }

    /// Parses `K/N` (e.g. `0/4`), as [`Shard::new`] checks it.
    pub fn parse(text: &str) -> Result<Shard, RunError> {
        let shape = || {
            RunError::bad(
                "--shard",
                text,
                "must be K/N with integers 0 <= K < N, e.g. 0/4",
            )
        };
        let (k, n) = text.trim().split_once('/').ok_or_else(shape)?;
        let k: u64 = k.trim().parse().map_err(|_| shape())?;
        let n: u64 = n.trim().parse().map_err(|_| shape())?;
        Shard::new(k, n)
    }

    /// `K`: which shard this is, from 0.
    pub fn index(self) -> u64 {
        self.index
    }

    /// `N`: how many shards the run is split into.
    pub fn count(self) -> u64 {
        self.count
    }

    /// Does this shard compute trial `t` (`t % N == K`)?
    pub fn owns(self, t: u64) -> bool {
        t % self.count == self.index
    }
}

impl fmt::Display for Shard {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The recorded values of one batch of trials.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Batch {
    /// How many trials the batch has (`n` of [`Context::trials`](crate::Context::trials)).
    pub trials: u64,
    /// Run whole by every shard ([`Context::trials_whole`](crate::Context::trials_whole)).
    pub whole: bool,
    /// Each recorded trial's value, by trial index.
    pub values: BTreeMap<u64, Value>,
}

/// Recorded batches by batch key.
pub type Records = BTreeMap<String, Batch>;

/// What one shard recorded, and where it came from (a file name, for messages).
#[derive(Debug, Clone, PartialEq)]
pub struct ShardRecords {
    /// Where the records came from, e.g. the partial file's path.
    pub source: String,
    /// Which shard recorded them.
    pub shard: Shard,
    /// The batches it recorded.
    pub records: Records,
}

/// Joins every shard's records into the records of the whole run, checking that they fit.
///
/// Rules, each broken one a [`RunError::BadInput`] naming the source and the rule:
/// - every shard has the same `N`, and every `K` from 0 to `N-1` is given exactly once;
/// - every shard recorded the same batches with the same trial counts (shards that ran
///   different batches took a decision from a sharded batch: that stage must use
///   [`Context::trials_whole`](crate::Context::trials_whole));
/// - a sharded batch of shard `K` holds exactly its trials `t < n` with `t % N == K`;
/// - a whole batch holds every trial, with the same values in every shard.
pub fn merge_records(parts: &[ShardRecords]) -> Result<Records, RunError> {
    let Some(first) = parts.first() else {
        return Err(RunError::bad(
            "merge",
            "shards",
            "no shard records to merge",
        ));
    };
    let by_index = shards_by_index(first, parts)?;
    let mut merged = Records::new();
    for (key, reference) in &first.records {
        merged.insert(
            key.clone(),
            Batch {
                trials: reference.trials,
                whole: reference.whole,
                values: BTreeMap::new(),
            },
        );
    }
    for p in by_index.values() {
        same_batches(first, p)?;
        for (key, batch) in &p.records {
            let into = merged
                .get_mut(key)
                .ok_or_else(|| RunError::Internal(format!("batch `{key}` vanished")))?;
            if batch.trials != into.trials || batch.whole != into.whole {
                return Err(RunError::bad(
                    &p.source,
                    format!("batch `{key}`"),
                    format!(
                        "has {} trials{}, but {} has {}{}: the shards disagree",
                        batch.trials,
                        if batch.whole { " (whole)" } else { "" },
                        first.source,
                        into.trials,
                        if into.whole { " (whole)" } else { "" }
                    ),
                ));
            }
            check_batch(p, key, batch)?;
            if batch.whole {
                if into.values.is_empty() {
                    into.values.clone_from(&batch.values);
                } else if into.values != batch.values {
                    return Err(RunError::bad(
                        &p.source,
                        format!("batch `{key}`"),
                        format!(
                            "is computed whole by every shard, but its values differ from {}'s: the shards did not run the same build or inputs",
                            first.source
                        ),
                    ));
                }
            } else {
                into.values
                    .extend(batch.values.iter().map(|(t, v)| (*t, v.clone())));
            }
        }
    }
    Ok(merged)
}

/// The shards of `parts` by index, refused unless they come from one split (that of `first`) and
/// every index is given exactly once.
fn shards_by_index<'a>(
    first: &ShardRecords,
    parts: &'a [ShardRecords],
) -> Result<BTreeMap<u64, &'a ShardRecords>, RunError> {
    let count = first.shard.count();
    let mut by_index: BTreeMap<u64, &ShardRecords> = BTreeMap::new();
    for p in parts {
        if p.shard.count() != count {
            return Err(RunError::bad(
                &p.source,
                format!("shard {}", p.shard),
                format!(
                    "splits the run into {} shards, but {} splits it into {count}: all shards must come from one split",
                    p.shard.count(),
                    first.source
                ),
            ));
        }
        if let Some(earlier) = by_index.insert(p.shard.index(), p) {
            return Err(RunError::bad(
                &p.source,
                format!("shard {}", p.shard),
                format!(
                    "is given twice (also {}): each shard must be given exactly once",
                    earlier.source
                ),
            ));
        }
    }
    let missing: Vec<String> = (0..count)
        .filter(|k| !by_index.contains_key(k))
        .map(|k| format!("{k}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(RunError::bad(
            "merge",
            format!("shard {}", missing.join(", ")),
            format!(
                "missing: every shard from 0/{count} to {}/{count} must be given exactly once",
                count - 1
            ),
        ));
    }

    Ok(by_index)
}

/// `p` recorded exactly the batches `first` did.
fn same_batches(first: &ShardRecords, p: &ShardRecords) -> Result<(), RunError> {
    // In the user's words: what to check, and what it means if the check passes.
    let hint = "the shards ran different batches of trials: run every shard with the same seed, --set values, config file and build; if they were, the experiment lets earlier shard results decide later batches, a bug to report";
    if let Some(key) = first.records.keys().find(|k| !p.records.contains_key(*k)) {
        return Err(RunError::bad(
            &p.source,
            format!("batch `{key}`"),
            format!("is missing here but recorded in {} ({hint})", first.source),
        ));
    }
    if let Some(key) = p.records.keys().find(|k| !first.records.contains_key(*k)) {
        return Err(RunError::bad(
            &p.source,
            format!("batch `{key}`"),
            format!("is recorded here but not in {} ({hint})", first.source),
        ));
    }
    Ok(())
}

/// A batch of shard `p` holds exactly the trials it owns (all of them if whole).
fn check_batch(p: &ShardRecords, key: &str, batch: &Batch) -> Result<(), RunError> {
    let owns = |t: u64| batch.whole || p.shard.owns(t);
    if let Some(t) = batch
        .values
        .keys()
        .find(|&&t| t >= batch.trials || !owns(t))
    {
        return Err(RunError::bad(
            &p.source,
            format!("batch `{key}` trial {t}"),
            format!(
                "does not belong to shard {} of a batch of {} trials",
                p.shard, batch.trials
            ),
        ));
    }
    let wanted = if batch.whole {
        batch.trials
    } else {
        owned_count(p.shard, batch.trials)
    };
    if batch.values.len() as u64 != wanted {
        let t = (0..batch.trials)
            .find(|&t| owns(t) && !batch.values.contains_key(&t))
            .unwrap_or(0);
        return Err(RunError::bad(
            &p.source,
            format!("batch `{key}` trial {t}"),
            format!(
                "is missing: shard {} must record every trial it owns",
                p.shard
            ),
        ));
    }
    Ok(())
}

/// How many of the trials `0..n` shard `s` owns.
fn owned_count(s: Shard, n: u64) -> u64 {
    if n > s.index() {
        (n - s.index()).div_ceil(s.count())
    } else {
        0
    }
}

/// Stores an `f64` as the 64 bits of its IEEE 754 encoding, for `#[serde(with = "registry::f64_bits")]`.
///
/// Recorded trial values go through JSON, which carries finite floats exactly but has no NaN or
/// infinity: a field that can hold one must be stored this way (a recorded NaN is otherwise
/// refused when it is recorded).
pub mod f64_bits {
    use serde::{Deserialize, Deserializer, Serializer};

    /// Writes `x` as `x.to_bits()`.
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_u64(x.to_bits())
    }

    /// Reads the bits written by [`serialize`].
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        u64::deserialize(d).map(f64::from_bits)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn shards_parse_and_refuse_bad_values() {
        let s = Shard::parse("1/3").unwrap();
        assert_eq!((s.index(), s.count()), (1, 3));
        assert_eq!(s.to_string(), "1/3");
        assert!(s.owns(4) && !s.owns(3));
        assert_eq!(Shard::parse(" 0 / 1 ").unwrap(), Shard::new(0, 1).unwrap());
        for bad in ["3/3", "0/0", "1", "a/2", "-1/2", "1/2/3", "", "/2"] {
            let e = Shard::parse(bad).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{bad}");
            assert!(e.to_string().starts_with("--shard: "), "{e}");
        }
        assert!(
            Shard::parse("3/3")
                .unwrap_err()
                .to_string()
                .contains("0 to N-1 = 2")
        );
    }

    #[test]
    fn owned_counts() {
        for n in 0..20 {
            for count in 1..5 {
                for index in 0..count {
                    let s = Shard::new(index, count).unwrap();
                    let direct = (0..n).filter(|&t| s.owns(t)).count() as u64;
                    assert_eq!(owned_count(s, n), direct, "{s} of {n}");
                }
            }
        }
    }

    fn part(k: u64, n: u64, trials: u64, whole: &[u64]) -> ShardRecords {
        let shard = Shard::new(k, n).unwrap();
        let mut records = Records::new();
        records.insert(
            "split".into(),
            Batch {
                trials,
                whole: false,
                values: (0..trials)
                    .filter(|&t| shard.owns(t))
                    .map(|t| (t, json!(t * 10)))
                    .collect(),
            },
        );
        records.insert(
            "whole".into(),
            Batch {
                trials: whole.len() as u64,
                whole: true,
                values: whole
                    .iter()
                    .enumerate()
                    .map(|(t, v)| (t as u64, json!(v)))
                    .collect(),
            },
        );
        ShardRecords {
            source: format!("p{k}.json"),
            shard,
            records,
        }
    }

    #[test]
    fn merge_joins_shards_in_any_order() {
        let merged = merge_records(&[
            part(2, 3, 7, &[1, 2]),
            part(0, 3, 7, &[1, 2]),
            part(1, 3, 7, &[1, 2]),
        ])
        .unwrap();
        let split = &merged["split"];
        assert_eq!(split.trials, 7);
        assert!(!split.whole);
        assert_eq!(
            split.values.values().cloned().collect::<Vec<_>>(),
            (0..7).map(|t| json!(t * 10)).collect::<Vec<_>>()
        );
        assert_eq!(merged["whole"].values.len(), 2);
        // One shard, and more shards than trials.
        assert_eq!(
            merge_records(&[part(0, 1, 3, &[])]).unwrap()["split"]
                .values
                .len(),
            3
        );
        let parts: Vec<_> = (0..5).map(|k| part(k, 5, 2, &[9])).collect();
        assert_eq!(merge_records(&parts).unwrap()["split"].values.len(), 2);
    }

    fn refused(parts: &[ShardRecords], words: &[&str]) {
        let e = merge_records(parts).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{e}");
        let text = e.to_string();
        for w in words {
            assert!(text.contains(w), "missing {w:?} in {text}");
        }
    }

    #[test]
    fn merge_refuses_what_does_not_fit() {
        refused(&[], &["no shard records"]);
        refused(
            &[part(0, 3, 7, &[]), part(2, 3, 7, &[])],
            &["shard 1/3", "missing"],
        );
        refused(
            &[part(0, 2, 7, &[]), part(1, 2, 7, &[]), part(1, 2, 7, &[])],
            &["p1.json", "shard 1/2", "given twice"],
        );
        refused(
            &[part(0, 2, 7, &[]), part(1, 3, 7, &[])],
            &["p1.json", "3 shards"],
        );
        refused(
            &[part(0, 2, 7, &[]), part(1, 2, 8, &[])],
            &["p1.json", "batch `split`", "8 trials"],
        );
        refused(
            &[part(0, 2, 7, &[1]), part(1, 2, 7, &[2])],
            &["p1.json", "batch `whole`", "differ"],
        );
        let mut lacking = part(1, 2, 7, &[]);
        lacking.records.remove("whole");
        refused(
            &[part(0, 2, 7, &[]), lacking],
            &[
                "p1.json",
                "batch `whole`",
                "missing here",
                "same seed, --set values",
            ],
        );
        let mut extra = part(1, 2, 7, &[]);
        extra.records.insert("more".into(), Batch::default());
        refused(
            &[part(0, 2, 7, &[]), extra],
            &["batch `more`", "not in p0.json"],
        );
        let mut gap = part(1, 2, 7, &[]);
        gap.records.get_mut("split").unwrap().values.remove(&3);
        refused(&[part(0, 2, 7, &[]), gap], &["trial 3", "is missing"]);
        let mut foreign = part(1, 2, 7, &[]);
        foreign
            .records
            .get_mut("split")
            .unwrap()
            .values
            .insert(2, json!(0));
        refused(
            &[part(0, 2, 7, &[]), foreign],
            &["trial 2", "does not belong"],
        );
    }

    #[derive(Serialize, Deserialize, PartialEq, Debug)]
    struct Bits(#[serde(with = "f64_bits")] f64);

    #[test]
    fn f64_bits_keeps_every_float() {
        for x in [
            f64::NAN,
            -f64::NAN,
            f64::INFINITY,
            -0.0,
            0.1,
            f64::MIN_POSITIVE / 3.0,
        ] {
            let text = serde_json::to_string(&Bits(x)).unwrap();
            let back: Bits = serde_json::from_str(&text).unwrap();
            assert_eq!(back.0.to_bits(), x.to_bits(), "{text}");
        }
    }
}
