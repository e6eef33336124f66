//! The numbered marks along a plot's x axis (the events of a figure): the band they need,
//! their numbers' rows, and the SVG that draws them.

use std::fmt::Write as _;

use super::*;

/// The share of the x range added at each end of a plot with marks: room for a marker at the
/// first or the last point (an idle start's, at the very start), inside the frame.
pub(super) const MARK_ROOM: f64 = 0.02;

/// Height of a row of mark numbers, px: their 11 px type and its line gap.
const NUMBER_ROW: f64 = 14.0;

/// Height of the marks' ticks below their numbers, px, with the space above and below them.
const MARK_TICK: f64 = 14.0;

/// The most rows of numbers above the data.
const MAX_NUMBER_ROWS: usize = 12;

/// The farthest a number may sit from its tick, px, before another row of numbers is tried.
const NUMBER_SHIFT: f64 = 24.0;

/// Space between two numbers of a row, and between a number and the frame, px.
const NUMBER_GAP: f64 = 3.0;

/// Half the width of mark number `n` at 11 px, px: digits about 7 px wide in the common
/// sans-serif faces (DejaVu Sans 0.64 em), with a margin.
fn number_half(n: usize) -> f64 {
    3.6 * n.to_string().len() as f64 + 1.0
}

/// The width of the plot area of an 800 px chart: the canvas less its 12 px margins and the
/// 70 px of the y axis' labels ([`chart_svg`]).
const PLOT_WIDTH: f64 = 800.0 - 2.0 * 12.0 - 70.0;

/// The band above the data that the marks' ticks and numbers take, as a share of the data's
/// y range (padding included): as many rows of numbers as every number needs to sit apart
/// ([`number_rows`], laid out on the plot's width) and the ticks below them, within the plot
/// area's height under a title of `title`'s lines. 0 without marks.
pub(super) fn mark_band(marks: &[Mark], (x0, x1): (f64, f64), title: &str) -> f64 {
    if marks.is_empty() {
        return 0.0;
    }
    let left = 12.0 + 70.0;
    let xs: Vec<(f64, usize)> = sorted_marks(marks)
        .iter()
        .map(|m| (left + (m.x - x0) / (x1 - x0) * PLOT_WIDTH, m.number))
        .collect();
    let rows = number_rows(&xs, (left, left + PLOT_WIDTH), MAX_NUMBER_ROWS)
        .map_or(MAX_NUMBER_ROWS, |(rows, _)| rows);
    let title_lines = wrap_words(title, ((800.0 - 24.0) / TITLE_CHAR) as usize).len();
    let height = f64::from(AXES_HEIGHT - title_height(title_lines)) - 12.0 - 40.0;
    let band = (rows as f64 * NUMBER_ROW + MARK_TICK).min(0.5 * height);
    band / (height - band)
}

/// The marks with a finite x, in order of x (then number).
fn sorted_marks(marks: &[Mark]) -> Vec<&Mark> {
    let mut order: Vec<&Mark> = marks.iter().filter(|m| m.x.is_finite()).collect();
    order.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.number.cmp(&b.number)));
    order
}

/// The numbers of marks at pixel x `marks` (sorted; each with its number) laid out in `rows`
/// rows within `(left, right)`: each in the row where it sits nearest its tick, moved right of
/// the number before it where that one is in the way, and every row then moved back left from
/// the right edge where it ran past it. Per mark, its row and the number's centre; `None`
/// where they do not fit.
fn number_layout(
    marks: &[(f64, usize)],
    (left, right): (f64, f64),
    rows: usize,
) -> Option<Vec<(usize, f64)>> {
    let mut ends = vec![f64::NEG_INFINITY; rows];
    let mut placed = Vec::with_capacity(marks.len());
    for &(x, n) in marks {
        let half = number_half(n);
        let want = x.clamp(left + NUMBER_GAP + half, right - NUMBER_GAP - half);
        let (r, centre) = (0..rows)
            .map(|r| (r, want.max(ends[r] + NUMBER_GAP + half)))
            .min_by(|a, b| (a.1 - want).total_cmp(&(b.1 - want)))?;
        ends[r] = centre + half;
        placed.push((r, centre));
    }
    for r in 0..rows {
        let mut limit = right - NUMBER_GAP;
        for i in (0..marks.len()).rev() {
            if placed[i].0 != r {
                continue;
            }
            let half = number_half(marks[i].1);
            placed[i].1 = placed[i].1.min(limit - half);
            limit = placed[i].1 - half - NUMBER_GAP;
        }
        if limit < left {
            return None;
        }
    }
    Some(placed)
}

