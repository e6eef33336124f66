//! `cosmos`: beyond the paper, the cosmos display of Freeth et al. 2021 (and, beside it, Freeth
//! & Jones 2012) through the paper's tests: each output's exact period relation; each planet's
//! pointer with ideal triangular teeth and Edmunds' Cases A-D, before and after its
//! pin-and-slot device; the cosmos meshes that limit it (their largest tolerable errors, Tables
//! 4-5's rule); the whole mechanism's first jams with the cosmos trains; the two designs side by
//! side; and a picture of each cosmos train coloured by its meshes' tolerances.
//!
//! Settings in, one call to `study::cosmos::compute`, its results (`study::cosmos::Results`)
//! stored; the tables and pictures drawn from them.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::interval;
use setting_groups::typed::label;
use study::cosmos::{self, DisplayRow, GearingResults, Interval, MeshTolerance, Results};
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing;
use study::tolerance::{RULE, RandomGrid, SystematicGrid};
use study::whole_mechanism::{CASES_PARAM, DAYS, RUNS_DEFAULT, parse_cases};

registry::params! {
    /// `gearings`: the cosmos gearings to run, comma-separated.
    const GEARINGS = Param::new("gearings", "freeth2021-cosmos,freeth2012-cosmos", "cosmos gearings, comma-separated (embedded names or RON files); the first two are compared", registry::Kind::Text);
    /// `display_trials`: trials per planet, input and run length.
    const DISPLAY_TRIALS = Param::new("display_trials", "10", "trials of each planet's pointer per input (ideal, Cases) and run length", registry::Kind::count(2, registry::MAX_TRIALS, "two trials at least, for an interval"));
    /// `period_cap`: the longest run over a period relation, years.
    const PERIOD_CAP = Param::new("period_cap", "500", "each planet's second run covers its period relation (Venus 462 years), or at most this many years", registry::Kind::number(1.0, 1000.0, "years of b"));
    /// `samples_per_engagement`: TD samples per tooth engagement of the busiest mesh.
    const SAMPLES = study::pointers::per_engagement("8", "TD samples per engagement of the busiest mesh of a train");
    /// `cell_trials`: trials per cell of the tolerance grids.
    const CELL_TRIALS = Param::new("cell_trials", "200", "trials per cell of the tolerance grids (Tables 4-5: 200)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
    /// `runs`: whole mechanisms per Case.
    const RUNS = Param::new("runs", RUNS_DEFAULT, "whole-mechanism runs per Case (the paper's study: 30)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
}

/// The cosmos study's settings: the gearings, the display trials and run lengths, the
/// tolerance grids with their trials and rule, the whole-mechanism runs with their horizon and
/// Cases, G and h, the Cases' errors and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// The cosmos gearings, comma-separated ([`GEARINGS`]).
    #[param(GEARINGS)]
    pub gearings: String,
    /// Trials per planet, input and run length ([`DISPLAY_TRIALS`]).
    #[param(DISPLAY_TRIALS)]
    pub display_trials: u64,
    /// The longest run over a period relation, years ([`PERIOD_CAP`]).
    #[param(PERIOD_CAP)]
    pub period_cap: f64,
    /// TD samples per engagement of a train's busiest mesh ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples_per_engagement: usize,
    /// Trials per cell of the tolerance grids ([`CELL_TRIALS`]).
    #[param(CELL_TRIALS)]
    pub cell_trials: u64,
    /// Whole-mechanism runs per Case ([`RUNS`]).
    #[param(RUNS)]
    pub runs: u64,
    /// The tolerance rule, % of trials jamming ([`RULE`]).
    #[param(RULE)]
    pub rule: f64,
    /// Horizon of each whole-mechanism run, days of b ([`DAYS`]).
    #[param(DAYS)]
    pub days: f64,
    /// Edmunds' Cases to run, comma-separated ([`CASES_PARAM`]).
    #[param(CASES_PARAM)]
    pub cases: String,
    /// Clearance G of every mesh, % of h ([`gearing::CLEARANCE`]).
    #[param(gearing::CLEARANCE)]
    pub clearance: f64,
    /// Tooth height h of every gear, mm ([`gearing::TOOTH_HEIGHT`]).
    #[param(gearing::TOOTH_HEIGHT)]
    pub tooth_height: f64,
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
}

/// The cosmos study.
pub struct Cosmos;

impl registry::Experiment for Cosmos {
    const ID: &'static str = "cosmos";
    const TITLE: &'static str = "The cosmos display with triangular teeth and Edmunds' errors: each planet's pointer, the meshes that limit it, the whole mechanism's first jams; 2021 beside 2012";
    const PAPER_ITEM: &'static str =
        "Beyond the paper: the cosmos display (Freeth et al. 2021; Freeth & Jones 2012)";
    const PLACE: Place = Place::Beyond(100);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        cosmos::compute(run.engine(), &study_settings(s)?)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, None, tables(s, r)?)
    }
}

