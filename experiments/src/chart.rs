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

/// A vertical mark on a plot: an event at `x`, labelled (e.g. its kind and size).
pub struct Mark {
    /// Where (x axis units).
    pub x: f64,
    /// Text written beside the mark.
    pub label: String,
    /// Colour group (marks of one kind share a colour).
    pub group: usize,
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

/// A marker shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Marker {
    /// A filled circle.
    Circle,
    /// A filled square.
    Square,
    /// A filled triangle, point up.
    TriangleUp,
    /// A filled diamond.
    Diamond,
    /// A filled triangle, point down.
    TriangleDown,
    /// An x.
    Cross,
    /// A +.
    Plus,
}

impl Marker {
    /// The marker's name, as `data-style` gives it.
    pub fn name(self) -> &'static str {
        match self {
            Marker::Circle => "circle",
            Marker::Square => "square",
            Marker::TriangleUp => "triangle-up",
            Marker::Diamond => "diamond",
            Marker::TriangleDown => "triangle-down",
            Marker::Cross => "cross",
            Marker::Plus => "plus",
        }
    }
}

/// How one series is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Style {
    /// Colour, `#rrggbb`.
    pub colour: &'static str,
    /// SVG `stroke-dasharray` of its line ("" for a solid line).
    pub dash: &'static str,
    /// Marker shape.
    pub marker: Marker,
}

impl Style {
    /// `colour dash marker`, the `data-style` attribute (`solid` for no dash).
    pub fn key(&self) -> String {
        let dash = if self.dash.is_empty() {
            "solid".to_owned()
        } else {
            self.dash.replace(' ', "-")
        };
        format!("{} {dash} {}", self.colour, self.marker.name())
    }
}

/// Ten colours that stay apart on white (and for the commonest colour blindness, mostly).
const PALETTE: [&str; 10] = [
    "#1f77b4", "#d62728", "#2ca02c", "#000000", "#9467bd", "#ff7f0e", "#17becf", "#8c564b",
    "#e377c2", "#7f7f00",
];

/// Solid, dashed, dotted, dash-dot.
const DASHES: [&str; 4] = ["", "8 4", "2 3", "10 3 2 3"];

const MARKERS: [Marker; 7] = [
    Marker::Circle,
    Marker::Square,
    Marker::TriangleUp,
    Marker::Diamond,
    Marker::TriangleDown,
    Marker::Cross,
    Marker::Plus,
];

/// How many series a chart can draw in styles that all differ: 140, the least common multiple
/// of the 10 colours, 4 dash patterns and 7 markers (their counts are coprime but for 10 and 4).
pub const DISTINCT_STYLES: usize = 140;

