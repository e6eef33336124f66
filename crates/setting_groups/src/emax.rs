//! The `emax` setting: whether Tables 5 and 6 run each mesh at the random error derived from
//! Table 4's grid, as the paper did, or at the paper's own E. max row
//! ([`presentation::emax::paper_random`]).

use registry::{Param, RunError};
use study::results::RandomFrom;

use presentation::emax::paper_random;

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
