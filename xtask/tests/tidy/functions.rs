//! Every function fits on a screen: at most 80 lines in an experiment's plugin file and in the
//! presentation, at most 100 in all other product code (tests aside).

use std::path::Path;

use syn::visit::Visit;

use crate::source::{crate_dirs, is_test, parse, product_files, rel};

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
    let rel = rel(file);
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
            let mut lengths = Lengths::default();
            lengths.visit_file(&parse(&file));
            let max = max_lines(&file);
            for (name, line, n) in lengths.0 {
                if n > max {
                    long.push(format!(
                        "{}:{line} `{name}`: {n} lines (at most {max})",
                        rel(&file)
                    ));
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
fn the_length_reader_counts_from_fn_to_the_closing_brace() {
    let file: syn::File = syn::parse_str(
        "/// doc\nfn a() {\n    1;\n}\n#[cfg(test)]\nmod tests {\n    fn long() {\n\n\n}\n}\n",
    )
    .unwrap();
    let mut lengths = Lengths::default();
    lengths.visit_file(&file);
    assert_eq!(lengths.0, vec![("a".to_owned(), 2, 3)]);
}

/// The most product lines one file may hold: past that a file is usually several modules.
const MAX_FILE_LINES: usize = 1000;

#[test]
fn no_file_is_past_a_thousand_lines() {
    let long: Vec<String> = crate_dirs()
        .iter()
        .flat_map(|k| product_files(k))
        .map(|f| (rel(&f), crate::source::product_text(&f).lines().count()))
        .filter(|(_, n)| *n > MAX_FILE_LINES)
        .map(|(f, n)| format!("{f}: {n} lines"))
        .collect();
    assert!(
        long.is_empty(),
        "files past {MAX_FILE_LINES} product lines (split them by concern):\n{}",
        long.join("\n")
    );
}
