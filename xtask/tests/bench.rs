//! `cargo xtask bench` on the command line: its arguments (a real bench takes many minutes, so
//! only refusals, which stop before anything runs, are tested; the parsed values are tested in
//! `src/args.rs`).

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

mod support;
use support::{stdout, xtask};

#[test]
fn bench_refuses_bad_arguments() {
    for (args, usage) in [
        (&["bench", "--only", "table6"][..], false),
        (&["bench", "--threads", "0"], false),
        (&["bench", "--threads", "1,two"], false),
        // The same limit as `run --threads`: no pool beyond it is even attempted.
        (&["bench", "--threads", "100000"], false),
        (&["bench", "--threads", "1,1025"], false),
        (&["bench", "table5"], true),
        (&["bench", "--seed", "1"], true),
        (&["bench", "--only"], true),
    ] {
        support::refused_in_one_line(args, usage);
    }
}

#[test]
fn bench_threads_beyond_the_run_limit_name_the_limit() {
    let o = xtask(&["bench", "--threads", "100000"]);
    assert_eq!(o.status.code(), Some(2));
    let err = support::stderr(&o);
    assert!(
        err.contains("--threads") && err.contains("at most 1024"),
        "{err}"
    );
}

#[test]
fn usage_describes_bench() {
    let o = xtask(&["help"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for word in ["cargo xtask bench", "--only table5|all", "--threads 1,2"] {
        assert!(text.contains(word), "missing {word:?} in:\n{text}");
    }
}
