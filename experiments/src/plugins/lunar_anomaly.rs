//! `lunar-anomaly`: the pin-and-slot (Freeth 2006) on the Lunar train, which the paper leaves
//! out. (a) The anomaly it puts on the Lunar pointer, from the geometry in the gearing data;
//! (b) the Lunar pointer's Theoretical Difference with triangular teeth, ideal and with Edmunds'
//! Cases A-D, without and with the pin-and-slot (then against the anomaly-bearing ideal), on the
//! same gears and initial angles trial by trial; (c) a plot of the anomaly over two anomalistic
//! months beside one simulated Case B trajectory.
//!
//! The Cases' trials use table2's random streams (the Case's `Draws::Case`, trial), so that
//! without the pin-and-slot they are table2's triangular Lunar trials, number for number.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::{DAYS_PER_YEAR, Estimate, mean_ci95};

use presentation::common::{Series, csv, line_plot, paper_cell};
use setting_groups::typed::label;
use study::anomaly::{AnomalyTrial, PinSlotTrain, Rows, RunStats};
use study::draws::Draws;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::{self, GearingParams};
use study::grids::CASES;
use study::pointers::pointer_runs;

/// `trials`: trials per row (ideal teeth, Cases A-D), each with fresh errors and initial angles, run without and with the pin-and-slot (table2's count and streams).
const TRIALS: Param = registry::interval_trials(
    "20",
    "trials per row (ideal teeth, Cases A-D), each with fresh errors and initial angles, run without and with the pin-and-slot (table2's count and streams)",
);

/// `lunar_turns`: run length (one turn of b: about 13 anomalistic months).
const LUNAR_TURNS: Param = study::pointers::turns(
    "lunar_turns",
    "1",
    "run length (one turn of b: about 13 anomalistic months)",
);

/// `samples_per_engagement`: TD samples per engagement of the busiest mesh.
const SAMPLES_PER_ENGAGEMENT: Param =
    study::pointers::per_engagement("8", "TD samples per engagement of the busiest mesh");

registry::params! {
    /// `curve_samples`: points of the anomaly curve over one anomalistic month (amplitude and plot).
    const CURVE_SAMPLES = Param::new("curve_samples", "2000", "points of the anomaly curve over one anomalistic month (amplitude and plot)", registry::Kind::count(100, registry::MAX_COUNT as u64, ""));
}

/// The lunar anomaly's settings: trials per row, the Lunar run, the TD and curve sampling, the
/// gearing with h and G, the Cases' errors and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per row ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: usize,
    /// Run length, turns of b ([`LUNAR_TURNS`]).
    #[param(LUNAR_TURNS)]
    pub lunar_turns: f64,
    /// TD samples per engagement of the busiest mesh ([`SAMPLES_PER_ENGAGEMENT`]).
    #[param(SAMPLES_PER_ENGAGEMENT)]
    pub samples_per_engagement: usize,
    /// Points of the anomaly curve over one anomalistic month ([`CURVE_SAMPLES`]).
    #[param(CURVE_SAMPLES)]
    pub curve_samples: usize,
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

/// The lunar anomaly's results: (a) the anomaly from the geometry, (b) every trial of every row
/// without and with the pin-and-slot, (c) the curves of the plot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// (a) The anomaly the pin-and-slot puts on the Lunar pointer.
    pub anomaly: Anomaly,
    /// The run's seed (the table names it).
    pub seed: u64,
    /// Clearance G of every mesh, % of h.
    pub clearance: f64,
    /// The Lunar run, turns of b.
    pub turns: f64,
    /// (b) Ideal teeth, then Cases A-D: each row's trials.
    pub rows: Vec<AnomalyRow>,
    /// (c) The anomaly from the geometry over two anomalistic months: (day of b, degrees).
    pub ideal_curve: Curve,
    /// (c) The first trial of Case B with the pin-and-slot, its pointer minus the mean motion,
    /// up to its first jam: (day of b, degrees).
    pub simulated: Curve,
}

