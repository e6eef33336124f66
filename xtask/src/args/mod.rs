//! Command-line parsing, by hand: every command and its flags, and `-q` / `-v` anywhere (`report`,
//! `fuzz` and `replay` take `-q` among their own flags).

use std::path::{Path, PathBuf};

use registry::{MAX_TRIALS, Shard};

/// Seed used when `--seed` is not given.
pub const DEFAULT_SEED: u64 = 2025;

/// The most worker threads `--threads` may ask for.
pub const MAX_THREADS: usize = 1024;

/// How much goes to stderr besides errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verbosity {
    /// `-q`: no progress bars, no logs, no notes; errors only.
    Quiet,
    /// The default: progress bars on a terminal, warnings, a note of where results went.
    Normal,
    /// `-v`: as normal, plus debug logs (per-experiment timing, per-batch sizes).
    Verbose,
}

/// What `run` and `merge` print on stdout (results files are written the same way whatever it is).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// The tables as Markdown, as `table.md` holds them.
    Md,
    /// Each table as CSV after a `# title` line, tables separated by a blank line.
    Csv,
    /// The report as `tables.json` holds it.
    Json,
}

/// What the command line asks for.
#[derive(Debug, PartialEq)]
pub enum Command {
    /// No arguments: commands and the table of experiments.
    Overview,
    /// `list`: ids one per line.
    List,
    /// `hypotheses`: the manufacturing-error hypotheses and their parameters.
    Hypotheses,
    /// `rules`: the event rules.
    Rules,
    /// `help` (no id: usage) or `help <id>`.
    Help(Option<String>),
    /// `run <id>... [flags]`, or `run all [flags]`.
    Run(RunArgs),
    /// `bench [--only table5|all] [--threads 1,2]`.
    Bench(BenchArgs),
    /// `merge DIR|FILE... [--out DIR] [--threads N] [--format F]`.
    Merge(MergeArgs),
    /// `report [--out DIR] [-q]`.
    Report(ReportArgs),
    /// `fuzz [--seconds N | --execs N] [--seed S] [--findings DIR]`.
    Fuzz(FuzzArgs),
    /// `replay <experiment> <cell> [<trial>] [flags]`.
    Replay(ReplayArgs),
}

/// Arguments of `merge`.
#[derive(Debug, PartialEq, Eq)]
pub struct MergeArgs {
    /// Partial files, or directories searched for them, in the order given (at least one).
    pub inputs: Vec<PathBuf>,
    /// `--out`; `None`: `<workspace>/results`.
    pub out: Option<PathBuf>,
    /// `--threads`, at least 1; `None`: available parallelism.
    pub threads: Option<usize>,
    /// `--format`: what is printed.
    pub format: Format,
}

/// What `bench` times.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BenchTarget {
    /// The `table5` experiment alone.
    Table5,
    /// Every registered experiment, as `run all` runs them.
    All,
}

impl BenchTarget {
    /// The name used on the command line and in the printed table.
    pub fn name(self) -> &'static str {
        match self {
            BenchTarget::Table5 => "table5",
            BenchTarget::All => "all",
        }
    }
}

/// Arguments of `bench`.
#[derive(Debug, PartialEq, Eq)]
pub struct BenchArgs {
    /// Targets in order (default: `table5`, then `all`).
    pub targets: Vec<BenchTarget>,
    /// Thread counts, each at least 1, in order (default: 1, 2).
    pub threads: Vec<usize>,
}

/// Arguments of `run`.
#[derive(Debug, PartialEq, Eq)]
pub struct RunArgs {
    /// Experiment ids as given (`all` included).
    pub ids: Vec<String>,
    /// `--seed`, default [`DEFAULT_SEED`].
    pub seed: u64,
    /// `--threads`, at least 1; `None`: available parallelism.
    pub threads: Option<usize>,
    /// `--out`; `None`: `<workspace>/results`.
    pub out: Option<PathBuf>,
    /// `--config`.
    pub config: Option<PathBuf>,
    /// `--set key=value`, in order.
    pub sets: Vec<(String, String)>,
    /// `--shard K/N`: compute only this shard's trials and write a partial file.
    pub shard: Option<Shard>,
    /// `--trials N`: the `trials` parameter of every experiment that declares one.
    pub trials: Option<u64>,
    /// `--gearing FILE`: the `gearing` parameter of every experiment that declares one.
    pub gearing: Option<PathBuf>,
    /// `--hypothesis NAME`: the `hypothesis` parameter of every experiment that declares one.
    pub hypothesis: Option<String>,
    /// `--errors FILE`: a table of measured per-gear errors, as `measured=FILE` where an
    /// experiment declares `measured`, else as `hypothesis=measured:FILE`.
    pub errors: Option<PathBuf>,
    /// `--format`: what is printed.
    pub format: Format,
}

