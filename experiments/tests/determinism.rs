//! A reduced `table1` gives the same bits with one thread and with two.
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
