//! `tableI`: jams / disengagements of each mesh on its own for Edmunds' Cases A-D at clearances of
//! 10, 40 and 70 % (Appendix II), 200 trials per cell. The 40 % rows are Table 3's cells.

use registry::{OutputFile, Place, Report, Run, RunError, Table};
use replay::{Cell, CellText};
use serde::{Deserialize, Serialize};

use presentation::cells::{
    CASE_TRIAL_NOTE, JamCells, case_paper_counts, counts_report, paper_counts, replay_note,
};
use setting_groups::typed::{Gearing, cells, label, off_paper_inputs};
use study::cell::{Purpose, run_cells};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::{MAX_LISTED_CLEARANCE, ShapeParams, TABLE_I_CLEARANCES as CLEARANCES};
use study::grids::{CASES, CellSettings, TRIALS, case_cells, cases_apply};
use study::results::{CaseClearanceTable, JamTable};

/// Table I's settings: trials per cell, the clearances, the gearing with h, the Cases' errors,
/// the event rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// The clearances G, % of h, comma-separated ([`CLEARANCES`]).
    #[param(CLEARANCES)]
    pub clearances: String,
    /// The gearing and h.
    #[group]
    pub shape: ShapeParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// Table I.
pub struct TableI;

impl registry::Experiment for TableI {
    const ID: &'static str = "tableI";
    const TITLE: &'static str =
        "Jams and disengagements of each mesh on its own, Cases A-D at G = 10, 40 and 70 %";
    const PAPER_ITEM: &'static str = "Table I (Appendix II)";
    const PLACE: Place = Place::Paper(170);
    type Settings = Settings;
    type Results = CaseClearanceTable;

    fn compute(s: &Settings, run: &Run) -> Result<CaseClearanceTable, RunError> {
        let cs = cell_settings(s)?;
        let gs = clearances(s)?;
        let meshes = cs.meshes();
        let apply = cases_apply(cs.hypothesis());
        let cases = if apply { CASES.len() } else { 1 };
        let counts = run_grid(run, &cs, &gs, cases * meshes.len())?;
        let (rows, cells) = case_by_case(&counts, &gs, apply, meshes.len());
        Ok(CaseClearanceTable {
            clearances: gs,
            cases_apply: apply,
            hypothesis: cs.hypothesis().name().to_owned(),
            table: JamTable::from_counts(meshes, rows, &cells),
        })
    }

    fn report(s: &Settings, r: &CaseClearanceTable) -> Result<Report, RunError> {
        let mut jam_cells =
            JamCells::new(&["case", "clearance", "mesh"]).off_paper(off_paper_inputs(s));
        let mut table = counts_table(s.trials, r, &mut jam_cells);
        table.note(jam_cells.tally.note());
        if let Some(note) = jam_cells.off_paper_note() {
            table.note(note);
        }
        table.note(jam_cells.rule_note());
        table.note(format!(
            "{CASE_TRIAL_NOTE} The 40 % rows are the cells of table3 (same streams, so the same counts)."
        ));
        table.note(replay_note("tableI", "B/70/m3-e3"));
        if let Some(note) = paper_printings_note(&r.table.meshes) {
            table.note(note);
        }
        let report = Report {
            tables: vec![table, jam_cells.rule_table("Table I", "case and G")],
            files: vec![OutputFile::new("tableI-data.csv", jam_cells.csv)],
            agreement: Some(jam_cells.tally.agreement()),
            ..counts_report(r.table.counts())
        };
        label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(TableI);

crate::replay_cells! { "tableI", "CASE/G/MESH, e.g. B/70/m3-e3" => cell }

/// The cells' settings read from Table I's.
fn cell_settings(s: &Settings) -> Result<CellSettings, RunError> {
    cells(
        Gearing::Shape(&s.shape),
        &s.errors,
        Some(&s.events),
        Some(&s.drive),
        s.trials,
        s,
    )
}

/// A cell of Table I for `cargo xtask replay`: `CASE/G/MESH`, at the experiment's split.
fn cell<'a>(s: &CellSettings, c: &CellText<'a>) -> Result<Cell<'a>, RunError> {
    let &[case, g, mesh] = c.parts() else {
        return Err(c.malformed());
    };
    Ok(Cell {
        mesh,
        errors: c.case_errors(s, case)?,
        clearance: c.clearance(g)?,
        typed: Vec::new(),
    })
}

