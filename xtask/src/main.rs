//! `cargo xtask`: lists and runs the experiments that reproduce the paper's figures and tables.
//!
//! Results go to stdout (the report's tables, exactly as snapshotted) and to
//! `<out>/<id>/` (see [`registry::write_results`]); logs go to stderr (`RUST_LOG`, default `warn`).
//! Exit status: 0 success, 1 internal error, 2 bad input (nothing written).
//!
//! `run all` runs every experiment even when some fail, then prints a summary table and writes it
//! to `<out>/summary.md` and `<out>/summary.json`; `bench` times `table5` and `all` in-process;
//! `report` writes `<out>/index.html` from the results; `fuzz` feeds mutated RON files to the
//! loaders (see `fuzz.rs` and `docs/fuzzing.md`).

mod args;
mod fuzz;
mod fuzz_targets;
mod provenance;
mod report;
mod summary;

use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use registry::{ConfigFile, Context, Experiment, RunError, Table};

use crate::args::{ArgError, BenchArgs, BenchTarget, Command, DEFAULT_SEED, RunArgs};

/// Experiments by id.
type Registry = BTreeMap<&'static str, &'static Experiment>;

/// Why the command failed.
#[derive(Debug)]
enum Failure {
    /// Unparseable command line: message, then usage; exit 2.
    Usage(String),
    /// Bad user input: message; exit 2.
    Bad(String),
    /// A bug or an I/O failure: message; exit 1.
    Internal(String),
    /// Failures already reported on stderr (`run all`, `bench`): only the exit status is left.
    Reported(u8),
}

impl Failure {
    fn code(&self) -> u8 {
        match self {
            Failure::Usage(_) | Failure::Bad(_) => 2,
            Failure::Internal(_) => 1,
            Failure::Reported(code) => *code,
        }
    }
}

impl From<ArgError> for Failure {
    fn from(e: ArgError) -> Self {
        match e {
            ArgError::Usage(m) => Failure::Usage(m),
            ArgError::Value(m) => Failure::Bad(m),
        }
    }
}

impl From<RunError> for Failure {
    fn from(e: RunError) -> Self {
        match e {
            RunError::BadInput { .. } => Failure::Bad(e.to_string()),
            RunError::Internal(_) => Failure::Internal(e.to_string()),
        }
    }
}

fn main() -> ExitCode {
    // Names the plugin crate so that its `inventory` registrations are linked in.
    experiments::link();
    hypotheses::link();
    init_logs();
    let args: Result<Vec<String>, _> = std::env::args_os()
        .skip(1)
        .map(|a| {
            a.into_string()
                .map_err(|a| Failure::Bad(format!("argument {a:?} is not valid UTF-8")))
        })
        .collect();
    match args.and_then(|a| dispatch(&a)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            match &f {
                Failure::Usage(m) => eprintln!("error: {m}\n\n{}", usage()),
                Failure::Bad(m) | Failure::Internal(m) => eprintln!("{m}"),
                Failure::Reported(_) => {}
            }
            ExitCode::from(f.code())
        }
    }
}

fn init_logs() {
    use tracing_subscriber::EnvFilter;
    let filter = EnvFilter::try_from_default_env().unwrap_or_else(|_| EnvFilter::new("warn"));
    // A second initialisation cannot happen here; if it did, logging would just stay as it was.
    let _ = tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_target(false)
        .try_init();
}

fn dispatch(args: &[String]) -> Result<(), Failure> {
    match args.split_first().map(|(c, r)| (c.as_str(), r)) {
        Some(("report", rest)) => return report::command(rest),
        Some(("fuzz", rest)) => return fuzz::command(rest),
        _ => {}
    }
    let cmd = args::parse(args)?;
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    match cmd {
        Command::Overview => print(&overview(&exps)),
        Command::List => print(&exps.keys().map(|id| format!("{id}\n")).collect::<String>()),
        Command::Hypotheses => print(&hypotheses::listing()),
        Command::Help(None) => print(&format!("{}\n", usage())),
        Command::Help(Some(id)) => print(&details(lookup(&exps, &id)?)),
        Command::Run(run) if run.is_all() => {
            let rows = run_every(&exps, &run, &mut |s| print(s))?;
            match summary::exit_code(&rows) {
                0 => Ok(()),
                code => Err(Failure::Reported(code)),
            }
        }
        Command::Run(run) => run_all(&exps, &run),
        Command::Bench(b) => bench(&exps, &b),
    }
}

