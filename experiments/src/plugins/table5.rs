//! `table5`: each mesh's largest tolerable random error, derived from Table 4's results by the
//! paper's 1 % rule, then jams / disengagements with systematic errors of 0.1 to 1.1° (split
//! 50/50) on top of it, 200 trials per cell.

use registry::{OutputFile, Place, Report, Run, RunError, Table};
use replay::{Cell, CellText};
use serde::{Deserialize, Serialize};

use presentation::cells::{JamCells, counts_report, paper_counts};
use presentation::emax::{paper_random, paper_systematic, show};
use setting_groups::emax::{EMAX, given_row, random_from};
use setting_groups::typed::{Gearing, cells, off_paper_inputs};
use study::cell::{Purpose, label};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::grids::{CellSettings, TRIALS, derive};
use study::results::{DerivedTolerances, RandomFrom};
use study::tolerance::{self, RULE, RandomGrid, SystematicGrid};

/// Table 5's settings: trials per cell, the rule, where the random E. max comes from, the
/// gearing with h and G, the split and hypothesis, the grids of Tables 4 and 5, the event rule
/// and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// The tolerance rule, % of trials jamming ([`RULE`]).
    #[param(RULE)]
    pub rule: f64,
    /// `derived` or `paper` ([`EMAX`]).
    #[param(EMAX)]
    pub emax: String,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// Table 4's random errors.
    #[group]
    pub random: RandomGrid,
    /// Table 5's systematic amplitudes.
    #[group]
    pub systematic: SystematicGrid,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// Table 5.
pub struct Table5;

impl registry::Experiment for Table5 {
    const ID: &'static str = "table5";
    const TITLE: &'static str = "Largest tolerable random error of each mesh (from Table 4 by the 1 % rule), then jams and disengagements against the systematic error";
    const PAPER_ITEM: &'static str = "Table 5 (section 5)";
    const PLACE: Place = Place::Paper(100);
    type Settings = Settings;
    type Results = DerivedTolerances;

    fn compute(s: &Settings, run: &Run) -> Result<DerivedTolerances, RunError> {
        let cs = cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            Some(&s.events),
            Some(&s.drive),
            s.trials,
            s,
        )?;
        let grids = (s.random.values(s)?, s.systematic.values(s)?);
        let from = random_from(&s.emax);
        let given = given_row(from, &cs.meshes())?;
        let t = derive(run.engine(), &cs, grids, s.rule, Purpose::Own, given)?;
        Ok(DerivedTolerances::new(&t, cs.clearance()?, from))
    }

    fn report(s: &Settings, t: &DerivedTolerances) -> Result<Report, RunError> {
        let given = random_from(&s.emax) == RandomFrom::Paper;
        let like_for_like = like_for_like(t);
        let mut table = Table::new(
            title(s, given, &like_for_like),
            std::iter::once("E. sys [deg]".to_string())
                .chain(t.random_grid.table.meshes.iter().cloned()),
        );
        let (row, same) = random_row(t);
        table.row(row);
        let mut jam_cells = JamCells::new(&["systematic", "mesh", "random"])
            .with_rule(s.rule)
            .off_paper(off_paper_inputs(s));
        for row in count_rows(t, &like_for_like, &mut jam_cells) {
            table.row(row);
        }
        let emax_csv = String::from(
            "mesh,random_emax,paper_random_emax,systematic_emax_deg,paper_systematic_emax_deg_by_rule\n",
        );
        let (row, emax_csv) = systematic_row(t, s.rule, emax_csv);
        table.row(row);
        table.note(jam_cells.tally.note());
        if let Some(note) = jam_cells.off_paper_note() {
            table.note(note);
        }
        table.note(jam_cells.rule_note());
        add_notes(
            &mut table,
            t,
            (s.rule, s.trials),
            given,
            (&like_for_like, same),
        );
        let report = Report {
            tables: vec![
                table,
                jam_cells.rule_table("Table 5", "E. sys [deg]"),
                emax_in_units(t, s.errors.split),
            ],
            files: vec![
                OutputFile::new("table5-data.csv", jam_cells.csv),
                OutputFile::new("table5-emax.csv", emax_csv),
            ],
            agreement: Some(jam_cells.tally.agreement()),
            ..counts_report(t.all())
        };
        setting_groups::typed::label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(Table5);

crate::replay_cells! { "table5", "RANDOM/SYSTEMATIC/MESH, e.g. 0.050/0.7/e4-f1" => cell }

/// A cell of Table 5 for `cargo xtask replay`: `RANDOM/SYSTEMATIC/MESH`, the random error the
/// mesh's E. max (Table 5's first row), the systematic one a row, at the experiment's G and split.
fn cell<'a>(s: &CellSettings, c: &CellText<'a>) -> Result<Cell<'a>, RunError> {
    let &[random, systematic, mesh] = c.parts() else {
        return Err(c.malformed());
    };
    let errors = vec![
        (
            "random",
            c.number("random error", &tolerance::RANDOM_FROM.kind, random)?,
        ),
        (
            "systematic",
            c.number(
                "systematic error",
                &tolerance::SYSTEMATIC_FROM.kind,
                systematic,
            )?,
        ),
        ("split", s.errors.split()?),
    ];
    Ok(Cell {
        mesh,
        errors,
        clearance: s.clearance()?,
        typed: vec![
            ("random", "random error", random),
            ("systematic", "systematic error", systematic),
        ],
    })
}