/// A command line that cannot be parsed: exit status 2.
#[derive(Debug, PartialEq, Eq)]
pub enum ArgError {
    /// Wrong shape (unknown command or flag, missing value): print usage too.
    Usage(String),
    /// Right shape, bad value.
    Value(String),
}

/// Parses the arguments after the program name: `-q` / `--quiet` and `-v` / `--verbose` may
/// stand anywhere (at most one of them); the rest is the command ([`parse`]). `report`, `fuzz`
/// and `replay` parse their own `-q` (and `-q report` is `report -q`, likewise `fuzz` and
/// `replay`); their verbosity is [`Verbosity::Normal`].
pub fn parse_invocation(args: &[String]) -> Result<(Command, Verbosity), ArgError> {
    // `-q` goes anywhere on the line, as the usage says: `cargo xtask -q report`.
    let moved: Vec<String>;
    let args = match args.split_first() {
        Some((q, rest))
            if (q == "-q" || q == "--quiet")
                && rest
                    .first()
                    .is_some_and(|c| ["report", "fuzz", "replay"].contains(&c.as_str())) =>
        {
            moved = rest.iter().cloned().chain(["-q".to_owned()]).collect();
            moved.as_slice()
        }
        _ => args,
    };
    // `COMMAND --help` (or `COMMAND -h` alone) asks for the usage, whatever the command.
    if let Some((_, rest)) = args.split_first()
        && (rest.iter().any(|a| a == "--help") || rest == ["-h"])
    {
        return Ok((Command::Help(None), Verbosity::Normal));
    }
    let own = match args.split_first().map(|(c, r)| (c.as_str(), r)) {
        Some(("report", rest)) => Some(Command::Report(parse_report(rest)?)),
        Some(("fuzz", rest)) => Some(Command::Fuzz(parse_fuzz(rest)?)),
        Some(("replay", rest)) => Some(Command::Replay(parse_replay(rest)?)),
        _ => None,
    };
    if let Some(cmd) = own {
        return Ok((cmd, Verbosity::Normal));
    }
    let mut verbosity = Verbosity::Normal;
    let mut rest = Vec::with_capacity(args.len());
    for a in args {
        let v = match a.as_str() {
            "-q" | "--quiet" => Verbosity::Quiet,
            "-v" | "--verbose" => Verbosity::Verbose,
            _ => {
                rest.push(a.clone());
                continue;
            }
        };
        if verbosity != Verbosity::Normal && verbosity != v {
            return Err(ArgError::Usage(
                "-q (quiet) and -v (verbose) cannot be combined".into(),
            ));
        }
        verbosity = v;
    }
    Ok((parse(&rest)?, verbosity))
}

/// Parses the arguments after the program name (without `-q` / `-v`).
pub fn parse(args: &[String]) -> Result<Command, ArgError> {
    let Some((cmd, rest)) = args.split_first() else {
        return Ok(Command::Overview);
    };
    match cmd.as_str() {
        "list" => {
            no_more(cmd, rest)?;
            Ok(Command::List)
        }
        "hypotheses" => {
            no_more(cmd, rest)?;
            Ok(Command::Hypotheses)
        }
        "rules" => {
            no_more(cmd, rest)?;
            Ok(Command::Rules)
        }
        "help" | "--help" | "-h" => match rest {
            [] => Ok(Command::Help(None)),
            [id] => Ok(Command::Help(Some(id.clone()))),
            _ => Err(ArgError::Usage(
                "help takes at most one experiment id".into(),
            )),
        },
        "run" => parse_run(rest).map(Command::Run),
        "bench" => parse_bench(rest).map(Command::Bench),
        "merge" => parse_merge(rest).map(Command::Merge),
        other => Err(ArgError::Usage(format!("unknown command `{other}`"))),
    }
}

