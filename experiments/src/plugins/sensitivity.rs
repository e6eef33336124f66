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

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use stats::mean_ci95;
use train::Gearing;

use crate::common::{Series, category_plot};
use crate::common::{mean_cell, percent_cell};
use study::errors;
use study::gearing;
use study::grids::CASES;
use study::whole_mechanism::{self as whole, Clearances, Input, MechanismRun, TRAINS, summarise};

registry::params! {
    /// `trials`: whole-mechanism runs per row (the paper's failure study: 30).
    const TRIALS = Param::new("trials", "60", "whole-mechanism runs per row (the paper's failure study: 30)", registry::Kind::count(2, registry::MAX_TRIALS, "an interval needs two runs"));
    /// `case`: Edmunds' case every row starts from (A, B, C or D).
    const CASE = Param::new("case", "B", "Edmunds' case every row starts from (A, B, C or D)", registry::Kind::Text);
}

crate::experiment! {
    id: "sensitivity", paper_item: "Section 6, assumptions (1)-(5)", run,
    title: "How the Case B failure study moves when one assumption of the paper is changed (beyond the paper)",
    params: [TRIALS, whole::DAYS, CASE, errors::SPLIT, errors::PARAM], groups: [study::gearing::GROUP, study::events::GROUP],
}

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

/// What one row measured.
struct Row<'v> {
    variant: &'v Variant,
    /// The hypotheses applied, in order.
    hypotheses: String,
    h: f64,
    outcomes: Vec<MechanismRun>,
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let gearing::Settings {
        gearing: base_gearing,
        file,
        tooth_height: h0,
        clearance,
    } = crate::settings::gearing(ctx)?;
    let trials = ctx.get(&TRIALS)?;
    let days = ctx.get(&study::whole_mechanism::DAYS)?;
    let case = ctx.text(&CASE)?.trim();
    let Some(ci) = CASES.iter().position(|c| c.0.eq_ignore_ascii_case(case)) else {
        return Err(RunError::bad(
            "--set",
            CASE.name,
            format!("unknown case `{case}` (known: A, B, C, D)"),
        ));
    };
    let (case, systematic, random) = CASES[ci];
    let split = ctx.get(&errors::SPLIT)?;
    let base = crate::settings::hypothesis(ctx)?;
    let rule = crate::settings::rule(ctx)?;
    let embedded = embedded_gearings()?;
    let base_params = case_params(base, [random, systematic, split])?;
    let mut rows = Vec::with_capacity(VARIANTS.len());
    for v in VARIANTS {
        let extra = row_hypothesis(v)?;
        let hypotheses = match &extra {
            Some((h, _)) => format!("{}, then {}", base.name(), h.name()),
            None => base.name().to_string(),
        };
        let g = match v.gearing {
            Some(name) => embedded
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, g)| g)
                .ok_or_else(|| RunError::Internal(format!("gearing {name}")))?,
            None => &base_gearing,
        };
        let h = v.tooth_height.unwrap_or(h0);
        whole::check_study(g, h, &Clearances::Uniform(clearance))?;
        // The legend names the row, so every row is its own batch.
        let input = Input {
            label: case.to_string(),
            legend: format!("Case {case}, {}", v.label),
            // Case `ci`'s streams, as in `failure`: the same Edmunds draws in every row.
            index: ci as u64,
            source: "--hypothesis",
            hypothesis: base,
            params: base_params.clone(),
            clearances: Clearances::Uniform(clearance),
            pin_and_slot: false,
            extra,
        };
        let inputs = std::slice::from_ref(&input);
        let key = whole::batch_key(&file, inputs, trials, h, clearance, days)?;
        rows.push(Row {
            variant: v,
            hypotheses,
            h,
            outcomes: whole::run_study(ctx.engine(), g, inputs, trials, h, days, &rule, &key)?,
        });
    }
    report(&rows, case, trials, days, clearance, ctx.seed())
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

/// The report: totals over every row, the headline table and the share plot.
fn report(
    rows: &[Row<'_>],
    case: &str,
    trials: u64,
    days: f64,
    clearance: f64,
    seed: u64,
) -> Result<Report, RunError> {
    let mut report = Report {
        trials: rows.iter().map(|r| r.outcomes.len() as u64).sum(),
        engagements: rows
            .iter()
            .flat_map(|r| &r.outcomes)
            .map(|o| o.engagements)
            .sum::<f64>()
            .round() as u64,
        ..Default::default()
    };
    report
        .tables
        .push(headline_table(rows, case, trials, days, clearance, seed));
    report.files.push(OutputFile::new(
        "sensitivity-share.svg",
        share_plot(rows, case, days)?,
    ));
    Ok(report)
}

/// The one table: per row, the share of mechanisms jammed within a year, the day of the first
/// jam and the Lunar σ.
fn headline_table(
    rows: &[Row<'_>],
    case: &str,
    trials: u64,
    days: f64,
    clearance: f64,
    seed: u64,
) -> Table {
    let mechanism = TRAINS.len();
    let mut t = Table::new(
        format!(
            "Case {case}, G = {clearance} %, {trials} whole-mechanism runs per row, horizon {days} d of b, seed {seed}: one assumption changed per row"
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
    for r in rows {
        let summary = summarise(&r.outcomes, days);
        let m = &summary[mechanism];
        let sigmas: Vec<f64> = r.outcomes.iter().filter_map(|o| o.lunar_sigma).collect();
        let sigma = match sigmas.len() {
            0 => "-".to_string(),
            1 => format!("{} (n = 1)", fmt_f64(sigmas[0], 3)),
            _ => crate::common::estimate(&mean_ci95(&sigmas), 3),
        };
        let first: Vec<String> = m
            .meshes
            .iter()
            .map(|(mesh, n)| format!("{mesh} ({n})"))
            .collect();
        let label = if r.variant.tooth_height.is_some() || r.variant.plugin.is_some() {
            format!("{} [h = {} mm; {}]", r.variant.label, r.h, r.hypotheses)
        } else {
            format!("{} [{}]", r.variant.label, r.hypotheses)
        };
        t.row(vec![
            r.variant.assumption.to_string(),
            label,
            format!("{}/{}", m.year.k, m.year.n),
            percent_cell(&m.year),
            mean_cell(&m.days, days),
            stats::median(&m.days).map_or("-".into(), |d| fmt_f64(d, 0)),
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
fn share_plot(rows: &[Row<'_>], case: &str, days: f64) -> Result<String, RunError> {
    let mechanism = TRAINS.len();
    let categories: Vec<String> = (1..=rows.len()).map(|i| format!("row {i}")).collect();
    let (mut share, mut lo, mut hi) = (Vec::new(), Vec::new(), Vec::new());
    for (i, r) in rows.iter().enumerate() {
        let p = &summarise(&r.outcomes, days)[mechanism].year;
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
