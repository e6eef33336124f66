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
