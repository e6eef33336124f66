//! Our counts of a jam cell beside the paper's: the two-sample mark, the tally under a table,
//! the printed cell and its CSV columns.

use registry::{Report, RunError, fmt_f64};
use study::cell::{CellSpec, Counts, PAPER_TRIALS};
use study::grids::CellSettings;

/// One cell of the paper's per-mesh tables: `mesh` under the settings' hypothesis with `errors`
/// at clearance `g` (% of h) and the settings' tooth height. Its rule is the default, for the
/// experiments that count a cell by other means (every rule at once, or other contact tests).
pub fn cell(
    s: &CellSettings,
    mesh: &str,
    errors: &[(&str, f64)],
    g: f64,
) -> Result<CellSpec, RunError> {
    let mut cell = s.cell(mesh, s.errors.params(errors)?, g);
    cell.events = rules::Rule::default();
    Ok(cell)
}

/// Which of the paper's per-mesh tables a cell of [`paper_table_cells`] belongs to.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum PaperTable {
    /// Table 3: a Case at the settings' clearance.
    Table3 {
        /// The Case: A to D.
        case: &'static str,
    },
    /// Table 4: a random error only.
    Table4 {
        /// The random error (of the pitch).
        random: f64,
    },
    /// Table I: a Case at one of its clearances.
    TableI {
        /// The Case: A to D.
        case: &'static str,
        /// The clearance G (% of h).
        clearance: f64,
    },
}

/// One cell of Tables 3, 4 and I and where its paper counts are.
pub struct PaperTableCell {
    /// The cell (the default rule).
    pub cell: CellSpec,
    /// Its table, and the Case, error or clearance it stands for there.
    pub table: PaperTable,
    /// The experiment id whose numbers `paper.ron` holds (`table3`, `table4`, `tableI`).
    pub id: &'static str,
    /// Its key there, e.g. `B.m3-e3`, `0.065.m3-e3`, `B.70.m3-e3`.
    pub key: String,
}

/// The cells of Tables 3 (Cases A-D at the settings' clearance), 4 (each random error of
/// `randoms`, no systematic error) and I (Cases A-D at each of `clearances`), each mesh in the
/// gearing's order: the paper's per-mesh counts that `event-rules` and `jam-readings` set beside
/// theirs.
pub fn paper_table_cells(
    s: &CellSettings,
    randoms: &[f64],
    clearances: &[f64],
) -> Result<Vec<PaperTableCell>, RunError> {
    use study::cell::label;
    let (clearance, split) = (s.clearance()?, s.errors.split()?);
    let meshes: Vec<&str> = s
        .gearing()
        .meshes()
        .iter()
        .map(|m| m.label.as_str())
        .collect();
    let case_errors =
        |sys: f64, random: f64| [("random", random), ("systematic", sys), ("split", split)];
    let mut out = Vec::new();
    for &(case, sys, random) in &study::grids::CASES {
        for m in &meshes {
            out.push(PaperTableCell {
                cell: cell(s, m, &case_errors(sys, random), clearance)?,
                table: PaperTable::Table3 { case },
                id: "table3",
                key: format!("{case}.{m}"),
            });
        }
    }
    for &random in randoms {
        for m in &meshes {
            out.push(PaperTableCell {
                cell: cell(s, m, &[("random", random), ("systematic", 0.0)], clearance)?,
                table: PaperTable::Table4 { random },
                id: "table4",
                key: format!("{}.{m}", label(random, 3)),
            });
        }
    }
    for &(case, sys, random) in &study::grids::CASES {
        for &g in clearances {
            for m in &meshes {
                out.push(PaperTableCell {
                    cell: cell(s, m, &case_errors(sys, random), g)?,
                    table: PaperTable::TableI { case, clearance: g },
                    id: "tableI",
                    key: format!("{case}.{}.{m}", label(g, 0)),
                });
            }
        }
    }
    Ok(out)
}

/// The paper's (jams, disengagements) of one cell: `{key}.jam` and `{key}.dis` of experiment `id`
/// in `paper.ron`, counts out of [`PAPER_TRIALS`].
pub fn paper_counts(id: &str, key: &str) -> (Option<u64>, Option<u64>) {
    let get = |q: &str| crate::paper::get(id, &format!("{key}.{q}")).map(|r| r.value as u64);
    (get("jam"), get("dis"))
}

/// [`paper_counts`] of a Case's cell where the Cases apply (`cases_apply`); none where they do
/// not (a hypothesis the Cases do not reach is compared with no Case).
pub fn case_paper_counts(cases_apply: bool, id: &str, key: &str) -> (Option<u64>, Option<u64>) {
    if cases_apply {
        paper_counts(id, key)
    } else {
        (None, None)
    }
}

