//! Largest tolerable errors and what they were read from: Table 5 (each mesh's random and
//! systematic E. max, and the systematic cells between), Table 6 (a mechanism built with them:
//! its inputs and its pointers' estimates), Figure 6 (each gear's tolerable random error) and
//! the tolerance search (each mesh's, found by a sequential search).

use serde::{Deserialize, Serialize};

use crate::cell::Counts;
use crate::grids::Tolerances;
use crate::pointers::ToFirstJam;
use crate::results::RandomErrorTable;
use crate::tolerance_search::Search;

/// How a mesh's largest tolerable random error (row E. max of Table 5) was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RandomFrom {
    /// Derived, as the paper did, from Table 4's grid by the rule: the largest random error up
    /// to which every value of the grid keeps it (`emax=derived`).
    Grid,
    /// The paper's own E. max row, taken as given (`emax=paper`).
    Paper,
}

/// One mesh's largest tolerable errors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshTolerance {
    /// The mesh, driver-driven (`b2-c1`).
    pub mesh: String,
    /// Largest tolerable random error, fraction of the pitch 360/N; `None`: even the smallest
    /// value of Table 4's grid breaks the rule (its systematic cells are then not run).
    pub random: Option<f64>,
    /// How [`MeshTolerance::random`] was found.
    pub random_from: RandomFrom,
    /// Largest tolerable systematic amplitude A at that random error, degrees; `None`: even the
    /// grid's smallest amplitude breaks the rule, or the random error is below its grid.
    pub systematic: Option<f64>,
}

/// One row of Table 5: each mesh's counts at one systematic amplitude, on top of the mesh's
/// largest tolerable random error.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SystematicRow {
    /// The systematic amplitude A, degrees.
    pub systematic: f64,
    /// Each mesh's counts, in the meshes' order; `None` where the mesh's random E. max is
    /// below its grid (nothing run).
    pub cells: Vec<Option<Counts>>,
}

/// Each mesh's tolerances derived the paper's way, Table 5's results and Table 6's inputs: the
/// random E. max from Table 4's grid (or the paper's row), then the systematic grid on top of it, the
/// rule read from the counts at each step.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DerivedTolerances {
    /// Table 4's cells the random E. max were read from; with `emax=paper` its grid's values
    /// only (no rows: not run).
    pub random_grid: RandomErrorTable,
    /// Each mesh's tolerances, in the gearing's order.
    pub meshes: Vec<MeshTolerance>,
    /// Table 5's rows, one per systematic amplitude of its grid, ascending.
    pub rows: Vec<SystematicRow>,
}

impl DerivedTolerances {
    /// The tolerances `t` [`crate::grids::derive`] found at clearance `clearance` (% of h), the
    /// random ones found as `random_from` says.
    pub fn new(t: &Tolerances, clearance: f64, random_from: RandomFrom) -> DerivedTolerances {
        let meshes = t
            .random_grid
            .meshes
            .iter()
            .enumerate()
            .map(|(m, mesh)| MeshTolerance {
                mesh: mesh.clone(),
                random: t.random[m],
                random_from,
                systematic: t.systematic[m],
            })
            .collect();
        let rows = t
            .sys_values
            .iter()
            .zip(&t.sys_counts)
            .map(|(&systematic, cells)| SystematicRow {
                systematic,
                cells: cells.clone(),
            })
            .collect();
        DerivedTolerances {
            random_grid: RandomErrorTable::from_grid(&t.random_grid, clearance),
            meshes,
            rows,
        }
    }

    /// The systematic amplitudes of the grid, degrees, ascending.
    pub fn systematic_values(&self) -> Vec<f64> {
        self.rows.iter().map(|r| r.systematic).collect()
    }

    /// Every cell run, Table 4's and the systematic ones, for the report's trial and engagement
    /// totals.
    pub fn all(&self) -> impl Iterator<Item = &Counts> {
        self.random_grid
            .table
            .counts()
            .chain(self.rows.iter().flat_map(|r| r.cells.iter().flatten()))
    }
}

/// One gear's values in Table 6's mechanism: its mesh's tolerances, a gear in two meshes the
/// smaller of each.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearTolerance {
    /// The gear, as the gearing file names it.
    pub gear: String,
    /// Its random error, fraction of the pitch (a value below its grid built as 0).
    pub random: f64,
    /// Its systematic amplitude A, degrees (a value below its grid built as 0).
    pub systematic: f64,
    /// The meshes it is in, in the gearing's order.
    pub meshes: Vec<String>,
}

/// A sample mean with its 95 % Student-t interval, degrees. The bits are stored as they are (a
/// single trial's, or a pointer's with no reading, may be NaN).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate95 {
    /// The mean over the trials, degrees.
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
    /// The interval's lower end, degrees.
    #[serde(with = "registry::f64_bits")]
    pub lo: f64,
    /// The interval's upper end, degrees.
    #[serde(with = "registry::f64_bits")]
    pub hi: f64,
    /// The trials it was made from.
    pub n: usize,
}

