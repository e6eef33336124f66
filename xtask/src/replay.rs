//! `cargo xtask replay <experiment> <cell> [<trial>]`: one trial of a per-mesh jam table rebuilt
//! and rerun (its events, and `pair.ron` to rerun it with `run pair`), or the cell's failed trials
//! listed (see `experiments::replay`).

use registry::Context;

use crate::args::ReplayArgs;
use crate::failure::Failure;
use crate::plan::lookup;
use crate::progress::note;
use crate::shared::{default_out, print};

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
pub(crate) fn command(a: &ReplayArgs) -> Result<(), Failure> {
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    let e = lookup(&exps, &a.id)?;
    let threads = crate::shared::default_threads();
    let ctx = Context::new(e, a.seed, threads, &a.sets, None)?;
    // Where the results go is checked before the trial is rebuilt and run, as `run` checks: an
    // `--out` that is a file, or a name the file system refuses, is refused with exit 2 first.
    let out = a.out.clone().unwrap_or_else(default_out);
    crate::plan::check_out(&out, &[crate::plan::Target::Results(folder(a))])?;
    let pool = crate::compute::make_pool(threads)?;
    let report = pool.install(|| experiments::replay::replay(&ctx, &a.id, &a.cell, a.trial))?;
    let dir = out.join(folder(a));
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