/// Is the paper's count (out of [`PAPER_TRIALS`]) consistent with ours (`k` of `n`)? The paper's
/// count is a sample of 200 trials too, so the two are compared as two samples: consistent
/// unless Fisher's exact two-sided test separates them at 5 % ([`stats::consistent`]). A run
/// with another trial count is judged the same way. No paper value counts as consistent.
pub fn consistent_with_paper(k: u64, n: u64, paper: Option<u64>) -> bool {
    paper.is_none_or(|p| stats::consistent(k, n, p.min(PAPER_TRIALS), PAPER_TRIALS))
}

/// Two-sided p-value of Fisher's exact test between our `k` of `n` and the paper's count of 200.
pub fn paper_p_value(k: u64, n: u64, paper: Option<u64>) -> Option<f64> {
    paper.map(|p| stats::fisher_exact_two_sided(k, n, p.min(PAPER_TRIALS), PAPER_TRIALS))
}

/// How many of the paper's counts are consistent with ours, jams and disengagements apart.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Tally {
    /// The paper's jam counts consistent with ours.
    pub jams_consistent: u64,
    /// The paper's jam counts compared.
    pub jams_compared: u64,
    /// The paper's disengagement counts consistent with ours.
    pub dis_consistent: u64,
    /// The paper's disengagement counts compared.
    pub dis_compared: u64,
}

impl Tally {
    /// Adds the comparison of one cell with the paper's counts (those it gives).
    pub fn add(&mut self, c: &Counts, paper: (Option<u64>, Option<u64>)) {
        if paper.0.is_some() {
            self.jams_compared += 1;
            self.jams_consistent += u64::from(consistent_with_paper(c.jams, c.trials, paper.0));
        }
        if paper.1.is_some() {
            self.dis_compared += 1;
            self.dis_consistent +=
                u64::from(consistent_with_paper(c.disengagements, c.trials, paper.1));
        }
    }

    /// As the report's agreement: every paper count compared, jams and disengagements alike.
    pub fn agreement(&self) -> registry::Agreement {
        let consistent = self.jams_consistent + self.dis_consistent;
        registry::Agreement {
            consistent,
            differ: self.jams_compared + self.dis_compared - consistent,
        }
    }

    /// The note printed under a table of cells.
    pub fn note(&self) -> String {
        format!(
            "The paper's counts consistent with ours by Fisher's exact two-sample test (both are samples: ours of this run's trials, the paper's of 200; separated at 5 %): jams {}, disengagements {}. `*` after one of our counts: the test separates it from the paper's.",
            share(self.jams_consistent, self.jams_compared),
            share(self.dis_consistent, self.dis_compared),
        )
    }
}

/// `k of n (p %)`, or `none compared`.
pub fn share(k: u64, n: u64) -> String {
    if n == 0 {
        "none compared".into()
    } else {
        format!("{k} of {n} ({} %)", fmt_f64(100.0 * k as f64 / n as f64, 0))
    }
}

/// A printed cell, `jams/dis (paper jams/paper dis)`, with `*` after each of our counts that
/// the two-sample test separates from the paper's ([`consistent_with_paper`]); the cell's
/// comparison is added to `tally`.
pub fn cell_text(c: &Counts, paper: (Option<u64>, Option<u64>), tally: &mut Tally) -> String {
    tally.add(c, paper);
    let mark = |k: u64, p: Option<u64>| {
        if consistent_with_paper(k, c.trials, p) {
            ""
        } else {
            "*"
        }
    };
    let show = |p: Option<u64>| p.map_or_else(|| "-".to_string(), |v| v.to_string());
    format!(
        "{}{}/{}{} ({}/{})",
        c.jams,
        mark(c.jams, paper.0),
        c.disengagements,
        mark(c.disengagements, paper.1),
        show(paper.0),
        show(paper.1),
    )
}

/// CSV columns of one cell's counts, after [`CSV_COLUMNS`]: counts, interval bounds (as counts
/// out of our trials), the paper's counts (out of 200; empty when it gives none) and the
/// two-sample test's p-values.
pub fn csv_columns(c: &Counts, paper: (Option<u64>, Option<u64>)) -> String {
    let (wj, wd) = (c.jam_interval(), c.dis_interval());
    let n = c.trials as f64;
    let show = |p: Option<u64>| p.map_or_else(String::new, |v| v.to_string());
    let p_value = |k: u64, p: Option<u64>| {
        paper_p_value(k, c.trials, p).map_or_else(String::new, |v| format!("{v:.4}"))
    };
    format!(
        "{},{},{},{},{},{},{},{},{},{},{}",
        c.trials,
        c.jams,
        wj.lo * n,
        wj.hi * n,
        show(paper.0),
        p_value(c.jams, paper.0),
        c.disengagements,
        wd.lo * n,
        wd.hi * n,
        show(paper.1),
        p_value(c.disengagements, paper.1),
    )
}

