//! `table6`: σ, Dm and P of the five pointers for a mechanism built with each mesh's largest
//! tolerable random and systematic errors (Tables 4 and 5 by the 1 % rule), 30 trials.

use std::collections::BTreeMap;

use hypotheses::Params;
use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use stats::{Estimate, PointerStats, mean_ci95};

use crate::emax::{paper_random, paper_systematic, show};
use study::cell::{Purpose, label};
use study::pointers::{Manufactured, POINTERS, pointer_runs};
use study::tolerance::RULE;

/// `trials`: runs of the whole mechanism, each with fresh errors and initial angles (the paper: 30).
const TRIALS: Param = registry::interval_trials(
    "30",
    "runs of the whole mechanism, each with fresh errors and initial angles (the paper: 30)",
);

registry::params! {
    /// `cell_trials`: trials per cell of Tables 4 and 5, from which the tolerances are derived.
    const CELL_TRIALS = Param::new("cell_trials", "200", "trials per cell of Tables 4 and 5, from which the tolerances are derived", registry::Kind::count(1, registry::MAX_TRIALS, ""));
}

crate::experiment! {
    id: "table6", paper_item: "Table 6 (section 5)", run,
    title: "Pointer errors of a mechanism built with each mesh's largest tolerable random and systematic errors",
    params: [TRIALS, CELL_TRIALS, RULE, crate::emax::EMAX], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::tolerance::RANDOM_GRID, study::tolerance::SYSTEMATIC_GRID, study::pointers::RUN_LENGTHS, study::events::GROUP, study::drive::GROUP],
}

/// One trial: per pointer (statistics up to the first jam, jammed, tooth engagements).
type PointerTrials = Vec<(PointerStats, bool, u64)>;

/// Each gear's tolerances (random, systematic) and the meshes it is in.
type PerGear = BTreeMap<String, (f64, f64, Vec<String>)>;

/// Each gear's tolerances (random, systematic) and its meshes: its mesh's; a gear in two meshes
/// (b2) the smaller of each. Below a grid counts as 0 (no error known to be tolerable).
fn per_gear(g: &train::Gearing, tol: &study::grids::Tolerances) -> PerGear {
    let mut per_gear: BTreeMap<String, (f64, f64, Vec<String>)> = BTreeMap::new();
    for (m, mesh) in g.meshes().iter().enumerate() {
        let r = tol.random[m].unwrap_or(0.0);
        let s = tol.systematic[m].unwrap_or(0.0);
        for gear in [&mesh.driver, &mesh.driven] {
            let e =
                per_gear
                    .entry(gear.clone())
                    .or_insert((f64::INFINITY, f64::INFINITY, Vec::new()));
            e.0 = e.0.min(r);
            e.1 = e.1.min(s);
            e.2.push(mesh.label.clone());
        }
    }
    per_gear
}

/// Table 6's inputs: each mesh's tolerances beside the paper's, and table6-inputs.csv.
fn inputs_table(
    tol: &study::grids::Tolerances,
    rule: f64,
    cell_trials: u64,
    per_gear: &PerGear,
) -> (Table, String) {
    let mut inputs = Table::new(
        format!(
            "Table 6 inputs: each mesh's largest tolerable errors (rule {rule} % of {cell_trials} trials): ours (paper)"
        ),
        ["mesh", "random E. max [pitch]", "systematic E. max [deg]"],
    );
    let mut inputs_csv = String::from("mesh,random_emax,systematic_emax_deg\n");
    for (m, mesh) in tol.random_grid.meshes.iter().enumerate() {
        let paper_sys = paper_systematic(mesh, &tol.sys_values, rule)
            .map_or_else(|| "-".into(), |p| show(p, tol.sys_values.first(), 1));
        let ours_sys = if tol.random[m].is_some() {
            show(tol.systematic[m], tol.sys_values.first(), 1)
        } else {
            "-".into()
        };
        inputs.row(vec![
            mesh.clone(),
            format!(
                "{} ({})",
                show(tol.random[m], tol.random_grid.values.first(), 3),
                paper_random(mesh).map_or_else(|| "-".into(), |p| label(p, 3))
            ),
            format!("{ours_sys} ({paper_sys})"),
        ]);
        inputs_csv.push_str(&registry::csv_line([
            mesh.clone(),
            tol.random[m].unwrap_or(0.0).to_string(),
            tol.systematic[m].unwrap_or(0.0).to_string(),
        ]));
    }
    let shared: Vec<String> = per_gear
        .iter()
        .filter(|(_, (_, _, meshes))| meshes.len() > 1)
        .map(|(gear, (r, s, meshes))| {
            format!(
                "{gear} ({}): random {}, systematic {} deg",
                meshes.join(" and "),
                label(*r, 3),
                label(*s, 1)
            )
        })
        .collect();
    inputs.note(format!(
        "Each gear takes its mesh's values; a gear in two meshes takes the smaller of each: {}.",
        if shared.is_empty() {
            "none".to_string()
        } else {
            shared.join("; ")
        }
    ));
    inputs.note("A value below its grid (`< ...`) is built as 0. Systematic: the paper's value in brackets is what its own Table 5 counts give by the same rule.");
    (inputs, inputs_csv)
}

