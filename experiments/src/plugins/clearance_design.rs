//! `clearance-design`: each mesh's clearance that minimises the probability of a jam or a
//! disengagement per pair run, for each of Edmunds' Cases (a coarse grid, then a finer look
//! around the best), and the 30-run failure study rerun with those clearances against the
//! paper's one clearance for every mesh (beyond the paper).
//!
//! The pair runs are the cells of Tables 3, 4 and I (`study::cell`: one full turn of the gear with
//! more teeth, both gears manufactured afresh, a random initial angle), so a cell this search
//! shares with another experiment gives the same counts. The failure study's runs are
//! `failure`'s: the same gears and initial angles at both settings, so its 40 % columns are
//! `failure`'s numbers and the difference is the clearances' alone.

use std::collections::BTreeMap;

use registry::{MAX_TRIALS, Param, Place, Report, Run, RunError};
use serde::{Deserialize, Serialize};
use train::Gearing;

use presentation::reports::clearance_design::{self, Made, MeshYears, Results, StudyArm};
use setting_groups::typed::{Gearing as CellGearing, cells};
use study::cell::label;
use study::clearance_search::{Design, MeshSearch, search};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::ShapeParams;
use study::grids::CASES;
use study::grids::CellSettings;
use study::whole_mechanism::{self as whole, Clearances, Input};