/// Header of [`csv_columns`]: `*_p_fisher` is the two-sided p-value of Fisher's exact test of
/// our count against the paper's (empty where the paper gives none).
pub const CSV_COLUMNS: &str = "trials,jams,jam_lo,jam_hi,paper_jams,jam_p_fisher,disengagements,dis_lo,dis_hi,paper_disengagements,dis_p_fisher";

/// The cells of a jam table as they are filled: each printed beside the paper's counts, its CSV
/// line (key columns, then [`CSV_COLUMNS`]) and the [`Tally`] of the two-sample marks.
#[derive(Debug, Clone, Default)]
pub struct JamCells {
    /// The CSV: the header, then one line per cell.
    pub csv: String,
    /// The comparison with the paper's counts so far.
    pub tally: Tally,
}

impl JamCells {
    /// No cells yet; the CSV's header is `keys` (the key columns, e.g. `case,mesh`), then
    /// [`CSV_COLUMNS`].
    pub fn new(keys: &str) -> JamCells {
        JamCells {
            csv: format!("{keys},{CSV_COLUMNS}\n"),
            tally: Tally::default(),
        }
    }

    /// One cell: its CSV line (`keys`, the values of the key columns, then [`csv_columns`]),
    /// added to the tally; returns the printed cell ([`cell_text`]).
    pub fn cell(&mut self, keys: &str, c: &Counts, paper: (Option<u64>, Option<u64>)) -> String {
        self.csv
            .push_str(&format!("{keys},{}\n", csv_columns(c, paper)));
        cell_text(c, paper, &mut self.tally)
    }
}

/// What one trial of a Case's cell is, noted under the tables of Cases A-D.
pub const CASE_TRIAL_NOTE: &str = "Each trial: both gears manufactured afresh (hypothesis and Case), a random initial angle, one full turn of the gear with more teeth.";

/// The note under a per-mesh table saying how to see a failed trial of its cell `example`
/// (`cargo xtask replay ID CELL`).
pub fn replay_note(id: &str, example: &str) -> String {
    format!(
        "See a failed trial: `cargo xtask replay {id} {example}` lists the trials of that cell that jammed or disengaged; `cargo xtask replay {id} {example} TRIAL` rebuilds one from its random stream, prints its events and writes a pair file to rerun it (same --seed and --set as this run)."
    )
}

/// A report counting the trials and tooth engagements of `counts`, the rest empty: the base of
/// a jam table's report (`Report { tables, files, ..counts_report(cells) }`).
pub fn counts_report<'a>(counts: impl IntoIterator<Item = &'a Counts>) -> Report {
    let mut report = Report::default();
    for c in counts {
        report.trials += c.trials;
        report.engagements += c.engagements;
    }
    report
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn cells_are_marked_by_the_two_sample_test_not_by_our_interval() {
        let c = |jams: u64, dis: u64| Counts {
            jams,
            disengagements: dis,
            trials: 200,
            ..Counts::default()
        };
        // 40 of 200 against the paper's 55: outside our Wilson interval (14.9-26.2 %, 27.5 % is
        // above it), but as two samples of 200 not separated at 5 % (Fisher p = 0.100).
        assert!(!c(40, 0).jam_interval().contains_count(55));
        assert!(consistent_with_paper(40, 200, Some(55)));
        // 40 against 70 is separated (p = 0.0011).
        assert!(!consistent_with_paper(40, 200, Some(70)));
        // No paper value: nothing to separate.
        assert!(consistent_with_paper(3, 200, None));
        let mut tally = Tally::default();
        assert_eq!(
            cell_text(&c(40, 5), (Some(55), Some(30)), &mut tally),
            "40/5* (55/30)"
        );
        assert_eq!(
            cell_text(&c(40, 30), (Some(70), None), &mut tally),
            "40*/30 (70/-)"
        );
        assert_eq!(
            tally,
            Tally {
                jams_consistent: 1,
                jams_compared: 2,
                dis_consistent: 0,
                dis_compared: 1,
            }
        );
        assert_eq!(
            tally.agreement(),
            registry::Agreement {
                consistent: 1,
                differ: 2
            }
        );
        assert!(
            tally
                .note()
                .contains("jams 1 of 2 (50 %), disengagements 0 of 1 (0 %)")
        );
        // A run of another size is compared as a sample of its own size.
        assert!(consistent_with_paper(4, 20, Some(55)));
        assert!(!consistent_with_paper(20, 20, Some(55)));
    }
}
