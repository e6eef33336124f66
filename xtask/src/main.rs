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

mod args;
mod fuzz;
mod fuzz_targets;
mod progress;
mod provenance;
mod report;
mod shard;
mod summary;

use std::collections::BTreeMap;
use std::io::Write;
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use registry::{ConfigFile, Context, Experiment, Report, RunError, Table};
use serde_json::Value;

use crate::args::{
    ArgError, BenchArgs, BenchTarget, Command, DEFAULT_SEED, Format, MAX_THREADS, MergeArgs,
    RunArgs,
};
use crate::progress::note;

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
    rules::link();
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
            // One line each: what was wrong and the rule (a usage error points to the usage).
            match &f {
                Failure::Usage(m) => eprintln!(
                    "error: {} (`cargo xtask help` shows the usage)",
                    one_line(m)
                ),
                Failure::Bad(m) | Failure::Internal(m) => eprintln!("{}", one_line(m)),
                Failure::Reported(_) => {}
            }
            ExitCode::from(f.code())
        }
    }
}

/// `text` on one line: line breaks become `; `, and numbers printed with dozens of digits
/// (see [`short_numbers`]) in exponent form.
fn one_line(text: &str) -> String {
    short_numbers(
        &text
            .lines()
            .map(str::trim_end)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; "),
    )
}

/// `text` with every number of more than 30 digits (a float such as 1e308 printed in full,
/// which no one can read; integer limits such as 2^64 - 1 have 20) in exponent form: `1e308`. Only numbers standing on their own are
/// touched (after a space, `(`, `=` or the start, before a space, punctuation or the end), not
/// digits inside a path or a name.
fn short_numbers(text: &str) -> String {
    let b = text.as_bytes();
    let mut out = String::with_capacity(text.len());
    let mut i = 0;
    while i < b.len() {
        let starts = (i == 0 || matches!(b[i - 1], b' ' | b'(' | b'=' | b'[')) && {
            let d = usize::from(b[i] == b'-');
            b.get(i + d).is_some_and(u8::is_ascii_digit)
        };
        if starts {
            let mut j = i + usize::from(b[i] == b'-');
            let mut digits = 0;
            while j < b.len() && (b[j].is_ascii_digit() || b[j] == b'.') {
                digits += usize::from(b[j].is_ascii_digit());
                j += 1;
            }
            let ends = j == b.len() || matches!(b[j], b' ' | b',' | b';' | b')' | b']' | b':');
            if digits > 30
                && ends
                && let Ok(x) = text[i..j].parse::<f64>()
            {
                out.push_str(&format!("{x:e}"));
                i = j;
                continue;
            }
            out.push_str(&text[i..j]);
            i = j;
            continue;
        }
        let c = text[i..].chars().next().unwrap_or(' ');
        out.push(c);
        i += c.len_utf8();
    }
    out
}

