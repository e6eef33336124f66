//! ARCHITECTURE.md is the map a newcomer navigates by: a bird's-eye view whose floors are the
//! crates' real layering (every dependency on a lower floor), the entry points, a code map with
//! one heading per crate and per top-level folder (none missing, none stale, none twice), each
//! crate's section marking what it keeps true and naming its entry points (each found in the
//! crate), and the concerns that cut across crates.

use std::collections::BTreeMap;
use std::fs;
use std::path::Path;

use crate::crates::{PRODUCT_TABLES, dependencies};
use crate::source::{crate_dirs, crate_name, product_files, product_text, root};

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

#[test]
fn no_folder_has_two_headings() {
    let doc = doc();
    let map = mapped(section(&doc, "Code map"));
    let mut seen = std::collections::BTreeSet::new();
    let twice: Vec<&str> = map
        .iter()
        .map(|(n, _)| n.as_str())
        .filter(|n| !seen.insert(*n))
        .collect();
    assert!(
        twice.is_empty(),
        "the code map has two headings for {twice:?}"
    );
}

/// The floors of the bird's-eye view's numbered list (`0. `stdx`, ...`, continued on indented
/// lines): each crate named in backticks on a floor's item, with that floor's number.
fn floors(view: &str, crates: &[String]) -> BTreeMap<String, Vec<usize>> {
    let mut out: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    let mut floor = None;
    for line in view.lines() {
        let number = line
            .split_once(". ")
            .and_then(|(n, _)| n.parse::<usize>().ok());
        if let Some(n) = number {
            floor = Some(n);
        } else if !line.starts_with("   ") {
            floor = None;
        }
        let Some(f) = floor else { continue };
        for (i, word) in line.split('`').enumerate() {
            if i % 2 == 1 && crates.iter().any(|c| c == word) {
                out.entry(word.to_owned()).or_default().push(f);
            }
        }
    }
    out
}

/// Each crate with the workspace crates its product depends on.
fn crate_dependencies() -> BTreeMap<String, Vec<String>> {
    let names: Vec<String> = crate_dirs().iter().map(|k| crate_name(k)).collect();
    crate_dirs()
        .iter()
        .map(|k| {
            let manifest = fs::read_to_string(k.join("Cargo.toml")).unwrap();
            let deps = dependencies(&manifest, PRODUCT_TABLES)
                .into_iter()
                .filter(|d| names.contains(d))
                .collect();
            (crate_name(k), deps)
        })
        .collect()
}

/// Where the stated floors and the dependencies disagree: a crate on no floor or on two, a
/// dependency on the same floor or above.
fn floor_faults(
    floors: &BTreeMap<String, Vec<usize>>,
    deps: &BTreeMap<String, Vec<String>>,
) -> Vec<String> {
    let mut faults = Vec::new();
    let floor_of = |c: &str| floors.get(c).and_then(|f| (f.len() == 1).then(|| f[0]));
    for (krate, on) in deps {
        let Some(f) = floor_of(krate) else {
            faults.push(format!(
                "`{krate}` is on {} floors",
                floors.get(krate).map_or(0, Vec::len)
            ));
            continue;
        };
        for d in on {
            if floor_of(d).is_some_and(|g| g >= f) {
                faults.push(format!(
                    "`{krate}` (floor {f}) depends on `{d}` (floor {})",
                    floor_of(d).unwrap()
                ));
            }
        }
    }
    faults
}

#[test]
fn every_crate_is_on_one_floor_above_what_it_depends_on() {
    let doc = doc();
    let deps = crate_dependencies();
    let names: Vec<String> = deps.keys().cloned().collect();
    let floors = floors(section(&doc, "Bird's-eye view"), &names);
    assert!(
        floors.len() > 10,
        "the floor reader found the list: {floors:?}"
    );
    let faults = floor_faults(&floors, &deps);
    assert!(
        faults.is_empty(),
        "ARCHITECTURE.md's floors disagree with the manifests:\n{}",
        faults.join("\n")
    );
}