impl From<stats::Estimate> for Estimate95 {
    fn from(e: stats::Estimate) -> Estimate95 {
        Estimate95 {
            mean: e.mean,
            lo: e.lo,
            hi: e.hi,
            n: e.n,
        }
    }
}

impl From<Estimate95> for stats::Estimate {
    fn from(e: Estimate95) -> stats::Estimate {
        stats::Estimate {
            mean: e.mean,
            lo: e.lo,
            hi: e.hi,
            n: e.n,
        }
    }
}

/// One pointer of Table 6: its run and its statistics over the trials, each up to its first
/// jam.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PointerEstimates {
    /// The pointer (`Lunar`, `Metonic`, ...).
    pub pointer: String,
    /// Input turns of its run.
    pub turns: f64,
    /// Samples of its Theoretical Difference per run.
    pub samples: usize,
    /// σ of the Theoretical Difference, degrees.
    pub sigma: Estimate95,
    /// Dm, the largest deviation from the mean, degrees.
    pub dm: Estimate95,
    /// P, the absolute value of the oscillation's mean, degrees.
    pub p: Estimate95,
    /// Trials in which the pointer jammed.
    pub jammed: u64,
    /// Tooth engagements of its train over all trials.
    pub engagements: u64,
}

impl PointerEstimates {
    /// Pointer `index`'s estimates over `trials` (per trial, per pointer), its run `(pointer,
    /// turns, samples)`.
    pub fn of(
        (pointer, turns, samples): (&str, f64, usize),
        index: usize,
        trials: &[Vec<ToFirstJam>],
    ) -> PointerEstimates {
        let column = |f: fn(&ToFirstJam) -> f64| -> Estimate95 {
            let values: Vec<f64> = trials.iter().map(|t| f(&t[index])).collect();
            stats::mean_ci95(&values).into()
        };
        PointerEstimates {
            pointer: pointer.to_owned(),
            turns,
            samples,
            sigma: column(|r| r.sigma),
            dm: column(|r| r.dm),
            p: column(|r| r.mean.abs()),
            jammed: trials.iter().filter(|t| t[index].jammed).count() as u64,
            engagements: trials.iter().map(|t| t[index].engaged).sum(),
        }
    }
}

/// Table 6's results: a mechanism built with each mesh's largest tolerable errors, and its
/// pointers' σ, Dm and P over the trials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TolerableMechanism {
    /// Each mesh's tolerances (Tables 4 and 5 at `cell_trials` trials a cell).
    pub tolerances: DerivedTolerances,
    /// Each gear's values as built, by gear name.
    pub gears: Vec<GearTolerance>,
    /// The whole-mechanism trials run.
    pub trials: u64,
    /// Each pointer's estimates over the trials, in the paper's order.
    pub pointers: Vec<PointerEstimates>,
}

/// One gear of Figure 6.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearRandom {
    /// The gear, as the gearing file names it.
    pub gear: String,
    /// The gear as the paper names it: the name its mesh's label writes (the file's own name
    /// where the two agree; they differ for the paper's n2, the file's n3).
    pub paper_name: String,
    /// Where the gearing file says the gear comes from (its `source`).
    pub source: String,
    /// The meshes it is in, in the gearing's order.
    pub meshes: Vec<String>,
    /// Its largest tolerable random error, fraction of the pitch: its mesh's, a gear in two
    /// meshes the smaller; `None`: below Table 4's grid.
    pub tolerable: Option<f64>,
    /// Its random error in the measured table given (`measured`), fraction of the pitch.
    pub measured: Option<f64>,
}

/// The measured table Figure 6 draws beside ours.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeasuredFile {
    /// The file as given.
    pub file: String,
    /// The gears it lists.
    pub gears: usize,
}

/// Figure 6's results: each gear's largest tolerable random error, read from Table 4's grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearTolerances {
    /// Table 4's cells the values were read from.
    pub random_grid: RandomErrorTable,
    /// Each gear, in mesh order of first appearance.
    pub gears: Vec<GearRandom>,
    /// The measured table given, if any.
    pub measured: Option<MeasuredFile>,
}

/// One mesh of the tolerance search.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshSearchResult {
    /// The mesh, driver-driven.
    pub mesh: String,
    /// The search: its bracket, the largest value found tolerable (`pass`) and the smallest
    /// found not (`fail`), fractions of the pitch, and every probe with its counts.
    pub search: Search,
    /// The largest tolerable random error Table 4's grid gives by the same rule, fraction of
    /// the pitch; `None`: below the grid.
    pub grid: Option<f64>,
}

/// The tolerance search's results: each mesh's largest tolerable random error by a sequential
/// search, and Table 4's grid it is compared with.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SearchedTolerances {
    /// Each mesh, in the gearing's order.
    pub meshes: Vec<MeshSearchResult>,
    /// Table 4's cells at the search's cap of trials per cell.
    pub random_grid: RandomErrorTable,
}
