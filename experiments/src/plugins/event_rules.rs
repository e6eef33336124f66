//! `event-rules`: Tables 3, 4 and I and the ideal meshes' clearance limits counted under every
//! registered event rule and every drive reading (which gear of each mesh drives) at once, with
//! each reading's share of the paper's counts that a two-sample test finds consistent with ours:
//! which reading of "jam" and "disengagement", and of the driver, reproduces the paper best.
//!
//! Every trial runs once with each gear driving and is counted under all the rules (the gears do
//! not depend on the rule or the drive; the contact motion depends on the drive only), and the
//! per-reading counts go into the shared cell cache, so Tables 3, 4 and I run afterwards in the
//! same process (`run all`) find their cells already run.

use registry::{Param, Place, Report, Run, RunError};
use rules::Rule;
use serde::{Deserialize, Serialize};

use presentation::cells::{PaperTable, Tally, paper_counts, paper_table_cells};
use presentation::reports::event_rules;
use setting_groups::typed::{Gearing, cells};
use study::cell::{CellSpec, Counting, Purpose, label, run_cells_counted};
use study::drive::Drive;
use study::errors::CaseParams;
use study::gearing::GearingParams;
use study::grids::CellSettings;
use study::limits::IdealPair;
use study::results::event_rules::{
    ClearanceLimits, Consistency, Counted, EventRules, Reading, RuleCell,
};
use study::tolerance::RandomGrid;
use study::trial_end::End;

registry::params! {
    /// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70).
    const CLEARANCES = Param::new("clearances", "10,40,70", "Table I's clearances G, comma-separated (the paper: 10, 40 and 70)", registry::Kind::Text).unit("% of h").a_clearance();
    /// `limit_tolerance`: how closely each ideal mesh's clearance limits are located (bisection).
    const LIMIT_TOLERANCE = Param::new("limit_tolerance", "0.1", "how closely each ideal mesh's clearance limits are located (bisection)", registry::Kind::number(0.001, 10.0, "% of h")).unit("% of h");
}

/// The settings: trials per cell, Table I's clearances, how closely the limits are located,
/// where a trial's counting ends, the gearing with h and G, the Cases' errors and Table 4's grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell ([`study::grids::TRIALS`]).
    #[param(study::grids::TRIALS)]
    pub trials: u64,
    /// Table I's clearances, comma-separated, % of h ([`CLEARANCES`]).
    #[param(CLEARANCES)]
    pub clearances: String,
    /// How closely the limits are located, % of h ([`LIMIT_TOLERANCE`]).
    #[param(LIMIT_TOLERANCE)]
    pub limit_tolerance: f64,
    /// Where a trial's counting ends ([`study::trial_end::PARAM`]).
    #[param(study::trial_end::PARAM)]
    pub end: String,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// Table 4's grid of random errors.
    #[group]
    pub random: RandomGrid,
}

/// Every event rule and drive side by side.
pub struct EventRulesExperiment;

impl registry::Experiment for EventRulesExperiment {
    const ID: &'static str = "event-rules";
    const TITLE: &'static str = "Every event rule and drive side by side: the paper's counts of Tables 3, 4 and I consistent with ours, and the ideal meshes' clearance limits";
    const PAPER_ITEM: &'static str =
        "Tables 3, 4, I and section 3 / Appendix II (what counts as a jam or a disengagement)";
    const PLACE: Place = Place::Beyond(50);
    type Settings = Settings;
    type Results = EventRules;

    fn compute(s: &Settings, run: &Run) -> Result<EventRules, RunError> {
        let mut cs = cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            None,
            None,
            s.trials,
            s,
        )?;
        cs.end = End::parse(&s.end)?;
        let (g, trials) = (cs.gearing(), cs.trials);
        let (rules, countings) = (every_rule()?, every_counting(cs.end)?);
        let (specs, mut cells) = all_cells(s, &cs)?;
        let counts = run_cells_counted(
            run.engine(),
            g,
            &specs,
            Some(&countings),
            trials,
            Purpose::Own,
        )?;
        for (cell, per_counting) in cells.iter_mut().zip(counts) {
            cell.counts = per_counting;
        }
        let limits = ideal_limits(g, cs.gearing.tooth_height, &rules, s.limit_tolerance)?;
        Ok(EventRules {
            trials,
            consistency: consistency(&cells, countings.len()),
            countings: countings
                .iter()
                .map(|c| Reading {
                    rule: c.rule.name().to_owned(),
                    rule_label: c.rule.label(),
                    drive: c.drive.name().to_owned(),
                    end: c.end.name().to_owned(),
                })
                .collect(),
            cells,
            meshes: g.meshes().iter().map(|m| m.label.clone()).collect(),
            rules: rules.iter().map(Rule::label).collect(),
            limits,
        })
    }

    fn report(s: &Settings, r: &EventRules) -> Result<Report, RunError> {
        event_rules::report(r, End::parse(&s.end)?, s.limit_tolerance)
    }
}

registry::register!(EventRulesExperiment);

/// The tables compared, in the order they are printed.
const TABLES: [&str; 3] = ["table3", "table4", "tableI"];

