//! `run all` on the command line: the refusals, which stop before anything runs.
//! (Running every experiment takes minutes; `run all` itself is tested on a fake registry in
//! `src/main.rs`, and the summary's formatting in `src/summary.rs`.)

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::Path;

mod support;
use support::{Scratch, stderr, stdout, xtask};

#[test]
fn run_all_with_ids_is_refused() {
    for args in [&["run", "all", "fig2"][..], &["run", "fig2", "all"]] {
        let o = xtask(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let err = stderr(&o);
        assert!(
            err.contains("`run all`") && err.contains("not both"),
            "{err}"
        );
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn run_all_refuses_a_key_no_experiment_declares() {
    let s = Scratch::new("all-key");
    let out = s.path("out");
    let o = xtask(&["run", "all", "--set", "no_such_key=1", "--out", &out]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("no_such_key"), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    assert!(!Path::new(&out).exists(), "nothing may be written");
}

#[test]
fn usage_describes_run_all() {
    let o = xtask(&["help"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for word in ["run all", "summary.md", "summary.json"] {
        assert!(text.contains(word), "missing {word:?} in:\n{text}");
    }
}

#[test]
fn a_file_parameter_at_its_default_is_not_read_as_a_file() {
    // fig6's `measured` default, "no table", was once read as a file name by the checks made
    // before anything runs, which refused `run fig6` and so `run all` at their defaults.
    let s = Scratch::new("all-defaults");
    let out = s.path("out");
    // A tiny fig6 (one trial, one random error), with `extra` settings.
    let fig6 = |extra: &[&str]| {
        let mut args = vec!["run", "fig6", "-q", "--out", &out];
        args.extend(["--set", "trials=1", "--set", "random_from=0.04"]);
        args.extend(["--set", "random_to=0.04"]);
        args.extend(extra);
        xtask(&args)
    };
    let o = fig6(&[]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = fig6(&["--set", "measured=none"]);
    assert!(o.status.success(), "measured=none: {}", stderr(&o));
}

/// A value of a shared setting that every experiment declaring it would refuse (an unknown event
/// rule, a mesh the gearing lacks) is refused before the first experiment computes: one line,
/// nothing written, no experiment's output on stdout.
#[test]
fn run_all_refuses_a_shared_setting_before_anything_computes() {
    for (set, words) in [
        ("events=bogus", &["--set: events: ", "bogus"][..]),
        ("mesh=z9-y9", &["--set: mesh: ", "no mesh `z9-y9`"]),
    ] {
        let s = Scratch::new("shared-setting");
        let out = s.path("out");
        let start = std::time::Instant::now();
        let o = xtask(&["run", "all", "--set", set, "--out", &out]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{set}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{set}: {err}");
        for w in words {
            assert!(err.contains(w), "{set}: missing {w:?}: {err}");
        }
        assert!(stdout(&o).is_empty(), "{set}: something ran");
        assert!(!Path::new(&out).exists(), "{set}: something was written");
        assert!(
            start.elapsed().as_secs() < 10,
            "{set}: refused after {:?}",
            start.elapsed()
        );
    }
}
