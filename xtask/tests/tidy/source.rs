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

/// The attributes of an item of a file (those kinds a test can be).
fn item_attrs(item: &syn::Item) -> &[syn::Attribute] {
    match item {
        syn::Item::Mod(i) => &i.attrs,
        syn::Item::Fn(i) => &i.attrs,
        syn::Item::Use(i) => &i.attrs,
        syn::Item::Impl(i) => &i.attrs,
        syn::Item::Const(i) => &i.attrs,
        syn::Item::Static(i) => &i.attrs,
        syn::Item::Struct(i) => &i.attrs,
        syn::Item::Enum(i) => &i.attrs,
        syn::Item::Macro(i) => &i.attrs,
        syn::Item::Type(i) => &i.attrs,
        syn::Item::Trait(i) => &i.attrs,
        _ => &[],
    }
}

/// The lines (first, last; 1-based) of `text`'s top-level test items, their attributes included.
fn test_items(text: &str) -> Vec<(usize, usize)> {
    use syn::spanned::Spanned;
    let Ok(file) = syn::parse_file(text) else {
        return Vec::new();
    };
    file.items
        .iter()
        .filter(|item| is_test(item_attrs(item)))
        .map(|item| {
            let first = item_attrs(item)[0].pound_token.span.start().line;
            (first, item.span().end().line)
        })
        .collect()
}

/// The product text of `text`: its lines outside top-level test items (`#[cfg(test)] mod
/// tests`, a `#[cfg(test)] use`, a `#[test] fn`), wherever in the file they stand.
pub fn product_lines_of(text: &str) -> String {
    let tests = test_items(text);
    text.lines()
        .enumerate()
        .filter(|(i, _)| !tests.iter().any(|&(a, b)| (a..=b).contains(&(i + 1))))
        .map(|(_, l)| l)
        .collect::<Vec<_>>()
        .join("\n")
}

/// The product text of `file` (see [`product_lines_of`]).
pub fn product_text(file: &Path) -> String {
    product_lines_of(&fs::read_to_string(file).unwrap())
}

#[test]
fn product_text_leaves_out_test_items_wherever_they_stand() {
    let text = "fn a() {}\n#[cfg(test)]\nuse x::y;\nfn b() {\n    1;\n}\n#[cfg(test)]\nmod tests {\n    fn t() {}\n}\n";
    assert_eq!(product_lines_of(text), "fn a() {}\nfn b() {\n    1;\n}");
}

/// `file` parsed, or a failure naming it.
pub fn parse(file: &Path) -> syn::File {
    let text = fs::read_to_string(file).unwrap();
    syn::parse_file(&text).unwrap_or_else(|e| panic!("{}: {e}", rel(file)))
}
