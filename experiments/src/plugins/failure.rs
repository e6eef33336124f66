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
use registry::{Agreement, Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use stats::DAYS_PER_YEAR;

use study::gearing;
use study::whole_mechanism::{
    CASES_PARAM, Clearances, DAYS, Input, MEASURED_INDEX, MechanismRun, RUNS_DEFAULT, Summary,
    TRAINS, batch_key, case_input, check_study, jam_of, measured_table, parse_cases, run_study,
    runs_csv, summarise, train_names,
};

use crate::common::{Plot, Series, mean_cell, percent_cell};

registry::params! {
    /// `trials`: whole-mechanism runs per input (the paper: 30).
    const TRIALS = Param::new("trials", RUNS_DEFAULT, "whole-mechanism runs per input (the paper: 30)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
    /// `measured`: per-gear error table (RON, as crates/hypotheses/data/measured-example.ron), run with the measured hypothesis; empty: not run.
    const MEASURED = Param::new("measured", "", "per-gear error table (RON, as crates/hypotheses/data/measured-example.ron), run with the measured hypothesis; empty: not run", registry::Kind::Text);
}

crate::experiment! {
    id: "failure", paper_item: "Section 5, the 30-run study", run,
    title: "Days to the first jam of each train, whole mechanisms with Edmunds' errors at G = 40 %",
    params: [TRIALS, DAYS, CASES_PARAM, MEASURED, gearing::PIN_AND_SLOT], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::events::GROUP],
}

/// Points of b at which the survival table is read: degrees of the solar (b) pointer.
const READ_AT_DEG: [f64; 5] = [30.0, 60.0, 120.0, 180.0, 360.0];

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let settings = crate::settings::gearing(ctx)?;
    let trials = ctx.get(&TRIALS)?;
    let days = ctx.get(&study::whole_mechanism::DAYS)?;
    // Read here, before the gearing's checks, with the split each case takes.
    let errors = crate::settings::errors(ctx)?;
    let rule = crate::settings::rule(ctx)?;
    let (g, h, clearance) = (&settings.gearing, settings.tooth_height, settings.clearance);
    check_study(g, h, &Clearances::Uniform(clearance))?;
    let pin_and_slot = ctx.get(&study::gearing::PIN_AND_SLOT)?;
    // A pin-and-slot asked of a gearing without one is refused before anything runs.
    let ideal = study::pointers::ideal_mechanism(&settings, &rule)?;
    gearing::with_pin_and_slot(&settings.file, ideal, pin_and_slot)?;

    let measured = measured_table(ctx.text(&MEASURED)?)?;
    let inputs = study_inputs(ctx, &errors, measured.as_ref(), clearance, pin_and_slot)?;

    let outcomes = run_study(
        ctx.engine(),
        g,
        &inputs,
        trials,
        h,
        days,
        &rule,
        &batch_key(&settings.file, &inputs, trials, h, clearance, days)?,
    )?;
    let per_input: Vec<&[MechanismRun]> = outcomes.chunks(trials as usize).collect();

    let mut report = Report {
        trials: outcomes.len() as u64,
        engagements: outcomes.iter().map(|o| o.engagements).sum::<f64>().round() as u64,
        ..Default::default()
    };
    let summaries: Vec<Vec<Summary>> = per_input.iter().map(|runs| summarise(runs, days)).collect();
    let (mut paper_table, agreement) = paper_table(&inputs, &summaries, trials, days, clearance);
    if pin_and_slot {
        paper_table.note("The Lunar train includes the pin-and-slot (--set pin_and_slot=true), beyond the paper: e5-k1 and k2-e6 turn in the frame of the e3 turntable, which turns at its mean rate.");
    }
    report.tables.push(paper_table);
    report
        .tables
        .push(detail_table(&inputs, &summaries, trials, days));
    report
        .tables
        .push(survival_table(&inputs, per_input.as_slice(), days));
    report.agreement = agreement;
    report.files.push(OutputFile::new(
        "failure-runs.csv",
        runs_csv(&inputs, &per_input, days),
    ));
    report
        .files
        .extend(survival_files(&inputs, &per_input, trials, days)?);
    Ok(report)
}

