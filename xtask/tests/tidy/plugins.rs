//! Plugins are leaves: no plugin file (an experiment, a hypothesis, a rule, a motion model)
//! names another plugin of its folder; what several share lives below them.

use std::fs;

use crate::source::{crate_dirs, rel, rust_files};

/// A `src/plugins/` folder: its path, its plugins' names, and each file with its text.
type Folder = (String, Vec<String>, Vec<(String, String)>);

/// Every `src/plugins/` folder of the workspace.
fn plugin_folders() -> Vec<Folder> {
    crate_dirs()
        .iter()
        .map(|k| k.join("src/plugins"))
        .filter(|d| d.is_dir())
        .map(|dir| {
            let files = rust_files(&dir);
            let stems = files
                .iter()
                .map(|f| f.file_stem().unwrap().to_string_lossy().into_owned())
                .collect();
            let texts = files
                .iter()
                .map(|f| (rel(f), fs::read_to_string(f).unwrap()))
                .collect();
            (rel(&dir), stems, texts)
        })
        .collect()
}

/// Where `text` names a plugin of `stems` other than `own`, by any of the paths a plugin could
/// be reached by.
fn names_another(text: &str, own: &str, stems: &[String]) -> Vec<String> {
    stems
        .iter()
        .filter(|s| s.as_str() != own)
        .filter(|s| {
            [
                format!("super::{s}::"),
                format!("plugins::{s}::"),
                format!("crate::{s}::"),
                format!("super::{s};"),
            ]
            .iter()
            .any(|p| text.contains(p.as_str()))
        })
        .cloned()
        .collect()
}

#[test]
fn no_plugin_imports_another() {
    let folders = plugin_folders();
    assert!(folders.len() >= 4, "{} plugin folders", folders.len());
    let mut found = Vec::new();
    for (dir, stems, files) in &folders {
        assert!(stems.len() >= 3, "{dir}: {} plugins", stems.len());
        for (file, text) in files {
            let own = file.rsplit('/').next().unwrap().trim_end_matches(".rs");
            for other in names_another(text, own, stems) {
                found.push(format!("{file} imports {other}"));
            }
        }
    }
    assert!(
        found.is_empty(),
        "plugins importing another (move what they share below them):\n{}",
        found.join("\n")
    );
}

#[test]
fn the_plugin_reader_sees_an_import() {
    let stems = ["table3".to_owned(), "table4".to_owned()];
    assert_eq!(
        names_another("use super::table4::Grid;", "table3", &stems),
        ["table4"]
    );
    assert!(names_another("use study::table4_cells;", "table3", &stems).is_empty());
}

#[test]
fn every_experiment_file_registers_exactly_one_experiment() {
    let folders = plugin_folders();
    let (_, stems, files) = folders
        .iter()
        .find(|(dir, _, _)| dir == "experiments/src/plugins")
        .unwrap();
    for (file, text) in files {
        // One registration: `registry::register!` of a typed experiment, its cell grammar (if
        // any) beside it in `crate::replay_cells!`; nothing else registered around it.
        assert_eq!(
            text.matches("registry::register!(").count(),
            1,
            "{file} should register exactly one experiment, with `registry::register!`"
        );
        assert!(
            text.matches("crate::replay_cells!").count() <= 1,
            "{file} registers more than one cell grammar"
        );
        assert!(
            !text.contains("inventory::submit!"),
            "{file} registers something beside its experiment: one `registry::register!` (with `crate::replay_cells!` for its cell grammar)"
        );
    }
    experiments::link();
    assert_eq!(registry::experiments().unwrap().len(), stems.len());
}