/// (a): the anomaly from the gearing's pin-and-slot geometry.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Anomaly {
    /// Axes apart e, mm.
    pub offset: f64,
    /// Pin radius R, mm.
    pub pin_radius: f64,
    /// Largest lead of the pointer over its mean motion (sampled over a period), radians.
    pub lead: f64,
    /// Largest lag (sampled), radians (negative).
    pub lag: f64,
    /// Amplitude asin(e/R) on the pointer (closed form), radians.
    pub amplitude: f64,
    /// Period of the anomaly (anomalistic month), days.
    pub period_days: f64,
    /// One turn of the turntable (apsidal line), years.
    pub turntable_years: f64,
}

/// A curve of the plot: (day of b, degrees).
pub type Curve = Vec<(f64, f64)>;

/// (b): one row of the TD table.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AnomalyRow {
    /// `ideal teeth` or `Case A`-`Case D`.
    pub label: String,
    /// Each trial's statistics without and with the pin-and-slot.
    pub trials: Vec<AnomalyTrial>,
}

/// The lunar anomaly.
pub struct LunarAnomaly;

impl registry::Experiment for LunarAnomaly {
    const ID: &'static str = "lunar-anomaly";
    const TITLE: &'static str =
        "The pin-and-slot lunar anomaly on the Lunar pointer (beyond the paper)";
    const PAPER_ITEM: &'static str = "Section 6 (assumptions) / Freeth 2006";
    const PLACE: Place = Place::Beyond(30);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        compute(s, run)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, None, tables(s, r)?)
    }
}

registry::register!(LunarAnomaly);

/// The pointer the pin-and-slot sits on.
const LUNAR: &str = "Lunar";

/// The Case whose first trial is plotted.
const PLOTTED_CASE: &str = "B";

/// One row of the TD table: label and what its trials draw; `None` errors means ideal teeth.
struct Row {
    label: String,
    draws: Draws<'static>,
    case: Option<(f64, f64)>,
}

/// Every simulation: the anomaly from the geometry, the rows' trials and the plotted trial.
fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
    let gearing::Settings {
        gearing: g,
        file,
        tooth_height: h,
        clearance,
    } = s.gearing.load()?;
    let (trials, curve_samples) = (s.trials, s.curve_samples);
    let runs = pointer_runs(&g, &[(LUNAR, s.lunar_turns)], s.samples_per_engagement)?;
    let rule = s.events.rule()?;
    let &[(_, turns, samples)] = runs.as_slice() else {
        return Err(RunError::Internal("one Lunar run expected".into()));
    };
    // (b)'s rows: ideal teeth and Cases A-D, each with its stream.
    let errors = s.errors.load(s)?;
    let rows = rows();
    let params: Vec<Option<hypotheses::Params>> = rows
        .iter()
        .map(|r| r.case.map(|case| errors.case_params(case)).transpose())
        .collect::<Result<_, _>>()?;
    let setup = Rows {
        gearing: &g,
        file: &file,
        tooth_height: h,
        clearance,
        hypothesis: errors.hypothesis,
        rule: &rule,
        rows: rows.iter().map(|r| r.draws).zip(params.clone()).collect(),
    };
    let train = setup.train(LUNAR)?;

    // (a) The anomaly from the geometry.
    let anomaly = anomaly(&train, curve_samples);

    // (b) TD statistics, ideal teeth and Cases A-D, without and with the pin-and-slot.
    let seed = run.seed();
    let typed = (file.as_str(), s.errors.errors.hypothesis.as_str());
    let key = batch_key(typed, &rows, &params, trials, h, clearance, turns, samples);
    let results = setup.trials(run.engine(), &key, LUNAR, (turns, samples), trials as u64)?;
    let rows = rows
        .iter()
        .zip(results.chunks(trials))
        .map(|(row, t)| AnomalyRow {
            label: row.label.clone(),
            trials: t.to_vec(),
        })
        .collect();

    // (c) The anomaly over two anomalistic months, and one Case B trajectory.
    let (ideal_curve, simulated) = anomaly_curves(&setup, &train, seed, curve_samples)?;
    Ok(Results {
        anomaly,
        seed,
        clearance,
        turns,
        rows,
        ideal_curve,
        simulated,
    })
}