/// Every registered rule at its defaults, in name order.
fn every_rule() -> Result<Vec<Rule>, RunError> {
    let names = rules::rules().map_err(|e| RunError::Internal(e.to_string()))?;
    names
        .keys()
        .map(|n| Rule::parse(n).map_err(|e| RunError::Internal(e.to_string())))
        .collect()
}

/// Every registered rule under every drive, each trial's counting ending at `end`: rule by
/// rule in name order, each under `listed`, `other` and `either`; then the default rule under
/// every drive with each other end (counting costs nothing more: the same runs).
fn every_counting(end: End) -> Result<Vec<Counting>, RunError> {
    let mut out: Vec<Counting> = every_rule()?
        .into_iter()
        .flat_map(|rule| {
            Drive::ALL.into_iter().map(move |drive| Counting {
                rule: rule.clone(),
                drive,
                end,
            })
        })
        .collect();
    let default = Rule::parse(rules::DEFAULT).map_err(|e| RunError::Internal(e.to_string()))?;
    for other in End::ALL.into_iter().filter(|&e| e != end) {
        for drive in Drive::ALL {
            out.push(Counting {
                rule: default.clone(),
                drive,
                end: other,
            });
        }
    }
    Ok(out)
}

/// The cells of Tables 3 (Cases A-D at the clearance), 4 (the random grid, no systematic error)
/// and I (Cases A-D at each of its clearances), each with where its paper counts are (its
/// counts not yet filled in).
fn all_cells(s: &Settings, cs: &CellSettings) -> Result<(Vec<CellSpec>, Vec<RuleCell>), RunError> {
    let clearances = study::gearing::clearance_list(&s.clearances, CLEARANCES.name, 200.0)?;
    let randoms = s.random.values(s)?;
    let cells = paper_table_cells(cs, &randoms, &clearances)?;
    let table3_clearance = cs.clearance()?;
    let at = |g: f64| format!("G = {} %", label(g, 0));
    Ok(cells
        .into_iter()
        .map(|c| {
            let (group, region, case) = match c.table {
                PaperTable::Table3 { case } => (
                    format!("Table 3, Case {case}"),
                    at(table3_clearance),
                    Some(case),
                ),
                PaperTable::Table4 { .. } => (
                    "Table 4, random error only".to_string(),
                    "Table 4".to_string(),
                    None,
                ),
                PaperTable::TableI { case, clearance } => (
                    format!("Table I, Case {case}, G = {} %", label(clearance, 0)),
                    at(clearance),
                    Some(case),
                ),
            };
            let paper = RuleCell {
                table: c.id.to_owned(),
                key: c.key,
                group,
                region,
                case_d: case.is_some_and(|c| c == "D"),
                mesh: c.cell.mesh.clone(),
                counts: Vec::new(),
            };
            (c.cell, paper)
        })
        .unzip())
}

/// Per reading, per table: the paper's counts consistent with ours; and the same over every
/// table without the paper's counts that look copied from another cell (`suspect` in the
/// reference file).
fn consistency(cells: &[RuleCell], readings: usize) -> Vec<Consistency> {
    let mut out = vec![[Tally::default(); 4]; readings];
    for p in cells {
        let paper = paper_counts(&p.table, &p.key);
        let slip = |q: &str| presentation::paper::suspect(&p.table, &format!("{}.{q}", p.key));
        let trusted = (
            paper.0.filter(|_| !slip("jam")),
            paper.1.filter(|_| !slip("dis")),
        );
        let t = TABLES.iter().position(|&id| id == p.table).unwrap_or(0);
        for (r, c) in p.counts.iter().enumerate() {
            out[r][t].add(c, paper);
            out[r][3].add(c, trusted);
        }
    }
    let counted = |t: &Tally| Counted {
        jams_consistent: t.jams_consistent,
        jams_compared: t.jams_compared,
        dis_consistent: t.dis_consistent,
        dis_compared: t.dis_compared,
    };
    out.iter()
        .map(|[t3, t4, ti, trusted]| Consistency {
            table3: counted(t3),
            table4: counted(t4),
            table_i: counted(ti),
            without_copy_slips: counted(trusted),
        })
        .collect()
}

/// The ideal meshes' limits under every rule, located to `tol` % of h: per mesh, per rule.
fn ideal_limits(
    g: &train::Gearing,
    h: f64,
    rules: &[Rule],
    tol: f64,
) -> Result<Vec<Vec<ClearanceLimits>>, RunError> {
    let pairs: Vec<IdealPair> = g
        .meshes()
        .iter()
        .map(|m| {
            IdealPair::of_mesh(g, &m.label, h)
                .ok_or_else(|| RunError::Internal(format!("mesh {} has no geometry", m.label)))
        })
        .collect::<Result<_, RunError>>()?;
    let per_mesh = study::limits::limits_under_rules(&pairs, tol, rules)?;
    Ok(per_mesh
        .into_iter()
        .map(|per_rule| {
            per_rule
                .into_iter()
                .map(|(jam_below, disengage_above)| ClearanceLimits {
                    jam_below,
                    disengage_above,
                })
                .collect()
        })
        .collect())
}
