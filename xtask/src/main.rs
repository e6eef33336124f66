//! `cargo xtask`: lists and runs the experiments that reproduce the paper's figures and tables.
//!
//! Results go to stdout (the report's tables, exactly as snapshotted, or as CSV or JSON with
//! `--format`) and to `<out>/<id>/` (see [`registry::write_results`]); logs and progress bars go
//! to stderr (see [`progress`]). Exit status: 0 success, 1 internal error, 2 bad input (one line
//! on stderr naming the input and the rule; nothing written).
//!
//! `run all` runs every experiment even when some fail, then prints a summary table and writes it
//! to `<out>/summary.md` and `<out>/summary.json`; `bench` times `table5` and `all` in-process;
//! `report` writes `<out>/index.html` from the results; `fuzz` feeds mutated RON files to the
//! loaders (see `fuzz.rs` and `docs/fuzzing.md`).
//!
//! `run <id> --shard K/N` computes one shard of an experiment's trials (see
//! [`registry::Context::trials`]) and writes `<out>/<id>/partial-K-of-N.json`; `merge` joins the
//! partial files of every shard and writes the results a single run would write, bit for bit.
//!
//! This file declares the modules (one concern each; the declarations below are the list) and
//! dispatches the parsed command line to them.

mod args;
mod bench;
mod compute;
mod execute;
mod failure;
mod fuzz;
mod fuzz_settings;
mod fuzz_targets;
mod help;
mod hints;
mod plan;
mod print;
mod progress;
mod provenance;
mod replay;
mod report;
mod shard;
mod shared;
mod summary;

use std::process::ExitCode;

use crate::args::Command;
use crate::execute::{run_all, run_every};
use crate::failure::{Failure, one_line};
use crate::help::{details, hypothesis_details, overview, rule_details, usage};
use crate::shared::{print, stop_cleanly_on_signals};

fn main() -> ExitCode {
    // The run locks end with the process however `main` ends, a panic included.
    let _locks = shared::LocksEnd;
    // Names the plugin crate so that its `inventory` registrations are linked in.
    experiments::link();
    hypotheses::link();
    rules::link();
    stop_cleanly_on_signals();
    let args: Result<Vec<String>, _> = std::env::args_os()
        .skip(1)
        .map(|a| {
            a.into_string()
                .map_err(|a| Failure::Bad(format!("argument {a:?} is not valid UTF-8")))
        })
        .collect();
    let done = args.and_then(|a| dispatch(&a));
    // A signal taken while the command ended: its thread is cleaning up and exits with the
    // signal's status, which must be the process's (not 0 for results it is removing).
    while registry::stopping() {
        std::thread::park();
    }
    // The run locks end with the run, whatever its outcome (a refused run leaves no empty --out).
    registry::release_locks();
    match done {
        // What could not be said on stderr (its disk full, or closed) makes a run that did its
        // work end with status 1 all the same: whoever started it never read its notes.
        Ok(()) if progress::stderr_failed() => ExitCode::from(1),
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            // One line each: what was wrong and the rule (a usage error points to the usage).
            match &f {
                Failure::Usage(m) => progress::say(&format!(
                    "error: {} (`cargo xtask help` shows the usage)",
                    one_line(m)
                )),
                Failure::Bad(m) => progress::say(&one_line(&hints::did_you_mean(m))),
                Failure::Internal(m) => progress::say(&one_line(m)),
                Failure::Reported(_) => {}
            }
            ExitCode::from(f.code())
        }
    }
}

fn dispatch(args: &[String]) -> Result<(), Failure> {
    let (cmd, verbosity) = args::parse_invocation(args)?;
    progress::check_setting().map_err(Failure::Bad)?;
    match cmd {
        Command::Report(r) => return report::command(&r),
        Command::Fuzz(f) => return fuzz::command(&f),
        Command::Replay(r) => {
            progress::init(args::Verbosity::Normal);
            return replay::command(&r);
        }
        _ => {}
    }
    progress::init(verbosity);
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    match cmd {
        Command::Overview => print(&overview(&exps)),
        Command::List => print(&exps.keys().map(|id| format!("{id}\n")).collect::<String>()),
        Command::Hypotheses => print(&hypotheses::listing()),
        Command::Rules => print(&rules::listing()),
        Command::Help(None) => print(&format!("{}\n", usage())),
        Command::Help(Some(id)) => match (exps.get(id.as_str()), hypotheses::lookup(&id)) {
            (Some(e), _) => print(&details(e)),
            (None, Ok(h)) => print(&hypothesis_details(h, &exps)),
            (None, Err(_)) => match rules::Rule::parse(&id) {
                Ok(r) => print(&rule_details(&r, &exps)),
                Err(_) => Err(Failure::Bad(format!(
                    "unknown experiment, error hypothesis or event rule `{id}` (known experiments: {}; error hypotheses: cargo xtask hypotheses; event rules: cargo xtask rules)",
                    exps.keys().copied().collect::<Vec<_>>().join(", ")
                ))),
            },
        },
        Command::Run(run) if run.is_all() => {
            let rows = run_every(&exps, &run, &mut |s| print(s))?;
            tracing::debug!(experiments = rows.len(), "run all done");
            match summary::exit_code(&rows) {
                0 => Ok(()),
                code => Err(Failure::Reported(code)),
            }
        }
        Command::Run(run) => run_all(&exps, &run),
        Command::Bench(b) => bench::bench(&exps, &b),
        Command::Merge(m) => shard::merge(&exps, &m),
        // Run above: they read the registry themselves, or not at all.
        Command::Report(_) | Command::Fuzz(_) | Command::Replay(_) => Ok(()),
    }
}

#[cfg(test)]
mod tests;