/// (b)'s rows: ideal teeth, then Cases A-D, each with its stream.
fn rows() -> Vec<Row> {
    let mut rows = vec![Row {
        label: "ideal teeth".into(),
        draws: Draws::IdealMechanism,
        case: None,
    }];
    for &(case, systematic, random) in &CASES {
        rows.push(Row {
            label: format!("Case {case}"),
            draws: Draws::Case(case),
            case: Some((systematic, random)),
        });
    }
    rows
}

/// The tables, the plot and the CSV files, drawn from the results.
fn tables(s: &Settings, r: &Results) -> Result<Report, RunError> {
    let tables = vec![
        anomaly_table(&r.anomaly),
        td_table(&r.rows, s.trials, r.seed, r.clearance, r.turns),
    ];
    let (svg, curve_csv) = anomaly_plot(&r.ideal_curve, &r.simulated)?;
    Ok(Report {
        tables,
        files: vec![
            OutputFile::new("lunar-anomaly.svg", svg),
            OutputFile::new("lunar-anomaly-curve.csv", curve_csv),
            OutputFile::new("lunar-anomaly-td.csv", td_csv(&r.rows)),
        ],
        // Mechanisms built: one per (row, trial), each run twice.
        trials: r.rows.iter().map(|row| row.trials.len() as u64).sum(),
        ..Default::default()
    })
}

/// (c): the anomaly over two anomalistic months from the geometry, and the first trial of
/// Case B with the pin-and-slot (its pointer minus the mean motion) up to its first jam: each
/// as (day of b, degrees).
fn anomaly_curves(
    setup: &Rows<'_>,
    train: &PinSlotTrain,
    seed: u64,
    curve_samples: usize,
) -> Result<(Curve, Curve), RunError> {
    let period = train.anomaly_period();
    let days_per_radian = DAYS_PER_YEAR / std::f64::consts::TAU;
    let points = 2 * curve_samples;
    let xs: Vec<f64> = (0..=points)
        .map(|i| 2.0 * period * i as f64 / points as f64)
        .collect();
    let ideal_curve: Vec<(f64, f64)> = xs
        .iter()
        .map(|&psi| (psi * days_per_radian, train.anomaly(psi).to_degrees()))
        .collect();
    let plotted = CASES
        .iter()
        .position(|c| c.0 == PLOTTED_CASE)
        .ok_or_else(|| RunError::Internal(format!("Case {PLOTTED_CASE}")))?;
    let months = 2.0 * train.anomaly_period_turns();
    let traj = setup.trajectory(seed, (plotted + 1, 0), LUNAR, months)?;
    let end = traj
        .first_stop()
        .map_or(traj.input_range, |s| s.input_angle);
    let simulated: Vec<(f64, f64)> = xs
        .iter()
        .filter(|&&psi| psi <= end)
        .map(|&psi| {
            (
                psi * days_per_radian,
                (traj.pointer_angle(psi) - train.mean_ratio() * psi).to_degrees(),
            )
        })
        .collect();
    Ok((ideal_curve, simulated))
}

/// (c): the plot of both curves, and its CSV.
fn anomaly_plot(
    ideal_curve: &[(f64, f64)],
    simulated: &[(f64, f64)],
) -> Result<(String, String), RunError> {
    let legend_sim = format!(
        "Case {PLOTTED_CASE}, trial 0, triangular teeth, with the pin-and-slot: pointer minus mean motion"
    );
    let svg = line_plot(
        "The pin-and-slot's lunar anomaly on the Lunar pointer (Freeth 2006 geometry; beyond the paper)",
        "days of b",
        "Lunar pointer minus its mean motion [deg]",
        &[
            Series {
                label: "ideal gears: the anomaly from the geometry",
                points: ideal_curve.to_vec(),
            },
            Series {
                label: &legend_sim,
                points: simulated.to_vec(),
            },
        ],
    )?;
    let curve_csv = csv(
        &["day", "ideal_anomaly_deg", "case_b_trial0_deviation_deg"],
        ideal_curve
            .iter()
            .enumerate()
            .map(|(i, &(d, a))| vec![d, a, simulated.get(i).map_or(f64::NAN, |s| s.1)]),
        6,
    );
    Ok((svg, curve_csv))
}