fn no_more(cmd: &str, rest: &[String]) -> Result<(), ArgError> {
    match rest.first() {
        None => Ok(()),
        Some(extra) => Err(ArgError::Usage(format!(
            "`{cmd}` takes no arguments (got `{extra}`)"
        ))),
    }
}

/// The flag of `arg` and its value (`--flag=value`, or `--flag value` with the value taken from
/// `rest`) when the flag is one of `known`; `Ok(None)` for anything else, which the caller
/// refuses in its own words. A known flag without a value is `Err("--flag needs a value")`.
pub(crate) fn flag_value<'a>(
    arg: &'a str,
    rest: &mut std::slice::Iter<'_, String>,
    known: &[&str],
) -> Result<Option<(&'a str, String)>, String> {
    let (flag, inline) = match arg.split_once('=') {
        Some((f, v)) if f.starts_with("--") => (f, Some(v.to_owned())),
        _ => (arg, None),
    };
    if !known.contains(&flag) {
        return Ok(None);
    }
    let value = match inline {
        Some(v) => v,
        None => match rest.next() {
            Some(v) if !v.starts_with("--") => v.clone(),
            _ => return Err(format!("{flag} needs a value")),
        },
    };
    Ok(Some((flag, value)))
}

/// Refuses a flag given twice (`--seed 1 --seed 2`: which one was meant?), and `--set` of the
/// same key twice; `seen` holds what was given so far.
fn once(seen: &mut Vec<String>, flag: &str, value: &str) -> Result<(), ArgError> {
    let what = if flag == "--set" {
        match value.split_once('=') {
            Some((key, _)) => format!("--set {}=...", key.trim()),
            None => return Ok(()),
        }
    } else {
        flag.to_owned()
    };
    if seen.contains(&what) {
        return Err(ArgError::Usage(format!("{what} given twice: give it once")));
    }
    seen.push(what);
    Ok(())
}

fn parse_run(args: &[String]) -> Result<RunArgs, ArgError> {
    let mut run = RunArgs {
        ids: Vec::new(),
        seed: DEFAULT_SEED,
        threads: None,
        out: None,
        config: None,
        sets: Vec::new(),
        shard: None,
        trials: None,
        gearing: None,
        hypothesis: None,
        errors: None,
        format: Format::Md,
    };
    let mut seen = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if !arg.starts_with('-') {
            run.ids.push(arg.clone());
            continue;
        }
        const RUN_FLAGS: [&str; 11] = [
            "--seed",
            "--threads",
            "--out",
            "--config",
            "--set",
            "--gearing",
            "--hypothesis",
            "--shard",
            "--trials",
            "--errors",
            "--format",
        ];
        let Some((flag, value)) = flag_value(arg, &mut it, &RUN_FLAGS).map_err(ArgError::Usage)?
        else {
            return Err(ArgError::Usage(format!("unknown flag `{arg}`")));
        };
        once(&mut seen, flag, &value)?;
        set_run_flag(&mut run, flag, value)?;
    }
    check_run(&run)?;
    Ok(run)
}

/// Sets `run`'s field for one flag of `run` and its value (`--set` adds a setting).
fn set_run_flag(run: &mut RunArgs, flag: &str, value: String) -> Result<(), ArgError> {
    match flag {
        "--seed" => {
            run.seed = value.trim().parse().map_err(|_| {
                ArgError::Value(format!(
                    "--seed: must be an integer from 0 to {} (got `{value}`)",
                    u64::MAX
                ))
            })?;
        }
        "--threads" => run.threads = Some(threads(&value)?),
        "--out" => run.out = Some(out(value)?),
        "--format" => run.format = format(&value)?,
        "--trials" => run.trials = Some(trials(&value)?),
        "--shard" => {
            run.shard = Some(Shard::parse(&value).map_err(|e| ArgError::Value(e.to_string()))?);
        }
        "--config" => {
            if value.is_empty() {
                return Err(ArgError::Value("--config: must not be empty".into()));
            }
            run.config = Some(PathBuf::from(value));
        }
        // The error hypothesis of experiments that manufacture gears: `--set hypothesis=NAME`.
        "--hypothesis" => run.hypothesis = Some(not_empty(flag, value)?),
        // The gearing file of train experiments: the same as `--set gearing=FILE`.
        "--gearing" => run.gearing = Some(PathBuf::from(not_empty(flag, value)?)),
        "--errors" => run.errors = Some(PathBuf::from(not_empty(flag, value)?)),
        _ => {
            let Some((key, val)) = value.split_once('=').filter(|(k, _)| !k.trim().is_empty())
            else {
                return Err(ArgError::Usage(format!(
                    "--set takes KEY=VALUE (got `{value}`)"
                )));
            };
            run.sets.push((key.trim().to_owned(), val.to_owned()));
        }
    }
    Ok(())
}

