//! `table6`: σ, Dm and P of the five pointers for a mechanism built with each mesh's largest
//! tolerable random and systematic errors (Tables 4 and 5 by the 1 % rule), 30 trials.

use std::collections::BTreeMap;

use hypotheses::Params;
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::Estimate;

use presentation::emax::{paper_random, paper_systematic, show};
use setting_groups::emax::{EMAX, given_row, random_from};
use setting_groups::typed::{Gearing, cells, off_paper_inputs};
use study::cell::{Purpose, label};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::pointers::{Manufactured, RunLengths, pointer_runs};
use study::results::{
    DerivedTolerances, GearTolerance, PointerEstimates, RandomFrom, TolerableMechanism,
};
use study::tolerance::{RULE, RandomGrid, SystematicGrid};

/// `trials`: runs of the whole mechanism, each with fresh errors and initial angles (the paper: 30).
const TRIALS: Param = registry::interval_trials(
    "30",
    "runs of the whole mechanism, each with fresh errors and initial angles (the paper: 30)",
);

registry::params! {
    /// `cell_trials`: trials per cell of Tables 4 and 5, from which the tolerances are derived.
    const CELL_TRIALS = Param::new("cell_trials", "200", "trials per cell of Tables 4 and 5, from which the tolerances are derived", registry::Kind::count(1, registry::MAX_TRIALS, ""));
}

/// Table 6's settings: the mechanism's trials, the cells' trials, the rule, where the random E.
/// max comes from, the gearing with h and G, the split and hypothesis, the grids of Tables 4
/// and 5, the pointers' run lengths, the event rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Whole-mechanism trials ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: usize,
    /// Trials per cell of Tables 4 and 5 ([`CELL_TRIALS`]).
    #[param(CELL_TRIALS)]
    pub cell_trials: u64,
    /// The tolerance rule, % of trials jamming ([`RULE`]).
    #[param(RULE)]
    pub rule: f64,
    /// `derived` or `paper` ([`EMAX`]).
    #[param(EMAX)]
    pub emax: String,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// Table 4's random errors.
    #[group]
    pub random: RandomGrid,
    /// Table 5's systematic amplitudes.
    #[group]
    pub systematic: SystematicGrid,
    /// The pointers' run lengths and sampling.
    #[group]
    pub run_lengths: RunLengths,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// Table 6.
pub struct Table6;

impl registry::Experiment for Table6 {
    const ID: &'static str = "table6";
    const TITLE: &'static str = "Pointer errors of a mechanism built with each mesh's largest tolerable random and systematic errors";
    const PAPER_ITEM: &'static str = "Table 6 (section 5)";
    const PLACE: Place = Place::Paper(120);
    type Settings = Settings;
    type Results = TolerableMechanism;