/// The key of the trial batch: everything that determines the trials; `typed` is the gearing
/// and the hypothesis as typed.
#[allow(
    clippy::too_many_arguments,
    reason = "one key from every input, spelt out"
)]
fn batch_key(
    (gearing, hypothesis): (&str, &str),
    rows: &[Row],
    params: &[Option<hypotheses::Params>],
    trials: usize,
    h: f64,
    clearance: f64,
    turns: f64,
    samples: usize,
) -> String {
    let rows: Vec<String> = rows
        .iter()
        .zip(params)
        .map(|(r, p)| {
            let p = p.as_ref().map_or_else(String::new, |p| {
                p.iter()
                    .map(|(k, v)| format!("{k}={v}"))
                    .collect::<Vec<_>>()
                    .join(",")
            });
            format!("{} stream {} ({p})", r.label, r.draws)
        })
        .collect();
    format!(
        "lunar-anomaly: {trials} trials per row, Lunar {turns} turns {samples} samples, h = {h} mm, G = {clearance} %, gearing {gearing}, hypothesis {hypothesis}, rows: {}",
        rows.join("; ")
    )
}

/// (a): the anomaly from the geometry: amplitude sampled over one period (`curve_samples`
/// points) and in closed form, the periods.
fn anomaly(train: &PinSlotTrain, curve_samples: usize) -> Anomaly {
    let period = train.anomaly_period();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=curve_samples {
        let a = train.anomaly(period * i as f64 / curve_samples as f64);
        lo = lo.min(a);
        hi = hi.max(a);
    }
    Anomaly {
        offset: train.offset,
        pin_radius: train.pin_radius,
        lead: hi,
        lag: lo,
        amplitude: train.pointer_amplitude(),
        period_days: train.anomaly_period_turns() * DAYS_PER_YEAR,
        turntable_years: 1.0 / train.turntable_ratio,
    }
}

/// (a): amplitude (sampled over one period and in closed form), periods, and the paper's value.
fn anomaly_table(a: &Anomaly) -> Table {
    let mut t = Table::new(
        "The anomaly from the geometry: the Lunar pointer's ideal motion with the pin-and-slot, minus its mean motion",
        ["quantity", "ours", "unit", "paper"],
    );
    t.row(vec![
        "axes apart e / pin radius R (gearing data)".into(),
        format!("{} / {}", fmt_f64(a.offset, 2), fmt_f64(a.pin_radius, 2)),
        "mm".into(),
        "-".into(),
    ]);
    t.row(vec![
        "largest lead of the pointer over its mean motion (sampled)".into(),
        fmt_f64(a.lead.to_degrees(), 3),
        "deg".into(),
        paper_cell("lunar-anomaly", "amplitude", 2),
    ]);
    let mut quantity = |q: &str, v: f64, unit: &str| {
        t.row(vec![q.into(), fmt_f64(v, 3), unit.into(), "-".into()]);
    };
    quantity("largest lag (sampled)", a.lag.to_degrees(), "deg");
    quantity(
        "amplitude asin(e/R) on the pointer (closed form)",
        a.amplitude.to_degrees(),
        "deg",
    );
    quantity(
        "period of the anomaly (anomalistic month)",
        a.period_days,
        "days",
    );
    quantity(
        "one turn of the turntable (apsidal line)",
        a.turntable_years,
        "years",
    );
    t.note("Ideal gears, the turntable at its mean rate from the gear ratios (b2-l1, l2-m1, m3-e3), the pin on the line of centres at the start; the anomaly is computed from the gearing file's pin_and_slot section, not typed in.");
    t.note("Paper: section 3 quotes the anomaly's angular variation as +-6.53 deg (Freeth et al. 2006) and compares it with Table 1; the paper itself leaves the pin-and-slot out.");
    t
}

/// `mean [lo .. hi]` of an estimate.
fn show(e: &Estimate) -> String {
    presentation::common::estimate(e, 3)
}