/// The pointers' rows: σ, Dm and P of each over the trials beside the paper's (into `layout`),
/// the detail table, table6-data.csv, and how many of the paper's values lie inside and outside
/// our intervals (none compared, and no `*`, unless `compared`: the run's inputs are the
/// paper's).
fn pointer_rows(
    layout: &mut Table,
    runs: &[(&str, f64, usize)],
    per_trial: &[PointerTrials],
    compared: bool,
) -> (Table, String, (u64, u64)) {
    let trials = per_trial.len();
    let mut detail = Table::new(
        "Table 6 in detail: mean over trials with its 95 % interval, the paper's value, trials that jammed",
        [
            "pointer",
            "statistic",
            "ours [deg]",
            "95 % interval [deg]",
            "paper [deg]",
            "trials that jammed",
        ],
    );
    let mut csv = String::from("pointer,statistic,mean_deg,lo_deg,hi_deg,paper_deg,jammed\n");
    let mut rows: Vec<Vec<String>> = ["sigma", "Dm", "P"]
        .iter()
        .map(|s| vec![(*s).to_string()])
        .collect();
    let (mut inside, mut outside) = (0, 0);
    for (i, &(name, turns, _)) in runs.iter().enumerate() {
        let jammed = per_trial.iter().filter(|t| t[i].1).count();
        let columns: [(&str, &str, Vec<f64>); 3] = [
            (
                "sigma",
                "sigma",
                per_trial.iter().map(|t| t[i].0.sigma).collect(),
            ),
            ("Dm", "dm", per_trial.iter().map(|t| t[i].0.dm).collect()),
            // P: the average absolute value of the oscillation mean, as in Table 1.
            (
                "P",
                "mean",
                per_trial.iter().map(|t| t[i].0.mean.abs()).collect(),
            ),
        ];
        for (row, (label_text, key, values)) in columns.into_iter().enumerate() {
            let e: Estimate = mean_ci95(&values);
            let paper = crate::paper::get("table6", &format!("{name}.{key}")).map(|r| r.value);
            let ok = !compared || paper.is_none_or(|p| e.contains(p));
            if compared && paper.is_some() {
                if ok { inside += 1 } else { outside += 1 }
            }
            let cell =
                |x: Option<f64>, dec: usize| x.map_or_else(|| "-".to_string(), |v| fmt_f64(v, dec));
            rows[row].push(format!(
                "{} ({}){}",
                fmt_f64(e.mean, 3),
                cell(paper, 2),
                if ok { "" } else { "*" }
            ));
            let mut cells = crate::common::estimate_cells(name, turns, label_text, &e);
            cells.extend([cell(paper, 2), format!("{jammed}/{trials}")]);
            detail.row(cells);
            let paper_csv = paper.map_or(String::new(), |v| v.to_string());
            let mut fields = crate::common::estimate_csv(name, label_text, &e);
            fields.extend([paper_csv, jammed.to_string()]);
            csv.push_str(&registry::csv_line(fields));
        }
    }
    for r in rows {
        layout.row(r);
    }
    (detail, csv, (inside, outside))
}

/// The meshes that ran at tolerances other than the paper's, as a note: a random E. max other
/// than the paper's row, or a systematic one other than what the paper's own Table 5 counts give
/// by the same rule. The paper's values come from its own tolerances, so where these differ the
/// comparison is not like for like; none where every mesh ran at the paper's.
fn tolerances_note(tol: &study::grids::Tolerances, rule: f64) -> Option<String> {
    let differs = |ours: Option<f64>, paper: Option<f64>| match (ours, paper) {
        (Some(o), Some(p)) => (o - p).abs() > 1e-9,
        (None, None) => false,
        _ => true,
    };
    let mut random = Vec::new();
    let mut systematic = Vec::new();
    for (m, mesh) in tol.random_grid.meshes.iter().enumerate() {
        if differs(tol.random[m], paper_random(mesh)) {
            random.push(mesh.as_str());
        }
        let paper_sys = paper_systematic(mesh, &tol.sys_values, rule);
        if paper_sys.is_some_and(|p| differs(tol.systematic[m], p)) {
            systematic.push(mesh.as_str());
        }
    }
    if random.is_empty() && systematic.is_empty() {
        return None;
    }
    let list = |v: &[&str]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    Some(format!(
        "Not like for like in every mesh: the paper's values come from its own tolerances, and this run's differ (the inputs table) in random E. max for {} of {} meshes ({}) and in systematic E. max for {} ({}); `--set emax=paper` takes the paper's random E. max row.",
        random.len(),
        tol.random_grid.meshes.len(),
        list(&random),
        systematic.len(),
        list(&systematic)
    ))
}

