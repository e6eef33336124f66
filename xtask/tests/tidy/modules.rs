//! The modules of every crate, read with `syn` from its files: the `crate::` and `super::` paths
//! between them form no circle (a circle hides which concern depends on which); the runner's
//! `main.rs` only declares modules and dispatches (nothing else refers to its items); and the
//! contact solver's layers - the exact core, the speed layer, the entry points - never name a
//! layer above them, so that each reads (and the core builds) without the ones above.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use syn::visit::Visit;

use crate::source::{crate_dirs, crate_name, is_test, product_files, root};

/// A crate's modules by path (`""` for the crate root, `shard` for `shard.rs` or
/// `shard/mod.rs`, `shard::partial` for `shard/partial.rs`), each with its source text.
pub type Sources = BTreeMap<String, String>;

/// The module path of `file` under `src`.
fn module_of(src: &Path, file: &Path) -> String {
    let parts: Vec<String> = file
        .strip_prefix(src)
        .unwrap()
        .with_extension("")
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    let keep = |(i, p): (usize, &String)| {
        !(p == "mod" || (i == 0 && parts.len() == 1 && (p == "lib" || p == "main")))
    };
    parts
        .iter()
        .enumerate()
        .filter(|&x| keep(x))
        .map(|(_, p)| p.clone())
        .collect::<Vec<_>>()
        .join("::")
}

/// The sources of a crate's modules (its build script aside: it is no module).
pub fn sources(krate: &Path) -> Sources {
    let src = krate.join("src");
    product_files(krate)
        .into_iter()
        .filter(|f| f.starts_with(&src))
        .map(|f| (module_of(&src, &f), std::fs::read_to_string(&f).unwrap()))
        .collect()
}

/// Every path a file's product code names (tests aside), as segments: `use` trees expanded
/// (`use crate::{a::b, c}` gives `crate::a::b` and `crate::c`), and paths in code and types.
#[derive(Default)]
struct Paths(Vec<Vec<String>>);

impl Paths {
    fn tree(&mut self, prefix: &mut Vec<String>, tree: &syn::UseTree) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.tree(prefix, &p.tree);
                prefix.pop();
            }
            syn::UseTree::Name(n) if n.ident == "self" => self.0.push(prefix.clone()),
            syn::UseTree::Name(n) => self.push(prefix, &n.ident),
            syn::UseTree::Rename(r) => self.push(prefix, &r.ident),
            syn::UseTree::Glob(_) => self.0.push(prefix.clone()),
            syn::UseTree::Group(g) => g.items.iter().for_each(|t| self.tree(prefix, t)),
        }
    }

    fn push(&mut self, prefix: &[String], last: &syn::Ident) {
        let mut p = prefix.to_vec();
        p.push(last.to_string());
        self.0.push(p);
    }
}

impl<'ast> Visit<'ast> for Paths {
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if !is_test(&m.attrs) {
            syn::visit::visit_item_mod(self, m);
        }
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        if !is_test(&f.attrs) {
            syn::visit::visit_item_fn(self, f);
        }
    }

    fn visit_item_use(&mut self, u: &'ast syn::ItemUse) {
        self.tree(&mut Vec::new(), &u.tree);
    }

    fn visit_path(&mut self, p: &'ast syn::Path) {
        self.0
            .push(p.segments.iter().map(|s| s.ident.to_string()).collect());
        syn::visit::visit_path(self, p);
    }
}

/// The paths `text` names (empty if it does not parse: a file `include!`d in pieces).
fn paths(text: &str) -> Vec<Vec<String>> {
    let mut found = Paths::default();
    if let Ok(file) = syn::parse_file(text) {
        found.visit_file(&file);
    }
    found.0
}

/// A path made absolute from module `from`: `crate::a::b` as `a::b`, `super::x` from `m::n` as
/// `m::x`; None for a path that leaves the crate or is relative to `from` itself.
fn absolute(from: &str, path: &[String]) -> Option<Vec<String>> {
    let mut here: Vec<String> = if from.is_empty() {
        Vec::new()
    } else {
        from.split("::").map(str::to_owned).collect()
    };
    match path.first().map(String::as_str) {
        Some("crate") => Some(path[1..].to_vec()),
        Some("self") => {
            here.extend(path[1..].iter().cloned());
            Some(here)
        }
        Some("super") => {
            let mut rest = path;
            while rest.first().is_some_and(|s| s == "super") {
                here.pop()?;
                rest = &rest[1..];
            }
            here.extend(rest.iter().cloned());
            Some(here)
        }
        _ => None,
    }
}

