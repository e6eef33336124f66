//! `table4`: trials with at least one jam / disengagement of each mesh on its own, random tooth
//! error from 0.035 to 0.065 of the pitch, no systematic error, G = 40 %, 200 trials per cell.

use crate::replay::{Cell, CellGrammar, CellText};
use registry::{Context, Experiment, OutputFile, Param, Report, RunError, Table};

use study::cell::{Purpose, label};
use crate::cells::{CSV_COLUMNS, Tally, cell_text, csv_columns, paper_counts};
use study::grids::{CellSettings, TRIALS, run_grid};

const PARAMS: &[Param] = &[TRIALS];

registry::inventory::submit! {
    Experiment {
        id: "table4",
        title: "Jams and disengagements of each mesh on its own against the random tooth error, no systematic error, G = 40 %",
        paper_item: "Table 4 (section 5)",
        params: PARAMS,
        groups: &[study::gearing::GROUP, study::errors::GROUP, study::tolerance::RANDOM_GRID, study::events::GROUP],
        config: None,
        run,
    }
}

registry::inventory::submit! {
    CellGrammar {
        experiment: "table4",
        form: "RANDOM/MESH, e.g. 0.050/m3-e3",
        parse: cell,
    }
}

/// A cell of Table 4 for `cargo xtask replay`: `RANDOM/MESH` (a random error of its grid, no
/// systematic error), at the experiment's G.
fn cell<'a>(s: &CellSettings, c: &CellText<'a>) -> Result<Cell<'a>, RunError> {
    let &[random, mesh] = c.parts() else {
        return Err(c.malformed());
    };
    let value = c.number("random error", &study::tolerance::RANDOM_FROM.kind, random)?;
    Ok(Cell {
        mesh,
        errors: vec![("random", value), ("systematic", 0.0)],
        clearance: s.clearance()?,
        typed: vec![("random", "random error", random)],
    })
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let s = crate::settings::cells(ctx, &TRIALS)?;
    let (trials, clearance) = (s.trials, s.clearance()?);
    let grid = run_grid(ctx.engine(), &s, crate::settings::random_grid(ctx)?, trials, Purpose::Own)?;

    let mut header = vec!["random error".to_string()];
    header.extend(grid.meshes.iter().cloned());
    let mut table = Table::new(
        format!(
            "Table 4: trials (of {trials}) with at least one jam / disengagement, random error only, G = {clearance} %: ours (paper); * where a two-sample test separates our count from the paper's"
        ),
        header,
    );
    let mut csv = format!("random,mesh,{CSV_COLUMNS}\n");
    let mut tally = Tally::default();
    for (e, row) in grid.values.iter().zip(&grid.counts) {
        let key = label(*e, 3);
        let mut cells = vec![key.clone()];
        for (mesh, c) in grid.meshes.iter().zip(row) {
            let paper = paper_counts("table4", &format!("{key}.{mesh}"));
            cells.push(cell_text(c, paper, &mut tally));
            csv.push_str(&format!("{key},{mesh},{}\n", csv_columns(c, paper)));
        }
        table.row(cells);
    }
    table.note(tally.note());
    table.note("Random error: sd of each tip's displacement as a fraction of the pitch 360/N (Edmunds' tooth error; Case A's 0.04). No systematic error. Each trial: both gears manufactured afresh, a random initial angle, one full turn of the gear with more teeth.");
    table.note("See a failed trial: `cargo xtask replay table4 0.065/m3-e3` lists the trials of that cell that jammed or disengaged; `cargo xtask replay table4 0.065/m3-e3 TRIAL` rebuilds one from its random stream, prints its events and writes a pair file to rerun it (same --seed and --set as this run).");
    table.note("The paper's text says the error went from 0.04 to 0.65 by 0.005; its table shows 0.035 to 0.065, which is what we run.");
    Ok(Report {
        tables: vec![table],
        files: vec![OutputFile::new("table4-data.csv", csv)],
        trials: grid.all().map(|c| c.trials).sum(),
        engagements: grid.all().map(|c| c.engagements).sum(),
        agreement: Some(tally.agreement()),
        ..Default::default()
    })
}
