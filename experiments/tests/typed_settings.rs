//! Settings are read by their declarations, never by a name typed as a string: `registry`'s
//! `Context`, and the parameter values of hypotheses and rules (`registry::Values`), have no
//! reader that takes a name, so a literal key does not compile (their `compile_fail` examples
//! hold it). Here: `study` takes settings as values, never a `Context`.

use std::path::{Path, PathBuf};

/// Every `.rs` file under `dir`, recursively.
fn sources(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            sources(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

#[test]
fn study_takes_values_not_a_context() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut files = Vec::new();
    sources(&root.join("crates/study/src"), &mut files);
    assert!(!files.is_empty(), "the scan found study's sources");
    let found: Vec<String> = files
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(f).unwrap_or_default();
            text.lines()
                .enumerate()
                .filter(|(_, l)| l.contains("Context"))
                .map(|(i, l)| format!("{}:{}: {}", f.display(), i + 1, l.trim()))
                .collect::<Vec<_>>()
        })
        .collect();
    assert!(
        found.is_empty(),
        "study takes settings as values and trials through `registry::TrialEngine`; the parsing of a Context belongs in experiments/src/settings.rs:\n{}",
        found.join("\n")
    );
}
