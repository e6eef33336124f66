//! `sensitivity`: how the headline numbers move when one of the paper's assumptions is changed:
//! the share of Case B mechanisms jamming within a year, the day of the first jam and the Lunar
//! pointer's σ, for each assumption of section 6 that a plugin relaxes ((1), (2), (3), (5)), the
//! tooth height and the Freeth 2021 radii.
//!
//! Every row is the `failure` study of Case B (its runs, horizon and clearance), with one thing
//! changed. A shape hypothesis is applied to each gear after Edmunds' errors (the tips are
//! displaced first, then, say, the valleys), drawing from a stream of its own. Trial t of every
//! row draws Edmunds' errors and the initial angles from the stream `failure` gives Case B's
//! trial t, so every row runs the same mechanisms, changed only by its assumption: the rows
//! differ by the assumption, not by luck in the draws (common random numbers).

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::mean_ci95;
use train::Gearing;

use presentation::common::{Series, category_plot};
use presentation::common::{mean_day_cell, percent_cell};
use setting_groups::typed::label;
use study::errors;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::grids::CASES;
use study::results::{FailureRun, TrainSummary};
use study::whole_mechanism::{self as whole, Clearances, Input, TRAINS};

registry::params! {
    /// `trials`: whole-mechanism runs per row (the paper's failure study: 30).
    const TRIALS = Param::new("trials", "60", "whole-mechanism runs per row (the paper's failure study: 30)", registry::Kind::count(2, registry::MAX_TRIALS, "an interval needs two runs")).recorded();
    /// `case`: Edmunds' case every row starts from (A, B, C or D).
    const CASE = Param::new("case", "B", "Edmunds' case every row starts from (A, B, C or D)", registry::Kind::Text);
}

/// The sensitivity study's settings: runs per row, the horizon, the Case and the split every
/// row starts from, the base hypothesis, the gearing with h and G, and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Whole-mechanism runs per row ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// Horizon of each run, days of b ([`whole::DAYS`]).
    #[param(whole::DAYS)]
    pub days: f64,
    /// Edmunds' Case every row starts from ([`CASE`]).
    #[param(CASE)]
    pub case: String,
    /// Share of the systematic error on the sinusoid ([`errors::SPLIT`]).
    #[param(errors::SPLIT)]
    pub split: f64,
    /// The hypothesis that makes every row's gears first ([`errors::PARAM`]).
    #[param(errors::PARAM)]
    pub hypothesis: String,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// What the rows measured: the Case they start from, the seed their draws come from, and each
/// row's runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// The Case every row starts from, as Edmunds names it (`A`-`D`).
    pub case: String,
    /// The seed of the run (every row draws trial t's errors and angles from it alike).
    pub seed: u64,
    /// One per row of the table, in its order.
    pub rows: Vec<RowResults>,
}

/// One row: the paper's model with one thing changed, its runs and what they show.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RowResults {
    /// Which assumption it changes: the paper's numbering in section 6, or the model input.
    pub assumption: String,
    /// What it is changed to, with its values.
    pub variant: String,
    /// The hypotheses applied to each gear, in order.
    pub hypotheses: String,
    /// Tooth height h of its gears, mm.
    pub tooth_height: f64,
    /// Whether the row changes the gears' shape or h (the table then names h beside the
    /// hypotheses).
    pub shape_changed: bool,
    /// Every run, in trial order.
    pub runs: Vec<FailureRun>,
    /// Per train, then the mechanism (a jam in any train): what the runs show.
    pub trains: Vec<TrainSummary>,
}

/// The sensitivity study.
pub struct Sensitivity;