/// Writes to stdout; a closed pipe (`cargo xtask list | head -1`) is not an error.
fn print(s: &str) -> Result<(), Failure> {
    let mut out = std::io::stdout().lock();
    match out.write_all(s.as_bytes()).and_then(|()| out.flush()) {
        Err(e) if e.kind() != std::io::ErrorKind::BrokenPipe => {
            Err(Failure::Internal(format!("cannot write to stdout: {e}")))
        }
        _ => Ok(()),
    }
}

fn default_threads() -> usize {
    std::thread::available_parallelism().map_or(1, |n| n.get())
}

/// `<workspace root>/results`.
fn default_out() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map_or_else(|| manifest.join(".."), Path::to_path_buf)
        .join("results")
}

fn usage() -> String {
    format!(
        "\
Usage:
  cargo xtask                   this overview: commands and experiments
  cargo xtask list              experiment ids, one per line
  cargo xtask help <id>         an experiment's paper item, parameters and config file
  cargo xtask hypotheses        manufacturing-error hypotheses, their parameters and defaults
  cargo xtask run <id>... [options]
                                run experiments, print their tables and write
                                results to <out>/<id>/
  cargo xtask run all [options]
                                run every experiment in id order, going on past
                                failures; then print a summary (wall time, trials,
                                tooth engagements, agreement with the paper) and
                                write it to <out>/summary.md and <out>/summary.json
  cargo xtask bench [--only table5|all] [--threads 1,2]
                                time table5 and all at their defaults with each
                                thread count, in-process; prints a table, writes nothing
  cargo xtask report [--out DIR]
                                write <out>/index.html: one self-contained page with
                                every experiment's tables, figures and provenance
  cargo xtask fuzz [--seconds N | --execs N] [--seed S] [--findings DIR]
                                feed mutated RON files to the gearing and measured-
                                errors loaders (default 60 s); exit 1 on a panic or
                                a broken promise, inputs saved in DIR

Options of run:
  --seed S          seed of every random number generator (default {DEFAULT_SEED})
  --threads N       worker threads, at least 1 (default: available parallelism, here {})
  --out DIR         where results go (default {})
  --config FILE     RON config file, for experiments that take one (see help <id>)
  --gearing FILE    gearing RON file for train experiments (same as --set gearing=FILE)
  --hypothesis NAME error hypothesis for experiments that apply errors (see `hypotheses`)
  --set KEY=VALUE   set a parameter (repeatable; see help <id>); with several
                    experiments or `all`, each gets the keys it declares, and a
                    key no experiment declares is refused
                    (with `all`, --config likewise goes to those that take one)

Exit status: 0 done, 1 internal error, 2 bad input (the failing experiment writes nothing).
`run all` runs the others after a failure and exits 1 if any failed internally, else 2 if any
had bad input.
Logs go to stderr; set RUST_LOG (e.g. RUST_LOG=info) for more.",
        default_threads(),
        default_out().display()
    )
}

fn overview(exps: &Registry) -> String {
    let mut s = String::from(
        "xtask: runs the experiments that reproduce the paper's figures and tables.\n\n",
    );
    s.push_str(&usage());
    s.push_str("\n\n");
    if exps.is_empty() {
        s.push_str("Experiments: none registered yet.\n");
    } else {
        let mut t = Table::new("Experiments", ["id", "paper item", "title"]);
        for e in exps.values() {
            t.row(vec![e.id.into(), e.paper_item.into(), e.title.into()]);
        }
        s.push_str(&t.render());
    }
    s
}