/// The items the crate root re-exports (`pub use solver::Run;`), each with where it comes from.
fn root_reexports(root_text: &str) -> BTreeMap<String, Vec<String>> {
    let mut out = BTreeMap::new();
    let Ok(file) = syn::parse_file(root_text) else {
        return out;
    };
    for item in &file.items {
        if let syn::Item::Use(u) = item {
            let mut found = Paths::default();
            found.tree(&mut Vec::new(), &u.tree);
            for p in found.0 {
                let p = if p.first().is_some_and(|s| s == "crate" || s == "self") {
                    p[1..].to_vec()
                } else {
                    p
                };
                if let Some(last) = p.last() {
                    out.insert(last.clone(), p.clone());
                }
            }
        }
    }
    out
}

/// The module a path (absolute, without `crate`) lands in: its longest prefix that is a module,
/// an item the root re-exports counted as where it comes from.
fn target(path: &[String], sources: &Sources, reexports: &BTreeMap<String, Vec<String>>) -> String {
    let resolved: Vec<String> = match path.first().and_then(|f| reexports.get(f)) {
        Some(from) if !sources.contains_key(&path[0]) => {
            from.iter().chain(&path[1..]).cloned().collect()
        }
        _ => path.to_vec(),
    };
    (0..=resolved.len())
        .rev()
        .map(|n| resolved[..n].join("::"))
        .find(|m| sources.contains_key(m))
        .unwrap_or_default()
}

/// Each module (the root aside: it declares and re-exports all of them) with the modules its
/// `crate::` and `super::` paths land in.
pub fn graph(sources: &Sources) -> BTreeMap<String, BTreeSet<String>> {
    let reexports = sources
        .get("")
        .map(|r| root_reexports(r))
        .unwrap_or_default();
    sources
        .iter()
        .filter(|(m, _)| !m.is_empty())
        .map(|(m, text)| {
            let to: BTreeSet<String> = paths(text)
                .iter()
                .filter_map(|p| absolute(m, p))
                .map(|p| target(&p, sources, &reexports))
                .filter(|t| t != m && !t.is_empty())
                .collect();
            (m.clone(), to)
        })
        .collect()
}

/// A cycle of `graph`, as the modules along it with the first repeated at the end
/// (`a -> b -> a`), or None. Depth-first in the graph's order, so the same one is reported.
pub fn cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn walk(
        node: &str,
        graph: &BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) -> Option<Vec<String>> {
        if let Some(i) = path.iter().position(|p| p == node) {
            let mut c = path[i..].to_vec();
            c.push(node.to_owned());
            return Some(c);
        }
        if !done.insert(node.to_owned()) {
            return None;
        }
        path.push(node.to_owned());
        let found = graph
            .get(node)
            .into_iter()
            .flatten()
            .find_map(|next| walk(next, graph, path, done));
        path.pop();
        found
    }
    let mut done = BTreeSet::new();
    graph
        .keys()
        .find_map(|n| walk(n, graph, &mut Vec::new(), &mut done))
}

#[test]
fn no_crate_has_a_module_circle() {
    let mut circles = Vec::new();
    let mut edges = 0;
    for krate in crate_dirs() {
        let g = graph(&sources(&krate));
        edges += g.values().map(BTreeSet::len).sum::<usize>();
        if let Some(c) = cycle(&g) {
            circles.push(format!("{}: {}", crate_name(&krate), c.join(" -> ")));
        }
    }
    assert!(
        edges > 100,
        "the reader found the modules' paths ({edges} edges)"
    );
    assert!(
        circles.is_empty(),
        "module circles (move what both need to a module below them):\n{}",
        circles.join("\n")
    );
}

/// The items the runner's `main.rs` defines itself (its modules and `use`s aside).
fn root_items(root_text: &str) -> BTreeSet<String> {
    let file = syn::parse_file(root_text).unwrap();
    file.items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Fn(f) => Some(f.sig.ident.to_string()),
            syn::Item::Struct(s) => Some(s.ident.to_string()),
            syn::Item::Enum(e) => Some(e.ident.to_string()),
            syn::Item::Const(c) => Some(c.ident.to_string()),
            syn::Item::Static(s) => Some(s.ident.to_string()),
            syn::Item::Type(t) => Some(t.ident.to_string()),
            syn::Item::Trait(t) => Some(t.ident.to_string()),
            _ => None,
        })
        .collect()
}

