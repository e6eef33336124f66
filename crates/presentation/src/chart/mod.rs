//! The chart builder every figure of the experiments is drawn with.
//!
//! Two properties hold for every chart, whatever the figure:
//!
//! - **Every series has a style of its own**: series `k` of a chart is drawn in [`style`]`(k)`,
//!   a colour, a dash pattern and a marker, and no two series of one chart share all three
//!   (nor, up to 28 series, both the dash and the marker, so a chart stays readable in grey).
//! - **The legend is outside the plotted data**: it is drawn below the axes, in a box of its own
//!   that never intersects the plot area, however many series there are.
//!
//! Axes, ticks, grid and caption are drawn by `plotters`; the series, their markers and the
//! legend are written as SVG elements that carry what a check needs to see these properties:
//! `<rect class="plot-area">`, `<g class="series" data-series="k" data-style="...">` and
//! `<g class="legend">` with its `<rect class="legend-box">` (`xtask/tests/figures.rs` checks
//! them in headless Chromium on every figure).

use std::fmt::Write as _;

use plotters::coord::Shift;
use plotters::coord::ranged1d::AsRangedCoord;
use plotters::prelude::*;
use registry::RunError;

mod legend;
mod marks;
mod style;
mod svg;

use legend::{Entry, LegendLayout, Sample, legend_svg};
pub use marks::every_mark_numbered;
use marks::{MARK_ROOM, mark_band, marks_svg};
pub use style::{DISTINCT_STYLES, Marker, Style, style};
use svg::{bracket_svg, marker_svg, polyline_svg, px};

use crate::escape_xml as esc;

/// One series of a chart.
pub struct Series<'a> {
    /// Legend text.
    pub label: &'a str,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
}

impl<'a> Series<'a> {
    /// The series of `values` against `angles` (radians, as the simulations give them), drawn
    /// in degrees.
    pub fn in_degrees(label: &'a str, angles: &[f64], values: &[f64]) -> Series<'a> {
        Series {
            label,
            points: angles
                .iter()
                .map(|a| a.to_degrees())
                .zip(values.iter().copied())
                .collect(),
        }
    }
}

/// A mark on a plot: an event at `x`, drawn as a marker on the curve at `y` (its value there)
/// and as a tick in a band above the data, numbered there where the numbers do not crowd.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mark {
    /// Where (x axis units).
    pub x: f64,
    /// The series' value at `x`, where the marker sits; `None`: only the tick above the data.
    pub y: Option<f64>,
    /// Its number (the event's, as the event table numbers it).
    pub number: usize,
    /// Its kind: an index into the kinds given with the marks ([`Plot::marks`]); marks of one
    /// kind share a colour, a marker and a legend entry.
    pub group: usize,
}

/// How the marks of kind `g` are drawn: dark colours that read on white and stay apart from
/// the series' first colours, each with a marker of its own.
pub fn mark_style(g: usize) -> (&'static str, Marker) {
    const STYLES: [(&str, Marker); 6] = [
        ("#b2182b", Marker::TriangleDown),
        ("#5e3c99", Marker::Diamond),
        ("#b35806", Marker::Square),
        ("#1b7837", Marker::TriangleUp),
        ("#222222", Marker::Cross),
        ("#8c510a", Marker::Plus),
    ];
    STYLES[g % STYLES.len()]
}

/// Which end of a series' running range a [`Limit`] marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LimitKind {
    /// The series starts here (drawn `[`): below it, e.g., the gears jam.
    Lower,
    /// The series ends here (drawn `]`): above it, e.g., the gears disengage.
    Upper,
}

/// A limit of one series on the x axis (a mesh's jam or disengagement limit), drawn as a
/// bracket in the series' colour at the series' value nearest to it, joined to the series by a
/// dotted line.
pub struct Limit {
    /// Index of the series in the chart.
    pub series: usize,
    /// Where (x axis units).
    pub x: f64,
    /// Lower (`[`) or upper (`]`) end.
    pub kind: LimitKind,
}

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

