//! Tests of the runner as a whole: `run all` past failures, numbers in messages, bench rows.
#![allow(clippy::unwrap_used, reason = "tests fail loudly on purpose")]

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use registry::{Entry, Param, Report, RunError, Table};

use crate::args::{Format, RunArgs};
use crate::bench::bench_row;
use crate::execute::run_every;
use crate::failure::{one_line, short_numbers};
use crate::shared::Registry;
use crate::summary;

/// `a-fine`'s one parameter, read by this declaration.
const N: Param = Param {
    name: "n",
    default: "5",
    unit: "",
    help: "trials",
    kind: registry::Kind::Text,
    reading: false,
};

/// `a-fine`'s settings: its one parameter as typed.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
struct FineSettings {
    #[param(N)]
    n: String,
}

/// Reports its parameter, trials and agreement.
struct Fine;
impl registry::Experiment for Fine {
    const ID: &'static str = "a-fine";
    const TITLE: &'static str = "fine";
    const PAPER_ITEM: &'static str = "Table 0";
    const PLACE: registry::Place = registry::Place::Beyond(0);
    type Settings = FineSettings;
    type Results = u64;
    fn compute(s: &FineSettings, _: &registry::Run) -> Result<u64, RunError> {
        s.n.parse()
            .map_err(|_| RunError::bad("--set", "n", "must be a count"))
    }
    fn report(s: &FineSettings, n: &u64) -> Result<Report, RunError> {
        let mut t = Table::new("Fine", ["n"]);
        t.row(vec![s.n.clone()]);
        Ok(Report {
            tables: vec![t],
            trials: *n,
            engagements: 10,
            agreement: Some(registry::Agreement {
                consistent: 2,
                differ: 1,
            }),
            ..Default::default()
        })
    }
}

/// Refuses its input.
struct Refuses;
impl registry::Experiment for Refuses {
    const ID: &'static str = "b-bad";
    const TITLE: &'static str = "refuses";
    const PAPER_ITEM: &'static str = "Table 0";
    const PLACE: registry::Place = registry::Place::Beyond(1);
    type Settings = registry::NoSettings;
    type Results = ();
    fn compute(_: &registry::NoSettings, _: &registry::Run) -> Result<(), RunError> {
        Err(RunError::bad("--set", "x", "must be sensible"))
    }
    fn report(_: &registry::NoSettings, _: &()) -> Result<Report, RunError> {
        Ok(Report::default())
    }
}

/// Panics.
struct Panics;
impl registry::Experiment for Panics {
    const ID: &'static str = "c-panic";
    const TITLE: &'static str = "panics";
    const PAPER_ITEM: &'static str = "Table 0";
    const PLACE: registry::Place = registry::Place::Beyond(2);
    type Settings = registry::NoSettings;
    type Results = ();
    fn compute(_: &registry::NoSettings, _: &registry::Run) -> Result<(), RunError> {
        panic!("deliberately")
    }
    fn report(_: &registry::NoSettings, _: &()) -> Result<Report, RunError> {
        Ok(Report::default())
    }
}

static A_FINE: Entry = Entry::of::<Fine>();
static B_BAD: Entry = Entry::of::<Refuses>();
static C_PANIC: Entry = Entry::of::<Panics>();

fn registry(with_panic: bool) -> Registry {
    let mut r: Registry = BTreeMap::new();
    r.insert(A_FINE.id, &A_FINE);
    r.insert(B_BAD.id, &B_BAD);
    if with_panic {
        r.insert(C_PANIC.id, &C_PANIC);
    }
    r
}

