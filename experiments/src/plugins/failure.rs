//! `failure`: the paper's 30-run study (section 5, after Figure 6): whole mechanisms with
//! manufacturing errors at G = 40 %, each run until its trains jam; per train the day of the
//! first jam, the share of runs jamming within a year, and survival curves.
//!
//! One run is one mechanism: every gear manufactured once (a gear in two meshes carries the same
//! errors in both), every one of the gearing's meshes given one random initial angle, and every
//! mesh simulated once over the horizon, up to its first jam. Trains that share meshes (b2-l1 and
//! l2-m1 are in both the Metonic/Games and the Saros/Exeligmos trains) share their motion.
//!
//! `Report::engagements` counts, for every mesh simulated in every run, the driver's turns over
//! the simulated stretch (to the horizon or the mesh's first jam) times its teeth: the teeth that
//! passed through the mesh.

use hypotheses::{MeasuredHypothesis, Params};
use registry::{Param, Place, Report, Run, RunError};
use serde::{Deserialize, Serialize};

use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::{self, GearingParams};
use study::results::{FailureInput, FailureStudy};
use study::whole_mechanism::{
    CASES_PARAM, Clearances, DAYS, Input, MEASURED_INDEX, RUNS_DEFAULT, batch_key, case_input,
    check_study, measured_table, parse_cases, run_study,
};

use presentation::reports::failure;
use setting_groups::typed::label;

registry::params! {
    /// `trials`: whole-mechanism runs per input (the paper: 30).
    const TRIALS = Param::new("trials", RUNS_DEFAULT, "whole-mechanism runs per input (the paper: 30)", registry::Kind::count(1, registry::MAX_TRIALS, "")).recorded();
    /// `measured`: per-gear error table (RON, as crates/hypotheses/data/measured-example.ron), run with the measured hypothesis; empty: not run.
    const MEASURED = Param::new("measured", "", "per-gear error table (RON, as crates/hypotheses/data/measured-example.ron), run with the measured hypothesis; empty: not run", registry::Kind::Text).recorded();
}

/// The failure study's settings: runs per input, the horizon, the Cases and the measured table
/// to run, the pin-and-slot, the gearing with h and G, the Cases' errors and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Whole-mechanism runs per input ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// Horizon of each run, days of b ([`DAYS`]).
    #[param(DAYS)]
    pub days: f64,
    /// Edmunds' Cases to run, comma-separated ([`CASES_PARAM`]).
    #[param(CASES_PARAM)]
    pub cases: String,
    /// A per-gear error table to run with the measured hypothesis; empty: none ([`MEASURED`]).
    #[param(MEASURED)]
    pub measured: String,
    /// Whether the Lunar train includes the pin-and-slot ([`gearing::PIN_AND_SLOT`]).
    #[param(gearing::PIN_AND_SLOT)]
    pub pin_and_slot: bool,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// The failure study.
pub struct Failure;

impl registry::Experiment for Failure {
    const ID: &'static str = "failure";
    const TITLE: &'static str =
        "Days to the first jam of each train, whole mechanisms with Edmunds' errors at G = 40 %";
    const PAPER_ITEM: &'static str = "Section 5, the 30-run study";
    const PLACE: Place = Place::Paper(130);
    type Settings = Settings;
    type Results = FailureStudy;

    fn compute(s: &Settings, run: &Run) -> Result<FailureStudy, RunError> {
        let settings = s.gearing.load()?;
        // Read here, before the gearing's checks, with the split each case takes.
        let errors = s.errors.load(s)?;
        let rule = s.events.rule()?;
        let (g, h, clearance) = (&settings.gearing, settings.tooth_height, settings.clearance);
        check_study(g, h, &Clearances::Uniform(clearance))?;
        // A pin-and-slot asked of a gearing without one is refused before anything runs.
        let ideal = study::pointers::ideal_mechanism(&settings, &rule)?;
        gearing::with_pin_and_slot(&settings.file, ideal, s.pin_and_slot)?;

        let measured = measured_table(&s.measured)?;
        let inputs = study_inputs(s, &errors, measured.as_ref(), clearance)?;
        let (trials, days) = (s.trials, s.days);
        let outcomes = run_study(
            run.engine(),
            g,
            &inputs,
            trials,
            h,
            days,
            &rule,
            &batch_key(&settings.file, &inputs, trials, h, clearance, days)?,
        )?;
        Ok(FailureStudy {
            horizon: days,
            runs_per_input: trials,
            inputs: inputs
                .iter()
                .zip(outcomes.chunks(trials as usize))
                .map(|(inp, runs)| FailureInput::new(inp, inp.index == MEASURED_INDEX, runs, days))
                .collect(),
        })
    }

    fn report(s: &Settings, r: &FailureStudy) -> Result<Report, RunError> {
        let report = failure::report(r, s.gearing.clearance, s.pin_and_slot)?;
        label(&s.events, None, report)
    }
}

registry::register!(Failure);