fn dispatch(args: &[String]) -> Result<(), Failure> {
    match args.split_first().map(|(c, r)| (c.as_str(), r)) {
        Some(("report", rest)) => return report::command(rest),
        // `-q` goes anywhere on the line, as the usage says: `cargo xtask -q report`.
        Some(("-q" | "--quiet", rest)) if rest.first().is_some_and(|c| c == "report") => {
            let mut rest = rest[1..].to_vec();
            rest.push("-q".into());
            return report::command(&rest);
        }
        Some(("fuzz", rest)) => return fuzz::command(rest),
        _ => {}
    }
    let (cmd, verbosity) = args::parse_invocation(args)?;
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
        Command::Bench(b) => bench(&exps, &b),
        Command::Merge(m) => merge(&exps, &m),
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
  cargo xtask                   this overview: commands, experiments, error hypotheses
  cargo xtask list              experiment ids, one per line
  cargo xtask help <id>         what an experiment reproduces, its parameters,
                                config file and outputs
  cargo xtask help <hypothesis> what an error hypothesis models, its parameters
                                and how to run it (a+b: b applied after a)
  cargo xtask hypotheses        manufacturing-error hypotheses, their parameters and defaults
  cargo xtask rules             event rules: which events count as jams and disengagements
  cargo xtask help <rule>       what an event rule counts, and the sentences it rests on
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
  cargo xtask run <id> --shard K/N [options]
                                compute only shard K (0..N-1) of the experiment's
                                trials, those with index % N == K, e.g. one task
                                of a cluster job array; writes
                                <out>/<id>/partial-K-of-N.json, no tables
  cargo xtask merge DIR|FILE... [--out DIR] [--threads N] [--format F]
                                join the partial files of shards 0..N-1 (searched
                                for in the directories given), check they fit, and
                                print and write the results as `run` would:
                                bit-identical to one run without --shard
  cargo xtask report [--out DIR]
                                write <out>/index.html: one self-contained page with
                                every experiment's tables, figures and provenance
  cargo xtask fuzz [--seconds N | --execs N] [--seed S] [--findings DIR]
                                feed mutated RON files to the gearing, measured-
                                errors and pair config loaders (default 60 s); exit 1
                                on a panic or a broken promise, inputs saved in DIR

Options of run:
  --seed S          seed of every random number generator, 0 to {max_seed}
                    (default {DEFAULT_SEED})
  --trials N        the `trials` parameter of every selected experiment that
                    declares one, 1 to {max_trials} (refused if none does)
  --threads N       worker threads, 1 to {MAX_THREADS} (default: available
                    parallelism, here {threads})
  --out DIR         where results go (default {out})
  --format F        what is printed on stdout: md (the tables, as table.md),
                    csv (each table as CSV after a `# title` line, blank line
                    between tables) or json (the report, as tables.json);
                    results files are written the same way whatever F is
  --config FILE     RON config file, for experiments that take one (see help <id>)
  --gearing FILE    gearing RON file for every experiment with a `gearing`
                    parameter (as --set gearing=FILE); checked before anything runs
  --hypothesis NAME error hypothesis for every experiment with a `hypothesis`
                    parameter (see `hypotheses`; measured:FILE reads your table)
  --errors FILE     a table of measured per-gear errors (the format of
                    crates/hypotheses/data/measured-example.ron): --set
                    measured=FILE for experiments with a `measured` parameter,
                    --hypothesis measured:FILE for the others that apply errors
  --set KEY=VALUE   set a parameter (repeatable; see help <id>); with several
                    experiments or `all`, each gets the keys it declares, and a
                    key no experiment declares is refused
                    (with `all`, --config likewise goes to those that take one)
  --shard K/N       run shard K of N of one experiment (not with `all` or several
                    ids); give every shard the same seed, --set and --config

Anywhere on the line:
  -q, --quiet       no progress bars, no logs, no notes on stderr; errors only
  -v, --verbose     debug logs on stderr (per-experiment timing, per-batch sizes)

Exit status: 0 done, 1 internal error, 2 bad input (one line on stderr names the file or
flag, the field and the rule; the failing experiment writes nothing).
`run all` runs the others after a failure and exits 1 if any failed internally, else 2 if any
had bad input.
Progress bars (trials done, rate, time left) appear on stderr when it is a terminal and an
experiment runs longer than a second. Logs go to stderr; set RUST_LOG (e.g. RUST_LOG=info)
for more.",
        max_seed = u64::MAX,
        max_trials = registry::MAX_TRIALS,
        threads = default_threads(),
        out = default_out().display()
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
    s.push('\n');
    match hypotheses::hypotheses() {
        Ok(all) => {
            let mut t = Table::new(
                "Error hypotheses (--hypothesis NAME; `cargo xtask hypotheses` lists their parameters)",
                ["name", "what it models"],
            );
            for h in all.values() {
                t.row(vec![h.name().into(), h.summary().into()]);
            }
            t.row(vec![
                "measured:FILE".into(),
                "the measured hypothesis over your own table of per-gear errors (or --errors FILE)"
                    .into(),
            ]);
            s.push_str(&t.render());
        }
        Err(e) => s.push_str(&format!("Error hypotheses: {e}\n")),
    }
    s.push('\n');
    match rules::rules() {
        Ok(all) => {
            let mut t = Table::new(
                format!(
                    "Event rules (--set events=NAME, default {}; `cargo xtask help NAME` quotes what each rests on)",
                    rules::DEFAULT
                ),
                ["name", "what it counts"],
            );
            for r in all.values() {
                t.row(vec![r.name().into(), r.summary().into()]);
            }
            s.push_str(&t.render());
        }
        Err(e) => s.push_str(&format!("Event rules: {e}\n")),
    }
    s
}

/// `help <id>`: what the experiment reproduces, its parameters, the flags that reach it, its
/// config file and its outputs (with the files of its last run in the default results
/// directory, when there is one).
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
    let declares = |name: &str| e.params.iter().any(|p| p.name == name);
    let mut flags = Vec::new();
    if declares("trials") {
        flags.push(format!(
            "--trials N sets `trials` (at most {})",
            registry::MAX_TRIALS
        ));
    }
    if declares("gearing") {
        flags.push("--gearing FILE sets `gearing`".to_string());
    }
    if declares("hypothesis") {
        flags.push("--hypothesis NAME sets `hypothesis`".to_string());
    }
    if declares("measured") {
        flags.push("--errors FILE sets `measured`".to_string());
    } else if declares("hypothesis") {
        flags.push("--errors FILE sets `hypothesis` to measured:FILE".to_string());
    }
    if !flags.is_empty() {
        s.push_str(&format!("\nShorthands: {}.\n", flags.join("; ")));
    }
    s.push('\n');
    match e.config {
        Some(text) => s.push_str(&format!("Config file (--config FILE, RON): {text}\n")),
        None => s.push_str("Config file: none (takes no --config).\n"),
    }
    s.push_str(&outputs(e, &default_out()));
    s
}