/// The inputs of the study: the cases asked for, then the measured table if one is given, each
/// with the pin-and-slot as asked; refused when there is nothing to run.
fn study_inputs<'a>(
    ctx: &Context,
    errors: &'a study::errors::Settings,
    measured: Option<&'a (String, MeasuredHypothesis)>,
    clearance: f64,
    pin_and_slot: bool,
) -> Result<Vec<Input<'a>>, RunError> {
    let mut inputs: Vec<Input<'_>> = Vec::new();
    for ci in parse_cases(ctx.text(&CASES_PARAM)?)? {
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
        inp.pin_and_slot = pin_and_slot;
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
fn survival_files(
    inputs: &[Input<'_>],
    per_input: &[&[MechanismRun]],
    trials: u64,
    days: f64,
) -> Result<Vec<OutputFile>, RunError> {
    let mut files = Vec::new();
    for (ti, name) in train_names().enumerate() {
        let curves: Vec<(String, Vec<(f64, f64)>)> = inputs
            .iter()
            .zip(per_input)
            .map(|(inp, runs)| {
                let times: Vec<Option<f64>> =
                    runs.iter().map(|o| jam_of(o, ti).map(|j| j.day)).collect();
                (
                    inp.legend.clone(),
                    stats::step_points(&stats::kaplan_meier(&times, days), days),
                )
            })
            .collect();
        let svg = survival_plot(
            &format!(
                "Section 5's failure study, {trials} runs per input: {name}, runs not yet jammed (Kaplan-Meier)"
            ),
            days,
            &curves,
        )?;
        files.push(OutputFile::new(
            format!("failure-{}.svg", file_stem(name)),
            svg,
        ));
    }
    Ok(files)
}

/// One input's cell of the paper table, and whether the paper's value `p` is inside its 95 %
/// interval (none where there is no paper value, or too few jams for a mean's interval).
fn judged_cell(s: &Summary, share: bool, p: Option<f64>, days: f64) -> (String, Option<bool>) {
    if share {
        let inside = p.map(|v| {
            let r = v / 100.0;
            s.year.lo <= r && r <= s.year.hi
        });
        (percent_cell(&s.year), inside)
    } else {
        let e = study::whole_mechanism::mean_days(&s.days, days);
        let inside = p.filter(|_| s.days.len() >= 2).map(|v| e.contains(v));
        (mean_cell(&s.days, days), inside)
    }
}

fn file_stem(train: &str) -> String {
    let first = train.split(' ').next().unwrap_or(train);
    first.to_lowercase().replace('/', "-")
}

/// The paper's numbers beside ours, per input; the agreement counts the measured input only.
fn paper_table(
    inputs: &[Input<'_>],
    summaries: &[Vec<Summary>],
    trials: u64,
    days: f64,
    clearance: f64,
) -> (Table, Option<Agreement>) {
    let mut header = vec!["quantity".to_string(), "paper".to_string()];
    header.extend(inputs.iter().map(|i| match i.index {
        MEASURED_INDEX => "measured table".to_string(),
        _ => format!("Case {}", i.label),
    }));
    let mut table = Table::new(
        format!(
            "Section 5, the 30-run study: the paper beside ours (G = {clearance} %, {trials} runs per input, {} days of b): ours [95 % interval]; * where the paper's value is outside it",
            fmt_f64(days, 2)
        ),
        header,
    );
    let paper = |q: &str| crate::paper::get("failure", q).map(|r| r.value);
    let mut agreement = Agreement::default();
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
        for (inp, s) in inputs.iter().zip(summaries) {
            let s = &s[ti];
            let (cell, inside) = judged_cell(s, share, p, days);
            let mark = if inside == Some(false) { " *" } else { "" };
            row.push(format!("{cell}{mark}"));
            if inp.index == MEASURED_INDEX
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
    // The conclusion's "one-third (120 deg)": the median day the mechanism stopped.
    let third = paper("stop_angle").map(|deg| deg / 360.0 * DAYS_PER_YEAR);
    let mut row = vec![
        "median day the mechanism stopped (of the runs that did)".to_string(),
        third.map_or_else(|| "-".into(), |d| format!("about {}", fmt_f64(d, 0))),
    ];
    for s in summaries {
        row.push(
            stats::median(&s[TRAINS.len()].days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
        );
    }
    table.row(row);
    table.note("The paper ran Edmunds' measured per-gear errors (its Figure 6), which are not available here: our inputs are Edmunds' Cases A-D until a measured table is given with --set measured=FILE. Only that column is counted as agreement with the paper; the cases are for orientation.");
    table.note("Shares: runs whose mechanism (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed within the horizon, 95 % Student-t interval clipped to 0 .. horizon (none for fewer than two).");
    table.note("The paper's horizon is not stated (Table 1 ran 1, 3.8 and 4.5 turns of b); ours is the days parameter. The last row compares with the conclusions: a mechanism with Edmunds' errors 'would generally stop after the solar pointer completed one-third (120 deg)'.");
    (table, judged.then_some(agreement))
}

fn detail_table(inputs: &[Input<'_>], summaries: &[Vec<Summary>], trials: u64, days: f64) -> Table {
    let mut table = Table::new(
        format!(
            "Days to the first jam per input and train ({trials} runs each, horizon {} days of b)",
            fmt_f64(days, 2)
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
    for (inp, s) in inputs.iter().zip(summaries) {
        for (name, s) in train_names().zip(s) {
            table.row(vec![
                inp.label.clone(),
                name.into(),
                format!("{}/{}", s.year.k, s.year.n),
                format!(
                    "{} .. {}",
                    fmt_f64(100.0 * s.year.lo, 0),
                    fmt_f64(100.0 * s.year.hi, 0)
                ),
                format!("{}/{}", s.days.len(), s.year.n),
                mean_cell(&s.days, days),
                stats::median(&s.days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                crate::common::jammed_first(&s.meshes),
            ]);
        }
    }
    for inp in inputs {
        let p: Vec<String> = inp
            .params
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        table.note(format!(
            "{}: hypothesis {} with {}.",
            inp.label,
            inp.hypothesis.name(),
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
fn survival_table(inputs: &[Input<'_>], per_input: &[&[MechanismRun]], days: f64) -> Table {
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
    for (inp, runs) in inputs.iter().zip(per_input) {
        unplaceable += runs.iter().filter(|o| o.unplaceable.is_some()).count();
        for (ti, name) in train_names().enumerate() {
            let times: Vec<Option<f64>> =
                runs.iter().map(|o| jam_of(o, ti).map(|j| j.day)).collect();
            let steps = stats::kaplan_meier(&times, days);
            let mut row = vec![inp.label.clone(), name.to_string()];
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
    crate::common::interval(at.survival, at.lo, at.hi, 0)
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
