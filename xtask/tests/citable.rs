//! The toolkit can be cited and reused: its licence files exist and match Cargo.toml's
//! licence, and CITATION.cff names the toolkit and the paper it reproduces.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::Path;

fn repo_file(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("..").join(name);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn licence_files_match_the_declared_licence() {
    let cargo = repo_file("Cargo.toml");
    assert!(cargo.contains("license = \"MIT OR Apache-2.0\""));
    let mit = repo_file("LICENSE-MIT");
    assert!(mit.contains("Permission is hereby granted, free of charge"));
    let apache = repo_file("LICENSE-APACHE");
    assert!(apache.contains("Apache License") && apache.contains("Version 2.0, January 2004"));
}

#[test]
fn citation_names_the_toolkit_its_licence_and_the_paper() {
    let cff = repo_file("CITATION.cff");
    let cargo = repo_file("Cargo.toml");
    let version = cargo
        .lines()
        .find_map(|l| l.strip_prefix("version = \""))
        .and_then(|v| v.strip_suffix('"'))
        .unwrap();
    assert!(cff.starts_with("cff-version: 1.2.0"));
    assert!(cff.contains(&format!("version: {version}")), "{cff}");
    assert!(cff.contains("- MIT") && cff.contains("- Apache-2.0"));
    assert!(cff.contains("arXiv:2504.00327"));
    assert!(cff.contains("family-names: Szigety") && cff.contains("family-names: Arenas"));
}
