//! Settings are read by their declarations, never by a name typed as a string: outside the
//! `registry` crate no source reads a parameter with a literal key (`ctx.f64("clearance")`).
//! A literal key compiles whatever it names - another experiment's parameter, a misspelling, a
//! parameter that shares a name with another (fig5's own `clearance` is not the gearing's) - and
//! fails only when that code runs; a declaration (`ctx.get(&CLEARANCE)`) is checked by the
//! compiler, and by `Context::get` against the one the experiment declares.

use std::path::{Path, PathBuf};

/// Reads of a parameter by a literal key: the `Context` readers, and the helpers that take a
/// parameter's name.
const LITERAL_READS: &[&str] = &[
    ".f64(\"",
    ".usize(\"",
    ".u64(\"",
    ".param(\"",
    ".str(\"",
    ".text(\"",
    ".bool(\"",
    ".declares(\"",
    "value(ctx, \"",
    "clearance_list(ctx, \"",
    "::read(ctx, \"",
];

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

/// The literal-keyed reads in `text`, as `line: text`.
fn literal_reads(text: &str) -> Vec<String> {
    text.lines()
        .enumerate()
        .filter(|(_, line)| LITERAL_READS.iter().any(|p| line.contains(p)))
        .map(|(i, line)| format!("{}: {}", i + 1, line.trim()))
        .collect()
}

/// Files that hold the patterns for another reason: this test's own samples, and the cluster
/// manifests' YAML reader (`.str("name")` reads a YAML field, not a parameter).
const NOT_READS: &[&str] = &[
    "experiments/tests/typed_settings.rs",
    "xtask/tests/cluster.rs",
];

/// The source directories scanned: the experiments and their tests, the runner and its tests,
/// and every crate but `registry`, which defines the readers (and tests them by name).
fn scanned() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_default();
    let mut dirs = vec![
        root.join("experiments/src"),
        root.join("experiments/tests"),
        root.join("xtask/src"),
        root.join("xtask/tests"),
    ];
    if let Ok(crates) = std::fs::read_dir(root.join("crates")) {
        for c in crates.flatten() {
            if c.file_name() != "registry" {
                dirs.push(c.path().join("src"));
            }
        }
    }
    dirs
}

#[test]
fn no_parameter_is_read_by_a_literal_key() {
    let mut files = Vec::new();
    for dir in scanned() {
        sources(&dir, &mut files);
    }
    assert!(
        files
            .iter()
            .any(|f| f.ends_with("experiments/src/plugins/table5.rs")),
        "the scan found the plugins"
    );
    assert!(
        files.iter().any(|f| f.ends_with("xtask/src/tests.rs")),
        "the scan found the runner's tests"
    );
    let mut found = Vec::new();
    for f in &files {
        if NOT_READS.iter().any(|n| f.ends_with(n)) {
            continue;
        }
        let text = std::fs::read_to_string(f).unwrap_or_default();
        for hit in literal_reads(&text) {
            found.push(format!("{}:{hit}", f.display()));
        }
    }
    assert!(
        found.is_empty(),
        "parameters read by a literal key; read them by their declaration (ctx.get(&PARAM), ctx.text(&PARAM)) or a setting group's struct:\n{}",
        found.join("\n")
    );
}

#[test]
fn the_scan_sees_a_literal_read() {
    let sample = "fn f(ctx: &Context) {\n    let g = ctx.f64(\"clearance\")?;\n    let h = ctx.get(&TOOTH_HEIGHT)?;\n}";
    assert_eq!(
        literal_reads(sample),
        ["2: let g = ctx.f64(\"clearance\")?;"]
    );
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
