//! The flags of `run` that shape what is printed and what reaches the experiments: `--format`,
//! `--trials`, `--errors`, `-q`, `-v`, and progress bars leaving results untouched; and what
//! `cargo xtask` and `help <id>` describe. Everything runs reduced experiments (a second or so).

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::fs;
use std::path::Path;
use std::process::Output;

mod support;
use support::{Scratch, files, stderr, succeeded_output, xtask, xtask_env};

/// A reduced table1 (its trial count comes from `--trials`).
const TABLE1: &[&str] = support::TABLE1_SHORT;

/// `xtask run ids extra --out out`.
fn run_into(ids: &[&str], extra: &[&str], out: &str) -> Output {
    support::run_args(ids, &[extra, &["--out", out]].concat())
}

fn tables_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(dir.join("tables.json")).unwrap()).unwrap()
}

#[test]
fn format_json_prints_tables_json() {
    let s = Scratch::new("json");
    let (out, _) = succeeded_output(&run_into(&["fig2"], &["--format", "json"], &s.path("r")));
    let file = fs::read_to_string(s.0.join("r/fig2/tables.json")).unwrap();
    assert_eq!(out, file, "stdout is tables.json");
    assert!(
        s.0.join("r/fig2/table.md").exists(),
        "results written as ever"
    );

    let (out, _) = succeeded_output(&run_into(
        &["fig2", "fig3"],
        &["--format=json"],
        &s.path("two"),
    ));
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for id in ["fig2", "fig3"] {
        assert_eq!(
            v["experiments"][id],
            tables_json(&s.0.join("two").join(id)),
            "{id}"
        );
    }
}

#[test]
fn format_csv_prints_each_table_after_its_title() {
    let s = Scratch::new("csv");
    let (out, _) = succeeded_output(&run_into(&["fig2"], &["--format", "csv"], &s.path("r")));
    let dir = s.0.join("r/fig2");
    let titles: Vec<String> = tables_json(&dir)["tables"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["title"].as_str().unwrap().to_owned())
        .collect();
    let blocks: Vec<&str> = out.split("\n\n").collect();
    assert_eq!(blocks.len(), titles.len(), "{out}");
    let csvs: Vec<Vec<u8>> = files(&dir)
        .into_iter()
        .filter(|(n, _)| n.ends_with(".csv") && n != "fig2.csv")
        .map(|(_, b)| b)
        .collect();
    for (block, title) in blocks.iter().zip(&titles) {
        let (first, body) = block.split_once('\n').unwrap();
        assert_eq!(first, format!("# {title}"));
        let body = format!("{}\n", body.trim_end_matches('\n'));
        assert!(
            csvs.iter().any(|c| c == body.as_bytes()),
            "the CSV of `{title}` is one of the files:\n{body}"
        );
    }
    // Several experiments: titles name the experiment.
    let (out, _) = succeeded_output(&run_into(
        &["fig2", "fig3"],
        &["--format", "csv"],
        &s.path("two"),
    ));
    assert!(out.starts_with("# fig2: "), "{out}");
    assert!(out.contains("\n\n# fig3: "), "{out}");
}

#[test]
fn trials_reaches_every_experiment_that_declares_it() {
    let s = Scratch::new("trials");
    let mut extra = vec!["--trials", "3"];
    extra.extend_from_slice(TABLE1);
    let (out, _) = succeeded_output(&run_into(&["table1", "fig2"], &extra, &s.path("r")));
    assert!(out.contains("3 trials"), "{out}");
    // A shard records it with its other parameters, so that the merge replays it.
    let mut extra = vec!["--trials", "3", "--shard", "0/1"];
    extra.extend_from_slice(TABLE1);
    succeeded_output(&run_into(&["table1"], &extra, &s.path("shard")));
    let partial = fs::read_to_string(s.0.join("shard/table1/partial-0-of-1.json")).unwrap();
    assert!(partial.contains(r#"["trials","3"]"#), "{partial}");
}

#[test]
fn quiet_prints_nothing_on_stderr_and_verbose_logs_batches() {
    let s = Scratch::new("quiet");
    let (_, err) = succeeded_output(&run_into(&["fig2"], &[], &s.path("a")));
    assert!(err.contains("results: "), "{err}");
    let (_, err) = succeeded_output(&run_into(&["fig2"], &["-q"], &s.path("b")));
    assert_eq!(err, "", "-q: errors only");
    let mut extra = vec!["--trials", "2", "-v"];
    extra.extend_from_slice(TABLE1);
    let (_, err) = succeeded_output(&run_into(&["table1"], &extra, &s.path("c")));
    assert!(
        err.contains("DEBUG") && err.contains("trial batch"),
        "{err}"
    );
    assert!(
        err.contains("done seconds="),
        "per-experiment timing: {err}"
    );
}

#[test]
fn progress_bars_leave_results_untouched() {
    let s = Scratch::new("progress");
    let reduced = |out: &str, extra: &[&str], env: &[(&str, &str)]| {
        let mut args = vec![
            "run", "table1", "failure", "--trials", "4", "--set", "cases=D",
        ];
        args.extend_from_slice(TABLE1);
        args.extend_from_slice(extra);
        args.extend(["--out", out]);
        succeeded_output(&xtask_env(&args, env))
    };
    let (with, err) = reduced(&s.path("with"), &["-v"], &[("XTASK_PROGRESS", "always")]);
    assert!(err.contains("progress bar shown"), "the bars ran: {err}");
    let (without, _) = reduced(&s.path("without"), &["-q"], &[]);
    assert_eq!(with, without, "printed tables");
    for id in ["table1", "failure"] {
        assert_eq!(
            files(&s.0.join("with").join(id)),
            files(&s.0.join("without").join(id)),
            "{id}: results files"
        );
    }
}

#[test]
fn errors_points_the_measured_hypothesis_at_a_table() {
    let s = Scratch::new("errors");
    let table = s.0.join("pair.ron");
    fs::write(
        &table,
        r#"(gears: [
            (gear: "driver", random: 0.05, systematic: 0.5),
            (gear: "driven", random: 0.03, systematic: 0.2, phase: 90.0),
        ])"#,
    )
    .unwrap();
    let file = table.to_str().unwrap();
    let (by_errors, _) = succeeded_output(&run_into(&["fig5"], &["--errors", file], &s.path("a")));
    let name = format!("measured:{file}");
    let (by_name, _) =
        succeeded_output(&run_into(&["fig5"], &["--hypothesis", &name], &s.path("b")));
    let (default, _) = succeeded_output(&run_into(&["fig5"], &[], &s.path("c")));
    assert_eq!(by_errors, by_name);
    assert_ne!(by_errors, default, "the table's errors were applied");
    // A gear the table lacks is named.
    fs::write(
        &table,
        r#"(gears: [(gear: "driver", random: 0.05, systematic: 0.5)])"#,
    )
    .unwrap();
    let o = run_into(&["fig5"], &["--errors", file], &s.path("d"));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("gear driven: missing from the table"), "{err}");
    assert!(!s.0.join("d").exists());
}

