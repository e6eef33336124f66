//! The runner's module structure, read from `xtask/src`: no module but `main.rs` refers to an
//! item `main.rs` defines (what every command shares lives in a module of its own, and
//! `main.rs` only declares the modules and dispatches), and the `crate::` paths between modules
//! form no cycle (a module circle hides which concern depends on which).

#![allow(clippy::unwrap_used, reason = "tests fail loudly on purpose")]

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Every `.rs` file under `dir`, by module path (`""` for `main.rs`, `shard` for
/// `shard/mod.rs` or `shard.rs`, `shard::partial` for `shard/partial.rs`), with its text.
fn modules(dir: &Path, prefix: &[String], into: &mut BTreeMap<String, String>) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_stem().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            let mut p = prefix.to_vec();
            p.push(name);
            modules(&path, &p, into);
        } else if path.extension().is_some_and(|x| x == "rs") {
            let mut p = prefix.to_vec();
            if !(name == "mod" || (prefix.is_empty() && name == "main")) {
                p.push(name);
            }
            into.insert(p.join("::"), std::fs::read_to_string(&path).unwrap());
        }
    }
}

/// `text` without comments (doc comments' links name modules without depending on them) and
/// without the contents of string literals.
fn code(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for line in text.lines() {
        let mut in_str = false;
        let mut escaped = false;
        let mut prev = ' ';
        for c in line.chars() {
            if in_str {
                if escaped {
                    escaped = false;
                } else if c == '\\' {
                    escaped = true;
                } else if c == '"' {
                    in_str = false;
                    out.push('"');
                }
                prev = c;
                continue;
            }
            if c == '/' && prev == '/' {
                out.pop();
                break;
            }
            if c == '"' && prev != '\'' {
                in_str = true;
            }
            out.push(c);
            prev = c;
        }
        out.push('\n');
    }
    out
}

fn is_ident(c: char) -> bool {
    c.is_alphanumeric() || c == '_'
}

/// The paths a `use` tree or inline path starting at `s` names, each as its segments
/// (`{a::{b, c}, d}` gives `a::b`, `a::c`, `d`); returns them and the bytes read.
fn tree(s: &str) -> (Vec<Vec<String>>, usize) {
    let s_trim = s.trim_start();
    let mut pos = s.len() - s_trim.len();
    if s_trim.starts_with('{') {
        pos += 1;
        let mut all = Vec::new();
        loop {
            let rest = &s[pos..];
            let skip = rest.len() - rest.trim_start_matches([' ', '\n', '\t', ',']).len();
            pos += skip;
            if s[pos..].starts_with('}') || pos >= s.len() {
                return (all, pos + 1);
            }
            let (paths, used) = tree(&s[pos..]);
            pos += used.max(1);
            all.extend(paths);
            // `x as y`: the alias is no path.
            let rest = &s[pos..];
            if let Some(alias) = rest.trim_start().strip_prefix("as ") {
                let alias = alias.trim_start();
                let name = alias.chars().take_while(|&c| is_ident(c)).count();
                pos = s.len() - alias.len() + name;
            }
        }
    }
    let ident: String = s_trim.chars().take_while(|&c| is_ident(c)).collect();
    if ident.is_empty() {
        return (vec![Vec::new()], pos);
    }
    pos += ident.len();
    if let Some(after) = s[pos..].strip_prefix("::") {
        let (subs, used) = tree(after);
        pos += 2 + used;
        let paths = subs
            .into_iter()
            .map(|mut p| {
                p.insert(0, ident.clone());
                p
            })
            .collect();
        return (paths, pos);
    }
    (vec![vec![ident]], pos)
}

/// Every path a module names through `crate::`, as its segments after `crate`.
fn crate_paths(text: &str) -> Vec<Vec<String>> {
    let code = code(text);
    let mut paths = Vec::new();
    let mut from = 0;
    while let Some(i) = code[from..].find("crate::") {
        let at = from + i;
        from = at + "crate::".len();
        if code[..at].chars().next_back().is_some_and(is_ident) {
            continue;
        }
        let (found, _) = tree(&code[from..]);
        paths.extend(found.into_iter().map(|mut p| {
            if p.last().is_some_and(|s| s == "self") {
                p.pop();
            }
            p
        }));
    }
    paths
}

/// The items `main.rs` defines (not the modules it declares).
fn root_items(text: &str) -> BTreeSet<String> {
    let mut items = BTreeSet::new();
    for line in code(text).lines() {
        let words = line
            .split(|c: char| !is_ident(c) && c != '!')
            .filter(|w| !w.is_empty());
        let mut prev = "";
        for w in words {
            if [
                "fn",
                "type",
                "struct",
                "enum",
                "const",
                "static",
                "trait",
                "macro_rules!",
                "union",
            ]
            .contains(&prev)
                && w != "fn"
            {
                items.insert(w.to_owned());
                break;
            }
            prev = w;
        }
    }
    items
}

