//! Small helpers shared by experiments: units, radii, Theoretical-Difference statistics, plots.

use plotters::coord::ranged1d::AsRangedCoord;
use plotters::prelude::*;
use registry::{RunError, fmt_f64};

/// Radians to degrees.
pub fn deg(x: f64) -> f64 {
    x.to_degrees()
}

/// A value with the paper's beside it (or "-" when the paper gives none).
pub fn paper_cell(id: &str, quantity: &str, decimals: usize) -> String {
    crate::paper::get(id, quantity).map_or_else(|| "-".to_string(), |r| fmt_f64(r.value, decimals))
}

/// One line of a plot.
pub struct Series<'a> {
    /// Legend text.
    pub label: &'a str,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
}

/// A line plot as SVG text: title naming the paper item, labelled axes with units, a legend.
pub fn line_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    plot(title, x_label, y_label, series, false, &[])
}

/// A vertical mark on a plot: an event at `x`, labelled (e.g. its kind and size).
pub struct Mark {
    /// Where (x axis units).
    pub x: f64,
    /// Text written beside the mark.
    pub label: String,
    /// Colour group (marks of one kind share a colour).
    pub group: usize,
}

/// [`line_plot`] with vertical marks (events), each labelled.
pub fn marked_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    marks: &[Mark],
) -> Result<String, RunError> {
    plot(title, x_label, y_label, series, false, marks)
}

/// A semi-logarithmic line plot: `series` hold positive values, drawn on a log10 y axis whose
/// ticks are labelled with the values themselves.
pub fn semilog_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    let logged: Vec<Series<'_>> = series
        .iter()
        .map(|s| Series {
            label: s.label,
            points: s
                .points
                .iter()
                .filter(|p| p.1 > 0.0)
                .map(|&(x, y)| (x, y.log10()))
                .collect(),
        })
        .collect();
    plot(title, x_label, y_label, &logged, true, &[])
}

pub use registry::MAX_DATA_ROWS;

/// The most points of one series a figure draws: 50 000 (the default runs draw at most 36 001).
/// A longer series is thinned to the first, smallest, largest and last point of each of 12 500
/// runs of consecutive points, so the drawn envelope is the data's and the SVG stays a few MB.
pub const MAX_PLOT_POINTS: usize = 50_000;

/// `points` thinned as [`MAX_PLOT_POINTS`] says; unchanged when there are not more.
fn thinned(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    if points.len() <= MAX_PLOT_POINTS {
        return points.to_vec();
    }
    let run = points.len().div_ceil(MAX_PLOT_POINTS / 4);
    let mut out = Vec::with_capacity(MAX_PLOT_POINTS);
    for chunk in points.chunks(run) {
        let (mut lo, mut hi) = (0, 0);
        for (i, p) in chunk.iter().enumerate() {
            if p.1 < chunk[lo].1 {
                lo = i;
            }
            if p.1 > chunk[hi].1 {
                hi = i;
            }
        }
        let mut keep = [0, lo.min(hi), lo.max(hi), chunk.len() - 1];
        keep.sort_unstable();
        let mut last = None;
        for k in keep {
            if last != Some(k) {
                out.push(chunk[k]);
                last = Some(k);
            }
        }
    }
    out
}

/// An axis range the chart can label: `(lo, hi)` itself when both are finite and `hi` exceeds
/// `lo` by more than 10^-12 of their magnitude (some 4500 steps of f64 rounding), else a range
/// of width 1 (or 10^-3 of the magnitude, if more) about the middle of what is finite (0 if
/// nothing is). The tick search of `plotters` never ends on an empty, infinite or zero-width
/// range: a figure with no finite point, or with values too large for their spread, would
/// hang its run.
pub fn drawable(lo: f64, hi: f64) -> (f64, f64) {
    let magnitude = lo.abs().max(hi.abs());
    if lo.is_finite() && hi.is_finite() && hi - lo > magnitude * 1e-12 {
        return (lo, hi);
    }
    let mid = match (lo.is_finite(), hi.is_finite()) {
        (true, true) => 0.5 * lo + 0.5 * hi,
        (true, false) => lo,
        (false, true) => hi,
        (false, false) => 0.0,
    };
    let half = (mid.abs() * 5e-4).max(0.5);
    (mid - half, mid + half)
}