#[test]
fn overview_and_help_describe_hypotheses_flags_and_outputs() {
    let (out, _) = succeeded_output(&xtask(&[]));
    for word in [
        "Error hypotheses",
        "edmunds-split",
        "measured:FILE",
        "--trials N",
        "--format F",
        "--errors FILE",
        "-q, --quiet",
        "-v, --verbose",
    ] {
        assert!(out.contains(word), "overview lacks {word:?}");
    }
    let (out, _) = succeeded_output(&xtask(&["help", "failure"]));
    for word in [
        "Paper item: Section 5",
        "| trials ",
        "--trials N sets `trials`",
        "--errors FILE sets `measured`",
        "Outputs, written to <out>/failure/",
        "table.md",
        "tables.json",
        "<title>.csv",
    ] {
        assert!(out.contains(word), "help failure lacks {word:?}:\n{out}");
    }
    let (out, _) = succeeded_output(&xtask(&["help", "table2"]));
    assert!(
        out.contains("--errors FILE sets `hypothesis` to measured:FILE"),
        "{out}"
    );
    let (out, _) = succeeded_output(&xtask(&["help", "fig2"]));
    assert!(!out.contains("Shorthands"), "{out}");
}

/// A measured-errors file whose path holds `+`, the separator of a hypothesis stack, is read as
/// that file through `--errors` and `--hypothesis measured:FILE`, alone or as a stack's layer,
/// with the same results as the same table under a plain name; a `+` that starts another layer
/// still does.
#[test]
fn an_errors_file_with_a_plus_in_its_path_is_one_file() {
    let s = Scratch::new("plus-path");
    let table = r#"(gears: [
        (gear: "driver", random: 0.05, systematic: 0.5),
        (gear: "driven", random: 0.03, systematic: 0.2, phase: 90.0),
    ])"#;
    fs::create_dir_all(s.0.join("a+b")).unwrap();
    let plus = s.0.join("a+b/my+errors.ron");
    let plain = s.0.join("plain.ron");
    fs::write(&plus, table).unwrap();
    fs::write(&plain, table).unwrap();
    let (plus, plain) = (plus.to_str().unwrap(), plain.to_str().unwrap());
    let (expected, _) = succeeded_output(&run_into(&["fig5"], &["--errors", plain], &s.path("p")));
    let (by_errors, _) = succeeded_output(&run_into(&["fig5"], &["--errors", plus], &s.path("e")));
    let by_name = format!("measured:{plus}");
    let (by_hypothesis, _) = succeeded_output(&run_into(
        &["fig5"],
        &["--hypothesis", &by_name],
        &s.path("h"),
    ));
    // The file's path is in the titles; the numbers are the same.
    let numbers = |printed: &str| -> Vec<String> {
        printed
            .lines()
            .filter(|l| l.starts_with("| ") && !l.contains("measured:"))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(numbers(&by_errors), numbers(&expected));
    assert_eq!(numbers(&by_hypothesis), numbers(&expected));
    // As the first layer of a stack, with another layer after it.
    let stacked = format!("measured:{plus}+eccentric-only");
    let o = run_into(&["fig5"], &["--hypothesis", &stacked], &s.path("s"));
    assert!(o.status.success(), "{}", stderr(&o));
    // A file that does not exist is refused in one line naming the flag.
    let missing = format!("measured:{}", s.path("no+such.ron"));
    let o = run_into(&["fig5"], &["--hypothesis", &missing], &s.path("m"));
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with("--hypothesis: "), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}