    fn compute(s: &Settings, run: &Run) -> Result<TolerableMechanism, RunError> {
        // The cells of Tables 4 and 5 count `cell_trials` trials each.
        let cells = cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            Some(&s.events),
            Some(&s.drive),
            s.cell_trials,
            s,
        )?;
        let g = cells.gearing();
        let runs = pointer_runs(
            g,
            &s.run_lengths.turns(),
            s.run_lengths.samples_per_engagement,
        )?;
        let grids = (s.random.values(s)?, s.systematic.values(s)?);
        let from = random_from(&s.emax);
        let given = given_row(from, &cells.meshes())?;
        let tol = study::grids::derive(run.engine(), &cells, grids, s.rule, Purpose::Input, given)?;
        let tolerances = DerivedTolerances::new(&tol, cells.clearance()?, from);
        let gears = per_gear(g, &tolerances);
        let recorded = mechanism_trials(run, s, &cells, &gears, &runs)?;
        let pointers = runs
            .iter()
            .enumerate()
            .map(|(i, &run)| PointerEstimates::of(run, i, &recorded))
            .collect();
        Ok(TolerableMechanism {
            tolerances,
            gears,
            trials: s.trials as u64,
            pointers,
        })
    }

    fn report(s: &Settings, r: &TolerableMechanism) -> Result<Report, RunError> {
        let from_paper = random_from(&s.emax) == RandomFrom::Paper;
        let trials = r.trials as usize;
        let mut layout = layout_table(from_paper, s.gearing.clearance, trials);
        let off_paper = off_paper_inputs(s);
        let (detail, csv, (inside, outside)) =
            pointer_rows(&mut layout, &r.pointers, trials, off_paper.is_empty());
        layout.note(format!(
            "Values of the paper inside our 95 % Student-t intervals: {inside}; outside: {outside}."
        ));
        if let Some(note) = tolerances_note(&r.tolerances, s.rule) {
            layout.note(note);
        }
        layout.note("Each trial: every gear manufactured afresh with its tolerances (systematic split as the split parameter says), random initial angles; a jam stops the pointer, so a trial that jammed is measured up to its first jam (as in table2).");
        let (inputs, inputs_csv) = inputs_table(&r.tolerances, s.rule, s.cell_trials, &r.gears);
        let cells = || r.tolerances.all();
        let trains = r.trials * r.pointers.len() as u64;
        let train_engagements: u64 = r.pointers.iter().map(|p| p.engagements).sum();
        let report = Report {
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
                what: "the paper's values inside / outside our 95 % Student-t intervals".into(),
            }),
            ..Default::default()
        };
        setting_groups::typed::label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(Table6);

/// Each gear's tolerances (random, systematic) and its meshes: its mesh's; a gear in two meshes
/// (b2) the smaller of each. Below a grid counts as 0 (no error known to be tolerable). By gear
/// name.
fn per_gear(g: &train::Gearing, tol: &DerivedTolerances) -> Vec<GearTolerance> {
    let mut per_gear: BTreeMap<String, GearTolerance> = BTreeMap::new();
    for (mesh, t) in g.meshes().iter().zip(&tol.meshes) {
        let r = t.random.unwrap_or(0.0);
        let s = t.systematic.unwrap_or(0.0);
        for gear in [&mesh.driver, &mesh.driven] {
            let e = per_gear
                .entry(gear.clone())
                .or_insert_with(|| GearTolerance {
                    gear: gear.clone(),
                    random: f64::INFINITY,
                    systematic: f64::INFINITY,
                    meshes: Vec::new(),
                });
            e.random = e.random.min(r);
            e.systematic = e.systematic.min(s);
            e.meshes.push(mesh.label.clone());
        }
    }
    per_gear.into_values().collect()
}

