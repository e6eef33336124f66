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
use registry::{Agreement, OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::DAYS_PER_YEAR;

use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::{self, GearingParams};
use study::results::{FailureInput, FailureStudy, TrainSummary};
use study::whole_mechanism::{
    CASES_PARAM, Clearances, DAYS, Input, MEASURED_INDEX, RUNS_DEFAULT, TRAINS, batch_key,
    case_input, check_study, measured_table, parse_cases, run_study,
};

use presentation::common::{Plot, Series, mean_day_cell, percent_cell};
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
        let runs = r.inputs.iter().flat_map(|i| &i.runs);
        let mut report = Report {
            trials: runs.clone().count() as u64,
            engagements: runs.map(|o| o.engagements).sum::<f64>().round() as u64,
            ..Default::default()
        };
        let (mut paper_table, agreement) = paper_table(r, s.gearing.clearance);
        if s.pin_and_slot {
            paper_table.note("The Lunar train includes the pin-and-slot (--set pin_and_slot=true), beyond the paper: e5-k1 and k2-e6 turn in the frame of the e3 turntable, which turns at its mean rate.");
        }
        report.tables.push(paper_table);
        report.tables.push(detail_table(r));
        report.tables.push(survival_table(r));
        report.agreement = agreement;
        report
            .files
            .push(OutputFile::new("failure-runs.csv", runs_csv(r)));
        report.files.extend(survival_files(r)?);
        label(&s.events, None, report)
    }
}

registry::register!(Failure);

/// Points of b at which the survival table is read: degrees of the solar (b) pointer.
const READ_AT_DEG: [f64; 5] = [30.0, 60.0, 120.0, 180.0, 360.0];

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

/// Per train, the share of runs not yet jammed against the day (Kaplan-Meier), every input a
/// curve.
fn survival_files(r: &FailureStudy) -> Result<Vec<OutputFile>, RunError> {
    let mut files = Vec::new();
    let Some(first) = r.inputs.first() else {
        return Ok(files);
    };
    for (ti, train) in first.trains.iter().enumerate() {
        let curves: Vec<(String, Vec<(f64, f64)>)> = r
            .inputs
            .iter()
            .map(|inp| {
                let steps: Vec<stats::Step> =
                    inp.trains[ti].survival.iter().map(|s| s.step()).collect();
                (inp.legend.clone(), stats::step_points(&steps, r.horizon))
            })
            .collect();
        let svg = survival_plot(
            &format!(
                "Section 5's failure study, {} runs per input: {}, runs not yet jammed (Kaplan-Meier)",
                r.runs_per_input, train.train
            ),
            r.horizon,
            &curves,
        )?;
        files.push(OutputFile::new(
            format!("failure-{}.svg", file_stem(&train.train)),
            svg,
        ));
    }
    Ok(files)
}

/// One input's cell of the paper table, and whether the paper's value `p` is inside its 95 %
/// interval (none where there is no paper value, or too few jams for a mean's interval).
fn judged_cell(s: &TrainSummary, share: bool, p: Option<f64>) -> (String, Option<bool>) {
    if share {
        let inside = p.map(|v| {
            let r = v / 100.0;
            s.within_year.lo <= r && r <= s.within_year.hi
        });
        (percent_cell(&s.within_year.proportion()), inside)
    } else {
        let inside = s
            .mean_day
            .filter(|_| s.days.len() >= 2)
            .and_then(|e| p.map(|v| e.lo <= v && v <= e.hi));
        (mean_day_cell(s.mean_day.as_ref()), inside)
    }
}

fn file_stem(train: &str) -> String {
    let first = train.split(' ').next().unwrap_or(train);
    first.to_lowercase().replace('/', "-")
}