/// Each module's references to the crate root's own items, as `module: path`.
fn root_references(sources: &Sources) -> Vec<String> {
    let items = root_items(&sources[""]);
    let mut found = Vec::new();
    for (m, text) in sources.iter().filter(|(m, _)| !m.is_empty()) {
        for p in paths(text) {
            let Some(abs) = absolute(m, &p) else { continue };
            if abs.len() == 1 && items.contains(&abs[0]) && !sources.contains_key(&abs[0]) {
                found.push(format!("{m}: {}", p.join("::")));
            }
        }
    }
    found.sort();
    found.dedup();
    found
}

#[test]
fn the_runner_main_only_declares_and_dispatches() {
    let sources = sources(&root().join("xtask"));
    assert!(sources.len() > 10, "{:?}", sources.keys());
    let found = root_references(&sources);
    assert!(
        found.is_empty(),
        "items of xtask's main.rs used elsewhere (move them to a module of their own):\n{}",
        found.join("\n")
    );
}

/// The contact solver's layers, lowest first, and the top-level modules of each.
const CONTACT_LAYERS: [(&str, &[&str]); 3] = [
    (
        "exact core",
        &[
            "tooth", "roots", "meet", "mesh", "closing", "held", "solver", "stats",
        ],
    ),
    ("speed layer", &["speed"]),
    ("entry points", &["entry"]),
];

/// The layer of a top-level module of contact (its index in [`CONTACT_LAYERS`]).
fn layer(module: &str) -> usize {
    let top = module.split("::").next().unwrap();
    CONTACT_LAYERS
        .iter()
        .position(|(_, modules)| modules.contains(&top))
        .unwrap_or_else(|| panic!("contact's module `{top}` is in no layer of CONTACT_LAYERS"))
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
fn the_contact_solver_keeps_its_layers() {
    let g = graph(&sources(&root().join("crates/contact")));
    let names = |m: &str| {
        g.get(m)
            .into_iter()
            .flatten()
            .any(|u| u.starts_with("mesh"))
    };
    assert!(
        names("solver") || names("solver::walk"),
        "the reader finds the solver's paths: {g:?}"
    );
    assert_eq!(
        upward(&g),
        Vec::new(),
        "a layer of contact names one above it"
    );
}

/// Synthetic crates: the readers find what they look for (the tests above would pass on a
/// reader that sees nothing).
fn synthetic(files: &[(&str, &str)]) -> Sources {
    files
        .iter()
        .map(|(m, t)| ((*m).to_owned(), (*t).to_owned()))
        .collect()
}

#[test]
fn the_readers_catch_a_circle_a_root_reference_and_a_layer_crossed() {
    let s = synthetic(&[
        (
            "",
            "mod a;\nmod b;\nmod c;\npub use c::Deep;\ntype Registry = ();\nfn print() {}\nfn main() {}\n",
        ),
        (
            "a",
            "use crate::{Registry, b::{self, x}};\n// crate::c::y in a comment is no use\nfn f() { let s = \"crate::c\"; }\n",
        ),
        ("b", "use crate::Deep;\n"),
        (
            "c",
            "pub struct Deep;\nfn g() { super::print(); }\n#[cfg(test)]\nmod tests { use crate::a::f; }\n",
        ),
        ("c::d", "use super::Deep;\n"),
    ]);
    let g = graph(&s);
    assert_eq!(g["a"], BTreeSet::from(["b".to_owned()]));
    assert_eq!(g["b"], BTreeSet::from(["c".to_owned()]));
    assert_eq!(g["c::d"], BTreeSet::from(["c".to_owned()]));
    assert_eq!(cycle(&g), None, "a test module's paths are no dependency");
    let mut circle = s.clone();
    circle.insert("c".into(), "fn g() { crate::a::f(); }\n".into());
    assert_eq!(
        cycle(&graph(&circle)).unwrap(),
        ["a", "b", "c", "a"].map(str::to_owned)
    );
    assert_eq!(
        root_references(&s),
        ["a: crate::Registry", "c: super::print"]
    );
    let mut layered = BTreeMap::new();
    layered.insert(
        "mesh".to_owned(),
        BTreeSet::from(["speed::cache".to_owned()]),
    );
    layered.insert(
        "speed::cache".to_owned(),
        BTreeSet::from(["solver".to_owned()]),
    );
    assert_eq!(
        upward(&layered),
        vec![("mesh".to_owned(), "speed::cache".to_owned())]
    );
}
