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

use registry::{Param, Place, Report, Run, RunError};
use serde::{Deserialize, Serialize};
use train::Gearing;

use presentation::reports::sensitivity::{self, Results, RowResults};
use setting_groups::typed::label;
use study::errors;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::grids::CASES;
use study::results::{FailureRun, TrainSummary};
use study::whole_mechanism::{self as whole, Clearances, Input};

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
        let report = sensitivity::report(r, (s.trials, s.days, s.gearing.clearance))?;
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