fn details(e: &Experiment) -> String {
    let mut s = format!("{}: {}\nPaper item: {}\n\n", e.id, e.title, e.paper_item);
    if e.params.is_empty() {
        s.push_str("Parameters: none.\n");
    } else {
        let mut t = Table::new(
            "Parameters (set with --set NAME=VALUE)",
            ["name", "default", "unit", "help"],
        );
        for p in e.params {
            t.row(vec![
                p.name.into(),
                p.default.into(),
                p.unit.into(),
                p.help.into(),
            ]);
        }
        s.push_str(&t.render());
    }
    s.push('\n');
    match e.config {
        Some(text) => s.push_str(&format!("Config file (--config FILE, RON): {text}\n")),
        None => s.push_str("Config file: none (takes no --config).\n"),
    }
    s
}

fn known(exps: &Registry) -> String {
    if exps.is_empty() {
        "no experiments are registered yet".into()
    } else {
        let ids: Vec<&str> = exps.keys().copied().collect();
        format!("known experiments: {}", ids.join(", "))
    }
}

fn lookup(exps: &Registry, id: &str) -> Result<&'static Experiment, Failure> {
    exps.get(id)
        .copied()
        .ok_or_else(|| Failure::Bad(format!("unknown experiment `{id}`\n{}", known(exps))))
}

/// The experiments `ids` names, in order, without repeats (`run all` is handled by [`run_every`]).
fn select(exps: &Registry, ids: &[String]) -> Result<Vec<&'static Experiment>, Failure> {
    let mut chosen: Vec<&'static Experiment> = Vec::new();
    for id in ids {
        let e = lookup(exps, id)?;
        if !chosen.iter().any(|c| c.id == e.id) {
            chosen.push(e);
        }
    }
    Ok(chosen)
}

/// The file given with `--config`, read.
fn read_config(run: &RunArgs) -> Result<Option<ConfigFile>, Failure> {
    match &run.config {
        None => Ok(None),
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| {
                Failure::Bad(format!("--config: {}: cannot read: {e}", path.display()))
            })?;
            Ok(Some(ConfigFile {
                path: path.clone(),
                text,
            }))
        }
    }
}

/// With several experiments each gets the `--set` keys it declares, but every key must be someone's.
fn check_sets(chosen: &[&'static Experiment], sets: &[(String, String)]) -> Result<(), Failure> {
    for (key, _) in sets {
        if !chosen
            .iter()
            .any(|e| e.params.iter().any(|p| p.name == key))
        {
            return Err(Failure::Bad(format!(
                "--set: {key}: no selected experiment has this parameter"
            )));
        }
    }
    Ok(())
}

/// The `--set` pairs `e` declares.
fn sets_for(e: &Experiment, sets: &[(String, String)]) -> Vec<(String, String)> {
    sets.iter()
        .filter(|(k, _)| e.params.iter().any(|p| p.name == k))
        .cloned()
        .collect()
}

fn make_pool(threads: usize) -> Result<rayon::ThreadPool, Failure> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("xtask-worker-{i}"))
        .build()
        .map_err(|e| Failure::Internal(format!("cannot start {threads} threads: {e}")))
}

/// Runs `e` in `pool`: its report (a panic is an internal error) and the wall time in seconds.
fn execute(
    e: &Experiment,
    ctx: &Context,
    pool: &rayon::ThreadPool,
) -> (Result<registry::Report, RunError>, f64) {
    let _span = tracing::info_span!("run", id = e.id).entered();
    tracing::info!(seed = ctx.seed(), threads = ctx.threads(), "start");
    let start = Instant::now();
    let result = pool
        .install(|| catch_unwind(AssertUnwindSafe(|| (e.run)(ctx))))
        .unwrap_or_else(|_| {
            Err(RunError::Internal(format!(
                "experiment `{}` panicked",
                e.id
            )))
        });
    let seconds = start.elapsed().as_secs_f64();
    tracing::info!(seconds, "done");
    (result, seconds)
}

