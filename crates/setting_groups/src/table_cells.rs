//! Whether a cell typed for `cargo xtask replay` is a cell of its table under the run's settings:
//! a clearance of Table I's list, a random error of Table 4's grid, a systematic error of Table
//! 5's rows at the mesh's own E. max. A cell the grammar reads but the table never ran
//! (`tableI B/55/m3-e3`, `table4 0.066/m3-e3`, `table5 0.035/0.7/e4-f1`) would otherwise be
//! replayed and titled as if the table had counted it. Refused naming the part typed, the
//! table's values for it and the setting that changes them.
//!
//! The grammar ([`replay::CellGrammar`], registered by each table's file with
//! `experiments`' `replay_cells!`) says what a cell names; this says which of those the table holds, by
//! the same settings the table reads (its grids, its clearances, its E. max), and reads those
//! settings for it.

use registry::{Context, RunError, fmt_number};
use study::cell::{Purpose, run_cells};
use study::grids::CellSettings;
use study::tolerance;

/// The cell settings of a replayable table under `ctx`: every replayable table counts its cells
/// with the per-cell `trials` parameter.
///
/// # Errors
/// A setting [`crate::read::cells`] refuses.
pub fn settings(ctx: &Context) -> Result<CellSettings, RunError> {
    crate::read::cells(ctx, &study::grids::TRIALS)
}

/// Refuses a cell of experiment `id` that its table does not hold under `ctx`'s settings (`s`
/// read from them); a cell the grammar refuses is refused with the grammar's words. Experiments
/// whose every cell the grammar checks (Table 3: a Case and a mesh at the table's G) pass.
///
/// # Errors
/// [`RunError::BadInput`] naming the cell, the part typed and the table's values.
pub fn check(ctx: &Context, s: &CellSettings, id: &str, cell: &str) -> Result<(), RunError> {
    let (spec, typed) = replay::unchecked_cell_spec(s, id, cell)?;
    let parts: Vec<&str> = cell.split('/').collect();
    let bad = |rule: String| RunError::bad("replay", format!("cell `{cell}` of {id}"), rule);
    let typed_value = |key: &str| {
        typed
            .iter()
            .find(|(k, _, _)| *k == key)
            .map(|&(_, name, text)| {
                (
                    name,
                    text.trim(),
                    text.trim().parse::<f64>().unwrap_or(f64::NAN),
                )
            })
    };
    match id {
        "tableI" => {
            let [_, g, _] = parts.as_slice() else {
                return Ok(());
            };
            let listed = crate::read::clearance_list(
                ctx,
                &study::gearing::TABLE_I_CLEARANCES,
                study::gearing::MAX_LISTED_CLEARANCE,
            )?;
            one_of(spec.clearance, &listed).map_err(|near| {
                bad(format!(
                    "G `{}`: {near}one of the table's clearances ({}; --set clearances=... runs others)",
                    g.trim(),
                    list(&listed)
                ))
            })
        }
        "table4" => {
            let Some((name, text, value)) = typed_value("random") else {
                return Ok(());
            };
            let grid = crate::read::random_grid(ctx)?;
            one_of(value, &grid).map_err(|near| {
                bad(format!(
                    "{name} `{text}`: {near}a row of the table ({}; --set random_from, random_to and random_step run others)",
                    list(&grid)
                ))
            })
        }
        "table5" => {
            if let Some((name, text, value)) = typed_value("systematic") {
                let rows = crate::read::systematic_grid(ctx)?;
                one_of(value, &rows).map_err(|near| {
                    bad(format!(
                        "{name} `{text}`: {near}a row of the table ({}; --set systematic_from, systematic_to and systematic_step run others)",
                        list(&rows)
                    ))
                })?;
            }
            let Some((name, text, value)) = typed_value("random") else {
                return Ok(());
            };
            let emax = mesh_emax(ctx, s, &spec.mesh)?;
            match emax {
                None => Err(bad(format!(
                    "mesh {}: has no E. max (every random error of Table 4's grid jams it beyond the rule), so the table runs none of its cells",
                    spec.mesh
                ))),
                Some((e, how)) => one_of(value, &[e]).map_err(|near| {
                    bad(format!(
                        "{name} `{text}`: {near}the random error the table runs mesh {} at, its E. max {} ({how})",
                        spec.mesh,
                        fmt_number(e)
                    ))
                }),
            }
        }
        _ => Ok(()),
    }
}

/// `Ok` when `value` is bit for bit one of `values` (a cell's random stream follows its values'
/// bits); otherwise the start of the refusal: "is not " or, for a `-0` where the table has 0,
/// "is written 0 in the table: -0 is not ".
fn one_of(value: f64, values: &[f64]) -> Result<(), &'static str> {
    if values.iter().any(|v| v.to_bits() == value.to_bits()) {
        return Ok(());
    }
    if value == 0.0 && values.contains(&0.0) {
        return Err("is written 0 in the table, and -0 is not ");
    }
    Err("is not ")
}

/// Values in words: `0.035, 0.04, 0.045`.
fn list(values: &[f64]) -> String {
    values
        .iter()
        .map(|v| fmt_number(*v))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The random error Table 5 runs `mesh` at, and how it was found: the paper's (`--set
/// emax=paper`) or the largest of Table 4's grid within the rule, from the mesh's column of
/// Table 4 run here (`None`: no value of the grid is within the rule).
fn mesh_emax(
    ctx: &Context,
    s: &CellSettings,
    mesh: &str,
) -> Result<Option<(f64, String)>, RunError> {
    let from = crate::emax::random_from(ctx.text(&crate::emax::EMAX)?);
    let meshes = s.meshes();
    if let Some(row) = crate::emax::given_row(from, &meshes)? {
        let at = meshes.iter().position(|m| m == mesh);
        return Ok(at
            .and_then(|i| row.get(i).copied().flatten())
            .map(|e| (e, "the paper's, emax=paper".to_owned())));
    }
    let rule = ctx.get(&tolerance::RULE)?;
    let grid = crate::read::random_grid(ctx)?;
    let clearance = s.clearance()?;
    let mut cells = Vec::with_capacity(grid.len());
    for &e in &grid {
        let params = s.errors.params(&[("random", e), ("systematic", 0.0)])?;
        cells.push(s.cell(mesh, params, clearance));
    }
    let counts = run_cells(ctx.engine(), s.gearing(), &cells, s.trials, Purpose::Input)?;
    let column: Vec<(f64, u64)> = grid
        .iter()
        .zip(&counts)
        .map(|(&e, c)| (e, c.jams))
        .collect();
    Ok(
        tolerance::largest_tolerable(&column, s.trials, rule).map(|e| {
            (
                e,
                format!(
                    "the largest of Table 4's grid with at most {} of {} trials jammed, rule {rule} %",
                    tolerance::allowed_jams(s.trials, rule),
                    s.trials
                ),
            )
        }),
    )
}
