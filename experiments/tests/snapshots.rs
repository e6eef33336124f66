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
    let w = map.keys().map(|id| id.len()).max().unwrap_or(0);
    let lines: Vec<String> = map
        .values()
        .map(|e| format!("{:<w$} {}", e.id, e.paper_item))
        .collect();
    pin("experiment-ids", &lines.join("\n"));
}

/// The registered error hypotheses with their parameters and defaults (`cargo xtask
/// hypotheses`): a plugin added, removed or with a changed default shows here.
#[test]
fn registered_hypotheses() {
    hypotheses::link();
    pin("hypotheses", &hypotheses::listing());
}

/// The registered event rules with their parameters (`cargo xtask rules`): a rule added,
/// removed or with a changed default shows here.
#[test]
fn registered_rules() {
    rules::link();
    pin("rules", &rules::listing());
}

/// Every experiment in one process, so that cells one experiment ran are reused by the next
/// (Table 5 reads Table 4's grid from the cache) and each is computed once. A failing
/// experiment does not hide the others: each runs and is compared, and the test then fails
/// naming every experiment whose table moved or that failed to run.
#[test]
fn every_experiment_table_is_pinned() {
    experiments::link();
    let mut failed = Vec::new();
    for (id, exp) in registry::experiments().unwrap() {
        let checked = std::panic::catch_unwind(|| {
            let ctx = Context::new(exp, SEED, 1, &[], None).unwrap();
            let report = (exp.run)(&ctx).unwrap_or_else(|e| panic!("{id}: {e}"));
            pin(id, &report.text());
            // The README's results section shows these tables as computed here.
            if id == "sensitivity" || id == "event-rules" {
                readme_carries(id, &report.tables[0].render());
            }
        });
        if checked.is_err() {
            failed.push(id);
        }
    }
    assert!(
        failed.is_empty(),
        "{} experiments moved or failed (each reported above): {}",
        failed.len(),
        failed.join(", ")
    );
}

/// The marks around experiment `id`'s computed block in README.md.
fn readme_marks(id: &str) -> (String, String) {
    (
        format!("<!-- {id} table: written by experiments/tests/snapshots.rs -->"),
        format!("<!-- end of the {id} table -->"),
    )
}

/// The README's results section shows experiment `id`'s first table as this pinned run computes
/// it. With `UPDATE_README=1` the block is rewritten; otherwise a difference fails, so the README
/// cannot drift from the snapshot.
fn readme_carries(id: &str, table: &str) {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md");
    let text = std::fs::read_to_string(path).unwrap();
    let (start, end) = readme_marks(id);
    let (Some(a), Some(b)) = (text.find(&start), text.find(&end)) else {
        panic!("README.md has no block between `{start}` and `{end}`");
    };
    let block = format!("\n\n{}\n\n", table.trim());
    let current = &text[a + start.len()..b];
    if current == block {
        return;
    }
    if std::env::var_os("UPDATE_README").is_some() {
        let updated = format!("{}{block}{}", &text[..a + start.len()], &text[b..]);
        std::fs::write(path, updated).unwrap();
    } else {
        panic!(
            "README.md's {id} table is not the computed one; rerun with UPDATE_README=1 and review `git diff README.md`.\ncomputed:\n{table}"
        );
    }
}
