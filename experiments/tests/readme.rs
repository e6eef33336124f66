//! The README's experiment table names only registered experiments, each once: an experiment
//! renamed or removed with its row left behind fails here. An experiment added needs no row: the
//! README points to `cargo xtask list` and `snapshots/experiment-ids.snap` for every registered
//! one, so adding an experiment is its plugin file and its snapshots alone.
#![allow(clippy::unwrap_used, reason = "tests")]

/// The ids in the first column of the table under the README's `## Experiments` heading.
fn readme_ids(readme: &str) -> Vec<String> {
    let section = readme
        .split("\n## Experiments\n")
        .nth(1)
        .expect("README.md has an `## Experiments` section");
    let table_end = section.find("\n\n").map_or(section.len(), |i| i);
    let mut ids = Vec::new();
    for line in section[..table_end].lines() {
        let Some(first) = line.strip_prefix("| `") else {
            continue;
        };
        if let Some(end) = first.find('`') {
            ids.push(first[..end].to_owned());
        }
    }
    ids
}

#[test]
fn readme_table_names_registered_experiments_once() {
    experiments::link();
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md")).unwrap();
    let mut listed = readme_ids(&readme);
    let count = listed.len();
    listed.sort();
    listed.dedup();
    assert_eq!(
        listed.len(),
        count,
        "an experiment is listed twice in README.md"
    );
    let registered: Vec<String> = registry::experiments()
        .unwrap()
        .keys()
        .map(|id| (*id).to_owned())
        .collect();
    assert!(
        registered.len() > 20,
        "the experiments crate is linked: {registered:?}"
    );
    let unknown: Vec<&String> = listed
        .iter()
        .filter(|id| !registered.contains(id))
        .collect();
    assert!(
        unknown.is_empty(),
        "README.md's experiment table names experiments that are not registered: {unknown:?}"
    );
    assert!(
        readme.contains("cargo xtask list") && readme.contains("snapshots/experiment-ids.snap"),
        "README.md points to the runner's listing and the snapshot of registered ids"
    );
}

#[test]
fn the_parser_finds_rows_and_stops_at_the_table_end() {
    let text = "x\n## Experiments\n\n| id | a |\n|---|---|\n| `t1` | y |\n| `t2` | z |\n\n| `later` | q |\n";
    assert_eq!(readme_ids(text), ["t1", "t2"]);
}