registry::params! {
    const GRID = Param::new("grid", "20,30,40,50,60,70", "coarse grid of clearances tried for every mesh and case, comma-separated (the reference clearance is always added)", registry::Kind::Text).unit("% of h").a_clearance();
    const COARSE_TRIALS = Param::new("coarse_trials", "20", "trials per mesh, case and clearance of the coarse grid", registry::Kind::count(1, registry::MAX_TRIALS, "")).unit("pair runs");
    const REFINE_STEP = Param::new("refine_step", "5", "the refinement tries the coarse grid's best clearance plus and minus this (0: no refinement; the coarse grid decides)", registry::Kind::number(0.0, 100.0, "% of h")).unit("% of h");
    const REFINE_TRIALS = Param::new("refine_trials", "40", "trials per clearance compared in the refinement: the coarse best, its two neighbours and the reference, each brought to this count (at least coarse_trials)", registry::Kind::count(1, registry::MAX_TRIALS, "")).unit("pair runs");
    const RUNS = Param::new("runs", whole::RUNS_DEFAULT, "whole-mechanism runs per case and clearance setting (failure's trials; the paper: 30)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
    /// The reference clearance, typed as `clearance` like the gearing group's
    /// ([`study::gearing::CLEARANCE`]), which this experiment does not declare: here it is not every
    /// mesh's clearance but the one the search always tries and measures the chosen ones against.
    const REFERENCE_CLEARANCE = Param::new("clearance", "40", "reference clearance: the paper's one value for every mesh, always tried, and the failure study's first setting", registry::Kind::positive(100.0, "% of the tooth height h")).unit("% of h").a_clearance();
}

/// The clearance design's settings: the search's grid, trials and refinement, the failure
/// study's runs, horizon and cases, the reference clearance, the gearing with h, the Cases'
/// errors, the event rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
#[settings(check = check)]
pub struct Settings {
    /// The coarse grid of clearances, % of h, comma-separated ([`GRID`]).
    #[param(GRID)]
    pub grid: String,
    /// Pair runs per clearance of the coarse grid ([`COARSE_TRIALS`]).
    #[param(COARSE_TRIALS)]
    pub coarse_trials: u64,
    /// The refinement's step, % of h; 0: none ([`REFINE_STEP`]).
    #[param(REFINE_STEP)]
    pub refine_step: f64,
    /// Pair runs per clearance compared in the refinement ([`REFINE_TRIALS`]).
    #[param(REFINE_TRIALS)]
    pub refine_trials: u64,
    /// Whole-mechanism runs per case and setting ([`RUNS`]).
    #[param(RUNS)]
    pub runs: u64,
    /// Horizon of each run, days of b ([`whole::DAYS`]).
    #[param(whole::DAYS)]
    pub days: f64,
    /// Edmunds' cases to run, comma-separated ([`whole::CASES_PARAM`]).
    #[param(whole::CASES_PARAM)]
    pub cases: String,
    /// The reference clearance, % of h ([`REFERENCE_CLEARANCE`]).
    #[param(REFERENCE_CLEARANCE)]
    pub clearance: f64,
    /// The gearing and h.
    #[group]
    pub shape: ShapeParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// The clearance design.
pub struct ClearanceDesign;

impl registry::Experiment for ClearanceDesign {
    const ID: &'static str = "clearance-design";
    const TITLE: &'static str = "Per-mesh clearance that minimises jams and disengagements, for each of Edmunds' Cases, and the failure study rerun with it (beyond the paper)";
    const PAPER_ITEM: &'static str = "Section 6 / beyond the paper";
    const PLACE: Place = Place::Beyond(20);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        // The coarse grid's cells count `coarse_trials` trials each.
        let cells = cells(
            CellGearing::Shape(&s.shape),
            &s.errors,
            Some(&s.events),
            Some(&s.drive),
            s.coarse_trials,
            s,
        )?;
        let (g, h) = (cells.gearing(), cells.gearing.tooth_height);
        let d = design(s)?;
        whole::check_study(g, h, &Clearances::Uniform(d.reference))?;
        let searches = search(run.engine(), &cells, &d.search())?;
        let meshes = cells.meshes();
        let maps = chosen(&d, &searches, meshes.len());
        let study = failure_study(run, &cells, &d, &maps)?;
        Ok(Results {
            meshes: meshes
                .into_iter()
                .map(|mesh| MeshYears {
                    years: years_per_pair_run(g, &mesh),
                    mesh,
                })
                .collect(),
            searches,
            hypothesis: cells.hypothesis().name().to_owned(),
            study,
            gears: study::units::mesh_gears(g),
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let made = Made {
            tooth_height: s.shape.tooth_height,
            split: s.errors.split,
        };
        let report = clearance_design::report(&design(s)?, made, r)?;
        setting_groups::typed::label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(ClearanceDesign);

/// A count parameter `p` of pair runs or mechanism runs, `n`: at least 1, at most [`MAX_TRIALS`].
fn count(p: &Param, n: u64) -> Result<u64, RunError> {
    if n == 0 || n > MAX_TRIALS {
        return Err(RunError::bad(
            "--set",
            p.name,
            format!("must be from 1 to {MAX_TRIALS} (got {n})"),
        ));
    }
    Ok(n)
}

/// The checks across the design's parameters ([`design`]), before anything runs.
fn check(s: &Settings, _: &registry::Context) -> Result<(), RunError> {
    design(s).map(|_| ())
}

/// The design the settings ask for: the grid with the reference, the trials, the refinement,
/// the study's runs, horizon and cases, each checked.
fn design(s: &Settings) -> Result<Design, RunError> {
    let reference = s.clearance;
    let mut grid = study::gearing::clearance_list(&s.grid, GRID.name, 100.0)?;
    grid.push(reference);
    grid.sort_by(f64::total_cmp);
    grid.dedup();
    let coarse = count(&COARSE_TRIALS, s.coarse_trials)?;
    let refine = count(&REFINE_TRIALS, s.refine_trials)?;
    if refine < coarse {
        return Err(RunError::bad(
            "--set",
            REFINE_TRIALS.name,
            format!(
                "must be at least {} = {coarse} (got {refine})",
                COARSE_TRIALS.name
            ),
        ));
    }
    let step = s.refine_step;
    if !(0.0..100.0).contains(&step) {
        return Err(RunError::bad(
            "--set",
            REFINE_STEP.name,
            format!("must be at least 0 and below 100 % of h (got {step})"),
        ));
    }
    let runs = count(&RUNS, s.runs)?;
    let cases = whole::parse_cases(&s.cases)?;
    if cases.is_empty() {
        return Err(RunError::bad(
            "--set",
            whole::CASES_PARAM.name,
            "no case: nothing to run",
        ));
    }
    Ok(Design {
        grid,
        reference,
        coarse,
        step,
        refine,
        runs,
        days: s.days,
        cases,
    })
}

/// Years of the b arbor (the input, one turn a year) in one pair run of `mesh`: one turn of its
/// gear with more teeth, driven through the first pointer train that holds the mesh. `None` for a
/// mesh on no pointer's train.
fn years_per_pair_run(g: &Gearing, mesh: &str) -> Option<f64> {
    let chain = g
        .pointers()
        .iter()
        .find(|p| p.meshes.iter().any(|m| m == mesh))?;
    let mut driver_turns = 1.0;
    for label in chain.meshes.iter().take_while(|m| *m != mesh) {
        driver_turns *= g.mesh_ratio(label)?.to_f64();
    }
    let m = g.mesh(mesh)?;
    let (driver, driven) = (g.gear(&m.driver)?.teeth, g.gear(&m.driven)?.teeth);
    let larger_turns = driver_turns * f64::from(driver) / f64::from(driver.max(driven));
    Some(1.0 / larger_turns)
}

/// Each case's chosen clearances, as a map from mesh to clearance (`meshes` meshes a case).
fn chosen(d: &Design, searches: &[MeshSearch], meshes: usize) -> Vec<BTreeMap<String, f64>> {
    (0..d.cases.len())
        .map(|k| {
            searches[k * meshes..(k + 1) * meshes]
                .iter()
                .map(|sr| (sr.mesh.clone(), sr.best))
                .collect()
        })
        .collect()
}

/// The failure study at both settings, each case at the reference clearance for every mesh and
/// at its chosen clearances (`maps`), on the same gears and initial angles.
fn failure_study(
    run: &Run,
    cells: &CellSettings,
    d: &Design,
    maps: &[BTreeMap<String, f64>],
) -> Result<Vec<StudyArm>, RunError> {
    let (g, h) = (cells.gearing(), cells.gearing.tooth_height);
    let inputs = study_inputs(cells, d, maps)?;
    let key = format!(
        "clearance-design/{}",
        whole::batch_key(&cells.gearing.file, &inputs, d.runs, h, d.reference, d.days)?
    );
    let outcomes = whole::run_study(
        run.engine(),
        g,
        &inputs,
        d.runs,
        h,
        d.days,
        &cells.rule,
        &key,
    )?;
    Ok(inputs
        .iter()
        .zip(outcomes.chunks(d.runs as usize))
        .map(|(input, runs)| StudyArm {
            label: input.label.clone(),
            runs: runs.to_vec(),
        })
        .collect())
}

/// The failure study's inputs: each case at the reference clearance for every mesh, then at its
/// chosen clearances, on the same gears and initial angles.
fn study_inputs<'a>(
    cells: &'a CellSettings,
    d: &Design,
    maps: &[BTreeMap<String, f64>],
) -> Result<Vec<Input<'a>>, RunError> {
    let (g, h) = (cells.gearing(), cells.gearing.tooth_height);
    let rl = label(d.reference, 0);
    let mut inputs: Vec<Input<'_>> = Vec::new();
    for (&ci, map) in d.cases.iter().zip(maps) {
        let per_mesh = Clearances::PerMesh {
            default: d.reference,
            meshes: map.clone(),
        };
        whole::check_study(g, h, &per_mesh)?;
        let mut at_ref = whole::case_input(&cells.errors, ci, Clearances::Uniform(d.reference))?;
        at_ref.label = format!("{} at {rl} %", CASES[ci].0);
        let mut at_best = whole::case_input(&cells.errors, ci, per_mesh)?;
        at_best.label = format!("{} at best", CASES[ci].0);
        inputs.push(at_ref);
        inputs.push(at_best);
    }
    Ok(inputs)
}

#[cfg(test)]
#[path = "../plugin_tests/clearance_design.rs"]
mod tests;
