//! Our counts of a jam cell beside the paper's: the two-sample mark, the tally under a table,
//! the printed cell and its CSV columns.

use registry::{Report, RunError, fmt_f64};
use study::cell::{CellSpec, Counts, PAPER_TRIALS};
use study::grids::CellSettings;
use study::tolerance;

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

/// What a per-mesh table's agreement counts ([`Tally::agreement`]): its cells' counts, jams and
/// disengagements, each judged against the paper's by Fisher's exact two-sample test.
pub const COUNTS_COMPARED: &str = "counts (jams and disengagements of the cells compared): Fisher's exact test at 5 % does not separate the paper's count from ours / separates them";

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
            what: COUNTS_COMPARED.into(),
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

/// The mark after a side of a printed cell (ours, or the paper's in brackets) that keeps the
/// paper's 1 % rule ([`keeps_rule`]): the cells the paper shades.
pub const RULE_MARK: char = '✓';

/// The mark after a cell whose paper counts come from other inputs than ours (Table 5's meshes
/// run at our own E. max): shown for reference, not compared.
pub const NOT_COMPARED_MARK: char = '†';

pub use study::tolerance::{PAPER_RULE_PERCENT, keeps_rule};

/// The note under a table of cells on the rule marks, for a rule of `rule_percent` % and our
/// `trials` per cell.
pub fn rule_note(rule_percent: f64, trials: u64) -> String {
    let ours = tolerance::allowed_jams(trials, rule_percent);
    let paper = tolerance::allowed_jams(PAPER_TRIALS, rule_percent);
    format!(
        "`{RULE_MARK}` after a side of a cell (ours, or the paper's in brackets): that side keeps the paper's {} % rule, at most {paper} of {PAPER_TRIALS} trials jammed and at most {paper} disengaged (ours: at most {ours} of {trials} each), the cells the paper shades. The paper's text allows 2 of 200 (\"a maximum of 2 jams is acceptable\", and its E. max row tolerates m2-n1's 2 jams at 0.035); its captions word the shading as \"the jamming percentage was below 1%\" and \"one or fewer trials showing jamming or disengagement\", which would leave its cells with exactly 2 unshaded.",
        registry::fmt_number(rule_percent),
    )
}

/// A printed cell, `jams/dis (paper jams/paper dis)`, with `*` after each of our counts that
/// the two-sample test separates from the paper's ([`consistent_with_paper`]) and
/// [`RULE_MARK`] after each side that keeps the rule of `rule_percent` % ([`keeps_rule`]);
/// the cell's comparison is added to `tally`. A cell not `compared` (its paper counts come from
/// other inputs) gets no `*`, is not tallied, and ends with [`NOT_COMPARED_MARK`].
pub fn cell_text(
    c: &Counts,
    paper: (Option<u64>, Option<u64>),
    (rule_percent, compared): (f64, bool),
    tally: &mut Tally,
) -> String {
    if compared {
        tally.add(c, paper);
    }
    let mark = |k: u64, p: Option<u64>| {
        if !compared || consistent_with_paper(k, c.trials, p) {
            ""
        } else {
            "*"
        }
    };
    let show = |p: Option<u64>| p.map_or_else(|| "-".to_string(), |v| v.to_string());
    let rule = |kept: bool| {
        if kept {
            RULE_MARK.to_string()
        } else {
            String::new()
        }
    };
    let paper_rule = match paper {
        (Some(j), Some(d)) => rule(keeps_rule(j, d, PAPER_TRIALS, rule_percent)),
        _ => String::new(),
    };
    format!(
        "{}{}/{}{}{} ({}/{}{paper_rule}){}",
        c.jams,
        mark(c.jams, paper.0),
        c.disengagements,
        mark(c.disengagements, paper.1),
        rule(keeps_rule(c.jams, c.disengagements, c.trials, rule_percent)),
        show(paper.0),
        show(paper.1),
        if compared {
            String::new()
        } else {
            NOT_COMPARED_MARK.to_string()
        },
    )
}

