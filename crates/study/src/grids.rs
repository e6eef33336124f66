//! Edmunds' Cases as data and the grids of jam cells the paper's tables run: Cases A-D at one
//! clearance (Tables 3 and I), the random-error grid (Table 4) and the sequential tolerances
//! derived from it (Tables 5 and 6, Figure 6).

use hypotheses::Hypothesis;
use registry::{Context, Param, RunError};
use train::Gearing;

use crate::cell::{CellSpec, Counts, Purpose, run_cells};
use crate::errors;
use crate::events;
use crate::tolerance::{
    self, RANDOM_FROM, RANDOM_STEP, RANDOM_TO, SYSTEMATIC_FROM, SYSTEMATIC_STEP, SYSTEMATIC_TO,
};

/// Edmunds' cases: (name, systematic amplitude in degrees, random fraction of the pitch).
pub const CASES: [(&str, f64, f64); 4] = [
    ("A", 0.0, 0.04),
    ("B", 0.5, 0.04),
    ("C", 1.0, 0.04),
    ("D", 2.0, 0.08),
];

/// The parameters of `hyp` for an error of `systematic` degrees and `random` of the pitch (as
/// Edmunds' Cases give them), with the `split` parameter: those `hyp` declares, then the user's
/// `hypothesis_params` ([`errors::params`]).
pub fn case_params(
    ctx: &Context,
    hyp: &dyn Hypothesis,
    (systematic, random): (f64, f64),
) -> Result<hypotheses::Params, RunError> {
    let split = ctx.f64("split")?;
    let values = [
        ("random", random),
        ("systematic", systematic),
        ("split", split),
    ];
    errors::params(ctx, hyp, &values)
}

/// The cells of Cases A-D at clearance `clearance`, case by case, each case's meshes in the
/// gearing's order: what Table 3 runs at G = 40 % and Table I at each of its clearances.
pub fn case_cells(
    ctx: &Context,
    g: &train::Gearing,
    hyp: &'static dyn hypotheses::Hypothesis,
    clearance: f64,
) -> Result<Vec<CellSpec>, RunError> {
    let h = ctx.f64("tooth_height")?;
    let mut cells = Vec::new();
    for &(_, systematic, random) in &CASES {
        let params = case_params(ctx, hyp, (systematic, random))?;
        for m in g.meshes() {
            cells.push(CellSpec {
                mesh: m.label.clone(),
                hypothesis: hyp,
                params: params.clone(),
                tooth_height: h,
                clearance,
                events: events::chosen(ctx)?,
            });
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

/// Runs Table 4's grid (`random_from`..`random_to` by `random_step`, systematic error 0, at the
/// context's clearance and tooth height) through the shared cell runner: Table 5, Table 6 and
/// Figure 6 call this too, and get Table 4's own cells (from the cache when it already ran).
pub fn run_grid(
    ctx: &Context,
    g: &Gearing,
    hyp: &'static dyn Hypothesis,
    trials: u64,
    purpose: Purpose,
) -> Result<RandomGrid, RunError> {
    let values = tolerance::grid(ctx, &RANDOM_FROM, &RANDOM_TO, &RANDOM_STEP)?;
    let (h, clearance) = (ctx.f64("tooth_height")?, ctx.f64("clearance")?);
    let meshes: Vec<String> = g.meshes().iter().map(|m| m.label.clone()).collect();
    let mut cells = Vec::new();
    for &e in &values {
        let params = errors::params(ctx, hyp, &[("random", e), ("systematic", 0.0)])?;
        for m in &meshes {
            cells.push(CellSpec {
                mesh: m.clone(),
                hypothesis: hyp,
                params: params.clone(),
                tooth_height: h,
                clearance,
                events: events::chosen(ctx)?,
            });
        }
    }
    let flat = run_cells(ctx, g, &cells, trials, purpose)?;
    let counts = flat.chunks(meshes.len()).map(<[Counts]>::to_vec).collect();
    Ok(RandomGrid {
        values,
        meshes,
        counts,
    })
}

/// What every table of jam cells reads first, parsed and checked once: the gearing (read and
/// checked against h and G), the error hypothesis and the trials per cell.
pub struct CellSettings {
    /// The gearing.
    pub gearing: Gearing,
    /// The error hypothesis the cells' gears are made with.
    pub hypothesis: &'static dyn Hypothesis,
    /// Trials per cell (the parameter named when reading).
    pub trials: u64,
}

impl CellSettings {
    /// Reads the gearing group, the hypothesis and the trials parameter `trials`.
    pub fn read(ctx: &Context, trials: &str) -> Result<CellSettings, RunError> {
        Ok(CellSettings {
            gearing: crate::gearing::load(ctx)?,
            hypothesis: errors::chosen(ctx)?,
            trials: ctx.u64(trials)?,
        })
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

/// Runs Table 4's grid, derives each mesh's largest tolerable random error by `rule` %, then runs
/// the systematic grid on top of it (split by the `split` parameter) and derives the largest
/// tolerable systematic amplitude the same way. Every cell goes through the shared runner, so
/// cells Table 4 or Table 5 already ran in this process are not run again.
///
/// With `given_random` (one entry per mesh, e.g. the paper's own E. max row, `--set emax=paper`)
/// the random errors are those instead and Table 4's grid is not run (`random_grid` then has the
/// grid's values but no counts).
pub fn derive(
    ctx: &Context,
    g: &Gearing,
    hyp: &'static dyn Hypothesis,
    trials: u64,
    rule: f64,
    purpose: Purpose,
    given_random: Option<Vec<Option<f64>>>,
) -> Result<Tolerances, RunError> {
    // Every parameter checked before anything runs.
    let sys_values = tolerance::grid(ctx, &SYSTEMATIC_FROM, &SYSTEMATIC_TO, &SYSTEMATIC_STEP)?;
    let (h, clearance, split) = (
        ctx.f64("tooth_height")?,
        ctx.f64("clearance")?,
        ctx.f64("split")?,
    );
    let (random_grid, random) = if let Some(random) = given_random {
        let meshes: Vec<String> = g.meshes().iter().map(|m| m.label.clone()).collect();
        let values = tolerance::grid(ctx, &RANDOM_FROM, &RANDOM_TO, &RANDOM_STEP)?;
        let grid = RandomGrid {
            values,
            meshes,
            counts: Vec::new(),
        };
        (grid, random)
    } else {
        let grid = run_grid(ctx, g, hyp, trials, Purpose::Input)?;
        let random = grid.tolerable(trials, rule);
        (grid, random)
    };
    let mut cells = Vec::new();
    let mut index = Vec::new();
    for &s in &sys_values {
        for (m, mesh) in random_grid.meshes.iter().enumerate() {
            let Some(e) = random[m] else {
                index.push(None);
                continue;
            };
            let params = errors::params(
                ctx,
                hyp,
                &[("random", e), ("systematic", s), ("split", split)],
            )?;
            index.push(Some(cells.len()));
            cells.push(CellSpec {
                mesh: mesh.clone(),
                hypothesis: hyp,
                params,
                tooth_height: h,
                clearance,
                events: events::chosen(ctx)?,
            });
        }
    }
    let flat = run_cells(ctx, g, &cells, trials, purpose)?;
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
