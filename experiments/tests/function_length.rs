//! Every function in an experiment file fits on a screen: at most 80 lines, signature to closing
//! brace. A longer one is usually several phases (settings, computation through `study`, report)
//! that read better named. Measured on a real parse of each file (`syn`), so braces in strings,
//! comments and macros do not fool it.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::fs;
use std::path::Path;

use syn::visit::Visit;

/// The most lines a function may span.
const MAX_LINES: usize = 80;

/// (name, first line, line count) of each function.
type Functions = Vec<(String, usize, usize)>;

/// Every function, method and nested function it visits.
#[derive(Default)]
struct Lengths(Functions);

impl Lengths {
    /// From the `fn` keyword (not the doc comment or attributes above it) to the closing brace.
    fn record(&mut self, sig: &syn::Signature, block: &syn::Block) {
        let start = sig.fn_token.span.start().line;
        let end = block.brace_token.span.close().end().line;
        self.0.push((sig.ident.to_string(), start, end - start + 1));
    }
}

impl<'ast> Visit<'ast> for Lengths {
    fn visit_item_fn(&mut self, f: &'ast syn::ItemFn) {
        self.record(&f.sig, &f.block);
        syn::visit::visit_item_fn(self, f);
    }

    fn visit_impl_item_fn(&mut self, f: &'ast syn::ImplItemFn) {
        self.record(&f.sig, &f.block);
        syn::visit::visit_impl_item_fn(self, f);
    }

    fn visit_trait_item_fn(&mut self, f: &'ast syn::TraitItemFn) {
        if let Some(block) = &f.default {
            self.record(&f.sig, block);
        }
        syn::visit::visit_trait_item_fn(self, f);
    }
}

/// (file name, functions) of every plugin file, sorted by name.
fn plugin_functions() -> Vec<(String, Functions)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/plugins");
    let mut out: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            let text = fs::read_to_string(&p).unwrap();
            let file = syn::parse_file(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
            let mut lengths = Lengths::default();
            lengths.visit_file(&file);
            (name, lengths.0)
        })
        .collect();
    out.sort();
    out
}

#[test]
fn no_plugin_function_is_over_80_lines() {
    let all = plugin_functions();
    assert!(all.len() >= 20, "{} plugin files", all.len());
    let long: Vec<String> = all
        .iter()
        .flat_map(|(file, fns)| {
            fns.iter()
                .filter(|(_, _, lines)| *lines > MAX_LINES)
                .map(move |(name, line, lines)| format!("{file}:{line}: fn {name}, {lines} lines"))
        })
        .collect();
    assert!(
        long.is_empty(),
        "functions over {MAX_LINES} lines (name their phases):\n{}",
        long.join("\n")
    );
}

#[test]
fn the_measure_sees_long_functions() {
    // The measure itself: a 100-line function is seen as 100 lines, a method too.
    let body = "    let _x = 1;\n".repeat(98);
    let text = format!(
        "fn long() {{\n{body}}}\nstruct S;\nimpl S {{\n    fn m(&self) {{\n{body}    }}\n}}\n"
    );
    let mut lengths = Lengths::default();
    lengths.visit_file(&syn::parse_file(&text).unwrap());
    assert_eq!(
        lengths.0,
        vec![("long".to_owned(), 1, 100), ("m".to_owned(), 103, 100)]
    );
}