/// The points of `points` with no infinite coordinate: those are left off the axes
/// ([`drawable`]), and placing one would overflow the pixel arithmetic.
fn placeable(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    points
        .iter()
        .copied()
        .filter(|p| !p.0.is_infinite() && !p.1.is_infinite())
        .collect()
}

/// How plotting errors are reported: naming the figure.
type PlotErr<'a> = &'a dyn Fn(&dyn std::fmt::Display) -> RunError;

/// The chart every figure is drawn on, in one place: a white `width` x 480 SVG canvas, the
/// title as caption, the same margins and label areas, axes `x` by `y`; `draw` adds the mesh,
/// the series and marks, then the legend is drawn (where `legend` is set, at that position).
pub fn chart_svg<X, Y>(
    title: &str,
    width: u32,
    (x, y): (X, Y),
    legend: Option<SeriesLabelPosition>,
    draw: impl for<'a> FnOnce(
        &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X::CoordDescType, Y::CoordDescType>>,
        PlotErr<'_>,
    ) -> Result<(), RunError>,
) -> Result<String, RunError>
where
    X: AsRangedCoord,
    Y: AsRangedCoord,
{
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, 480)).into_drawing_area();
        let plot_err = |e: &dyn std::fmt::Display| RunError::Internal(format!("plot {title}: {e}"));
        root.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x, y)
            .map_err(|e| plot_err(&e))?;
        draw(&mut chart, &plot_err)?;
        let mut labels = chart.configure_series_labels();
        if let Some(at) = legend {
            labels.position(at);
        }
        labels
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(|e| plot_err(&e))?;
        root.present().map_err(|e| plot_err(&e))?;
    }
    Ok(svg)
}

fn plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    log_y: bool,
    marks: &[Mark],
) -> Result<String, RunError> {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    // The axes span what can be placed on them: an infinite coordinate cannot (a NaN is
    // passed over by `min` and `max`).
    for p in series.iter().flat_map(|s| &s.points) {
        if !p.0.is_infinite() {
            x0 = x0.min(p.0);
            x1 = x1.max(p.0);
        }
        if !p.1.is_infinite() {
            y0 = y0.min(p.1);
            y1 = y1.max(p.1);
        }
    }
    if x0.partial_cmp(&x1) != Some(std::cmp::Ordering::Less) {
        x1 = x0 + 1.0;
    }
    let (x0, x1) = drawable(x0, x1);
    let pad = ((y1 - y0) * 0.05).max(1e-9);
    let (y0, y1) = drawable(y0 - pad, y1 + pad);
    let colours = [BLUE, RED, BLACK, GREEN, MAGENTA];
    chart_svg(title, 800, (x0..x1, y0..y1), None, |chart, plot_err| {
        let decade = |v: &f64| format!("{:.1e}", 10f64.powf(*v));
        let plain = |v: &f64| {
            // Six decimals at most, without trailing zeros: 0.1 + 0.2 prints as 0.3.
            let t = format!("{v:.6}");
            let t = t.trim_end_matches('0').trim_end_matches('.');
            if t == "-0" {
                "0".to_string()
            } else {
                t.to_string()
            }
        };
        let y_fmt: &dyn Fn(&f64) -> String = if log_y { &decade } else { &plain };
        chart
            .configure_mesh()
            .x_desc(x_label)
            .y_desc(y_label)
            .y_label_formatter(y_fmt)
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (i, s) in series.iter().enumerate() {
            let colour = colours[i % colours.len()];
            chart
                .draw_series(LineSeries::new(
                    thinned(&placeable(&s.points)),
                    colour.stroke_width(1),
                ))
                .map_err(|e| plot_err(&e))?
                .label(s.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], colour));
        }
        let mark_colours = [RED, MAGENTA, CYAN, GREEN, BLACK];
        for (i, m) in marks.iter().enumerate() {
            let colour = mark_colours[m.group % mark_colours.len()];
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(m.x, y0), (m.x, y1)],
                    colour.mix(0.6).stroke_width(1),
                )))
                .map_err(|e| plot_err(&e))?;
            // Labels step down the plot so that neighbouring events stay legible.
            let y = y1 - (y1 - y0) * (0.04 + 0.06 * (i % 8) as f64);
            chart
                .draw_series(std::iter::once(Text::new(
                    m.label.clone(),
                    (m.x, y),
                    ("sans-serif", 11).into_font().color(&colour),
                )))
                .map_err(|e| plot_err(&e))?;
        }
        Ok(())
    })
}

