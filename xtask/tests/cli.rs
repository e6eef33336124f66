//! Runs the built `xtask` binary as a user would. These tests work whatever experiments are
//! registered, none included, and never run one.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::Path;

mod support;
use support::{Scratch, stderr, stdout, xtask};

fn ids() -> Vec<String> {
    let o = xtask(&["list"]);
    assert!(o.status.success(), "{}", stderr(&o));
    stdout(&o).lines().map(str::to_owned).collect()
}

/// An id to run, or `all` when none is registered.
fn some_id() -> String {
    ids().into_iter().next().unwrap_or_else(|| "all".into())
}

#[test]
fn no_args_lists_commands_and_experiments() {
    let o = xtask(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    for word in ["run", "list", "help", "--seed", "2025", "Experiments"] {
        assert!(text.contains(word), "missing {word:?} in:\n{text}");
    }
    for id in ids() {
        assert!(
            text.contains(&format!("| {id} ")),
            "missing {id} in:\n{text}"
        );
    }
}

#[test]
fn list_prints_sorted_ids() {
    let ids = ids();
    let mut sorted = ids.clone();
    sorted.sort();
    assert_eq!(ids, sorted);
    assert!(ids.iter().all(|id| !id.is_empty() && !id.contains(' ')));
}

#[test]
fn help_describes_each_experiment() {
    for id in ids() {
        let o = xtask(&["help", &id]);
        assert!(o.status.success(), "{}", stderr(&o));
        let text = stdout(&o);
        assert!(text.starts_with(&format!("{id}: ")), "{text}");
        assert!(text.contains("Paper item:"), "{text}");
        assert!(text.contains("Config file"), "{text}");
    }
    let o = xtask(&["help", "no-such-experiment"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o)
            .contains("unknown experiment, error hypothesis or event rule `no-such-experiment`")
    );
}

/// `rules` lists every event rule and `help NAME` documents each: its reading, its parameters
/// and the experiments that count with it.
#[test]
fn rules_are_listed_and_documented() {
    let o = xtask(&["rules"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let listing = stdout(&o);
    for (name, r) in rules::rules().unwrap() {
        assert!(listing.contains(name), "{listing}");
        let o = xtask(&["help", name]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let text = stdout(&o);
        assert!(text.starts_with(&format!("{name} - event rule")), "{text}");
        assert!(text.contains("table3"), "{text}");
        for p in r.params() {
            assert!(text.contains(p.name), "{name}: {}: {text}", p.name);
        }
    }
    let o = xtask(&[
        "run",
        "fig2",
        "--set",
        "events=no-such-rule",
        "--out",
        "/nonexistent-dir/x",
    ]);
    assert_eq!(o.status.code(), Some(2));
    let known: Vec<&str> = rules::rules().unwrap().keys().copied().collect();
    assert!(
        stderr(&o).contains(&format!("unknown; known rules: {}", known.join(", "))),
        "{}",
        stderr(&o)
    );
}

/// `help NAME` documents every registered error hypothesis (and a stack of them): its model in
/// words where it gives one, its parameters, and a command that runs it.
#[test]
fn help_describes_each_hypothesis() {
    let all = hypotheses::hypotheses().unwrap();
    for (name, h) in all {
        let o = xtask(&["help", name]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let text = stdout(&o);
        assert!(
            text.starts_with(&format!("{name}: error hypothesis: ")),
            "{text}"
        );
        assert!(
            text.contains(h.details().split_whitespace().next().unwrap_or("")),
            "{text}"
        );
        for p in h.params() {
            assert!(
                text.contains(&format!("| {} ", p.name)),
                "{name}: {}: {text}",
                p.name
            );
        }
        assert!(text.contains(&format!("--hypothesis {name}")), "{text}");
    }
    let o = xtask(&["help", "edmunds-split+asymmetric-teeth"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = stdout(&o);
    assert!(
        text.contains("| valley_shift ") && text.contains("| random "),
        "{text}"
    );
}

#[test]
fn unknown_id_exits_2_and_writes_nothing() {
    let scratch = Scratch::new("cli-unknown");
    let out = scratch.path("out");
    let o = xtask(&["run", "no-such-experiment", "--out", &out]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("unknown experiment `no-such-experiment`"),
        "{err}"
    );
    for id in ids() {
        assert!(err.contains(&id), "list of known ids missing {id}: {err}");
    }
    assert!(stdout(&o).is_empty());
    assert!(!Path::new(&out).exists(), "results directory was created");
}

#[test]
fn unknown_param_exits_2_and_writes_nothing() {
    let scratch = Scratch::new("cli-set");
    let out = scratch.path("out");
    let id = some_id();
    let o = xtask(&["run", &id, "--set", "nonsense=1", "--out", &out]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("nonsense"), "{}", stderr(&o));
    assert!(!Path::new(&out).exists(), "results directory was created");
}

#[test]
fn zero_threads_exits_2() {
    let scratch = Scratch::new("cli-threads");
    let out = scratch.path("out");
    let o = xtask(&["run", "all", "--threads", "0", "--out", &out]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--threads"));
    assert!(!Path::new(&out).exists());
}

#[test]
fn bad_command_lines_exit_2_pointing_to_the_usage() {
    for args in [
        &["frobnicate"][..],
        &["run"],
        &["run", "all", "--bogus"],
        &["run", "all", "--seed"],
        &["run", "all", "--set", "novalue"],
        &["list", "extra"],
    ] {
        let o = xtask(args);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: one line: {err}");
        assert!(
            err.starts_with("error: ") && err.contains("`cargo xtask help` shows the usage"),
            "{args:?}: {err}"
        );
    }
    let o = xtask(&["run", "all", "--seed", "minus-one"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--seed"));
}

#[test]
fn unreadable_config_exits_2_naming_the_file() {
    let scratch = Scratch::new("cli-config");
    let missing = scratch.0.join("missing.ron");
    let out = scratch.path("out");
    let id = some_id();
    let o = xtask(&[
        "run",
        &id,
        "--config",
        missing.to_str().unwrap(),
        "--out",
        &out,
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("missing.ron"), "{}", stderr(&o));
    assert!(!Path::new(&out).exists());
}

#[test]
fn config_for_an_experiment_without_one_exits_2() {
    let scratch = Scratch::new("cli-noconfig");
    let file = scratch.0.join("c.ron");
    std::fs::write(&file, "()").unwrap();
    let out = scratch.0.join("results");
    let ids = ids();
    // An experiment that takes no config, or `all` with none registered (nothing takes it).
    let target = if ids.is_empty() {
        Some("all".to_owned())
    } else {
        ids.into_iter()
            .find(|id| stdout(&xtask(&["help", id])).contains("takes no --config"))
    };
    let Some(id) = target else { return };
    let o = xtask(&[
        "run",
        &id,
        "--config",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("--config"), "{}", stderr(&o));
    assert!(!out.exists());
}
