//! A table of jam cells (rows by meshes, each cell's counts): Tables 3, 4, 5 and I.

use serde::{Deserialize, Serialize};

use crate::cell::Counts;

/// A table of jam cells: rows (a Case, a Case at a clearance, an error) by meshes.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct JamTable {
    /// The meshes, the table's columns, in the gearing's order (driver-driven).
    pub meshes: Vec<String>,
    /// The rows, in the table's order.
    pub rows: Vec<JamRow>,
}

/// One row of a [`JamTable`].
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct JamRow {
    /// The row as the table prints it (`A`, `B/40`, `0.045`).
    pub label: String,
    /// Each mesh's counts, in [`JamTable::meshes`]' order.
    pub cells: Vec<Counts>,
}

impl JamTable {
    /// The table of `counts` laid out row by row (`rows.len() * meshes.len()` cells, row-major).
    pub fn from_counts(meshes: Vec<String>, rows: Vec<String>, counts: &[Counts]) -> JamTable {
        let width = meshes.len().max(1);
        let rows = rows
            .into_iter()
            .zip(counts.chunks(width))
            .map(|(label, cells)| JamRow {
                label,
                cells: cells.to_vec(),
            })
            .collect();
        JamTable { meshes, rows }
    }

    /// The counts of `mesh` in the row labelled `row`.
    pub fn cell(&self, row: &str, mesh: &str) -> Option<&Counts> {
        let m = self.meshes.iter().position(|x| x == mesh)?;
        self.rows.iter().find(|r| r.label == row)?.cells.get(m)
    }

    /// Every cell's counts, row by row.
    pub fn counts(&self) -> impl Iterator<Item = &Counts> {
        self.rows.iter().flat_map(|r| r.cells.iter())
    }
}

/// Table 3's results: each Case's cells at one clearance (one row of them when the hypothesis
/// takes no Case's errors), the hypothesis that made the gears and the clearance they ran at.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseTable {
    /// Rows `A`-`D` (or the one row of a hypothesis the Cases do not apply to) by meshes.
    pub table: JamTable,
    /// Whether the Cases' errors applied to the hypothesis (else one row, compared with no Case).
    pub cases_apply: bool,
    /// The hypothesis the gears were made with.
    pub hypothesis: String,
    /// Clearance G of every mesh, % of h.
    pub clearance: f64,
}