/// `help NAME` for an error hypothesis: what it models, its parameters, and how to run it.
/// `cargo xtask help RULE`: what an event rule counts, its reading, parameters and the
/// experiments it applies to.
fn rule_details(r: &rules::Rule, exps: &Registry) -> String {
    let d = r.definition();
    let mut s = format!("{} - event rule\n\n{}\n\n", d.name(), d.summary());
    s.push_str(&wrap(d.details(), 96));
    s.push_str("\n\n");
    if d.params().is_empty() {
        s.push_str("Parameters: none\n");
    } else {
        s.push_str("Parameters (--set events=NAME:key=value):\n");
        for p in d.params() {
            s.push_str(&format!(
                "  {} = {} {} ({} to {}): {}\n",
                p.name, p.default, p.unit, p.min, p.max, p.help
            ));
        }
    }
    let users: Vec<&str> = exps
        .values()
        .filter(|e| e.params.iter().any(|p| p.name == "events"))
        .map(|e| e.id)
        .collect();
    s.push_str(&format!(
        "\nDefault rule: {}. Experiments that count events (--set events={}): {}\n",
        rules::DEFAULT,
        d.name(),
        users.join(", ")
    ));
    s
}

fn hypothesis_details(h: &dyn hypotheses::Hypothesis, exps: &Registry) -> String {
    let name = h.name();
    let mut s = format!("{name}: error hypothesis: {}\n", h.summary());
    if !h.details().is_empty() {
        s.push('\n');
        s.push_str(&wrap(h.details(), 96));
    }
    s.push('\n');
    if h.params().is_empty() {
        s.push_str("Parameters: none.\n");
    } else {
        let mut t = Table::new(
            "Parameters (set with --set hypothesis_params=NAME=VALUE[,NAME=VALUE])",
            ["name", "default", "unit", "help"],
        );
        for p in h.params() {
            t.row(vec![
                p.name.into(),
                p.default.to_string(),
                p.unit.into(),
                p.help.into(),
            ]);
        }
        s.push_str(&t.render());
    }
    let takes: Vec<&str> = exps
        .values()
        .filter(|e| e.params.iter().any(|p| p.name == "hypothesis"))
        .map(|e| e.id)
        .collect();
    let example = h
        .params()
        .first()
        .map(|p| format!(" --set hypothesis_params={}={}", p.name, p.default))
        .unwrap_or_default();
    s.push_str(&format!(
        "\nRun it with any experiment that takes --hypothesis ({}), e.g.\n  cargo xtask run failure --hypothesis {name}{example}\n",
        takes.join(", ")
    ));
    if !name.contains(hypotheses::SEPARATOR) && name != "edmunds-split" {
        s.push_str(&format!(
            "On top of Edmunds' errors (applied to each gear after them):\n  cargo xtask run failure --hypothesis edmunds-split+{name}\n"
        ));
    }
    s
}

/// `text` broken into lines of at most `width` characters, at spaces.
fn wrap(text: &str, width: usize) -> String {
    let mut out = String::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.chars().count() + 1 + word.chars().count() > width {
            out.push_str(&line);
            out.push('\n');
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        out.push_str(&line);
        out.push('\n');
    }
    out
}

