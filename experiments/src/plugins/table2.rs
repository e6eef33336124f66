//! `table2`: Edmunds' Cases A-D with his radial-line model (his Table 2 beside ours), then the
//! same manufactured gears with triangular teeth, trial by trial, with the difference and its
//! 95 % interval.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::Estimate;

use presentation::common::{Series, semilog_plot};
use setting_groups::typed::{Gearing, cells, label};
use study::draws::Draws;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::{self, GearingParams};
use study::grids::CASES;
use study::pointers::{BothModels, CaseMechanism, both_model_trials, pointer_runs};
use study::results::{CasePointer, CasePointers, CaseRun};

/// `trials`: trials per case, each with fresh errors and initial angles (Edmunds gives no count).
const TRIALS: Param = registry::interval_trials(
    "20",
    "trials per case, each with fresh errors and initial angles (Edmunds gives no count)",
);

/// `lunar_turns`: run length, Lunar.
const LUNAR_TURNS: Param = study::pointers::turns("lunar_turns", "1", "run length, Lunar");

/// `metonic_turns`: run length, Metonic.
const METONIC_TURNS: Param = study::pointers::turns("metonic_turns", "3.8", "run length, Metonic");

/// `saros_turns`: run length, Saros.
const SAROS_TURNS: Param = study::pointers::turns("saros_turns", "4.5", "run length, Saros");

/// `samples_per_engagement`: TD samples per engagement of the busiest mesh.
const SAMPLES_PER_ENGAGEMENT: Param =
    study::pointers::per_engagement("8", "TD samples per engagement of the busiest mesh");

/// Table 2's settings: trials per Case, the three pointers' run lengths and TD sampling, the
/// pin-and-slot, the gearing with h and G, the Cases' errors and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per Case ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// Run length of the Lunar pointer, turns of b ([`LUNAR_TURNS`]).
    #[param(LUNAR_TURNS)]
    pub lunar_turns: f64,
    /// Run length of the Metonic pointer, turns of b ([`METONIC_TURNS`]).
    #[param(METONIC_TURNS)]
    pub metonic_turns: f64,
    /// Run length of the Saros pointer, turns of b ([`SAROS_TURNS`]).
    #[param(SAROS_TURNS)]
    pub saros_turns: f64,
    /// TD samples per engagement of the busiest mesh ([`SAMPLES_PER_ENGAGEMENT`]).
    #[param(SAMPLES_PER_ENGAGEMENT)]
    pub samples_per_engagement: usize,
    /// Whether the Lunar train runs with the pin-and-slot ([`gearing::PIN_AND_SLOT`]).
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

/// Table 2.
pub struct Table2;

impl registry::Experiment for Table2 {
    const ID: &'static str = "table2";
    const TITLE: &'static str = "Edmunds' Cases A-D: his radial-line model beside his Table 2, and triangular teeth on the same gears";
    const PAPER_ITEM: &'static str = "Table 2 (section 4)";
    const PLACE: Place = Place::Paper(60);
    type Settings = Settings;
    type Results = CasePointers;

    fn compute(s: &Settings, run: &Run) -> Result<CasePointers, RunError> {
        let cells = cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            Some(&s.events),
            None,
            s.trials,
            s,
        )?;
        let (g, trials, clearance) = (cells.gearing(), cells.trials as usize, cells.clearance()?);
        let turns = [
            ("Lunar", s.lunar_turns),
            ("Metonic", s.metonic_turns),
            ("Saros", s.saros_turns),
        ];
        let runs = pointer_runs(g, &turns, s.samples_per_engagement)?;
        let results = simulate(run, &cells, &runs, s.pin_and_slot)?;
        let cases = CASES
            .iter()
            .zip(results)
            .map(|(&(case, systematic, random), per_trial)| CaseRun {
                case: case.to_owned(),
                systematic,
                random,
                pointers: runs
                    .iter()
                    .enumerate()
                    .map(|(pi, &(name, _, _))| CasePointer {
                        pointer: name.to_owned(),
                        trials: per_trial.iter().map(|t| t[pi]).collect(),
                    })
                    .collect(),
            })
            .collect();
        Ok(CasePointers {
            clearance,
            trials,
            pin_and_slot: s.pin_and_slot,
            pointers: runs
                .iter()
                .map(|&(name, _, _)| (name.to_owned(), g.days_per_degree(name)))
                .collect(),
            cases,
        })
    }

    fn report(s: &Settings, r: &CasePointers) -> Result<Report, RunError> {
        label(&s.events, None, tables(r)?)
    }
}

registry::register!(Table2);