registry::register!(Cosmos);

/// Every setting read and checked before anything runs: each gearing loaded, and refused
/// where it has no cosmos.
fn study_settings(s: &Settings) -> Result<cosmos::Settings, RunError> {
    let mut gearings = Vec::new();
    for name in s.gearings.split(',').map(str::trim) {
        // A file that cannot be read or is refused is named by the setting that gave it.
        let shape = gearing::Shape::load(name, s.tooth_height).map_err(|e| match e {
            RunError::BadInput {
                source,
                field,
                rule,
            } => RunError::bad(format!("--set gearings: {source}"), field, rule),
            other => other,
        })?;
        if shape.gearing.epicyclic().is_none() {
            return Err(RunError::bad(
                "--set gearings",
                name,
                "has no cosmos (no epicyclic section): give freeth2021-cosmos, freeth2012-cosmos or a file like them",
            ));
        }
        gearings.push(shape);
    }
    Ok(cosmos::Settings {
        gearings,
        clearance: s.clearance,
        errors: s.errors.load(s)?,
        rule: s.events.rule()?,
        display_trials: s.display_trials,
        period_cap_years: s.period_cap,
        samples_per_engagement: s.samples_per_engagement,
        cell_trials: s.cell_trials,
        grids: (s.random.values(s)?, s.systematic.values(s)?),
        rule_percent: s.rule,
        failure_runs: s.runs,
        days: s.days,
        cases: parse_cases(&s.cases)?,
    })
}

/// The tables, the pictures and the data files, drawn from the results.
fn tables(s: &Settings, r: &Results) -> Result<Report, RunError> {
    let cases = parse_cases(&s.cases)?;
    let grids = (s.random.values(s)?, s.systematic.values(s)?);
    let mut tables = vec![outputs_table(r)];
    tables.push(display_table(s, r, false));
    tables.push(display_table(s, r, true));
    tables.push(limiting_table(s, r, &grids));
    tables.push(failure_table(s, r));
    if !r.compared.is_empty() {
        tables.push(compared_table(s, r));
    }
    tables.push(verdict_table(s, r, &cases));
    let mut files = Vec::new();
    for g in &r.gearings {
        let stem = file_stem(&g.gearing);
        files.push(OutputFile::new(
            format!("cosmos-train-{stem}.svg"),
            presentation::cosmos_svg::train_picture(g, s.clearance),
        ));
        files.push(OutputFile::new(
            format!("cosmos-survival-{stem}.svg"),
            survival_plot(s, g)?,
        ));
    }
    Ok(Report {
        tables,
        files,
        trials: r.totals.trials,
        engagements: r.totals.engagements,
        ..Default::default()
    })
}