/// The paper's numbers beside ours, per input; the agreement counts the measured input only.
fn paper_table(r: &FailureStudy, clearance: f64) -> (Table, Option<Agreement>) {
    let mut header = vec!["quantity".to_string(), "paper".to_string()];
    header.extend(r.inputs.iter().map(|i| {
        if i.measured {
            "measured table".to_string()
        } else {
            format!("Case {}", i.label)
        }
    }));
    let mut table = Table::new(
        format!(
            "Section 5, the 30-run study: the paper beside ours (G = {clearance} %, {} runs per input, {} days of b): ours [95 % interval]; * where the paper's value is outside it",
            r.runs_per_input,
            fmt_f64(r.horizon, 2)
        ),
        header,
    );
    let paper = |q: &str| presentation::paper::get("failure", q).map(|r| r.value);
    let mut agreement = Agreement {
        what: "the paper's values inside / outside our 95 % intervals, the measured input's column"
            .into(),
        ..Agreement::default()
    };
    let mut judged = false;
    // (label, paper quantity, train index, is the share row)
    let mut rows: Vec<(String, String, usize, bool)> = vec![(
        "mechanisms jammed within a year [%]".into(),
        "mechanisms_jammed".into(),
        TRAINS.len(),
        true,
    )];
    for (ti, (name, _)) in TRAINS.iter().enumerate() {
        rows.push((
            format!("{name}: mean day of the first jam"),
            format!("{name}.mean_days"),
            ti,
            false,
        ));
    }
    for (label, quantity, ti, share) in rows {
        let p = paper(&quantity);
        let mut row = vec![label, p.map_or_else(|| "-".into(), |v| fmt_f64(v, 0))];
        for inp in &r.inputs {
            let (cell, inside) = judged_cell(&inp.trains[ti], share, p);
            let mark = if inside == Some(false) { " *" } else { "" };
            row.push(format!("{cell}{mark}"));
            if inp.measured
                && let Some(inside) = inside
            {
                judged = true;
                if inside {
                    agreement.consistent += 1;
                } else {
                    agreement.differ += 1;
                }
            }
        }
        table.row(row);
    }
    table.row(stop_row(r, paper("stop_angle")));
    table.note("The paper ran Edmunds' measured per-gear errors (its Figure 6), which are not available here: our inputs are Edmunds' Cases A-D until a measured table is given with --set measured=FILE. Only that column is counted as agreement with the paper; the cases are for orientation.");
    table.note("Shares: runs whose mechanism (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed within the horizon, 95 % Student-t interval clipped to 0 .. horizon (none for fewer than two).");
    table.note("The paper's horizon is not stated (Table 1 ran 1, 3.8 and 4.5 turns of b); ours is the days parameter. The last row compares with the conclusions: a mechanism with Edmunds' errors 'would generally stop after the solar pointer completed one-third (120 deg)'.");
    (table, judged.then_some(agreement))
}

/// The conclusion's "one-third (120 deg)" (`stop_angle`, degrees of b) beside the median day
/// each input's mechanism stopped.
fn stop_row(r: &FailureStudy, stop_angle: Option<f64>) -> Vec<String> {
    let third = stop_angle.map(|deg| deg / 360.0 * DAYS_PER_YEAR);
    let mut row = vec![
        "median day the mechanism stopped (of the runs that did)".to_string(),
        third.map_or_else(|| "-".into(), |d| format!("about {}", fmt_f64(d, 0))),
    ];
    for inp in &r.inputs {
        row.push(
            inp.trains[TRAINS.len()]
                .median_day
                .map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
        );
    }
    row
}

fn detail_table(r: &FailureStudy) -> Table {
    let mut table = Table::new(
        format!(
            "Days to the first jam per input and train ({} runs each, horizon {} days of b)",
            r.runs_per_input,
            fmt_f64(r.horizon, 2)
        ),
        [
            "input",
            "train",
            "jammed within a year",
            "95 % interval [%]",
            "jammed within the horizon",
            "mean day [95 % interval]",
            "median day",
            "meshes that jammed first (runs)",
        ],
    );
    for inp in &r.inputs {
        for s in &inp.trains {
            let year = &s.within_year;
            table.row(vec![
                inp.label.clone(),
                s.train.clone(),
                format!("{}/{}", year.k, year.n),
                format!(
                    "{} .. {}",
                    fmt_f64(100.0 * year.lo, 0),
                    fmt_f64(100.0 * year.hi, 0)
                ),
                format!("{}/{}", s.days.len(), year.n),
                mean_day_cell(s.mean_day.as_ref()),
                s.median_day.map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                presentation::common::jammed_first(&s.first_meshes),
            ]);
        }
    }
    for inp in &r.inputs {
        let p: Vec<String> = inp
            .params
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        table.note(format!(
            "{}: hypothesis {} with {}.",
            inp.label,
            inp.hypothesis,
            if p.is_empty() {
                "no parameters".into()
            } else {
                p.join(", ")
            }
        ));
    }
    table.note("One run is one mechanism: every gear manufactured once, each mesh given one random initial angle, each mesh run once up to its first jam; trains sharing meshes (b2-l1, l2-m1) share their motion. A train's first jam is the earliest jam on any of its pointers' meshes, dated on the b arbor. Trains are counted separately, as the paper did; in the real mechanism any jam stops every train (the mechanism row).");
    table
}

