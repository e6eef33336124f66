//! `cargo xtask replay <experiment> <cell> [<trial>]`: one trial of a per-mesh jam table rebuilt
//! and rerun (its events, and `pair.ron` to rerun it with `run pair`), or the cell's failed trials
//! listed (see the `replay` crate).

use registry::Context;

use crate::args::ReplayArgs;
use crate::failure::Failure;
use crate::plan::lookup;
use crate::progress::note;
use crate::shared::{default_out, print};

/// Characters kept in a folder name; any other becomes `-`.
fn plain(text: &str) -> String {
    text.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect()
}

/// The one setting left out of the folder's name: the number of trials changes neither a
/// trial's gears nor its events (a trial's stream depends on its cell, the seed and its index),
/// so `--trials 12` replays the trial the table of 12 trials counted, into the same folder.
const SAME_TRIALS: &str = "trials";

/// The longest folder name a replay gives itself; longer settings are named by a hash.
const MAX_FOLDER: usize = 120;

/// The folder of a replay at the defaults: `replay-table3-B-m3-e3-17` (`-failed` for a listing).
fn base(a: &ReplayArgs) -> String {
    let trial = a
        .trial
        .map_or_else(|| "failed".to_owned(), |t| t.to_string());
    format!("replay-{}-{}-{trial}", a.id, plain(&a.cell))
}

/// What names a replay's settings in a folder name: every setting that differs from the
/// defaults (but [`SAME_TRIALS`]), sorted by name, and a seed other than the default
/// (`clearance-50-seed-7`); empty at the defaults. Settings longer than [`MAX_FOLDER`] allows
/// are named by the first 12 hex digits of their SHA-256.
fn suffix(seed: u64, changed: &[(&str, &str)]) -> String {
    let mut named: Vec<(&str, String)> = changed
        .iter()
        .filter(|(k, _)| *k != SAME_TRIALS)
        .map(|&(k, v)| (k, plain(v.trim())))
        .collect();
    named.sort();
    let mut settings: Vec<String> = named.into_iter().map(|(k, v)| format!("{k}-{v}")).collect();
    if seed != crate::args::DEFAULT_SEED {
        settings.push(format!("seed-{seed}"));
    }
    let joined = settings.join("-");
    if joined.len() + 40 <= MAX_FOLDER {
        return joined;
    }
    let hashed = crate::provenance::sha256(settings.join("\n").as_bytes());
    format!("settings-{}", &hashed[..12])
}

/// The folder name of the replay `a` under settings `changed`: [`base`], then `-` and
/// [`suffix`] unless the settings are the defaults
/// (`replay-table3-B-m3-e3-17-clearance-50-seed-7`).
fn folder(a: &ReplayArgs, changed: &[(&str, &str)]) -> String {
    match suffix(a.seed, changed) {
        s if s.is_empty() => base(a),
        s => format!("{}-{s}", base(a)),
    }
}

/// The [`suffix`] of the replay whose results are in `dir`, from its `run.json` (`None` when
/// there is none to read: no folder, or one written before replays recorded their settings).
fn recorded_suffix(e: &registry::Entry, dir: &std::path::Path) -> Option<String> {
    let text = input_file::read_to_string(&dir.join(crate::provenance::RUN_JSON), 1 << 20).ok()?;
    let run: serde_json::Value = serde_json::from_str(&text).ok()?;
    let seed = run["seed"].as_u64()?;
    let overrides = run["overrides"].as_object()?;
    let changed: Vec<(&str, &str)> = overrides
        .iter()
        .filter_map(|(k, v)| Some((k.as_str(), v.as_str()?)))
        .filter(|(k, v)| {
            e.all_params()
                .find(|p| p.name == *k)
                .is_some_and(|p| p.default.trim() != v.trim())
        })
        .collect();
    Some(suffix(seed, &changed))
}

/// Where replay `a` (its settings' suffix `mine`) writes in `out`, and the replay of other
/// settings to move out of the way first: a replay of one cell under other settings never
/// overwrites another's results. A replay at the defaults owns [`base`] (a replay of other
/// settings found there moves to its own name, [`folder`]); a replay of other settings takes
/// [`base`] when it is free or holds the same settings' replay, and its own name otherwise.
fn placed(
    e: &registry::Entry,
    a: &ReplayArgs,
    changed: &[(&str, &str)],
    out: &std::path::Path,
) -> (String, Option<(String, String)>) {
    let mine = suffix(a.seed, changed);
    let base = base(a);
    let here = out.join(&base);
    let there = recorded_suffix(e, &here);
    if mine.is_empty() {
        return match there {
            Some(s) if !s.is_empty() => (base.clone(), Some((base.clone(), format!("{base}-{s}")))),
            _ => (base, None),
        };
    }
    match there {
        _ if !here.exists() => (base, None),
        Some(s) if s == mine => (base, None),
        _ => (folder(a, changed), None),
    }
}

