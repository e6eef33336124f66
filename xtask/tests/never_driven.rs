//! A driven gear that no driver tooth ever moves is never reported as driven: every command that
//! reports on a run says so, and gives no statistic of a motion that did not happen.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{Scratch, stderr, succeeded, xtask};

/// The example pair file with its clearance set to `g` % of h.
fn pair_at(s: &Scratch, g: &str) -> String {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../experiments/data/pair-example.ron"
    ))
    .unwrap();
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with("clearance_percent:"))
        .unwrap();
    let changed = text.replace(line, &format!("    clearance_percent: Some({g}),"));
    let path = s.path(&format!("pair-{g}.ron"));
    std::fs::write(&path, changed).unwrap();
    path
}

#[test]
fn pair_out_of_reach_reports_an_idle_start_and_no_sigma() {
    let s = Scratch::new("never-driven-pair");
    for g in ["95.0", "99.0", "99.9"] {
        let out = succeeded(&[
            "run",
            "pair",
            "-q",
            "--config",
            &pair_at(&s, g),
            "--out",
            &s.path(g),
        ]);
        assert!(!out.contains("driven throughout"), "G = {g}: {out}");
        assert!(out.contains("| idle start "), "G = {g}: {out}");
        let sigma = out
            .lines()
            .find(|l| l.starts_with("| Theoretical Difference sigma"))
            .unwrap();
        assert!(sigma.contains("never driven"), "G = {g}: {sigma}");
        let dis = out
            .lines()
            .find(|l| l.starts_with("| disengagements"))
            .unwrap();
        assert!(dis.contains("| 1 "), "G = {g}: {dis}");
    }
}

#[test]
fn fig5_at_full_clearance_gives_no_triangular_sigma() {
    // At full clearance and without a systematic error nothing brings the gears closer than
    // tip to tip (the random error moves teeth along the pitch circle), so no draw drives them;
    // with an eccentricity some draws do.
    let s = Scratch::new("never-driven-fig5");
    let out = succeeded(&[
        "run",
        "fig5",
        "-q",
        "--set",
        "clearance=100",
        "--set",
        "systematic=0",
        "--out",
        &s.path("o"),
    ]);
    for split in ["| A: ", "| B: ", "| C: "] {
        let row = out.lines().find(|l| l.starts_with(split)).unwrap();
        assert!(row.contains("never driven"), "{row}");
    }
}

#[test]
fn fig2_and_fig3_with_the_gears_out_of_reach_are_refused() {
    let s = Scratch::new("never-driven-fig3");
    for id in ["fig2", "fig3"] {
        for d in ["400", "400.5", "1000"] {
            let set = format!("centre_distance={d}");
            let o = xtask(&["run", id, "-q", "--set", &set, "--out", &s.path(id)]);
            let err = stderr(&o);
            assert_eq!(o.status.code(), Some(2), "{id} {set}: {err}");
            assert!(err.contains("centre_distance"), "{id} {set}: {err}");
            assert!(err.contains("never turned"), "{id} {set}: {err}");
        }
    }
}