/// Writes `text` to `path` through a temporary sibling renamed into place.
fn write_atomically(path: &Path, text: &str) -> Result<(), Failure> {
    let tmp = path.with_file_name(format!(
        ".{}.tmp-{}",
        path.file_name()
            .map_or_else(|| "summary".into(), |n| n.to_string_lossy().into_owned()),
        std::process::id()
    ));
    let fail = |what: &str, e: std::io::Error| {
        Failure::Internal(format!(
            "internal error: cannot {what} {}: {e}",
            path.display()
        ))
    };
    std::fs::write(&tmp, text).map_err(|e| fail("write", e))?;
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        fail("rename into", e)
    })
}

/// `run all`: every experiment in id order, each written as `run <id>` writes it; a failing
/// experiment is reported on stderr and the others still run. Then the summary is printed
/// (through `out`) and written to `<out>/summary.md` and `<out>/summary.json`.
///
/// `--set KEY=VALUE` goes to every experiment that declares KEY (a KEY none declares is refused
/// before anything runs); `--config` goes to every experiment that takes one (refused if none
/// does). Returns the summary rows; [`summary::exit_code`] turns them into the exit status.
fn run_every(
    exps: &Registry,
    run: &RunArgs,
    out: &mut dyn FnMut(&str) -> Result<(), Failure>,
) -> Result<Vec<summary::Row>, Failure> {
    let chosen: Vec<&'static Experiment> = exps.values().copied().collect();
    let config = read_config(run)?;
    if config.is_some() && !chosen.iter().any(|e| e.config.is_some()) {
        return Err(Failure::Bad(
            "--config: no experiment takes a config file".into(),
        ));
    }
    check_sets(&chosen, &run.sets)?;
    if chosen.is_empty() {
        eprintln!("nothing to run: {}", known(exps));
        return Ok(Vec::new());
    }
    let threads = run.threads.unwrap_or_else(default_threads);
    let mut contexts = Vec::with_capacity(chosen.len());
    for e in &chosen {
        let file = config.clone().filter(|_| e.config.is_some());
        contexts.push(Context::new(
            e,
            run.seed,
            threads,
            &sets_for(e, &run.sets),
            file,
        )?);
    }
    let pool = make_pool(threads)?;
    let dir = run.out.clone().unwrap_or_else(default_out);
    let mut rows = Vec::with_capacity(chosen.len());
    for (i, (e, ctx)) in chosen.iter().zip(&contexts).enumerate() {
        let (result, seconds) = execute(e, ctx, &pool);
        let result = match result {
            Ok(report) => {
                let gap = if i == 0 { "" } else { "\n" };
                out(&format!("{gap}## {}: {}\n\n", e.id, e.title))?;
                out(&report.text())?;
                let results = dir.join(e.id);
                let stamped = provenance::stamp(&report, e, ctx, run);
                registry::write_results(&results, &stamped).map(|()| {
                    eprintln!("results: {}", results.display());
                    report
                })
            }
            Err(err) => Err(err),
        };
        if let Err(err) = &result {
            eprintln!("{}: {err}", e.id);
        }
        rows.push(summary::Row::new(e.id, seconds, result.as_ref()));
    }
    out(&format!("\n{}", summary::table(&rows).render()))?;
    std::fs::create_dir_all(&dir).map_err(|e| {
        Failure::Internal(format!(
            "internal error: cannot create {}: {e}",
            dir.display()
        ))
    })?;
    write_atomically(
        &dir.join("summary.md"),
        &summary::markdown(&rows, run.seed, threads),
    )?;
    write_atomically(
        &dir.join("summary.json"),
        &summary::json(&rows, run.seed, threads),
    )?;
    eprintln!("summary: {}", dir.join("summary.md").display());
    Ok(rows)
}

