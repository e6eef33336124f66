//! The structural rules of the house in one place, each measured on the source itself (a real
//! parse with `syn` where a rule is about code, so that braces in strings, comments and macros do
//! not fool it):
//!
//! - every function fits on a screen: at most 80 lines in an experiment's plugin file and in the
//!   presentation (charts, pictures, pages), at most 100 in all other product code (tests aside);
//! - every library crate opens with a one-line `//!` saying what it is;
//! - no parameter is looked up by a name typed again as a string literal (a parameter is read
//!   by its declaration: `ctx.get(&CLEARANCE)`, a settings struct's field);
//! - no crate declares a dependency its code never names.
//!
//! Layering, module circles and the code map are held by `module_graph.rs` and
//! `architecture.rs` beside this file.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::fs;
use std::path::{Path, PathBuf};

use syn::visit::Visit;

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Every crate folder: `crates/*`, `experiments`, `xtask`.
fn crate_dirs() -> Vec<PathBuf> {
    let root = root();
    let mut dirs: Vec<PathBuf> = fs::read_dir(root.join("crates"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("Cargo.toml").is_file())
        .collect();
    dirs.push(root.join("experiments"));
    dirs.push(root.join("xtask"));
    dirs.sort();
    dirs
}

/// Every `.rs` file under `dir`, recursively.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let Ok(entries) = fs::read_dir(dir) else {
        return out;
    };
    for e in entries {
        let p = e.unwrap().path();
        if p.is_dir() {
            out.extend(rust_files(&p));
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
    out.sort();
    out
}

/// The product source files of a crate: its `src/` (a plugin's tests kept in `plugin_tests/`
/// aside) and its build script.
fn product_files(krate: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = rust_files(&krate.join("src"))
        .into_iter()
        .filter(|p| !p.components().any(|c| c.as_os_str() == "plugin_tests"))
        .collect();
    if krate.join("build.rs").is_file() {
        files.push(krate.join("build.rs"));
    }
    files
}

/// Whether the attributes mark test code (`#[test]`, `#[cfg(test)]`).
fn is_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("test")
            || (a.path().is_ident("cfg")
                && a.meta
                    .require_list()
                    .is_ok_and(|l| l.tokens.to_string().split(',').any(|t| t.trim() == "test")))
    })
}

/// (name, first line, line count) of every function outside test code.
#[derive(Default)]
struct Lengths(Vec<(String, usize, usize)>);

impl Lengths {
    /// From the `fn` keyword (not the doc comment above it) to the closing brace.
    fn record(&mut self, sig: &syn::Signature, block: &syn::Block) {
        let start = sig.fn_token.span.start().line;
        let end = block.brace_token.span.close().end().line;
        self.0.push((sig.ident.to_string(), start, end - start + 1));
    }
}

impl<'ast> Visit<'ast> for Lengths {
    fn visit_item_mod(&mut self, m: &'ast syn::ItemMod) {
        if !is_test(&m.attrs) {
            syn::visit::visit_item_mod(self, m);
        }
    }

    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        if !is_test(&f.attrs) {
            self.record(&f.sig, &f.block);
            syn::visit::visit_item_fn(self, f);
        }
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        if !is_test(&f.attrs) {
            self.record(&f.sig, &f.block);
            syn::visit::visit_impl_item_fn(self, f);
        }
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if let Some(block) = &f.default {
            self.record(&f.sig, block);
        }
        syn::visit::visit_trait_item_fn(self, f);
    }
}

/// The most lines a function of `file` may span: 80 in plugins and presentation, else 100.
fn max_lines(file: &Path) -> usize {
    let rel = file
        .strip_prefix(root())
        .unwrap()
        .to_string_lossy()
        .into_owned();
    let screen = rel.starts_with("experiments/src/")
        || rel.starts_with("crates/presentation/")
        || rel.contains("/src/plugins/");
    if screen { 80 } else { 100 }
}

#[test]
fn every_function_fits_on_a_screen() {
    let mut long = Vec::new();
    for krate in crate_dirs() {
        for file in product_files(&krate) {
            let text = fs::read_to_string(&file).unwrap();
            let parsed =
                syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
            let mut lengths = Lengths::default();
            lengths.visit_file(&parsed);
            let max = max_lines(&file);
            for (name, line, n) in lengths.0 {
                if n > max {
                    let rel = file.strip_prefix(root()).unwrap().display().to_string();
                    long.push(format!("{rel}:{line} `{name}`: {n} lines (at most {max})"));
                }
            }
        }
    }
    assert!(
        long.is_empty(),
        "functions longer than a screen (name their phases):\n{}",
        long.join("\n")
    );
}

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
            file.display()
        );
    }
}

/// The product text of `file` before its first `#[cfg(test)]` (tests may name parameters as a
/// user types them).
fn product_text(file: &Path) -> String {
    let text = fs::read_to_string(file).unwrap();
    match text.find("#[cfg(test)]") {
        Some(at) => text[..at].to_owned(),
        None => text,
    }
}

#[test]
fn no_parameter_is_looked_up_by_a_name_typed_again() {
    // A parameter (`p`, `param`, a context's value) compared with, or fetched by, a literal.
    let forbidden = [
        "p.name == \"",
        "param.name == \"",
        ".name == \"trials\"",
        ".name == \"clearance",
        ".name == \"hypothesis",
        ".name == \"events\"",
        "inputs.get(\"",
        "values().find(|(p, _)| p.name == \"",
    ];
    let mut found = Vec::new();
    for krate in crate_dirs() {
        for file in product_files(&krate) {
            let text = product_text(&file);
            for (i, line) in text.lines().enumerate() {
                if forbidden.iter().any(|f| line.contains(f)) {
                    let rel = file.strip_prefix(root()).unwrap().display().to_string();
                    found.push(format!("{rel}:{}: {}", i + 1, line.trim()));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "parameters looked up by a name typed again (read them by their declaration):\n{}",
        found.join("\n")
    );
}

/// The names of the `[dependencies]` (and `[build-dependencies]`) of a crate's manifest, as its
/// code spells them (`-` as `_`).
fn dependencies(manifest: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut inside = false;
    for line in manifest.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            inside = line == "[dependencies]" || line == "[build-dependencies]";
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

#[test]
fn no_crate_declares_a_dependency_it_never_names() {
    let mut unused = Vec::new();
    for krate in crate_dirs() {
        let manifest = fs::read_to_string(krate.join("Cargo.toml")).unwrap();
        let code: String = product_files(&krate)
            .iter()
            .map(|f| fs::read_to_string(f).unwrap())
            .collect();
        for dep in dependencies(&manifest) {
            if !code.contains(&format!("{dep}::"))
                && !code.contains(&format!("use {dep}"))
                && !code.contains(&format!("{dep} as"))
                && !code.contains(&format!("extern crate {dep}"))
            {
                unused.push(format!("{}: {dep}", krate.display()));
            }
        }
    }
    assert!(
        unused.is_empty(),
        "dependencies never named:\n{}",
        unused.join("\n")
    );
}
