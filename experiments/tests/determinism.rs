//! Reduced `table1` and `clearance-design` runs give the same bits with one thread and with two.
#![allow(clippy::unwrap_used, reason = "tests")]

use registry::Context;

fn table1_text(threads: usize) -> String {
    experiments::link();
    let map = registry::experiments().unwrap();
    let exp = map["table1"];
    let set = |k: &str, v: &str| (k.to_string(), v.to_string());
    let overrides = [
        set("trials", "4"),
        set("lunar_turns", "0.2"),
        set("metonic_turns", "0.2"),
        set("saros_turns", "0.2"),
        set("games_turns", "0.2"),
        set("exeligmos_turns", "0.2"),
        set("samples_per_engagement", "4"),
    ];
    let ctx = Context::new(exp, 99, threads, &overrides, None).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| (exp.run)(&ctx).unwrap().text())
}

#[test]
fn table1_is_identical_with_one_and_two_threads() {
    assert_eq!(table1_text(1), table1_text(2));
}

/// A reduced `clearance-design` (Case D, two grid values, few trials) with `threads` threads,
/// its cell cache emptied first so that every pair run is computed again.
fn clearance_design_report(threads: usize) -> registry::Report {
    experiments::link();
    experiments::forget_cached_cells();
    let map = registry::experiments().unwrap();
    let exp = map["clearance-design"];
    let set = |k: &str, v: &str| (k.to_string(), v.to_string());
    let overrides = [
        set("cases", "D"),
        set("grid", "30,50"),
        set("coarse_trials", "3"),
        set("refine_trials", "4"),
        set("runs", "4"),
    ];
    let ctx = Context::new(exp, 99, threads, &overrides, None).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| (exp.run)(&ctx).unwrap())
}

#[test]
fn clearance_design_is_identical_with_one_and_two_threads() {
    assert_eq!(clearance_design_report(1), clearance_design_report(2));
}