/// Round ticks for an axis from `lo` to `hi`: every multiple of a step of 1, 2 or 5 times a
/// power of ten within the range, the step chosen to give about `target` of them (at least
/// two where the range allows), and the decimals that step needs to print each exactly.
pub fn nice_ticks(lo: f64, hi: f64, target: usize) -> (Vec<f64>, usize) {
    let (lo, hi) = drawable(lo.min(hi), lo.max(hi));
    let raw = (hi - lo) / target.max(1) as f64;
    let decade = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * decade)
        .find(|s| *s >= raw)
        .unwrap_or(10.0 * decade);
    let first = (lo / step).ceil();
    let last = (hi / step).floor();
    let ticks: Vec<f64> = (0..=((last - first).max(0.0) as usize).min(1000))
        .map(|i| {
            let v = (first + i as f64) * step;
            if v.abs() < step * 1e-9 { 0.0 } else { v }
        })
        .collect();
    let decimals = (-(step.log10().floor())).max(0.0) as usize;
    (ticks, decimals)
}

/// A tick value printed with `decimals` decimals, a negative zero without its sign.
pub fn tick_label(v: f64, decimals: usize) -> String {
    let t = format!("{v:.decimals$}");
    match t.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_owned(),
        _ => t,
    }
}

/// Width and height of the area `plotters` draws the axes in; the legend goes below it.
const AXES_HEIGHT: u32 = 480;

/// A pixel rectangle (x, y, width, height).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// Left.
    pub x: f64,
    /// Top.
    pub y: f64,
    /// Width.
    pub w: f64,
    /// Height.
    pub h: f64,
}

impl Rect {
    /// Do the two rectangles share any point (touching edges included)?
    pub fn intersects(&self, o: &Rect) -> bool {
        self.x <= o.x + o.w
            && o.x <= self.x + self.w
            && self.y <= o.y + o.h
            && o.y <= self.y + self.h
    }
}

/// The legend's entry of each series, in order, each in its own style; `line`: drawn with its
/// line (a line plot) or as markers only (a category plot).
fn series_entries(series: &[Series<'_>], line: bool) -> Vec<Entry> {
    series
        .iter()
        .enumerate()
        .map(|(k, s)| Entry {
            label: s.label.to_owned(),
            sample: Sample::Series {
                style: style(k),
                line,
            },
            series: Some(k),
        })
        .collect()
}

/// How plotting errors are reported: naming the figure.
type PlotErr<'a> = &'a dyn Fn(&dyn std::fmt::Display) -> RunError;

/// Font size of a chart's title, px.
const TITLE_FONT: f64 = 15.0;
/// Distance between the lines of a title, px.
const TITLE_LINE: f64 = 19.0;
/// The width of a title's character, about, px.
const TITLE_CHAR: f64 = 8.4;

/// The space above the axes for a title of `lines` lines, px.
fn title_height(lines: usize) -> u32 {
    (TITLE_LINE * lines as f64 + 10.0).ceil() as u32
}

/// `s` broken at spaces into lines of at most `width` characters; a word longer than a line is
/// cut into lines of its own.
fn wrap_words(s: &str, width: usize) -> Vec<String> {
    let width = width.max(1);
    let mut lines: Vec<String> = vec![String::new()];
    for word in s.split(' ') {
        let chars: Vec<char> = word.chars().collect();
        for piece in chars.chunks(width) {
            let piece: String = piece.iter().collect();
            let fits = lines.last().is_some_and(|l| {
                l.is_empty() || l.chars().count() + 1 + piece.chars().count() <= width
            });
            if !fits {
                lines.push(String::new());
            }
            if let Some(last) = lines.last_mut() {
                if !last.is_empty() {
                    last.push(' ');
                }
                last.push_str(&piece);
            }
        }
    }
    lines
}

/// The chart every figure is drawn on, in one place: a white `width`-wide SVG canvas, the title
/// above the axes in as many lines as it needs, the same margins and label areas, axes `x` by `y` 480 px high and the legend of
/// `entries` below them. `draw` adds the mesh and anything `plotters` draws (marks), and returns
/// the SVG of the series, in pixels of the canvas, given the plot area.
fn chart_svg<X, Y>(
    title: &str,
    width: u32,
    (x, y): (X, Y),
    entries: &[Entry],
    draw: impl for<'a> FnOnce(
        &mut ChartContext<'a, SVGBackend<'a>, Cartesian2d<X::CoordDescType, Y::CoordDescType>>,
        PlotErr<'_>,
    ) -> Result<String, RunError>,
) -> Result<String, RunError>
where
    X: AsRangedCoord,
    Y: AsRangedCoord,
{
    let layout = LegendLayout::new(entries, width);
    // The title in as many centred lines as the canvas' width needs.
    let title_lines = wrap_words(title, ((f64::from(width) - 24.0) / TITLE_CHAR) as usize);
    let height = AXES_HEIGHT + layout.height();
    let mut svg = String::new();
    let (plot_area, series) = {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        let plot_err = |e: &dyn std::fmt::Display| RunError::Internal(format!("plot {title}: {e}"));
        root.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let (axes, _legend): (DrawingArea<_, Shift>, _) = root.split_vertically(AXES_HEIGHT);
        let mut chart = ChartBuilder::on(&axes)
            .margin(12)
            .margin_top(title_height(title_lines.len()))
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x, y)
            .map_err(|e| plot_err(&e))?;
        let (xr, yr) = chart.plotting_area().get_pixel_range();
        let plot_area = Rect {
            x: f64::from(xr.start),
            y: f64::from(yr.start),
            w: f64::from(xr.end - xr.start),
            h: f64::from(yr.end - yr.start),
        };
        let series = draw(&mut chart, &plot_err)?;
        root.present().map_err(|e| plot_err(&e))?;
        (plot_area, series)
    };
    let mut extra = format!(
        "<rect class=\"plot-area\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"none\"/>\n",
        px(plot_area.x),
        px(plot_area.y),
        px(plot_area.w),
        px(plot_area.h)
    );
    for (i, line) in title_lines.iter().enumerate() {
        let _ = writeln!(
            extra,
            "<text class=\"title\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" font-family=\"sans-serif\" font-size=\"{TITLE_FONT}\">{}</text>",
            px(f64::from(width) / 2.0),
            px(12.0 + TITLE_FONT + TITLE_LINE * i as f64),
            esc(line)
        );
    }
    extra.push_str(&series);
    extra.push_str(&legend_svg(entries, &layout, f64::from(AXES_HEIGHT)));
    match svg.rfind("</svg>") {
        Some(end) => svg.insert_str(end, &extra),
        None => return Err(RunError::Internal(format!("plot {title}: no </svg>"))),
    }
    Ok(svg)
}

