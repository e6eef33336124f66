//! `table3`: trials with at least one jam / at least one disengagement, each of the 15 meshes on
//! its own, Edmunds' Cases A-D at G = 40 %, 200 trials per cell, with 95 % Wilson intervals.

use registry::{OutputFile, Place, Report, Run, RunError, Table};
use replay::{Cell, CellText};
use serde::{Deserialize, Serialize};

use presentation::cells::{
    CASE_TRIAL_NOTE, JamCells, case_paper_counts, counts_report, replay_note,
};
use setting_groups::typed::{Gearing, cells, label, off_paper_inputs};
use study::cell::{Purpose, run_cells};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::grids::{CASES, CellSettings, TRIALS, case_cells, cases_apply};
use study::results::{CaseTable as Results, JamTable};

/// Table 3's settings: trials per cell, the gearing with h and G, the Cases' errors, the event
/// rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
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

/// Table 3.
pub struct Table3;

impl registry::Experiment for Table3 {
    const ID: &'static str = "table3";
    const TITLE: &'static str = "Jams and disengagements of each mesh on its own, Cases A-D at G = 40 %, 200 trials per cell";
    const PAPER_ITEM: &'static str = "Table 3 (section 5)";
    const PLACE: Place = Place::Paper(80);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        let cs = cell_settings(s)?;
        let (g, hyp, clearance) = (cs.gearing(), cs.hypothesis(), cs.clearance()?);
        let meshes = cs.meshes();
        let mut specs = case_cells(&cs, clearance)?;
        // A hypothesis that takes neither a random nor a systematic error (ideal, measured, a
        // shape-only one) makes the four Cases the same cells: one row, compared with no Case.
        let cases_apply = cases_apply(hyp);
        if !cases_apply {
            specs.truncate(meshes.len());
        }
        let counts = run_cells(run.engine(), g, &specs, s.trials, Purpose::Own)?;
        let rows: Vec<String> = if cases_apply {
            CASES.iter().map(|c| c.0.to_string()).collect()
        } else {
            vec![format!(
                "Cases A-D alike ({} takes no random or systematic error)",
                hyp.name()
            )]
        };
        Ok(Results {
            table: JamTable::from_counts(meshes, rows, &counts),
            cases_apply,
            hypothesis: hyp.name().to_owned(),
            clearance,
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let mut ours = Table::new(
            format!(
                "Table 3: trials (of {}) with at least one jam / disengagement, G = {} %: ours (paper); * where a two-sample test separates our count from the paper's; ✓ where a cell keeps the paper's 1 % rule",
                s.trials, r.clearance
            ),
            ours_header(&r.table.meshes),
        );
        let mut cells = JamCells::new(&["case", "mesh"]).off_paper(off_paper_inputs(s));
        for row in &r.table.rows {
            let case = &row.label;
            let mut line = vec![case.clone()];
            for (mesh, n) in r.table.meshes.iter().zip(&row.cells) {
                let paper = case_paper_counts(r.cases_apply, "table3", &format!("{case}.{mesh}"));
                line.push(cells.cell((case, mesh), &[case, mesh], n, paper));
            }
            ours.row(line);
        }
        ours.note(cells.tally.note());
        if let Some(note) = cells.off_paper_note() {
            ours.note(note);
        }
        ours.note(cells.rule_note());
        ours.note(CASE_TRIAL_NOTE);
        ours.note(replay_note("table3", "B/m3-e3"));
        let report = Report {
            tables: vec![
                ours,
                cells.rule_table("Table 3", "case"),
                intervals_table(s, r),
            ],
            files: vec![OutputFile::new("table3-data.csv", cells.csv)],
            agreement: Some(cells.tally.agreement()),
            ..counts_report(r.table.counts())
        };
        label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(Table3);

crate::replay_cells! { "table3", "CASE/MESH, e.g. B/m3-e3" => cell }

/// The cells' settings read from Table 3's.
fn cell_settings(s: &Settings) -> Result<CellSettings, RunError> {
    cells(
        Gearing::WithClearance(&s.gearing),
        &s.errors,
        Some(&s.events),
        Some(&s.drive),
        s.trials,
        s,
    )
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
fn ours_header(meshes: &[String]) -> Vec<String> {
    let mut header = vec!["case".to_string()];
    header.extend(meshes.iter().cloned());
    header
}

/// Our counts with their 95 % Wilson intervals, as counts of trials.
fn intervals_table(s: &Settings, r: &Results) -> Table {
    let mut intervals = Table::new(
        format!(
            "Table 3, ours with 95 % Wilson intervals: jams [interval] / disengagements [interval], counts of {} trials, G = {} %",
            s.trials, r.clearance
        ),
        ours_header(&r.table.meshes),
    );
    for row in &r.table.rows {
        let mut with_intervals = vec![row.label.clone()];
        for n in &row.cells {
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
    intervals
}
