//! Edmunds' Cases as data and the grids of jam cells the paper's tables run: Cases A-D at one
//! clearance (Tables 3 and I), the random-error grid (Table 4) and the sequential tolerances
//! derived from it (Tables 5 and 6, Figure 6).

use hypotheses::Hypothesis;
use registry::{Param, RunError, TrialEngine};
use train::Gearing;

use rules::Rule;

use crate::cell::{CellSpec, Counts, Purpose, run_cells};
use crate::drive::Drive;
use crate::tolerance;
use crate::{errors, gearing};

/// Edmunds' cases: (name, systematic amplitude in degrees, random fraction of the pitch).
pub const CASES: [(&str, f64, f64); 4] = [
    ("A", 0.0, 0.04),
    ("B", 0.5, 0.04),
    ("C", 1.0, 0.04),
    ("D", 2.0, 0.08),
];

/// The cells of Cases A-D at clearance `clearance`, case by case, each case's meshes in the
/// gearing's order: what Table 3 runs at G = 40 % and Table I at each of its clearances.
pub fn case_cells(s: &CellSettings, clearance: f64) -> Result<Vec<CellSpec>, RunError> {
    let mut cells = Vec::new();
    for &(_, systematic, random) in &CASES {
        let params = s.errors.case_params((systematic, random))?;
        for m in s.gearing.gearing.meshes() {
            cells.push(s.cell(&m.label, params.clone(), clearance));
        }
    }
    Ok(cells)
}

/// Whether Edmunds' Cases (a random and a systematic error each) reach `hyp`: it declares
/// `random` or `systematic` (a stack: any of its layers).
pub fn cases_apply(hyp: &dyn hypotheses::Hypothesis) -> bool {
    hyp.params()
        .iter()
        .any(|p| p.name == "random" || p.name == "systematic")
}

/// The `trials` parameter of the per-cell experiments (Tables 4, 5, I and Figure 6).
pub const TRIALS: Param = Param {
    name: "trials",
    default: "200",
    unit: "",
    help: "trials per cell (the paper: 200)",
    kind: registry::Kind::count(1, registry::MAX_TRIALS, ""),
    reading: false,
};

/// Table 4's results: counts for every (random error, mesh).
pub struct RandomGrid {
    /// Random errors (fractions of the pitch), ascending.
    pub values: Vec<f64>,
    /// Mesh labels in the gearing's order.
    pub meshes: Vec<String>,
    /// `counts[row][mesh]`.
    pub counts: Vec<Vec<Counts>>,
}

impl RandomGrid {
    /// Each mesh's largest tolerable random error under the rule (`None`: below the grid).
    pub fn tolerable(&self, trials: u64, rule: f64) -> Vec<Option<f64>> {
        (0..self.meshes.len())
            .map(|m| {
                let column: Vec<(f64, u64)> = self
                    .values
                    .iter()
                    .zip(&self.counts)
                    .map(|(&e, row)| (e, row[m].jams))
                    .collect();
                tolerance::largest_tolerable(&column, trials, rule)
            })
            .collect()
    }

    /// Every cell, for the report's trial and engagement totals.
    pub fn all(&self) -> impl Iterator<Item = &Counts> {
        self.counts.iter().flatten()
    }
}

/// Runs Table 4's grid (the random errors `values`, systematic error 0, at the settings'
/// clearance and tooth height) through the shared cell runner: Table 5, Table 6 and Figure 6
/// call this too, and get Table 4's own cells (from the cache when it already ran). `engine` runs
/// the trials ([`run_cells`]); the settings come from `s`.
pub fn run_grid(
    engine: &TrialEngine,
    s: &CellSettings,
    values: Vec<f64>,
    trials: u64,
    purpose: Purpose,
) -> Result<RandomGrid, RunError> {
    let clearance = s.clearance()?;
    let meshes: Vec<String> = s.meshes();
    let mut cells = Vec::new();
    for &e in &values {
        let params = s.errors.params(&[("random", e), ("systematic", 0.0)])?;
        for m in &meshes {
            cells.push(s.cell(m, params.clone(), clearance));
        }
    }
    let flat = run_cells(engine, &s.gearing.gearing, &cells, trials, purpose)?;
    let counts = flat.chunks(meshes.len()).map(<[Counts]>::to_vec).collect();
    Ok(RandomGrid {
        values,
        meshes,
        counts,
    })
}

/// What every table of jam cells reads first, parsed and checked once: the gearing (read and
/// checked against h) and, where the experiment declares it, the clearance G of every mesh; the
/// error settings (hypothesis, its parameters, the split); the event rule (the default where
/// the experiment counts by other means and declares none); the trials per cell.
pub struct CellSettings {
    /// The gearing, its file and h.
    pub gearing: gearing::Shape,
    /// The gearing's clearance G ([`gearing::CLEARANCE`]), when the experiment declares it.
    pub clearance: Option<f64>,
    /// The error hypothesis the cells' gears are made with, and its parameters.
    pub errors: errors::Settings,
    /// The event rule the cells count with.
    pub rule: Rule,
    /// Which gear of each mesh drives the cells' trials.
    pub drive: Drive,
    /// Where each trial's counting ends.
    pub end: crate::trial_end::End,
    /// Trials per cell.
    pub trials: u64,
}

