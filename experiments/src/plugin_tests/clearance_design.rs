//! The `clearance-design` experiment's tests: the `tests` module of
//! `plugins/clearance_design.rs`, kept beside the plugins so that the plugin file holds the
//! experiment alone.
#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;

#[test]
fn a_pair_run_is_one_turn_of_the_larger_gear_in_years_of_b() {
    let g = Gearing::freeth2006();
    // b2 (64) drives c1 (38): b2 is larger and turns once a year.
    assert_eq!(years_per_pair_run(&g, "b2-c1"), Some(1.0));
    // e3 (223) behind b2-l1 (64:38), l2-m1 (53:96) and m3 (27): 8.88 years.
    let e3 = years_per_pair_run(&g, "m3-e3").unwrap();
    let want = (38.0 * 96.0 * 223.0) / (64.0 * 53.0 * 27.0);
    assert!((e3 - want).abs() < 1e-12, "{e3} vs {want}");
    assert_eq!(years_per_pair_run(&g, "x-y"), None);
}

fn run_with(threads: usize, sets: &[(&str, &str)]) -> Result<Report, RunError> {
    crate::run("clearance-design", 2025, threads, sets)
}

#[test]
fn bad_parameters_are_bad_input() {
    for (k, v) in [
        ("grid", "0,40"),
        ("grid", "40,101"),
        ("grid", "x"),
        ("coarse_trials", "0"),
        ("refine_trials", "5"),
        ("refine_step", "-1"),
        ("runs", "0"),
        ("days", "100"),
        ("cases", ""),
        ("cases", "E"),
        ("clearance", "0"),
    ] {
        let e = run_with(1, &[(k, v)]).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{k}={v}: {e}");
        assert!(e.to_string().contains(k), "{k}={v}: {e}");
    }
}

/// A small run: Case D (jams early, so quick), three clearances, few trials.
const SMALL: [(&str, &str); 6] = [
    ("cases", "D"),
    ("grid", "30,50"),
    ("coarse_trials", "2"),
    ("refine_trials", "3"),
    ("refine_step", "5"),
    ("runs", "3"),
];

#[test]
fn a_small_design_runs_and_its_reference_arm_is_the_failure_study() {
    let r = run_with(2, &SMALL).unwrap();
    // The design, the failure study's arm, its trains, and the Cases' tolerances in mm and deg.
    assert_eq!(r.tables.len(), 4);
    // 15 meshes of one case.
    assert_eq!(r.tables[0].rows.len(), 15);
    assert_eq!(r.tables[1].rows.len(), 1);
    // 3 trains and the mechanism.
    assert_eq!(r.tables[2].rows.len(), 4);
    // Pair runs: 3 coarse values at 2 each, then at most 4 finalists brought to 3.
    let pair = r.trials - 2 * 3;
    assert!(
        (15 * (3 * 2 + 3)..=15 * (3 * 2 + 4 * 3)).contains(&pair),
        "{pair}"
    );
    let best = String::from_utf8(r.files[0].contents.clone()).unwrap();
    for line in best.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        assert_eq!(f[4], "3", "the chosen clearance has refine_trials: {line}");
        assert_eq!(f[11], "3", "so has the reference: {line}");
        let chosen: u64 = f[5].parse().unwrap();
        let reference: u64 = f[12].parse().unwrap();
        assert!(chosen <= reference, "{line}");
    }

    // The reference arm's runs are failure's runs with the same seed, cases and count.
    let map = registry::experiments().unwrap();
    let set = |k: &str, v: &str| (k.to_string(), v.to_string());
    let ctx = registry::Context::new(
        map["failure"],
        2025,
        2,
        &[set("cases", "D"), set("trials", "3")],
        None,
    )
    .unwrap();
    let f = (map["failure"].run)(&ctx, ctx.engine()).unwrap().report;
    let theirs = String::from_utf8(f.files[0].contents.clone()).unwrap();
    let ours = String::from_utf8(r.files[2].contents.clone()).unwrap();
    let ours_at_40: Vec<String> = ours
        .lines()
        .filter(|l| l.starts_with("D at 40 %,"))
        .map(|l| l.replacen("D at 40 %,", "D,", 1))
        .collect();
    let theirs: Vec<&str> = theirs.lines().skip(1).collect();
    assert_eq!(ours_at_40.len(), 12);
    assert_eq!(ours_at_40, theirs);
}

#[test]
fn a_horizon_beyond_a_year_is_counted_whole() {
    let sets = [
        ("cases", "D"),
        ("grid", "40"),
        ("coarse_trials", "1"),
        ("refine_trials", "1"),
        ("refine_step", "0"),
        ("runs", "2"),
        ("days", "730.5"),
    ];
    let r = run_with(1, &sets).unwrap();
    let notes = r.tables[2].notes.join("\n");
    assert!(
        notes.contains("Within the whole horizon (730.50 days of b): 2/2 at 40 %"),
        "{notes}"
    );
    // At one year (the default) there is no such note.
    let one_year = run_with(1, &sets[..6]).unwrap();
    assert!(
        !one_year.tables[2]
            .notes
            .join("\n")
            .contains("whole horizon")
    );
}

#[test]
fn without_refinement_the_coarse_grid_decides() {
    let sets = [
        ("cases", "D"),
        ("grid", "30,50"),
        ("coarse_trials", "2"),
        ("refine_trials", "2"),
        ("refine_step", "0"),
        ("runs", "1"),
    ];
    let r = run_with(1, &sets).unwrap();
    // 15 meshes x (30, 40, 50) x 2 trials, and one mechanism per setting.
    assert_eq!(r.trials, 15 * 3 * 2 + 2);
}

/// The `<text>` bodies of an SVG, trimmed.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| Some(t[t.find('>')? + 1..t.find("</text>")?].trim().to_owned()))
        .collect()
}

#[test]
fn every_cases_plot_shares_its_axes_and_names_meshes_no_clearance_saves() {
    let sets = [
        ("cases", "A,D"),
        ("grid", "30,50"),
        ("coarse_trials", "2"),
        ("refine_step", "0"),
        ("runs", "1"),
    ];
    let r = run_with(2, &sets).unwrap();
    let plots: Vec<String> = r
        .files
        .iter()
        .filter(|f| f.name.starts_with("clearance-design-case-"))
        .map(|f| String::from_utf8(f.contents.clone()).unwrap())
        .collect();
    assert_eq!(plots.len(), 2);
    // The same tick labels on both: one x range (every clearance tried), y 0-100 %.
    let ticks = |svg: &str| -> Vec<String> {
        texts(svg)
            .into_iter()
            .filter(|t| t.parse::<f64>().is_ok())
            .collect()
    };
    assert_eq!(ticks(&plots[0]), ticks(&plots[1]));
    assert!(
        ticks(&plots[0]).contains(&"100".to_owned()),
        "{:?}",
        ticks(&plots[0])
    );
    // Case D at 2 trials a clearance: its worst meshes fail every run at every clearance, and
    // the legend says so instead of calling one clearance the best.
    let legends: Vec<String> = texts(&plots[1])
        .into_iter()
        .filter(|t| t.contains(" (") && t.contains('-'))
        .collect();
    assert!(!legends.is_empty(), "{:?}", texts(&plots[1]));
    for l in &legends {
        assert!(
            l.contains("fails at every G tried; fewest at") || l.contains("(best "),
            "{l}"
        );
    }
    assert!(
        legends.iter().any(|l| l.contains("fails at every G tried")),
        "{legends:?}"
    );
}
