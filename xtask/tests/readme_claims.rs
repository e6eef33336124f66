//! The README as a newcomer reads it, checked against the program: it cites the paper and
//! defines its symbols before using them, starts with `table5` and the test command, keeps the
//! developers' material in CONTRIBUTING.md, and what it promises an experiment prints is printed
//! (Table 3's Wilson intervals). No user-facing text (README, the overview, `list`, every `help`)
//! points to a tracker instead of saying the reason.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{stdout, xtask};

fn read(name: &str) -> String {
    std::fs::read_to_string(format!("{}/../{name}", env!("CARGO_MANIFEST_DIR"))).unwrap()
}

#[test]
fn the_readme_starts_with_the_paper_its_symbols_and_table5() {
    let readme = read("README.md");
    assert!(
        readme.contains("Szigety") && readme.contains("Arenas"),
        "the paper's authors"
    );
    assert!(readme.contains(
        "*The Impact of Triangular-Toothed\n> Gears on the Functionality of the Antikythera Mechanism*"
    ));
    // The symbols are defined in a table before the experiments use them.
    let symbols =
        &readme[readme.find("### The symbols").unwrap()..readme.find("## Experiments").unwrap()];
    for symbol in [
        "| TD |",
        "| σ |",
        "| Dm |",
        "| P |",
        "| G |",
        "| h |",
        "| b2-c1, m3-e3, ... |",
    ] {
        assert!(symbols.contains(symbol), "{symbol} is not defined");
    }
    // The first commands: table5, then the test command CI runs.
    let first = readme.split("```sh\n").nth(1).unwrap();
    let first = &first[..first.find("```").unwrap()];
    assert_eq!(
        first,
        "cargo xtask run table5\ncargo test --workspace --release\n"
    );
    let ci = read(".ci/run");
    assert!(
        ci.contains("\ncargo test --workspace --release\n"),
        "CI runs the README's test command"
    );
    // The time of the first command is stated, with how it was measured.
    let start =
        &readme[readme.find("## Start here").unwrap()..readme.find("## Experiments").unwrap()];
    assert!(
        start.contains("it takes about") && start.contains(" s "),
        "{start}"
    );
    // Results before the developers' material, which lives in CONTRIBUTING.md.
    let results = readme.find("\n## Results\n").unwrap();
    let dev = readme.find("\n## For developers\n").unwrap();
    assert!(results < dev);
    let contributing = read("CONTRIBUTING.md");
    for heading in [
        "## Timing the toolkit",
        "## Running a large sweep on a cluster",
        "## Fuzzing the input files",
        "## Adding an error hypothesis",
        "## Adding an event rule",
        "## Adding an experiment",
        "## Reviewing snapshot changes",
    ] {
        assert!(
            !readme.contains(&format!("\n{heading}")),
            "{heading} in README.md"
        );
        assert!(
            contributing.contains(&format!("\n{heading}")),
            "{heading} not in CONTRIBUTING.md"
        );
    }
}

#[test]
fn table3_prints_the_wilson_intervals_the_readme_promises() {
    let readme = read("README.md");
    let row = readme
        .lines()
        .find(|l| l.starts_with("| `table3` |"))
        .unwrap();
    assert!(row.contains("95 % Wilson intervals"), "{row}");
    let s = support::Scratch::new("readme-table3");
    let o = xtask(&[
        "run",
        "table3",
        "-q",
        "--trials",
        "2",
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success());
    let text = stdout(&o);
    let title = text
        .lines()
        .find(|l| l.starts_with("### ") && l.contains("95 % Wilson intervals"))
        .unwrap_or_else(|| panic!("no table of Wilson intervals:\n{text}"));
    let table = &text[text.find(title).unwrap()..];
    let row = table.lines().find(|l| l.starts_with("| A ")).unwrap();
    // Each cell: jams [lo .. hi] / disengagements [lo .. hi].
    assert_eq!(row.matches(" .. ").count(), 2 * 15, "{row}");
}

#[test]
fn no_user_facing_text_points_to_a_tracker() {
    let mut texts = vec![
        ("README.md".to_owned(), read("README.md")),
        ("CONTRIBUTING.md".to_owned(), read("CONTRIBUTING.md")),
    ];
    for args in [&[][..], &["list"], &["hypotheses"], &["rules"]] {
        texts.push((format!("xtask {args:?}"), stdout(&xtask(args))));
    }
    let ids = stdout(&xtask(&["list"]));
    for id in ids.lines() {
        texts.push((format!("help {id}"), stdout(&xtask(&["help", id]))));
    }
    for (what, text) in texts {
        let lower = text.to_lowercase();
        for word in ["issue", "session"] {
            assert!(!lower.contains(word), "{what} says `{word}`");
        }
    }
}
