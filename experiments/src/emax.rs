//! The paper's largest tolerable errors (Table 5's E. max row and the systematic tolerances its
//! counts give) beside ours, and the `emax` setting that runs Tables 5 and 6 on the paper's row.

use registry::{Param, RunError};
use study::cell::{PAPER_TRIALS, label};
use study::results::RandomFrom;
use study::tolerance;

use presentation::cells::paper_counts;

/// Where each mesh's random error comes from: derived, as the paper did, or the paper's own row.
pub const EMAX: Param = Param {
    name: "emax",
    default: "derived",
    unit: "",
    help: "each mesh's random error (row E. max): `derived` from Table 4's grid by the rule, as the paper did, or `paper`, the paper's own E. max row, so that every cell is run on the paper's inputs and compared like for like",
    kind: registry::Kind::Choice(&["derived", "paper"]),
    reading: true,
    clearance: false,
    recorded: false,
};

/// Where the `emax` parameter's value `emax` takes each mesh's random error from: the paper's
/// own E. max row for `paper`, else derived from Table 4's grid (its kind admits only `derived`
/// and `paper`).
pub fn random_from(emax: &str) -> RandomFrom {
    if emax.trim() == "paper" {
        RandomFrom::Paper
    } else {
        RandomFrom::Grid
    }
}

/// Each mesh's random error from the paper's E. max row; an error naming the first mesh the
/// paper gives none for (a custom gearing).
fn paper_emax_row(meshes: &[String]) -> Result<Vec<Option<f64>>, RunError> {
    meshes
        .iter()
        .map(|m| {
            paper_random(m).map(Some).ok_or_else(|| {
                RunError::bad(
                    "--set",
                    EMAX.name,
                    format!("`paper` needs the paper's E. max of every mesh, and it gives none for mesh {m}"),
                )
            })
        })
        .collect()
}

/// The paper's largest tolerable random error of `mesh` (Table 5, row E. max).
pub fn paper_random(mesh: &str) -> Option<f64> {
    presentation::paper::get("table5", &format!("emax.{mesh}")).map(|r| r.value)
}

/// The largest tolerable systematic amplitude the paper's own Table 5 counts give for `mesh` by
/// the same rule (the paper states it in words for two meshes only); `None` when the paper has
/// no count for some value of the grid.
pub fn paper_systematic(mesh: &str, sys_values: &[f64], rule: f64) -> Option<Option<f64>> {
    let column: Option<Vec<(f64, u64)>> = sys_values
        .iter()
        .map(|&s| {
            paper_counts("table5", &format!("{}.{mesh}", label(s, 1)))
                .0
                .map(|j| (s, j))
        })
        .collect();
    column.map(|c| tolerance::largest_tolerable(&c, PAPER_TRIALS, rule))
}

/// A tolerance as printed: the value, or `< smallest` when below the grid.
pub fn show(v: Option<f64>, smallest: Option<&f64>, decimals: usize) -> String {
    match (v, smallest) {
        (Some(v), _) => label(v, decimals),
        (None, Some(s)) => format!("< {}", label(*s, decimals)),
        (None, None) => "-".into(),
    }
}

/// The random errors `--set emax` asks [`study::grids::derive`] to use: the paper's E. max row
/// (one per mesh of `meshes`) where they come `from` the paper, `None` (derive them) where from
/// Table 4's grid.
pub fn given_row(
    from: RandomFrom,
    meshes: &[String],
) -> Result<Option<Vec<Option<f64>>>, RunError> {
    match from {
        RandomFrom::Grid => Ok(None),
        RandomFrom::Paper => paper_emax_row(meshes).map(Some),
    }
}
