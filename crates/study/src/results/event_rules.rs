//! `event-rules`' results: the cells of Tables 3, 4 and I counted under every event rule and
//! every drive reading (which gear of each mesh drives) and end of a trial's counting, how many
//! of the paper's counts each reading finds consistent with ours, and each rule's clearance
//! limits of the ideal meshes.

use serde::{Deserialize, Serialize};

use crate::cell::Counts;

/// Every reading's counts of the paper's cells, and the ideal meshes' limits under every rule.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct EventRules {
    /// Trials per cell (each counted under every reading).
    pub trials: u64,
    /// The readings, in the order every cell's counts are given: each registered rule (name
    /// order) under each drive at the run's end, then the default rule under each drive at each
    /// other end.
    pub countings: Vec<Reading>,
    /// Per reading (in [`EventRules::countings`]' order): the paper's counts consistent with ours.
    pub consistency: Vec<Consistency>,
    /// Every cell of the paper's tables compared, in the order the tables print them (Table I's
    /// 40 % cells are Table 3's, listed under each).
    pub cells: Vec<RuleCell>,
    /// The gearing's meshes, in its order (driver-driven).
    pub meshes: Vec<String>,
    /// The registered rules at their defaults, in name order, as the titles name them: the
    /// columns of [`EventRules::limits`].
    pub rules: Vec<String>,
    /// Per mesh (in [`EventRules::meshes`]' order), per rule (in [`EventRules::rules`]' order):
    /// the ideal pair's clearance limits.
    pub limits: Vec<Vec<ClearanceLimits>>,
}

/// One reading: a rule of what counts as a jam or a disengagement, which gear drives, and where
/// a trial's counting ends.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Reading {
    /// The rule's name (`idle-rotation`, `paper`, ...).
    pub rule: String,
    /// The rule as the titles name it (with any parameters).
    pub rule_label: String,
    /// Which gear drives: `listed`, `other` or `either`.
    pub drive: String,
    /// Where a trial's counting ends: `turn`, `first-event` or `first-disengagement`.
    pub end: String,
}

/// How many of the paper's counts a reading finds consistent with ours (Fisher's exact
/// two-sample test at 5 %, ours of [`EventRules::trials`] trials, the paper's of 200), per table.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Consistency {
    /// Table 3's counts (Cases A-D at the clearance G).
    pub table3: Counted,
    /// Table 4's counts (random error only, its grid of rows).
    pub table4: Counted,
    /// Table I's counts (Cases A-D at each of its clearances).
    pub table_i: Counted,
    /// The three tables' counts without those that look copied from another cell (flagged
    /// `suspect` in the paper's reference file).
    pub without_copy_slips: Counted,
}

/// The paper's counts consistent with ours, out of those compared: jams and disengagements.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Counted {
    /// Jam counts consistent with ours.
    pub jams_consistent: u64,
    /// Jam counts compared (the paper gives them).
    pub jams_compared: u64,
    /// Disengagement counts consistent with ours.
    pub dis_consistent: u64,
    /// Disengagement counts compared.
    pub dis_compared: u64,
}

/// One of the paper's cells and our counts of it under every reading.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RuleCell {
    /// The table its paper counts are in: `table3`, `table4` or `tableI`.
    pub table: String,
    /// Its key in the paper's reference file (`B.m3-e3`, `0.065.m3-e3`, `B.70.m3-e3`).
    pub key: String,
    /// The group it is reported in (table, Case and clearance).
    pub group: String,
    /// Its region: `Table 4`, or the clearance of a Case's cell (`G = 40 %`).
    pub region: String,
    /// Whether it is a cell of Edmunds' Case D (at any clearance).
    pub case_d: bool,
    /// Its mesh (driver-driven).
    pub mesh: String,
    /// Our counts under each reading, in [`EventRules::countings`]' order.
    pub counts: Vec<Counts>,
}

/// An ideal mesh's clearance limits under one rule, % of the tooth height h.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct ClearanceLimits {
    /// The smallest clearance without a jam (`None`: none in 0-100 %).
    pub jam_below: Option<f64>,
    /// The largest clearance without a disengagement (`None`: none in 0-100 %).
    pub disengage_above: Option<f64>,
}

impl Consistency {
    /// The tables' counts, in the order `table3`, `table4`, `tableI`.
    pub fn tables(&self) -> [&Counted; 3] {
        [&self.table3, &self.table4, &self.table_i]
    }
}