#[test]
fn the_floor_reader_catches_a_dependency_upward() {
    let view = "0. `a`, the base;\n1. `b` and\n   `c`, above it;\nsome prose naming `a`.\n";
    let names: Vec<String> = ["a", "b", "c"].map(str::to_owned).to_vec();
    let floors = floors(view, &names);
    assert_eq!(floors["a"], [0]);
    assert_eq!(floors["c"], [1]);
    let mut deps: BTreeMap<String, Vec<String>> = BTreeMap::new();
    deps.insert("a".into(), vec![]);
    deps.insert("b".into(), vec!["a".into()]);
    deps.insert("c".into(), vec!["b".into()]);
    assert_eq!(
        floor_faults(&floors, &deps),
        ["`c` (floor 1) depends on `b` (floor 1)"]
    );
}

/// The marker of a crate section's line naming its entry points.
const ENTRY: &str = "**Entry points:**";

/// The names in backticks on a section's entry-points line (None if it has none).
fn entry_points(text: &str) -> Option<Vec<String>> {
    let line = text.lines().find(|l| l.starts_with(ENTRY))?;
    Some(
        line.split('`')
            .enumerate()
            .filter(|(i, _)| i % 2 == 1)
            .map(|(_, w)| w.to_owned())
            .collect(),
    )
}

/// Whether an entry point is found in the crate: a file path that exists in it, or a name
/// (`Mesh::solve`, `register!`) that its product code defines.
fn found_in(krate: &Path, entry: &str) -> bool {
    if entry.ends_with(".rs") || entry.ends_with(".ron") || entry.contains('/') {
        return krate.join(entry).exists() || root().join(entry).exists();
    }
    let name = entry
        .rsplit("::")
        .next()
        .unwrap()
        .trim_end_matches("()")
        .trim_end_matches('!');
    let code: String = product_files(krate)
        .iter()
        .map(|f| product_text(f))
        .collect();
    defines(&code, name)
}

/// Whether `code` defines an item called `name` (a function, type, constant, module or macro).
fn defines(code: &str, name: &str) -> bool {
    let by = |kw: &str| {
        code.match_indices(&format!("{kw} {name}")).any(|(i, m)| {
            !code[i + m.len()..].starts_with(|c: char| c.is_alphanumeric() || c == '_')
        })
    };
    [
        "fn",
        "struct",
        "enum",
        "trait",
        "type",
        "const",
        "static",
        "mod",
        "macro_rules!",
    ]
    .iter()
    .any(|kw| by(kw))
}

#[test]
fn the_entry_reader_finds_a_definition_not_a_mention() {
    let code = "pub fn solve_all() {}\n/// calls solve\nmacro_rules! register { () => {} }\n";
    assert!(defines(code, "register"));
    assert!(defines(code, "solve_all"));
    assert!(
        !defines(code, "solve"),
        "a longer name or a comment is no definition"
    );
}

#[test]
fn every_crate_names_its_entry_points_and_each_is_found() {
    let doc = doc();
    let map = mapped(section(&doc, "Code map"));
    let mut faults = Vec::new();
    for krate in crate_dirs() {
        let heading = crate::source::rel(&krate);
        let Some((_, text)) = map.iter().find(|(n, _)| *n == heading) else {
            continue; // a missing heading is the test above's to report
        };
        match entry_points(text) {
            None => faults.push(format!("`### {heading}` has no `{ENTRY}` line")),
            Some(e) if e.is_empty() => faults.push(format!("`### {heading}`: {ENTRY} names none")),
            Some(entries) => faults.extend(
                entries
                    .iter()
                    .filter(|e| !found_in(&krate, e))
                    .map(|e| format!("`### {heading}`: entry point `{e}` is not in the crate")),
            ),
        }
    }
    assert!(faults.is_empty(), "{}", faults.join("\n"));
}