/// Whether each mesh's cells compare with the paper's: only where they ran on the paper's
/// inputs, its E. max being the paper's (always under emax=paper).
fn like_for_like(t: &DerivedTolerances) -> Vec<bool> {
    t.meshes
        .iter()
        .map(|m| match (m.random, paper_random(&m.mesh)) {
            (Some(o), Some(p)) => (o - p).abs() <= 1e-9,
            _ => false,
        })
        .collect()
}

/// The table's title: the split, G, the E. max it ran at, and the marks it uses.
fn title(s: &Settings, given: bool, like_for_like: &[bool]) -> String {
    let (trials, clearance, split, rule) = (s.trials, s.gearing.clearance, s.errors.split, s.rule);
    let apart = like_for_like.iter().filter(|l| !**l).count();
    format!(
        "Table 5: trials (of {trials}) with at least one jam / disengagement against the systematic error (share {split} on the sinusoid, the rest on the axis) at each mesh's largest tolerable random error (row E. max{}), G = {clearance} %: ours (paper); * where a two-sample test separates our count from the paper's; ≠ where our E. max is not the paper's; ✓ where a cell keeps the {rule} % rule{}",
        if given {
            ": the paper's own, emax=paper"
        } else {
            ""
        },
        if apart == 0 {
            String::new()
        } else {
            format!(
                "; † where the mesh ran at our own E. max, not the paper's ({apart} of {} meshes): not compared, emax=paper runs every cell like for like",
                like_for_like.len()
            )
        }
    )
}

/// The first row, each mesh's largest tolerable random error beside the paper's (`≠` where
/// they differ: values of a grid compared, no test, so not the counts' `*`), and how many
/// agree.
fn random_row(t: &DerivedTolerances) -> (Vec<String>, usize) {
    let mut row = vec!["E. max (random)".to_string()];
    let mut same = 0;
    for m in &t.meshes {
        let ours = m.random;
        let paper = paper_random(&m.mesh);
        let differs = paper.is_some_and(|p| ours.is_none_or(|o| (o - p).abs() > 1e-9));
        if paper.is_some() && !differs {
            same += 1;
        }
        row.push(format!(
            "{} ({}){}",
            show(ours, t.random_grid.random.first(), 3),
            paper.map_or_else(|| "-".into(), |p| label(p, 3)),
            if differs { "≠" } else { "" }
        ));
    }
    (row, same)
}

/// A row per systematic error: each mesh's counts beside the paper's, compared where
/// `like_for_like`.
fn count_rows(
    t: &DerivedTolerances,
    like_for_like: &[bool],
    jam_cells: &mut JamCells,
) -> Vec<Vec<String>> {
    let mut rows = Vec::new();
    for sys_row in &t.rows {
        let key = label(sys_row.systematic, 1);
        let mut row = vec![key.clone()];
        for (m, tol) in t.meshes.iter().enumerate() {
            let mesh = &tol.mesh;
            let Some(c) = &sys_row.cells[m] else {
                row.push("-".into());
                continue;
            };
            let paper = paper_counts("table5", &format!("{key}.{mesh}"));
            let random = tol.random.map_or_else(String::new, |e| e.to_string());
            row.push(jam_cells.cell_compared(
                (&key, mesh),
                &[&key, mesh, &random],
                c,
                paper,
                like_for_like[m],
            ));
        }
        rows.push(row);
    }
    rows
}