/// The style of series `k`: colour `k mod 10`, dash `k mod 4`, marker `k mod 7`. Two series
/// below [`DISTINCT_STYLES`] differ in at least one; below 10 in colour; below 28 in dash or
/// marker.
pub fn style(k: usize) -> Style {
    Style {
        colour: PALETTE[k % PALETTE.len()],
        dash: DASHES[k % DASHES.len()],
        marker: MARKERS[k % MARKERS.len()],
    }
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

/// Width and height of the area `plotters` draws the axes in; the legend goes below it.
const AXES_HEIGHT: u32 = 480;
/// Height of one legend row, px.
const LEGEND_ROW: f64 = 18.0;
/// Font size of the legend, px.
const LEGEND_FONT: f64 = 12.0;
/// Width of a legend entry's sample (line and marker), px.
const SAMPLE: f64 = 34.0;

/// What a legend entry shows beside its text.
#[derive(Clone, Copy)]
enum Sample {
    /// A series: its line (if drawn with one) and marker.
    Series { style: Style, line: bool },
    /// A limit bracket, in black.
    Limit(LimitKind),
}

/// One legend entry.
struct Entry {
    label: String,
    sample: Sample,
    /// The series it names (`data-series`), if it names one.
    series: Option<usize>,
}

/// The legend's layout below the axes: the series' entries in columns of equal width, down
/// the columns first, rows of [`LEGEND_ROW`]; the other entries (limits) below them, one a row.
/// A label too long for the canvas is wrapped onto rows of its own.
struct LegendLayout {
    column_width: f64,
    /// Per entry: its column, its first row, and its label's lines.
    placed: Vec<(usize, usize, Vec<String>)>,
    /// Rows in all.
    rows: usize,
    /// The legend box's width, px.
    width: f64,
}

impl LegendLayout {
    fn new(entries: &[Entry], width: u32) -> Self {
        // About 0.6 em per character of a sans-serif font.
        let char_w = LEGEND_FONT * 0.6;
        let room = f64::from(width) - 2.0 * LEGEND_MARGIN - 2.0 * LEGEND_PAD;
        let beside = SAMPLE + 10.0 + 18.0;
        let fits = ((room - beside) / char_w).max(8.0) as usize;
        let entry_width = |e: &Entry| beside + e.label.chars().count() as f64 * char_w;
        let in_grid: Vec<&Entry> = entries.iter().filter(|e| e.series.is_some()).collect();
        let column_width = in_grid
            .iter()
            .map(|e| entry_width(e))
            .fold(0.0, f64::max)
            .min(room);
        let columns =
            ((room / column_width.max(1.0)).floor() as usize).clamp(1, in_grid.len().max(1));
        let mut placed = Vec::with_capacity(entries.len());
        let mut rows = 0;
        let grid_rows = in_grid.len().div_ceil(columns);
        for (k, e) in in_grid.iter().enumerate() {
            if columns > 1 {
                placed.push((k / grid_rows, k % grid_rows, vec![e.label.clone()]));
                rows = grid_rows;
            } else {
                let lines = wrap_words(&e.label, fits);
                let n = lines.len();
                placed.push((0, rows, lines));
                rows += n;
            }
        }
        let mut widest: f64 = 0.0;
        for e in entries.iter().filter(|e| e.series.is_none()) {
            let lines = wrap_words(&e.label, fits);
            let n = lines.len();
            widest = widest.max(entry_width(e).min(room));
            placed.push((0, rows, lines));
            rows += n;
        }
        // The entries in the order given: the series first, then the others.
        let order: Vec<usize> = (0..entries.len())
            .filter(|&i| entries[i].series.is_some())
            .chain((0..entries.len()).filter(|&i| entries[i].series.is_none()))
            .collect();
        let mut by_entry = vec![(0, 0, Vec::new()); entries.len()];
        for (slot, i) in placed.into_iter().zip(order) {
            by_entry[i] = slot;
        }
        LegendLayout {
            column_width,
            placed: by_entry,
            rows,
            width: (columns as f64 * column_width).max(widest) + 2.0 * LEGEND_PAD,
        }
    }

    /// The height the legend takes below the axes, its margins included (0 with no entry).
    fn height(&self) -> u32 {
        if self.rows == 0 {
            0
        } else {
            (self.rows as f64 * LEGEND_ROW + 2.0 * LEGEND_PAD + LEGEND_GAP).ceil() as u32
        }
    }
}

/// Space between the axes' area and the legend box, px.
const LEGEND_GAP: f64 = 6.0;
/// Padding inside the legend box, px.
const LEGEND_PAD: f64 = 6.0;
/// Left margin of the legend box, px.
const LEGEND_MARGIN: f64 = 12.0;

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

/// How plotting errors are reported: naming the figure.
type PlotErr<'a> = &'a dyn Fn(&dyn std::fmt::Display) -> RunError;

/// Number formatting of the SVG's coordinates.
fn px(v: f64) -> String {
    format!("{v:.1}")
}

/// `s` with the characters that SVG text must escape escaped.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A marker of `shape` centred at (x, y), `r` px in radius, in `colour`.
fn marker_svg(shape: Marker, x: f64, y: f64, r: f64, colour: &str) -> String {
    let poly = |pts: &[(f64, f64)]| {
        let p: Vec<String> = pts
            .iter()
            .map(|(dx, dy)| format!("{},{}", px(x + dx * r), px(y + dy * r)))
            .collect();
        format!("<polygon points=\"{}\" fill=\"{colour}\"/>", p.join(" "))
    };
    match shape {
        Marker::Circle => format!(
            "<circle cx=\"{}\" cy=\"{}\" r=\"{}\" fill=\"{colour}\"/>",
            px(x),
            px(y),
            px(0.9 * r)
        ),
        Marker::Square => poly(&[(-0.8, -0.8), (0.8, -0.8), (0.8, 0.8), (-0.8, 0.8)]),
        Marker::TriangleUp => poly(&[(0.0, -1.1), (1.0, 0.7), (-1.0, 0.7)]),
        Marker::Diamond => poly(&[(0.0, -1.1), (1.0, 0.0), (0.0, 1.1), (-1.0, 0.0)]),
        Marker::TriangleDown => poly(&[(0.0, 1.1), (1.0, -0.7), (-1.0, -0.7)]),
        Marker::Cross => format!(
            "<path d=\"M{} {}L{} {}M{} {}L{} {}\" stroke=\"{colour}\" stroke-width=\"2\"/>",
            px(x - r),
            px(y - r),
            px(x + r),
            px(y + r),
            px(x - r),
            px(y + r),
            px(x + r),
            px(y - r)
        ),
        Marker::Plus => format!(
            "<path d=\"M{} {}L{} {}M{} {}L{} {}\" stroke=\"{colour}\" stroke-width=\"2\"/>",
            px(x - 1.1 * r),
            px(y),
            px(x + 1.1 * r),
            px(y),
            px(x),
            px(y - 1.1 * r),
            px(x),
            px(y + 1.1 * r)
        ),
    }
}

/// A bracket `[` or `]` at (x, y) in `colour`, `h` px tall.
fn bracket_svg(kind: LimitKind, x: f64, y: f64, h: f64, colour: &str) -> String {
    let serif = match kind {
        LimitKind::Lower => 5.0,
        LimitKind::Upper => -5.0,
    };
    format!(
        "<path d=\"M{} {}L{} {}L{} {}L{} {}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2.5\"/>",
        px(x + serif),
        px(y - h / 2.0),
        px(x),
        px(y - h / 2.0),
        px(x),
        px(y + h / 2.0),
        px(x + serif),
        px(y + h / 2.0)
    )
}

/// A polyline through `pts` (pixels) in `style`, `width` px wide.
fn polyline_svg(pts: &[(f64, f64)], style: &Style, width: f64) -> String {
    let p: Vec<String> = pts
        .iter()
        .map(|(x, y)| format!("{},{}", px(*x), px(*y)))
        .collect();
    let dash = if style.dash.is_empty() {
        String::new()
    } else {
        format!(" stroke-dasharray=\"{}\"", style.dash)
    };
    format!(
        "<polyline points=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"{width}\"{dash}/>",
        p.join(" "),
        style.colour
    )
}

/// The legend below the axes: a box at the canvas' left, entries in columns.
fn legend_svg(entries: &[Entry], layout: &LegendLayout, top: f64) -> String {
    let mut s = String::new();
    if entries.is_empty() {
        return s;
    }
    let top = top + LEGEND_GAP;
    let w = layout.width;
    let h = layout.rows as f64 * LEGEND_ROW + 2.0 * LEGEND_PAD;
    let _ = writeln!(
        s,
        "<g class=\"legend\" font-family=\"sans-serif\" font-size=\"{LEGEND_FONT}\">\n<rect class=\"legend-box\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"white\" stroke=\"#888888\"/>",
        px(LEGEND_MARGIN),
        px(top),
        px(w),
        px(h)
    );
    for (e, (col, row, lines)) in entries.iter().zip(&layout.placed) {
        let x = LEGEND_MARGIN + LEGEND_PAD + *col as f64 * layout.column_width;
        let y = top + LEGEND_PAD + (*row as f64 + 0.5) * LEGEND_ROW;
        let attr = e
            .series
            .map_or_else(String::new, |k| format!(" data-series=\"{k}\""));
        let _ = write!(s, "<g class=\"legend-entry\"{attr}>");
        match e.sample {
            Sample::Series { style, line } => {
                if line {
                    s.push_str(&polyline_svg(&[(x, y), (x + SAMPLE, y)], &style, 2.0));
                }
                s.push_str(&marker_svg(
                    style.marker,
                    x + SAMPLE / 2.0,
                    y,
                    4.5,
                    style.colour,
                ));
            }
            Sample::Limit(kind) => {
                s.push_str(&bracket_svg(kind, x + SAMPLE / 2.0, y, 12.0, "#000000"));
            }
        }
        for (l, line) in lines.iter().enumerate() {
            let _ = write!(
                s,
                "<text x=\"{}\" y=\"{}\" dominant-baseline=\"middle\">{}</text>",
                px(x + SAMPLE + 8.0),
                px(y + l as f64 * LEGEND_ROW),
                esc(line)
            );
        }
        s.push_str("</g>\n");
    }
    s.push_str("</g>\n");
    s
}

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
    limits: &'a [Limit],
    limit_labels: (&'a str, &'a str),
    x_range: Option<(f64, f64)>,
    y_range: Option<(f64, f64)>,
    whole_ticks: bool,
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
            limits: &[],
            limit_labels: ("lower limit", "upper limit"),
            x_range: None,
            y_range: None,
            whole_ticks: false,
        }
    }

    /// A logarithmic y axis: the series hold positive values (others are left out), drawn on a
    /// log10 axis whose ticks are labelled with the values themselves.
    pub fn log_y(mut self) -> Self {
        self.log_y = true;
        self
    }

    /// Vertical marks (events), each labelled.
    pub fn marks(mut self, marks: &'a [Mark]) -> Self {
        self.marks = marks;
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
        let mut entries: Vec<Entry> = self
            .series
            .iter()
            .enumerate()
            .map(|(k, s)| Entry {
                label: s.label.to_owned(),
                sample: Sample::Series {
                    style: style(k),
                    line: true,
                },
                series: Some(k),
            })
            .collect();
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

    /// The chart as SVG text.
    pub fn svg(&self) -> Result<String, RunError> {
        let y_of = |y: f64| {
            if self.log_y {
                if y > 0.0 { y.log10() } else { f64::NAN }
            } else {
                y
            }
        };
        let series: Vec<Vec<(f64, f64)>> = self
            .series
            .iter()
            .map(|s| {
                s.points
                    .iter()
                    .filter(|p| !self.log_y || p.1 > 0.0)
                    .map(|&(x, y)| (x, y_of(y)))
                    .collect()
            })
            .collect();
        // Each limit at the value of its series nearest to it (none: at the bottom).
        let limits: Vec<(usize, f64, Option<f64>, LimitKind)> = self
            .limits
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
            .collect();
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        // The axes span what can be placed on them: an infinite coordinate cannot (a NaN is
        // passed over by `min` and `max`).
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
        for l in &limits {
            x0 = x0.min(l.1);
            x1 = x1.max(l.1);
        }
        if x0.partial_cmp(&x1) != Some(std::cmp::Ordering::Less) {
            x1 = x0 + 1.0;
        }
        let (x0, x1) = match self.x_range {
            Some(r) => drawable(r.0, r.1),
            None => drawable(x0, x1),
        };
        let (y0, y1) = match self.y_range {
            Some(r) => drawable(r.0, r.1),
            None => {
                let pad = ((y1 - y0) * 0.05).max(1e-9);
                drawable(y0 - pad, y1 + pad)
            }
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
                if whole {
                    mesh.x_label_formatter(&whole_x);
                }
                mesh.draw().map_err(|e| plot_err(&e))?;
                let mark_colours = [RED, MAGENTA, CYAN, GREEN, BLACK];
                for (i, m) in self.marks.iter().enumerate() {
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
                let (xr, yr) = chart.plotting_area().get_pixel_range();
                let (left, right) = (f64::from(xr.start), f64::from(xr.end));
                let (top, bottom) = (f64::from(yr.start), f64::from(yr.end));
                let at = |x: f64, y: f64| {
                    (
                        left + (x - x0) / (x1 - x0) * (right - left),
                        bottom - (y - y0) / (y1 - y0) * (bottom - top),
                    )
                };
                let mut out = String::new();
                for (k, points) in series.iter().enumerate() {
                    let st = style(k);
                    let _ = writeln!(
                        out,
                        "<g class=\"series\" data-series=\"{k}\" data-style=\"{}\">",
                        st.key()
                    );
                    for run in finite_runs(points) {
                        let pts: Vec<(f64, f64)> =
                            thinned(&run).iter().map(|&(x, y)| at(x, y)).collect();
                        out.push_str(&polyline_svg(&pts, &st, 1.5));
                        out.push('\n');
                        for i in marked_points(pts.len(), k) {
                            out.push_str(&marker_svg(
                                st.marker, pts[i].0, pts[i].1, 3.5, st.colour,
                            ));
                        }
                        out.push('\n');
                    }
                    for &(_, x, near, kind) in limits.iter().filter(|l| l.0 == k) {
                        let y = near.unwrap_or(y0);
                        let (bx, by) = at(x, y);
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
                    }
                    out.push_str("</g>\n");
                }
                Ok(out)
            },
        )
    }
}

