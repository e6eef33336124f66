//! `cargo xtask`: lists and runs the experiments that reproduce the paper's figures and tables.
//!
//! Results go to stdout (the report's tables, exactly as snapshotted) and to
//! `<out>/<id>/` (see [`registry::write_results`]); logs go to stderr (`RUST_LOG`, default `warn`).
//! Exit status: 0 success, 1 internal error, 2 bad input (nothing written).

mod args;

use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use registry::{ConfigFile, Context, Experiment, RunError, Table};

use crate::args::{ArgError, Command, DEFAULT_SEED, RunArgs};

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
}

impl Failure {
    fn code(&self) -> u8 {
        match self {
            Failure::Usage(_) | Failure::Bad(_) => 2,
            Failure::Internal(_) => 1,
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
    let cmd = args::parse(args)?;
    let exps = registry::experiments().map_err(|e| Failure::Internal(e.to_string()))?;
    match cmd {
        Command::Overview => print(&overview(&exps)),
        Command::List => print(&exps.keys().map(|id| format!("{id}\n")).collect::<String>()),
        Command::Hypotheses => print(&hypotheses::listing()),
        Command::Help(None) => print(&format!("{}\n", usage())),
        Command::Help(Some(id)) => print(&details(lookup(&exps, &id)?)),
        Command::Run(run) => run_all(&exps, &run),
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
                                run experiments (`all` runs every one), print their
                                tables and write results to <out>/<id>/

Options of run:
  --seed S          seed of every random number generator (default {DEFAULT_SEED})
  --threads N       worker threads, at least 1 (default: available parallelism, here {})
  --out DIR         where results go (default {})
  --config FILE     RON config file, for experiments that take one (see help <id>)
  --gearing FILE    gearing RON file for train experiments (same as --set gearing=FILE)
  --hypothesis NAME error hypothesis for experiments that apply errors (see `hypotheses`)
  --set KEY=VALUE   set a parameter (repeatable; see help <id>); with several
                    experiments, each gets the keys it declares

Exit status: 0 done, 1 internal error, 2 bad input (the failing experiment writes nothing).
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

/// The experiments `ids` names, in order, without repeats (`all`: every one, by id).
fn select(exps: &Registry, ids: &[String]) -> Result<Vec<&'static Experiment>, Failure> {
    let mut chosen: Vec<&'static Experiment> = Vec::new();
    for id in ids {
        let add: Vec<&'static Experiment> = if id == "all" {
            exps.values().copied().collect()
        } else {
            vec![lookup(exps, id)?]
        };
        for e in add {
            if !chosen.iter().any(|c| c.id == e.id) {
                chosen.push(e);
            }
        }
    }
    Ok(chosen)
}

/// Checks everything the user gave, then runs each experiment in turn; stops at the first failure.
fn run_all(exps: &Registry, run: &RunArgs) -> Result<(), Failure> {
    let chosen = select(exps, &run.ids)?;
    let config = match &run.config {
        None => None,
        Some(path) => {
            let text = std::fs::read_to_string(path).map_err(|e| {
                Failure::Bad(format!("--config: {}: cannot read: {e}", path.display()))
            })?;
            Some(ConfigFile {
                path: path.clone(),
                text,
            })
        }
    };
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
        // With several experiments each gets the keys it declares, but every key must be someone's.
        for (key, _) in &run.sets {
            if !chosen
                .iter()
                .any(|e| e.params.iter().any(|p| p.name == key))
            {
                return Err(Failure::Bad(format!(
                    "--set: {key}: no selected experiment has this parameter"
                )));
            }
        }
    }
    let threads = run.threads.unwrap_or_else(default_threads);
    let mut contexts = Vec::with_capacity(chosen.len());
    for e in &chosen {
        let sets: Vec<(String, String)> = if chosen.len() == 1 {
            run.sets.clone()
        } else {
            run.sets
                .iter()
                .filter(|(k, _)| e.params.iter().any(|p| p.name == k))
                .cloned()
                .collect()
        };
        contexts.push(Context::new(e, run.seed, threads, &sets, config.clone())?);
    }
    if chosen.is_empty() {
        eprintln!("nothing to run: {}", known(exps));
        return Ok(());
    }
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("xtask-worker-{i}"))
        .build()
        .map_err(|e| Failure::Internal(format!("cannot start {threads} threads: {e}")))?;
    let out = run.out.clone().unwrap_or_else(default_out);
    let several = chosen.len() > 1;
    for (i, (e, ctx)) in chosen.iter().zip(&contexts).enumerate() {
        let _span = tracing::info_span!("run", id = e.id).entered();
        tracing::info!(seed = run.seed, threads, "start");
        let start = Instant::now();
        let report = pool
            .install(|| catch_unwind(AssertUnwindSafe(|| (e.run)(ctx))))
            .map_err(|_| {
                Failure::Internal(format!("internal error: experiment `{}` panicked", e.id))
            })??;
        tracing::info!(seconds = start.elapsed().as_secs_f64(), "done");
        if several {
            let gap = if i == 0 { "" } else { "\n" };
            print(&format!("{gap}## {}: {}\n\n", e.id, e.title))?;
        }
        print(&report.text())?;
        let dir = out.join(e.id);
        registry::write_results(&dir, &report)?;
        eprintln!("results: {}", dir.display());
    }
    Ok(())
}