/// Share of runs not yet jammed at fixed angles of b.
fn survival_table(r: &FailureStudy) -> Table {
    let mut header = vec!["input".to_string(), "train".to_string()];
    for deg in READ_AT_DEG {
        header.push(format!(
            "{deg} deg of b ({} d)",
            fmt_f64(deg / 360.0 * DAYS_PER_YEAR, 1)
        ));
    }
    let mut table = Table::new(
        "Runs not yet jammed [%] at angles of the solar pointer (b arbor)",
        header,
    );
    let mut unplaceable = 0;
    for inp in &r.inputs {
        unplaceable += inp.runs.iter().filter(|o| o.unplaceable.is_some()).count();
        for s in &inp.trains {
            let steps: Vec<stats::Step> = s.survival.iter().map(|p| p.step()).collect();
            let mut row = vec![inp.label.clone(), s.train.clone()];
            for deg in READ_AT_DEG {
                row.push(survival_cell(&steps, deg / 360.0 * DAYS_PER_YEAR));
            }
            table.row(row);
        }
    }
    table.note("Kaplan-Meier estimate [95 % band]; every run is observed to the same horizon, so it is the share of runs whose first jam came later, and the band is that share's exact (Clopper-Pearson) interval.");
    if unplaceable > 0 {
        table.note(format!(
            "{unplaceable} runs had gears whose bodies overlapped at every angle (errors too large for the clearance): counted as jammed at day 0."
        ));
    }
    table
}

/// Per run and train: the day of the first jam, or the horizon and "censored".
fn runs_csv(r: &FailureStudy) -> String {
    let mut csv = String::from("input,trial,train,first_jam_day,status,mesh\n");
    for inp in &r.inputs {
        for (t, o) in inp.runs.iter().enumerate() {
            for (jam, s) in o.first_jams.iter().zip(&inp.trains) {
                let (label, name) = (&inp.label, &s.train);
                csv.push_str(&match jam {
                    Some(j) => registry::csv_row!(label, t, name, j.day, "jammed", j.mesh),
                    None => registry::csv_row!(label, t, name, r.horizon, "censored", ""),
                });
            }
        }
    }
    csv
}

/// A survival share [%] at `day` with its 95 % band: `50 [33 .. 70]`.
fn survival_cell(steps: &[stats::Step], day: f64) -> String {
    let at = steps
        .iter()
        .take_while(|p| p.day <= day)
        .last()
        .copied()
        .unwrap_or(stats::Step {
            day: 0.0,
            survival: 100.0,
            lo: 100.0,
            hi: 100.0,
        });
    presentation::common::interval(at.survival, at.lo, at.hi, 0)
}

fn survival_plot(
    title: &str,
    horizon: f64,
    curves: &[(String, Vec<(f64, f64)>)],
) -> Result<String, RunError> {
    let series: Vec<Series<'_>> = curves
        .iter()
        .map(|(label, points)| Series {
            label,
            points: points.clone(),
        })
        .collect();
    Plot::new(
        title,
        "days of the b arbor (solar pointer; 365.25 d per turn)",
        "runs not yet jammed [%]",
        &series,
    )
    .ranges((0.0, horizon), (0.0, 102.0))
    .whole_ticks()
    .svg()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn survival_cells_carry_their_band() {
        let steps = stats::kaplan_meier(&[Some(30.0), None, Some(10.0), Some(10.0)], 100.0);
        // 4 of 4 not yet jammed: the exact interval still reaches down to 40 %.
        assert_eq!(survival_cell(&steps, 5.0), "100 [40 .. 100]");
        let at_10 = survival_cell(&steps, 10.0);
        assert!(at_10.starts_with("50 ["), "{at_10}");
        assert_eq!(
            stats::survival_at(&steps, 99.0),
            25.0,
            "the cell reads the same curve"
        );
    }

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
