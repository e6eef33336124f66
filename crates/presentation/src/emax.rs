//! The paper's largest tolerable errors (Table 5's E. max row and the systematic tolerances its
//! counts give), to print beside ours, and a tolerance as the tables print it.

use study::cell::{PAPER_TRIALS, label};
use study::tolerance;

use crate::cells::paper_counts;

/// The paper's largest tolerable random error of `mesh` (Table 5, row E. max).
pub fn paper_random(mesh: &str) -> Option<f64> {
    crate::paper::get("table5", &format!("emax.{mesh}")).map(|r| r.value)
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
