//! `table1`: σ, Dm and P of the five pointers with ideal triangular teeth (no manufacturing
//! error) at G = 40 %, averaged over trials with random initial angles.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::Estimate;

use setting_groups::typed::label;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::pointers::{PointerTrial, RunLengths, pointer_runs};
use study::results::{IdealPointer, IdealPointers};

/// `trials`: trials, each with fresh random initial angles.
const TRIALS: Param =
    registry::interval_trials("30", "trials, each with fresh random initial angles");

/// Table 1's settings: the trials, the gearing with h and G, the pointers' run lengths and the
/// event rule that stops a pointer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: usize,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// Each pointer's run length and the TD sampling.
    #[group]
    pub runs: RunLengths,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Table 1.
pub struct Table1;

impl registry::Experiment for Table1 {
    const ID: &'static str = "table1";
    const TITLE: &'static str =
        "Pointer errors of ideal triangular teeth: sigma, Dm and P of five pointers";
    const PAPER_ITEM: &'static str = "Table 1 (section 3)";
    const PLACE: Place = Place::Paper(50);
    type Settings = Settings;
    type Results = IdealPointers;

    fn compute(s: &Settings, run: &Run) -> Result<IdealPointers, RunError> {
        let settings = s.gearing.load()?;
        let mech = study::pointers::ideal_mechanism(&settings, &s.events.rule()?)?;
        let g = &settings.gearing;
        let runs = pointer_runs(g, &s.runs.turns(), s.runs.samples_per_engagement)?;
        let (file, h, clearance) = (&settings.file, settings.tooth_height, settings.clearance);
        let key = batch_key(file, s.trials, h, clearance, &runs);
        let per_trial =
            study::pointers::ideal_trials(run.engine(), &key, &mech, &runs, s.trials as u64)?;
        // A trial of another shard (`--shard`) is an empty default: read it as zeros.
        let at = |t: &[PointerTrial], i: usize| t.get(i).copied().unwrap_or_default();
        let pointers = runs
            .iter()
            .enumerate()
            .map(|(i, &(name, turns, samples))| IdealPointer {
                pointer: name.to_owned(),
                turns,
                samples,
                meshes: g.pointer(name).map_or(0, |p| p.meshes.len()),
                ratio: g.pointer_ratio(name),
                days_per_degree: g.days_per_degree(name),
                trials: per_trial.iter().map(|t| at(t, i)).collect(),
            })
            .collect();
        Ok(IdealPointers {
            clearance,
            tooth_height: h,
            trials: s.trials,
            pointers,
        })
    }

    fn report(s: &Settings, r: &IdealPointers) -> Result<Report, RunError> {
        label(&s.events, None, tables(r))
    }
}

registry::register!(Table1);

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
fn ratios_table(pointers: &[IdealPointer]) -> Table {
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
    for p in pointers {
        let r = p.ratio;
        ratios.row(vec![
            p.pointer.clone(),
            p.meshes.to_string(),
            r.map_or_else(|| "-".into(), |r| r.to_string()),
            r.map_or_else(|| "-".into(), |r| format!("{:.9}", r.to_f64())),
            p.days_per_degree
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
/// `e`, its mean over the trials: its cell of the paper's layout, its detail row and its CSV
/// line. `days` converts degrees of the pointer to days.
fn statistic_cells(
    (name, turns, days): (&str, f64, Option<f64>),
    (label, key): (&str, &str),
    e: &Estimate,
) -> (String, Vec<String>, String) {
    let paper = presentation::paper::get("table1", &format!("{name}.{key}")).map(|r| r.value);
    let paper_days =
        presentation::paper::get("table1", &format!("{name}.{key}.days")).map(|r| r.value);
    let ratio = paper.map(|p| e.mean / p);
    let ours_days = days.map(|d| e.mean * d);
    let cell = |x: Option<f64>, dec: usize| x.map_or_else(|| "-".to_string(), |v| fmt_f64(v, dec));
    let mut lay = format!("{} / {}", fmt_f64(e.mean, 3), cell(paper, 3));
    if let Some(d) = ours_days {
        lay.push_str(&format!(" ({} / {} d)", fmt_f64(d, 3), cell(paper_days, 3)));
    }
    let mut cells = presentation::common::estimate_cells(name, turns, label, e);
    cells.extend([
        cell(paper, 3),
        cell(ratio, 2),
        cell(ours_days, 3),
        cell(paper_days, 3),
    ]);
    let mut fields = presentation::common::estimate_csv(name, label, e);
    fields.extend(
        [paper, ratio, ours_days, paper_days].map(|v| v.map_or(String::new(), |v| v.to_string())),
    );
    let line = registry::csv_line(fields);
    (lay, cells, line)
}

/// The tables and the CSV drawn from the results (before the event rule is named).
fn tables(r: &IdealPointers) -> Report {
    let (h, clearance, trials) = (r.tooth_height, r.clearance, r.trials);
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
    for p in &r.pointers {
        jammed += p.jammed();
        // P: the average absolute value of the oscillation mean (Table 1 caption).
        let columns = [
            ("sigma", "sigma", p.sigma()),
            ("Dm", "dm", p.dm()),
            ("P", "mean", p.p()),
        ];
        for (row, (label, key, e)) in columns.into_iter().enumerate() {
            let which = (p.pointer.as_str(), p.turns, p.days_per_degree);
            let (lay, cells, line) = statistic_cells(which, (label, key), &e);
            layout_rows[row].push(lay);
            detail.row(cells);
            csv.push_str(&line);
        }
    }
    for row in layout_rows {
        layout.row(row);
    }
    layout.note("Days: degrees times the pointer's days per degree, computed from its exact ratio (365.25 d per turn of b).");
    detail.note(format!(
        "sigma, Dm, P: standard deviation, largest |TD| and |mean TD| of each trial's Theoretical Difference in degrees; trials that jammed: {jammed}."
    ));
    detail.note("Radii: one least-squares module per group of meshed gears (crates/train); D = R1 + R2 - h + G; each mesh's initial angle is drawn per trial.");
    Report {
        tables: vec![layout, detail, ratios_table(&r.pointers)],
        files: vec![OutputFile::new("table1-data.csv", csv)],
        // Mechanisms run (each drives the five pointers).
        trials: trials as u64,
        ..Default::default()
    }
}
