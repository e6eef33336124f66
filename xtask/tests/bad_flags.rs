//! Bad flags, tried on purpose: every flag and setting with malformed, unknown, out-of-range and
//! enormous values, an `--out` that is a file, a hypothesis's parameters refused by name. Each
//! must be refused with exit status 2 and ONE line on stderr naming the flag and the rule,
//! without a panic, and without writing anything. The files' own are in `bad_input.rs`.
//!
//! Each test collects every case that misbehaves and fails once, listing them all.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;

mod support;
use support::hostile::{assert_none, case, failures};
use support::{Scratch, stderr, xtask};

#[test]
fn enormous_counts() {
    let cases = vec![
        case(
            "fig2 step 1e-9 (aborted on allocation)",
            None,
            "run fig2 --set step=1e-9 --out {out}",
            &["--set: step: must be at least 0.00036 degrees", "1e-9"],
        ),
        case(
            "--trials u64::MAX",
            None,
            "run table1 --trials 18446744073709551615 --out {out}",
            &["--trials: must be at most 1000000 (the limit on trials"],
        ),
        case(
            "--trials beyond u64",
            None,
            "run table1 --trials 99999999999999999999 --out {out}",
            &["--trials: must be an integer from 1 to 1000000"],
        ),
        case(
            "--trials 1 where the experiment needs 2 (blamed --set)",
            None,
            "run table1 --trials 1 --out {out}",
            &["--trials: table1: must be at least 2 (an interval needs two trials)"],
        ),
        case(
            "--trials 0",
            None,
            "run table1 --trials 0 --out {out}",
            &["--trials: must be at least 1"],
        ),
        case(
            "--trials -1",
            None,
            "run table1 --trials=-1 --out {out}",
            &["--trials: must be an integer"],
        ),
        case(
            "--set trials u64::MAX",
            None,
            "run table3 --set trials=18446744073709551615 --out {out}",
            &["--set: trials: must be at most 1000000, the limit on trials"],
        ),
        case(
            "--set trials u64::MAX, failure",
            None,
            "run failure --set trials=18446744073709551615 --out {out}",
            &["--set: trials: must be at most 1000000, the limit on trials"],
        ),
        case(
            "--set trials huge under run all",
            None,
            "run all --set trials=1000001 --out {out}",
            &["--set: trials: must be at most 1000000, the limit on trials"],
        ),
        case(
            "--set trials not a number",
            None,
            "run all --set trials=many --out {out}",
            &["--set: trials: must be a non-negative integer"],
        ),
        case(
            "a trillion samples",
            None,
            "run fig3 --set samples=1000000000000 --out {out}",
            &["--set: samples: must be at most 10000000, the limit on counts"],
        ),
        case(
            "a billion teeth",
            None,
            "run fig2 --set teeth=1000000000 --out {out}",
            &["--set: teeth: must be at most 100000 (a gear needs three teeth)"],
        ),
        case(
            "fig2 with 100000 teeth (ran for months, silently)",
            None,
            "run fig2 --set teeth=100000 --out {out}",
            &["--set: teeth: must be at most 500 for fig2 (got 100000)"],
        ),
        case(
            "200000 teeth",
            None,
            "run fig5 --set teeth=200000 --out {out}",
            &["--set: teeth: must be at most 100000 (a gear needs three teeth) (got `200000`)"],
        ),
        case(
            "a billion pitches",
            None,
            "run fig3 --set pitches=1000000000 --out {out}",
            &["--set: pitches: must be at most 10000000"],
        ),
        case(
            "samples per engagement",
            None,
            "run table1 --set samples_per_engagement=1000000000000 --out {out}",
            &["--set: samples_per_engagement: must be at most 10000000"],
        ),
    ];
    assert_none(failures("counts", cases));
}