/// Every Case's trials under both contact models: `results[case][trial][pointer]`.
fn simulate(
    run: &Run,
    cells: &study::grids::CellSettings,
    runs: &[(&str, f64, usize)],
    pin_and_slot: bool,
) -> Result<Vec<Vec<Vec<BothModels>>>, RunError> {
    let (g, hyp, trials) = (cells.gearing(), cells.hypothesis(), cells.trials as usize);
    let (h, clearance) = (cells.gearing.tooth_height, cells.clearance()?);
    let mut results = Vec::new();
    for &(case, systematic, random) in &CASES {
        let p = cells.errors.case_params((systematic, random))?;
        // Named by everything that determines the trials, so shards run and merge them.
        let key = format!(
            "table2: case {case} ({} {:?}), {trials} trials, h = {h} mm, G = {clearance} %, gearing {}, pin_and_slot {pin_and_slot}, events {}, pointers {:?}",
            hyp.name(),
            p.iter().collect::<Vec<_>>(),
            cells.gearing.file,
            cells.rule.label(),
            runs,
        );
        let made = CaseMechanism {
            gearing: (g, &cells.gearing.file),
            tooth_height: h,
            clearance,
            errors: (hyp, &p),
            rule: &cells.rule,
            pin_and_slot,
        };
        results.push(both_model_trials(
            run.engine(),
            &key,
            Draws::Case(case),
            &made,
            runs,
            trials as u64,
        )?);
    }
    Ok(results)
}

/// The plot: each pointer's σ against the systematic error, per model (`curves`, by label).
fn plot(curves: &std::collections::BTreeMap<String, Vec<(f64, f64)>>) -> Result<String, RunError> {
    let series: Vec<Series<'_>> = curves
        .iter()
        .map(|(label, points)| Series {
            label: label.as_str(),
            points: points.clone(),
        })
        .collect();
    semilog_plot(
        "Table 2: pointer sigma against Edmunds' systematic error (Cases A-D)",
        "systematic error amplitude [deg] (Case A 0, B 0.5, C 1, D 2)",
        "sigma of the Theoretical Difference [deg], logarithmic scale",
        &series,
    )
}

/// An estimate as printed: "mean [lo .. hi]".
fn show(e: &stats::Estimate) -> String {
    presentation::common::estimate(e, 3)
}

/// The notes under both tables: what each Case draws, the days per degree, and the
/// pin-and-slot when it is in.
fn notes(edm_table: &mut Table, tri_table: &mut Table, r: &CasePointers) {
    let pin_and_slot = r.pin_and_slot;
    let days = |name: &str| {
        r.pointers
            .iter()
            .find(|(p, _)| p == name)
            .and_then(|(_, d)| *d)
            .map_or_else(|| "-".into(), |d| fmt_f64(d, 3))
    };
    edm_table.note("Each case: every gear gets random tooth errors (sd = random x pitch) and the systematic error split between a sinusoid of tip position and an eccentric axis (split parameter, 0.5 as in the paper).");
    edm_table.note(format!(
        "Days: from each pointer's exact ratio (Metonic {} d/deg, Saros {} d/deg).",
        days("Metonic"),
        days("Saros"),
    ));
    if pin_and_slot {
        let note = "Lunar: with the pin-and-slot (--set pin_and_slot=true), beyond the paper; its TD is taken against the anomaly-bearing ideal motion (cargo xtask help lunar-anomaly).";
        edm_table.note(note);
        tri_table.note(note);
    }
}

/// The CSV lines of one Case and pointer `p`: each model's σ and Dm over the trials, with the
/// paper's for Edmunds' model.
fn csv_lines(
    csv: &mut String,
    case: &str,
    p: &CasePointer,
    (paper_sigma, paper_dm): (Option<f64>, Option<f64>),
) {
    let name = &p.pointer;
    for (model, stat, e, paper) in [
        ("edmunds", "sigma", p.edmunds_sigma(), paper_sigma),
        ("edmunds", "dm", p.edmunds_dm(), paper_dm),
        ("triangular", "sigma", p.triangular_sigma(), None),
        ("triangular", "dm", p.triangular_dm(), None),
    ] {
        csv.push_str(&registry::csv_row!(
            case,
            name,
            model,
            stat,
            e.mean,
            e.lo,
            e.hi,
            paper.map_or(String::new(), |x| x.to_string())
        ));
    }
}