/// The runs of finite points of `points`: a line is broken where a coordinate is not finite
/// (those points cannot be placed on the axes, see [`drawable`]).
fn finite_runs(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs = vec![Vec::new()];
    for &p in points {
        if p.0.is_finite() && p.1.is_finite() {
            if let Some(last) = runs.last_mut() {
                last.push(p);
            }
        } else if runs.last().is_some_and(|r| !r.is_empty()) {
            runs.push(Vec::new());
        }
    }
    runs.retain(|r| !r.is_empty());
    runs
}

/// Indices of the points of a line of `n` points that carry its markers: every point of a
/// short line, about ten along a long one (shifted by the series' index, so that lines lying
/// on each other show each its own markers).
fn marked_points(n: usize, k: usize) -> Vec<usize> {
    if n <= 60 {
        return (0..n).collect();
    }
    let step = n as f64 / 10.0;
    let phase = (k % 7) as f64 / 7.0;
    (0..10)
        .map(|m| (((m as f64 + phase) * step) as usize).min(n - 1))
        .collect()
}

/// A tick label of a logarithmic axis: the value to at least two significant digits, written plainly
/// from 0.001 to 99 999 (0.032, 0.1, 3.2, 316), in exponent form beyond.
fn log_tick(v: f64) -> String {
    if !(1e-3..1e5).contains(&v) {
        return format!("{v:.1e}");
    }
    let decimals = (1.0 - v.log10().floor()).max(0.0) as usize;
    let t = format!("{v:.decimals$}");
    if t.contains('.') {
        t.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        t
    }
}

/// A chart of lines against a numeric x axis: title naming the paper item, labelled axes with
/// units, every series in a style of its own ([`style`]), the legend below the axes. Build it
/// with [`Plot::new`], add what the figure needs, and draw it with [`Plot::svg`].
pub struct Plot<'a> {
    title: &'a str,
    x_label: &'a str,
    y_label: &'a str,
    series: &'a [Series<'a>],
    log_y: bool,
    marks: &'a [Mark],
    mark_kinds: &'a [String],
    plain: bool,
    limits: &'a [Limit],
    limit_labels: (&'a str, &'a str),
    x_range: Option<(f64, f64)>,
    y_range: Option<(f64, f64)>,
    whole_ticks: bool,
    shade: Option<(f64, &'a str)>,
}

