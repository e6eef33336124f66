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
            // Since lengths are checked for scale, refused for its driver's radius first.
            "driver.tip_radius: must be from 1e-9 to 1000000000",
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
            "driver.root_radius: the gears' teeth must be of one size: the driver gear's tooth height tip_radius - root_radius = 4.5 is more than 4 times the driven gear's 1",
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

/// Angles beyond what a double holds as finely as the solver places a contact ran until killed
/// (`start_deg: 1e17`) or answered "never driven" (`1e20`); statistics from one sample printed
/// sigma 0. Each is refused at once, naming the field and the rule, and nothing is written.
#[test]
fn huge_angles_and_too_few_samples_are_refused_at_once() {
    let good = "clearance_percent: Some(40.0)";
    let with = |extra: &str| mesh(GOOD_DRIVER, &format!("{good}, {extra}"));
    let cases = [
        ("start 1e17", with("start_deg: 1e17"), "start_deg: must be at most 1000000 degrees either way (got 1e17)"),
        ("start 1e18", with("start_deg: 1e18"), "start_deg: must be at most 1000000 degrees"),
        ("start -1e17", with("start_deg: -1e17"), "start_deg: must be at most 1000000 degrees either way (got -1e17)"),
        ("start 1e20", with("start_deg: 1e20"), "start_deg: must be at most 1000000 degrees"),
        ("start 1e300", with("start_deg: 1e300"), "start_deg: must be at most"),
        ("start 3e16", with("start_deg: 3e16"), "start_deg: must be at most"),
        ("start NaN", with("start_deg: NaN"), "start_deg: must be a finite number of degrees"),
        (
            "at-rest start far away",
            with("start: at_rest(theta_deg: 1e19)"),
            "start.theta_deg: must be at most 1000000 degrees",
        ),
        (
            "a tip angle of 1e17",
            mesh(
                "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([1e17, 1.2e17, 1.4e17]))",
                good,
            ),
            "driver.tips_deg[0]: must be at most 1000000 degrees",
        ),
        (
            "an arbor angle of -1e30",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: 0.01, angle_deg: -1e30)))",
                good,
            ),
            "driver.arbor.angle_deg: must be at most 1000000 degrees",
        ),
        ("one sample a turn", with("sample_deg: 360.0"), "sample_deg: must be at most 4.5 degrees, a quarter of the driving gear's pitch 360/20 (got 360)"),
        ("a sample past the run", with("sample_deg: 720.0"), "sample_deg: must be at most 4.5 degrees"),
        ("a whole pitch", with("sample_deg: 18.0"), "sample_deg: must be at most 4.5 degrees"),
        (
            "a run of a billionth of a degree",
            with("run_deg: Some(1e-9)"),
            "in steps of 0.1 give 1 sample of the Theoretical Difference, and sigma, Dm and P need at least 100",
        ),
        (
            "a run of 99 samples",
            with("run_deg: Some(9.8), sample_deg: 0.1"),
            "run_deg: is too short",
        ),
        (
            "a default run of 3 teeth too coarsely sampled",
            "(driver: (teeth: 3, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 3, tip_radius: 10.0, root_radius: 9.0), clearance_percent: Some(40.0), sample_deg: 10.0)".to_string(),
            "sample_deg: must be at most 3.6363",
        ),
    ];
    for (tag, text, expected) in cases {
        let started = std::time::Instant::now();
        let (code, err, written) = run_pair(tag, &text);
        assert_eq!(code, Some(2), "{tag}: {err}");
        assert!(err.contains(expected), "{tag}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{tag}: {err}");
        assert!(!written, "{tag}: results were written");
        assert!(
            started.elapsed().as_secs() < 30,
            "{tag}: took {:?}",
            started.elapsed()
        );
    }
    // At the limit the run goes through, and from a whole number of turns it is the run from 0.
    let sigma = |start: &str| {
        let s = support::Scratch::new("pair-at-limit");
        let file = s.path("m.ron");
        std::fs::write(&file, with(&format!("start_deg: {start}"))).unwrap();
        let out = support::succeeded(&[
            "run",
            "pair",
            "-q",
            "--config",
            &file,
            "--out",
            &s.path("o"),
        ]);
        out.lines()
            .find(|l| l.contains("Theoretical Difference sigma"))
            .unwrap()
            .split('|')
            .nth(2)
            .unwrap()
            .trim()
            .to_owned()
    };
    assert_eq!(sigma("0.0"), sigma("999720.0"), "999720 = 2777 turns");
}

