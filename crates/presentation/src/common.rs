//! Small helpers shared by experiments: units, radii, Theoretical-Difference statistics; the
//! plots are [`crate::chart`]'s, re-exported here.

use registry::fmt_f64;

/// Radians to degrees.
pub fn deg(x: f64) -> f64 {
    x.to_degrees()
}

/// A value with the paper's beside it (or "-" when the paper gives none).
pub fn paper_cell(id: &str, quantity: &str, decimals: usize) -> String {
    crate::paper::get(id, quantity).map_or_else(|| "-".to_string(), |r| fmt_f64(r.value, decimals))
}

pub use crate::chart::{
    Band, Limit, LimitKind, Mark, Plot, Series, category_plot, category_plot_band, drawable,
    line_plot, marked_plot, semilog_plot,
};
pub use registry::MAX_DATA_ROWS;

/// CSV text ([`registry::Csv`]) from a header and rows of numbers printed with `decimals`
/// decimals.
pub fn csv(header: &[&str], rows: impl Iterator<Item = Vec<f64>>, decimals: usize) -> String {
    let mut out = registry::Csv::new(header);
    for r in rows {
        out.row(r.iter().map(|x| format!("{x:.decimals$}")));
    }
    out.text()
}

/// "value [lo .. hi]", each with `decimals` decimals: how an estimate and its interval print.
pub fn interval(value: f64, lo: f64, hi: f64, decimals: usize) -> String {
    format!(
        "{} [{} .. {}]",
        fmt_f64(value, decimals),
        fmt_f64(lo, decimals),
        fmt_f64(hi, decimals)
    )
}

/// "mean [lo .. hi]" of an estimate, with `decimals` decimals.
pub fn estimate(e: &stats::Estimate, decimals: usize) -> String {
    interval(e.mean, e.lo, e.hi, decimals)
}

/// "mean [lo .. hi]" of days (no interval for one value, "-" for none).
pub fn mean_cell(days: &[f64], horizon: f64) -> String {
    let e = study::whole_mechanism::mean_days(days, horizon);
    match days.len() {
        0 => "-".into(),
        1 => format!("{} (n = 1)", fmt_f64(e.mean, 0)),
        _ => estimate(&e, 0),
    }
}

/// "rate [lo .. hi]" of a proportion, in whole percent.
pub fn percent_cell(p: &stats::Proportion) -> String {
    interval(100.0 * p.rate(), 100.0 * p.lo, 100.0 * p.hi, 0)
}

/// The meshes that jammed first most often (the first four of `meshes`, most frequent first),
/// each with its runs, e.g. `e3-f1 (12), b2-c1 (3)`; `-` where none did.
pub fn jammed_first(meshes: &[(String, usize)]) -> String {
    if meshes.is_empty() {
        return "-".into();
    }
    let first: Vec<String> = meshes
        .iter()
        .take(4)
        .map(|(m, c)| format!("{m} ({c})"))
        .collect();
    first.join(", ")
}

/// The first cells of a pointer's row in a table of estimates: the pointer `name` with its
/// `turns`, the `reading` (how the value was measured), the mean and its 95 % interval.
pub fn estimate_cells(name: &str, turns: f64, reading: &str, e: &stats::Estimate) -> Vec<String> {
    vec![
        format!("{name} ({turns} turns)"),
        reading.into(),
        fmt_f64(e.mean, 4),
        format!("{} .. {}", fmt_f64(e.lo, 4), fmt_f64(e.hi, 4)),
    ]
}

/// The CSV fields of the same: `name,reading,mean,lo,hi`, the values in full.
pub fn estimate_csv(name: &str, reading: &str, e: &stats::Estimate) -> Vec<String> {
    vec![
        name.to_owned(),
        reading.to_owned(),
        e.mean.to_string(),
        e.lo.to_string(),
        e.hi.to_string(),
    ]
}

/// `text` broken at spaces into lines of at most `width` characters; a word longer than `width`
/// stays whole on a line of its own. For captions and notes drawn or printed in lines.
pub fn wrap_at_spaces(text: &str, width: usize) -> Vec<String> {
    let mut lines = vec![String::new()];
    for word in text.split_whitespace() {
        let fits = lines
            .last()
            .is_some_and(|l| l.is_empty() || l.chars().count() + 1 + word.chars().count() <= width);
        if !fits {
            lines.push(String::new());
        }
        if let Some(l) = lines.last_mut() {
            if !l.is_empty() {
                l.push(' ');
            }
            l.push_str(word);
        }
    }
    lines
}

/// "mean [lo .. hi]" of a stored mean day (no interval for one day, "-" for none): what
/// [`mean_cell`] prints, read from the stored estimate.
pub fn mean_day_cell(m: Option<&study::results::MeanDay>) -> String {
    match m {
        None => "-".into(),
        Some(e) if e.n == 1 => format!("{} (n = 1)", fmt_f64(e.mean, 0)),
        Some(e) => interval(e.mean, e.lo, e.hi, 0),
    }
}