/// Refuses flags of `run` that cannot go together: no id, `all` beside ids, a flag beside the
/// `--set` it stands for, `--errors` with `--hypothesis`, `--shard` of more than one experiment.
fn check_run(run: &RunArgs) -> Result<(), ArgError> {
    if run.ids.is_empty() {
        return Err(ArgError::Usage(
            "run needs at least one experiment id (or `all`)".into(),
        ));
    }
    if run.ids.len() > 1 && run.ids.iter().any(|id| id == "all") {
        return Err(ArgError::Usage(format!(
            "`run all` runs every experiment and takes no other ids (got `{}`): give either `all` or experiment ids, not both",
            run.ids.join(" ")
        )));
    }
    for (flag, given, key) in [
        ("--trials", run.trials.is_some(), "trials"),
        ("--gearing", run.gearing.is_some(), "gearing"),
        ("--hypothesis", run.hypothesis.is_some(), "hypothesis"),
        ("--errors", run.errors.is_some(), "hypothesis"),
        ("--errors", run.errors.is_some(), "measured"),
    ] {
        if given && run.sets.iter().any(|(k, _)| k == key) {
            return Err(ArgError::Usage(format!(
                "{flag} and --set {key}=... cannot be combined: give one of them"
            )));
        }
    }
    if run.errors.is_some() && run.hypothesis.is_some() {
        return Err(ArgError::Usage(
            "--errors and --hypothesis cannot be combined: --errors chooses the measured hypothesis with your table"
                .into(),
        ));
    }
    if run.shard.is_some() && (run.ids.len() != 1 || run.is_all()) {
        return Err(ArgError::Usage(format!(
            "--shard splits the trials of one experiment: give exactly one experiment id, not `{}` (`run all` and several ids cannot be sharded)",
            run.ids.join(" ")
        )));
    }
    Ok(())
}

/// The value of a counting flag: an integer from 1 to `max`; `limit` names what the maximum is
/// (empty when it needs no words).
fn count(flag: &str, value: &str, max: u64, limit: &str) -> Result<u64, ArgError> {
    let n: u64 = value.trim().parse().map_err(|_| {
        ArgError::Value(format!(
            "{flag}: must be an integer from 1 to {max} (got `{value}`)"
        ))
    })?;
    if n == 0 {
        return Err(ArgError::Value(format!(
            "{flag}: must be at least 1 (got `0`)"
        )));
    }
    if n > max {
        return Err(ArgError::Value(format!(
            "{flag}: must be at most {max} ({limit}got `{value}`)"
        )));
    }
    Ok(n)
}

/// The value of `--threads`: an integer from 1 to [`MAX_THREADS`].
fn threads(value: &str) -> Result<usize, ArgError> {
    // MAX_THREADS fits both types, so neither conversion loses anything.
    count("--threads", value, MAX_THREADS as u64, "").map(|n| n as usize)
}

/// The value of `--trials`: an integer from 1 to [`MAX_TRIALS`].
fn trials(value: &str) -> Result<u64, ArgError> {
    count("--trials", value, MAX_TRIALS, "the limit on trials; ")
}

/// The value of `--format`: `md`, `csv` or `json`.
fn format(value: &str) -> Result<Format, ArgError> {
    match value.trim() {
        "md" => Ok(Format::Md),
        "csv" => Ok(Format::Csv),
        "json" => Ok(Format::Json),
        _ => Err(ArgError::Value(format!(
            "--format: must be md, csv or json (got `{value}`)"
        ))),
    }
}

/// A value that must not be empty.
fn not_empty(flag: &str, value: String) -> Result<String, ArgError> {
    if value.trim().is_empty() {
        return Err(ArgError::Value(format!("{flag}: must not be empty")));
    }
    Ok(value)
}

/// The value of `--out`: not empty.
fn out(value: String) -> Result<PathBuf, ArgError> {
    if value.is_empty() {
        return Err(ArgError::Value("--out: must not be empty".into()));
    }
    Ok(PathBuf::from(value))
}