impl registry::Experiment for Sensitivity {
    const ID: &'static str = "sensitivity";
    const TITLE: &'static str = "How the Case B failure study moves when one assumption of the paper is changed (beyond the paper)";
    const PAPER_ITEM: &'static str = "Section 6, assumptions (1)-(5)";
    const PLACE: Place = Place::Beyond(40);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        let base_gearing = s.gearing.load()?;
        let case = s.case.trim();
        let Some(ci) = CASES.iter().position(|c| c.0.eq_ignore_ascii_case(case)) else {
            return Err(RunError::bad(
                "--set",
                CASE.name,
                format!("unknown case `{case}` (known: A, B, C, D)"),
            ));
        };
        let (case, systematic, random) = CASES[ci];
        let base = errors::lookup(&s.hypothesis)?;
        let rule = s.events.rule()?;
        let embedded = embedded_gearings()?;
        let base_params = case_params(base, [random, systematic, s.split])?;
        let mut rows = Vec::with_capacity(VARIANTS.len());
        for v in VARIANTS {
            let g = match v.gearing {
                Some(name) => embedded
                    .iter()
                    .find(|(n, _)| *n == name)
                    .map(|(_, g)| g)
                    .ok_or_else(|| RunError::Internal(format!("gearing {name}")))?,
                None => &base_gearing.gearing,
            };
            let start = Start {
                case: (ci, case),
                base,
                params: &base_params,
            };
            rows.push(run_row(s, run, &base_gearing, g, v, &start, &rule)?);
        }
        Ok(Results {
            case: case.to_string(),
            seed: run.seed(),
            rows,
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let runs = r.rows.iter().flat_map(|row| &row.runs);
        let mut report = Report {
            trials: r.rows.iter().map(|row| row.runs.len() as u64).sum(),
            engagements: runs.map(|o| o.engagements).sum::<f64>().round() as u64,
            ..Default::default()
        };
        report.tables.push(headline_table(s, r));
        report.files.push(OutputFile::new(
            "sensitivity-share.svg",
            share_plot(r, &r.case)?,
        ));
        label(&s.events, None, report)
    }
}

registry::register!(Sensitivity);

/// One row: the paper's model with one thing changed.
struct Variant {
    /// Which assumption it changes: the paper's numbering in section 6, or the model input.
    assumption: &'static str,
    /// What it is, with its values.
    label: &'static str,
    /// A hypothesis applied after the case's errors, with its parameters.
    plugin: Option<(&'static str, &'static [(&'static str, f64)])>,
    /// Tooth height h [mm] instead of the `tooth_height` parameter.
    tooth_height: Option<f64>,
    /// An embedded gearing instead of the `gearing` parameter.
    gearing: Option<&'static str>,
}

const fn plain(assumption: &'static str, label: &'static str) -> Variant {
    Variant {
        assumption,
        label,
        plugin: None,
        tooth_height: None,
        gearing: None,
    }
}

const fn with_plugin(
    assumption: &'static str,
    label: &'static str,
    name: &'static str,
    set: &'static [(&'static str, f64)],
) -> Variant {
    Variant {
        plugin: Some((name, set)),
        ..plain(assumption, label)
    }
}

/// The rows, the paper's assumptions first. Plugin values are written out here (not taken from
/// the plugins' defaults) so that a changed default cannot silently move this table.
const VARIANTS: &[Variant] = &[
    plain("-", "as the paper assumed"),
    with_plugin(
        "(1) circular gears",
        "non-circular: radial error 0.02 mm per tip and valley",
        "non-circular",
        &[("radial_error", 0.02), ("lobe", 0.0)],
    ),
    with_plugin(
        "(1) circular gears",
        "non-circular: radial error 0.05 mm and a 0.05 mm lobe",
        "non-circular",
        &[("radial_error", 0.05), ("lobe", 0.05)],
    ),
    with_plugin(
        "(2) straight flanks",
        "curved flanks: convex, sagitta 0.05 mm",
        "curved-flanks",
        &[("sagitta", 0.05), ("sagitta_spread", 0.0)],
    ),
    with_plugin(
        "(2) straight flanks",
        "curved flanks: concave, sagitta 0.05 mm",
        "curved-flanks",
        &[("sagitta", -0.05), ("sagitta_spread", 0.0)],
    ),
    with_plugin(
        "(3) symmetric teeth",
        "asymmetric teeth: valley shift 0.05 of the tip gap",
        "asymmetric-teeth",
        &[("valley_shift", 0.05)],
    ),
    with_plugin(
        "(3) symmetric teeth",
        "asymmetric teeth: valley shift 0.10 of the tip gap",
        "asymmetric-teeth",
        &[("valley_shift", 0.10)],
    ),
    with_plugin(
        "(5) R1/R2 = N1/N2",
        "ratio mismatch: module spread 1 %",
        "ratio-mismatch",
        &[("module_spread", 1.0)],
    ),
    with_plugin(
        "(5) R1/R2 = N1/N2",
        "ratio mismatch: module spread 3.3 % (meshing gears 3.7 % apart on average)",
        "ratio-mismatch",
        &[("module_spread", 3.3)],
    ),
    Variant {
        tooth_height: Some(0.8),
        ..plain("tooth height 1.1 mm", "tooth height 0.8 mm")
    },
    Variant {
        tooth_height: Some(1.4),
        ..plain("tooth height 1.1 mm", "tooth height 1.4 mm")
    },
    Variant {
        gearing: Some("freeth2021"),
        ..plain(
            "Freeth 2006 radii",
            "Freeth 2021 radii (Table S8 outer radii, embedded freeth2021)",
        )
    },
];

/// What every row starts from: the Case (its index in `CASES` and its name), the base
/// hypothesis and its parameters at the Case's errors.
struct Start<'a> {
    case: (usize, &'static str),
    base: &'static dyn hypotheses::Hypothesis,
    params: &'a hypotheses::Params,
}

/// One row's runs: the Case's mechanisms on gearing `g` with `v`'s change.
fn run_row(
    s: &Settings,
    run: &Run,
    base: &study::gearing::Settings,
    g: &Gearing,
    v: &Variant,
    start: &Start<'_>,
    rule: &rules::Rule,
) -> Result<RowResults, RunError> {
    let (trials, days, clearance) = (s.trials, s.days, base.clearance);
    let (ci, case) = start.case;
    let extra = row_hypothesis(v)?;
    let hypotheses = match &extra {
        Some((h, _)) => format!("{}, then {}", start.base.name(), h.name()),
        None => start.base.name().to_string(),
    };
    let h = v.tooth_height.unwrap_or(base.tooth_height);
    whole::check_study(g, h, &Clearances::Uniform(clearance))?;
    // The legend names the row, so every row is its own batch.
    let input = Input {
        label: case.to_string(),
        legend: format!("Case {case}, {}", v.label),
        // Case `ci`'s streams, as in `failure`: the same Edmunds draws in every row.
        index: ci as u64,
        source: "--hypothesis",
        hypothesis: start.base,
        params: start.params.clone(),
        clearances: Clearances::Uniform(clearance),
        pin_and_slot: false,
        extra,
    };
    let inputs = std::slice::from_ref(&input);
    let key = whole::batch_key(&base.file, inputs, trials, h, clearance, days)?;
    let outcomes = whole::run_study(run.engine(), g, inputs, trials, h, days, rule, &key)?;
    Ok(RowResults {
        assumption: v.assumption.to_string(),
        variant: v.label.to_string(),
        hypotheses,
        tooth_height: h,
        shape_changed: v.tooth_height.is_some() || v.plugin.is_some(),
        runs: outcomes.iter().map(|o| FailureRun::of(o, days)).collect(),
        trains: TrainSummary::every_train(&outcomes, days),
    })
}

/// The embedded gearings some rows use instead of the `gearing` parameter.
fn embedded_gearings() -> Result<Vec<(&'static str, Gearing)>, RunError> {
    VARIANTS
        .iter()
        .filter_map(|v| v.gearing)
        .map(|name| {
            Gearing::builtin(name)
                .map(|g| (name, g))
                .ok_or_else(|| RunError::Internal(format!("embedded gearing {name} is missing")))
        })
        .collect()
}

/// The base hypothesis' parameters: the case's values (random, systematic, split) where it
/// declares them (eccentric-only has no split).
fn case_params(
    base: &dyn hypotheses::Hypothesis,
    [random, systematic, split]: [f64; 3],
) -> Result<hypotheses::Params, RunError> {
    let case_values: Vec<(String, String)> = [
        ("random", random),
        ("systematic", systematic),
        ("split", split),
    ]
    .iter()
    .filter(|(k, _)| base.params().iter().any(|p| p.name == *k))
    .map(|(k, v)| ((*k).to_string(), v.to_string()))
    .collect();
    hypotheses::Params::new(base, &case_values)
        .map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}

/// The hypothesis a row applies after the case's errors, with its written-out values.
fn row_hypothesis(
    v: &Variant,
) -> Result<Option<(&'static dyn hypotheses::Hypothesis, hypotheses::Params)>, RunError> {
    let Some((name, set)) = v.plugin else {
        return Ok(None);
    };
    let h = hypotheses::lookup(name)
        .map_err(|e| RunError::Internal(format!("sensitivity row: {e}")))?;
    let set: Vec<(String, String)> = set
        .iter()
        .map(|(k, v)| ((*k).to_string(), v.to_string()))
        .collect();
    let p = hypotheses::Params::new(h, &set)
        .map_err(|e| RunError::Internal(format!("sensitivity row: {e}")))?;
    Ok(Some((h, p)))
}

/// The one table: per row, the share of mechanisms jammed within a year, the day of the first
/// jam and the Lunar σ.
fn headline_table(s: &Settings, r: &Results) -> Table {
    let mechanism = TRAINS.len();
    let (case, trials, days) = (&r.case, s.trials, s.days);
    let mut t = Table::new(
        format!(
            "Case {case}, G = {} %, {trials} whole-mechanism runs per row, horizon {days} d of b, seed {}: one assumption changed per row",
            s.gearing.clearance, r.seed
        ),
        [
            "assumption",
            "changed to",
            "mechanisms jammed within a year",
            "share [%] and 95 % interval",
            "day of the first jam: mean [95 % interval]",
            "median day",
            "Lunar sigma [deg]: mean [95 % interval]",
            "meshes that jammed first (runs)",
        ],
    );
    for row in &r.rows {
        let m = &row.trains[mechanism];
        let sigmas: Vec<f64> = row.runs.iter().filter_map(|o| o.lunar_sigma).collect();
        let sigma = match sigmas.len() {
            0 => "-".to_string(),
            1 => format!("{} (n = 1)", fmt_f64(sigmas[0], 3)),
            _ => presentation::common::estimate(&mean_ci95(&sigmas), 3),
        };
        let first: Vec<String> = m
            .first_meshes
            .iter()
            .map(|(mesh, n)| format!("{mesh} ({n})"))
            .collect();
        let label = if row.shape_changed {
            format!(
                "{} [h = {} mm; {}]",
                row.variant, row.tooth_height, row.hypotheses
            )
        } else {
            format!("{} [{}]", row.variant, row.hypotheses)
        };
        t.row(vec![
            row.assumption.clone(),
            label,
            format!("{}/{}", m.within_year.k, m.within_year.n),
            percent_cell(&m.within_year.proportion()),
            mean_day_cell(m.mean_day.as_ref()),
            m.median_day.map_or("-".into(), |d| fmt_f64(d, 0)),
            sigma,
            if first.is_empty() {
                "-".into()
            } else {
                first.join(", ")
            },
        ]);
    }
    t.note(format!(
        "Every row is the failure study of Case {case} with one thing changed; a shape hypothesis is applied to each gear after Edmunds' errors (in brackets: what is applied, in order), drawing from a stream of its own. Edmunds' errors and the initial angles of trial t are the same draws in every row (those of Case {case}'s trial t in `failure`, so the first row is `failure`'s Case {case} row when the run counts agree): the rows run the same mechanisms and differ only by the change."
    ));
    t.note("Share: mechanisms (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed, 95 % Student-t interval clipped to the horizon. Lunar sigma: standard deviation of the Lunar pointer's Theoretical Difference over each run up to its first jam (8 samples per engagement of the busiest mesh), mean over runs with a 95 % Student-t interval.");
    t.note("ratio-mismatch keeps every arbor where the design puts it, so a gear cut with a larger module also reaches deeper into its partner: at Freeth et al.'s 3.7 % the clearance changes by more than the tooth height on the large gears, and most such mechanisms cannot turn at all (day 0) or slip (the Lunar sigma of hundreds of degrees). A maker who set each arbor to suit the gears he had cut would keep the clearance; that reading is not modelled here.");
    t.note("Assumption (4), flat gears turning in one plane, is outside a planar model and is not varied.");
    t
}

/// Share jammed within a year per row, with its interval, as an SVG chart.
fn share_plot(r: &Results, case: &str) -> Result<String, RunError> {
    let mechanism = TRAINS.len();
    let categories: Vec<String> = (1..=r.rows.len()).map(|i| format!("row {i}")).collect();
    let (mut share, mut lo, mut hi) = (Vec::new(), Vec::new(), Vec::new());
    for (i, row) in r.rows.iter().enumerate() {
        let p = row.trains[mechanism].within_year.proportion();
        share.push((i as f64, 100.0 * p.rate()));
        lo.push((i as f64, 100.0 * p.lo));
        hi.push((i as f64, 100.0 * p.hi));
    }
    category_plot(
        &format!(
            "Case {case}: mechanisms jammed within a year, one assumption changed per row (rows as in the table)"
        ),
        &categories,
        "row of the sensitivity table",
        "jammed within a year [%]",
        &[
            Series {
                label: "share",
                points: share,
            },
            Series {
                label: "95 % interval, lower end",
                points: lo,
            },
            Series {
                label: "95 % interval, upper end",
                points: hi,
            },
        ],
    )
}