/// Table: each output's exact rates, from the tooth counts, and its device.
fn outputs_table(r: &Results) -> Table {
    let mut t = Table::new(
        "The cosmos's outputs: exact rates from the tooth counts (turns a year), devices from their pins",
        [
            "gearing",
            "output",
            "device",
            "device input, relative to b1",
            "period relation [years]",
            "mean rate",
            "device's largest swing [deg]",
            "pin / offset [mm]",
        ]
        .map(String::from)
        .to_vec(),
    );
    for g in &r.gearings {
        for o in &g.outputs {
            t.row(vec![
                g.gearing.clone(),
                o.name.clone(),
                o.device.clone(),
                o.synodic.clone().unwrap_or_else(|| "-".into()),
                o.period_years.to_string(),
                o.rate.clone(),
                o.amplitude_deg
                    .map_or_else(|| "-".into(), |a| fmt_f64(a, 2)),
                o.pin_mm
                    .map_or_else(|| "-".into(), |(p, e)| format!("{p} / {e}")),
            ]);
        }
    }
    t.note("Device input: the synodic rate (the epicycle's or the pin gear's turns relative to b1; the true Sun's epicycle -1, so it keeps its orientation). Mean rate: in the frame of the mechanism, b1's one turn a year added; a follower swings about b1, so its mean is 1. Period relation: the years after which the device input (or, without a device, the output) repeats, the denominator of its exact rate. Largest swing: a follower's greatest elongation asin(pin / offset), a slot gear's equation asin(offset / pin).");
    t.note("Every rate is composed exactly from the gearing file's tooth counts (crates/train/tests/cosmos.rs checks each against its source's period relation); the Moon phase is the Moon pointer's rate less the mean Sun's through its 20:20 crown gear.");
    t
}

/// A mean with its interval, or `-` where there is none.
fn mean_cell(i: &Interval, decimals: usize) -> String {
    match i.n {
        0 => "-".into(),
        1 => fmt_f64(i.mean, decimals),
        _ => interval(i.mean, i.lo, i.hi, decimals),
    }
}

/// Table: each planet's pointer under each input, over a year (`period` false) or its period
/// relation.
fn display_table(s: &Settings, r: &Results, period: bool) -> Table {
    let what = if period {
        format!(
            "over its period relation (at most {} years)",
            fmt_f64(s.period_cap, 0)
        )
    } else {
        "over a year".into()
    };
    let mut t = Table::new(
        format!(
            "Each planet's pointer {what}: σ, Dm, P of its Theoretical Difference [deg], ideal triangular teeth and Edmunds' Cases, {} trials, G = {} %",
            s.display_trials,
            fmt_f64(s.clearance, 0)
        ),
        [
            "gearing",
            "planet",
            "input",
            "years",
            "jammed",
            "σ train alone",
            "σ shown",
            "Dm shown",
            "P shown",
            "device ×",
        ]
        .map(String::from)
        .to_vec(),
    );
    for g in &r.gearings {
        for d in g.display.iter().filter(|d| d.period == period) {
            t.row(display_cells(g, d));
        }
    }
    t.note("σ train alone: the gear train's TD without its device (a slot gear rigid on its pin gear; the pin gear itself where a follower follows it). σ, Dm, P shown: the pointer through its device, against the device's own ideal output (the anomaly is no error). Device ×: σ shown / σ train alone, what the pin-and-slot multiplies the train's tooth error by (a follower amplifies it near inferior conjunction by up to offset / (offset - pin), a slot gear by up to pin / (pin - offset)). Means over trials [95 % interval]; a jammed train's statistics run up to its jam, as Table 2's; jammed: trials whose train jammed within the run.");
    t.note("Each trial: the gears made once (Case errors, Edmunds' split model) and every planet run on them in turn from random initial angles; a follower's pin starts at a random phase, a slot gear's on the line of centres.");
    t
}

fn display_cells(g: &GearingResults, d: &DisplayRow) -> Vec<String> {
    vec![
        g.gearing.clone(),
        d.planet.clone(),
        d.input.clone(),
        fmt_f64(d.years, 0),
        format!("{} of {}", d.jammed, d.trials),
        mean_cell(&d.train_sigma, 3),
        mean_cell(&d.sigma, 3),
        mean_cell(&d.dm, 3),
        mean_cell(&d.p, 3),
        if d.gain.is_finite() {
            fmt_f64(d.gain, 2)
        } else {
            "-".into()
        },
    ]
}

