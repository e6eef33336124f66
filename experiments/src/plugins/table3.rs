//! `table3`: trials with at least one jam / at least one disengagement, each of the 15 meshes on
//! its own, Edmunds' Cases A-D at G = 40 %, 200 trials per cell, with 95 % Wilson intervals.

use crate::replay::{Cell, CellGrammar, CellText};
use registry::{Context, Experiment, OutputFile, Param, Report, RunError, Table};

use study::cell::{Purpose, run_cells};
use crate::cells::{CSV_COLUMNS, Tally, cell_text, csv_columns, paper_counts};
use study::grids::{CASES, CellSettings, TRIALS, case_cells, cases_apply};

const PARAMS: &[Param] = &[TRIALS];

registry::inventory::submit! {
    Experiment {
        id: "table3",
        title: "Jams and disengagements of each mesh on its own, Cases A-D at G = 40 %, 200 trials per cell",
        paper_item: "Table 3 (section 5)",
        params: PARAMS,
        groups: &[study::gearing::GROUP, study::errors::CASES_GROUP, study::events::GROUP],
        config: None,
        run,
    }
}

registry::inventory::submit! {
    CellGrammar {
        experiment: "table3",
        form: "CASE/MESH, e.g. B/m3-e3",
        parse: cell,
    }
}

/// A cell of Table 3 for `cargo xtask replay`: `CASE/MESH`, at the experiment's G and split.
fn cell<'a>(s: &CellSettings, c: &CellText<'a>) -> Result<Cell<'a>, RunError> {
    let &[case, mesh] = c.parts() else {
        return Err(c.malformed());
    };
    let (systematic, random) = c.case(case)?;
    let split = s.errors.split()?;
    Ok(Cell {
        mesh,
        errors: vec![
            ("random", random),
            ("systematic", systematic),
            ("split", split),
        ],
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
    let mut cells = case_cells(&s, clearance)?;
    // A hypothesis that takes neither a random nor a systematic error (ideal, measured, a
    // shape-only one) makes the four Cases the same cells: one row, compared with no Case.
    let cases_apply = cases_apply(hyp);
    if !cases_apply {
        cells.truncate(meshes.len());
    }
    let counts = run_cells(ctx.engine(), g, &cells, trials, Purpose::Own)?;

    let mut ours = Table::new(
        format!(
            "Table 3: trials (of {trials}) with at least one jam / disengagement, G = {clearance} %: ours (paper); * where a two-sample test separates our count from the paper's"
        ),
        ours_header(&meshes),
    );
    let mut csv = format!("case,mesh,{CSV_COLUMNS}\n");
    let mut tally = Tally::default();
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
            let paper = if cases_apply {
                paper_counts("table3", &format!("{case}.{mesh}"))
            } else {
                (None, None)
            };
            row.push(cell_text(n, paper, &mut tally));
            csv.push_str(&format!("{case},{mesh},{}\n", csv_columns(n, paper)));
        }
        ours.row(row);
    }
    ours.note(tally.note());
    ours.note("Each trial: both gears manufactured afresh (hypothesis and Case), a random initial angle, one full turn of the gear with more teeth.");
    ours.note("See a failed trial: `cargo xtask replay table3 B/m3-e3` lists the trials of that cell that jammed or disengaged; `cargo xtask replay table3 B/m3-e3 TRIAL` rebuilds one from its random stream, prints its events and writes a pair file to rerun it (same --seed and --set as this run).");
    Ok(Report {
        tables: vec![ours, intervals],
        files: vec![OutputFile::new("table3-data.csv", csv)],
        trials: counts.iter().map(|c| c.trials).sum(),
        engagements: counts.iter().map(|c| c.engagements).sum(),
        agreement: Some(tally.agreement()),
        ..Default::default()
    })
}
