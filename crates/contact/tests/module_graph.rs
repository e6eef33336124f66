//! The solver crate's modules, read from `crates/contact/src`: the `crate::` paths between its
//! top-level modules (outside their unit tests) form no cycle, so each layer - one tooth, the
//! mesh, the contact conditions and their roots, the solver, the certificates it may use for
//! speed - can be read without the ones above it.

#![allow(clippy::unwrap_used, reason = "tests fail loudly on purpose")]

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use module_graph::cycle;

/// Each top-level module (`mesh` for `mesh.rs`, `solver` for everything under `solver/`) with
/// the code of its files, unit tests and comments left out.
fn modules(src: &Path) -> BTreeMap<String, String> {
    let mut out: BTreeMap<String, String> = BTreeMap::new();
    let mut add = |module: String, path: &Path| {
        let text = std::fs::read_to_string(path).unwrap();
        let body = text.split("#[cfg(test)]").next().unwrap();
        let code: String = body
            .lines()
            .map(|l| l.split("//").next().unwrap())
            .collect::<Vec<_>>()
            .join("\n");
        out.entry(module).or_default().push_str(&code);
    };
    for entry in std::fs::read_dir(src).unwrap() {
        let path = entry.unwrap().path();
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            for inner in std::fs::read_dir(&path).unwrap() {
                add(name.clone(), &inner.unwrap().path());
            }
        } else if name != "lib" {
            add(name, &path);
        }
    }
    out
}

/// The items `lib.rs` re-exports at the crate root, each with the module it comes from.
fn reexports(lib: &str) -> BTreeMap<String, String> {
    let mut out = BTreeMap::new();
    for item in lib.split("pub use ").skip(1) {
        let item = item.split(';').next().unwrap();
        let (module, names) = item.split_once("::").unwrap();
        for name in names.split([',', '{', '}', ' ', '\n']) {
            if !name.is_empty() {
                out.insert(name.to_string(), module.to_string());
            }
        }
    }
    out
}

/// The modules a module's code names through `crate::` (a module, or an item re-exported at the
/// root, counted as its module).
fn uses(
    code: &str,
    names: &BTreeSet<String>,
    roots: &BTreeMap<String, String>,
) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for after in code.split("crate::").skip(1) {
        let heads: Vec<&str> = match after.strip_prefix('{') {
            Some(list) => list.split('}').next().unwrap().split(',').collect(),
            None => vec![after],
        };
        for head in heads {
            let ident: String = head
                .trim_start()
                .chars()
                .take_while(|c| c.is_alphanumeric() || *c == '_')
                .collect();
            if names.contains(&ident) {
                out.insert(ident);
            } else if let Some(module) = roots.get(&ident) {
                out.insert(module.clone());
            }
        }
    }
    out
}

#[test]
fn the_solver_modules_form_no_cycle() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let modules = modules(&src);
    let roots = reexports(&std::fs::read_to_string(src.join("lib.rs")).unwrap());
    let names: BTreeSet<String> = modules.keys().cloned().collect();
    let graph: BTreeMap<String, BTreeSet<String>> = modules
        .iter()
        .map(|(m, code)| {
            let mut used = uses(code, &names, &roots);
            used.remove(m);
            (m.clone(), used)
        })
        .collect();
    assert!(
        graph["solver"].contains("mesh") && graph["mesh"].contains("certify"),
        "the reading of `crate::` paths finds nothing: {graph:?}"
    );
    assert_eq!(cycle(&graph), None, "{graph:?}");
    // The same check finds a cycle where there is one.
    let mut with_cycle = graph.clone();
    with_cycle.get_mut("tooth").unwrap().insert("solver".into());
    assert!(cycle(&with_cycle).is_some());
}