fn parse_merge(args: &[String]) -> Result<MergeArgs, ArgError> {
    let mut merge = MergeArgs {
        inputs: Vec::new(),
        out: None,
        threads: None,
        format: Format::Md,
    };
    let mut seen = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if !arg.starts_with('-') {
            merge.inputs.push(PathBuf::from(arg));
            continue;
        }
        let known = ["--out", "--threads", "--format"];
        let Some((flag, value)) = flag_value(arg, &mut it, &known).map_err(ArgError::Usage)? else {
            return Err(ArgError::Usage(format!(
                "unknown flag `{arg}` of merge (the seed, parameters and config come from the partial files)"
            )));
        };
        once(&mut seen, flag, &value)?;
        match flag {
            "--out" => merge.out = Some(out(value)?),
            "--format" => merge.format = format(&value)?,
            _ => merge.threads = Some(threads(&value)?),
        }
    }
    if merge.inputs.is_empty() {
        return Err(ArgError::Usage(
            "merge needs the partial files of `run <id> --shard K/N`, or directories holding them"
                .into(),
        ));
    }
    Ok(merge)
}

impl RunArgs {
    /// Is this `run all`?
    pub fn is_all(&self) -> bool {
        self.ids.len() == 1 && self.ids[0] == "all"
    }
}

fn parse_bench(args: &[String]) -> Result<BenchArgs, ArgError> {
    let mut bench = BenchArgs {
        targets: vec![BenchTarget::Table5, BenchTarget::All],
        threads: vec![1, 2],
    };
    let mut seen = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let known = ["--only", "--threads"];
        let Some((flag, value)) = flag_value(arg, &mut it, &known).map_err(ArgError::Usage)? else {
            return Err(ArgError::Usage(if arg.starts_with('-') {
                format!("unknown flag `{arg}` of bench")
            } else {
                format!("bench takes no ids (got `{arg}`); use --only table5|all")
            }));
        };
        // As every other command: a flag given twice is refused, not won by the last.
        once(&mut seen, flag, &value)?;
        if flag == "--only" {
            bench.targets = vec![match value.trim() {
                "table5" => BenchTarget::Table5,
                "all" => BenchTarget::All,
                _ => {
                    return Err(ArgError::Value(format!(
                        "--only: must be `table5` or `all` (got `{value}`)"
                    )));
                }
            }];
        } else {
            let mut threads = Vec::new();
            for part in value.split(',') {
                let n: usize = part.trim().parse().map_err(|_| {
                    ArgError::Value(format!(
                        "--threads: must be positive integers separated by commas, e.g. 1,2 (got `{value}`)"
                    ))
                })?;
                if n == 0 {
                    return Err(ArgError::Value(format!(
                        "--threads: every count must be at least 1 (got `{value}`)"
                    )));
                }
                // The same limit as `run --threads`: a pool beyond it cannot be built.
                if n > MAX_THREADS {
                    return Err(ArgError::Value(format!(
                        "--threads: every count must be at most {MAX_THREADS} (got `{value}`)"
                    )));
                }
                threads.push(n);
            }
            bench.threads = threads;
        }
    }
    Ok(bench)
}

/// Arguments of `report`.
#[derive(Debug, PartialEq, Eq)]
pub struct ReportArgs {
    /// `--out`; `None`: `<workspace>/results`.
    pub out: Option<PathBuf>,
    /// `-q` / `--quiet`: no note on stderr.
    pub quiet: bool,
    /// `--bundle FILE`: also write one `.tar.gz` of the results and their inputs.
    pub bundle: Option<PathBuf>,
}

/// Parses the arguments of `report`: `--out DIR`, `--bundle FILE` and `-q`.
fn parse_report(args: &[String]) -> Result<ReportArgs, ArgError> {
    let mut out = None;
    let mut bundle = None;
    let mut quiet = false;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "-q" || arg == "--quiet" {
            quiet = true;
            continue;
        }
        let (flag, value) = match arg.split_once('=') {
            Some((f @ ("--out" | "--bundle"), v)) => (f, v.to_owned()),
            None if arg == "--out" || arg == "--bundle" => match it.next() {
                Some(v) if !v.starts_with("--") => (arg.as_str(), v.clone()),
                _ => return Err(ArgError::Usage(format!("{arg} needs a value"))),
            },
            _ => {
                return Err(ArgError::Usage(format!(
                    "report takes only --out DIR, --bundle FILE and -q (got `{arg}`)"
                )));
            }
        };
        let slot = if flag == "--out" {
            &mut out
        } else {
            &mut bundle
        };
        if slot.is_some() {
            return Err(ArgError::Usage(format!("{flag} given twice")));
        }
        if value.is_empty() {
            return Err(ArgError::Value(format!("{flag}: must not be empty")));
        }
        *slot = Some(PathBuf::from(value));
    }
    Ok(ReportArgs { out, quiet, bundle })
}

