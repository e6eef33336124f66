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

/// GitHub's anchor of a heading: lower case, spaces to hyphens, other punctuation dropped.
fn anchor(heading: &str) -> String {
    heading
        .trim()
        .to_lowercase()
        .chars()
        .filter_map(|c| match c {
            ' ' => Some('-'),
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c),
            _ => None,
        })
        .collect()
}

/// Every in-page link `[text](#anchor)`: (byte offset, anchor, the direction the text or the
/// word after the link gives: "above", "below" or "").
fn in_page_links(readme: &str) -> Vec<(usize, String, &'static str)> {
    let mut links = Vec::new();
    let mut from = 0;
    while let Some(i) = readme[from..].find("](#") {
        let at = from + i;
        let start = readme[..at].rfind('[').unwrap_or(at);
        let end = at + readme[at..].find(')').unwrap_or(readme.len() - at);
        let text = &readme[start..at];
        let after: String = readme[end + 1..].chars().take(8).collect();
        let said = |w: &str| text.contains(w) || after.trim_start().starts_with(w);
        let direction = if said("below") {
            "below"
        } else if said("above") {
            "above"
        } else {
            ""
        };
        links.push((at, readme[at + 3..end].to_owned(), direction));
        from = end;
    }
    links
}

/// Every in-page link lands on a heading, and one that says "above" or "below" points that way:
/// a section moved with its pointers left behind fails here.
#[test]
fn readme_links_land_on_headings_in_the_direction_they_say() {
    let readme =
        std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../README.md")).unwrap();
    let mut headings = Vec::new();
    let mut offset = 0;
    for line in readme.split_inclusive('\n') {
        if let Some(h) = line.strip_prefix('#') {
            headings.push((offset, anchor(h.trim_start_matches('#'))));
        }
        offset += line.len();
    }
    let links = in_page_links(&readme);
    assert!(links.len() > 2, "the README's in-page links are found");
    for (at, target, direction) in links {
        let heading = headings.iter().find(|(_, a)| *a == target);
        let Some((h, _)) = heading else {
            panic!("README.md links to #{target}, which no heading has");
        };
        let line = readme[..at].lines().count();
        match direction {
            "below" => assert!(*h > at, "README.md line {line} says #{target} is below"),
            "above" => assert!(*h < at, "README.md line {line} says #{target} is above"),
            _ => {}
        }
    }
}

#[test]
fn links_are_read_with_their_direction() {
    let text = "# Top\nsee [below](#end) and [the top](#top) above\n## End\n";
    let links = in_page_links(text);
    assert_eq!(links.len(), 2);
    assert_eq!((links[0].1.as_str(), links[0].2), ("end", "below"));
    assert_eq!((links[1].1.as_str(), links[1].2), ("top", "above"));
    assert_eq!(
        anchor(" Which gear drives: the paper's jams"),
        "which-gear-drives-the-papers-jams"
    );
}
