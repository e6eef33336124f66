//! Reduced `table1` and `clearance-design` runs give the same bits with one thread and with two.
#![allow(clippy::unwrap_used, reason = "tests")]

fn table1_text(threads: usize) -> String {
    let sets = [
        ("trials", "4"),
        ("lunar_turns", "0.2"),
        ("metonic_turns", "0.2"),
        ("saros_turns", "0.2"),
        ("games_turns", "0.2"),
        ("exeligmos_turns", "0.2"),
        ("samples_per_engagement", "4"),
    ];
    experiments::run("table1", 99, threads, &sets)
        .unwrap()
        .text()
}

#[test]
fn table1_is_identical_with_one_and_two_threads() {
    assert_eq!(table1_text(1), table1_text(2));
}

/// A reduced `clearance-design` (Case D, two grid values, few trials) with `threads` threads,
/// its cell cache emptied first so that every pair run is computed again.
fn clearance_design_report(threads: usize) -> registry::Report {
    experiments::forget_cached_cells();
    let sets = [
        ("cases", "D"),
        ("grid", "30,50"),
        ("coarse_trials", "3"),
        ("refine_trials", "4"),
        ("runs", "4"),
    ];
    experiments::run("clearance-design", 99, threads, &sets).unwrap()
}

#[test]
fn clearance_design_is_identical_with_one_and_two_threads() {
    assert_eq!(clearance_design_report(1), clearance_design_report(2));
}
