//! The replayed trials among the result folders (`replay-<id>-<cell>-<trial>/` and the listings
//! `replay-<id>-<cell>-failed/`, written by `cargo xtask replay`): linked from their
//! experiment's section and from its heatmaps' cells, never shown as experiments of their own.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::Provenance;

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

/// The replayed trials among the result folders, by the experiment they come from, and the
/// other folders.
pub(super) fn split_replays(found: Vec<(String, PathBuf)>) -> (Vec<(String, PathBuf)>, Replays) {
    let mut replays = Replays::new();
    let mut rest = Vec::new();
    for (name, path) in found {
        let from = name.strip_prefix("replay-").and_then(|r| {
            experiments::replay::REPLAYABLE
                .iter()
                .map(|(id, _)| *id)
                .find(|id| r.starts_with(&format!("{id}-")))
        });
        match from {
            Some(id) => {
                let page = path.join("pair.html").is_file();
                let settings = recorded(&path);
                replays.entry(id.to_owned()).or_default().push(Replayed {
                    folder: name,
                    dir: path,
                    page,
                    settings,
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
    let text =
        input_file::read_to_string(&dir.join(experiments::replay::FAILED_TRIALS_CSV), 64 << 20)
            .ok()?;
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