/// A line plot as SVG text: title naming the paper item, labelled axes with units, a legend.
pub fn line_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    Plot::new(title, x_label, y_label, series).svg()
}

/// [`line_plot`] with vertical marks (events), each labelled.
pub fn marked_plot(
    title: &str,
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
    marks: &[Mark],
) -> Result<String, RunError> {
    Plot::new(title, x_label, y_label, series)
        .marks(marks)
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

/// A chart of values by category (e.g. one per gear) as SVG text: the categories along the x
/// axis, one marker per value, each series in a style of its own (its colour and marker; see
/// [`style`]) and set a little aside from the others within its category, so that equal values
/// stay visible, and the legend below the axes. `series` points are (category index, value); a
/// category with no value in a series simply has no marker.
pub fn category_plot(
    title: &str,
    categories: &[String],
    x_label: &str,
    y_label: &str,
    series: &[Series<'_>],
) -> Result<String, RunError> {
    let values = series.iter().flat_map(|s| s.points.iter().map(|p| p.1));
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for y in values.filter(|y| y.is_finite()) {
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if y0 > y1 {
        (y0, y1) = (0.0, 1.0);
    }
    let pad = ((y1 - y0) * 0.1).max(1e-3);
    let (y0, y1) = drawable((y0 - pad).max(0.0), y1 + pad);
    let n = categories.len().max(1) as i32;
    let entries: Vec<Entry> = series
        .iter()
        .enumerate()
        .map(|(k, s)| Entry {
            label: s.label.to_owned(),
            sample: Sample::Series {
                style: style(k),
                line: false,
            },
            series: Some(k),
        })
        .collect();
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
                    let (cx, cy) =
                        chart.backend_coord(&(SegmentValue::CenterOf(x.round() as i32), y));
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
            Ok(out)
        },
    )
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
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

    #[test]
    fn log_ticks_read_plainly() {
        assert_eq!(log_tick(0.031_622_776), "0.032");
        assert_eq!(log_tick(0.1), "0.1");
        assert_eq!(log_tick(3.162_277_6), "3.2");
        assert_eq!(log_tick(316.227_76), "316");
        assert_eq!(log_tick(1e-5), "1.0e-5");
        assert_eq!(log_tick(1e6), "1.0e6");
    }

    #[test]
    fn styles_differ_as_promised() {
        let all: Vec<Style> = (0..DISTINCT_STYLES).map(style).collect();
        let distinct: std::collections::HashSet<&Style> = all.iter().collect();
        assert_eq!(
            distinct.len(),
            DISTINCT_STYLES,
            "every series its own style"
        );
        assert_eq!(style(DISTINCT_STYLES), style(0), "and no more than that");
        for i in 0..28 {
            for j in 0..i {
                let (a, b) = (style(i), style(j));
                assert!((a.dash, a.marker) != (b.dash, b.marker), "{i}, {j}: grey");
                if i < 10 {
                    assert_ne!(a.colour, b.colour, "{i}, {j}: colour");
                }
            }
        }
    }

    /// The value of attribute `name` in the first tag of `svg` holding `marker`.
    fn attr(svg: &str, marker: &str, name: &str) -> f64 {
        let start = svg.find(marker).unwrap();
        let tag_start = svg[..=start].rfind('<').unwrap();
        let tag = &svg[tag_start..start + svg[start..].find('>').unwrap()];
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
    }

    fn rect(svg: &str, class: &str) -> Rect {
        let m = format!("class=\"{class}\"");
        Rect {
            x: attr(svg, &m, "x"),
            y: attr(svg, &m, "y"),
            w: attr(svg, &m, "width"),
            h: attr(svg, &m, "height"),
        }
    }

    /// The `data-style` of every `<g class="series">` of `svg`, in order.
    fn series_styles(svg: &str) -> Vec<String> {
        svg.match_indices("<g class=\"series\"")
            .map(|(i, _)| {
                let tag = &svg[i..i + svg[i..].find('>').unwrap()];
                let at = tag.find("data-style=\"").unwrap() + 12;
                tag[at..at + tag[at..].find('"').unwrap()].to_owned()
            })
            .collect()
    }

    fn many(n: usize, label_len: usize) -> Vec<(String, Vec<(f64, f64)>)> {
        (0..n)
            .map(|k| {
                // Words, and one word longer than any canvas (a file's path).
                let mut label = format!("{k}");
                while label.len() < label_len {
                    label.push_str(if label.len() % 7 == 0 { " /a/very/long/path/of/a/measured/table/that/no/legend/column/can/hold/on/one/line.ron" } else { " word" });
                }
                let points = (0..50)
                    .map(|i| (f64::from(i), 1.0 + (k as f64 + f64::from(i)).sin().abs()))
                    .collect();
                (label, points)
            })
            .collect()
    }

    #[test]
    fn n_series_get_n_distinct_styles_and_the_legend_stays_off_the_plot() {
        for (n, label_len) in [
            (1, 3),
            (2, 40),
            (5, 10),
            (15, 5),
            (30, 60),
            (140, 4),
            (3, 300),
        ] {
            let data = many(n, label_len);
            let series: Vec<Series<'_>> = data
                .iter()
                .map(|(l, p)| Series {
                    label: l,
                    points: p.clone(),
                })
                .collect();
            let categories: Vec<String> = (0..50).map(|i| format!("c{i}")).collect();
            let limits = [
                Limit {
                    series: 0,
                    x: -3.0,
                    kind: LimitKind::Lower,
                },
                Limit {
                    series: n - 1,
                    x: 55.0,
                    kind: LimitKind::Upper,
                },
            ];
            let charts = [
                line_plot("t", "x", "y", &series).unwrap(),
                semilog_plot("t", "x", "y", &series).unwrap(),
                Plot::new("t", "x", "y", &series)
                    .limits(&limits, "jam", "disengagement")
                    .svg()
                    .unwrap(),
                category_plot("t", &categories, "x", "y", &series).unwrap(),
            ];
            for svg in &charts {
                let styles = series_styles(svg);
                assert_eq!(styles.len(), n, "{n} series drawn");
                let distinct: std::collections::HashSet<&String> = styles.iter().collect();
                assert_eq!(distinct.len(), n, "{n} series, {} styles", distinct.len());
                let plot = rect(svg, "plot-area");
                let legend = rect(svg, "legend-box");
                assert!(
                    !plot.intersects(&legend),
                    "{n} series: legend {legend:?} on the plot {plot:?}"
                );
                let canvas_h = attr(svg, "<svg", "height");
                let canvas_w = attr(svg, "<svg", "width");
                assert!(
                    legend.y + legend.h <= canvas_h && legend.x >= 0.0,
                    "{n}: the legend is on the canvas: {legend:?} in {canvas_w} x {canvas_h}"
                );
                assert!(
                    legend.x + legend.w <= canvas_w,
                    "{n}: {legend:?} wider than {canvas_w}"
                );
                // Every series named in the legend, in its own style.
                assert_eq!(
                    svg.matches("<g class=\"legend-entry\" data-series=")
                        .count(),
                    n
                );
            }
            let with_limits = &charts[2];
            assert_eq!(with_limits.matches("<g class=\"legend-entry\">").count(), 2);
        }
    }

    #[test]
    fn limits_widen_the_axis_and_sit_on_their_series() {
        let series = [Series {
            label: "a",
            points: vec![(10.0, 1.0), (20.0, 2.0)],
        }];
        let limits = [
            Limit {
                series: 0,
                x: 5.0,
                kind: LimitKind::Lower,
            },
            Limit {
                series: 0,
                x: 25.0,
                kind: LimitKind::Upper,
            },
        ];
        let svg = Plot::new("t", "x", "y", &series)
            .limits(&limits, "jam limit", "disengagement limit")
            .svg()
            .unwrap();
        assert!(svg.contains(">jam limit</text>"));
        assert!(svg.contains(">disengagement limit</text>"));
        let plot = rect(&svg, "plot-area");
        // Both brackets drawn inside the plot area, in the series' colour.
        let brackets: Vec<&str> = svg
            .match_indices("stroke-width=\"2.5\"")
            .map(|(i, _)| &svg[svg[..i].rfind('<').unwrap()..i])
            .collect();
        assert_eq!(brackets.len(), 4, "two on the plot, two in the legend");
        for b in &brackets[..2] {
            assert!(b.contains(style(0).colour), "{b}");
            let d = &b[b.find("d=\"M").unwrap() + 4..];
            let x: f64 = d[..d.find(' ').unwrap()].parse().unwrap();
            assert!(x >= plot.x - 6.0 && x <= plot.x + plot.w + 6.0, "{b}");
        }
    }
}