#[test]
fn names_and_flags() {
    let cases = vec![
        case(
            "unknown experiment",
            None,
            "run no-such --out {out}",
            &["unknown experiment `no-such`", "known experiments: "],
        ),
        case(
            "help of unknown experiment",
            None,
            "help no-such",
            &["unknown experiment, error hypothesis or event rule `no-such`"],
        ),
        case(
            "unknown hypothesis",
            None,
            "run table2 --hypothesis no-such --out {out}",
            &[
                "--hypothesis: error hypothesis `no-such`: unknown",
                "edmunds-split",
            ],
        ),
        case(
            "unknown hypothesis with --set",
            None,
            "run all --set hypothesis=no-such --out {out}",
            &["error hypothesis `no-such`: unknown"],
        ),
        case(
            "unknown hypothesis parameter",
            None,
            "run fig5 --set hypothesis_params=wobble=1 --out {out}",
            &["wobble", "known keys"],
        ),
        case(
            "unknown case",
            None,
            "run failure --set cases=Z --out {out}",
            &["--set: cases: unknown case `Z`"],
        ),
        case(
            "unknown mesh",
            None,
            "run clearance --set mesh=zz-yy --out {out}",
            &["zz-yy"],
        ),
        case(
            "unknown parameter",
            None,
            "run fig2 --set nonsense=1 --out {out}",
            &["--set: nonsense: unknown parameter of experiment `fig2`"],
        ),
        case(
            "parameter nobody declares",
            None,
            "run fig2 fig3 --set nonsense=1 --out {out}",
            &["--set: nonsense: no selected experiment has this parameter"],
        ),
        case(
            "--set without =",
            None,
            "run fig2 --set novalue --out {out}",
            &["--set takes KEY=VALUE"],
        ),
        case(
            "unknown flag",
            None,
            "run fig2 --bogus --out {out}",
            &["unknown flag `--bogus`"],
        ),
        case(
            "unknown command",
            None,
            "frobnicate",
            &["unknown command `frobnicate`"],
        ),
        case(
            "-q and -v",
            None,
            "-q run fig2 -v --out {out}",
            &["cannot be combined"],
        ),
        case(
            "--seed abc",
            None,
            "run fig2 --seed abc --out {out}",
            &["--seed: must be an integer from 0 to 18446744073709551615"],
        ),
        case(
            "--seed -1",
            None,
            "run fig2 --seed=-1 --out {out}",
            &["--seed: must be an integer"],
        ),
        case(
            "--seed beyond u64",
            None,
            "run fig2 --seed 18446744073709551616 --out {out}",
            &["--seed: must be an integer"],
        ),
        case(
            "--seed 1.5",
            None,
            "run fig2 --seed 1.5 --out {out}",
            &["--seed: "],
        ),
        case(
            "--seed missing",
            None,
            "run fig2 --out {out} --seed",
            &["--seed needs a value"],
        ),
        case(
            "--threads 0",
            None,
            "run fig2 --threads 0 --out {out}",
            &["--threads: must be at least 1"],
        ),
        case(
            "--threads -1",
            None,
            "run fig2 --threads=-1 --out {out}",
            &["--threads: must be an integer from 1 to 1024"],
        ),
        case(
            "--threads huge",
            None,
            "run fig2 --threads 1000000 --out {out}",
            &["--threads: must be at most 1024"],
        ),
        case(
            "--threads abc",
            None,
            "run all --threads abc --out {out}",
            &["--threads: "],
        ),
        case(
            "--format xml",
            None,
            "run fig2 --format xml --out {out}",
            &["--format: must be md, csv or json"],
        ),
        case(
            "--format empty",
            None,
            "run fig2 --format= --out {out}",
            &["--format: must be md, csv or json"],
        ),
        case(
            "--shard K = N",
            None,
            "run table1 --shard 3/3 --out {out}",
            &["--shard: 3/3: K must be from 0 to N-1"],
        ),
        case(
            "--shard N = 0",
            None,
            "run table1 --shard 0/0 --out {out}",
            &["--shard: 0/0: N (the number of shards) must be at least 1"],
        ),
        case(
            "--shard words",
            None,
            "run table1 --shard a/b --out {out}",
            &["--shard: a/b: must be K/N"],
        ),
        case(
            "--shard one number",
            None,
            "run table1 --shard 1 --out {out}",
            &["--shard: 1: must be K/N"],
        ),
        case(
            "--shard negative",
            None,
            "run table1 --shard=-1/2 --out {out}",
            &["--shard: -1/2: must be K/N"],
        ),
        case(
            "--shard with all",
            None,
            "run all --shard 0/2 --out {out}",
            &["--shard splits the trials of one experiment"],
        ),
        case(
            "--trials where none declares it",
            None,
            "run fig2 fig3 --trials 5 --out {out}",
            &["--trials: no selected experiment has a `trials` parameter"],
        ),
        case(
            "--gearing where none declares it",
            None,
            "run fig2 --gearing x.ron --out {out}",
            &["--gearing: no selected experiment has a `gearing` parameter"],
        ),
        case(
            "--errors where none declares it",
            None,
            "run fig2 --errors x.ron --out {out}",
            &["--errors: no selected experiment has a `measured` or `hypothesis` parameter"],
        ),
        case(
            "--errors with --hypothesis",
            None,
            "run table2 --errors x.ron --hypothesis ideal --out {out}",
            &["--errors and --hypothesis cannot be combined"],
        ),
        case(
            "--trials with --set trials",
            None,
            "run table1 --trials 3 --set trials=4 --out {out}",
            &["--trials and --set trials=... cannot be combined"],
        ),
        case(
            "--config for an experiment without one",
            None,
            "run fig2 --config x.ron --out {out}",
            &["--config: "],
        ),
        case(
            "--config missing",
            None,
            "run pair --config /no/such/mesh.ron --out {out}",
            &["--config: /no/such/mesh.ron: cannot read"],
        ),
        case(
            "--out empty",
            None,
            "run fig2 --out=",
            &["--out: must not be empty"],
        ),
        case(
            "--hypothesis empty",
            None,
            "run table2 --hypothesis= --out {out}",
            &["--hypothesis: must not be empty"],
        ),
        case(
            "--seed twice (the last silently won)",
            None,
            "run fig2 --seed 1 --seed 2 --out {out}",
            &["--seed given twice: give it once"],
        ),
        case(
            "--set of one key twice",
            None,
            "run fig2 --set step=1 --set step=2 --out {out}",
            &["--set step=... given twice"],
        ),
        case(
            "merge --out twice",
            None,
            "merge /no/such --out {out} --out {out}",
            &["--out given twice"],
        ),
        case(
            "report --out twice",
            None,
            "report --out {out} --out {out}",
            &["--out given twice"],
        ),
        case(
            "hypothesis_params and a plain --set of one parameter",
            None,
            "run fig5 --set random=0.03 --set hypothesis_params=random=0.04 --out {out}",
            &[
                "--set: hypothesis_params: `random` is also set with --set random=0.03: give one of them",
            ],
        ),
        case(
            "run all with ids",
            None,
            "run all fig2 --out {out}",
            &["`run all` runs every experiment"],
        ),
    ];
    assert_none(failures("flags", cases));
}

