//! `cargo xtask hypotheses` lists the registered manufacturing-error hypotheses.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::Path;

mod support;
use support::{Scratch, stderr, stdout, xtask};

#[test]
fn hypotheses_lists_every_registered_one_with_its_params() {
    let o = xtask(&["hypotheses"]);
    let out = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    hypotheses::link();
    let registered = hypotheses::hypotheses().unwrap();
    assert!(registered.len() >= 5, "the hypotheses crate is linked");
    for name in registered.keys() {
        assert!(out.contains(&format!("{name}: ")), "{name} missing:\n{out}");
    }
    for param in ["random", "systematic", "split", "scale"] {
        assert!(out.contains(param), "{param} missing:\n{out}");
    }
}

#[test]
fn hypotheses_takes_no_arguments_and_the_overview_mentions_it() {
    let o = xtask(&["hypotheses", "extra"]);
    assert_eq!(o.status.code(), Some(2));
    let o = xtask(&[]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("cargo xtask hypotheses"));
}

/// Runs `fig5` with `args` into a fresh results dir: expects exit 2, nothing written, and returns
/// stderr.
fn fig5_refused(tag: &str, args: &[&str]) -> String {
    let s = Scratch::new(&format!("hyp-{tag}"));
    let out = s.path("out");
    let mut all = vec!["run", "fig5", "--out", &out];
    all.extend_from_slice(args);
    let o = xtask(&all);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(!Path::new(&out).exists());
    err
}

#[test]
fn unknown_hypothesis_lists_the_known_ones_and_exits_2() {
    let err = fig5_refused("unknown", &["--hypothesis", "no-such-thing"]);
    assert!(
        err.contains("no-such-thing") && err.contains("edmunds-split") && err.contains("ideal"),
        "{err}"
    );
}

#[test]
fn a_bad_hypothesis_parameter_names_it_and_the_known_ones() {
    let err = fig5_refused("param", &["--set", "hypothesis_params=wobble=1"]);
    assert!(
        err.contains("wobble") && err.contains("random") && err.contains("systematic"),
        "{err}"
    );
}
