//! `jam-readings`' results: the jams of the paper's per-mesh tables (Tables 3, 4 and I) counted
//! under each contact test - our exact solver under each drive, the paper's kind of stepped area
//! test at each overlap tolerance - and how many of the paper's jam counts each reading finds
//! consistent with ours, per region.

use serde::{Deserialize, Serialize};

/// Every reading's jam counts of the paper's cells, and the summary of each against the paper.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct JamReadings {
    /// Trials per cell (every reading runs the same gears and initial angle of trial t).
    pub trials: u64,
    /// The readings, in the order every cell's jams are given: the exact solver under each
    /// drive, then the area test at each tolerance.
    pub readings: Vec<ContactReading>,
    /// The regions the paper's counts are tallied in, in print order: `Table 4`, each clearance
    /// (`G = 10 %`, ...), then `Case D` (its cells at every clearance, also in their G's region).
    pub regions: Vec<String>,
    /// Per reading (in [`JamReadings::readings`]' order): the paper's jam counts consistent
    /// with ours, per region and in all.
    pub shares: Vec<ReadingShares>,
    /// Every paper cell compared, in the order of `event-rules` (Table I's 40 % cells are Table
    /// 3's, compared under each).
    pub cells: Vec<ReadingCell>,
    /// Distinct cells run (Table 3's cells are Table I's at G = 40 %, run once).
    pub cells_run: usize,
    /// The gearing's meshes, in its order (driver-driven).
    pub meshes: Vec<String>,
    /// The seed every cell's stream comes from.
    pub seed: u64,
}

/// One contact test applied to every cell alike.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactReading {
    /// The reading as the tables name it (`exact solver, drive listed`,
    /// `area T = 0.0010 mm^2, drive listed`).
    pub name: String,
    /// The overlap area the area test ignores, mm²; `None`: our exact solver.
    pub tolerance: Option<f64>,
    /// Which gear of each mesh drives: `listed`, `other` or `either`.
    pub drive: String,
}

/// One reading's tally against the paper's jam counts.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ReadingShares {
    /// Per region (in [`JamReadings::regions`]' order).
    pub per_region: Vec<JamConsistency>,
    /// Every paper jam count once.
    pub all: JamConsistency,
}

/// The paper's jam counts consistent with ours (Fisher's exact two-sample test at 5 %, ours of
/// [`JamReadings::trials`] trials, the paper's of 200), and of the others how many of ours are
/// higher.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct JamConsistency {
    /// The paper's counts consistent with ours.
    pub consistent: u64,
    /// The paper's counts compared (those it gives).
    pub compared: u64,
    /// Among the counts the test separates, those where our rate is the higher.
    pub higher: u64,
}

/// One of the paper's cells and our jam counts of it under every reading.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ReadingCell {
    /// The table its paper counts are in: `table3`, `table4` or `tableI`.
    pub table: String,
    /// Its key in the paper's reference file (`B.m3-e3`, `0.065.m3-e3`, `B.70.m3-e3`).
    pub key: String,
    /// Its region (`Table 4`, or its clearance `G = 40 %`).
    pub region: String,
    /// Its mesh (driver-driven).
    pub mesh: String,
    /// Whether it is a cell of Edmunds' Case D.
    pub case_d: bool,
    /// Trials with at least one jam under each reading, of [`JamReadings::trials`], in
    /// [`JamReadings::readings`]' order.
    pub jams: Vec<u64>,
}