/// `fuzz`'s run time when neither `--seconds` nor `--execs` is given.
pub const DEFAULT_FUZZ_SECONDS: f64 = 60.0;

/// How long to fuzz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Budget {
    /// Wall-clock seconds, shared equally between the targets.
    Seconds(f64),
    /// Executions per target.
    Execs(u64),
}

/// Arguments of `fuzz`.
#[derive(Debug, PartialEq)]
pub struct FuzzArgs {
    /// `--seconds N` or `--execs N`, default [`DEFAULT_FUZZ_SECONDS`] seconds.
    pub budget: Budget,
    /// `--seed`, default [`DEFAULT_SEED`].
    pub seed: u64,
    /// `--findings`, default `<workspace>/target/fuzz-findings`.
    pub findings: PathBuf,
    /// `-q` / `--quiet`: no note of what is fuzzed (findings are still named).
    pub quiet: bool,
}

/// Parses the arguments of `fuzz`, as `run` parses its own: a flag given twice is refused, and
/// so are `--seconds` and `--execs` together (both set how long to fuzz); `-q` anywhere.
fn parse_fuzz(args: &[String]) -> Result<FuzzArgs, ArgError> {
    let mut opts = FuzzArgs {
        budget: Budget::Seconds(DEFAULT_FUZZ_SECONDS),
        seed: DEFAULT_SEED,
        findings: default_findings(),
        quiet: false,
    };
    let mut seen = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "-q" || arg == "--quiet" {
            opts.quiet = true;
            continue;
        }
        let known = ["--seconds", "--execs", "--seed", "--findings"];
        let Some((flag, value)) = flag_value(arg, &mut it, &known).map_err(ArgError::Usage)? else {
            return Err(ArgError::Usage(format!(
                "fuzz takes --seconds N or --execs N, --seed S, --findings DIR and -q (got `{arg}`)"
            )));
        };
        once(&mut seen, flag, &value)?;
        let budgets = ["--seconds", "--execs"];
        if budgets.contains(&flag)
            && budgets
                .iter()
                .filter(|b| seen.iter().any(|s| s == *b))
                .count()
                > 1
        {
            return Err(ArgError::Usage(
                "--seconds and --execs cannot be combined: give one of them (how long to fuzz)"
                    .into(),
            ));
        }
        match flag {
            "--seconds" => {
                opts.budget = value
                    .trim()
                    .parse()
                    .ok()
                    .filter(|s: &f64| s.is_finite() && *s > 0.0 && *s <= 86_400.0)
                    .map(Budget::Seconds)
                    .ok_or_else(|| {
                        ArgError::Value(format!(
                            "--seconds: must be a number of seconds above 0, at most 86400 (got `{value}`)"
                        ))
                    })?;
            }
            "--execs" => {
                opts.budget = value
                    .trim()
                    .parse()
                    .ok()
                    .filter(|n: &u64| *n > 0)
                    .map(Budget::Execs)
                    .ok_or_else(|| {
                        ArgError::Value(format!(
                            "--execs: must be a positive number of executions per target (got `{value}`)"
                        ))
                    })?;
            }
            "--seed" => {
                opts.seed = value.trim().parse().map_err(|_| {
                    ArgError::Value(format!(
                        "--seed: must be an integer from 0 to {} (got `{value}`)",
                        u64::MAX
                    ))
                })?;
            }
            _ => {
                if value.is_empty() {
                    return Err(ArgError::Value("--findings: must not be empty".into()));
                }
                opts.findings = PathBuf::from(value);
            }
        }
    }
    Ok(opts)
}

/// `<workspace>/target/fuzz-findings`.
fn default_findings() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .unwrap_or(manifest)
        .join("target")
        .join("fuzz-findings")
}

