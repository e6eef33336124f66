//! `table5`: each mesh's largest tolerable random error, derived from Table 4's results by the
//! paper's 1 % rule, then jams / disengagements with systematic errors of 0.1 to 1.1° (split
//! 50/50) on top of it, 200 trials per cell.

use registry::{Place, Report, Run, RunError};
use replay::{Cell, CellText};
use serde::{Deserialize, Serialize};

use presentation::reports::table5::{self, Ran};
use setting_groups::emax::{EMAX, given_row, random_from};
use setting_groups::typed::{Gearing, cells, off_paper_inputs};
use study::cell::Purpose;
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
        let ran = Ran {
            trials: s.trials,
            rule: s.rule,
            clearance: s.gearing.clearance,
            split: s.errors.split,
            given: random_from(&s.emax) == RandomFrom::Paper,
            off_paper: off_paper_inputs(s),
        };
        setting_groups::typed::label(&s.events, Some(&s.drive), table5::report(t, ran))
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
            let paper = presentation::emax::paper_random(mesh).unwrap();
            assert_eq!(
                cell,
                &format!(
                    "{} ({})",
                    study::cell::label(paper, 3),
                    study::cell::label(paper, 3)
                ),
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
