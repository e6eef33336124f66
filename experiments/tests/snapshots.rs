//! Pins the printed table of every registered experiment, and the list of registered ids, in the
//! top-level `snapshots/` folder. Review changes with `cargo insta review`.
#![allow(clippy::unwrap_used, reason = "tests")]

use registry::Context;

/// The one snapshot helper: every snapshot of the project goes through here into `snapshots/`.
fn pin(name: &str, text: &str) {
    let mut settings = insta::Settings::clone_current();
    settings.set_snapshot_path(concat!(env!("CARGO_MANIFEST_DIR"), "/../snapshots"));
    settings.set_prepend_module_to_snapshot(false);
    settings.set_omit_expression(true);
    settings.bind(|| insta::assert_snapshot!(name, text));
}

/// Seed used for every pinned run (the runner's default).
const SEED: u64 = 2025;

#[test]
fn registered_experiment_ids() {
    experiments::link();
    let map = registry::experiments().unwrap();
    let lines: Vec<String> = map
        .values()
        .map(|e| format!("{:<10} {}", e.id, e.paper_item))
        .collect();
    pin("experiment-ids", &lines.join("\n"));
}

#[test]
fn every_experiment_table_is_pinned() {
    experiments::link();
    for (id, exp) in registry::experiments().unwrap() {
        let ctx = Context::new(exp, SEED, 1, &[], None).unwrap();
        let report = (exp.run)(&ctx).unwrap_or_else(|e| panic!("{id}: {e}"));
        pin(id, &report.text());
    }
}