/// The module a path names: the longest prefix that is a module; `""` (the crate root, main.rs)
/// when its first segment is no module.
fn target(path: &[String], mods: &BTreeSet<String>) -> String {
    (1..=path.len())
        .rev()
        .map(|n| path[..n].join("::"))
        .find(|m| mods.contains(m))
        .unwrap_or_default()
}

/// Each module's references to `main.rs`'s items, as `module: crate::path`.
fn root_references(srcs: &BTreeMap<String, String>) -> Vec<String> {
    let items = root_items(&srcs[""]);
    let mods: BTreeSet<String> = srcs.keys().cloned().collect();
    let mut found = Vec::new();
    for (m, text) in srcs.iter().filter(|(m, _)| !m.is_empty()) {
        for p in crate_paths(text) {
            let first = p.first().map(String::as_str).unwrap_or("");
            // `crate::print` names both a module and a function of main.rs when both exist:
            // counted as the function, which is what a call or a `use` of it needs.
            let root = target(&p, &mods).is_empty() || (p.len() == 1 && items.contains(first));
            if root && (items.contains(first) || first.is_empty()) {
                found.push(format!("{m}: crate::{}", p.join("::")));
            }
        }
        // A child of the root reaches its items through `super::` as well.
        if !m.contains("::") {
            let code = code(text);
            for item in &items {
                let needle = format!("super::{item}");
                if code.match_indices(&needle).any(|(i, _)| {
                    !code[i + needle.len()..].starts_with(is_ident)
                        && !code[..i].ends_with(is_ident)
                }) {
                    found.push(format!("{m}: {needle}"));
                }
            }
        }
    }
    found
}

/// The `crate::` graph between modules (the root's own references left out: it declares and
/// dispatches to all of them), and a cycle of it if there is one.
fn cycle(srcs: &BTreeMap<String, String>) -> Option<Vec<String>> {
    let mods: BTreeSet<String> = srcs.keys().cloned().collect();
    let mut edges: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (m, text) in srcs.iter().filter(|(m, _)| !m.is_empty()) {
        let to = edges.entry(m.clone()).or_default();
        for p in crate_paths(text) {
            let t = target(&p, &mods);
            if &t != m {
                to.insert(t);
            }
        }
    }
    module_graph::cycle(&edges)
}

fn sources() -> BTreeMap<String, String> {
    let mut srcs = BTreeMap::new();
    modules(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("src"),
        &[],
        &mut srcs,
    );
    srcs
}

#[test]
fn no_module_refers_to_main_rs_items() {
    let srcs = sources();
    assert!(
        srcs.contains_key("") && srcs.len() > 10,
        "{:?}",
        srcs.keys()
    );
    let found = root_references(&srcs);
    assert!(
        found.is_empty(),
        "items of main.rs used elsewhere (move them to a module of their own):\n{}",
        found.join("\n")
    );
}

#[test]
fn modules_form_no_cycle() {
    let srcs = sources();
    if let Some(c) = cycle(&srcs) {
        panic!("module cycle: {}", c.join(" -> "));
    }
}

/// The checks find what they look for (the tests above would pass on a checker that sees nothing).
#[test]
fn the_checks_catch_a_root_reference_and_a_cycle() {
    let srcs: BTreeMap<String, String> = [
        (
            "",
            "mod a;\nmod b;\nmod c;\ntype Registry = ();\nfn print() {}\n/// [`crate::a`]\nfn main() {}\n",
        ),
        (
            "a",
            "use crate::{Registry, b::{self, x}};\n// crate::c::y in a comment is no use\nfn f() { let s = \"crate::c\"; }\n",
        ),
        ("b", "use crate::c::{self as cc};\n"),
        ("c", "fn g() { crate::a::f(); super::print(); }\n"),
        ("c::d", "use crate::c;\n"),
    ]
    .into_iter()
    .map(|(m, t)| (m.to_owned(), t.to_owned()))
    .collect();
    assert_eq!(
        root_items(&srcs[""]),
        ["Registry", "main", "print"]
            .map(str::to_owned)
            .into_iter()
            .collect()
    );
    assert_eq!(
        root_references(&srcs),
        ["a: crate::Registry", "c: super::print"]
    );
    assert_eq!(
        cycle(&srcs).unwrap(),
        ["a", "b", "c", "a"].map(str::to_owned)
    );
    let mut acyclic = srcs.clone();
    acyclic.insert("c".into(), "fn g() {}\n".into());
    assert_eq!(cycle(&acyclic), None);
    assert_eq!(
        crate_paths("use crate::{x::{y, z as w}, v};\nlet _ = crate::q::r(1);"),
        [vec!["x", "y"], vec!["x", "z"], vec!["v"], vec!["q", "r"]]
            .map(|p| p.into_iter().map(str::to_owned).collect::<Vec<_>>())
    );
}
