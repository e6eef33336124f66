//! `cargo xtask replay <experiment> <cell> [<trial>]`: one trial of a per-mesh jam table rebuilt
//! and rerun (its events, and `pair.ron` to rerun it with `run pair`), or the cell's failed trials
//! listed (see `experiments::replay`).

use std::path::PathBuf;

use registry::Context;

use crate::args::DEFAULT_SEED;
use crate::failure::Failure;
use crate::plan::lookup;
use crate::progress::note;
use crate::shared::{default_out, print};

/// What `replay` was given.
struct ReplayArgs {
    id: String,
    cell: String,
    trial: Option<u64>,
    seed: u64,
    sets: Vec<(String, String)>,
    out: Option<PathBuf>,
    quiet: bool,
}

const USAGE: &str = "replay <experiment> <cell> [<trial>] [--seed S] [--trials N] [--set KEY=VALUE]... [--out DIR] [-q]";

fn usage(what: impl std::fmt::Display) -> Failure {
    Failure::Usage(format!("{what}\nusage: cargo xtask {USAGE}"))
}

/// The value of a flag: `--flag=V` or `--flag V`.
fn value(
    arg: &str,
    flag: &str,
    it: &mut std::slice::Iter<'_, String>,
) -> Result<Option<String>, Failure> {
    if let Some(v) = arg.strip_prefix(flag).and_then(|r| r.strip_prefix('=')) {
        return Ok(Some(v.to_owned()));
    }
    if arg != flag {
        return Ok(None);
    }
    match it.next() {
        Some(v) if !v.starts_with("--") => Ok(Some(v.clone())),
        _ => Err(usage(format!("{flag} needs a value"))),
    }
}

fn parse(args: &[String]) -> Result<ReplayArgs, Failure> {
    let mut positional = Vec::new();
    let (mut seed, mut sets, mut out, mut quiet) = (None, Vec::new(), None, false);
    let mut trials: Option<String> = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "-q" || arg == "--quiet" {
            quiet = true;
        } else if let Some(v) = value(arg, "--seed", &mut it)? {
            if seed.is_some() {
                return Err(usage("--seed given twice"));
            }
            seed = Some(v.parse::<u64>().map_err(|_| {
                Failure::Bad(format!(
                    "--seed: `{v}` is not a whole number 0 to {}",
                    u64::MAX
                ))
            })?);
        } else if let Some(v) = value(arg, "--set", &mut it)? {
            let (k, val) = v
                .split_once('=')
                .ok_or_else(|| Failure::Bad(format!("--set: `{v}` must be KEY=VALUE")))?;
            sets.push((k.trim().to_owned(), val.trim().to_owned()));
        } else if let Some(v) = value(arg, "--trials", &mut it)? {
            // As `run` takes it: the experiment's `trials` parameter, so that a replay names the
            // same trials as the run it follows.
            if trials.is_some() {
                return Err(usage("--trials given twice"));
            }
            trials = Some(v);
        } else if let Some(v) = value(arg, "--out", &mut it)? {
            if out.is_some() {
                return Err(usage("--out given twice"));
            }
            if v.is_empty() {
                return Err(Failure::Bad("--out: must not be empty".into()));
            }
            out = Some(PathBuf::from(v));
        } else if arg.starts_with('-') && arg.parse::<f64>().is_err() {
            return Err(usage(format!("replay does not take `{arg}`")));
        } else {
            positional.push(arg.clone());
        }
    }
    if let Some(v) = trials {
        if sets.iter().any(|(k, _)| k == "trials") {
            return Err(Failure::Bad(
                "--trials: give the trials once, as --trials N or as --set trials=N".into(),
            ));
        }
        sets.push(("trials".to_owned(), v));
    }
    let (id, cell, trial) = match positional.as_slice() {
        [id, cell] => (id.clone(), cell.clone(), None),
        [id, cell, t] => {
            let t = t.parse::<u64>().map_err(|_| {
                Failure::Bad(format!(
                    "replay: trial `{t}` is not a trial index (0, 1, 2, ...)"
                ))
            })?;
            (id.clone(), cell.clone(), Some(t))
        }
        _ => {
            return Err(usage(
                "replay takes an experiment, a cell and optionally a trial",
            ));
        }
    };
    Ok(ReplayArgs {
        id,
        cell,
        trial,
        seed: seed.unwrap_or(DEFAULT_SEED),
        sets,
        out,
        quiet,
    })
}

/// A folder name for the replay's results: `replay-table3-B-m3-e3-17`.
fn folder(a: &ReplayArgs) -> String {
    let cell: String = a
        .cell
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '.' || c == '-' {
                c
            } else {
                '-'
            }
        })
        .collect();
    let trial = a
        .trial
        .map_or_else(|| "failed".to_owned(), |t| t.to_string());
    format!("replay-{}-{cell}-{trial}", a.id)
}

/// Runs `replay`: prints the report and writes it (with `pair.ron` for one trial) to
/// `<out>/replay-<id>-<cell>-<trial>/`.
pub(crate) fn command(args: &[String]) -> Result<(), Failure> {
    let a = parse(args)?;
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    let e = lookup(&exps, &a.id)?;
    let threads = crate::shared::default_threads();
    let ctx = Context::new(e, a.seed, threads, &a.sets, None)?;
    // Where the results go is checked before the trial is rebuilt and run, as `run` checks: an
    // `--out` that is a file, or a name the file system refuses, is refused with exit 2 first.
    let out = a.out.clone().unwrap_or_else(default_out);
    crate::plan::check_out(&out, &[crate::plan::Target::Results(folder(&a))])?;
    let pool = crate::compute::make_pool(threads)?;
    let report = pool.install(|| experiments::replay::replay(&ctx, &a.id, &a.cell, a.trial))?;
    let dir = out.join(folder(&a));
    registry::write_results(&dir, &report)?;
    print(&report.text())?;
    if !a.quiet {
        note(&format!("results: {}", dir.display()));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

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
        assert_eq!(folder(&a), "replay-table3-B-m3-e3-17");
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
        assert_eq!(folder(&listing), "replay-tableI-B-70-m3-e3-failed");
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