/// A refusal names a field the file has and the gear at fault: uneven tooth heights with
/// `clearance_percent`, or a large `eccentricity`, were blamed on `centre_distance`, which the
/// file did not have, and an oversized driver on the driven gear's `tip_radius`/`root_radius`.
/// New instances: the offset given as `arbor`, and an oversized driver's tooth height.
#[test]
fn a_refusal_names_the_field_the_file_has_and_the_gear_at_fault() {
    let driven = |extra: &str| format!("(teeth: 20, tip_radius: 10.0, root_radius: 9.0{extra})");
    let pair = |driver: &str, driven: &str, distance: &str| {
        format!("(driver: {driver}, driven: {driven}, {distance})")
    };
    let cases = [
        (
            "uneven heights",
            pair(
                GOOD_DRIVER,
                "(teeth: 20, tip_radius: 10.0, root_radius: 6.2)",
                "clearance_percent: Some(40.0)",
            ),
            "mesh.ron: clearance_percent: must exceed",
        ),
        (
            "eccentricity",
            pair(
                GOOD_DRIVER,
                &driven(", eccentricity: Some((3.0, 0.0))"),
                "clearance_percent: Some(40.0)",
            ),
            "mesh.ron: driven.eccentricity: must exceed",
        ),
        (
            "arbor",
            pair(
                "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: 3.0, angle_deg: 0.0)))",
                &driven(""),
                "clearance_percent: Some(40.0)",
            ),
            "mesh.ron: driver.arbor: must exceed",
        ),
        (
            "oversized driver pitch",
            pair(
                "(teeth: 20, tip_radius: 200.0, root_radius: 199.0)",
                &driven(""),
                "clearance_percent: Some(40.0)",
            ),
            "mesh.ron: driver.tip_radius: the gears' teeth must be of one size: the driver gear's tooth pitch",
        ),
        (
            "oversized driver height",
            pair(
                "(teeth: 20, tip_radius: 10.0, root_radius: 5.5)",
                &driven(""),
                "centre_distance: Some(19.5)",
            ),
            "mesh.ron: driver.root_radius: the gears' teeth must be of one size: the driver gear's tooth height",
        ),
    ];
    for (tag, text, expected) in cases {
        let (code, err, written) = run_pair(tag, &text);
        assert_eq!(code, Some(2), "{tag}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{tag}: {err}");
        assert!(err.contains(expected), "{tag}: {err}");
        assert!(
            !err.contains("centre_distance") || text.contains("centre_distance"),
            "{tag}: {err}"
        );
        assert!(!written, "{tag}: results were written");
    }
}

/// The example pair with every length multiplied by `s`.
fn scaled(s: f64) -> String {
    format!(
        "(driver: (teeth: 50, tip_radius: {:?}, root_radius: {:?}), driven: (teeth: 50, tip_radius: {:?}, root_radius: {:?}, eccentricity: Some(({:?}, {:?}))), clearance_percent: Some(50.0))",
        200.0 * s,
        180.0 * s,
        200.0 * s,
        180.0 * s,
        1.5 * s,
        0.5 * s
    )
}

/// A pair scaled by 2e152 or 1e-160 (every length) counted "disengagements 1, sigma -" where
/// every scale from 1e-155 to 1e150 gave 0/0: the answer depended on the unit through
/// overflow; a tooth 1e-13 high at R = 200 gave 50 jams of noise. Lengths outside 1e-9 to 1e9
/// of the file's unit are refused, and so is a tooth height or clearance below 1e-8 of the
/// larger tip radius; inside the range the events are the same in every unit. New instances:
/// an eccentricity of 1e200, a clearance_percent of 1e-12, and the gearing's `--set
/// clearance=1e-12` (which ran with its tips 1e-14 mm from the valleys).
#[test]
fn every_length_is_checked_for_scale() {
    let cases = [
        ("2e152", scaled(2e152), "driver.tip_radius: must be from 1e-9 to 1000000000"),
        ("1e-160", scaled(1e-160), "driver.tip_radius: must be from 1e-9 to 1000000000"),
        (
            "eccentricity",
            scaled(1.0).replace("Some((1.5, 0.5))", "Some((1e200, 0.0))"),
            "driven.eccentricity: must be at most 1000000000 either way",
        ),
        (
            "a tooth 1e-13 high",
            "(driver: (teeth: 50, tip_radius: 200.0, root_radius: 199.9999999999999), driven: (teeth: 50, tip_radius: 200.0, root_radius: 199.9999999999999), clearance_percent: Some(40.0))".to_string(),
            "driver.root_radius: leaves a tooth height",
        ),
        (
            "a clearance of 1e-12 %",
            mesh(GOOD_DRIVER, "clearance_percent: Some(1e-12)"),
            "clearance_percent: leaves the driver gear's tips",
        ),
    ];
    for (tag, text, expected) in cases {
        let (code, err, written) = run_pair(tag, &text);
        assert_eq!(code, Some(2), "{tag}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{tag}: {err}");
        assert!(err.contains(expected), "{tag}: {err}");
        assert!(!written, "{tag}: results were written");
    }
    // Inside the range, one answer in every unit: the event logs agree line for line.
    let events = |s: f64| {
        let dir = support::Scratch::new(&format!("scaled-{s}"));
        let file = dir.0.join("pair.ron");
        std::fs::write(&file, scaled(s)).unwrap();
        let out = dir.0.join("out");
        let o = support::xtask(&[
            "run",
            "pair",
            "-q",
            "--config",
            file.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{s}: {}", support::stderr(&o));
        std::fs::read_to_string(out.join("pair/event-log.csv")).unwrap()
    };
    let unit = events(1.0);
    for s in [1e-9, 1e-3, 1e3, 1e6] {
        assert_eq!(events(s), unit, "scale {s}: other events");
    }
    // The gearing's clearance, before anything runs.
    let s = support::Scratch::new("tiny-clearance");
    let o = support::xtask(&[
        "run",
        "table3",
        "--set",
        "clearance=1e-12",
        "--out",
        s.path("out").as_str(),
    ]);
    let err = support::stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("--set: clearance: 1e-12 % of h") && err.contains("give at least"),
        "{err}"
    );
    assert!(!s.0.join("out").exists());
}