/// The fewest rows, up to `max_rows`, in which every number of `marks` (as [`number_layout`]
/// takes them) fits within [`NUMBER_SHIFT`] of its tick, or, where none does, the layout that
/// fits with the numbers least moved; with its layout. `None` where they fit in no layout.
fn number_rows(
    marks: &[(f64, usize)],
    bounds: (f64, f64),
    max_rows: usize,
) -> Option<(usize, Vec<(usize, f64)>)> {
    let shift = |l: &[(usize, f64)]| {
        l.iter()
            .zip(marks)
            .map(|(p, m)| (p.1 - m.0).abs())
            .fold(0.0, f64::max)
    };
    let mut best: Option<(usize, Vec<(usize, f64)>)> = None;
    for rows in 1..=max_rows.max(1) {
        let Some(layout) = number_layout(marks, bounds, rows) else {
            continue;
        };
        if shift(&layout) <= NUMBER_SHIFT {
            return Some((rows, layout));
        }
        if best.as_ref().is_none_or(|b| shift(&layout) < shift(&b.1)) {
            best = Some((rows, layout));
        }
    }
    best
}

/// The marks of a plot as SVG, in pixels (`at` places a point of the axes in the plot area
/// `frame`; the marks' band runs from its top to `band_bottom`): in the band, every mark's
/// number in rows ([`number_rows`]), on a thin leader where it had to move from above its
/// tick, and below them its tick; on the curve, a marker in its kind's style, outlined in
/// white so that it stands out of the line. Where the numbers fit in no layout the band has
/// room for, a number that would overlap one in every row is left out (its tick and marker
/// still drawn).
pub(super) fn marks_svg(
    marks: &[Mark],
    at: &dyn Fn(f64, f64) -> (f64, f64),
    frame: &Rect,
    band_bottom: f64,
) -> String {
    if marks.is_empty() {
        return String::new();
    }
    let top = frame.y;
    let order = sorted_marks(marks);
    let xs: Vec<(f64, usize)> = order.iter().map(|m| (at(m.x, 0.0).0, m.number)).collect();
    let room = (((band_bottom - top - MARK_TICK) / NUMBER_ROW).floor() as usize).max(1);
    let layout = number_rows(&xs, (frame.x, frame.x + frame.w), room)
        .map(|(rows, l)| (rows, l.into_iter().map(Some).collect()))
        .unwrap_or_else(|| (room, crowded_layout(&xs, room)));
    let (rows, placed): (usize, Vec<Option<(usize, f64)>>) = layout;
    let tick_top = top + rows as f64 * NUMBER_ROW + 3.0;
    let mut s = String::from("<g class=\"marks\" font-family=\"sans-serif\" font-size=\"11\">\n");
    for (m, (&(x, _), place)) in order.iter().zip(xs.iter().zip(&placed)) {
        let (colour, marker) = mark_style(m.group);
        let _ = writeln!(
            s,
            "<line class=\"mark-tick\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"{colour}\" stroke-width=\"1.5\"/>",
            px(x),
            px(tick_top),
            px(x),
            px(band_bottom - 2.0)
        );
        if let Some((r, centre)) = *place {
            let baseline = top + (r as f64 + 0.85) * NUMBER_ROW;
            if (centre - x).abs() > 1.5 {
                let _ = writeln!(
                    s,
                    "<line class=\"mark-leader\" x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\" stroke=\"#999999\" stroke-width=\"0.6\"/>",
                    px(centre),
                    px(baseline + 2.0),
                    px(x),
                    px(tick_top)
                );
            }
            let _ = writeln!(
                s,
                "<text class=\"mark-number\" x=\"{}\" y=\"{}\" text-anchor=\"middle\" fill=\"{colour}\" stroke=\"#ffffff\" stroke-width=\"3\" paint-order=\"stroke\">{}</text>",
                px(centre),
                px(baseline),
                m.number
            );
        }
        if let Some(y) = m.y.filter(|y| y.is_finite()) {
            let (mx, my) = at(m.x, y);
            s.push_str(&marker_svg(marker, mx, my, 6.5, "#ffffff"));
            s.push_str(&marker_svg(marker, mx, my, 4.5, colour));
            s.push('\n');
        }
    }
    s.push_str("</g>\n");
    s
}

/// The numbers of `marks` where they do not all fit: each above its tick in the first of
/// `rows` rows where it overlaps no number placed before it, else left out.
fn crowded_layout(marks: &[(f64, usize)], rows: usize) -> Vec<Option<(usize, f64)>> {
    let mut ends = vec![f64::NEG_INFINITY; rows];
    marks
        .iter()
        .map(|&(x, n)| {
            let half = number_half(n);
            let r = ends.iter().position(|&end| x - half > end + NUMBER_GAP)?;
            ends[r] = x + half;
            Some((r, x))
        })
        .collect()
}

/// Whether every mark of the SVG of a plot with `marks` marks carries its number: a figure whose
/// numbers had to be left out says so in its title.
pub fn every_mark_numbered(svg: &str, marks: usize) -> bool {
    svg.matches("class=\"mark-number\"").count() == marks
}