/// The inputs of the study: the cases asked for, then the measured table if one is given, each
/// with the pin-and-slot as asked; refused when there is nothing to run.
fn study_inputs<'a>(
    s: &Settings,
    errors: &'a study::errors::Settings,
    measured: Option<&'a (String, MeasuredHypothesis)>,
    clearance: f64,
) -> Result<Vec<Input<'a>>, RunError> {
    let mut inputs: Vec<Input<'_>> = Vec::new();
    for ci in parse_cases(&s.cases)? {
        inputs.push(case_input(errors, ci, Clearances::Uniform(clearance))?);
    }
    if let Some((file, m)) = measured {
        inputs.push(Input {
            label: "measured".into(),
            legend: format!("measured table {file}"),
            index: MEASURED_INDEX,
            source: "--set measured",
            hypothesis: m,
            params: Params::new(m, &[])
                .map_err(|e| RunError::bad("--set measured", e.what, e.rule))?,
            clearances: Clearances::Uniform(clearance),
            pin_and_slot: false,
            extra: None,
        });
    }
    for inp in &mut inputs {
        inp.pin_and_slot = s.pin_and_slot;
    }
    if inputs.is_empty() {
        return Err(RunError::bad(
            "--set",
            "cases",
            "no case and no measured table: nothing to run",
        ));
    }

    Ok(inputs)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn cases_parse_and_refuse_unknown_names() {
        assert_eq!(parse_cases("A, c,D").unwrap(), [0, 2, 3]);
        assert!(parse_cases("").unwrap().is_empty());
        // A Case named twice (whatever its case) is refused, as every list refuses a repeat.
        let e = parse_cases("A, c,D,a").unwrap_err();
        assert!(e.to_string().contains("names the case `a` twice"), "{e}");
        let e = parse_cases("A,E").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("`E`"), "{e}");
    }

    fn run_with(threads: usize, sets: &[(&str, &str)]) -> Result<Report, RunError> {
        crate::run("failure", 11, threads, sets)
    }

    #[test]
    fn bad_parameters_are_refused_as_bad_input() {
        for sets in [
            &[("days", "100")][..],
            &[("trials", "0")],
            &[("cases", "X")],
            &[("cases", "")],
            &[("measured", "/no/such/file.ron")],
        ] {
            let e = run_with(1, sets).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{sets:?}: {e}");
        }
    }

    #[test]
    fn case_d_is_identical_with_one_and_two_threads() {
        // Case D jams early in almost every run, so this is quick.
        let sets = [("cases", "D"), ("trials", "3")];
        let one = run_with(1, &sets).unwrap();
        let two = run_with(2, &sets).unwrap();
        assert_eq!(one, two);
        assert_eq!(one.trials, 3);
        assert!(one.engagements > 0);
        assert_eq!(
            one.agreement, None,
            "cases are not judged against the paper"
        );
        // The stored results hold every run's first jam of each train and of the mechanism.
        let data = crate::outcome("failure", 11, 1, &sets).unwrap().data;
        let study: FailureStudy = serde_json::from_value(data["results"].clone()).unwrap();
        assert_eq!(study.inputs.len(), 1);
        assert_eq!(study.inputs[0].runs.len(), 3);
        assert!(study.inputs[0].runs.iter().all(|o| o.first_jams.len() == 4));
        assert_eq!(study.inputs[0].trains[3].within_year.n, 3);
        let csv = &one.files[0];
        assert_eq!(csv.name, "failure-runs.csv");
        // 3 runs x (3 trains + mechanism) + header.
        assert_eq!(String::from_utf8_lossy(&csv.contents).lines().count(), 13);
        // Each survival plot names the runs made, not the paper's count.
        for f in one.files.iter().filter(|f| f.name.ends_with(".svg")) {
            let svg = String::from_utf8_lossy(&f.contents);
            assert!(svg.contains("3 runs per input"), "{}", f.name);
            assert!(!svg.contains("30-run"), "{}", f.name);
        }
    }

    #[test]
    fn a_measured_table_is_run_and_judged() {
        let path =
            std::env::temp_dir().join(format!("failure-measured-{}.ron", std::process::id()));
        // Every gear with Case D's errors: quick, and a judged column.
        let mut text = String::from("(gears: [\n");
        for g in train::Gearing::freeth2006().gears() {
            text.push_str(&format!(
                "(gear: \"{}\", random: 0.08, systematic: 2.0),\n",
                g.name
            ));
        }
        text.push_str("])\n");
        std::fs::write(&path, text).unwrap();
        let r = run_with(
            2,
            &[
                ("cases", ""),
                ("trials", "2"),
                ("measured", path.to_str().unwrap()),
            ],
        );
        let _ = std::fs::remove_file(&path);
        let r = r.unwrap();
        assert_eq!(r.trials, 2);
        let a = r.agreement.unwrap();
        assert!(a.consistent + a.differ >= 1, "{a:?}");
        assert!(r.tables[0].columns.iter().any(|c| c == "measured table"));
    }
}