/// Table: every cosmos mesh's tolerances, least tolerant first.
fn limiting_table(s: &Settings, r: &Results, grids: &(Vec<f64>, Vec<f64>)) -> Table {
    let mut t = Table::new(
        format!(
            "The meshes that limit the cosmos: each mesh's largest tolerable random error (Table 4's grid), then systematic error on top of it (Table 5's), rule {} %, {} trials per cell, G = {} %, least tolerant first",
            fmt_f64(s.rule, 0),
            s.cell_trials,
            fmt_f64(s.clearance, 0)
        ),
        [
            "gearing",
            "mesh",
            "pointers",
            "teeth",
            "stated margin [mm]",
            "E. max random [pitch]",
            "[deg] driver / driven",
            "[mm of tip] driver / driven",
            "E. max systematic [deg]",
            "eccentricity [mm] driver / driven",
            "Table 3's cells, jams/disengagements",
        ]
        .map(String::from)
        .to_vec(),
    );
    for g in &r.gearings {
        for m in g.limiting() {
            t.row(limiting_cells(&g.gearing, m, grids));
        }
    }
    t.note("E. max random: the largest value of the grid up to which every value keeps the rule (`<` the grid's first: even that fails); in degrees of each gear (fraction × 360 / N) and as the tip's displacement (fraction × 2π R / N). E. max systematic: the same on the systematic grid at that random error, split as the paper splits it; the eccentricity is the share on the axis, R tan((1 - split) A). Stated margin: the centre-distance margin over the pitch radii the gearing's source gives (the runs use G). Table 3's cells: each Case at G (trials as the grids'), `✓` where the cell keeps the rule.");
    t
}

/// A pair of numbers `a / b`.
fn pair(p: Option<(f64, f64)>, decimals: usize) -> String {
    p.map_or_else(
        || "-".into(),
        |(a, b)| format!("{} / {}", fmt_f64(a, decimals), fmt_f64(b, decimals)),
    )
}

fn limiting_cells(gearing: &str, m: &MeshTolerance, grids: &(Vec<f64>, Vec<f64>)) -> Vec<String> {
    let below = |grid: &[f64], decimals| {
        grid.first()
            .map_or_else(|| "-".into(), |v| format!("< {}", fmt_f64(*v, decimals)))
    };
    vec![
        gearing.to_owned(),
        m.mesh.clone(),
        m.pointers.join(", "),
        format!("{}:{}", m.gears.0.teeth, m.gears.1.teeth),
        m.margin_mm.map_or_else(|| "-".into(), |x| fmt_f64(x, 2)),
        m.random
            .map_or_else(|| below(&grids.0, 3), |x| fmt_f64(x, 3)),
        pair(m.random_deg, 3),
        pair(m.random_mm, 4),
        match (m.random, m.systematic) {
            (None, _) => "-".into(),
            (_, None) => below(&grids.1, 1),
            (_, Some(x)) => fmt_f64(x, 1),
        },
        pair(m.eccentricity_mm, 4),
        m.cases
            .iter()
            .map(|c| {
                let mark = if c.keeps { "✓" } else { "" };
                format!("{} {}/{}{mark}", c.case, c.jams, c.disengagements)
            })
            .collect::<Vec<_>>()
            .join(", "),
    ]
}

/// The days of b at which survival is read.
const READ_AT_DAYS: [f64; 4] = [30.0, 91.3125, 182.625, 365.25];

/// A survival share [%] at `day` with its 95 % band.
fn survival_at(curve: &[cosmos::Step], day: f64) -> String {
    curve
        .iter()
        .take_while(|p| p.day <= day)
        .last()
        .map_or_else(|| "100".into(), |p| interval(p.survival, p.lo, p.hi, 0))
}

