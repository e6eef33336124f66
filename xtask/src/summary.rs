//! The summary of `run all` (and the rows of `bench`): per experiment its wall time, trials,
//! tooth engagements and agreement with the paper, and a total.

use registry::{Agreement, Report, RunError, Table, fmt_f64};
use serde_json::{Value, json};

/// How one experiment ended.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Status {
    /// It ran and its results were written.
    Ok,
    /// Bad input (exit status 2): the message.
    BadInput(String),
    /// A bug, a panic or an I/O failure (exit status 1): the message.
    Internal(String),
}

impl Status {
    /// The failure of `e`.
    pub fn of(e: &RunError) -> Self {
        match e {
            RunError::BadInput { .. } => Status::BadInput(e.to_string()),
            RunError::Internal(_) => Status::Internal(e.to_string()),
        }
    }

    fn word(&self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::BadInput(_) => "bad input",
            Status::Internal(_) => "internal error",
        }
    }

    fn message(&self) -> Option<&str> {
        match self {
            Status::Ok => None,
            Status::BadInput(m) | Status::Internal(m) => Some(m),
        }
    }
}

/// One experiment's line of the summary.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Experiment id.
    pub id: String,
    /// Wall time of its run, seconds (computing the report, not writing it).
    pub seconds: f64,
    /// Simulated trials ([`Report::trials`]); 0 for a failed run.
    pub trials: u64,
    /// Tooth engagements ([`Report::engagements`]); 0 when not counted or failed.
    pub engagements: u64,
    /// Agreement with the paper, where the experiment judges it.
    pub agreement: Option<Agreement>,
    /// How it ended.
    pub status: Status,
}

impl Row {
    /// The row of a finished run: from its report, or from its error.
    pub fn new(id: &str, seconds: f64, result: Result<&Report, &RunError>) -> Self {
        match result {
            Ok(r) => Row {
                id: id.to_owned(),
                seconds,
                trials: r.trials,
                engagements: r.engagements,
                agreement: r.agreement.clone(),
                status: Status::Ok,
            },
            Err(e) => Row {
                id: id.to_owned(),
                seconds,
                trials: 0,
                engagements: 0,
                agreement: None,
                status: Status::of(e),
            },
        }
    }
}

/// Sum of the agreements of the rows that judge it; `None` when none does.
fn total_agreement(rows: &[Row]) -> Option<Agreement> {
    rows.iter()
        .filter_map(|r| r.agreement.clone())
        .reduce(|a, b| Agreement {
            consistent: a.consistent + b.consistent,
            differ: a.differ + b.differ,
            what: if a.what == b.what { a.what } else { "".into() },
        })
}

fn agreement_cell(a: Option<Agreement>) -> String {
    a.map_or_else(
        || "-".into(),
        |a| format!("{} / {}", a.consistent, a.differ),
    )
}

fn count_cell(n: u64) -> String {
    if n == 0 { "-".into() } else { n.to_string() }
}

/// The summary table: one row per experiment, then the total.
pub fn table(rows: &[Row]) -> Table {
    let mut t = Table::new(
        "Summary of run all",
        [
            "experiment",
            "wall time [s]",
            "trials",
            "tooth engagements",
            "paper consistent / differ",
            "status",
        ],
    );
    for r in rows {
        t.row(vec![
            r.id.clone(),
            fmt_f64(r.seconds, 2),
            r.trials.to_string(),
            count_cell(r.engagements),
            agreement_cell(r.agreement.clone()),
            r.status.word().into(),
        ]);
    }
    let failed = rows.iter().filter(|r| r.status != Status::Ok).count();
    t.row(vec![
        "total".into(),
        fmt_f64(rows.iter().map(|r| r.seconds).sum(), 2),
        rows.iter().map(|r| r.trials).sum::<u64>().to_string(),
        count_cell(rows.iter().map(|r| r.engagements).sum()),
        agreement_cell(total_agreement(rows)),
        format!("{} ok, {failed} failed", rows.len() - failed),
    ]);
    t.note("Wall time: the experiment's run (computing its report), not writing results. Trials: simulated pair turns or train runs (0: none random). Tooth engagements: teeth passed through each mesh over the runs ('-': not counted).");
    t.note("Paper consistent / differ: how many of the paper's numbers are consistent with ours and how many differ (counts of trials, the paper's being samples of 200 too: Fisher's exact two-sample test at 5 %; other values: inside our 95 % interval); '-': the experiment does not judge it.");
    for r in rows {
        if let Some(m) = r.status.message() {
            t.note(format!("{} failed: {m}", r.id));
        }
    }
    t
}

/// `summary.md`, as [`markdown`] writes it: replaced only by another.
pub(crate) const MARKDOWN_KIND: registry::FileKind = registry::FileKind {
    what: "the summary of `run all`",
    recognise: |head| head.starts_with(b"# cargo xtask run all\n"),
};

/// `summary.json`, as [`json()`] writes it: replaced only by another.
pub(crate) const JSON_KIND: registry::FileKind = registry::FileKind {
    what: "the summary of `run all`",
    recognise: |head| head.starts_with(b"{\n  \"experiments\": ["),
};

/// `summary.md`: a heading naming the seed and threads, then the table.
pub fn markdown(rows: &[Row], seed: u64, threads: usize) -> String {
    format!(
        "# cargo xtask run all\n\nSeed {seed}, {threads} thread{}.\n\n{}",
        if threads == 1 { "" } else { "s" },
        table(rows).render()
    )
}

