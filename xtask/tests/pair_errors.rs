//! `cargo xtask run pair --config FILE` with bad files: one line naming file, field and rule,
//! exit status 2, and no results written.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;
use support::run_with_file;

/// Runs `pair` on `text`; returns (exit code, stderr, whether the results dir exists).
fn run_pair(tag: &str, text: &str) -> (Option<i32>, String, bool) {
    run_with_file(
        &format!("pair-{tag}"),
        "mesh.ron",
        text,
        &["run", "pair", "--config", "{file}", "--out", "{out}"],
    )
}

fn mesh(driver: &str, extra: &str) -> String {
    format!("(driver: {driver}, driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), {extra})")
}

const GOOD_DRIVER: &str = "(teeth: 20, tip_radius: 10.0, root_radius: 9.0)";

#[test]
fn bad_mesh_files_exit_2_naming_field_and_rule_and_write_nothing() {
    let cases = [
        (
            "teeth",
            mesh(
                "(teeth: 2, tip_radius: 10.0, root_radius: 9.0)",
                "clearance_percent: Some(40.0)",
            ),
            "driver.teeth: must be at least 3",
        ),
        (
            "radii",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 11.0)",
                "clearance_percent: Some(40.0)",
            ),
            "driver.root_radius: must be less than tip_radius",
        ),
        (
            "distance",
            mesh(GOOD_DRIVER, "centre_distance: Some(18.5)"),
            "centre_distance: must exceed",
        ),
        (
            "syntax",
            "(driver: (teeth: 20,".to_string(),
            "line 1, column",
        ),
        (
            "unknown field",
            mesh(GOOD_DRIVER, "clearance_percent: Some(40.0), colour: 3"),
            "line 1",
        ),
    ];
    for (tag, text, expected) in cases {
        let (code, err, written) = run_pair(tag, &text);
        assert_eq!(code, Some(2), "{tag}: {err}");
        let line = err
            .lines()
            .find(|l| l.contains("mesh.ron"))
            .unwrap_or_else(|| panic!("{tag}: no line naming the file in {err}"));
        assert!(line.contains(expected), "{tag}: {line}");
        assert!(!err.contains("panicked"), "{tag}: {err}");
        assert!(!written, "{tag}: results were written");
    }
}

#[test]
fn good_mesh_file_writes_results() {
    let (code, err, written) =
        run_pair("good", &mesh(GOOD_DRIVER, "clearance_percent: Some(40.0)"));
    assert_eq!(code, Some(0), "{err}");
    assert!(written);
}

/// Proportions that make the solver's work per driver pitch grow without bound are refused
/// before anything runs, in numbers without a unit (a pair file takes any length unit).
#[test]
fn proportions_without_bound_on_the_work_per_pitch_are_refused() {
    let cases = [
        (
            // Found by `cargo xtask fuzz`: accepted, and its one pitch took 55.6 s.
            "needle teeth",
            "(driver: (teeth: 50, tip_radius: 4.3e9, root_radius: 180.0), driven: (teeth: 50, tip_radius: 1.8e19, root_radius: 180.0, eccentricity: Some((1.5, 0.5))), clearance_percent: Some(50.0), run_deg: Some(7.2))".to_string(),
            "driver.root_radius: must be at least half of tip_radius (2150000000; got 180)",
        ),
        (
            "teeth as tall as the gear",
            "(driver: (teeth: 50, tip_radius: 200.0, root_radius: 1.0), driven: (teeth: 50, tip_radius: 200.0, root_radius: 1.0), clearance_percent: Some(50.0))".to_string(),
            "driver.root_radius: must be at least half of tip_radius",
        ),
        (
            "pitches 100000 times apart",
            "(driver: (teeth: 10, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 50, tip_radius: 1e6, root_radius: 999999.0), clearance_percent: Some(50.0), run_deg: Some(36.0))".to_string(),
            "driven.tip_radius: the gears' teeth must be of one size: the driven gear's tooth pitch",
        ),
        (
            "heights 4.5 times apart",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 5.5)",
                "centre_distance: Some(19.5)",
            ),
            "driven.root_radius: the gears' teeth must be of one size: the driven gear's tooth height tip_radius - root_radius = 1 and the driver's 4.5",
        ),
        (
            "eccentric tips below the valleys at every angle",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, eccentricity: Some((0.1, 0.0)))",
                "centre_distance: Some(18.85)",
            ),
            "centre_distance: the driver gear's tips reach below the driven gear's valleys at every angle",
        ),
    ];
    for (tag, text, expected) in cases {
        let (code, err, written) = run_pair(tag, &text);
        assert_eq!(code, Some(2), "{tag}: {err}");
        let line = err
            .lines()
            .find(|l| l.contains("mesh.ron"))
            .unwrap_or_else(|| panic!("{tag}: no line naming the file in {err}"));
        assert!(line.contains(expected), "{tag}: {line}");
        assert_eq!(err.trim().lines().count(), 1, "{tag}: {err}");
        assert!(!written, "{tag}: results were written");
    }
}

/// The limits hold every pair the toolkit itself studies: Thorndike's example pair (fig2: N = 8,
/// R = 200, r = 100, D = 310), teeth at the tallest allowed, is run.
#[test]
fn thorndikes_example_pair_is_at_the_limit_and_runs() {
    let gear = "(teeth: 8, tip_radius: 200.0, root_radius: 100.0)";
    let (code, err, written) = run_pair(
        "thorndike",
        &format!("(driver: {gear}, driven: {gear}, centre_distance: Some(310.0))"),
    );
    assert_eq!(code, Some(0), "{err}");
    assert!(written);
}