impl<'a> Plot<'a> {
    /// A line chart of `series`.
    pub fn new(
        title: &'a str,
        x_label: &'a str,
        y_label: &'a str,
        series: &'a [Series<'a>],
    ) -> Self {
        Plot {
            title,
            x_label,
            y_label,
            series,
            log_y: false,
            marks: &[],
            mark_kinds: &[],
            plain: false,
            limits: &[],
            limit_labels: ("lower limit", "upper limit"),
            x_range: None,
            y_range: None,
            whole_ticks: false,
            shade: None,
        }
    }

    /// The plot greyed from `x` on to its right end, named in the legend by `label`: a stretch
    /// of the series read differently (a run's motion after its first lock, the paper's
    /// protocol rather than a physical motion).
    pub fn shaded_from(mut self, x: f64, label: &'a str) -> Self {
        self.shade = Some((x, label));
        self
    }

    /// A logarithmic y axis: the series hold positive values (others are left out), drawn on a
    /// log10 axis whose ticks are labelled with the values themselves.
    pub fn log_y(mut self) -> Self {
        self.log_y = true;
        self
    }

    /// Marks (events) on the series, of the kinds `kinds` (each a legend entry, e.g. `lock,
    /// counted as a jam: 25`): each a marker on the curve in its kind's style ([`mark_style`])
    /// and a tick in a band above the data, numbered there where numbers do not crowd.
    pub fn marks(mut self, marks: &'a [Mark], kinds: &'a [String]) -> Self {
        self.marks = marks;
        self.mark_kinds = kinds;
        self
    }

    /// Lines without markers: for a dense series whose markers would be taken for marks.
    pub fn plain_lines(mut self) -> Self {
        self.plain = true;
        self
    }

    /// Limits of the series on the x axis, with the legend's words for the lower and the upper
    /// kind.
    pub fn limits(mut self, limits: &'a [Limit], lower: &'a str, upper: &'a str) -> Self {
        self.limits = limits;
        self.limit_labels = (lower, upper);
        self
    }

    /// Fixed axis ranges instead of the data's.
    pub fn ranges(mut self, x: (f64, f64), y: (f64, f64)) -> Self {
        self.x_range = Some(x);
        self.y_range = Some(y);
        self
    }

    /// Tick labels without decimals.
    pub fn whole_ticks(mut self) -> Self {
        self.whole_ticks = true;
        self
    }

    /// The legend's entries: the series, then one per kind of limit drawn.
    fn entries(&self) -> Vec<Entry> {
        let mut entries = series_entries(self.series, true);
        if self.plain {
            for e in &mut entries {
                if let Sample::Series { style, .. } = e.sample {
                    e.sample = Sample::Line(style);
                }
            }
        }
        for (g, kind) in self.mark_kinds.iter().enumerate() {
            if self.marks.iter().any(|m| m.group == g) {
                let (colour, marker) = mark_style(g);
                entries.push(Entry {
                    label: kind.clone(),
                    sample: Sample::Mark { colour, marker },
                    series: None,
                });
            }
        }
        if let Some((_, label)) = self.shade {
            entries.push(Entry {
                label: label.to_owned(),
                sample: Sample::Shade,
                series: None,
            });
        }
        for (kind, label) in [
            (LimitKind::Lower, self.limit_labels.0),
            (LimitKind::Upper, self.limit_labels.1),
        ] {
            if self.limits.iter().any(|l| l.kind == kind) {
                entries.push(Entry {
                    label: label.to_owned(),
                    sample: Sample::Limit(kind),
                    series: None,
                });
            }
        }
        entries
    }

    /// The series as drawn: on a log axis, the log10 of the positive values only.
    fn drawn_series(&self) -> Vec<Vec<(f64, f64)>> {
        let y_of = |y: f64| {
            if self.log_y {
                if y > 0.0 { y.log10() } else { f64::NAN }
            } else {
                y
            }
        };
        self.series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .filter(|p| !self.log_y || p.1 > 0.0)
                    .map(|&(x, y)| (x, y_of(y)))
                    .collect()
            })
            .collect()
    }

    /// Each limit at the value of its series nearest to it (none: at the bottom): (series, x,
    /// that value, kind).
    fn placed_limits(&self, series: &[Vec<(f64, f64)>]) -> Vec<PlacedLimit> {
        self.limits
            .iter()
            .filter(|l| l.x.is_finite() && l.series < series.len())
            .map(|l| {
                let near = series[l.series]
                    .iter()
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .min_by(|a, b| (a.0 - l.x).abs().total_cmp(&(b.0 - l.x).abs()))
                    .map(|p| p.1);
                (l.series, l.x, near, l.kind)
            })
            .collect()
    }

    /// The axes' ranges: what can be placed on them (an infinite coordinate cannot; a NaN is
    /// passed over by `min` and `max`), or the fixed ranges. With marks, the x range leaves
    /// room for a marker at either end and the y range a band above the data for their ticks
    /// and numbers ([`mark_band`]), so that nothing of a mark leaves the frame or sits on the
    /// curve.
    fn axis_ranges(
        &self,
        series: &[Vec<(f64, f64)>],
        limits: &[PlacedLimit],
    ) -> ((f64, f64), (f64, f64)) {
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in series.iter().flatten() {
            if !p.0.is_infinite() {
                x0 = x0.min(p.0);
                x1 = x1.max(p.0);
            }
            if !p.1.is_infinite() {
                y0 = y0.min(p.1);
                y1 = y1.max(p.1);
            }
        }
        for l in limits {
            x0 = x0.min(l.1);
            x1 = x1.max(l.1);
        }
        if x0.partial_cmp(&x1) != Some(std::cmp::Ordering::Less) {
            x1 = x0 + 1.0;
        }
        let (x0, x1) = match self.x_range {
            Some(r) => drawable(r.0, r.1),
            None if !self.marks.is_empty() => {
                let room = (x1 - x0) * MARK_ROOM;
                drawable(x0 - room, x1 + room)
            }
            None => drawable(x0, x1),
        };
        let y = match self.y_range {
            Some(r) => drawable(r.0, r.1),
            None => {
                let pad = ((y1 - y0) * 0.05).max(1e-9);
                let band = mark_band(self.marks, (x0, x1), self.title) * (y1 - y0 + 2.0 * pad);
                drawable(y0 - pad, y1 + pad + band)
            }
        };
        ((x0, x1), y)
    }

    /// The chart as SVG text.
    pub fn svg(&self) -> Result<String, RunError> {
        let series = self.drawn_series();
        let limits = self.placed_limits(&series);
        let ((x0, x1), (y0, y1)) = self.axis_ranges(&series, &limits);
        // The top of the data, below the marks' band.
        let data_top = if self.y_range.is_none() && !self.marks.is_empty() {
            let band = mark_band(self.marks, (x0, x1), self.title);
            y1 - (y1 - y0) * band / (1.0 + band)
        } else {
            y1
        };
        let log_y = self.log_y;
        let whole = self.whole_ticks;
        let entries = self.entries();
        chart_svg(
            self.title,
            800,
            (x0..x1, y0..y1),
            &entries,
            |chart, plot_err| {
                let decade = |v: &f64| log_tick(10f64.powf(*v));
                let plain = |v: &f64| {
                    if whole {
                        return format!("{v:.0}");
                    }
                    // Six decimals at most, without trailing zeros: 0.1 + 0.2 prints as 0.3.
                    let t = format!("{v:.6}");
                    let t = t.trim_end_matches('0').trim_end_matches('.');
                    if t == "-0" {
                        "0".to_string()
                    } else {
                        t.to_string()
                    }
                };
                let whole_x = |v: &f64| format!("{v:.0}");
                let y_fmt: &dyn Fn(&f64) -> String = if log_y { &decade } else { &plain };
                let mut mesh = chart.configure_mesh();
                mesh.x_desc(self.x_label)
                    .y_desc(self.y_label)
                    .y_label_formatter(y_fmt);
                // x ticks as plainly as y's: 50, not 50.0.
                if whole {
                    mesh.x_label_formatter(&whole_x);
                } else {
                    mesh.x_label_formatter(&plain);
                }
                mesh.draw().map_err(|e| plot_err(&e))?;
                let (xr, yr) = chart.plotting_area().get_pixel_range();
                let frame = Rect {
                    x: f64::from(xr.start),
                    y: f64::from(yr.start),
                    w: f64::from(xr.end - xr.start),
                    h: f64::from(yr.end - yr.start),
                };
                let at = |x: f64, y: f64| {
                    (
                        frame.x + (x - x0) / (x1 - x0) * frame.w,
                        frame.y + frame.h - (y - y0) / (y1 - y0) * frame.h,
                    )
                };
                Ok(self.drawn(&series, &limits, (y0, at(x0, data_top).1), &frame, &at))
            },
        )
    }

    /// What the chart draws itself on the axes `plotters` drew, in pixels (`at` places a point
    /// of the axes in the plot area `frame`; `y0` is the bottom of the y axis and `band_bottom`
    /// the pixel row where the marks' band ends): the shaded stretch, the marks, each series
    /// with its markers and limits.
    fn drawn(
        &self,
        series: &[Vec<(f64, f64)>],
        limits: &[PlacedLimit],
        (y0, band_bottom): (f64, f64),
        frame: &Rect,
        at: &dyn Fn(f64, f64) -> (f64, f64),
    ) -> String {
        let (top, right) = (frame.y, frame.x + frame.w);
        let mut out = self.shade.map_or_else(String::new, |(x, _)| {
            let sx = at(x, y0).0.clamp(frame.x, right);
            format!(
                "<rect class=\"shade\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {SHADE}/>\n",
                px(sx),
                px(top),
                px(right - sx),
                px(frame.h)
            )
        });
        out.push_str(&marks_svg(self.marks, at, frame, band_bottom));
        for (k, points) in series.iter().enumerate() {
            let st = style(k);
            let _ = writeln!(
                out,
                "<g class=\"series\" data-series=\"{k}\" data-style=\"{}\">",
                st.key()
            );
            for run in finite_runs(points) {
                let pts: Vec<(f64, f64)> = thinned(&run).iter().map(|&(x, y)| at(x, y)).collect();
                out.push_str(&polyline_svg(&pts, &st, 1.5));
                out.push('\n');
                let marked = if self.plain {
                    Vec::new()
                } else {
                    marked_points(pts.len(), k)
                };
                for i in marked {
                    out.push_str(&marker_svg(st.marker, pts[i].0, pts[i].1, 3.5, st.colour));
                }
                out.push('\n');
            }
            for &(_, x, near, kind) in limits.iter().filter(|l| l.0 == k) {
                out.push_str(&limit_svg(points, (x, near.unwrap_or(y0)), kind, &st, at));
            }
            out.push_str("</g>\n");
        }
        out
    }
}