/// Table: the whole mechanism (the back and the cosmos) per train and Case.
fn failure_table(s: &Settings, r: &Results) -> Table {
    let mut header = [
        "gearing",
        "input",
        "train",
        "jammed within the horizon",
        "mean day",
        "jammed first",
    ]
    .map(String::from)
    .to_vec();
    header.extend(
        READ_AT_DAYS
            .iter()
            .map(|d| format!("not jammed at day {} [%]", fmt_f64(*d, 0))),
    );
    let mut t = Table::new(
        format!(
            "Whole mechanisms with the cosmos: {} runs per Case, {} days of b, G = {} %, first jam per train (Kaplan-Meier with 95 % bands)",
            s.runs,
            fmt_f64(s.days, 2),
            fmt_f64(s.clearance, 0)
        ),
        header,
    );
    for g in &r.gearings {
        for f in &g.failure {
            let mut row = vec![
                g.gearing.clone(),
                f.input.clone(),
                f.train.clone(),
                format!(
                    "{} of {} [{} .. {} %]",
                    f.jammed,
                    f.runs,
                    fmt_f64(100.0 * f.share.0, 0),
                    fmt_f64(100.0 * f.share.1, 0)
                ),
                mean_cell(&f.mean_day, 0),
                presentation::common::jammed_first(&f.meshes),
            ];
            row.extend(READ_AT_DAYS.iter().map(|d| survival_at(&f.curve, *d)));
            t.row(row);
        }
    }
    t.note("One run is one mechanism: every gear made once, every mesh of the back and of the cosmos given one random initial angle, each train run to its first jam; the cosmos trains in b1's frame with their devices' rigid couplings, as the paper's study leaves the lunar pin-and-slot out (a jam falls at the same driver angle; only its day would move). Share jammed with its exact 95 % interval; survival: Kaplan-Meier, every run observed to the horizon, its band the exact interval of the share.");
    t
}

/// Table: the first two gearings' trains side by side, with Fisher's exact test.
fn compared_table(s: &Settings, r: &Results) -> Table {
    let names: Vec<&str> = r.gearings.iter().map(|g| g.gearing.as_str()).collect();
    let mut t = Table::new(
        format!(
            "{} beside {}: runs jammed within {} days per train and Case, Fisher's exact two-sided test",
            names[0],
            names[1],
            fmt_f64(s.days, 2)
        ),
        vec![
            "input".into(),
            "train".into(),
            names[0].to_owned(),
            names[1].to_owned(),
            "p".into(),
        ],
    );
    for c in &r.compared {
        let cell = |i: usize| format!("{} of {}", c.counts[i].0, c.counts[i].1);
        t.row(vec![
            c.input.clone(),
            c.train.clone(),
            cell(0),
            cell(1),
            p_value(c.p_value),
        ]);
    }
    t.note("p: Fisher's exact two-sided test of the two counts; below 0.05 the two designs' shares differ at 5 %. The paper's trains (the back) are the same gearing in both, made with the same errors but started from other initial angles (drawn after the cosmos gears' errors), so they differ by chance alone.");
    t
}

/// A file name's stem from a gearing as typed (`freeth2021-cosmos`, `my/file.ron` -> `file`).
fn file_stem(gearing: &str) -> String {
    let base = std::path::Path::new(gearing)
        .file_stem()
        .map_or_else(|| gearing.to_owned(), |s| s.to_string_lossy().into_owned());
    base.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '-' })
        .collect()
}

/// A p-value as printed: three decimals, `< 0.001` below.
fn p_value(p: f64) -> String {
    if p < 0.001 {
        "< 0.001".into()
    } else {
        fmt_f64(p, 3)
    }
}