/// Arguments of `replay`.
#[derive(Debug, PartialEq, Eq)]
pub struct ReplayArgs {
    /// The experiment.
    pub id: String,
    /// The cell of its jam table.
    pub cell: String,
    /// The trial; `None`: list the cell's failed trials.
    pub trial: Option<u64>,
    /// `--seed`, default [`DEFAULT_SEED`].
    pub seed: u64,
    /// `--set KEY=VALUE`, in order, then `--trials N` as `trials=N`.
    pub sets: Vec<(String, String)>,
    /// `--out`; `None`: `<workspace>/results`.
    pub out: Option<PathBuf>,
    /// `-q` / `--quiet`: no note of where the results went.
    pub quiet: bool,
}

const REPLAY_USAGE: &str = "replay <experiment> <cell> [<trial>] [--seed S] [--trials N] [--set KEY=VALUE]... [--out DIR] [-q]";

/// A usage error of `replay`, followed by its usage.
fn replay_usage(what: impl std::fmt::Display) -> ArgError {
    ArgError::Usage(format!("{what}\nusage: cargo xtask {REPLAY_USAGE}"))
}

/// The value of a flag of `replay`: `--flag=V` or `--flag V`.
fn replay_value(
    arg: &str,
    flag: &str,
    it: &mut std::slice::Iter<'_, String>,
) -> Result<Option<String>, ArgError> {
    if let Some(v) = arg.strip_prefix(flag).and_then(|r| r.strip_prefix('=')) {
        return Ok(Some(v.to_owned()));
    }
    if arg != flag {
        return Ok(None);
    }
    match it.next() {
        Some(v) if !v.starts_with("--") => Ok(Some(v.clone())),
        _ => Err(replay_usage(format!("{flag} needs a value"))),
    }
}

/// Parses the arguments of `replay`.
pub(crate) fn parse_replay(args: &[String]) -> Result<ReplayArgs, ArgError> {
    let mut positional = Vec::new();
    let (mut seed, mut sets, mut out, mut quiet) = (None, Vec::new(), None, false);
    let mut trials: Option<String> = None;
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "-q" || arg == "--quiet" {
            quiet = true;
        } else if let Some(v) = replay_value(arg, "--seed", &mut it)? {
            if seed.is_some() {
                return Err(replay_usage("--seed given twice"));
            }
            seed = Some(v.parse::<u64>().map_err(|_| {
                ArgError::Value(format!(
                    "--seed: `{v}` is not a whole number 0 to {}",
                    u64::MAX
                ))
            })?);
        } else if let Some(v) = replay_value(arg, "--set", &mut it)? {
            let (k, val) = v
                .split_once('=')
                .ok_or_else(|| ArgError::Value(format!("--set: `{v}` must be KEY=VALUE")))?;
            sets.push((k.trim().to_owned(), val.trim().to_owned()));
        } else if let Some(v) = replay_value(arg, "--trials", &mut it)? {
            // As `run` takes it: the experiment's `trials` parameter, so that a replay names the
            // same trials as the run it follows.
            if trials.is_some() {
                return Err(replay_usage("--trials given twice"));
            }
            trials = Some(v);
        } else if let Some(v) = replay_value(arg, "--out", &mut it)? {
            if out.is_some() {
                return Err(replay_usage("--out given twice"));
            }
            if v.is_empty() {
                return Err(ArgError::Value("--out: must not be empty".into()));
            }
            out = Some(PathBuf::from(v));
        } else if arg.starts_with('-') && arg.parse::<f64>().is_err() {
            return Err(replay_usage(format!("replay does not take `{arg}`")));
        } else {
            positional.push(arg.clone());
        }
    }
    if let Some(v) = trials {
        if sets.iter().any(|(k, _)| k == "trials") {
            return Err(ArgError::Value(
                "--trials: give the trials once, as --trials N or as --set trials=N".into(),
            ));
        }
        sets.push(("trials".to_owned(), v));
    }
    let (id, cell, trial) = match positional.as_slice() {
        [id, cell] => (id.clone(), cell.clone(), None),
        [id, cell, t] => {
            let t = t.parse::<u64>().map_err(|_| {
                ArgError::Value(format!(
                    "replay: trial `{t}` is not a trial index (0, 1, 2, ...)"
                ))
            })?;
            (id.clone(), cell.clone(), Some(t))
        }
        _ => {
            return Err(replay_usage(
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

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests;
