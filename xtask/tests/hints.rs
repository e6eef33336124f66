//! Likely mistakes are caught: a name close to a known one gets a "did you mean", an optional
//! RON field written without `Some(...)` gets the way to write it, and input that runs but is
//! probably not what was meant - tip angles in radians, a clearance below 1 % of h, `run pair`
//! with no file - is warned about on stderr.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{Scratch, stderr, xtask};

/// `args` are refused (exit 2) in one line that ends with `ending`.
fn refused_with(args: &[&str], ending: &str) {
    let o = xtask(args);
    assert_eq!(o.status.code(), Some(2), "{args:?}");
    let err = stderr(&o);
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: one line: {err}"
    );
    assert!(err.trim_end().ends_with(ending), "{args:?}: {err}");
}

#[test]
fn close_names_get_a_did_you_mean() {
    for (args, ending) in [
        (&["run", "tabel5"][..], "did you mean `table5`?"),
        (&["help", "tabel3"], "did you mean `table3`?"),
        (&["help", "idle-rotaton"], "did you mean `idle-rotation`?"),
        (&["replay", "tabel3", "B/m3-e3"], "did you mean `table3`?"),
        (
            &["run", "table3", "--hypothesis", "edmund-split"],
            "did you mean `edmunds-split`?",
        ),
        (
            &["run", "table3", "--set", "events=idle-rotaton"],
            "did you mean `idle-rotation`?",
        ),
        (
            &["run", "table3", "--set", "clearence=40"],
            "did you mean `clearance`?",
        ),
        (
            &["run", "table3", "table4", "--set", "clearence=40"],
            "did you mean `clearance`?",
        ),
        (
            &["run", "table3", "--set", "hypothesis_params=randm=0.05"],
            "did you mean `random`?",
        ),
        (
            &["run", "table3", "--set", "events=friction:m=0.1"],
            "did you mean `mu`?",
        ),
    ] {
        refused_with(args, ending);
    }
    // Nothing close: no guess.
    let o = xtask(&["run", "qqqqqqqq"]);
    assert!(!stderr(&o).contains("did you mean"), "{}", stderr(&o));
}

#[test]
fn an_option_without_some_is_explained() {
    let s = Scratch::new("hints-option");
    let file = s.path("pair.ron");
    std::fs::write(
        &file,
        "(\n    driver: (teeth: 20, tip_radius: 20.0, root_radius: 18.0),\n    driven: (teeth: 30, tip_radius: 30.0, root_radius: 28.0),\n    clearance_percent: 50.0,\n)",
    )
    .unwrap();
    refused_with(
        &["run", "pair", "--config", &file],
        "`clearance_percent` is optional: write its value inside Some(...), e.g. `clearance_percent: Some(...)`, or leave the field out",
    );
}

#[test]
fn likely_mistakes_that_run_are_warned_about() {
    let s = Scratch::new("hints-warnings");
    let out = s.path("out");
    // Tips in radians, 2 pi / 30 apart, and a clearance of half a per cent.
    let tips: Vec<String> = (0..30)
        .map(|i| format!("{:.6}", f64::from(i) * std::f64::consts::TAU / 30.0))
        .collect();
    let file = s.path("radians.ron");
    std::fs::write(
        &file,
        format!(
            "(\n    driver: (teeth: 20, tip_radius: 20.0, root_radius: 18.0),\n    driven: (teeth: 30, tip_radius: 30.0, root_radius: 28.0, tips_deg: Some([{}])),\n    clearance_percent: Some(0.5),\n)",
            tips.join(", ")
        ),
    )
    .unwrap();
    let o = xtask(&["run", "pair", "--config", &file, "--out", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    let err = stderr(&o);
    assert!(
        err.contains("driven.tips_deg: the tips are 0.2094 deg apart on average, far from 360/30 = 12.0000 deg - as if they were in radians"),
        "{err}"
    );
    assert!(
        err.contains("clearance_percent: 0.5 is 0.5 % of the tooth height h")
            && err.contains("write Some(50)"),
        "{err}"
    );
    // The example, said to be one.
    let o = xtask(&["run", "pair", "--out", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("no --config given, so this runs the example pair"),
        "{}",
        stderr(&o)
    );
    // A clearance typed as a fraction.
    let o = xtask(&[
        "run",
        "table3",
        "--set",
        "clearance=0.4",
        "--trials",
        "2",
        "--out",
        &out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("--set clearance=0.4 is 0.4 % of the tooth height h (the unit is % of h, not a fraction of it); for 40 % write --set clearance=40"),
        "{}",
        stderr(&o)
    );
    // -q: errors only.
    let o = xtask(&["run", "pair", "-q", "--config", &file, "--out", &out]);
    assert!(
        o.status.success() && stderr(&o).is_empty(),
        "{}",
        stderr(&o)
    );
    // Measured tips in degrees: no warning.
    let example = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../experiments/data/pair-example.ron"
    );
    let o = xtask(&["run", "pair", "--config", example, "--out", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stderr(&o).contains("warning:"), "{}", stderr(&o));
}

/// A clearance far below 1 % of h (`clearance_percent: Some(1e-5)`) ran with no warning and
/// printed jams and a sigma of hundreds of degrees: it is warned as tips all but touching the
/// opposite valleys, in a pair file (by clearance or by centre distance) and in `--set`, one
/// value or a list.
#[test]
fn tiny_clearances_are_warned() {
    let s = Scratch::new("tiny-clearance");
    let out = s.path("out");
    let gear = "(teeth: 20, tip_radius: 10.0, root_radius: 9.0)";
    for (tag, extra, words) in [
        (
            "percent",
            "clearance_percent: Some(1e-5)",
            "clearance_percent: a clearance of 0.00001 % of the tooth height h",
        ),
        // R1 + R2 - h = 19: a centre distance 1e-6 beyond it is a clearance of 0.0001 %.
        (
            "distance",
            "centre_distance: Some(19.000001)",
            "centre_distance: 19.000001 gives a clearance of 0.0001 % of the mean tooth height h",
        ),
    ] {
        let file = s.path(&format!("{tag}.ron"));
        std::fs::write(
            &file,
            format!("(driver: {gear}, driven: {gear}, {extra}, run_deg: Some(36.0))"),
        )
        .unwrap();
        let o = xtask(&["run", "pair", "--config", &file, "--out", &out]);
        let err = stderr(&o);
        assert!(
            err.contains("warning: ") && err.contains(words),
            "{tag}: {err}"
        );
        assert!(err.contains("jam at nearly every tooth"), "{tag}: {err}");
    }
    for (args, words) in [
        (
            &["run", "table3", "--set", "clearance=0.001"][..],
            "warning: table3: --set clearance=0.001: a clearance of 0.001 %",
        ),
        (
            &["run", "tableI", "--set", "clearances=40,0.0001"],
            "warning: tableI: --set clearances=40,0.0001: a clearance of 0.0001 %",
        ),
    ] {
        let mut all = args.to_vec();
        // Refused once it starts (a random error below 0): the warning comes before, and
        // nothing is computed.
        all.extend(["--set", "hypothesis_params=random=-1", "--out", &out]);
        let o = xtask(&all);
        let err = stderr(&o);
        assert!(err.contains(words), "{all:?}: {err}");
    }
}
