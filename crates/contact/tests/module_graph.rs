//! The solver crate's modules, read from `crates/contact/src`: the `crate::` paths between its
//! top-level modules (outside their unit tests) form no cycle, and they keep the order of the
//! crate's layers - the exact core (one tooth, the contact conditions and their roots, the mesh,
//! closings, held gears, the solver, the step counts) names neither the speed layer nor the entry points, and the
//! speed layer does not name the entry points - so each layer can be read without the ones
//! above it, and the core builds without the speed layer.

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

/// The crate's layers, lowest first, and the top-level modules of each.
const LAYERS: [(&str, &[&str]); 3] = [
    (
        "exact core",
        &[
            "tooth", "roots", "meet", "mesh", "closing", "held", "solver", "stats",
        ],
    ),
    ("speed layer", &["speed"]),
    ("entry points", &["entry"]),
];

/// The layer a module belongs to (its index in [`LAYERS`]).
fn layer(module: &str) -> usize {
    LAYERS
        .iter()
        .position(|(_, modules)| modules.contains(&module))
        .unwrap_or_else(|| panic!("module `{module}` is in no layer of LAYERS"))
}

/// Every use of a module of a higher layer than the user's: (user, used).
fn upward(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<(String, String)> {
    graph
        .iter()
        .flat_map(|(m, used)| used.iter().map(move |u| (m.clone(), u.clone())))
        .filter(|(m, u)| layer(u) > layer(m))
        .collect()
}

#[test]
fn the_solver_modules_form_no_cycle_and_keep_their_layers() {
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
        graph["solver"].contains("mesh")
            && graph["speed"].contains("solver")
            && graph["entry"].contains("speed"),
        "the reading of `crate::` paths finds nothing: {graph:?}"
    );
    assert_eq!(cycle(&graph), None, "{graph:?}");
    assert_eq!(upward(&graph), Vec::new(), "a layer names one above it");
    // The same checks find a cycle and a use across the layers where there is one.
    let mut with_cycle = graph.clone();
    with_cycle.get_mut("tooth").unwrap().insert("solver".into());
    assert!(cycle(&with_cycle).is_some());
    let mut core_on_speed = graph.clone();
    core_on_speed
        .get_mut("mesh")
        .unwrap()
        .insert("speed".into());
    assert_eq!(
        upward(&core_on_speed),
        vec![("mesh".to_string(), "speed".to_string())]
    );
}
