//! `table1`: σ, Dm and P of the five pointers with ideal triangular teeth (no manufacturing
//! error) at G = 40 %, averaged over trials with random initial angles.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use stats::{Estimate, mean_ci95};

use study::pointers::{POINTERS, PointerTrial, pointer_runs};

/// `trials`: trials, each with fresh random initial angles.
const TRIALS: Param =
    registry::interval_trials("30", "trials, each with fresh random initial angles");

crate::experiment! {
    id: "table1", paper_item: "Table 1 (section 3)", run,
    title: "Pointer errors of ideal triangular teeth: sigma, Dm and P of five pointers",
    params: [TRIALS], groups: [study::gearing::GROUP, study::pointers::RUN_LENGTHS, study::events::GROUP],
}

/// The key of the trial batch: everything that determines the trials.
fn batch_key(
    gearing: &str,
    trials: usize,
    h: f64,
    clearance: f64,
    runs: &[(&str, f64, usize)],
) -> String {
    let runs: Vec<String> = runs
        .iter()
        .map(|(name, turns, samples)| format!("{name} {turns} turns {samples} samples"))
        .collect();
    format!(
        "table1: {trials} trials, ideal teeth, h = {h} mm, G = {clearance} %, gearing {gearing}, pointers: {}",
        runs.join(", ")
    )
}

/// The pointers' exact ratios from the gearing, beside Freeth 2006's.
fn ratios_table(g: &train::Gearing, runs: &[(&str, f64, usize)]) -> Table {
    let mut ratios = Table::new(
        "Pointer ratios from the gearing (exact; turns per turn of the b arbor)",
        [
            "pointer",
            "meshes",
            "ratio",
            "as decimal",
            "days per degree",
        ],
    );
    for &(name, _, _) in runs {
        let r = g.pointer_ratio(name);
        ratios.row(vec![
            name.into(),
            g.pointer(name).map_or(0, |p| p.meshes.len()).to_string(),
            r.map_or_else(|| "-".into(), |r| r.to_string()),
            r.map_or_else(|| "-".into(), |r| format!("{:.9}", r.to_f64())),
            g.days_per_degree(name)
                .map_or_else(|| "-".into(), |d| fmt_f64(d, 4)),
        ]);
    }
    ratios.note("Freeth 2006 gives Lunar 254/19, Metonic 5/19, Games 1/4, Saros 940/4237, Exeligmos 235/12711.");
    ratios
}

/// The detail table's title and columns.
fn detail_table() -> Table {
    Table::new(
        "Table 1 in detail: mean over trials with its 95 % interval, the paper's value and ours/paper",
        [
            "pointer",
            "statistic",
            "ours [deg]",
            "95 % interval [deg]",
            "paper [deg]",
            "ours/paper",
            "ours [days]",
            "paper [days]",
        ],
    )
}