/// `summary.json`: `{seed, threads, experiments: [{id, seconds, trials, engagements,
/// agreement: {consistent, differ} | null, status, error}], total: {...}}`.
pub fn json(rows: &[Row], seed: u64, threads: usize) -> String {
    let experiments: Vec<Value> = rows
        .iter()
        .map(|r| {
            json!({
                "id": r.id,
                "seconds": r.seconds,
                "trials": r.trials,
                "engagements": r.engagements,
                "agreement": r.agreement,
                "status": r.status.word(),
                "error": r.status.message(),
            })
        })
        .collect();
    let failed = rows.iter().filter(|r| r.status != Status::Ok).count();
    let mut s = format!(
        "{:#}",
        json!({
            "seed": seed,
            "threads": threads,
            "experiments": experiments,
            "total": {
                "seconds": rows.iter().map(|r| r.seconds).sum::<f64>(),
                "trials": rows.iter().map(|r| r.trials).sum::<u64>(),
                "engagements": rows.iter().map(|r| r.engagements).sum::<u64>(),
                "agreement": total_agreement(rows),
                "ok": rows.len() - failed,
                "failed": failed,
            },
        })
    );
    s.push('\n');
    s
}

/// Exit status of a `run all`: 1 if any experiment failed internally (a bug outranks bad
/// input), else 2 if any had bad input, else 0.
pub fn exit_code(rows: &[Row]) -> u8 {
    if rows.iter().any(|r| matches!(r.status, Status::Internal(_))) {
        1
    } else if rows.iter().any(|r| matches!(r.status, Status::BadInput(_))) {
        2
    } else {
        0
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    fn rows() -> Vec<Row> {
        let judged = Report {
            trials: 800,
            engagements: 0,
            agreement: Some(Agreement {
                consistent: 17,
                differ: 43,
                what: "".into(),
            }),
            ..Default::default()
        };
        let counted = Report {
            trials: 120,
            engagements: 1_234_567,
            agreement: Some(Agreement {
                consistent: 1,
                differ: 3,
                what: "".into(),
            }),
            ..Default::default()
        };
        vec![
            Row::new("fig2", 0.25, Ok(&Report::default())),
            Row::new("table3", 61.0, Ok(&judged)),
            Row::new("failure", 40.5, Ok(&counted)),
            Row::new(
                "pair",
                0.01,
                Err(&RunError::bad("--set", "days", "must be at least 1")),
            ),
        ]
    }

    #[test]
    fn table_has_a_row_per_experiment_and_a_total() {
        let text = table(&rows()).render();
        let expected = "\
### Summary of run all

| experiment | wall time [s] | trials | tooth engagements | paper consistent / differ | status         |
|:-----------|--------------:|-------:|------------------:|:--------------------------|:---------------|
| fig2       |          0.25 |      0 |                 - | -                         | ok             |
| table3     |         61.00 |    800 |                 - | 17 / 43                   | ok             |
| failure    |         40.50 |    120 |           1234567 | 1 / 3                     | ok             |
| pair       |          0.01 |      0 |                 - | -                         | bad input      |
| total      |        101.76 |    920 |           1234567 | 18 / 46                   | 3 ok, 1 failed |

- Wall time: the experiment's run (computing its report), not writing results. Trials: simulated pair turns or train runs (0: none random). Tooth engagements: teeth passed through each mesh over the runs ('-': not counted).
- Paper consistent / differ: how many of the paper's numbers are consistent with ours and how many differ (counts of trials, the paper's being samples of 200 too: Fisher's exact two-sample test at 5 %; other values: inside our 95 % interval); '-': the experiment does not judge it.
- pair failed: --set: days: must be at least 1
";
        assert_eq!(text, expected);
    }

    #[test]
    fn no_judging_experiment_gives_a_dash_total() {
        let rows = vec![Row::new("fig2", 1.0, Ok(&Report::default()))];
        let t = table(&rows);
        let total = t.rows.last().unwrap();
        assert_eq!(total[0], "total");
        assert_eq!(total[4], "-");
        assert_eq!(total[5], "1 ok, 0 failed");
    }

    #[test]
    fn json_and_markdown_carry_the_same_numbers() {
        let rows = rows();
        let v: Value = serde_json::from_str(&json(&rows, 2025, 2)).unwrap();
        assert_eq!(v["seed"], 2025);
        assert_eq!(v["threads"], 2);
        assert_eq!(v["experiments"].as_array().unwrap().len(), 4);
        assert_eq!(v["experiments"][1]["agreement"]["consistent"], 17);
        assert_eq!(v["experiments"][0]["agreement"], Value::Null);
        assert_eq!(v["experiments"][3]["status"], "bad input");
        assert_eq!(
            v["experiments"][3]["error"],
            "--set: days: must be at least 1"
        );
        assert_eq!(v["total"]["trials"], 920);
        assert_eq!(v["total"]["engagements"], 1_234_567);
        assert_eq!(v["total"]["agreement"]["differ"], 46);
        assert_eq!(v["total"]["failed"], 1);
        let md = markdown(&rows, 2025, 2);
        assert!(md.starts_with("# cargo xtask run all\n\nSeed 2025, 2 threads.\n\n### Summary"));
        assert!(md.contains("| failure "));
    }

    #[test]
    fn exit_code_reflects_the_worst_failure() {
        let mut rows = rows();
        assert_eq!(exit_code(&rows), 2);
        rows.push(Row::new(
            "x",
            0.0,
            Err(&RunError::Internal("experiment `x` panicked".into())),
        ));
        assert_eq!(exit_code(&rows), 1);
        assert_eq!(exit_code(&rows[..3]), 0);
        assert_eq!(exit_code(&[]), 0);
    }
}
