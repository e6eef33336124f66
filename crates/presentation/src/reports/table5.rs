//! What `table5` shows: each mesh's largest tolerable random error beside the paper's E. max
//! row, the counts against the systematic error beside the paper's (compared where the mesh ran
//! on the paper's inputs), the largest tolerable systematic error, and E. max in units of each
//! gear.

use registry::{OutputFile, Report, Table};
use study::cell::label;
use study::results::DerivedTolerances;
use study::tolerance;

use crate::cells::{JamCells, counts_report, paper_counts};
use crate::emax::{paper_random, paper_systematic, show};

/// How Table 5 was run, as its title and notes say it.
#[derive(Debug, Clone)]
pub struct Ran {
    /// Trials per cell.
    pub trials: u64,
    /// The tolerance rule, % of trials jamming.
    pub rule: f64,
    /// The clearance G, % of h.
    pub clearance: f64,
    /// The share of the systematic error on the sinusoid.
    pub split: f64,
    /// Whether the E. max row is the paper's own (`emax=paper`).
    pub given: bool,
    /// The inputs that depart from the paper's (`name=value`); none: cells are compared.
    pub off_paper: Vec<String>,
}

/// Table 5 from the derived tolerances `t`, run as `ran`: the table beside the paper's, its
/// rule table, E. max in units of each gear, and the CSVs.
pub fn report(t: &DerivedTolerances, ran: Ran) -> Report {
    let like_for_like = like_for_like(t);
    let mut table = Table::new(
        title(&ran, &like_for_like),
        std::iter::once("E. sys [deg]".to_string())
            .chain(t.random_grid.table.meshes.iter().cloned()),
    );
    let (row, same) = random_row(t);
    table.row(row);
    let mut jam_cells = JamCells::new(&["systematic", "mesh", "random"])
        .with_rule(ran.rule)
        .off_paper(ran.off_paper.clone());
    for row in count_rows(t, &like_for_like, &mut jam_cells) {
        table.row(row);
    }
    let emax_csv = String::from(
        "mesh,random_emax,paper_random_emax,systematic_emax_deg,paper_systematic_emax_deg_by_rule\n",
    );
    let (row, emax_csv) = systematic_row(t, ran.rule, emax_csv);
    table.row(row);
    table.note(jam_cells.tally.note());
    if let Some(note) = jam_cells.off_paper_note() {
        table.note(note);
    }
    table.note(jam_cells.rule_note());
    add_notes(
        &mut table,
        t,
        (ran.rule, ran.trials),
        ran.given,
        (&like_for_like, same),
    );
    Report {
        tables: vec![
            table,
            jam_cells.rule_table("Table 5", "E. sys [deg]"),
            emax_in_units(t, ran.split),
        ],
        files: vec![
            OutputFile::new("table5-data.csv", jam_cells.csv),
            OutputFile::new("table5-emax.csv", emax_csv),
        ],
        agreement: Some(jam_cells.tally.agreement()),
        ..counts_report(t.all())
    }
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
fn title(ran: &Ran, like_for_like: &[bool]) -> String {
    let (trials, clearance, split, rule, given) =
        (ran.trials, ran.clearance, ran.split, ran.rule, ran.given);
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
    crate::units::derived_tolerances_table(
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