/// Each gear's hypothesis parameters: its tolerances, with the split the cells run.
fn gear_params(
    cells: &study::grids::CellSettings,
    per_gear: &PerGear,
    split: f64,
) -> Result<BTreeMap<String, Params>, RunError> {
    let mut params: BTreeMap<String, Params> = BTreeMap::new();
    for (gear, (r, s, _)) in per_gear {
        params.insert(
            gear.clone(),
            cells
                .errors
                .params(&[("random", *r), ("systematic", *s), ("split", split)])?,
        );
    }

    Ok(params)
}

/// The trials as recorded, as each pointer's statistics, whether it jammed and its engagements.
fn pointer_trials(recorded: Vec<Vec<study::pointers::ToFirstJam>>) -> Vec<PointerTrials> {
    recorded
        .into_iter()
        .map(|trial| {
            trial
                .into_iter()
                .map(|r| {
                    let s = PointerStats {
                        sigma: r.sigma,
                        dm: r.dm,
                        mean: r.mean,
                    };
                    (s, r.jammed, r.engaged)
                })
                .collect()
        })
        .collect()
}

/// The table in the paper's layout, its title saying where the random tolerances come from.
fn layout_table(emax_from_paper: bool, clearance: f64, trials: usize) -> Table {
    Table::new(
        format!(
            "Table 6: tolerable errors{}, G = {clearance} %, {trials} trials: ours (paper) [deg]; * where the paper's value is outside our 95 % interval",
            if emax_from_paper {
                " (random: the paper's E. max row, emax=paper)"
            } else {
                ""
            }
        ),
        study::pointers::COLUMNS,
    )
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    // The cells of Tables 4 and 5 count `cell_trials` trials each.
    let cells = crate::settings::cells(ctx, &CELL_TRIALS)?;
    let trials: usize = ctx.get(&TRIALS)?;
    let (g, hyp, cell_trials) = (cells.gearing(), cells.hypothesis(), cells.trials);
    let rule = ctx.get(&study::tolerance::RULE)?;
    let (h, clearance, split) = (
        cells.gearing.tooth_height,
        cells.clearance()?,
        cells.errors.split()?,
    );
    let per = ctx.get(&study::pointers::SAMPLES_PER_ENGAGEMENT)?;
    let runs = pointer_runs(g, &crate::settings::turns(ctx, &POINTERS)?, per)?;
    let grids = (
        crate::settings::random_grid(ctx)?,
        crate::settings::systematic_grid(ctx)?,
    );
    let given = crate::emax::given_random(ctx, g)?;
    let tol = study::grids::derive(ctx.engine(), &cells, grids, rule, Purpose::Input, given)?;

    let per_gear = per_gear(g, &tol);
    let params = gear_params(&cells, &per_gear, split)?;

    // Named by everything that determines the trials (the tolerances are derived from the
    // parameters, so naming those names them), so shards run and merge them.
    let key = format!(
        "table6: {trials} trials, hypothesis {}, tolerances {:?}, h = {h} mm, G = {clearance} %, gearing {}, events {}, pointers {:?}",
        hyp.name(),
        params
            .iter()
            .map(|(gear, p)| (gear.as_str(), p.iter().collect::<Vec<_>>()))
            .collect::<Vec<_>>(),
        cells.gearing.file,
        cells.rule.label(),
        runs,
    );
    let made = Manufactured {
        gearing: g,
        tooth_height: h,
        clearance,
        hypothesis: hyp,
        params: &params,
        rule: &cells.rule,
    };
    let recorded =
        study::pointers::tolerated_trials(ctx.engine(), &key, &made, &runs, trials as u64)?;
    let per_trial = pointer_trials(recorded);

    let mut layout = layout_table(crate::emax::emax_from_paper(ctx)?, clearance, trials);
    let off_paper = crate::cells::off_paper_inputs(ctx);
    let (detail, csv, (inside, outside)) =
        pointer_rows(&mut layout, &runs, &per_trial, off_paper.is_empty());
    layout.note(format!(
        "Values of the paper inside our 95 % Student-t intervals: {inside}; outside: {outside}."
    ));
    if let Some(note) = tolerances_note(&tol, rule) {
        layout.note(note);
    }
    layout.note("Each trial: every gear manufactured afresh with its tolerances (systematic split as the split parameter says), random initial angles; a jam stops the pointer, so a trial that jammed is measured up to its first jam (as in table2).");

    let (inputs, inputs_csv) = inputs_table(&tol, rule, cell_trials, &per_gear);

    let cells = || tol.all();
    let trains: u64 = (trials * runs.len()) as u64;
    let train_engagements: u64 = per_trial.iter().flatten().map(|x| x.2).sum();
    Ok(Report {
        tables: vec![layout, detail, inputs],
        files: vec![
            OutputFile::new("table6-data.csv", csv),
            OutputFile::new("table6-inputs.csv", inputs_csv),
        ],
        trials: cells().map(|c| c.trials).sum::<u64>() + trains,
        engagements: cells().map(|c| c.engagements).sum::<u64>() + train_engagements,
        agreement: off_paper.is_empty().then_some(registry::Agreement {
            consistent: inside,
            differ: outside,
        }),
        ..Default::default()
    })
}
