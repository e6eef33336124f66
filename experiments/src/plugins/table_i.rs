//! `tableI`: jams / disengagements of each mesh on its own for Edmunds' Cases A-D at clearances of
//! 10, 40 and 70 % (Appendix II), 200 trials per cell. The 40 % rows are Table 3's cells.

use crate::replay::{Cell, CellText};
use registry::{Context, OutputFile, Param, Report, RunError, Table};

use crate::cells::{
    CASE_TRIAL_NOTE, JamCells, case_paper_counts, counts_report, paper_counts, replay_note,
};
use study::cell::{Purpose, label, run_cells};
use study::grids::{CASES, CellSettings, TRIALS, case_cells};

registry::params! {
    /// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70).
    const CLEARANCES = Param::new("clearances", "10,40,70", "clearances G, comma-separated (the paper: 10, 40 and 70)", registry::Kind::Text).unit("% of h");
}

crate::experiment! {
    id: "tableI", paper_item: "Table I (Appendix II)", run,
    title: "Jams and disengagements of each mesh on its own, Cases A-D at G = 10, 40 and 70 %",
    params: [TRIALS, CLEARANCES], groups: [study::gearing::SHAPE, study::errors::CASES_GROUP, study::events::GROUP, study::drive::GROUP],
    replay: "CASE/G/MESH, e.g. B/70/m3-e3" => cell,
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
fn clearances(ctx: &Context) -> Result<Vec<f64>, RunError> {
    crate::settings::clearance_list(ctx, &CLEARANCES, study::gearing::MAX_LISTED_CLEARANCE)
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let s = crate::settings::cells(ctx, &TRIALS)?;
    let gs = clearances(ctx)?;
    let meshes: Vec<String> = s
        .gearing()
        .meshes()
        .iter()
        .map(|m| m.label.clone())
        .collect();
    let grid = run_grid(ctx, &s, &gs, meshes.len())?;
    let mut jam_cells = JamCells::new(&["case", "clearance", "mesh"])
        .off_paper(crate::cells::off_paper_inputs(ctx));
    let mut table = counts_table(&s, &gs, &meshes, &grid, &mut jam_cells);
    table.note(jam_cells.tally.note());
    if let Some(note) = jam_cells.off_paper_note() {
        table.note(note);
    }
    table.note(jam_cells.rule_note());
    table.note(format!(
        "{CASE_TRIAL_NOTE} The 40 % rows are the cells of table3 (same streams, so the same counts)."
    ));
    table.note(replay_note("tableI", "B/70/m3-e3"));
    if let Some(note) = paper_printings_note(&meshes) {
        table.note(note);
    }
    Ok(Report {
        tables: vec![table, jam_cells.rule_table("Table I", "case and G")],
        files: vec![OutputFile::new("tableI-data.csv", jam_cells.csv)],
        agreement: Some(jam_cells.tally.agreement()),
        ..counts_report(grid.counts.iter())
    })
}

/// Table I's counts: every (clearance, case, mesh) cell, run in one call.
struct Grid {
    /// Counts by clearance, then case, then mesh.
    counts: Vec<study::cell::Counts>,
    /// Whether the hypothesis takes the Cases' errors; if not, Case A's cells stand for all.
    cases_apply: bool,
    /// Cases run: four, or one where they would be the same cells.
    cases: usize,
}

/// Runs every cell in one call: Cases by clearance, as case_cells lays them out. A hypothesis
/// the Cases do not reach makes them the same cells: Case A's alone, in one row per clearance.
fn run_grid(ctx: &Context, s: &CellSettings, gs: &[f64], meshes: usize) -> Result<Grid, RunError> {
    let cases_apply = study::grids::cases_apply(s.hypothesis());
    let cases = if cases_apply { CASES.len() } else { 1 };
    let mut cells = Vec::new();
    for &clearance in gs {
        let mut these = case_cells(s, clearance)?;
        these.truncate(cases * meshes);
        cells.extend(these);
    }
    let counts = run_cells(ctx.engine(), s.gearing(), &cells, s.trials, Purpose::Own)?;
    Ok(Grid {
        counts,
        cases_apply,
        cases,
    })
}

/// The table: a row per case and clearance, ours beside the paper's in each mesh's cell.
fn counts_table(
    s: &CellSettings,
    gs: &[f64],
    meshes: &[String],
    grid: &Grid,
    jam_cells: &mut JamCells,
) -> Table {
    let trials = s.trials;
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
        s.hypothesis().name()
    );
    let per_g = grid.cases * meshes.len();
    for (c, &(case, _, _)) in CASES.iter().enumerate().take(grid.cases) {
        let case = if grid.cases_apply {
            case
        } else {
            alike.as_str()
        };
        for (k, &clearance) in gs.iter().enumerate() {
            let gl = label(clearance, 0);
            let first = if k == 0 {
                case.to_string()
            } else {
                String::new()
            };
            let mut row = vec![first, gl.clone()];
            for (m, mesh) in meshes.iter().enumerate() {
                let n = &grid.counts[k * per_g + c * meshes.len() + m];
                let paper =
                    case_paper_counts(grid.cases_apply, "tableI", &format!("{case}.{gl}.{mesh}"));
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