/// Runs `replay`: prints the report and writes it (with `pair.ron` for one trial) to
/// `<out>/replay-<id>-<cell>-<trial>/`, or, where a replay of the cell under other settings is
/// there, to a folder named by its own settings ([`placed`]), with `run.json` and, where the
/// settings differ from the defaults, every title saying so (as `run` labels its results).
pub(crate) fn command(a: &ReplayArgs) -> Result<(), Failure> {
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    let e = lookup(&exps, &a.id)?;
    let threads = crate::shared::default_threads();
    let ctx = Context::new(e, a.seed, threads, &a.sets, None)?;
    // The files the replay reads, resolved and checked by the rule `run` and `merge` use: a
    // built-in name that is also a file here is refused, as is a file that breaks its rules.
    setting_groups::inputs::check(
        &ctx,
        ("--set: hypothesis", "--set: measured"),
        &mut std::collections::BTreeSet::new(),
    )
    .map_err(Failure::Bad)?;
    if !a.quiet {
        for w in crate::hints::warnings(e, &a.sets, None) {
            note(&w);
        }
    }
    let out = a.out.clone().unwrap_or_else(default_out);
    let (name, aside) = placed(e, a, &ctx.changed(), &out);
    // Where the results go is checked before the trial is rebuilt and run, as `run` checks: an
    // `--out` that is a file, or a name the file system refuses, is refused with exit 2 first.
    let mut targets = vec![crate::plan::Target::Results(name.clone())];
    if let Some((_, to)) = &aside {
        targets.push(crate::plan::Target::Results(to.clone()));
    }
    crate::plan::check_out(&out, &targets)?;
    let pool = crate::compute::make_pool(threads)?;
    let report = pool.install(|| ::replay::replay(&ctx, &a.id, &a.cell, a.trial))?;
    let report = crate::provenance::stamp(&report, e, &ctx, &a.sets, None);
    if let Some((from, to)) = &aside {
        let (from, to) = (out.join(from), out.join(to));
        // An older replay of those same settings is superseded by the one moved there.
        if to.exists() {
            std::fs::remove_dir_all(&to).map_err(|err| {
                Failure::Internal(format!("cannot replace {}: {err}", to.display()))
            })?;
        }
        std::fs::rename(&from, &to).map_err(|err| {
            Failure::Internal(format!(
                "cannot move {} to {}: {err}",
                from.display(),
                to.display()
            ))
        })?;
        note(&format!(
            "the replay under other settings that was in {} is now in {}",
            from.display(),
            to.display()
        ));
    }
    let dir = out.join(name);
    registry::write_results(&dir, &report)?;
    let printed = print(&report.text());
    if !a.quiet {
        note(&format!("results: {}", dir.display()));
    }
    printed
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::args::parse_replay as parse;

    fn args(s: &[&str]) -> Vec<String> {
        s.iter().map(|a| (*a).to_owned()).collect()
    }

    #[test]
    fn parses_cells_trials_and_flags() {
        let a = parse(&args(&[
            "table3",
            "B/m3-e3",
            "17",
            "--seed=3",
            "--set",
            "trials=40",
        ]))
        .unwrap();
        assert_eq!(
            (a.id.as_str(), a.cell.as_str(), a.trial, a.seed),
            ("table3", "B/m3-e3", Some(17), 3)
        );
        assert_eq!(a.sets, [("trials".to_owned(), "40".to_owned())]);
        assert_eq!(folder(&a, &[]), "replay-table3-B-m3-e3-17-seed-3");
        let mut default_seed = parse(&args(&["table3", "B/m3-e3", "17"])).unwrap();
        assert_eq!(folder(&default_seed, &[]), "replay-table3-B-m3-e3-17");
        assert_eq!(
            folder(
                &default_seed,
                &[("hypothesis", "a+b"), ("trials", "4"), ("clearance", "50")]
            ),
            "replay-table3-B-m3-e3-17-clearance-50-hypothesis-a-b"
        );
        let long = "x".repeat(200);
        default_seed.seed = 1;
        let hashed = folder(&default_seed, &[("hypothesis_params", &long)]);
        assert!(
            hashed.starts_with("replay-table3-B-m3-e3-17-settings-") && hashed.len() < 60,
            "{hashed}"
        );
        // `--trials N` is `--set trials=N`, as `run` takes it; both at once are refused.
        let short = parse(&args(&["table3", "B/m3-e3", "--trials", "40"])).unwrap();
        assert_eq!(short.sets, a.sets);
        assert!(
            parse(&args(&[
                "table3",
                "B/m3-e3",
                "--trials=4",
                "--set",
                "trials=4"
            ]))
            .is_err()
        );
        let listing = parse(&args(&["tableI", "B/70/m3-e3", "-q"])).unwrap();
        assert_eq!(listing.trial, None);
        assert_eq!(folder(&listing, &[]), "replay-tableI-B-70-m3-e3-failed");
        for bad in [
            &["table3"][..],
            &["table3", "B/m3-e3", "x"],
            &["table3", "B/m3-e3", "1", "2"],
            &["table3", "B/m3-e3", "--bogus"],
            &["table3", "B/m3-e3", "--seed", "-1"],
        ] {
            assert!(parse(&args(bad)).is_err(), "{bad:?}");
        }
    }
}
