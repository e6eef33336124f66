//! The legend below a chart's axes: its entries laid out in columns, in a box of its own that
//! never meets the plot area, written as SVG.

use std::fmt::Write as _;

use super::svg::{marker_svg, px};
use super::{BAND_OPACITY, LimitKind, Style, bracket_svg, polyline_svg, wrap_words};
use crate::escape_xml as esc;

/// Height of one legend row, px.
const LEGEND_ROW: f64 = 18.0;
/// Font size of the legend, px.
const LEGEND_FONT: f64 = 12.0;
/// Width of a legend entry's sample (line and marker), px.
const SAMPLE: f64 = 34.0;

/// What a legend entry shows beside its text.
#[derive(Clone, Copy)]
pub(super) enum Sample {
    /// A series: its line (if drawn with one) and marker.
    Series { style: Style, line: bool },
    /// A limit bracket, in black.
    Limit(LimitKind),
    /// A series drawn as a line only, without markers.
    Line(Style),
    /// A kind of mark: its marker in its colour.
    Mark {
        colour: &'static str,
        marker: super::Marker,
    },
    /// A shaded stretch of the plot: a grey swatch.
    Shade,
    /// A band of values: a shaded box in its colour.
    Band(&'static str),
}

/// One legend entry.
pub(super) struct Entry {
    pub(super) label: String,
    pub(super) sample: Sample,
    /// The series it names (`data-series`), if it names one.
    pub(super) series: Option<usize>,
}

/// The legend's layout below the axes: the series' entries in columns of equal width, down
/// the columns first, rows of [`LEGEND_ROW`]; the other entries (limits) below them, one a row.
/// A label too long for the canvas is wrapped onto rows of its own.
pub(super) struct LegendLayout {
    column_width: f64,
    /// Per entry: its column, its first row, and its label's lines.
    placed: Vec<(usize, usize, Vec<String>)>,
    /// Rows in all.
    rows: usize,
    /// The legend box's width, px.
    width: f64,
}

impl LegendLayout {
    pub(super) fn new(entries: &[Entry], width: u32) -> Self {
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
    pub(super) fn height(&self) -> u32 {
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

/// The legend below the axes: a box at the canvas' left, entries in columns.
pub(super) fn legend_svg(entries: &[Entry], layout: &LegendLayout, top: f64) -> String {
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
            Sample::Line(style) => {
                s.push_str(&polyline_svg(&[(x, y), (x + SAMPLE, y)], &style, 2.0));
            }
            Sample::Mark { colour, marker } => {
                s.push_str(&marker_svg(marker, x + SAMPLE / 2.0, y, 4.5, colour));
            }
            Sample::Shade => {
                let _ = write!(
                    s,
                    "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" {} stroke=\"#aaaaaa\"/>",
                    px(x),
                    px(y - 6.0),
                    px(SAMPLE),
                    px(12.0),
                    super::SHADE
                );
            }
            Sample::Band(colour) => {
                let _ = write!(
                    s,
                    "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"10\" fill=\"{colour}\" fill-opacity=\"{BAND_OPACITY}\" stroke=\"{colour}\"/>",
                    px(x),
                    px(y - 5.0),
                    px(SAMPLE)
                );
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