/// CSV columns of one cell's counts, after [`CSV_COLUMNS`]: counts, interval bounds (as counts
/// out of our trials), the paper's counts (out of 200; empty when it gives none), the
/// two-sample test's p-values (empty where not compared), whether each side keeps the rule of
/// `rule_percent` % and whether the cell is compared with the paper's.
pub fn csv_columns(
    c: &Counts,
    paper: (Option<u64>, Option<u64>),
    (rule_percent, compared): (f64, bool),
) -> Vec<String> {
    let (wj, wd) = (c.jam_interval(), c.dis_interval());
    let n = c.trials as f64;
    let show = |p: Option<u64>| p.map_or_else(String::new, |v| v.to_string());
    let p_value = |k: u64, p: Option<u64>| {
        if !compared {
            return String::new();
        }
        paper_p_value(k, c.trials, p).map_or_else(String::new, |v| format!("{v:.4}"))
    };
    let paper_rule = match paper {
        (Some(j), Some(d)) => keeps_rule(j, d, PAPER_TRIALS, rule_percent).to_string(),
        _ => String::new(),
    };
    vec![
        c.trials.to_string(),
        c.jams.to_string(),
        (wj.lo * n).to_string(),
        (wj.hi * n).to_string(),
        show(paper.0),
        p_value(c.jams, paper.0),
        c.disengagements.to_string(),
        (wd.lo * n).to_string(),
        (wd.hi * n).to_string(),
        show(paper.1),
        p_value(c.disengagements, paper.1),
        keeps_rule(c.jams, c.disengagements, c.trials, rule_percent).to_string(),
        paper_rule,
        compared.to_string(),
    ]
}

/// Header of [`csv_columns`]: `*_p_fisher` is the two-sided p-value of Fisher's exact test of
/// our count against the paper's (empty where the paper gives none or the cell is not
/// compared); `rule_kept` and `paper_rule_kept` whether our cell and the paper's keep the
/// paper's 1 % rule ([`keeps_rule`]; the run's `rule` where it has one); `compared` whether the
/// paper's counts come from the same inputs as ours.
pub const CSV_COLUMNS: &str = "trials,jams,jam_lo,jam_hi,paper_jams,jam_p_fisher,disengagements,dis_lo,dis_hi,paper_disengagements,dis_p_fisher,rule_kept,paper_rule_kept,compared";

/// One row of a jam table by the rule: how many of its cells keep it, ours and the paper's,
/// and the meshes where the two verdicts differ.
#[derive(Debug, Clone, Default)]
struct RuleRow {
    /// The row as the table labels it (a Case, an error, a Case and G).
    label: String,
    /// Our cells in the row, and those that keep the rule.
    ours: (u64, u64),
    /// The paper's cells in the row (where it gives both counts), and those that keep it.
    paper: (u64, u64),
    /// The compared cells where one side keeps the rule and the other does not: mesh, ours,
    /// the paper's (`jams/dis`).
    differ: Vec<(String, String, String)>,
}

/// The cells of a jam table as they are filled: each printed beside the paper's counts, its CSV
/// line (key columns, then [`CSV_COLUMNS`]), the [`Tally`] of the two-sample marks and the
/// verdicts of the paper's 1 % rule by row.
#[derive(Debug, Clone)]
pub struct JamCells {
    /// The CSV: the header, then one line per cell.
    pub csv: String,
    /// The inputs of this run that differ from the paper's (`name=value`): where any does, no
    /// cell is compared with the paper's counts.
    off_paper: Vec<String>,
    /// The comparison with the paper's counts so far.
    pub tally: Tally,
    /// The failure rule the cells are marked by, % of trials.
    rule_percent: f64,
    /// Our trials per cell (the last cell's), for the notes.
    trials: u64,
    rows: Vec<RuleRow>,
}

impl JamCells {
    /// No cells yet; the CSV's header is `keys` (the key columns, e.g. `["case", "mesh"]`), then
    /// [`CSV_COLUMNS`]; cells are marked by the paper's 1 % rule.
    pub fn new(keys: &[&str]) -> JamCells {
        JamCells {
            csv: registry::csv_line(keys.iter().copied().chain(CSV_COLUMNS.split(','))),
            off_paper: Vec::new(),
            tally: Tally::default(),
            rule_percent: PAPER_RULE_PERCENT,
            trials: PAPER_TRIALS,
            rows: Vec::new(),
        }
    }

    /// The same, for a run whose inputs differ from the paper's in `inputs` (`name=value`, see
    /// `setting_groups::typed::off_paper_inputs`): none of its cells is compared with the paper's counts, which came
    /// from other inputs; they are shown for reference.
    pub fn off_paper(mut self, inputs: Vec<String>) -> JamCells {
        self.off_paper = inputs;
        self
    }