/// The two tables' titles and columns: Edmunds' model in the paper's layout, and triangular
/// teeth against it.
fn tables_of(trials: usize, clearance: f64) -> (Table, Table) {
    let edm_table = Table::new(
        format!(
            "Table 2: Edmunds' model (radial lines), {trials} trials per case: sigma - Dm, ours / paper [deg] (days)"
        ),
        [
            "case",
            "systematic [deg]",
            "random",
            "Lunar",
            "Metonic",
            "Saros",
        ],
    );
    let tri_table = Table::new(
        format!(
            "Triangular teeth on the same gears (G = {clearance} %): triangular minus Edmunds, mean and 95 % interval over trials [deg]"
        ),
        [
            "case",
            "pointer",
            "Edmunds sigma",
            "triangular sigma",
            "difference sigma",
            "Edmunds Dm",
            "triangular Dm",
            "difference Dm",
            "trials that jammed",
        ],
    );
    (edm_table, tri_table)
}

/// A cell of the paper's layout: our sigma - Dm / the paper's (`paper`: sigma, Dm), and ours in
/// days where the pointer has a day scale.
fn edmunds_cell(
    es_m: &Estimate,
    ed_m: &Estimate,
    paper: (Option<f64>, Option<f64>),
    days: Option<f64>,
) -> String {
    let mut cell = format!(
        "{} - {} / {} - {}",
        fmt_f64(es_m.mean, 2),
        fmt_f64(ed_m.mean, 2),
        paper.0.map_or_else(|| "-".into(), |v| fmt_f64(v, 2)),
        paper.1.map_or_else(|| "-".into(), |v| fmt_f64(v, 2)),
    );
    if let Some(d) = days {
        cell.push_str(&format!(
            " ({} - {} d)",
            fmt_f64(es_m.mean * d, 1),
            fmt_f64(ed_m.mean * d, 1)
        ));
    }
    cell
}

/// The tables, the CSV and the plot drawn from the results (before the event rule is named).
fn tables(r: &CasePointers) -> Result<Report, RunError> {
    let (trials, clearance) = (r.trials, r.clearance);
    let (mut edm_table, mut tri_table) = tables_of(trials, clearance);
    // sigma against the systematic error, per pointer and model, for the plot.
    let mut curves: std::collections::BTreeMap<String, Vec<(f64, f64)>> =
        std::collections::BTreeMap::new();
    let mut csv = String::from("case,pointer,model,statistic,mean_deg,lo_deg,hi_deg,paper_deg\n");
    for c in &r.cases {
        let (case, systematic) = (c.case.as_str(), c.systematic);
        let mut row = vec![
            case.to_string(),
            fmt_f64(systematic, 2),
            fmt_f64(c.random, 3),
        ];
        for (p, (name, days)) in c.pointers.iter().zip(&r.pointers) {
            let (es_m, ed_m) = (p.edmunds_sigma(), p.edmunds_dm());
            let paper = |q: &str| {
                presentation::paper::get("table2", &format!("{case}.{name}.{q}")).map(|r| r.value)
            };
            row.push(edmunds_cell(
                &es_m,
                &ed_m,
                (paper("sigma"), paper("dm")),
                *days,
            ));
            let mut add = |label: String, y: Option<f64>| {
                if let Some(y) = y {
                    curves.entry(label).or_default().push((systematic, y));
                }
            };
            add(format!("{name}, Edmunds' model (ours)"), Some(es_m.mean));
            add(
                format!("{name}, triangular teeth (ours)"),
                Some(p.triangular_sigma().mean),
            );
            add(format!("{name}, Edmunds' Table 2 (paper)"), paper("sigma"));
            tri_table.row(triangular_row(case, p, trials));
            csv_lines(&mut csv, case, p, (paper("sigma"), paper("dm")));
        }
        edm_table.row(row);
    }
    notes(&mut edm_table, &mut tri_table, r);
    tri_table.note("A jam stops the pointer, so a triangular trial that jammed is measured up to its first jam (Edmunds' model never jams).");
    let svg = plot(&curves)?;
    Ok(Report {
        tables: vec![edm_table, tri_table],
        files: vec![
            OutputFile::new("table2-data.csv", csv),
            OutputFile::new("table2.svg", svg),
        ],
        // Mechanisms run, per Case (each under both contact models).
        trials: (r.cases.len() * trials) as u64,
        ..Default::default()
    })
}

/// One Case's row of the triangular table for pointer `p`: both models' means, the differences
/// with their intervals and the trials that jammed.
fn triangular_row(case: &str, p: &CasePointer, trials: usize) -> Vec<String> {
    vec![
        case.into(),
        p.pointer.clone(),
        fmt_f64(p.edmunds_sigma().mean, 3),
        fmt_f64(p.triangular_sigma().mean, 3),
        show(&p.sigma_difference()),
        fmt_f64(p.edmunds_dm().mean, 3),
        fmt_f64(p.triangular_dm().mean, 3),
        show(&p.dm_difference()),
        format!("{}/{trials}", p.jammed()),
    ]
}