/// A limit as placed on its series: (series, x, the series' value nearest it, kind).
type PlacedLimit = (usize, f64, Option<f64>, LimitKind);

/// A limit's bracket at `(x, y)` of the axes, joined by a dotted line to the point of `points`
/// nearest in x.
fn limit_svg(
    points: &[(f64, f64)],
    (x, y): (f64, f64),
    kind: LimitKind,
    st: &Style,
    at: &dyn Fn(f64, f64) -> (f64, f64),
) -> String {
    let (bx, by) = at(x, y);
    let mut out = String::new();
    if let Some(p) = points
        .iter()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .min_by(|a, b| (a.0 - x).abs().total_cmp(&(b.0 - x).abs()))
    {
        let (sx, sy) = at(p.0, p.1);
        let _ = write!(
            out,
            "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{}\" stroke-width=\"1\" stroke-dasharray=\"1 2\"/>",
            px(sx),
            px(sy),
            px(bx),
            px(by),
            st.colour
        );
    }
    out.push_str(&bracket_svg(kind, bx, by, 14.0, st.colour));
    out.push('\n');
    out
}

/// The fill of a shaded stretch of a plot ([`Plot::shaded_from`]): a grey through which the
/// grid still shows.
pub(crate) const SHADE: &str = "fill=\"#808080\" fill-opacity=\"0.2\"";

