//! `table2`: Edmunds' Cases A-D with his radial-line model (his Table 2 beside ours), then the
//! same manufactured gears with triangular teeth, trial by trial, with the difference and its
//! 95 % interval.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use stats::{Estimate, mean_ci95};

use crate::common::{Series, semilog_plot};
use study::gearing;
use study::grids::CASES;
use study::pointers::{CaseMechanism, both_model_trials, pointer_runs};

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

crate::experiment! {
    id: "table2", paper_item: "Table 2 (section 4)", run,
    title: "Edmunds' Cases A-D: his radial-line model beside his Table 2, and triangular teeth on the same gears",
    params: [TRIALS, LUNAR_TURNS, METONIC_TURNS, SAROS_TURNS, SAMPLES_PER_ENGAGEMENT, gearing::PIN_AND_SLOT], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::events::GROUP],
}

const POINTERS: [(&str, &Param); 3] = [
    ("Lunar", &LUNAR_TURNS),
    ("Metonic", &METONIC_TURNS),
    ("Saros", &SAROS_TURNS),
];

/// One trial of one case: per pointer, (Edmunds σ, Edmunds Dm, triangular σ, triangular Dm, jammed).
type CaseTrial = Vec<(f64, f64, f64, f64, bool)>;

/// Every Case's trials under both contact models: `results[case][trial][pointer]`.
fn simulate(
    ctx: &Context,
    cells: &study::grids::CellSettings,
    runs: &[(&str, f64, usize)],
    pin_and_slot: bool,
) -> Result<Vec<Vec<CaseTrial>>, RunError> {
    let (g, hyp, trials) = (cells.gearing(), cells.hypothesis(), cells.trials as usize);
    let (h, clearance) = (cells.gearing.tooth_height, cells.clearance()?);
    let mut results: Vec<Vec<CaseTrial>> = Vec::new();
    for (ci, &(case, systematic, random)) in CASES.iter().enumerate() {
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
        let per_trial =
            both_model_trials(ctx.engine(), &key, ci as u64, &made, runs, trials as u64)?;
        results.push(
            per_trial
                .into_iter()
                .map(|trial| {
                    trial
                        .into_iter()
                        .map(|r| {
                            (
                                r.edmunds_sigma,
                                r.edmunds_dm,
                                r.triangular_sigma,
                                r.triangular_dm,
                                r.jammed,
                            )
                        })
                        .collect()
                })
                .collect(),
        );
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

/// The mean of the trial-by-trial differences `a - b`, with its 95 % interval.
fn diff(a: &[f64], b: &[f64]) -> stats::Estimate {
    mean_ci95(&a.iter().zip(b).map(|(x, y)| x - y).collect::<Vec<_>>())
}

/// An estimate as printed: "mean [lo .. hi]".
fn show(e: &stats::Estimate) -> String {
    crate::common::estimate(e, 3)
}

/// The notes under both tables: what each Case draws, the days per degree, and the
/// pin-and-slot when it is in.
fn notes(edm_table: &mut Table, tri_table: &mut Table, g: &train::Gearing, pin_and_slot: bool) {
    edm_table.note("Each case: every gear gets random tooth errors (sd = random x pitch) and the systematic error split between a sinusoid of tip position and an eccentric axis (split parameter, 0.5 as in the paper).");
    edm_table.note(format!(
        "Days: from each pointer's exact ratio (Metonic {} d/deg, Saros {} d/deg).",
        g.days_per_degree("Metonic")
            .map_or_else(|| "-".into(), |d| fmt_f64(d, 3)),
        g.days_per_degree("Saros")
            .map_or_else(|| "-".into(), |d| fmt_f64(d, 3)),
    ));
    if pin_and_slot {
        let note = "Lunar: with the pin-and-slot (--set pin_and_slot=true), beyond the paper; its TD is taken against the anomaly-bearing ideal motion (cargo xtask help lunar-anomaly).";
        edm_table.note(note);
        tri_table.note(note);
    }
}

/// The CSV lines of one Case and pointer: each model's σ and Dm over the trials (`values`:
/// Edmunds' σ and Dm, then the triangular teeth'), with the paper's for Edmunds' model.
fn csv_lines(
    csv: &mut String,
    (case, name): (&str, &str),
    [es, ed, ts, td]: [&Vec<f64>; 4],
    (paper_sigma, paper_dm): (Option<f64>, Option<f64>),
) {
    for (model, stat, v, p) in [
        ("edmunds", "sigma", es, paper_sigma),
        ("edmunds", "dm", ed, paper_dm),
        ("triangular", "sigma", ts, None),
        ("triangular", "dm", td, None),
    ] {
        let e = mean_ci95(v);
        csv.push_str(&registry::csv_line([
            case.to_owned(),
            name.to_owned(),
            model.to_owned(),
            stat.to_owned(),
            e.mean.to_string(),
            e.lo.to_string(),
            e.hi.to_string(),
            p.map_or(String::new(), |x| x.to_string()),
        ]));
    }
}

/// The two tables' titles and columns: Edmunds' model in the paper's layout, and triangular
/// teeth against it.
fn tables(trials: usize, clearance: f64) -> (Table, Table) {
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

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let cells = crate::settings::cells(ctx, &TRIALS)?;
    let (g, trials, clearance) = (cells.gearing(), cells.trials as usize, cells.clearance()?);
    let per = ctx.get(&SAMPLES_PER_ENGAGEMENT)?;
    let pin_and_slot = ctx.get(&study::gearing::PIN_AND_SLOT)?;
    let runs = pointer_runs(g, &crate::settings::turns(ctx, &POINTERS)?, per)?;
    let results = simulate(ctx, &cells, &runs, pin_and_slot)?;

    let (mut edm_table, mut tri_table) = tables(trials, clearance);
    // sigma against the systematic error, per pointer and model, for the plot.
    let mut curves: std::collections::BTreeMap<String, Vec<(f64, f64)>> =
        std::collections::BTreeMap::new();
    let mut csv = String::from("case,pointer,model,statistic,mean_deg,lo_deg,hi_deg,paper_deg\n");
    for (ci, &(case, systematic, random)) in CASES.iter().enumerate() {
        let mut row = vec![case.to_string(), fmt_f64(systematic, 2), fmt_f64(random, 3)];
        for (pi, &(name, _, _)) in runs.iter().enumerate() {
            let col = |f: fn(&(f64, f64, f64, f64, bool)) -> f64| -> Vec<f64> {
                results[ci].iter().map(|t| f(&t[pi])).collect()
            };
            let (es, ed, ts, td) = (col(|x| x.0), col(|x| x.1), col(|x| x.2), col(|x| x.3));
            let (es_m, ed_m) = (mean_ci95(&es), mean_ci95(&ed));
            let paper = |q: &str| {
                crate::paper::get("table2", &format!("{case}.{name}.{q}")).map(|r| r.value)
            };
            let days = g.days_per_degree(name);
            let cell = edmunds_cell(&es_m, &ed_m, (paper("sigma"), paper("dm")), days);
            row.push(cell);
            let mut add = |label: String, y: Option<f64>| {
                if let Some(y) = y {
                    curves.entry(label).or_default().push((systematic, y));
                }
            };
            add(format!("{name}, Edmunds' model (ours)"), Some(es_m.mean));
            add(
                format!("{name}, triangular teeth (ours)"),
                Some(mean_ci95(&ts).mean),
            );
            add(format!("{name}, Edmunds' Table 2 (paper)"), paper("sigma"));
            let (dsig, ddm) = (diff(&ts, &es), diff(&td, &ed));
            let jammed = results[ci].iter().filter(|t| t[pi].4).count();
            tri_table.row(vec![
                case.into(),
                name.into(),
                fmt_f64(es_m.mean, 3),
                fmt_f64(mean_ci95(&ts).mean, 3),
                show(&dsig),
                fmt_f64(ed_m.mean, 3),
                fmt_f64(mean_ci95(&td).mean, 3),
                show(&ddm),
                format!("{jammed}/{trials}"),
            ]);
            let paper_values = (paper("sigma"), paper("dm"));
            csv_lines(&mut csv, (case, name), [&es, &ed, &ts, &td], paper_values);
        }
        edm_table.row(row);
    }
    notes(&mut edm_table, &mut tri_table, g, pin_and_slot);
    tri_table.note("A jam stops the pointer, so a triangular trial that jammed is measured up to its first jam (Edmunds' model never jams).");
    let svg = plot(&curves)?;
    Ok(Report {
        tables: vec![edm_table, tri_table],
        files: vec![
            OutputFile::new("table2-data.csv", csv),
            OutputFile::new("table2.svg", svg),
        ],
        // Mechanisms run, per Case (each under both contact models).
        trials: (CASES.len() * trials) as u64,
        ..Default::default()
    })
}
