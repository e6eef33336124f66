//! The replayed trials among the result folders (`replay-<id>-<cell>-<trial>/` and the listings
//! `replay-<id>-<cell>-failed/`, written by `cargo xtask replay`): linked from their
//! experiment's section and from its heatmaps' cells, never shown as experiments of their own.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use ::replay::ReplayedTrial;
use serde_json::Value;

use super::Provenance;
use crate::shared::Registry;

/// The settings a replay or a run was made under: the seed and every setting set, but
/// `trials` (which changes neither a trial's gears nor its events), sorted by name.
pub(super) type Settings = (u64, Vec<(String, String)>);

/// A replay's folder.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Replayed {
    /// Its name under the results folder.
    pub(super) folder: String,
    /// Where it is.
    pub(super) dir: PathBuf,
    /// Whether it has a `pair.html` (a replayed trial does, a listing does not).
    pub(super) page: bool,
    /// The settings its `run.json` records; `None` when there is none to read.
    pub(super) settings: Option<Settings>,
    /// The trial it replays and what that trial did, from its table's title (`None` for a
    /// listing, or a title that cannot be read).
    pub(super) trial: Option<ReplayedTrial>,
    /// What makes its trial the trial it is, whichever table counts it
    /// ([`replay::trial_key`]); `None` where it cannot be worked out.
    pub(super) key: Option<String>,
}

impl Replayed {
    /// Whether this is a replayed trial (with its page) that had `failure`.
    pub(super) fn had(&self, failure: TrialFailure) -> bool {
        self.page
            && self.trial.as_ref().is_some_and(|t| match failure {
                TrialFailure::Jam => t.jammed,
                TrialFailure::Disengagement => t.disengaged,
            })
    }
}

/// The failure a heatmap counts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum TrialFailure {
    /// Trials with at least one jam.
    Jam,
    /// Trials with at least one disengagement.
    Disengagement,
}

impl TrialFailure {
    /// The failure in words, as a listing of failed trials names it.
    pub(super) fn word(self) -> &'static str {
        match self {
            TrialFailure::Jam => "jam",
            TrialFailure::Disengagement => "disengagement",
        }
    }
}

/// Replayed trials and listings by experiment id.
pub(super) type Replays = BTreeMap<String, Vec<Replayed>>;

/// `(seed, overrides)` without `trials`, sorted: how [`Settings`] are compared.
fn normalised(seed: u64, overrides: &[(String, String)]) -> Settings {
    let mut o: Vec<(String, String)> = overrides
        .iter()
        .filter(|(k, _)| k != "trials")
        .map(|(k, v)| (k.clone(), v.trim().to_owned()))
        .collect();
    o.sort();
    (seed, o)
}

/// The settings of a run as its provenance records them (the default seed and none set when
/// it records none).
pub(super) fn settings_of(run: Option<&Provenance>) -> Settings {
    match run {
        Some(p) => normalised(p.seed, &p.overrides),
        None => normalised(crate::args::DEFAULT_SEED, &[]),
    }
}

/// The settings recorded in `dir/run.json`, if it can be read.
fn recorded(dir: &Path) -> Option<Settings> {
    let text = input_file::read_to_string(&dir.join(crate::provenance::RUN_JSON), 1 << 20).ok()?;
    let run: Value = serde_json::from_str(&text).ok()?;
    let seed = run["seed"].as_u64()?;
    let overrides: Vec<(String, String)> = match &run["overrides"] {
        Value::Object(m) => m
            .iter()
            .filter_map(|(k, v)| Some((k.clone(), v.as_str()?.to_owned())))
            .collect(),
        _ => Vec::new(),
    };
    Some(normalised(seed, &overrides))
}

/// The trial key ([`replay::trial_key`]) of cell `cell` of experiment `id` under
/// `settings`; `None` where the settings or the cell cannot be read.
pub(super) fn key_of(exps: &Registry, id: &str, cell: &str, settings: &Settings) -> Option<String> {
    let e = exps.get(id)?;
    let ctx = registry::Context::new(e, settings.0, 1, &settings.1, None).ok()?;
    ::replay::trial_key(&ctx, id, cell).ok()
}

/// The trial a replay's `tables.json` names in its first title.
fn replayed_trial(dir: &Path) -> Option<ReplayedTrial> {
    let text = input_file::read_to_string(&dir.join("tables.json"), 64 << 20).ok()?;
    let tables: Value = serde_json::from_str(&text).ok()?;
    ReplayedTrial::from_title(tables["tables"][0]["title"].as_str()?)
}

/// The replayed trials among the result folders, by the experiment they come from, and the
/// other folders.
pub(super) fn split_replays(
    exps: &Registry,
    found: Vec<(String, PathBuf)>,
) -> (Vec<(String, PathBuf)>, Replays) {
    let mut replays = Replays::new();
    let mut rest = Vec::new();
    for (name, path) in found {
        let from = name.strip_prefix("replay-").and_then(|r| {
            ::replay::REPLAYABLE
                .iter()
                .map(|(id, _)| *id)
                .find(|id| r.starts_with(&format!("{id}-")))
        });
        match from {
            Some(id) => {
                let page = path.join("pair.html").is_file();
                let settings = recorded(&path);
                let trial = if page { replayed_trial(&path) } else { None };
                let key = match (&trial, &settings) {
                    (Some(t), Some(s)) if t.experiment == id => key_of(exps, id, &t.cell, s),
                    _ => None,
                };
                replays.entry(id.to_owned()).or_default().push(Replayed {
                    folder: name,
                    dir: path,
                    page,
                    settings,
                    trial,
                    key,
                });
            }
            None => rest.push((name, path)),
        }
    }
    (rest, replays)
}

/// The failed trials a listing wrote (`failed-trials.csv`: `trial,jammed,disengaged`), each with
/// what it did (`jam`, `disengagement`, `jam and disengagement`); `None` when there is no such
/// file to read.
pub(super) fn failed_trials(dir: &Path) -> Option<Vec<(u64, &'static str)>> {
    let text = input_file::read_to_string(&dir.join(::replay::FAILED_TRIALS_CSV), 64 << 20).ok()?;
    let mut out = Vec::new();
    for line in text.lines().skip(1) {
        let mut f = line.split(',');
        let (Some(t), Some(j), Some(d)) = (f.next(), f.next(), f.next()) else {
            continue;
        };
        let Ok(t) = t.trim().parse::<u64>() else {
            continue;
        };
        let what = match (j.trim() == "true", d.trim() == "true") {
            (true, true) => "jam and disengagement",
            (true, false) => "jam",
            (false, true) => "disengagement",
            (false, false) => continue,
        };
        out.push((t, what));
    }
    Some(out)
}