/// One statistic of one pointer (`label`, read from the paper as `key`), over the trials'
/// `values`: its cell of the paper's layout, its detail row and its CSV line. `days` converts
/// degrees of the pointer to days.
fn statistic_cells(
    (name, turns, days): (&str, f64, Option<f64>),
    (label, key): (&str, &str),
    values: &[f64],
) -> (String, Vec<String>, String) {
    let e: Estimate = mean_ci95(values);
    let paper = crate::paper::get("table1", &format!("{name}.{key}")).map(|r| r.value);
    let paper_days = crate::paper::get("table1", &format!("{name}.{key}.days")).map(|r| r.value);
    let ratio = paper.map(|p| e.mean / p);
    let ours_days = days.map(|d| e.mean * d);
    let cell = |x: Option<f64>, dec: usize| x.map_or_else(|| "-".to_string(), |v| fmt_f64(v, dec));
    let mut lay = format!("{} / {}", fmt_f64(e.mean, 3), cell(paper, 3));
    if let Some(d) = ours_days {
        lay.push_str(&format!(" ({} / {} d)", fmt_f64(d, 3), cell(paper_days, 3)));
    }
    let mut cells = crate::common::estimate_cells(name, turns, label, &e);
    cells.extend([
        cell(paper, 3),
        cell(ratio, 2),
        cell(ours_days, 3),
        cell(paper_days, 3),
    ]);
    let mut fields = crate::common::estimate_csv(name, label, &e);
    fields.extend(
        [paper, ratio, ours_days, paper_days].map(|v| v.map_or(String::new(), |v| v.to_string())),
    );
    let line = registry::csv_line(fields);
    (lay, cells, line)
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let settings = crate::settings::gearing(ctx)?;
    let trials: usize = ctx.get(&TRIALS)?;
    let per = ctx.get(&study::pointers::SAMPLES_PER_ENGAGEMENT)?;
    let mech = study::pointers::ideal_mechanism(&settings, &crate::settings::rule(ctx)?)?;
    let runs = pointer_runs(
        &settings.gearing,
        &crate::settings::turns(ctx, &POINTERS)?,
        per,
    )?;
    let (file, h, clearance) = (&settings.file, settings.tooth_height, settings.clearance);
    let key = batch_key(file, trials, h, clearance, &runs);
    let g = &settings.gearing;
    let per_trial = study::pointers::ideal_trials(ctx.engine(), &key, &mech, &runs, trials as u64)?;
    // A trial of another shard (`--shard`) is an empty default: read it as zeros.
    let at = |t: &[PointerTrial], i: usize| t.get(i).copied().unwrap_or_default();

    let mut layout = Table::new(
        format!(
            "Table 1: ideal triangular teeth, G = {clearance} %, h = {h} mm, {trials} trials: ours / paper [deg] (days)"
        ),
        study::pointers::COLUMNS,
    );
    let mut detail = detail_table();
    let mut jammed = 0;
    let mut csv = String::from(
        "pointer,statistic,mean_deg,lo_deg,hi_deg,paper_deg,ratio,mean_days,paper_days\n",
    );
    let mut layout_rows: Vec<Vec<String>> = ["sigma", "Dm", "P"]
        .iter()
        .map(|s| vec![(*s).to_string()])
        .collect();
    for (i, &(name, turns, _)) in runs.iter().enumerate() {
        jammed += per_trial.iter().filter(|t| at(t, i).stopped).count();
        let days = g.days_per_degree(name);
        let columns: [(&str, &str, Vec<f64>); 3] = [
            (
                "sigma",
                "sigma",
                per_trial.iter().map(|t| at(t, i).sigma).collect(),
            ),
            ("Dm", "dm", per_trial.iter().map(|t| at(t, i).dm).collect()),
            // P: the average absolute value of the oscillation mean (Table 1 caption).
            (
                "P",
                "mean",
                per_trial.iter().map(|t| at(t, i).mean.abs()).collect(),
            ),
        ];
        for (row, (label, key, values)) in columns.into_iter().enumerate() {
            let (lay, cells, line) = statistic_cells((name, turns, days), (label, key), &values);
            layout_rows[row].push(lay);
            detail.row(cells);
            csv.push_str(&line);
        }
    }
    for r in layout_rows {
        layout.row(r);
    }
    layout.note("Days: degrees times the pointer's days per degree, computed from its exact ratio (365.25 d per turn of b).");
    detail.note(format!(
        "sigma, Dm, P: standard deviation, largest |TD| and |mean TD| of each trial's Theoretical Difference in degrees; trials that jammed: {jammed}."
    ));
    detail.note("Radii: one least-squares module per group of meshed gears (crates/train); D = R1 + R2 - h + G; each mesh's initial angle is drawn per trial.");
    let ratios = ratios_table(g, &runs);
    Ok(Report {
        tables: vec![layout, detail, ratios],
        files: vec![OutputFile::new("table1-data.csv", csv)],
        // Mechanisms run (each drives the five pointers).
        trials: trials as u64,
        ..Default::default()
    })
}