    /// The note on the `†` of a run off the paper's inputs: what it marks, and the inputs.
    pub fn off_paper_note(&self) -> Option<String> {
        (!self.off_paper.is_empty()).then(|| {
            format!(
                "`†`: not compared with the paper's counts, which come from other inputs than this run's ({}): no `*`, not tallied, not coloured in the report; the paper's 1 % rule marks stand on each side.",
                self.off_paper.join(", ")
            )
        })
    }

    /// The same, marked by a rule of `percent` % instead (a run that sets its `rule`).
    pub fn with_rule(mut self, percent: f64) -> JamCells {
        self.rule_percent = percent;
        self
    }

    /// One cell of row `row` (as the table labels it) and mesh `mesh`: its CSV line (`keys`, the
    /// values of the key columns, then [`csv_columns`]), added to the tally; returns the printed
    /// cell ([`cell_text`]).
    pub fn cell(
        &mut self,
        (row, mesh): (&str, &str),
        keys: &[&str],
        c: &Counts,
        paper: (Option<u64>, Option<u64>),
    ) -> String {
        self.cell_compared((row, mesh), keys, c, paper, true)
    }

    /// [`JamCells::cell`] for a cell whose paper counts may come from other inputs: not
    /// `compared`, it gets no two-sample mark and is not tallied.
    pub fn cell_compared(
        &mut self,
        (row, mesh): (&str, &str),
        keys: &[&str],
        c: &Counts,
        paper: (Option<u64>, Option<u64>),
        compared: bool,
    ) -> String {
        let compared = compared && self.off_paper.is_empty();
        let how = (self.rule_percent, compared);
        let fields = keys.iter().map(|k| (*k).to_owned());
        self.csv.push_str(&registry::csv_line(
            fields.chain(csv_columns(c, paper, how)),
        ));
        self.trials = c.trials;
        if self.rows.last().is_none_or(|r| r.label != row) {
            self.rows.push(RuleRow {
                label: row.to_owned(),
                ..RuleRow::default()
            });
        }
        let ours = keeps_rule(c.jams, c.disengagements, c.trials, self.rule_percent);
        let theirs = match paper {
            (Some(j), Some(d)) => Some(keeps_rule(j, d, PAPER_TRIALS, self.rule_percent)),
            _ => None,
        };
        if let Some(r) = self.rows.last_mut() {
            r.ours.0 += 1;
            r.ours.1 += u64::from(ours);
            if let Some(t) = theirs {
                r.paper.0 += 1;
                r.paper.1 += u64::from(t);
                if compared && t != ours {
                    r.differ.push((
                        mesh.to_owned(),
                        format!("{}/{}", c.jams, c.disengagements),
                        format!("{}/{}", paper.0.unwrap_or(0), paper.1.unwrap_or(0)),
                    ));
                }
            }
        }
        cell_text(c, paper, how, &mut self.tally)
    }

    /// The note on the rule marks ([`rule_note`]).
    pub fn rule_note(&self) -> String {
        rule_note(self.rule_percent, self.trials)
    }

