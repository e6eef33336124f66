//! `cargo xtask bench`: `table5` and `run all` timed in process, with tooth engagements per second.

use std::time::Instant;

use registry::{Context, Entry, Table};

use crate::args::{BenchArgs, BenchTarget, DEFAULT_SEED};
use crate::compute::{execute, make_pool};
use crate::failure::Failure;
use crate::progress;
use crate::progress::note;
use crate::shared::{Registry, default_threads, print};
use crate::summary;

/// `bench`: for each target and thread count, builds a pool, runs the target's experiments at
/// their defaults (seed [`DEFAULT_SEED`]) in-process, and prints one row: wall time, trials,
/// tooth engagements and engagements per second. Nothing is written.
pub(crate) fn bench(exps: &Registry, b: &BenchArgs) -> Result<(), Failure> {
    let mut t = Table::new(
        format!(
            "cargo xtask bench: end-to-end wall time at the defaults (the paper's trial counts), seed {DEFAULT_SEED}"
        ),
        [
            "target",
            "threads",
            "wall time [s]",
            "trials",
            "tooth engagements",
            "engagements per second",
        ],
    );
    let mut rows_all = Vec::new();
    for &target in &b.targets {
        let chosen: Vec<&'static Entry> = match target {
            BenchTarget::Table5 => match exps.get("table5") {
                Some(e) => vec![*e],
                None => {
                    note("bench: table5 is not registered in this build; skipped");
                    t.note("table5: not registered in this build; skipped.");
                    continue;
                }
            },
            BenchTarget::All => exps.values().copied().collect(),
        };
        for &threads in &b.threads {
            note(&format!(
                "bench: {} with {threads} thread{}...",
                target.name(),
                if threads == 1 { "" } else { "s" }
            ));
            // Every timed run does all its own work: nothing from an earlier run is reused.
            experiments::forget_cached_cells();
            let start = Instant::now();
            let pool = make_pool(threads)?;
            let mut rows = Vec::new();
            for e in &chosen {
                let ctx = progress::attach(Context::new(e, DEFAULT_SEED, threads, &[], None)?);
                let (result, seconds) = execute(e, &ctx, &pool);
                if let Err(err) = &result {
                    crate::progress::say(&format!("bench: {}: {err}", e.id));
                    t.note(format!(
                        "{} with {threads} threads: {} failed: {err}",
                        target.name(),
                        e.id
                    ));
                }
                let result = result.map(|o| o.report);
                rows.push(summary::Row::new(e.id, seconds, result.as_ref()));
            }
            let wall = start.elapsed().as_secs_f64();
            t.row(bench_row(target.name(), threads, wall, &rows));
            rows_all.extend(rows);
        }
    }
    t.note(format!(
        "Wall time: building the pool and running every experiment of the target in this process, results not written; {} threads available here.",
        default_threads()
    ));
    t.note("Tooth engagements: summed over the experiments that count them ('-': none does).");
    print(&t.render())?;
    match summary::exit_code(&rows_all) {
        0 => Ok(()),
        code => Err(Failure::Reported(code)),
    }
}

/// One row of the bench table.
pub(crate) fn bench_row(
    target: &str,
    threads: usize,
    wall: f64,
    rows: &[summary::Row],
) -> Vec<String> {
    let trials: u64 = rows.iter().map(|r| r.trials).sum();
    let engagements: u64 = rows.iter().map(|r| r.engagements).sum();
    let (eng, rate) = if engagements == 0 {
        ("-".to_string(), "-".to_string())
    } else {
        (
            engagements.to_string(),
            registry::fmt_f64(engagements as f64 / wall.max(1e-9), 0),
        )
    };
    vec![
        target.into(),
        threads.to_string(),
        registry::fmt_f64(wall, 2),
        trials.to_string(),
        eng,
        rate,
    ]
}
