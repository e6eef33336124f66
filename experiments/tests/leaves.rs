//! Experiments are leaves: each file in `src/plugins/` registers one experiment and imports no
//! other experiment (what several share lives in `study` or the presentation modules).
#![allow(clippy::unwrap_used, reason = "tests")]

use std::fs;
use std::path::Path;

/// (file stem, text) of every plugin file.
fn plugins() -> Vec<(String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/plugins");
    let mut out: Vec<(String, String)> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .map(|p| {
            let stem = p.file_stem().unwrap().to_string_lossy().into_owned();
            (stem, fs::read_to_string(&p).unwrap())
        })
        .collect();
    out.sort();
    out
}

#[test]
fn no_experiment_imports_another() {
    let all = plugins();
    assert!(all.len() >= 20, "{} plugin files", all.len());
    for (stem, text) in &all {
        assert!(
            !text.contains("crate::plugins") && !text.contains("super::super"),
            "{stem}.rs reaches into another experiment"
        );
        for (other, _) in &all {
            let path = format!("crate::{other}::");
            assert!(
                other == stem || !text.contains(&path),
                "{stem}.rs imports {other}: move what they share into `study` or a presentation module"
            );
        }
    }
}

#[test]
fn every_plugin_file_registers_exactly_one_experiment() {
    let all = plugins();
    for (stem, text) in &all {
        // One registration: `registry::register!` of a typed experiment, its cell grammar (if
        // any) beside it in `crate::replay_cells!`; nothing else registered around it.
        let typed = text.matches("registry::register!(").count();
        assert_eq!(
            typed, 1,
            "{stem}.rs should register exactly one experiment, with `registry::register!`"
        );
        assert!(
            text.matches("crate::replay_cells!").count() <= 1,
            "{stem}.rs registers more than one cell grammar"
        );
        assert!(
            !text.contains("inventory::submit!"),
            "{stem}.rs registers something beside its experiment: one `registry::register!` (with `crate::replay_cells!` for its cell grammar)"
        );
    }
    experiments::link();
    assert_eq!(registry::experiments().unwrap().len(), all.len());
}