/// Table: the verdict, computed from the tables above.
fn verdict_table(s: &Settings, r: &Results, cases: &[usize]) -> Table {
    let mut header = vec![
        "gearing".to_owned(),
        "cosmos meshes".into(),
        "limiting mesh".into(),
    ];
    let cases: Vec<(&str, f64, f64)> = cases.iter().map(|&c| study::grids::CASES[c]).collect();
    header.extend(cases.iter().map(|(c, sys, rnd)| {
        format!("meshes keeping the rule, Case {c} (random {rnd}, systematic {sys} deg)")
    }));
    header.extend(
        cases
            .iter()
            .map(|(c, _, _)| format!("mechanism jammed, Case {c}")),
    );
    let mut t = Table::new(
        format!(
            "Would the display have run? The cosmos meshes that keep the paper's rule under each of Edmunds' Cases (Table 3's cells, {} trials each, G = {} %), and the whole mechanism's runs jammed within the horizon",
            s.cell_trials,
            fmt_f64(s.clearance, 0)
        ),
        header,
    );
    for g in &r.gearings {
        t.row(verdict_cells(g, &cases));
    }
    t.note(format!(
        "A mesh keeps the rule under a Case when at most {} % of its trials (Table 3's protocol: both gears made afresh, one turn of the larger) jam and at most as many disengage. Edmunds' Cases A-D are the range of his measurements the paper runs (random 0.04-0.08 of the pitch, systematic 0-2 deg). The limiting mesh is the least tolerant of the table above; mechanism jammed: the whole mechanism (the back and the cosmos) within the horizon.",
        fmt_f64(s.rule, 0)
    ));
    t
}

fn verdict_cells(g: &GearingResults, cases: &[(&str, f64, f64)]) -> Vec<String> {
    let limiting = g.limiting().first().map_or_else(
        || "-".into(),
        |m| {
            format!(
                "{} (random {}, systematic {})",
                m.mesh,
                m.random
                    .map_or_else(|| "below the grid".into(), |x| fmt_f64(x, 3)),
                m.systematic
                    .map_or_else(|| "below the grid".into(), |x| fmt_f64(x, 1))
            )
        },
    );
    let mut row = vec![g.gearing.clone(), g.meshes.len().to_string(), limiting];
    for &(c, _, _) in cases {
        let of_case = |m: &&MeshTolerance| m.cases.iter().any(|x| x.case == c && x.keeps);
        let ok: Vec<&str> = g
            .meshes
            .iter()
            .filter(of_case)
            .map(|m| m.mesh.as_str())
            .collect();
        let failing: Vec<&str> = g
            .meshes
            .iter()
            .filter(|m| !of_case(m))
            .map(|m| m.mesh.as_str())
            .collect();
        row.push(match failing.len() {
            0 => format!("all {}", ok.len()),
            n if n <= 3 => format!(
                "{} of {} (not {})",
                ok.len(),
                g.meshes.len(),
                failing.join(", ")
            ),
            _ => format!("{} of {}", ok.len(), g.meshes.len()),
        });
    }
    for &(c, _, _) in cases {
        let cell = g
            .failure
            .iter()
            .find(|f| {
                f.train == study::whole_mechanism::MECHANISM && f.input == format!("Case {c}")
            })
            .map_or_else(|| "-".into(), |f| format!("{} of {}", f.jammed, f.runs));
        row.push(cell);
    }
    row
}

/// The whole mechanism's survival per Case (one curve each), for one gearing.
fn survival_plot(s: &Settings, g: &GearingResults) -> Result<String, RunError> {
    let curves: Vec<(String, Vec<(f64, f64)>)> = g
        .failure
        .iter()
        .filter(|f| f.train == study::whole_mechanism::MECHANISM)
        .map(|f| {
            let steps: Vec<stats::Step> = f
                .curve
                .iter()
                .map(|k| stats::Step {
                    day: k.day,
                    survival: k.survival,
                    lo: k.lo,
                    hi: k.hi,
                })
                .collect();
            (f.input.clone(), stats::step_points(&steps, s.days))
        })
        .collect();
    let series: Vec<presentation::common::Series<'_>> = curves
        .iter()
        .map(|(label, points)| presentation::common::Series {
            label,
            points: points.clone(),
        })
        .collect();
    presentation::common::Plot::new(
        &format!(
            "{}: whole mechanisms with the cosmos, {} runs per Case, runs not yet jammed (Kaplan-Meier)",
            g.gearing, s.runs
        ),
        "days of the b arbor (solar pointer; 365.25 d per turn)",
        "runs not yet jammed [%]",
        &series,
    )
    .ranges((0.0, s.days), (0.0, 102.0))
    .whole_ticks()
    .svg()
}
