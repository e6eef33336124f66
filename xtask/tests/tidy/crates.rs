//! The crates as a whole: each library says what it is, names every dependency it declares,
//! and none holds more than its share of the product (a crate that grows past a fifth of the
//! house is doing several jobs; `experiments` holds the plugins and little else).

use std::fs;
use std::path::Path;

use crate::source::{crate_dirs, crate_name, product_files, product_text, rel, root};

#[test]
fn every_library_says_what_it_is() {
    for krate in crate_dirs() {
        let lib = krate.join("src/lib.rs");
        let main = krate.join("src/main.rs");
        let file = if lib.is_file() { lib } else { main };
        let text = fs::read_to_string(&file).unwrap();
        let first = text.lines().next().unwrap_or_default();
        assert!(
            first.starts_with("//! ") && first.len() > 10,
            "{}: the first line should be a `//!` saying what the crate is, got `{first}`",
            rel(&file)
        );
    }
}

/// The names of a manifest's dependencies in the given tables (`[dependencies]`,
/// `[build-dependencies]`, ...), as its code spells them (`-` as `_`).
pub fn dependencies(manifest: &str, tables: &[&str]) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = tables.contains(&line);
            continue;
        }
        if inside && let Some((name, _)) = line.split_once(['=', '.']) {
            let name = name.trim();
            if !name.is_empty() && !name.starts_with('#') {
                out.push(name.replace('-', "_"));
            }
        }
    }
    out
}

/// What the product (not the tests) depends on.
pub const PRODUCT_TABLES: &[&str] = &["[dependencies]", "[build-dependencies]"];

/// Whether `code` names the crate `dep` as a path's first segment (`dep::x`, `use dep`,
/// `dep as`, `extern crate dep`), not as the tail of another name (`study::whole_mechanism::`
/// does not name `mechanism`).
fn names_crate(code: &str, dep: &str) -> bool {
    let ident = |c: char| c.is_alphanumeric() || c == '_';
    // A path's first segment: after no name, or after a leading `::` (`::replay::X` in a
    // macro) that follows no name, type or call.
    let starts_a_path = |i: usize| match code[..i].strip_suffix("::") {
        Some(before) => !before.ends_with(|c: char| ident(c) || c == '>' || c == ')'),
        None => !code[..i].ends_with(|c: char| ident(c) || c == ':'),
    };
    [format!("{dep}::"), format!("{dep} as ")].iter().any(|p| {
        code.match_indices(p.as_str())
            .any(|(i, _)| starts_a_path(i))
    }) || [format!("use {dep}"), format!("extern crate {dep}")]
        .iter()
        .any(|p| {
            code.match_indices(p.as_str()).any(|(i, m)| {
                !code[i + m.len()..].starts_with(|c: char| c.is_alphanumeric() || c == '_')
            })
        })
}

#[test]
fn no_crate_declares_a_dependency_it_never_names() {
    let mut unused = Vec::new();
    for krate in crate_dirs() {
        let manifest = fs::read_to_string(krate.join("Cargo.toml")).unwrap();
        let code: String = product_files(&krate)
            .iter()
            .map(|f| fs::read_to_string(f).unwrap())
            .collect();
        for dep in dependencies(&manifest, PRODUCT_TABLES) {
            if !names_crate(&code, &dep) {
                unused.push(format!("{}: {dep}", rel(&krate)));
            }
        }
    }
    assert!(
        unused.is_empty(),
        "dependencies never named:\n{}",
        unused.join("\n")
    );
}

#[test]
fn a_crate_is_named_by_a_path_not_by_the_tail_of_another_name() {
    assert!(names_crate("use mechanism::Mechanism;", "mechanism"));
    assert!(names_crate("let m = ::mechanism::run();", "mechanism"));
    assert!(names_crate("f(mechanism::run())", "mechanism"));
    assert!(!names_crate("study::whole_mechanism::RUNS", "mechanism"));
    assert!(!names_crate("use mechanisms::X;", "mechanism"));
    assert!(names_crate("use rand;", "rand"));
    assert!(!names_crate("use rand_chacha::X;", "rand"));
}

#[test]
fn the_dependency_reader_reads_the_tables_asked_for() {
    let manifest = "[package]\nname = \"x\"\n[dependencies]\nrand.workspace = true\n\
                    # a comment\nserde-json = { version = \"1\" }\n[dev-dependencies]\ninsta = \"1\"\n";
    assert_eq!(
        dependencies(manifest, PRODUCT_TABLES),
        ["rand", "serde_json"]
    );
    assert_eq!(dependencies(manifest, &["[dev-dependencies]"]), ["insta"]);
}

/// The product lines of a crate: its product files, each up to its unit tests.
fn product_lines(krate: &Path) -> usize {
    product_files(krate)
        .iter()
        .map(|f| product_text(f).lines().count())
        .sum()
}

/// The largest share of the product lines one crate may hold.
const MAX_SHARE: f64 = 0.20;

/// The most product lines `experiments` may hold: the plugins, each a short file.
const MAX_EXPERIMENTS_LINES: usize = 10_000;

#[test]
fn no_crate_holds_more_than_its_share_of_the_house() {
    let lines: Vec<(String, usize)> = crate_dirs()
        .iter()
        .map(|k| (crate_name(k), product_lines(k)))
        .collect();
    let total: usize = lines.iter().map(|(_, n)| n).sum();
    assert!(total > 10_000, "the count found the workspace: {lines:?}");
    let over: Vec<String> = lines
        .iter()
        .filter(|(_, n)| *n as f64 > MAX_SHARE * total as f64)
        .map(|(c, n)| {
            format!(
                "{c}: {n} of {total} lines ({:.1} %)",
                100.0 * *n as f64 / total as f64
            )
        })
        .collect();
    assert!(
        over.is_empty(),
        "crates holding more than {:.0} % of the product lines (split them by job):\n{}",
        100.0 * MAX_SHARE,
        over.join("\n")
    );
    let experiments = lines.iter().find(|(c, _)| c == "experiments").unwrap().1;
    assert!(
        experiments < MAX_EXPERIMENTS_LINES,
        "experiments holds {experiments} product lines (at most {MAX_EXPERIMENTS_LINES}): \
         move what its plugins share into study or presentation"
    );
}

/// What `experiments/src` may hold beside its plugins: the crate root and the plugins'
/// registration macros.
const EXPERIMENTS_GLUE: &[&str] = &["lib.rs", "register.rs"];

#[test]
fn experiments_holds_plugins_only() {
    let src = root().join("experiments/src");
    let mut others: Vec<String> = fs::read_dir(&src)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| {
            !EXPERIMENTS_GLUE.contains(&n.as_str()) && n != "plugins" && n != "plugin_tests"
        })
        .collect();
    others.sort();
    assert!(
        others.is_empty(),
        "experiments/src holds {others:?} beside its plugins: what plugins share belongs in \
         study (simulations), presentation (what is shown) or a crate of its own"
    );
}