/// A line plot as SVG text: title naming the paper item, labelled axes with units, a legend.
pub fn line_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    Plot::new(title, x_label, y_label, series).svg()
}

/// [`line_plot`] of lines without markers and with marks (events) of `kinds`
/// ([`Plot::marks`]).
pub fn marked_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    (marks, kinds): (&[Mark], &[String]),
) -> Result<String, RunError> {
    Plot::new(title, x_label, y_label, series)
        .plain_lines()
        .marks(marks, kinds)
        .svg()
}

/// A semi-logarithmic line plot: `series` hold positive values, drawn on a log10 y axis whose
/// ticks are labelled with the values themselves.
pub fn semilog_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    Plot::new(title, x_label, y_label, series).log_y().svg()
}

/// The y range of a [`category_plot_band`]: its finite values and the band's ends padded by a
/// tenth (0 to 1 with none), never below 0.
fn category_values_range(series: &[Series<'_>], band: Option<&Band<'_>>) -> (f64, f64) {
    let ends = band.iter().flat_map(|b| [b.lo, b.hi]);
    let values = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .chain(ends);
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for y in values.filter(|y| y.is_finite()) {
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if y0 > y1 {
        (y0, y1) = (0.0, 1.0);
    }
    let pad = ((y1 - y0) * 0.1).max(1e-3);
    drawable((y0 - pad).max(0.0), y1 + pad)
}

/// A band of values drawn across every category (a published range beside the points): a shaded
/// box from `lo` to `hi` on the y axis, with its legend entry.
pub struct Band<'a> {
    /// Legend text.
    pub label: &'a str,
    /// Its lower end (y axis units).
    pub lo: f64,
    /// Its upper end.
    pub hi: f64,
}

/// The colour of a [`Band`]: a grey that the series' colours read on.
pub const BAND_COLOUR: &str = "#7f7f7f";
/// How opaque a band's shading is.
pub const BAND_OPACITY: f64 = 0.18;

/// [`category_plot`] with no band.
pub fn category_plot(
    title: &str,
    categories: &[String],
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    category_plot_band(title, categories, (x_label, y_label), series, None)
}

/// A chart of values by category (e.g. one per gear) as SVG text: the categories along the x
/// axis, one marker per value, each series in a style of its own (its colour and marker; see
/// [`style`]) and set a little aside from the others within its category, so that equal values
/// stay visible, and the legend below the axes. `series` points are (category index, value); a
/// category with no value in a series simply has no marker. A `band`, when given, is shaded
/// behind the markers across the whole axis.
pub fn category_plot_band(
    title: &str,
    categories: &[String],
    (x_label, y_label): (&str, &str),
    series: &[Series<'_>],
    band: Option<&Band<'_>>,
) -> Result<String, RunError> {
    let (y0, y1) = category_values_range(series, band);
    let n = categories.len().max(1) as i32;
    let mut entries = series_entries(series, false);
    if let Some(b) = band {
        entries.push(Entry {
            label: b.label.to_owned(),
            sample: Sample::Band(BAND_COLOUR),
            series: None,
        });
    }
    chart_svg(
        title,
        1000,
        ((0..n).into_segmented(), y0..y1),
        &entries,
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
            let (xr, _) = chart.plotting_area().get_pixel_range();
            // Series side by side within a category, at most a third of its width in all.
            let slot = f64::from(xr.end - xr.start) / f64::from(n);
            let spread = (slot / 3.0).min(10.0 * series.len() as f64);
            let coord = |x: i32, y: f64| chart.backend_coord(&(SegmentValue::CenterOf(x), y));
            let mut out = String::new();
            if let Some(b) = band {
                out.push_str(&band_rect(&xr, coord(0, b.hi).1, coord(0, b.lo).1));
            }
            out.push_str(&category_markers(series, spread, &coord));
            Ok(out)
        },
    )
}

/// A band's shaded box across the plot's pixel columns `xr`, from pixel row `top` to `bottom`.
fn band_rect(xr: &std::ops::Range<i32>, top: i32, bottom: i32) -> String {
    format!(
        "<rect class=\"band\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{BAND_COLOUR}\" fill-opacity=\"{BAND_OPACITY}\" stroke=\"{BAND_COLOUR}\"/>\n",
        xr.start,
        top,
        xr.end - xr.start,
        (bottom - top).max(1)
    )
}

/// Every series' markers of a [`category_plot_band`], each series set `spread` pixels aside
/// across its category (`coord`: a category's index and a value to pixels).
fn category_markers(
    series: &[Series<'_>],
    spread: f64,
    coord: &dyn Fn(i32, f64) -> (i32, i32),
) -> String {
    let mut out = String::new();
    for (k, s) in series.iter().enumerate() {
        let st = style(k);
        let shift = if series.len() > 1 {
            spread * (k as f64 / (series.len() - 1) as f64 - 0.5)
        } else {
            0.0
        };
        let _ = writeln!(
            out,
            "<g class=\"series\" data-series=\"{k}\" data-style=\"{}\">",
            st.key()
        );
        for &(x, y) in s
            .points
            .iter()
            .filter(|p| p.0.is_finite() && p.1.is_finite())
        {
            let (cx, cy) = coord(x.round() as i32, y);
            out.push_str(&marker_svg(
                st.marker,
                f64::from(cx) + shift,
                f64::from(cy),
                5.0,
                st.colour,
            ));
        }
        out.push_str("\n</g>\n");
    }
    out
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests;