#[test]
fn out_that_is_a_file() {
    let s = Scratch::new("bad-outfile");
    let file = s.0.join("plain");
    fs::write(&file, "not a directory").unwrap();
    for args in [
        vec!["run", "fig2", "--out", file.to_str().unwrap()],
        vec!["run", "all", "--out", file.to_str().unwrap()],
    ] {
        let o = xtask(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(
            err.trim_end(),
            format!("--out: {}: exists and is not a directory", file.display())
        );
        assert_eq!(fs::read_to_string(&file).unwrap(), "not a directory");
    }
}

/// A hypothesis parameter that Edmunds' errors refuse is refused naming what the user typed
/// (`--set hypothesis_params` and the key), not `--hypothesis`, before anything is drawn.
#[test]
fn hypothesis_params_refused_by_edmunds_name_the_setting_typed() {
    let cases = vec![
        case(
            "a negative random error",
            None,
            "run fig5 --set hypothesis_params=random=-0.05 --out {out}",
            &[
                "--set: hypothesis_params: edmunds-split: random: must be a finite number >= 0 (got -0.05)",
            ],
        ),
        case(
            "a random error above the limit",
            None,
            "run fig5 --hypothesis edmunds-split --set hypothesis_params=random=0.5 --out {out}",
            &["--set: hypothesis_params: edmunds-split: random: must be at most 0.1"],
        ),
        case(
            "an eccentric share of 90 degrees or more",
            None,
            "run fig5 --hypothesis eccentric-only --set hypothesis_params=systematic=200 --out {out}",
            &["--set: hypothesis_params: eccentric-only: systematic: its eccentric share"],
        ),
        case(
            "a layer of a stack",
            None,
            "run fig5 --hypothesis design-valleys+edmunds-split --set hypothesis_params=random=-1 --out {out}",
            &["--set: hypothesis_params: edmunds-split: random: must be a finite number >= 0"],
        ),
    ];
    assert_none(failures("edmunds-params", cases));
}

/// A misspelled or unknown parameter of an event rule or an error hypothesis is refused with exit
/// 2, naming the key as typed and the keys the plugin declares, before anything runs.
#[test]
fn misspelled_rule_and_hypothesis_parameters_are_refused_naming_the_key_typed() {
    let cases = vec![
        case(
            "a rule parameter misspelled",
            None,
            "run table4 --set events=idle-rotation:pitchs=2 --set trials=1 --out {out}",
            &[
                "--set: events: event rule idle-rotation: parameter `pitchs`: unknown key (known keys of idle-rotation: pitches)",
            ],
        ),
        case(
            "a parameter of a rule that takes none",
            None,
            "run table3 --set events=paper:mu=0.3 --set trials=1 --out {out}",
            &["parameter `mu`: unknown key (paper takes no parameters)"],
        ),
        case(
            "a rule parameter out of its declared range",
            None,
            "run table3 --set events=friction:mu=20 --set trials=1 --out {out}",
            &["parameter `mu`: must be between 0 and 10 (got 20)"],
        ),
        case(
            "a hypothesis parameter misspelled",
            None,
            "run fig5 --set hypothesis_params=randum=0.05 --out {out}",
            &[
                "--set: hypothesis_params: edmunds-split: parameter `randum`: unknown key (known keys of edmunds-split: random, systematic, split)",
            ],
        ),
        case(
            "a hypothesis parameter that is no number",
            None,
            "run fig5 --hypothesis curved-flanks --set hypothesis_params=sagitta=wide --out {out}",
            &["curved-flanks: parameter `sagitta`: must be a finite number (got wide)"],
        ),
    ];
    assert_none(failures("plugin-params", cases));
}

/// Counts too large or malformed name their maximum, a value refused by one of several
/// experiments names that experiment, and `fuzz` parses its flags as `run` does: a repeated
/// flag, or both budgets, refused; `--findings` checked before any fuzzing.
#[test]
fn counts_name_their_limits_and_fuzz_flags_are_parsed_as_runs_are() {
    let s = Scratch::new("fuzz-flags");
    let file = s.0.join("plain");
    fs::write(&file, "x").unwrap();
    let findings = format!("{}/below", file.display());
    let below_a_file = format!("fuzz --execs 1 --findings {findings}");
    let cases = vec![
        case(
            "trials of 1e300",
            None,
            "run table3 --set trials=1e300 --out {out}",
            &[
                "--set: trials: must be a non-negative integer, from 1 to 1000000, the limit on trials (got `1e300`)",
            ],
        ),
        case(
            "trials of 1e300 by the shorthand",
            None,
            "run table3 --trials 1e300 --out {out}",
            &["--trials: must be an integer from 1 to 1000000"],
        ),
        case(
            "a count of 1e300",
            None,
            "run fig3 --set samples=1e300 --out {out}",
            &[
                "--set: samples: must be a non-negative integer, from ",
                "to 10000000, the limit on counts",
            ],
        ),
        case(
            "run all with one trial",
            None,
            "run all --set trials=1 --out {out}",
            &["--set: trials: must be at least 2", ", for experiment "],
        ),
        case(
            "two experiments, one refusing",
            None,
            "run table3 table1 --set trials=1 --out {out}",
            &[
                "--set: trials: must be at least 2",
                ", for experiment table1",
            ],
        ),
        case(
            "fuzz with a seed twice",
            None,
            "fuzz --seed 1 --seed 2",
            &["--seed given twice"],
        ),
        case(
            "fuzz with both budgets",
            None,
            "fuzz --seconds 1 --execs 5",
            &["--seconds and --execs cannot be combined"],
        ),
        case(
            "fuzz with the seconds twice",
            None,
            "fuzz --seconds 1 --seconds=2",
            &["--seconds given twice"],
        ),
        case(
            "fuzz with findings below a file",
            None,
            &below_a_file,
            &["--findings: ", "is not a directory"],
        ),
    ];
    let started = std::time::Instant::now();
    assert_none(failures("counts-fuzz", cases));
    assert!(
        started.elapsed().as_secs() < 60,
        "the refusals came only after fuzzing: {:?}",
        started.elapsed()
    );
    // `-q` is taken anywhere, as the usage says, and quiets the note of what is fuzzed.
    for args in [
        &["fuzz", "-q", "--execs", "1"][..],
        &["-q", "fuzz", "--execs", "1"],
    ] {
        let mut all = args.to_vec();
        let f = s.path("findings");
        all.extend(["--findings", &f]);
        let o = xtask(&all);
        assert!(o.status.success(), "{all:?}: {}", stderr(&o));
        assert!(!stderr(&o).contains("fuzz: "), "{all:?}: {}", stderr(&o));
    }
}

/// `XTASK_PROGRESS` takes always, never or auto: any other value did nothing without a word
/// and is refused; a `RUST_LOG` that is no filter is said to be ignored.
#[test]
fn environment_settings_that_mean_nothing_are_refused_or_warned() {
    for value in ["bogus", "ALWAYS", "1", "yes", "Never "] {
        let o = support::xtask_env(&["list"], &[("XTASK_PROGRESS", value)]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{value}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{value}: {err}");
        assert!(
            err.starts_with("XTASK_PROGRESS: must be always, never, auto")
                && err.contains(&format!("`{value}`")),
            "{value}: {err}"
        );
        assert!(o.stdout.is_empty(), "{value}: ran anyway");
    }
    for value in ["always", "never", "auto", ""] {
        let o = support::xtask_env(&["list"], &[("XTASK_PROGRESS", value)]);
        assert!(o.status.success(), "{value}: {}", stderr(&o));
    }
    let o = support::xtask_env(&["list"], &[("RUST_LOG", "bogus[[[")]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    assert!(
        err.contains("warning: RUST_LOG: `bogus[[[` is not a log filter")
            && err.contains("ignored"),
        "{err}"
    );
    let o = support::xtask_env(&["list"], &[("RUST_LOG", "info")]);
    assert!(!stderr(&o).contains("RUST_LOG"), "{}", stderr(&o));
}

/// `bench --only table5 --only all` and `--threads 1 --threads 2`: the last silently won, where
/// every other command refuses a repeated flag; `--bundle` was missing from the usage, and
/// `report --help` was refused. New instances: `merge --help`, `bench --help`, `fuzz --help`
/// and `replay --help` show the usage too.
#[test]
fn every_command_takes_a_flag_once_and_shows_its_usage() {
    let cases = vec![
        case(
            "bench --only twice",
            None,
            "bench --only table5 --only all",
            &["--only given twice"],
        ),
        case(
            "bench --threads twice",
            None,
            "bench --threads 1 --threads 2",
            &["--threads given twice"],
        ),
    ];
    assert_none(failures("once", cases));
    for cmd in ["report", "merge", "bench", "fuzz", "replay", "run"] {
        let o = xtask(&[cmd, "--help"]);
        let out = support::stdout(&o);
        assert!(o.status.success(), "{cmd} --help: {}", stderr(&o));
        assert!(
            out.contains("cargo xtask report [--out DIR] [--bundle FILE] [-q]"),
            "{cmd} --help: {out}"
        );
    }
}

/// `--out a/x` where `a` is a loop of symbolic links said "a is not a directory" (`report` and
/// `merge` said "Too many levels of symbolic links"): every command names the loop. New
/// instances: `replay`, and `report --bundle` into the loop.
#[test]
fn an_out_through_a_loop_of_links_is_named_as_one() {
    let s = Scratch::new("link-loop");
    std::os::unix::fs::symlink("b", s.0.join("a")).unwrap();
    std::os::unix::fs::symlink("a", s.0.join("b")).unwrap();
    let into = s.path("a/x");
    let o = xtask(&["run", "fig3", "-q", "--out", &s.path("r")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let bundle = s.path("a/b.tgz");
    let shards = s.path("sh");
    for k in ["0/2", "1/2"] {
        let mut args = vec!["run", "table1", "-q", "--shard", k, "--out", &shards];
        args.extend(support::TABLE1_TINY);
        let o = xtask(&args);
        assert!(o.status.success(), "{}", stderr(&o));
    }
    for args in [
        vec!["run", "fig3", "--out", &into],
        vec![
            "replay", "table3", "B/m3-e3", "0", "--trials", "2", "--out", &into,
        ],
        vec!["report", "--out", &into],
        vec!["merge", &shards, "--out", &into],
        vec!["report", "--out", &s.path("r"), "--bundle", &bundle],
    ] {
        let o = xtask(&args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.contains("Too many levels of symbolic links") && !err.contains("not a directory"),
            "{args:?}: {err}"
        );
    }
}
