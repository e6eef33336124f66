//! Running experiments: `run <id>...` and `run all` with its summary (one experiment is computed
//! by [`crate::compute`]).

use registry::Entry;

use crate::args::RunArgs;
use crate::compute::{execute, make_pool};
use crate::failure::Failure;
use crate::help::known;
use crate::plan::{as_typed, check_sets, plan, read_config, select};
use crate::print::Printer;
use crate::progress::note;
use crate::provenance;
use crate::shard::run_shard;
use crate::shared::{Registry, default_out, default_threads, print, write_atomically};
use crate::summary;

/// `run all`: every experiment in id order, each written as `run <id>` writes it; a failing
/// experiment is reported on stderr and the others still run. Then the summary is printed
/// (through `out`, in the `--format` asked for) and written to `<out>/summary.md` and
/// `<out>/summary.json`.
///
/// `--set KEY=VALUE` goes to every experiment that declares KEY (a KEY none declares is refused
/// before anything runs), and so do the shorthands (`--trials`, `--gearing`, `--hypothesis`,
/// `--errors`); `--config` goes to every experiment that takes one (refused if none does).
/// Returns the summary rows; [`summary::exit_code`] turns them into the exit status.
pub(crate) fn run_every(
    exps: &Registry,
    run: &RunArgs,
    out: &mut dyn FnMut(&str) -> Result<(), Failure>,
) -> Result<Vec<summary::Row>, Failure> {
    let chosen: Vec<&'static Entry> = exps.values().copied().collect();
    let config = read_config(run)?;
    if config.is_some() && !chosen.iter().any(|e| e.config.is_some()) {
        return Err(Failure::Bad(
            "--config: no experiment takes a config file".into(),
        ));
    }
    if chosen.is_empty() {
        check_sets(&chosen, &run.sets)?;
        note(&format!("nothing to run: {}", known(exps)));
        return Ok(Vec::new());
    }
    let threads = run.threads.unwrap_or_else(default_threads);
    let planned = plan(&chosen, run, config.as_ref(), false, threads)?;
    let pool = make_pool(threads)?;
    let dir = run.out.clone().unwrap_or_else(default_out);
    let mut printer = Printer::new(run.format, true, out);
    let mut rows = Vec::with_capacity(planned.len());
    for p in &planned {
        let (result, seconds) = execute(p.e, &p.ctx, &pool);
        let result = match result {
            Ok(report) => {
                // Printed as written: tables.json lists run.json among the files. Written
                // before it is printed, so that a failed print (a full disk behind stdout)
                // loses no results.
                let report =
                    provenance::stamp_outcome(&report, p.e, &p.ctx, &p.sets, run.config.as_deref());
                let results = dir.join(p.e.id);
                let written = registry::write_results(&results, &report);
                if written.is_ok() {
                    printer.report(p.e, &report)?;
                    note(&format!("results: {}", results.display()));
                }
                written.map(|()| report)
            }
            Err(err) => Err(as_typed(err, p.e.id, run)),
        };
        if let Err(err) = &result {
            crate::progress::say(&format!("{}: {err}", p.e.id));
        }
        rows.push(summary::Row::new(p.e.id, seconds, result.as_ref()));
    }
    printer.summary(&rows, run.seed, threads)?;
    printer.finish()?;
    std::fs::create_dir_all(&dir).map_err(|e| {
        Failure::Internal(format!(
            "internal error: cannot create {}: {e}",
            dir.display()
        ))
    })?;
    write_atomically(
        &dir.join("summary.md"),
        &summary::MARKDOWN_KIND,
        summary::markdown(&rows, run.seed, threads).as_bytes(),
    )?;
    write_atomically(
        &dir.join("summary.json"),
        &summary::JSON_KIND,
        summary::json(&rows, run.seed, threads).as_bytes(),
    )?;
    note(&format!("summary: {}", dir.join("summary.md").display()));
    Ok(rows)
}

/// Checks everything the user gave, then runs each experiment in turn; stops at the first failure.
pub(crate) fn run_all(exps: &Registry, run: &RunArgs) -> Result<(), Failure> {
    let chosen = select(exps, &run.ids)?;
    let config = read_config(run)?;
    if config.is_some() {
        if let Some(e) = chosen.iter().find(|e| e.config.is_none()) {
            return Err(Failure::Bad(format!(
                "--config: experiment {} takes no --config",
                e.id
            )));
        }
        if chosen.is_empty() {
            return Err(Failure::Bad("--config: no experiment to give it to".into()));
        }
    }
    if chosen.is_empty() {
        note(&format!("nothing to run: {}", known(exps)));
        return Ok(());
    }
    let threads = run.threads.unwrap_or_else(default_threads);
    let planned = plan(&chosen, run, config.as_ref(), chosen.len() == 1, threads)?;
    let pool = make_pool(threads)?;
    let out = run.out.clone().unwrap_or_else(default_out);
    if let (Some(shard), [p]) = (run.shard, planned.as_slice()) {
        return run_shard(p, p.ctx.clone().with_shard(shard), run, &pool, &out);
    }
    let mut stdout = |s: &str| print(s);
    let mut printer = Printer::new(run.format, planned.len() > 1, &mut stdout);
    for p in &planned {
        let report = match execute(p.e, &p.ctx, &pool).0 {
            Ok(r) => r,
            Err(e) => {
                // What finished is printed (JSON is held back until the end).
                printer.finish()?;
                return Err(as_typed(e, p.e.id, run).into());
            }
        };
        let report =
            provenance::stamp_outcome(&report, p.e, &p.ctx, &p.sets, run.config.as_deref());
        // Written before printed: a print that fails (stdout closed or its disk full) must not
        // cost the results.
        let dir = out.join(p.e.id);
        registry::write_results(&dir, &report)?;
        let printed = printer.report(p.e, &report);
        note(&format!("results: {}", dir.display()));
        printed?;
    }
    printer.finish()
}