impl CellSettings {
    /// The gearing.
    pub fn gearing(&self) -> &Gearing {
        &self.gearing.gearing
    }

    /// The hypothesis the cells' gears are made with.
    pub fn hypothesis(&self) -> &'static dyn Hypothesis {
        self.errors.hypothesis
    }

    /// Mesh labels in the gearing's order.
    pub fn meshes(&self) -> Vec<String> {
        self.gearing()
            .meshes()
            .iter()
            .map(|m| m.label.clone())
            .collect()
    }

    /// The gearing's clearance G; an experiment that does not declare it asking for it is a bug.
    pub fn clearance(&self) -> Result<f64, RunError> {
        self.clearance.ok_or_else(|| {
            RunError::Internal(format!(
                "the gearing's clearance was asked for without the `{}` parameter",
                gearing::CLEARANCE.name
            ))
        })
    }

    /// One cell: `mesh` with gears made under `params`, at `clearance` and the settings' h,
    /// rule and drive.
    pub fn cell(&self, mesh: &str, params: hypotheses::Params, clearance: f64) -> CellSpec {
        CellSpec {
            mesh: mesh.to_owned(),
            hypothesis: self.errors.hypothesis,
            params,
            tooth_height: self.gearing.tooth_height,
            clearance,
            events: self.rule.clone(),
            drive: self.drive,
            end: self.end,
        }
    }
}

/// Each mesh's tolerances, with the cells they were derived from.
pub struct Tolerances {
    /// Table 4's cells.
    pub random_grid: RandomGrid,
    /// Largest tolerable random error per mesh (`None`: even the grid's smallest fails).
    pub random: Vec<Option<f64>>,
    /// Systematic amplitudes of the grid (degrees), ascending.
    pub sys_values: Vec<f64>,
    /// `sys_counts[row][mesh]`, at the mesh's largest tolerable random error; `None` where that
    /// is below the grid (nothing run).
    pub sys_counts: Vec<Vec<Option<Counts>>>,
    /// Largest tolerable systematic amplitude per mesh; `None` when even the grid's smallest
    /// fails or the random error is below its grid.
    pub systematic: Vec<Option<f64>>,
}

impl Tolerances {
    /// Every cell run, for the report's trial and engagement totals.
    pub fn all(&self) -> impl Iterator<Item = &Counts> {
        self.random_grid
            .all()
            .chain(self.sys_counts.iter().flatten().flatten())
    }
}

/// Runs Table 4's grid (the random errors `random_values`), derives each mesh's largest
/// tolerable random error by `rule` %, then runs the systematic grid (`sys_values`) on top of it
/// (split as the settings say) and derives the largest tolerable systematic amplitude the same
/// way. Every cell goes through the shared runner, so cells Table 4 or Table 5 already ran in
/// this process are not run again.
///
/// With `given_random` (one entry per mesh, e.g. the paper's own E. max row, `--set emax=paper`)
/// the random errors are those instead and Table 4's grid is not run (`random_grid` then has the
/// grid's values but no counts).
pub fn derive(
    engine: &TrialEngine,
    s: &CellSettings,
    (random_values, sys_values): (Vec<f64>, Vec<f64>),
    rule: f64,
    purpose: Purpose,
    given_random: Option<Vec<Option<f64>>>,
) -> Result<Tolerances, RunError> {
    let trials = s.trials;
    let (clearance, split) = (s.clearance()?, s.errors.split()?);
    let (random_grid, random) = if let Some(random) = given_random {
        let grid = RandomGrid {
            values: random_values,
            meshes: s.meshes(),
            counts: Vec::new(),
        };
        (grid, random)
    } else {
        let grid = run_grid(engine, s, random_values, trials, Purpose::Input)?;
        let random = grid.tolerable(trials, rule);
        (grid, random)
    };
    let mut cells = Vec::new();
    let mut index = Vec::new();
    for &sys in &sys_values {
        for (m, mesh) in random_grid.meshes.iter().enumerate() {
            let Some(e) = random[m] else {
                index.push(None);
                continue;
            };
            let params =
                s.errors
                    .params(&[("random", e), ("systematic", sys), ("split", split)])?;
            index.push(Some(cells.len()));
            cells.push(s.cell(mesh, params, clearance));
        }
    }
    let flat = run_cells(engine, s.gearing(), &cells, trials, purpose)?;
    let n = random_grid.meshes.len();
    let sys_counts: Vec<Vec<Option<Counts>>> = index
        .chunks(n)
        .map(|row| row.iter().map(|i| i.map(|i| flat[i])).collect())
        .collect();
    let systematic = (0..n)
        .map(|m| {
            random[m]?;
            let column: Vec<(f64, u64)> = sys_values
                .iter()
                .zip(&sys_counts)
                .filter_map(|(&s, row)| row[m].map(|c| (s, c.jams)))
                .collect();
            tolerance::largest_tolerable(&column, trials, rule)
        })
        .collect();
    Ok(Tolerances {
        random_grid,
        random,
        sys_values,
        sys_counts,
        systematic,
    })
}