/// (b): per row, sigma, Dm and P without and with the pin-and-slot, and the paired difference.
fn td_table(rows: &[AnomalyRow], trials: usize, seed: u64, clearance: f64, turns: f64) -> Table {
    let mut t = Table::new(
        format!(
            "Lunar pointer TD, triangular teeth, G = {clearance} %, {turns} turn(s) of b, {trials} trials per row, seed {seed}: mean and 95 % interval over trials [deg]"
        ),
        [
            "errors",
            "statistic",
            "without the pin-and-slot (paper)",
            "with the pin-and-slot",
            "with minus without",
            "trials that jammed (without / with)",
        ],
    );
    for row in rows {
        let trials_of = &row.trials;
        let jams = |f: fn(&AnomalyTrial) -> bool| trials_of.iter().filter(|x| f(x)).count();
        let jammed = format!(
            "{}/{trials} / {}/{trials}",
            jams(|x| x.rigid.jammed),
            jams(|x| x.pin_slot.jammed)
        );
        for (name, f) in [
            ("sigma", (|s: &RunStats| s.sigma) as fn(&RunStats) -> f64),
            ("Dm", |s: &RunStats| s.dm),
            ("P", |s: &RunStats| s.p),
        ] {
            let without: Vec<f64> = trials_of.iter().map(|x| f(&x.rigid)).collect();
            let with: Vec<f64> = trials_of.iter().map(|x| f(&x.pin_slot)).collect();
            let diff: Vec<f64> = with.iter().zip(&without).map(|(a, b)| a - b).collect();
            t.row(vec![
                row.label.clone(),
                name.into(),
                show(&mean_ci95(&without)),
                show(&mean_ci95(&with)),
                show(&mean_ci95(&diff)),
                jammed.clone(),
            ]);
        }
    }
    t.note("Each trial: one set of gears (Cases: Edmunds' errors, as table2 draws them from the same streams) and one set of initial angles, run without the pin-and-slot (k1 -> k2 rigid, turntable still: the paper) and with it (e5-k1 and k2-e6 in the frame of the e3 turntable turning at its mean rate, k1's pin in k2's slot).");
    t.note("With the pin-and-slot the TD is taken against the anomaly-bearing ideal motion, so it holds only what the teeth add; P is the absolute oscillation mean. A jam stops the pointer: a trial that jammed is measured up to its first jam.");
    t
}

/// Every trial's statistics, per row and configuration.
fn td_csv(rows: &[AnomalyRow]) -> String {
    let mut out = String::from("errors,trial,pin_and_slot,sigma_deg,dm_deg,p_deg,jammed\n");
    for row in rows {
        for (t, x) in row.trials.iter().enumerate() {
            for (on, s) in [(false, x.rigid), (true, x.pin_slot)] {
                out.push_str(&registry::csv_row!(
                    row.label, t, on, s.sigma, s.dm, s.p, s.jammed
                ));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    fn run_with(threads: usize, sets: &[(&str, &str)]) -> Result<Report, RunError> {
        crate::run("lunar-anomaly", 7, threads, sets)
    }

    const SMALL: &[(&str, &str)] = &[
        ("trials", "2"),
        ("lunar_turns", "0.1"),
        ("samples_per_engagement", "2"),
        ("curve_samples", "200"),
    ];

    #[test]
    fn identical_with_one_and_two_threads() {
        let a = run_with(1, SMALL).unwrap();
        let b = run_with(2, SMALL).unwrap();
        assert_eq!(a.text(), b.text());
        assert!(a.text().contains("6.579"), "{}", a.text());
    }

    #[test]
    fn bad_parameters_are_refused_as_bad_input() {
        for (k, v) in [
            ("trials", "1"),
            ("curve_samples", "10"),
            ("lunar_turns", "0"),
        ] {
            let mut sets = SMALL.to_vec();
            sets.push((k, v));
            let e = run_with(1, &sets).unwrap_err();
            assert!(matches!(e, RunError::BadInput { .. }), "{k}={v}: {e}");
        }
    }
}