/// The mechanism's trials: every gear made with its tolerances (`gears`), each trial run
/// pointer by pointer (`runs`) up to its first jam.
fn mechanism_trials(
    run: &Run,
    s: &Settings,
    cells: &study::grids::CellSettings,
    gears: &[GearTolerance],
    runs: &[(&str, f64, usize)],
) -> Result<Vec<Vec<study::pointers::ToFirstJam>>, RunError> {
    let (g, hyp, h) = (
        cells.gearing(),
        cells.hypothesis(),
        cells.gearing.tooth_height,
    );
    let clearance = cells.clearance()?;
    let params = gear_params(cells, gears, s.errors.split)?;
    // Named by everything that determines the trials (the tolerances are derived from the
    // parameters, so naming those names them), so shards run and merge them.
    let key = format!(
        "table6: {} trials, hypothesis {}, tolerances {:?}, h = {h} mm, G = {clearance} %, gearing {}, events {}, pointers {:?}",
        s.trials,
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
    study::pointers::tolerated_trials(run.engine(), &key, &made, runs, s.trials as u64)
}

/// Table 6's inputs: each mesh's tolerances beside the paper's, and table6-inputs.csv.
fn inputs_table(
    tol: &DerivedTolerances,
    rule: f64,
    cell_trials: u64,
    gears: &[GearTolerance],
) -> (Table, String) {
    let mut inputs = Table::new(
        format!(
            "Table 6 inputs: each mesh's largest tolerable errors (rule {rule} % of {cell_trials} trials): ours (paper)"
        ),
        ["mesh", "random E. max [pitch]", "systematic E. max [deg]"],
    );
    let mut inputs_csv = String::from("mesh,random_emax,systematic_emax_deg\n");
    let sys_values = tol.systematic_values();
    for t in &tol.meshes {
        let mesh = &t.mesh;
        let paper_sys = paper_systematic(mesh, &sys_values, rule)
            .map_or_else(|| "-".into(), |p| show(p, sys_values.first(), 1));
        let ours_sys = if t.random.is_some() {
            show(t.systematic, sys_values.first(), 1)
        } else {
            "-".into()
        };
        inputs.row(vec![
            mesh.clone(),
            format!(
                "{} ({})",
                show(t.random, tol.random_grid.random.first(), 3),
                paper_random(mesh).map_or_else(|| "-".into(), |p| label(p, 3))
            ),
            format!("{ours_sys} ({paper_sys})"),
        ]);
        inputs_csv.push_str(&registry::csv_line([
            mesh.clone(),
            t.random.unwrap_or(0.0).to_string(),
            t.systematic.unwrap_or(0.0).to_string(),
        ]));
    }
    let shared: Vec<String> = gears
        .iter()
        .filter(|g| g.meshes.len() > 1)
        .map(|g| {
            format!(
                "{} ({}): random {}, systematic {} deg",
                g.gear,
                g.meshes.join(" and "),
                label(g.random, 3),
                label(g.systematic, 1)
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
    pointers: &[PointerEstimates],
    trials: usize,
    compared: bool,
) -> (Table, String, (u64, u64)) {
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
    for p in pointers {
        let (name, turns, jammed) = (p.pointer.as_str(), p.turns, p.jammed);
        // P: the average absolute value of the oscillation mean, as in Table 1.
        let columns = [
            ("sigma", "sigma", p.sigma),
            ("Dm", "dm", p.dm),
            ("P", "mean", p.p),
        ];
        for (row, (label_text, key, estimate)) in columns.into_iter().enumerate() {
            let e: Estimate = estimate.into();
            let paper =
                presentation::paper::get("table6", &format!("{name}.{key}")).map(|r| r.value);
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
            let mut cells = presentation::common::estimate_cells(name, turns, label_text, &e);
            cells.extend([cell(paper, 2), format!("{jammed}/{trials}")]);
            detail.row(cells);
            let paper_csv = paper.map_or(String::new(), |v| v.to_string());
            let mut fields = presentation::common::estimate_csv(name, label_text, &e);
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
fn tolerances_note(tol: &DerivedTolerances, rule: f64) -> Option<String> {
    let differs = |ours: Option<f64>, paper: Option<f64>| match (ours, paper) {
        (Some(o), Some(p)) => (o - p).abs() > 1e-9,
        (None, None) => false,
        _ => true,
    };
    let mut random = Vec::new();
    let mut systematic = Vec::new();
    let sys_values = tol.systematic_values();
    for t in &tol.meshes {
        let mesh = t.mesh.as_str();
        if differs(t.random, paper_random(mesh)) {
            random.push(mesh);
        }
        let paper_sys = paper_systematic(mesh, &sys_values, rule);
        if paper_sys.is_some_and(|p| differs(t.systematic, p)) {
            systematic.push(mesh);
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
        tol.meshes.len(),
        list(&random),
        systematic.len(),
        list(&systematic)
    ))
}

/// Each gear's hypothesis parameters: its tolerances, with the split the cells run.
fn gear_params(
    cells: &study::grids::CellSettings,
    gears: &[GearTolerance],
    split: f64,
) -> Result<BTreeMap<String, Params>, RunError> {
    let mut params: BTreeMap<String, Params> = BTreeMap::new();
    for g in gears {
        params.insert(
            g.gear.clone(),
            cells.errors.params(&[
                ("random", g.random),
                ("systematic", g.systematic),
                ("split", split),
            ])?,
        );
    }

    Ok(params)
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
