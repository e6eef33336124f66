//! Tables never mislead: a run whose inputs differ from the paper's says so
//! in every title and labels the paper's numbers; `tables.json` names the inputs; `run.json`
//! hashes every input file; `table3` with a hypothesis the Cases do not reach prints one row,
//! not four identical rows compared with four different paper rows; the report's heading
//! follows the run.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;

mod support;
use support::{Scratch, stderr, succeeded, xtask};

fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn table3_with_an_errors_file_prints_one_row_and_names_its_inputs() {
    let s = Scratch::new("labels-table3");
    let errors = s.0.join("errors.ron");
    let rows: Vec<String> = train::Gearing::freeth2006()
        .gears()
        .iter()
        .map(|g| format!("(gear: \"{}\", random: 0.04, systematic: 0.3)", g.name))
        .collect();
    fs::write(&errors, format!("(gears: [{}])", rows.join(", "))).unwrap();
    let out = s.path("out");
    // Each table with the errors file and two trials.
    let run = |id: &str| {
        let errors = errors.to_str().unwrap();
        succeeded(&[
            "run", id, "--errors", errors, "--trials", "2", "--out", &out,
        ])
    };
    let printed = run("table3");
    check_table3(&printed, &out, &errors);
    // tableI: one row per clearance, not four Cases per clearance.
    let printed = run("tableI");
    check_rows(&printed, 3);
}

/// The table's body has `rows` rows, the first saying the Cases do not reach the hypothesis.
fn check_rows(printed: &str, rows: usize) {
    // The first table (table3 prints its intervals in a second one, row for row).
    let first = printed
        .match_indices("\n### ")
        .next()
        .map_or(printed, |(i, _)| &printed[..i]);
    let body: Vec<&str> = first
        .lines()
        .filter(|l| l.starts_with("| ") && !l.starts_with("| case"))
        .collect();
    assert_eq!(body.len(), rows, "{printed}");
    assert!(body[0].contains("Cases A-D alike"), "{printed}");
}

fn check_table3(printed: &str, out: &str, errors: &std::path::Path) {
    let file = errors.to_str().unwrap();
    // One row: the Cases do not reach the measured hypothesis.
    check_rows(printed, 1);
    assert!(!printed.contains("| A "), "{printed}");
    // The title says the inputs differ, and the paper's numbers are labelled.
    assert!(
        printed.contains("[inputs differ from the defaults: trials=2, hypothesis=measured:"),
        "{printed}"
    );
    assert!(printed.contains("not as a check of these"), "{printed}");
    let dir = std::path::Path::new(out).join("table3");
    let tables = json(&dir.join("tables.json"));
    assert_eq!(tables["inputs"]["hypothesis"], format!("measured:{file}"));
    assert_eq!(tables["inputs"]["errors"], file);
    assert_eq!(tables["inputs"]["gearing"], "freeth2006");
    assert_eq!(tables["inputs"]["trials"], "2");
    assert_eq!(tables["agreement"], serde_json::Value::Null);
    let run = json(&dir.join("run.json"));
    let input = &run["inputs"][0];
    assert_eq!(input["role"], "measured errors");
    assert_eq!(input["path"], file);
    assert_eq!(input["sha256"].as_str().unwrap().len(), 64);
}

#[test]
fn default_runs_print_as_before_and_changed_runs_head_the_report_with_what_ran() {
    let s = Scratch::new("labels-report");
    let out = s.path("out");
    let plain = succeeded(&["run", "fig3", "--out", &out]);
    assert!(!plain.contains("inputs differ"), "{plain}");
    let tables = json(&s.0.join("out/fig3/tables.json"));
    assert!(tables["inputs"].is_object(), "{tables}");
    let changed = succeeded(&["run", "fig2", "--set", "step=0.5", "--out", &out]);
    assert!(
        changed.contains("[inputs differ from the defaults: step=0.5]"),
        "{changed}"
    );
    succeeded(&["report", "--out", &out, "-q"]);
    let page = fs::read_to_string(s.0.join("out/index.html")).unwrap();
    assert!(
        page.contains("<h2>fig2: Figure 2: N1 = N2 = 8") && page.contains("step=0.5]</h2>"),
        "the heading names what ran"
    );
    // A stray folder with a damaged tables.json does not break the report.
    fs::create_dir_all(s.0.join("out/old-copy")).unwrap();
    fs::write(s.0.join("out/old-copy/tables.json"), "{ damaged").unwrap();
    let o = xtask(&["-q", "report", "--out", &out]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(o.stderr.is_empty(), "-q: nothing on stderr");
}

#[test]
fn a_reading_of_the_paper_is_not_an_input_that_differs() {
    // The event rule (and `emax=paper`) choose how the paper is read; the run is still on the
    // paper's inputs, named in the title, and still compared.
    let s = Scratch::new("labels-reading");
    let out = s.path("out");
    let text = succeeded(&["run", "clearance", "--set", "events=strict", "--out", &out]);
    assert!(text.contains("[events: strict]"), "{text}");
    assert!(!text.contains("inputs differ"), "{text}");
    let tables = json(&s.0.join("out/clearance/tables.json"));
    assert_eq!(tables["inputs"]["events"], "strict", "{tables}");
}
