//! Tables of jam cells (rows by meshes, each cell's counts): Tables 3, 4 and I, and Table 4's
//! grid where Tables 5 and 6, Figure 6 and the tolerance search read it.

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

/// Table 4's results: each mesh's counts against the random tooth error, no systematic error,
/// at one clearance (Table 5, Table 6, Figure 6 and the tolerance search read their E. max from
/// the same cells).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RandomErrorTable {
    /// The grid's random errors, ascending: each the standard deviation of a tip's displacement
    /// as a fraction of the pitch 360/N (Edmunds' tooth error).
    pub random: Vec<f64>,
    /// The counts: a row per random error of [`RandomErrorTable::random`], labelled as printed
    /// (three decimals at least, `0.035`), a column per mesh. No rows where the grid was not
    /// run (Table 5 and Table 6 on the paper's own E. max row, `emax=paper`).
    pub table: JamTable,
    /// Clearance G of every mesh, % of the tooth height h.
    pub clearance: f64,
}

impl RandomErrorTable {
    /// The cells of a grid Table 4's way ([`crate::grids::run_grid`]) ran at `clearance`.
    pub fn from_grid(grid: &crate::grids::RandomGrid, clearance: f64) -> RandomErrorTable {
        let rows = grid
            .counts
            .iter()
            .zip(&grid.values)
            .map(|(cells, &e)| JamRow {
                label: crate::cell::label(e, 3),
                cells: cells.clone(),
            })
            .collect();
        RandomErrorTable {
            random: grid.values.clone(),
            table: JamTable {
                meshes: grid.meshes.clone(),
                rows,
            },
            clearance,
        }
    }
}

/// Table I's results: each mesh's counts for Edmunds' Cases A-D at each of several clearances.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct CaseClearanceTable {
    /// The clearances G run, % of the tooth height h, in the order listed (`clearances`).
    pub clearances: Vec<f64>,
    /// Whether the Cases' errors reach the hypothesis; if not, the four Cases are the same
    /// cells and Case A's stand for all (one row per clearance).
    pub cases_apply: bool,
    /// The hypothesis the gears were made with.
    pub hypothesis: String,
    /// The counts: a row per Case and clearance, Case by Case and each Case's clearances in
    /// [`CaseClearanceTable::clearances`]' order, labelled `CASE/G` (`B/70`; `A-D/70` where
    /// the Cases do not apply); a column per mesh.
    pub table: JamTable,
}

impl CaseClearanceTable {
    /// The row of Case number `case` (0 for A) at clearance number `clearance` of
    /// [`CaseClearanceTable::clearances`].
    pub fn row(&self, case: usize, clearance: usize) -> Option<&JamRow> {
        self.table
            .rows
            .get(case * self.clearances.len() + clearance)
    }
}