/// The notes under the table: which meshes are not compared, how each E. max was found, and the
/// split of the systematic error.
fn add_notes(
    table: &mut Table,
    t: &DerivedTolerances,
    (rule, trials): (f64, u64),
    given: bool,
    (like_for_like, same): (&[bool], usize),
) {
    let meshes = &t.random_grid.table.meshes;
    let apart = like_for_like.iter().filter(|l| !**l).count();
    if apart > 0 {
        let names: Vec<&str> = meshes
            .iter()
            .zip(like_for_like)
            .filter(|(_, l)| !**l)
            .map(|(m, _)| m.as_str())
            .collect();
        table.note(format!(
            "`†`: {apart} of {} meshes ({}) ran at our own E. max (row E. max), not the paper's, so their cells and the paper's come from different inputs: the paper's counts are shown for reference, not compared (no `*`, not in the count above, not coloured in the report). `--set emax=paper` runs every mesh at the paper's E. max, so that every cell is compared like for like.",
            meshes.len(),
            names.join(", ")
        ));
    }
    if given {
        table.note("E. max (random): the paper's own row (emax=paper), not derived from Table 4: every cell runs on the paper's inputs, so all of them are compared like for like.");
    } else {
        table.note(format!(
            "E. max (random): the largest random error of Table 4's grid up to which every value has at most {} of {trials} trials jammed (rule {rule} %); ours agree with the paper's row for {same} of {} meshes (`≠` where not: two values of the grid compared, no test of counts, unlike the cells' `*`). Below the grid: `< {}`, and the column is not run.",
            tolerance::allowed_jams(trials, rule),
            // Of the meshes the paper has a row for (a gearing with others, the cosmos, adds
            // meshes that agree or differ with nothing).
            meshes.iter().filter(|m| paper_random(m).is_some()).count(),
            t.random_grid
                .random
                .first()
                .map_or_else(|| "-".into(), |v| label(*v, 3)),
        ));
    }
    table.note(format!(
        "E. max (systematic): the same rule on this table's jams (disengagements are not counted, as in the paper); in brackets the value the paper's own counts give by that rule (its text: e1-b3 up to 0.6, d2-e2 up to 0.1). `< {}`: even the smallest amplitude fails.",
        t.rows
            .first()
            .map_or_else(|| "-".into(), |r| label(r.systematic, 1)),
    ));
    table.note("Systematic amplitude A split as in the paper: split x A on a sinusoid of tip positions, the rest an eccentric axis R tan((1 - split) A); random error as a fraction of the pitch.");
}

/// Rows E. max (random) and E. max (systematic) in units of both gears of each mesh, the
/// systematic amplitude split `split` on the teeth as the cells ran.
fn emax_in_units(t: &DerivedTolerances, split: f64) -> Table {
    presentation::units::derived_tolerances_table(
        "Table 5's E. max in units of each gear: the largest tolerable random error (row E. max (random)) and systematic amplitude on top of it (row E. max (systematic))".to_string(),
        t,
        split,
    )
}

