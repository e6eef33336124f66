//! Settings are read by their declarations, never by a name typed as a string: `registry`'s
//! `Context`, and the parameter values of hypotheses and rules (`registry::Values`), have no
//! reader that takes a name, so a literal key does not compile (their `compile_fail` examples
//! hold it). Here: `study` takes settings as values, never a `Context`; and neither `study` nor
//! an experiment makes a random generator itself: every trial draws through the trial engine's
//! one scheme (`registry::Streams`, named by a `study::draws::Draws`).

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

/// The workspace's folder.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default()
}

/// Every line of `files` on which `hit` holds, as `file:line: text`.
fn lines_where(files: &[PathBuf], hit: impl Fn(&str) -> bool) -> Vec<String> {
    files
        .iter()
        .flat_map(|f| {
            let text = std::fs::read_to_string(f).unwrap_or_default();
            text.lines()
                .enumerate()
                .filter(|(_, l)| hit(l))
                .map(|(i, l)| format!("{}:{}: {}", f.display(), i + 1, l.trim()))
                .collect::<Vec<_>>()
        })
        .collect()
}

#[test]
fn study_takes_values_not_a_context() {
    let mut files = Vec::new();
    sources(&root().join("crates/study/src"), &mut files);
    assert!(!files.is_empty(), "the scan found study's sources");
    let found = lines_where(&files, |l| l.contains("Context"));
    assert!(
        found.is_empty(),
        "study takes settings as values and trials through `registry::TrialEngine`; the parsing of a Context belongs in experiments/src/settings.rs:\n{}",
        found.join("\n")
    );
}

/// Every random number a study or an experiment draws comes from `registry::Streams` (through
/// `TrialEngine::stream` or a `study::draws::Draws`): none makes or reseeds a generator itself,
/// so one place says how a trial's numbers are chosen and no two studies share a stream by
/// accident.
#[test]
fn no_study_or_experiment_makes_a_generator() {
    let mut files = Vec::new();
    sources(&root().join("crates/study/src"), &mut files);
    sources(&root().join("experiments/src"), &mut files);
    assert!(files.len() > 50, "the scan found the sources");
    let makers = ["trial_rng(", "seed_from_u64", "set_stream", "from_seed"];
    let found = lines_where(&files, |l| makers.iter().any(|m| l.contains(m)));
    assert!(
        found.is_empty(),
        "draw through `TrialEngine::stream` / `Draws::stream` (registry's one scheme), naming what the draws are for in `study::draws`:\n{}",
        found.join("\n")
    );
}