/// CSV text from a header and rows of numbers printed with `decimals` decimals.
pub fn csv(header: &[&str], rows: impl Iterator<Item = Vec<f64>>, decimals: usize) -> String {
    let mut out = header.join(",");
    out.push('\n');
    for r in rows {
        let cells: Vec<String> = r.iter().map(|x| format!("{x:.decimals$}")).collect();
        out.push_str(&cells.join(","));
        out.push('\n');
    }
    out
}

/// A chart of values by category (e.g. one per gear) as SVG text: the categories along the x
/// axis, one marker per value, a marker shape and colour per series (circle, triangle, cross...),
/// and a legend. `series` points are (category index, value); a category with no value in a
/// series simply has no marker.
pub fn category_plot(
    title: &str,
    categories: &[String],
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    let values = series.iter().flat_map(|s| s.points.iter().map(|p| p.1));
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for y in values.filter(|y| !y.is_infinite()) {
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if y0 > y1 {
        (y0, y1) = (0.0, 1.0);
    }
    let pad = ((y1 - y0) * 0.1).max(1e-3);
    let (y0, y1) = drawable((y0 - pad).max(0.0), y1 + pad);
    let n = categories.len().max(1) as i32;
    let colours = [BLUE, RED, BLACK, GREEN, MAGENTA];
    chart_svg(
        title,
        1000,
        ((0..n).into_segmented(), y0..y1),
        None,
        |chart, plot_err| {
            let name = |v: &SegmentValue<i32>| match v {
                SegmentValue::CenterOf(i) | SegmentValue::Exact(i) => usize::try_from(*i)
                    .ok()
                    .and_then(|i| categories.get(i))
                    .cloned()
                    .unwrap_or_default(),
                SegmentValue::Last => String::new(),
            };
            chart
                .configure_mesh()
                .x_desc(x_label)
                .y_desc(y_label)
                .x_labels(categories.len() + 1)
                .x_label_formatter(&name)
                .disable_x_mesh()
                .draw()
                .map_err(|e| plot_err(&e))?;
            for (k, s) in series.iter().enumerate() {
                let colour = colours[k % colours.len()];
                let at = |x: f64, y: f64| (SegmentValue::CenterOf(x.round() as i32), y);
                let style = colour.stroke_width(2);
                let drawn = match k % 3 {
                    0 => chart.draw_series(
                        placeable(&s.points)
                            .into_iter()
                            .map(|(x, y)| Circle::new(at(x, y), 5, colour.filled())),
                    ),
                    1 => chart.draw_series(
                        placeable(&s.points)
                            .into_iter()
                            .map(|(x, y)| TriangleMarker::new(at(x, y), 7, style)),
                    ),
                    _ => chart.draw_series(
                        placeable(&s.points)
                            .into_iter()
                            .map(|(x, y)| Cross::new(at(x, y), 6, style)),
                    ),
                };
                let shape = k % 3;
                drawn.map_err(|e| plot_err(&e))?.label(s.label).legend(
                    move |(x, y)| -> DynElement<'static, SVGBackend<'_>, (i32, i32)> {
                        match shape {
                            0 => Circle::new((x + 10, y), 5, colour.filled()).into_dyn(),
                            1 => TriangleMarker::new((x + 10, y), 7, colour.stroke_width(2))
                                .into_dyn(),
                            _ => Cross::new((x + 10, y), 6, colour.stroke_width(2)).into_dyn(),
                        }
                    },
                );
            }
            Ok(())
        },
    )
}
/// "mean [lo .. hi]" of days (no interval for one value, "-" for none).
pub fn mean_cell(days: &[f64], horizon: f64) -> String {
    let e = study::whole_mechanism::mean_days(days, horizon);
    match days.len() {
        0 => "-".into(),
        1 => format!("{} (n = 1)", fmt_f64(e.mean, 0)),
        _ => format!(
            "{} [{} .. {}]",
            fmt_f64(e.mean, 0),
            fmt_f64(e.lo, 0),
            fmt_f64(e.hi, 0)
        ),
    }
}

/// "rate [lo .. hi]" of a proportion, in whole percent.
pub fn percent_cell(p: &stats::Proportion) -> String {
    format!(
        "{} [{} .. {}]",
        fmt_f64(100.0 * p.rate(), 0),
        fmt_f64(100.0 * p.lo, 0),
        fmt_f64(100.0 * p.hi, 0)
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod plot_tests {
    use super::*;

    /// Runs `f` on its own thread and fails if it has not returned within a minute (a figure
    /// whose axis range `plotters` cannot label never returns).
    fn within_a_minute(f: impl FnOnce() + Send + 'static) {
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::spawn(move || {
            f();
            let _ = tx.send(());
        });
        match rx.recv_timeout(std::time::Duration::from_secs(60)) {
            Ok(()) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                panic!("still drawing after a minute")
            }
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => panic!("drawing panicked"),
        }
    }

    #[test]
    fn figures_without_a_drawable_range_still_finish() {
        within_a_minute(figures_without_a_drawable_range);
    }

    fn figures_without_a_drawable_range() {
        let empty = Series {
            label: "none",
            points: Vec::new(),
        };
        let infinite = Series {
            label: "infinite",
            points: vec![(1.0, f64::INFINITY), (f64::NEG_INFINITY, 2.0)],
        };
        let flat_and_large = Series {
            label: "flat",
            points: vec![(1e20, 3e15), (1e20, 3e15)],
        };
        for s in [empty, infinite, flat_and_large] {
            let svg = line_plot("t", "x", "y", std::slice::from_ref(&s)).unwrap();
            assert!(svg.contains("<svg"), "{}", s.label);
            let svg = semilog_plot("t", "x", "y", std::slice::from_ref(&s)).unwrap();
            assert!(svg.contains("<svg"), "{}", s.label);
            // A category chart's x is the category's index.
            let by_category = Series {
                label: s.label,
                points: s.points.iter().map(|p| (0.0, p.1)).collect(),
            };
            let svg = category_plot("t", &["a".into()], "x", "y", &[by_category]).unwrap();
            assert!(svg.contains("<svg"), "{}", s.label);
        }
    }

    #[test]
    fn drawable_ranges_are_kept() {
        assert_eq!(drawable(-1e-9, 1e-9), (-1e-9, 1e-9));
        assert_eq!(drawable(0.0, 102.0), (0.0, 102.0));
        assert_eq!(drawable(f64::INFINITY, f64::NEG_INFINITY), (-0.5, 0.5));
        let (lo, hi) = drawable(1e20, 1e20);
        assert!(lo < 1e20 && hi > 1e20 && hi - lo > 1e16);
    }

    #[test]
    fn long_series_are_thinned_to_their_envelope() {
        let short: Vec<(f64, f64)> = (0..36_001).map(|i| (i as f64, (i % 7) as f64)).collect();
        assert_eq!(
            thinned(&short),
            short,
            "the default runs' curves are drawn whole"
        );
        // 3.6 million points (pair at sample_deg 1e-4 drew them all: a 27 MB SVG).
        let long: Vec<(f64, f64)> = (0..3_600_000)
            .map(|i| {
                (
                    i as f64,
                    ((i as f64) * 0.001).sin() + if i == 1_234_567 { 5.0 } else { 0.0 },
                )
            })
            .collect();
        let t = thinned(&long);
        assert!(t.len() <= MAX_PLOT_POINTS, "{}", t.len());
        assert_eq!(t.first(), long.first());
        assert_eq!(t.last(), long.last());
        assert!(t.windows(2).all(|w| w[0].0 < w[1].0), "in order");
        let peak = t.iter().map(|p| p.1).fold(f64::MIN, f64::max);
        assert!(peak > 5.0, "a one-point spike survives: {peak}");
    }
}