/// Table 5's last row, each mesh's largest tolerable systematic amplitude beside the one the
/// paper's own counts give by the same rule, and the lines of `table5-emax.csv` (after its
/// header, `emax_csv`).
fn systematic_row(t: &DerivedTolerances, rule: f64, mut emax_csv: String) -> (Vec<String>, String) {
    let sys_values = t.systematic_values();
    let mut row = vec!["E. max (systematic)".to_string()];
    for m in &t.meshes {
        let mesh = &m.mesh;
        let ours = if m.random.is_some() {
            show(m.systematic, sys_values.first(), 1)
        } else {
            "-".into()
        };
        let paper = paper_systematic(mesh, &sys_values, rule);
        let paper_text = match paper {
            Some(p) => show(p, sys_values.first(), 1),
            None => "-".into(),
        };
        row.push(format!("{ours} ({paper_text})"));
        emax_csv.push_str(&registry::csv_row!(
            mesh,
            m.random.map_or_else(String::new, |v| v.to_string()),
            paper_random(mesh).map_or_else(String::new, |v| v.to_string()),
            m.systematic.map_or_else(String::new, |v| v.to_string()),
            paper.flatten().map_or_else(String::new, |v| v.to_string()),
        ));
    }
    (row, emax_csv)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    /// Table 5's E. max row at a reduced size: three random values, one systematic value, 20
    /// trials per cell (so 1 % allows no jam and 5 % allows one). Returns the row of the printed table.
    fn emax_row(rule: &str) -> Vec<String> {
        let sets = [
            ("trials", "20"),
            ("rule", rule),
            ("random_from", "0.04"),
            ("random_to", "0.06"),
            ("random_step", "0.01"),
            ("systematic_from", "0.1"),
            ("systematic_to", "0.1"),
        ];
        let report = crate::run("table5", 2025, 2, &sets).unwrap();
        report.tables[0].rows[0].clone()
    }

    #[test]
    fn emax_paper_runs_on_the_papers_own_row() {
        let sets = [
            ("trials", "4"),
            ("emax", "paper"),
            ("systematic_from", "0.1"),
            ("systematic_to", "0.1"),
        ];
        let report = crate::run("table5", 2025, 2, &sets).unwrap();
        let t = &report.tables[0];
        assert!(
            t.title.contains("the paper's own, emax=paper"),
            "{}",
            t.title
        );
        // Every mesh's E. max is the paper's: printed beside itself, never marked.
        for (cell, mesh) in t.rows[0].iter().skip(1).zip(t.columns.iter().skip(1)) {
            let paper = super::paper_random(mesh).unwrap();
            assert_eq!(
                cell,
                &format!("{} ({})", super::label(paper, 3), super::label(paper, 3)),
                "{mesh}"
            );
        }
        // No Table 4 grid was run: only the systematic row's 15 cells of 4 trials.
        assert_eq!(report.trials, 15 * 4);
        // Refused before anything runs, by the parameter's kind.
        let e = crate::run("table5", 2025, 2, &[("emax", "derive")])
            .err()
            .unwrap();
        assert_eq!(e.exit_code(), 2);
        assert!(
            e.to_string()
                .contains("--set: emax: must be one of derived, paper (got `derive`)"),
            "{e}"
        );
    }

    /// `*` means one thing in the table, a count Fisher's test separates from the paper's: the
    /// E. max row, grid values compared with no test, marks a value unlike the paper's `≠`.
    #[test]
    fn the_e_max_row_marks_a_differing_value_apart_from_the_counts_star() {
        let row = emax_row("1");
        assert!(row.iter().any(|c| c.ends_with('≠')), "{row:?}");
        assert!(row.iter().all(|c| !c.contains('*')), "{row:?}");
        let report = crate::run(
            "table5",
            2025,
            2,
            &[
                ("trials", "20"),
                ("random_from", "0.04"),
                ("random_to", "0.06"),
                ("random_step", "0.01"),
                ("systematic_from", "0.1"),
                ("systematic_to", "0.1"),
            ],
        )
        .unwrap();
        let title = &report.tables[0].title;
        assert!(
            title.contains("* where a two-sample test separates our count from the paper's; ≠ where our E. max is not the paper's"),
            "{title}"
        );
    }

    #[test]
    fn a_looser_rule_moves_the_derived_e_max_row() {
        let one = emax_row("1");
        let again = emax_row("1");
        let five = emax_row("5");
        assert_eq!(one, again, "the same rule gives the same row");
        assert_ne!(one, five, "a looser rule must tolerate more somewhere");
        // No value tolerated under the strict rule is lost under the looser one.
        for (a, b) in one.iter().zip(&five).skip(1) {
            let value = |s: &str| s.split(' ').next().unwrap().parse::<f64>().ok();
            if let (Some(x), Some(y)) = (value(a), value(b)) {
                assert!(y >= x, "{a} -> {b}");
            }
        }
    }
}
