//! What the runner prints about itself: usage, the overview, and `help` for an experiment, a hypothesis or an event rule.

use std::path::Path;

use registry::{Entry, Table};
use serde_json::Value;

use crate::args::{DEFAULT_SEED, MAX_THREADS};
use crate::shared::{Registry, default_out, default_threads};

pub(crate) fn usage() -> String {
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
  cargo xtask replay <experiment> <cell> [<trial>] [--seed S] [--trials N] [--set KEY=VALUE]... [--out DIR]
                                rebuild one trial of table3, table4, table5 or tableI from
                                its random stream (cell as the table names it:
                                B/m3-e3, B/70/m3-e3, 0.050/m3-e3, 0.050/0.7/e4-f1)
                                and print its events; writes pair.ron to rerun it
                                with `run pair`;
                                with no trial, list the cell's failed trials
  cargo xtask report [--out DIR] [--bundle FILE] [-q]
                                write <out>/index.html: one self-contained page with
                                every experiment's tables, figures and provenance;
                                with --bundle, also FILE: one .tar.gz of the results
                                and the input files their runs read (checked against
                                the SHA-256 each run recorded)
  cargo xtask fuzz [--seconds N | --execs N] [--seed S] [--findings DIR] [-q]
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
had bad input. Stopped by a signal: 130 (SIGINT), 143 (SIGTERM), 129 (SIGHUP), with what was
being written removed. A run holding the results of the same experiment in the same --out is
never joined: the second is refused (exit 2).
Progress bars (trials done, rate, time left) appear on stderr when it is a terminal and an
experiment runs longer than a second (XTASK_PROGRESS=always|never|auto; any other value is
refused). Logs go to stderr; set RUST_LOG (e.g. RUST_LOG=info) for more.",
        max_seed = u64::MAX,
        max_trials = registry::MAX_TRIALS,
        threads = default_threads(),
        out = default_out().display()
    )
}

pub(crate) fn overview(exps: &Registry) -> String {
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
pub(crate) fn details(e: &Entry) -> String {
    let mut s = format!("{}: {}\nPaper item: {}\n\n", e.id, e.title, e.paper_item);
    if e.all_params().next().is_none() {
        s.push_str("Parameters: none.\n");
    } else {
        let mut t = Table::new(
            "Parameters (set with --set NAME=VALUE)",
            ["name", "default", "unit", "values", "help"],
        );
        for p in e.all_params() {
            t.row(vec![
                p.name.into(),
                p.default.into(),
                p.unit.into(),
                p.kind.describe(),
                p.help.into(),
            ]);
        }
        s.push_str(&t.render());
    }
    let declares = |name: &str| e.all_params().any(|p| p.name == name);
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
pub(crate) fn rule_details(r: &rules::Rule, exps: &Registry) -> String {
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
                "  {} = {} {} ({}): {}\n",
                p.name,
                p.default,
                p.unit,
                p.kind.describe(),
                p.help
            ));
        }
    }
    let users: Vec<&str> = exps
        .values()
        .filter(|e| e.all_params().any(|p| *p == study::events::PARAM))
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

pub(crate) fn hypothesis_details(h: &dyn hypotheses::Hypothesis, exps: &Registry) -> String {
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
        .filter(|e| e.all_params().any(|p| *p == study::errors::PARAM))
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
pub(crate) fn wrap(text: &str, width: usize) -> String {
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
pub(crate) fn outputs(e: &Entry, out: &Path) -> String {
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

pub(crate) fn known(exps: &Registry) -> String {
    if exps.is_empty() {
        "no experiments are registered yet".into()
    } else {
        let ids: Vec<&str> = exps.keys().copied().collect();
        format!("known experiments: {}", ids.join(", "))
    }
}
