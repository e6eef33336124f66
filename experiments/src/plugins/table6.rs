//! `table6`: σ, Dm and P of the five pointers for a mechanism built with each mesh's largest
//! tolerable random and systematic errors (Tables 4 and 5 by the 1 % rule), 30 trials.

use std::collections::BTreeMap;

use hypotheses::Params;
use registry::{Param, Place, Report, Run, RunError};
use serde::{Deserialize, Serialize};

use presentation::reports::table6::{self, Ran};
use setting_groups::emax::{EMAX, given_row, random_from};
use setting_groups::typed::{Gearing, cells, off_paper_inputs};
use study::cell::Purpose;
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
        let ran = Ran {
            rule: s.rule,
            cell_trials: s.cell_trials,
            clearance: s.gearing.clearance,
            from_paper: random_from(&s.emax) == RandomFrom::Paper,
            off_paper: off_paper_inputs(s),
        };
        setting_groups::typed::label(&s.events, Some(&s.drive), table6::report(r, &ran))
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
