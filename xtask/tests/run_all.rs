//! `run all` on the command line: the refusals, which stop before anything runs.
//! (Running every experiment takes minutes; `run all` itself is tested on a fake registry in
//! `src/main.rs`, and the summary's formatting in `src/summary.rs`.)

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::PathBuf;
use std::process::{Command, Output};

fn xtask(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .env_remove("RUST_LOG")
        .output()
        .unwrap()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn scratch(tag: &str) -> PathBuf {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    std::env::temp_dir().join(format!("xtask-all-{tag}-{}-{nanos}", std::process::id()))
}

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
    let out = scratch("key");
    let o = xtask(&[
        "run",
        "all",
        "--set",
        "no_such_key=1",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(stderr(&o).contains("no_such_key"), "{}", stderr(&o));
    assert!(o.stdout.is_empty());
    assert!(!out.exists(), "nothing may be written");
}

#[test]
fn usage_describes_run_all() {
    let o = xtask(&["help"]);
    assert!(o.status.success());
    let text = String::from_utf8_lossy(&o.stdout);
    for word in ["run all", "summary.md", "summary.json"] {
        assert!(text.contains(word), "missing {word:?} in:\n{text}");
    }
}

#[test]
fn a_file_parameter_at_its_default_is_not_read_as_a_file() {
    // fig6's `measured` default, "no table", was once read as a file name by the checks made
    // before anything runs, which refused `run fig6` and so `run all` at their defaults.
    let dir = scratch("defaults");
    let out = dir.join("out");
    let o = xtask(&[
        "run",
        "fig6",
        "-q",
        "--set",
        "trials=1",
        "--set",
        "random_from=0.04",
        "--set",
        "random_to=0.04",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let o = xtask(&[
        "run",
        "fig6",
        "-q",
        "--set",
        "trials=1",
        "--set",
        "random_from=0.04",
        "--set",
        "random_to=0.04",
        "--set",
        "measured=none",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "measured=none: {}", stderr(&o));
}