/// The outputs part of `help <id>`: the files every run writes, and the experiment's own files
/// as its last run in `out` listed them (they are only known once it has run).
fn outputs(e: &Experiment, out: &Path) -> String {
    let dir = out.join(e.id);
    let mut s = format!(
        "\nOutputs, written to <out>/{id}/ (default {dir}), replacing it whole:\n",
        id = e.id,
        dir = dir.display()
    );
    for line in [
        "  table.md      the tables as printed",
        "  tables.json   the tables, the names of the other files, trials, tooth engagements, agreement",
        "  <title>.csv   one CSV file per table, named after its title",
        "  and the experiment's own files (figures as SVG, data as CSV), listed under `files` in tables.json.",
    ] {
        s.push_str(line);
        s.push('\n');
    }
    let listed = std::fs::read_to_string(dir.join("tables.json"))
        .ok()
        .and_then(|text| serde_json::from_str::<Value>(&text).ok())
        .and_then(|v| {
            v.get("files")?.as_array().map(|files| {
                files
                    .iter()
                    .filter_map(Value::as_str)
                    .map(str::to_owned)
                    .collect::<Vec<_>>()
            })
        });
    match listed {
        Some(files) if files.is_empty() => s.push_str(&format!(
            "Its last run ({}) wrote no files of its own.\n",
            dir.display()
        )),
        Some(files) => s.push_str(&format!(
            "Its last run ({}) wrote: {}.\n",
            dir.display(),
            files.join(", ")
        )),
        None => s.push_str(&format!(
            "Its own files are known once it has run (none in {} yet).\n",
            dir.display()
        )),
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
        .ok_or_else(|| Failure::Bad(format!("unknown experiment `{id}` ({})", known(exps))))
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
            let text =
                input_file::read_to_string(path, input_file::MAX_INPUT_BYTES).map_err(|e| {
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

fn declares(e: &Experiment, name: &str) -> bool {
    e.params.iter().any(|p| p.name == name)
}

/// The `--set` pairs `e` declares.
fn declared_sets(e: &Experiment, sets: &[(String, String)]) -> Vec<(String, String)> {
    sets.iter()
        .filter(|(k, _)| declares(e, k))
        .cloned()
        .collect()
}

/// The shorthand flags given, as (flag, the parameter it sets in `e`, value) for an experiment
/// `e`; `None` where `e` declares no parameter the flag sets.
fn shorthands(e: &Experiment, run: &RunArgs) -> Vec<(&'static str, Option<(String, String)>)> {
    let mut out = Vec::new();
    let mut add = |flag: &'static str, key: &str, value: String| {
        out.push((flag, declares(e, key).then(|| (key.to_owned(), value))));
    };
    if let Some(n) = run.trials {
        add("--trials", "trials", n.to_string());
    }
    if let Some(g) = &run.gearing {
        add("--gearing", "gearing", g.display().to_string());
    }
    if let Some(h) = &run.hypothesis {
        add("--hypothesis", "hypothesis", h.clone());
    }
    if let Some(file) = &run.errors {
        let file = file.display().to_string();
        if declares(e, "measured") {
            add("--errors", "measured", file);
        } else {
            add("--errors", "hypothesis", format!("measured:{file}"));
        }
    }
    out
}

/// Every shorthand flag given must reach at least one of `chosen`.
fn check_shorthands(chosen: &[&'static Experiment], run: &RunArgs) -> Result<(), Failure> {
    let Some(first) = chosen.first() else {
        return Ok(());
    };
    for (i, (flag, _)) in shorthands(first, run).into_iter().enumerate() {
        if !chosen.iter().any(|e| shorthands(e, run)[i].1.is_some()) {
            let wanted = match flag {
                "--trials" => "a `trials` parameter",
                "--gearing" => "a `gearing` parameter",
                "--hypothesis" => "a `hypothesis` parameter",
                _ => "a `measured` or `hypothesis` parameter",
            };
            let ids: Vec<&str> = chosen.iter().map(|e| e.id).collect();
            return Err(Failure::Bad(format!(
                "{flag}: no selected experiment has {wanted} (selected: {})",
                ids.join(", ")
            )));
        }
    }
    Ok(())
}

/// One selected experiment, ready to run: its context and the `--set` pairs it was given
/// (recorded in a shard's partial file).
struct Planned {
    e: &'static Experiment,
    ctx: Context,
    sets: Vec<(String, String)>,
}

/// The contexts of `chosen`. `alone`: one experiment named on its own, which gets every `--set`
/// pair (an unknown key is refused naming its keys); otherwise each gets the keys it declares,
/// and every key must be someone's. Then the shorthands each declares; the config file goes to
/// those that take one. Everything the user gave is checked here, before anything runs:
/// [`preflight`].
fn plan(
    chosen: &[&'static Experiment],
    run: &RunArgs,
    config: Option<&ConfigFile>,
    alone: bool,
    threads: usize,
) -> Result<Vec<Planned>, Failure> {
    if !alone {
        check_sets(chosen, &run.sets)?;
    }
    check_shorthands(chosen, run)?;
    let mut planned = Vec::with_capacity(chosen.len());
    for &e in chosen {
        let mut sets = if alone {
            run.sets.clone()
        } else {
            declared_sets(e, &run.sets)
        };
        sets.extend(shorthands(e, run).into_iter().filter_map(|(_, s)| s));
        let file = config.filter(|_| e.config.is_some()).cloned();
        let ctx = progress::attach(Context::new(e, run.seed, threads, &sets, file)?);
        planned.push(Planned { e, ctx, sets });
    }
    preflight(&planned, run)?;
    Ok(planned)
}

/// Checks, before anything runs, what would otherwise fail only when an experiment reaches it
/// (and with `all`, after others had written their results): `--out` must not be a file, and
/// every gearing file, error hypothesis and measured-errors table the experiments were given
/// must read and pass its rules. Each is refused naming the file, the line or item and the rule.
fn preflight(planned: &[Planned], run: &RunArgs) -> Result<(), Failure> {
    check_out(&run.out.clone().unwrap_or_else(default_out))?;
    let mut seen = std::collections::BTreeSet::new();
    for p in planned {
        let value = |name: &str| {
            p.ctx
                .declares(name)
                .then(|| p.ctx.param(name).ok().map(str::to_owned))
                .flatten()
        };
        if let Some(g) = value("gearing")
            && train::Gearing::builtin(&g).is_none()
            && seen.insert(("gearing", g.clone()))
        {
            train::Gearing::load(Path::new(&g)).map_err(|e| Failure::Bad(e.to_string()))?;
        }
        let flag = if run.errors.is_some() {
            "--errors"
        } else {
            "--hypothesis"
        };
        if let Some(h) = value("hypothesis")
            && seen.insert(("hypothesis", h.clone()))
        {
            hypotheses::lookup(&h).map_err(|e| Failure::Bad(format!("{flag}: {e}")))?;
        }
        if let Some(m) = value("measured")
            && !m.trim().is_empty()
            && seen.insert(("measured", m.clone()))
        {
            let flag = if run.errors.is_some() {
                "--errors"
            } else {
                "--set measured"
            };
            hypotheses::measured_file(m.trim())
                .map_err(|e| Failure::Bad(format!("{flag}: {e}")))?;
        }
        measured_gears_in_gearing(p, run)?;
    }
    Ok(())
}

/// A measured-errors table given to an experiment that builds a gearing must name only gears of
/// that gearing: a row for another gear (a typo, another gearing's name) would be silently
/// unused. Refused naming the flag, the file, the gear and the gearing.
fn measured_gears_in_gearing(p: &Planned, run: &RunArgs) -> Result<(), Failure> {
    let value = |name: &str| {
        p.ctx
            .declares(name)
            .then(|| p.ctx.param(name).ok().map(str::to_owned))
            .flatten()
    };
    let Some(gearing_name) = value("gearing") else {
        return Ok(());
    };
    let from_hypothesis = value("hypothesis").and_then(|h| {
        h.split(hypotheses::SEPARATOR)
            .find_map(|layer| layer.strip_prefix("measured:").map(str::to_owned))
    });
    let (file, flag) = match (from_hypothesis, value("measured")) {
        (Some(f), _) => (
            f,
            if run.errors.is_some() {
                "--errors"
            } else {
                "--hypothesis"
            },
        ),
        (None, Some(m)) if !m.trim().is_empty() => (
            m.trim().to_owned(),
            if run.errors.is_some() {
                "--errors"
            } else {
                "--set measured"
            },
        ),
        _ => return Ok(()),
    };
    let Ok(h) = hypotheses::measured_file(&file) else {
        return Ok(()); // refused above with its own message
    };
    let gearing = match train::Gearing::builtin(&gearing_name) {
        Some(g) => g,
        None => train::Gearing::load(Path::new(&gearing_name))
            .map_err(|e| Failure::Bad(e.to_string()))?,
    };
    for (gear, _) in h.table().entries() {
        if gearing.gear(gear).is_none() {
            return Err(Failure::Bad(format!(
                "{flag}: {file}: gear {gear}: is not a gear of the gearing `{gearing_name}` ({} gears, e.g. {}), so its row would be silently unused",
                gearing.gears().len(),
                gearing
                    .gears()
                    .iter()
                    .take(3)
                    .map(|g| g.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            )));
        }
    }
    Ok(())
}

/// Checks, before anything is computed, that results can be written under `out` (`--out`):
/// it is a directory, or can be created as one, and a folder can be created in it. Then puts
/// back results a killed run left moved aside ([`registry::tidy`]). Refused (exit 2) naming
/// `--out` and the reason; nothing is left behind by the check.
fn check_out(out: &Path) -> Result<(), Failure> {
    let refuse = |why: String| Failure::Bad(format!("--out: {}: {why}", out.display()));
    if out.exists() && !out.is_dir() {
        return Err(refuse("exists and is not a directory".into()));
    }
    // The nearest folder that exists: where the first thing would be created.
    let mut base = out.to_path_buf();
    while !base.as_os_str().is_empty() && std::fs::symlink_metadata(&base).is_err() {
        base = base.parent().map(Path::to_path_buf).unwrap_or_default();
    }
    if base.as_os_str().is_empty() {
        base = PathBuf::from(".");
    }
    if !base.is_dir() {
        return Err(refuse(format!(
            "cannot be created: {} is not a directory",
            base.display()
        )));
    }
    let probe = base.join(format!(
        ".xtask-out-check.tmp-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos())
    ));
    std::fs::create_dir(&probe).map_err(|e| {
        refuse(format!(
            "cannot write results there (creating a folder in {} fails: {e})",
            base.display()
        ))
    })?;
    let _ = std::fs::remove_dir(&probe);
    registry::tidy(out)?;
    Ok(())
}

/// Prints reports on stdout (through `out`) as `--format` asks: Markdown or CSV as each
/// experiment finishes, JSON once at the end when there are several.
struct Printer<'a> {
    format: Format,
    /// Several experiments (or `all`): each is introduced by its id.
    several: bool,
    out: &'a mut dyn FnMut(&str) -> Result<(), Failure>,
    printed: usize,
    json: serde_json::Map<String, Value>,
    summary: Option<Value>,
}

impl<'a> Printer<'a> {
    fn new(
        format: Format,
        several: bool,
        out: &'a mut dyn FnMut(&str) -> Result<(), Failure>,
    ) -> Self {
        Printer {
            format,
            several,
            out,
            printed: 0,
            json: serde_json::Map::new(),
            summary: None,
        }
    }

    fn report(&mut self, e: &Experiment, report: &Report) -> Result<(), Failure> {
        let gap = if self.printed == 0 { "" } else { "\n" };
        self.printed += 1;
        match self.format {
            Format::Md => {
                if self.several {
                    (self.out)(&format!("{gap}## {}: {}\n\n", e.id, e.title))?;
                }
                (self.out)(&report.text())
            }
            Format::Csv => {
                let prefix = if self.several {
                    format!("{}: ", e.id)
                } else {
                    String::new()
                };
                (self.out)(&format!("{gap}{}", csv_tables(&report.tables, &prefix)))
            }
            Format::Json if self.several => {
                self.json
                    .insert(e.id.to_owned(), json_value(&report.to_json())?);
                Ok(())
            }
            Format::Json => (self.out)(&report.to_json()),
        }
    }

    /// The summary of `run all`: a table after the reports, or the `summary` member of the JSON.
    fn summary(&mut self, rows: &[summary::Row], seed: u64, threads: usize) -> Result<(), Failure> {
        let table = summary::table(rows);
        match self.format {
            Format::Md => (self.out)(&format!("\n{}", table.render())),
            Format::Csv => (self.out)(&format!(
                "\n{}",
                csv_tables(std::slice::from_ref(&table), "")
            )),
            Format::Json => {
                self.summary = Some(json_value(&summary::json(rows, seed, threads))?);
                Ok(())
            }
        }
    }

    /// Prints what was held back: the JSON of several experiments.
    fn finish(self) -> Result<(), Failure> {
        if self.format != Format::Json || !self.several {
            return Ok(());
        }
        let mut doc = serde_json::Map::new();
        doc.insert("experiments".into(), Value::Object(self.json));
        if let Some(s) = self.summary {
            doc.insert("summary".into(), s);
        }
        let text = serde_json::to_string_pretty(&Value::Object(doc))
            .map_err(|e| Failure::Internal(format!("internal error: cannot print JSON: {e}")))?;
        (self.out)(&format!("{text}\n"))
    }
}

/// Each table as CSV after a `# <prefix><title>` line, separated by blank lines.
fn csv_tables(tables: &[Table], prefix: &str) -> String {
    tables
        .iter()
        .map(|t| format!("# {prefix}{}\n{}", t.title, t.to_csv()))
        .collect::<Vec<_>>()
        .join("\n")
}

fn json_value(text: &str) -> Result<Value, Failure> {
    serde_json::from_str(text)
        .map_err(|e| Failure::Internal(format!("internal error: a report's JSON: {e}")))
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
    progress::experiment_starts();
    let start = Instant::now();
    let result = progress::watch(e.id, || {
        pool.install(|| catch_unwind(AssertUnwindSafe(|| (e.run)(ctx))))
    })
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
/// (through `out`, in the `--format` asked for) and written to `<out>/summary.md` and
/// `<out>/summary.json`.
///
/// `--set KEY=VALUE` goes to every experiment that declares KEY (a KEY none declares is refused
/// before anything runs), and so do the shorthands (`--trials`, `--gearing`, `--hypothesis`,
/// `--errors`); `--config` goes to every experiment that takes one (refused if none does).
/// Returns the summary rows; [`summary::exit_code`] turns them into the exit status.
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
                // Printed as written: tables.json lists run.json among the files.
                let report =
                    provenance::stamp(&report, p.e, &p.ctx, &p.sets, run.config.as_deref());
                printer.report(p.e, &report)?;
                let results = dir.join(p.e.id);
                registry::write_results(&results, &report).map(|()| {
                    note(&format!("results: {}", results.display()));
                    report
                })
            }
            Err(err) => Err(as_typed(err, p.e.id, run)),
        };
        if let Err(err) = &result {
            eprintln!("{}: {err}", p.e.id);
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
        &summary::markdown(&rows, run.seed, threads),
    )?;
    write_atomically(
        &dir.join("summary.json"),
        &summary::json(&rows, run.seed, threads),
    )?;
    note(&format!("summary: {}", dir.join("summary.md").display()));
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
        let report = provenance::stamp(&report, p.e, &p.ctx, &p.sets, run.config.as_deref());
        printer.report(p.e, &report)?;
        let dir = out.join(p.e.id);
        registry::write_results(&dir, &report)?;
        note(&format!("results: {}", dir.display()));
    }
    printer.finish()
}

/// `e` (of experiment `id`) as the user typed it: a refusal reached through a shorthand names
/// the shorthand (`--trials`, `--gearing`, `--errors`), not the `--set` or `--hypothesis` it
/// stands for.
fn as_typed(e: RunError, id: &str, run: &RunArgs) -> RunError {
    let RunError::BadInput {
        source,
        field,
        rule,
    } = e
    else {
        return e;
    };
    let shorthand = match (source.as_str(), field.as_str()) {
        ("--hypothesis", _) if run.errors.is_some() => Some(("--errors", field.clone())),
        ("--set", "trials") if run.trials.is_some() => Some(("--trials", id.to_owned())),
        ("--set", "gearing") if run.gearing.is_some() => Some(("--gearing", id.to_owned())),
        ("--set", "measured") if run.errors.is_some() => Some(("--errors", id.to_owned())),
        _ => None,
    };
    match shorthand {
        Some((flag, field)) => RunError::bad(flag, field, rule),
        None => RunError::BadInput {
            source,
            field,
            rule,
        },
    }
}

/// `run <id> --shard K/N`: runs the experiment in shard mode, discards its report and writes
/// the recorded trials to `<out>/<id>/partial-K-of-N.json` (through a temporary file renamed
/// into place; other files of the directory are left alone, so shards may share it).
fn run_shard(
    planned: &Planned,
    ctx: Context,
    run: &RunArgs,
    pool: &rayon::ThreadPool,
    out: &Path,
) -> Result<(), Failure> {
    let e = planned.e;
    let registry::TrialMode::Shard(shard) = ctx.trial_mode() else {
        return Err(Failure::Internal(
            "internal error: a shard run without a shard".into(),
        ));
    };
    execute(e, &ctx, pool)
        .0
        .map_err(|err| as_typed(err, e.id, run))?;
    let mut partial = shard::Partial::new(e.id, run.seed, &planned.sets, ctx.config(), shard);
    partial.batches = ctx.recorded();
    let text = partial.to_json()?;
    let dir = out.join(e.id);
    std::fs::create_dir_all(&dir).map_err(|err| {
        Failure::Internal(format!(
            "internal error: cannot create {}: {err}",
            dir.display()
        ))
    })?;
    registry::tidy(&dir)?;
    let path = dir.join(shard::file_name(shard));
    write_atomically(&path, &text)?;
    let (mut here, mut whole) = (0, 0);
    for b in partial.batches.values() {
        if b.whole {
            whole += b.values.len();
        } else {
            here += b.values.len();
        }
    }
    let plural =
        |n: usize, one: &str, more: &str| format!("{n} {}", if n == 1 { one } else { more });
    note(&format!(
        "partial: {} (shard {shard} of {}: {}, {} computed here{}); join the {} with `cargo xtask merge`",
        path.display(),
        e.id,
        plural(partial.batches.len(), "trial batch", "trial batches"),
        plural(here, "trial", "trials"),
        if whole > 0 {
            format!(", {whole} more in batches every shard runs whole")
        } else {
            String::new()
        },
        plural(shard.count() as usize, "shard", "shards")
    ));
    if partial.batches.is_empty() {
        note(&format!(
            "note: {} runs no trials that shards can split: every shard computes all of it, and the merge computes it again",
            e.id
        ));
    }
    Ok(())
}

/// `merge`: finds and reads the partial files, checks that they come from one sharded command
/// and cover every shard once, replays the experiment from their records, then prints and
/// writes its results as `run` would. Nothing is written unless every check passes.
fn merge(exps: &Registry, m: &MergeArgs) -> Result<(), Failure> {
    let files = shard::find(&m.inputs)?;
    let mut parts = Vec::with_capacity(files.len());
    for f in files.clone() {
        let (partial, shard) = shard::read(&f)?;
        parts.push((f, partial, shard));
    }
    shard::agree(&parts)?;
    let header = parts
        .first()
        .map(|(_, p, _)| p.clone())
        .ok_or_else(|| Failure::Internal("internal error: no partial file".into()))?;
    let e = lookup(exps, &header.experiment)?;
    let records: Vec<registry::ShardRecords> = parts
        .into_iter()
        .map(|(f, p, shard)| registry::ShardRecords {
            source: f.display().to_string(),
            shard,
            records: p.batches,
        })
        .collect();
    let merged = registry::merge_records(&records)?;
    drop(records);
    let threads = m.threads.unwrap_or_else(default_threads);
    let ctx = Context::new(e, header.seed, threads, &header.sets, header.config_file())?
        .with_replay(merged);
    let out = m.out.clone().unwrap_or_else(default_out);
    check_out(&out)?;
    keeps_partials(&out.join(e.id), &files, m.out.is_some())?;
    let pool = make_pool(threads)?;
    let report = execute(e, &ctx, &pool).0?;
    if let Some(batch) = ctx.unclaimed().first() {
        return Err(Failure::Bad(format!(
            "merge: batch `{batch}`: was recorded by the shards but not asked for by this run of {}: the shards ran different inputs or a different build",
            e.id
        )));
    }
    let config = header.config.as_ref().map(|c| PathBuf::from(&c.path));
    let report = provenance::stamp(&report, e, &ctx, &header.sets, config.as_deref());
    let mut stdout = |s: &str| print(s);
    Printer::new(m.format, false, &mut stdout).report(e, &report)?;
    let dir = out.join(e.id);
    registry::write_results(&dir, &report)?;
    note(&format!(
        "results: {} (merged from {} shards)",
        dir.display(),
        header.shards
    ));
    Ok(())
}

/// A merge replaces `dir` (`<out>/<id>`) whole: refused (exit 2) when it holds one of the
/// partial files being merged, which the replacement would delete.
fn keeps_partials(dir: &Path, partials: &[PathBuf], out_given: bool) -> Result<(), Failure> {
    let Ok(dir) = std::fs::canonicalize(dir) else {
        return Ok(());
    };
    for f in partials {
        if let Ok(f) = std::fs::canonicalize(f)
            && f.starts_with(&dir)
        {
            return Err(Failure::Bad(format!(
                "--out: {}: the merge would replace {}, which holds the partial file {} being merged; give another --out{}",
                dir.parent().unwrap_or(&dir).display(),
                dir.display(),
                f.display(),
                if out_given {
                    ""
                } else {
                    " (the shards wrote into the default results folder)"
                }
            )));
        }
    }
    Ok(())
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;
    use registry::Param;

    fn fine(ctx: &Context) -> Result<Report, RunError> {
        let mut t = Table::new("Fine", ["n"]);
        t.row(vec![ctx.param("n")?.to_owned()]);
        Ok(Report {
            tables: vec![t],
            trials: ctx.u64("n")?,
            engagements: 10,
            agreement: Some(registry::Agreement {
                consistent: 2,
                differ: 1,
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
            shard: None,
            trials: None,
            gearing: None,
            hypothesis: None,
            errors: None,
            format: Format::Md,
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
        // n = 7 is not the default, so no agreement with the paper is judged.
        assert!(md.contains("| a-fine ") && !md.contains("2 / 1"), "{md}");
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
    fn numbers_of_hundreds_of_digits_are_shortened_and_nothing_else() {
        let huge = format!("{}", 1e308);
        assert!(huge.len() > 300);
        assert_eq!(
            one_line(&format!(
                "m.ron: centre_distance: must exceed {huge} (got 5)"
            )),
            "m.ron: centre_distance: must exceed 1e308 (got 5)"
        );
        assert_eq!(
            short_numbers(&format!("= {huge}.5, and -{huge}")),
            "= 1e308, and -1e308"
        );
        for kept in [
            "/tmp/xtask-bad-1795543045569589936/e.ron: x",
            "seed 18446744073709551615 is fine",
            "gear b1: 0.25 é",
        ] {
            assert_eq!(short_numbers(kept), kept);
        }
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
