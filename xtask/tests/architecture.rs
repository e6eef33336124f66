//! ARCHITECTURE.md is the map a newcomer navigates by: it has a bird's-eye view, the entry
//! points, a code map with one heading per crate and per top-level folder (no folder missing,
//! none that is gone), each crate's section marking what it keeps true, and the concerns that
//! cut across crates.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::fs;
use std::path::{Path, PathBuf};

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// Folders the code map leaves out: build output, not the project's.
const NOT_MAPPED: &[&str] = &["target"];

/// Folders a run creates rather than the repository holds; mapped even where absent.
const MADE_BY_RUNS: &[&str] = &["results"];

/// The top-level folders and `crates/*` folders that hold a file git tracks, or `None` where git
/// cannot say (no git, or not a checkout): a stray folder of a local checkout is not the
/// project's and needs no heading.
fn tracked_folders(root: &Path) -> Option<std::collections::BTreeSet<String>> {
    let out = std::process::Command::new("git")
        .args(["ls-files", "-z"])
        .current_dir(root)
        .output()
        .ok()?;
    if !out.status.success() || out.stdout.is_empty() {
        return None;
    }
    let mut folders = std::collections::BTreeSet::new();
    for path in String::from_utf8_lossy(&out.stdout).split('\0') {
        let parts: Vec<&str> = path.split('/').collect();
        if parts.len() > 1 {
            folders.insert(parts[0].to_owned());
        }
        if parts.len() > 2 && parts[0] == "crates" {
            folders.insert(format!("crates/{}", parts[1]));
        }
    }
    Some(folders)
}

/// The folders that need a heading: every crate and every top-level folder that is not hidden
/// (of those git tracks, where git can say).
fn folders() -> Vec<String> {
    let root = root();
    let tracked = tracked_folders(&root);
    let names = |dir: &Path, prefix: &str| -> Vec<String> {
        let mut out: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.is_dir())
            .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
            .filter(|n| !n.starts_with('.') && !NOT_MAPPED.contains(&n.as_str()))
            .filter(|n| {
                tracked
                    .as_ref()
                    .is_none_or(|t| t.contains(&format!("{prefix}{n}")))
            })
            .collect();
        out.sort();
        out
    };
    let mut out: Vec<String> = names(&root.join("crates"), "crates/")
        .into_iter()
        .map(|c| format!("crates/{c}"))
        .collect();
    out.extend(names(&root, "").into_iter().filter(|n| n != "crates"));
    out
}

/// The text of the `##` section titled `title`, up to the next `##` heading.
fn section<'a>(doc: &'a str, title: &str) -> &'a str {
    let start = doc
        .find(&format!("\n## {title}\n"))
        .unwrap_or_else(|| panic!("ARCHITECTURE.md has no `## {title}` section"));
    let body = &doc[start + 1..];
    let end = body[3..].find("\n## ").map_or(body.len(), |i| i + 3);
    &body[..end]
}

/// (folder, text) of every `### `folder`` heading of the code map.
fn mapped(code_map: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let parts: Vec<&str> = code_map.split("\n### ").skip(1).collect();
    for part in parts {
        let (heading, text) = part.split_once('\n').unwrap_or((part, ""));
        if let Some(name) = heading.strip_prefix('`').and_then(|h| h.strip_suffix('`')) {
            out.push((name.to_owned(), text.to_owned()));
        }
    }
    out
}

fn doc() -> String {
    fs::read_to_string(root().join("ARCHITECTURE.md")).unwrap()
}

#[test]
fn the_map_has_its_sections() {
    let doc = doc();
    for title in [
        "Bird's-eye view",
        "Entry points",
        "Code map",
        "Cross-cutting concerns",
    ] {
        assert!(
            section(&doc, title).lines().count() > 3,
            "`## {title}` is empty"
        );
    }
}

#[test]
fn every_crate_and_folder_has_its_heading_and_none_is_stale() {
    let doc = doc();
    let map = mapped(section(&doc, "Code map"));
    let headings: Vec<&str> = map.iter().map(|(n, _)| n.as_str()).collect();
    let folders = folders();
    assert!(
        folders.iter().any(|f| f == "crates/contact") && folders.iter().any(|f| f == "xtask"),
        "the scan found the workspace: {folders:?}"
    );
    let missing: Vec<&String> = folders
        .iter()
        .filter(|f| !headings.contains(&f.as_str()))
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md's code map has no `### `folder`` heading for {missing:?}"
    );
    let stale: Vec<&&str> = headings
        .iter()
        .filter(|h| !root().join(h).is_dir() && !MADE_BY_RUNS.contains(h))
        .collect();
    assert!(
        stale.is_empty(),
        "ARCHITECTURE.md maps folders that do not exist: {stale:?}"
    );
}

#[test]
fn every_crate_marks_what_it_keeps_true() {
    let doc = doc();
    let map = mapped(section(&doc, "Code map"));
    let crates: Vec<&(String, String)> = map
        .iter()
        .filter(|(n, _)| n.starts_with("crates/") || n == "experiments" || n == "xtask")
        .collect();
    assert!(crates.len() >= 10, "{} crate headings", crates.len());
    for (name, text) in crates {
        assert!(
            text.contains("**Architecture Invariant:**"),
            "`### {name}` marks no **Architecture Invariant:**"
        );
    }
}

#[test]
fn the_heading_reader_sees_headings() {
    // The reader itself: two headings, the second's text up to the end.
    let map = mapped("intro\n### `crates/a`\none\n### `b`\ntwo\n");
    assert_eq!(
        map,
        vec![
            ("crates/a".to_owned(), "one".to_owned()),
            ("b".to_owned(), "two\n".to_owned())
        ]
    );
}