fn scratch(tag: &str) -> PathBuf {
    std::env::temp_dir().join(format!(
        "xtask-run-all-{tag}-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    ))
}

fn run_all_args(out: &Path, sets: &[(&str, &str)]) -> RunArgs {
    RunArgs {
        ids: vec!["all".into()],
        seed: 1,
        threads: Some(1),
        out: Some(out.to_path_buf()),
        config: None,
        sets: sets
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect(),
        shard: None,
        trials: None,
        gearing: None,
        hypothesis: None,
        errors: None,
        format: Format::Md,
    }
}

#[test]
fn run_all_goes_on_past_failures_and_writes_the_summary() {
    let out = scratch("past");
    let mut printed = String::new();
    let rows = run_every(
        &registry(true),
        &run_all_args(&out, &[(N.name, "7")]),
        &mut |s| {
            printed.push_str(s);
            Ok(())
        },
    )
    .unwrap();
    let ids: Vec<&str> = rows.iter().map(|r| r.id.as_str()).collect();
    assert_eq!(ids, ["a-fine", "b-bad", "c-panic"]);
    assert_eq!(
        rows[0].trials, 7,
        "--set n=7 reached the experiment declaring it"
    );
    assert!(matches!(rows[1].status, summary::Status::BadInput(_)));
    assert!(matches!(rows[2].status, summary::Status::Internal(_)));
    assert_eq!(summary::exit_code(&rows), 1);
    assert_eq!(summary::exit_code(&rows[..2]), 2);
    assert!(out.join("a-fine").join("table.md").exists());
    assert!(!out.join("b-bad").exists());
    assert!(!out.join("c-panic").exists());
    let md = std::fs::read_to_string(out.join("summary.md")).unwrap();
    // n = 7 is not the default, so no agreement with the paper is judged.
    assert!(md.contains("| a-fine ") && !md.contains("2 / 1"), "{md}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(json["total"]["trials"], 7);
    assert_eq!(json["experiments"][2]["status"], "internal error");
    assert!(
        printed.starts_with("## a-fine: fine\n\n### Fine"),
        "{printed}"
    );
    assert!(printed.contains("### Summary of run all"), "{printed}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn run_all_refuses_a_key_no_experiment_declares_before_running() {
    let out = scratch("key");
    let e = run_every(
        &registry(false),
        &run_all_args(&out, &[(N.name, "1"), ("nonsense", "1")]),
        &mut |_| Ok(()),
    )
    .unwrap_err();
    assert_eq!(e.code(), 2);
    assert!(format!("{e:?}").contains("nonsense"));
    assert!(!out.exists(), "nothing may be written");
}

#[test]
fn run_all_refuses_a_config_no_experiment_takes() {
    let out = scratch("config");
    std::fs::create_dir_all(&out).unwrap();
    let file = out.join("c.ron");
    std::fs::write(&file, "()").unwrap();
    let mut args = run_all_args(&out.join("results"), &[]);
    args.config = Some(file);
    let e = run_every(&registry(false), &args, &mut |_| Ok(())).unwrap_err();
    assert_eq!(e.code(), 2);
    assert!(!out.join("results").exists());
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn numbers_of_hundreds_of_digits_are_shortened_and_nothing_else() {
    let huge = format!("{}", 1e308);
    assert!(huge.len() > 300);
    assert_eq!(
        one_line(&format!(
            "m.ron: centre_distance: must exceed {huge} (got 5)"
        )),
        "m.ron: centre_distance: must exceed 1e308 (got 5)"
    );
    assert_eq!(
        short_numbers(&format!("= {huge}.5, and -{huge}")),
        "= 1e308, and -1e308"
    );
    for kept in [
        "/tmp/xtask-bad-1795543045569589936/e.ron: x",
        "seed 18446744073709551615 is fine",
        "gear b1: 0.25 é",
    ] {
        assert_eq!(short_numbers(kept), kept);
    }
}

#[test]
fn bench_rows_divide_engagements_by_wall_time() {
    let report = Report {
        trials: 4,
        engagements: 1000,
        ..Default::default()
    };
    let rows = vec![
        summary::Row::new("x", 1.0, Ok(&report)),
        summary::Row::new("y", 1.0, Ok(&Report::default())),
    ];
    assert_eq!(
        bench_row("all", 2, 2.0, &rows),
        ["all", "2", "2.00", "4", "1000", "500"]
    );
    assert_eq!(
        bench_row("table5", 1, 2.0, &rows[1..]),
        ["table5", "1", "2.00", "0", "-", "-"]
    );
}
