//! The workspace read as the rules see it: crates, their product files, their product text.

use std::fs;
use std::path::{Path, PathBuf};

/// The workspace root.
pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// `file` relative to the workspace root, for messages.
pub fn rel(file: &Path) -> String {
    file.strip_prefix(root())
        .unwrap_or(file)
        .display()
        .to_string()
}

/// Every crate folder: `crates/*`, `experiments`, `xtask`.
pub fn crate_dirs() -> Vec<PathBuf> {
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

/// A crate's name: its folder's (the house names each folder as its crate).
pub fn crate_name(krate: &Path) -> String {
    krate.file_name().unwrap().to_string_lossy().into_owned()
}

/// Every `.rs` file under `dir`, recursively.
pub fn rust_files(dir: &Path) -> Vec<PathBuf> {
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

/// Whether `file` is a plugin's tests (kept beside the plugins, not product code).
fn is_plugin_test(file: &Path) -> bool {
    file.components().any(|c| c.as_os_str() == "plugin_tests")
}

/// The product source files of a crate: its `src/` (a plugin's tests kept in `plugin_tests/`
/// aside) and its build script.
pub fn product_files(krate: &Path) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = rust_files(&krate.join("src"))
        .into_iter()
        .filter(|p| !is_plugin_test(p))
        .collect();
    if krate.join("build.rs").is_file() {
        files.push(krate.join("build.rs"));
    }
    files
}

/// Whether the attributes mark test code (`#[test]`, `#[cfg(test)]`).
pub fn is_test(attrs: &[syn::Attribute]) -> bool {
    attrs.iter().any(|a| {
        a.path().is_ident("test")
            || (a.path().is_ident("cfg")
                && a.meta
                    .require_list()
                    .is_ok_and(|l| l.tokens.to_string().split(',').any(|t| t.trim() == "test")))
    })
}

/// The product text of `file`: everything before its first `#[cfg(test)]` (the house keeps a
/// file's unit tests at its end).
pub fn product_text(file: &Path) -> String {
    let text = fs::read_to_string(file).unwrap();
    match text.find("#[cfg(test)]") {
        Some(at) => text[..at].to_owned(),
        None => text,
    }
}

/// `file` parsed, or a failure naming it.
pub fn parse(file: &Path) -> syn::File {
    let text = fs::read_to_string(file).unwrap();
    syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", rel(file)))
}
