//! `table3`: trials with at least one jam / at least one disengagement, each of the 15 meshes on
//! its own, Edmunds' Cases A-D at G = 40 %, 200 trials per cell, with 95 % Wilson intervals.

use crate::replay::{Cell, CellText};
use registry::{Context, OutputFile, Report, RunError, Table};

use crate::cells::{CASE_TRIAL_NOTE, JamCells, case_paper_counts, counts_report, replay_note};
use study::cell::{Purpose, run_cells};
use study::grids::{CASES, CellSettings, TRIALS, case_cells, cases_apply};

crate::experiment! {
    id: "table3", paper_item: "Table 3 (section 5)", run,
    title: "Jams and disengagements of each mesh on its own, Cases A-D at G = 40 %, 200 trials per cell",
    params: [TRIALS], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::events::GROUP, study::drive::GROUP],
    replay: "CASE/MESH, e.g. B/m3-e3" => cell,
}

/// A cell of Table 3 for `cargo xtask replay`: `CASE/MESH`, at the experiment's G and split.
fn cell<'a>(s: &CellSettings, c: &CellText<'a>) -> Result<Cell<'a>, RunError> {
    let &[case, mesh] = c.parts() else {
        return Err(c.malformed());
    };
    Ok(Cell {
        mesh,
        errors: c.case_errors(s, case)?,
        clearance: s.clearance()?,
        typed: Vec::new(),
    })
}

/// `case` and the meshes: the columns of both tables.
fn ours_header(meshes: &[&str]) -> Vec<String> {
    let mut header = vec!["case".to_string()];
    header.extend(meshes.iter().map(|m| (*m).to_string()));
    header
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let s = crate::settings::cells(ctx, &TRIALS)?;
    let (g, hyp, trials, clearance) = (s.gearing(), s.hypothesis(), s.trials, s.clearance()?);
    let meshes: Vec<&str> = g.meshes().iter().map(|m| m.label.as_str()).collect();
    let mut specs = case_cells(&s, clearance)?;
    // A hypothesis that takes neither a random nor a systematic error (ideal, measured, a
    // shape-only one) makes the four Cases the same cells: one row, compared with no Case.
    let cases_apply = cases_apply(hyp);
    if !cases_apply {
        specs.truncate(meshes.len());
    }
    let counts = run_cells(ctx.engine(), g, &specs, trials, Purpose::Own)?;

    let mut ours = Table::new(
        format!(
            "Table 3: trials (of {trials}) with at least one jam / disengagement, G = {clearance} %: ours (paper); * where a two-sample test separates our count from the paper's; ✓ where a cell keeps the paper's 1 % rule"
        ),
        ours_header(&meshes),
    );
    let mut cells = JamCells::new(&["case", "mesh"]).off_paper(crate::cells::off_paper_inputs(ctx));
    let rows: Vec<String> = if cases_apply {
        CASES.iter().map(|c| c.0.to_string()).collect()
    } else {
        vec![format!(
            "Cases A-D alike ({} takes no random or systematic error)",
            hyp.name()
        )]
    };
    // The printed intervals: our counts with their 95 % Wilson intervals, as counts of trials.
    let mut intervals = Table::new(
        format!(
            "Table 3, ours with 95 % Wilson intervals: jams [interval] / disengagements [interval], counts of {trials} trials, G = {clearance} %"
        ),
        ours_header(&meshes),
    );
    for (c, case) in rows.iter().enumerate() {
        let mut with_intervals = vec![case.clone()];
        for m in 0..meshes.len() {
            let n = &counts[c * meshes.len() + m];
            let (j, d) = (n.jam_interval(), n.dis_interval());
            let t = n.trials as f64;
            with_intervals.push(format!(
                "{} [{:.1} .. {:.1}] / {} [{:.1} .. {:.1}]",
                n.jams,
                j.lo * t,
                j.hi * t,
                n.disengagements,
                d.lo * t,
                d.hi * t
            ));
        }
        intervals.row(with_intervals);
    }
    intervals.note("Wilson score intervals at 95 % of each count, in trials; table3-data.csv has the same as jam_lo, jam_hi, dis_lo and dis_hi. The `*` of the table above comes from Fisher's exact two-sample test against the paper's count, not from these intervals (the paper's counts are samples too).");
    for (c, case) in rows.iter().enumerate() {
        let mut row = vec![case.clone()];
        for (m, mesh) in meshes.iter().enumerate() {
            let n = &counts[c * meshes.len() + m];
            let paper = case_paper_counts(cases_apply, "table3", &format!("{case}.{mesh}"));
            row.push(cells.cell((case, mesh), &[case, mesh], n, paper));
        }
        ours.row(row);
    }
    ours.note(cells.tally.note());
    if let Some(note) = cells.off_paper_note() {
        ours.note(note);
    }
    ours.note(cells.rule_note());
    ours.note(CASE_TRIAL_NOTE);
    ours.note(replay_note("table3", "B/m3-e3"));
    Ok(Report {
        tables: vec![ours, cells.rule_table("Table 3", "case"), intervals],
        files: vec![OutputFile::new("table3-data.csv", cells.csv)],
        agreement: Some(cells.tally.agreement()),
        ..counts_report(counts.iter())
    })
}