/// The `clearances` parameter: a comma-separated list of clearances, each in (0, 200] % of h.
fn clearances(s: &Settings) -> Result<Vec<f64>, RunError> {
    study::gearing::clearance_list(&s.clearances, CLEARANCES.name, MAX_LISTED_CLEARANCE)
}

/// Every cell in one call, clearance by clearance, each clearance's first `per_g` cells of
/// case_cells' layout (Cases by meshes): a hypothesis the Cases do not reach makes them the
/// same cells, and Case A's alone are run.
fn run_grid(
    run: &Run,
    s: &CellSettings,
    gs: &[f64],
    per_g: usize,
) -> Result<Vec<study::cell::Counts>, RunError> {
    let mut cells = Vec::new();
    for &clearance in gs {
        let mut these = case_cells(s, clearance)?;
        these.truncate(per_g);
        cells.extend(these);
    }
    run_cells(run.engine(), s.gearing(), &cells, s.trials, Purpose::Own)
}

/// The cells run clearance by clearance (`counts`, as [`run_grid`] ran them), laid out Case by
/// Case, each Case's clearances in order: the rows' labels (`B/70`; `A-D/70` where the Cases do
/// not `apply`) and their cells, row by row.
fn case_by_case(
    counts: &[study::cell::Counts],
    gs: &[f64],
    apply: bool,
    meshes: usize,
) -> (Vec<String>, Vec<study::cell::Counts>) {
    let cases = if apply { CASES.len() } else { 1 };
    let mut rows = Vec::new();
    let mut cells = Vec::new();
    for (c, &(case, _, _)) in CASES.iter().enumerate().take(cases) {
        let case = if apply { case } else { "A-D" };
        for (k, &g) in gs.iter().enumerate() {
            rows.push(format!("{case}/{}", study::cell::label(g, 0)));
            let at = (k * cases + c) * meshes;
            cells.extend_from_slice(&counts[at..at + meshes]);
        }
    }
    (rows, cells)
}

/// The table: a row per case and clearance, ours beside the paper's in each mesh's cell.
fn counts_table(trials: u64, r: &CaseClearanceTable, jam_cells: &mut JamCells) -> Table {
    let meshes = &r.table.meshes;
    let mut header = vec!["case".to_string(), "G [%]".to_string()];
    header.extend(meshes.iter().cloned());
    let mut table = Table::new(
        format!(
            "Table I: trials (of {trials}) with at least one jam / disengagement, Cases A-D at several clearances: ours (paper); * where a two-sample test separates our count from the paper's; ✓ where a cell keeps the paper's 1 % rule"
        ),
        header,
    );
    let alike = format!(
        "Cases A-D alike ({} takes no random or systematic error)",
        r.hypothesis
    );
    let cases = if r.cases_apply { CASES.len() } else { 1 };
    for (c, &(case, _, _)) in CASES.iter().enumerate().take(cases) {
        let case = if r.cases_apply { case } else { alike.as_str() };
        for (k, &clearance) in r.clearances.iter().enumerate() {
            let gl = study::cell::label(clearance, 0);
            let first = if k == 0 {
                case.to_string()
            } else {
                String::new()
            };
            let mut row = vec![first, gl.clone()];
            let cells = r.row(c, k).map_or(&[][..], |row| &row.cells);
            for (mesh, n) in meshes.iter().zip(cells) {
                let paper =
                    case_paper_counts(r.cases_apply, "tableI", &format!("{case}.{gl}.{mesh}"));
                row.push(jam_cells.cell(
                    (&format!("{case}, G = {gl} %"), mesh),
                    &[case, gl.as_str(), mesh],
                    n,
                    paper,
                ));
            }
            table.row(row);
        }
    }
    table
}

/// The paper's own two printings of the 40 % cells (Table I's and Table 3's), compared: a note
/// naming the cells where they differ, if any.
fn paper_printings_note(meshes: &[String]) -> Option<String> {
    let mut differ = Vec::new();
    for &(case, _, _) in &CASES {
        for mesh in meshes {
            let a = paper_counts("tableI", &format!("{case}.40.{mesh}"));
            let b = paper_counts("table3", &format!("{case}.{mesh}"));
            if a.0.is_some() && b.0.is_some() && a != b {
                differ.push(format!("{case} {mesh}"));
            }
        }
    }
    (!differ.is_empty()).then(|| {
        format!(
            "The paper says its 40 % rows are those of Table 3, but {} of its cells differ from Table 3 ({}); we compare with Table I as printed.",
            differ.len(),
            differ.join(", ")
        )
    })
}