    /// The table of the rule's verdicts by row, titled after `name` (e.g. `Table 3`) with the
    /// column heading `row` (e.g. `case`): per row, the cells that keep it, ours and the
    /// paper's, and the compared cells where the two verdicts differ.
    pub fn rule_table(&self, name: &str, row: &str) -> registry::Table {
        let percent = registry::fmt_number(self.rule_percent);
        let allowed = tolerance::allowed_jams(PAPER_TRIALS, self.rule_percent);
        let mut t = registry::Table::new(
            format!(
                "{name} by the paper's {percent} % rule: cells that keep it (at most {allowed} of {PAPER_TRIALS} trials jammed and at most {allowed} disengaged), ours and the paper's"
            ),
            [
                row,
                "cells kept: ours",
                "cells kept: paper",
                "verdicts differ at: mesh ours (paper)",
            ],
        );
        for r in &self.rows {
            let differ: Vec<String> = r
                .differ
                .iter()
                .map(|(m, o, p)| format!("{m} {o} ({p})"))
                .collect();
            t.row(vec![
                r.label.clone(),
                format!("{} of {}", r.ours.1, r.ours.0),
                if r.paper.0 == 0 {
                    "-".into()
                } else {
                    format!("{} of {}", r.paper.1, r.paper.0)
                },
                if differ.is_empty() {
                    "-".into()
                } else {
                    differ.join(", ")
                },
            ]);
        }
        t.note(format!(
            "The paper's conclusions rest on this rule (section 5, footnote 4: at 1 % per mesh, 15 meshes fail together about 14 % of the time). Ours keep it where at most {} of our {} trials jammed and at most as many disengaged. A verdict that differs is listed only where the two cells are compared (the same inputs).",
            tolerance::allowed_jams(self.trials, self.rule_percent),
            self.trials
        ));
        t
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
        let paper_rule = (PAPER_RULE_PERCENT, true);
        assert_eq!(
            cell_text(&c(40, 5), (Some(55), Some(30)), paper_rule, &mut tally),
            "40/5* (55/30)"
        );
        assert_eq!(
            cell_text(&c(40, 30), (Some(70), None), paper_rule, &mut tally),
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
                differ: 2,
                what: COUNTS_COMPARED.into(),
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

    /// The paper's 1 % rule marks each side of a cell: at most 2 of 200 trials jammed and at most
    /// 2 disengaged (Table 3's Case A m3-e3: ours 3, the paper's 2 - the paper's cell keeps the
    /// rule, ours does not), each side judged on its own trials.
    #[test]
    fn the_one_percent_rule_marks_each_side_of_a_cell() {
        let c = |jams: u64, dis: u64, trials: u64| Counts {
            jams,
            disengagements: dis,
            trials,
            ..Counts::default()
        };
        let rule = (PAPER_RULE_PERCENT, true);
        let mut tally = Tally::default();
        assert_eq!(
            cell_text(&c(3, 0, 200), (Some(2), Some(0)), rule, &mut tally),
            "3/0 (2/0✓)"
        );
        assert_eq!(
            cell_text(&c(2, 0, 200), (Some(2), Some(0)), rule, &mut tally),
            "2/0✓ (2/0✓)"
        );
        // A disengagement counts against a cell as a jam does (Case D's m3-e3: 0/200).
        assert_eq!(
            cell_text(&c(0, 3, 200), (Some(0), Some(200)), rule, &mut tally),
            "0/3* (0/200)"
        );
        // 20 trials allow no failure at 1 %; the paper's side is judged on its 200.
        assert_eq!(
            cell_text(&c(1, 0, 20), (Some(1), Some(0)), rule, &mut tally),
            "1/0 (1/0✓)"
        );
        // Another rule: 5 % of 200 is 10.
        assert!(keeps_rule(10, 0, 200, 5.0) && !keeps_rule(11, 0, 200, 5.0));
        // No paper count: only our side is judged.
        assert_eq!(
            cell_text(&c(0, 0, 200), (None, None), rule, &mut tally),
            "0/0✓ (-/-)"
        );
        // A cell whose paper counts come from other inputs: no `*`, not tallied, marked `†`.
        let before = tally;
        assert_eq!(
            cell_text(&c(40, 0, 200), (Some(1), Some(0)), (1.0, false), &mut tally),
            "40/0 (1/0✓)†"
        );
        assert_eq!(tally, before);
        // The verdicts by row: kept cells on each side, and where they differ.
        let mut cells = JamCells::new(&["case", "mesh"]);
        cells.cell(
            ("A", "m3-e3"),
            &["A", "m3-e3"],
            &c(3, 0, 200),
            (Some(2), Some(0)),
        );
        cells.cell(
            ("A", "b2-c1"),
            &["A", "b2-c1"],
            &c(0, 0, 200),
            (Some(0), Some(0)),
        );
        cells.cell(
            ("B", "m3-e3"),
            &["B", "m3-e3"],
            &c(141, 0, 200),
            (Some(168), Some(0)),
        );
        let t = cells.rule_table("Table 3", "case");
        assert_eq!(
            t.rows,
            vec![
                vec!["A", "1 of 2", "2 of 2", "m3-e3 3/0 (2/0)"],
                vec!["B", "0 of 1", "0 of 1", "-"],
            ]
        );
        let line = cells.csv.lines().nth(1).unwrap();
        assert!(line.ends_with(",false,true,true"), "{line}");
    }
}
