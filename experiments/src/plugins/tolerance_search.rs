//! `tolerance`: each mesh's largest tolerable random error (no systematic error, G = 40 %, as in
//! Table 4) found by a sequential search instead of Table 4's fixed grid: bisection on the random
//! error, and at each probed value trials added a batch at a time until the jam rate is clearly
//! below or above the rule's threshold (exact 95 % interval), or the paper's count rule decides
//! at the cap. Compared with the grid-derived value (Table 4 by the rule) and the paper's E. max,
//! with the pair turns each needed.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table};
use serde::{Deserialize, Serialize};

use presentation::emax::{paper_random, show};
use setting_groups::typed::{Gearing, off_paper_inputs, unsplit_cells};
use study::cell::{Purpose, label};
use study::drive::DriveParams;
use study::errors::ErrorParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::results::{MeshSearchResult, RandomErrorTable, SearchedTolerances};
use study::tolerance::{self, RULE, RandomGrid};
use study::tolerance_search::{self as sequential, Search, search};

use presentation::units::Value;

registry::params! {
    const SEARCH_LO = Param::new("search_lo", "0.02", "lower end of the searched random error (fraction of the pitch 360/N)", study::tolerance::RANDOM_KIND).unit("pitch");
    const SEARCH_HI = Param::new("search_hi", "0.08", "upper end of the searched random error", study::tolerance::RANDOM_KIND).unit("pitch");
    const RESOLUTION = Param::new("resolution", "0.0025", "the bisection stops when the bracket is at most this wide", registry::Kind::positive(f64::INFINITY, "")).unit("pitch");
    const BATCH = Param::new("batch", "20", "trials added to a probed value at a time", registry::Kind::count(1, registry::MAX_TRIALS, ""));
    const CAP = Param::new("cap", "200", "most trials at one probed value, where the paper's count rule decides; also the trials per cell of the Table 4 grid compared with (the paper: 200)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
}

/// The tolerance search's settings: the searched range and its resolution, the rule, the
/// trials per batch and at most per probe, the gearing with h and G, the hypothesis, Table 4's
/// grid compared with, the event rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
#[settings(check = check)]
pub struct Settings {
    /// Lower end of the searched random error, fraction of the pitch ([`SEARCH_LO`]).
    #[param(SEARCH_LO)]
    pub search_lo: f64,
    /// Upper end ([`SEARCH_HI`]).
    #[param(SEARCH_HI)]
    pub search_hi: f64,
    /// The bisection stops at a bracket this narrow ([`RESOLUTION`]).
    #[param(RESOLUTION)]
    pub resolution: f64,
    /// The tolerance rule, % of trials jamming ([`RULE`]).
    #[param(RULE)]
    pub rule: f64,
    /// Trials added to a probe at a time ([`BATCH`]).
    #[param(BATCH)]
    pub batch: u64,
    /// Most trials at one probe, and the trials per cell of Table 4's grid ([`CAP`]).
    #[param(CAP)]
    pub cap: u64,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The hypothesis and its parameters.
    #[group]
    pub errors: ErrorParams,
    /// Table 4's random errors, compared with.
    #[group]
    pub random: RandomGrid,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// The tolerance search.
pub struct ToleranceSearch;

impl registry::Experiment for ToleranceSearch {
    const ID: &'static str = "tolerance";
    const TITLE: &'static str = "Largest tolerable random error of each mesh by a sequential search (bisection, trials added until the jam rate is clearly below or above the rule), against Table 4's grid";
    const PAPER_ITEM: &'static str =
        "Section 5, Tables 4-5 (tolerance by sequential search; beyond the paper)";
    const PLACE: Place = Place::Beyond(10);
    type Settings = Settings;
    type Results = SearchedTolerances;

    fn compute(s: &Settings, run: &Run) -> Result<SearchedTolerances, RunError> {
        // Table 4's grid runs `cap` trials a cell, the most a search's probe runs.
        let cells = unsplit_cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            Some(&s.events),
            Some(&s.drive),
            s.cap,
            s,
        )?;
        let clearance = cells.clearance()?;
        // The grid's parameters are checked before anything runs.
        let values = s.random.values(s)?;
        let searches = search(run.engine(), &cells, &sequential_settings(s))?;
        let grid = study::grids::run_grid(run.engine(), &cells, values, s.cap, Purpose::Input)?;
        let random_grid = RandomErrorTable::from_grid(&grid, clearance);
        let tolerable = grid.tolerable(s.cap, s.rule);
        let meshes = grid
            .meshes
            .iter()
            .zip(searches)
            .zip(tolerable)
            .map(|((mesh, search), grid)| MeshSearchResult {
                mesh: mesh.clone(),
                search,
                grid,
            })
            .collect();
        Ok(SearchedTolerances {
            meshes,
            random_grid,
        })
    }

    fn report(s: &Settings, r: &SearchedTolerances) -> Result<Report, RunError> {
        let grid = &r.random_grid;
        let grid_per_mesh = grid.random.len() as u64 * s.cap;
        let mut table = search_table(s, grid.clearance);
        let mut csv = String::from(
            "mesh,search_emax,search_fail,grid_emax,paper_emax,probes,search_trials,grid_trials,saved_percent\n",
        );
        let mut probes_csv =
            String::from("mesh,probe,random,trials,jams,disengagements,decision\n");
        let compared = off_paper_inputs(s).is_empty();
        let (mut inside, mut outside) = (0, 0);
        let (mut used_total, mut grid_total, mut probes_total) = (0, 0, 0);
        for m in &r.meshes {
            let (mesh, sr) = (&m.mesh, &m.search);
            let paper = paper_random(mesh);
            // Compared only where the run's inputs are the paper's.
            let agrees = paper
                .filter(|_| compared)
                .map(|p| within_resolution(sr.pass, p, s.resolution));
            inside += u64::from(agrees == Some(true));
            outside += u64::from(agrees == Some(false));
            let used = sr.trials();
            used_total += used;
            grid_total += grid_per_mesh;
            probes_total += sr.probes.len();
            table.row(mesh_row(
                m,
                paper_cell(paper, agrees),
                used,
                grid_per_mesh,
                grid,
            ));
            csv.push_str(&csv_line(m, paper, used, grid_per_mesh));
            probes_csv.push_str(&probe_lines(mesh, sr));
        }
        table.row(total_row(probes_total, used_total, grid_total));
        explain(&mut table, s, grid, (inside, outside));
        let trials = used_total + grid.table.counts().map(|c| c.trials).sum::<u64>();
        let engagements = r.meshes.iter().map(|m| m.search.engagements()).sum::<u64>()
            + grid.table.counts().map(|c| c.engagements).sum::<u64>();
        let report = Report {
            tables: vec![table, emax_in_units(r)],
            files: vec![
                OutputFile::new("tolerance.csv", csv),
                OutputFile::new("tolerance-probes.csv", probes_csv),
            ],
            trials,
            engagements,
            agreement: compared.then_some(registry::Agreement {
                consistent: inside,
                differ: outside,
                what: "meshes whose E. max in the paper lies within one resolution of the search's / further (no test)".into(),
            }),
            ..Default::default()
        };
        setting_groups::typed::label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(ToleranceSearch);

/// Each mesh's largest tolerable random error by the search, in units of both its gears.
fn emax_in_units(r: &SearchedTolerances) -> Table {
    presentation::units::emax_table(
        "The search's largest tolerable random error in units of each gear".to_string(),
        &r.random_grid.gears,
        None,
        |m| {
            let sr = &r.meshes[m].search;
            let random = match (sr.pass, sr.fail) {
                (Some(p), None) => Value::AtLeast(p),
                (Some(p), Some(_)) => Value::At(p),
                (None, _) => Value::Below(sr.lo),
            };
            (random, Value::Missing)
        },
    )
}

/// What the sequential search runs.
fn sequential_settings(s: &Settings) -> sequential::Settings {
    sequential::Settings {
        lo: s.search_lo,
        hi: s.search_hi,
        resolution: s.resolution,
        rule: s.rule,
        batch: s.batch,
        cap: s.cap,
    }
}

/// The checks across the search's parameters: a range from low to high, a rule strictly
/// between 0 and 100 %, a cap of at least one batch; a refusal names the parameter the user set.
fn check(s: &Settings, _: &registry::Context) -> Result<(), RunError> {
    let (lo, hi, rule) = (s.search_lo, s.search_hi, s.rule);
    let short = registry::fmt_number;
    if hi.is_nan() || lo >= hi {
        // Name the one the user set: `search_hi` at or below the default low end, or
        // `search_lo` at or above the high end.
        let mut changed = Vec::new();
        registry::Settings::changed(s, &mut changed);
        let hi_set = changed.iter().any(|(p, _)| p.name == SEARCH_HI.name);
        let (field, rule) = if hi_set {
            (
                SEARCH_HI.name,
                format!(
                    "must be greater than {} = {} (got {})",
                    SEARCH_LO.name,
                    short(lo),
                    short(hi)
                ),
            )
        } else {
            (
                SEARCH_LO.name,
                format!(
                    "must be less than {} = {} (got {})",
                    SEARCH_HI.name,
                    short(hi),
                    short(lo)
                ),
            )
        };
        return Err(RunError::bad("--set", field, rule));
    }
    if rule.is_nan() || rule <= 0.0 || rule >= 100.0 {
        return Err(RunError::bad(
            "--set",
            RULE.name,
            format!(
                "must be a percentage strictly between 0 and 100 (got {})",
                short(rule)
            ),
        ));
    }
    if s.cap < s.batch {
        return Err(RunError::bad(
            "--set",
            CAP.name,
            format!(
                "must be at least {} = {} (got {})",
                BATCH.name, s.batch, s.cap
            ),
        ));
    }
    Ok(())
}

/// A search's result as printed: the largest tolerable value, `< lo` when even `lo` failed,
/// `>= hi` when even `hi` passed.
fn show_search(sr: &Search) -> String {
    match sr.pass {
        Some(p) if sr.fail.is_none() => format!(">= {}", label(p, 3)),
        Some(p) => label(p, 3),
        None => format!("< {}", label(sr.lo, 3)),
    }
}

/// The notes under the table: how the search brackets and decides, and what the grid ran;
/// `inside` and `outside` count the paper's E. max within one resolution of the search's and
/// further.
fn explain(
    table: &mut Table,
    s: &Settings,
    grid: &RandomErrorTable,
    (inside, outside): (u64, u64),
) {
    let allowed = tolerance::allowed_jams(s.cap, s.rule);
    table.note(format!(
        "Search: bisection of [{}, {}] (assuming the jam rate grows with the error) until the bracket is at most {} wide; the value shown is the largest probed value found tolerable, so the mesh's limit lies between it and the next probed value that failed (CSV). `< {}`: even the lower end failed; `>= {}`: even the upper end passed.",
        label(s.search_lo, 3),
        label(s.search_hi, 3),
        label(s.resolution, 3),
        label(s.search_lo, 3),
        label(s.search_hi, 3),
    ));
    table.note(format!(
        "Sequential test at each probed value: {} trials at a time, stopping as soon as the exact (Clopper-Pearson) 95 % interval of the jam rate lies entirely below or above {} %, or the count rule at the cap is already settled (more than {allowed} jams); at {} trials the paper's rule decides (at most {allowed} jams). With a 1 % rule and a cap of 200 a tolerable value always runs to the cap (0 of n has an upper bound below 1 % only from n = 368), so the savings come from failing values stopped early and from fewer values probed.",
        s.batch, s.rule, s.cap,
    ));
    table.note(format!(
        "Grid: Table 4's cells ({} values from {} by {}, {} trials each) by the same rule; a probed value on the grid uses the same trial streams as the grid's cell. Paper's E. max within one resolution of the search's: {inside} meshes; further: {outside}.",
        grid.random.len(),
        grid.random.first().map_or_else(|| "-".into(), |v| label(*v, 3)),
        label(s.random.random_step, 3),
        s.cap,
    ));
}

/// The share of a grid's `grid` trials a search saved by running `used` (%; 0 for no grid).
fn saved(used: u64, grid: u64) -> f64 {
    if grid == 0 {
        0.0
    } else {
        100.0 * (1.0 - used as f64 / grid as f64)
    }
}

/// The table's title and columns.
fn search_table(s: &Settings, clearance: f64) -> Table {
    Table::new(
        format!(
            "Largest tolerable random error of each mesh (rule {} %, no systematic error, G = {clearance} %) [fraction of the pitch]: sequential search against Table 4's grid and the paper's E. max; * where the paper's is more than one resolution ({}) from the search's",
            s.rule,
            label(s.resolution, 3),
        ),
        vec![
            "mesh",
            "search",
            "grid",
            "paper",
            "probes",
            "search pair turns",
            "grid pair turns",
            "saved %",
        ],
    )
}

/// One mesh's probes, a CSV line each, in the order the search ran them.
fn probe_lines(mesh: &str, sr: &Search) -> String {
    let mut out = String::new();
    for (i, p) in sr.probes.iter().enumerate() {
        out.push_str(&registry::csv_row!(
            mesh,
            i + 1,
            p.value,
            p.counts.trials,
            p.counts.jams,
            p.counts.disengagements,
            format!("{:?}", p.decision)
        ));
    }
    out
}

/// Whether the search's tolerable value is within one resolution of the paper's `p`.
fn within_resolution(pass: Option<f64>, p: f64, resolution: f64) -> bool {
    pass.is_some_and(|o| (o - p).abs() <= resolution * (1.0 + 1e-9))
}

/// The last row: probes and pair turns summed over the meshes.
fn total_row(probes: usize, used: u64, grid: u64) -> Vec<String> {
    vec![
        "total".into(),
        String::new(),
        String::new(),
        String::new(),
        probes.to_string(),
        used.to_string(),
        grid.to_string(),
        format!("{:.0}", saved(used, grid)),
    ]
}

/// The paper's E. max of a mesh, `*` where it is further than one resolution from the search's
/// (`agrees`: `None` where not compared).
fn paper_cell(paper: Option<f64>, agrees: Option<bool>) -> String {
    format!(
        "{}{}",
        paper.map_or_else(|| "-".into(), |p| label(p, 3)),
        if agrees == Some(false) { "*" } else { "" }
    )
}

/// One mesh's row: the search's value, the grid's and the paper's (`paper`, already marked),
/// the probes, the pair turns the search used (`used`) against the grid's, and the share saved.
fn mesh_row(
    m: &MeshSearchResult,
    paper: String,
    used: u64,
    grid_per_mesh: u64,
    grid: &RandomErrorTable,
) -> Vec<String> {
    vec![
        m.mesh.clone(),
        show_search(&m.search),
        show(m.grid, grid.random.first(), 3),
        paper,
        m.search.probes.len().to_string(),
        used.to_string(),
        grid_per_mesh.to_string(),
        format!("{:.0}", saved(used, grid_per_mesh)),
    ]
}

/// One mesh's line of tolerance.csv.
fn csv_line(m: &MeshSearchResult, paper: Option<f64>, used: u64, grid_per_mesh: u64) -> String {
    let opt = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
    registry::csv_row!(
        m.mesh,
        opt(m.search.pass),
        opt(m.search.fail),
        opt(m.grid),
        opt(paper),
        m.search.probes.len(),
        used,
        grid_per_mesh,
        format!("{:.1}", saved(used, grid_per_mesh))
    )
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    fn run_with(sets: &[(&str, &str)]) -> Result<Report, RunError> {
        crate::run("tolerance", 2025, 2, sets)
    }

    #[test]
    fn a_tiny_search_runs_end_to_end() {
        let sets = [
            ("search_lo", "0.03"),
            ("search_hi", "0.07"),
            ("resolution", "0.02"),
            ("batch", "5"),
            ("cap", "10"),
            ("rule", "10"),
            ("random_from", "0.05"),
            ("random_to", "0.05"),
        ];
        let report = run_with(&sets).unwrap();
        let table = &report.tables[0];
        assert_eq!(table.rows.len(), 16, "15 meshes and the total");
        let total = table.rows.last().unwrap();
        assert_eq!(total[0], "total");
        assert_eq!(
            total[6],
            (15 * 10).to_string(),
            "one grid value of 10 trials"
        );
        let used: u64 = total[5].parse().unwrap();
        assert!(used > 0 && used <= 15 * 3 * 10, "{used}");
        assert_eq!(report.trials, used + 150);
        assert_eq!(report, run_with(&sets).unwrap(), "deterministic");
    }

    #[test]
    fn bad_parameters_are_bad_input() {
        for (k, v) in [
            ("search_hi", "0.02"),
            ("resolution", "0"),
            ("rule", "0"),
            ("rule", "100"),
            ("batch", "0"),
            ("cap", "10"),
        ] {
            let e = run_with(&[(k, v)]).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{k}={v}");
            assert!(e.to_string().contains(k), "{k}={v}: {e}");
        }
    }
}
