//! No parameter is looked up by a name typed again as a string literal: a parameter is read by
//! its declaration (`ctx.get(&CLEARANCE)`, a settings struct's field), so that a renamed or
//! misspelled parameter fails to compile instead of reading nothing.

use crate::source::{crate_dirs, product_files, product_text, rel};

/// A parameter (`p`, `param`, a context's value) compared with, or fetched by, a literal.
const FORBIDDEN: &[&str] = &[
    "p.name == \"",
    "param.name == \"",
    ".name == \"trials\"",
    ".name == \"clearance",
    ".name == \"hypothesis",
    ".name == \"events\"",
    "inputs.get(\"",
    "values().find(|(p, _)| p.name == \"",
];

#[test]
fn no_parameter_is_looked_up_by_a_name_typed_again() {
    let mut found = Vec::new();
    for krate in crate_dirs() {
        for file in product_files(&krate) {
            for (i, line) in product_text(&file).lines().enumerate() {
                if FORBIDDEN.iter().any(|f| line.contains(f)) {
                    found.push(format!("{}:{}: {}", rel(&file), i + 1, line.trim()));
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

#[test]
fn study_takes_values_not_a_context() {
    // A context is parsed once, by the experiment's settings; the simulations take the values
    // (and trials through `registry::TrialEngine`), so that they can be called without a run.
    let study = crate::source::root().join("crates/study");
    let mut found = Vec::new();
    for file in crate::source::rust_files(&study.join("src")) {
        let text = std::fs::read_to_string(&file).unwrap();
        for (i, line) in text.lines().enumerate() {
            if line.contains("Context") {
                found.push(format!("{}:{}: {}", rel(&file), i + 1, line.trim()));
            }
        }
    }
    assert!(
        found.is_empty(),
        "study names a Context (read the settings into values in the experiment):\n{}",
        found.join("\n")
    );
}