/// `bench`: for each target and thread count, builds a pool, runs the target's experiments at
/// their defaults (seed [`DEFAULT_SEED`]) in-process, and prints one row: wall time, trials,
/// tooth engagements and engagements per second. Nothing is written.
fn bench(exps: &Registry, b: &BenchArgs) -> Result<(), Failure> {
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
        let chosen: Vec<&'static Experiment> = match target {
            BenchTarget::Table5 => match exps.get("table5") {
                Some(e) => vec![*e],
                None => {
                    eprintln!("bench: table5 is not registered in this build; skipped");
                    t.note("table5: not registered in this build; skipped.");
                    continue;
                }
            },
            BenchTarget::All => exps.values().copied().collect(),
        };
        for &threads in &b.threads {
            eprintln!(
                "bench: {} with {threads} thread{}...",
                target.name(),
                if threads == 1 { "" } else { "s" }
            );
            let start = Instant::now();
            let pool = make_pool(threads)?;
            let mut rows = Vec::new();
            for e in &chosen {
                let ctx = Context::new(e, DEFAULT_SEED, threads, &[], None)?;
                let (result, seconds) = execute(e, &ctx, &pool);
                if let Err(err) = &result {
                    eprintln!("bench: {}: {err}", e.id);
                    t.note(format!(
                        "{} with {threads} threads: {} failed: {err}",
                        target.name(),
                        e.id
                    ));
                }
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
fn bench_row(target: &str, threads: usize, wall: f64, rows: &[summary::Row]) -> Vec<String> {
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

/// Checks everything the user gave, then runs each experiment in turn; stops at the first failure.
fn run_all(exps: &Registry, run: &RunArgs) -> Result<(), Failure> {
    let chosen = select(exps, &run.ids)?;
    let config = read_config(run)?;
    if config.is_some() {
        if let Some(e) = chosen.iter().find(|e| e.config.is_none()) {
            return Err(Failure::Bad(format!(
                "experiment {} takes no --config",
                e.id
            )));
        }
        if chosen.is_empty() {
            return Err(Failure::Bad("--config: no experiment to give it to".into()));
        }
    }
    if chosen.len() != 1 {
        check_sets(&chosen, &run.sets)?;
    }
    let threads = run.threads.unwrap_or_else(default_threads);
    let mut contexts = Vec::with_capacity(chosen.len());
    for e in &chosen {
        let sets: Vec<(String, String)> = if chosen.len() == 1 {
            run.sets.clone()
        } else {
            sets_for(e, &run.sets)
        };
        contexts.push(Context::new(e, run.seed, threads, &sets, config.clone())?);
    }
    if chosen.is_empty() {
        eprintln!("nothing to run: {}", known(exps));
        return Ok(());
    }
    let pool = make_pool(threads)?;
    let out = run.out.clone().unwrap_or_else(default_out);
    let several = chosen.len() > 1;
    for (i, (e, ctx)) in chosen.iter().zip(&contexts).enumerate() {
        let report = execute(e, ctx, &pool).0?;
        if several {
            let gap = if i == 0 { "" } else { "\n" };
            print(&format!("{gap}## {}: {}\n\n", e.id, e.title))?;
        }
        print(&report.text())?;
        let dir = out.join(e.id);
        registry::write_results(&dir, &provenance::stamp(&report, e, ctx, run))?;
        eprintln!("results: {}", dir.display());
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use registry::{Param, Report};

    fn fine(ctx: &Context) -> Result<Report, RunError> {
        let mut t = Table::new("Fine", ["n"]);
        t.row(vec![ctx.param("n")?.to_owned()]);
        Ok(Report {
            tables: vec![t],
            trials: ctx.u64("n")?,
            engagements: 10,
            agreement: Some(registry::Agreement {
                inside: 2,
                outside: 1,
            }),
            ..Default::default()
        })
    }

    fn refuses(ctx: &Context) -> Result<Report, RunError> {
        let _ = ctx;
        Err(RunError::bad("--set", "x", "must be sensible"))
    }

    fn panics(_: &Context) -> Result<Report, RunError> {
        panic!("deliberately")
    }

    static A_FINE: Experiment = Experiment {
        id: "a-fine",
        title: "fine",
        paper_item: "Table 0",
        params: &[Param {
            name: "n",
            default: "5",
            unit: "",
            help: "trials",
        }],
        config: None,
        run: fine,
    };
    static B_BAD: Experiment = Experiment {
        id: "b-bad",
        title: "refuses",
        paper_item: "Table 0",
        params: &[],
        config: None,
        run: refuses,
    };
    static C_PANIC: Experiment = Experiment {
        id: "c-panic",
        title: "panics",
        paper_item: "Table 0",
        params: &[],
        config: None,
        run: panics,
    };

    fn registry(with_panic: bool) -> Registry {
        let mut r: Registry = BTreeMap::new();
        r.insert(A_FINE.id, &A_FINE);
        r.insert(B_BAD.id, &B_BAD);
        if with_panic {
            r.insert(C_PANIC.id, &C_PANIC);
        }
        r
    }

    fn scratch(tag: &str) -> PathBuf {
        std::env::temp_dir().join(format!(
            "xtask-run-all-{tag}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .unwrap()
                .as_nanos()
        ))
    }

    fn run_all_args(out: &Path, sets: &[(&str, &str)]) -> RunArgs {
        RunArgs {
            ids: vec!["all".into()],
            seed: 1,
            threads: Some(1),
            out: Some(out.to_path_buf()),
            config: None,
            sets: sets
                .iter()
                .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
                .collect(),
        }
    }

    #[test]
    fn run_all_goes_on_past_failures_and_writes_the_summary() {
        let out = scratch("past");
        let mut printed = String::new();
        let rows = run_every(
            &registry(true),
            &run_all_args(&out, &[("n", "7")]),
            &mut |s| {
                printed.push_str(s);
                Ok(())
            },
        )
        .unwrap();
        let ids: Vec<&str> = rows.iter().map(|r| r.id.as_str()).collect();
        assert_eq!(ids, ["a-fine", "b-bad", "c-panic"]);
        assert_eq!(
            rows[0].trials, 7,
            "--set n=7 reached the experiment declaring it"
        );
        assert!(matches!(rows[1].status, summary::Status::BadInput(_)));
        assert!(matches!(rows[2].status, summary::Status::Internal(_)));
        assert_eq!(summary::exit_code(&rows), 1);
        assert_eq!(summary::exit_code(&rows[..2]), 2);
        assert!(out.join("a-fine").join("table.md").exists());
        assert!(!out.join("b-bad").exists());
        assert!(!out.join("c-panic").exists());
        let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
        assert!(md.contains("| a-fine ") && md.contains("2 / 1"), "{md}");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(json["total"]["trials"], 7);
        assert_eq!(json["experiments"][2]["status"], "internal error");
        assert!(
            printed.starts_with("## a-fine: fine\n\n### Fine"),
            "{printed}"
        );
        assert!(printed.contains("### Summary of run all"), "{printed}");
        let _ = std::fs::remove_dir_all(&out);
    }

    #[test]
    fn run_all_refuses_a_key_no_experiment_declares_before_running() {
        let out = scratch("key");
        let e = run_every(
            &registry(false),
            &run_all_args(&out, &[("n", "1"), ("nonsense", "1")]),
            &mut |_| Ok(()),
        )
        .unwrap_err();
        assert_eq!(e.code(), 2);
        assert!(format!("{e:?}").contains("nonsense"));
        assert!(!out.exists(), "nothing may be written");
    }

    #[test]
    fn run_all_refuses_a_config_no_experiment_takes() {
        let out = scratch("config");
        std::fs::create_dir_all(&out).unwrap();
        let file = out.join("c.ron");
        std::fs::write(&file, "()").unwrap();
        let mut args = run_all_args(&out.join("results"), &[]);
        args.config = Some(file);
        let e = run_every(&registry(false), &args, &mut |_| Ok(())).unwrap_err();
        assert_eq!(e.code(), 2);
        assert!(!out.join("results").exists());
        let _ = std::fs::remove_dir_all(&out);
    }

    #[test]
    fn bench_rows_divide_engagements_by_wall_time() {
        let report = Report {
            trials: 4,
            engagements: 1000,
            ..Default::default()
        };
        let rows = vec![
            summary::Row::new("x", 1.0, Ok(&report)),
            summary::Row::new("y", 1.0, Ok(&Report::default())),
        ];
        assert_eq!(
            bench_row("all", 2, 2.0, &rows),
            ["all", "2", "2.00", "4", "1000", "500"]
        );
        assert_eq!(
            bench_row("table5", 1, 2.0, &rows[1..]),
            ["table5", "1", "2.00", "0", "-", "-"]
        );
    }
}
