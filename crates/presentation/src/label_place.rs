//! Labels of a picture placed clear of each other and of its outlines: each label tries
//! positions at growing distance from where it belongs, nearest first, and takes the first whose
//! box crosses no outline and no label already placed, lies within the canvas and, where asked,
//! outside the areas it must keep off (a gear's body). Presentation only.

use crate::chart::Rect;

/// Where a text's `x` sits in its box, as SVG's `text-anchor`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    /// `x` is the text's left end.
    Start,
    /// `x` is the text's middle.
    Middle,
    /// `x` is the text's right end.
    End,
}

impl Anchor {
    /// The SVG `text-anchor` value.
    pub fn svg(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// Advance of a character as a share of the font size: generous for the common sans-serif
/// faces (DejaVu Sans averages about 0.55 on these labels), so a box holds its text whichever
/// face the viewer has.
const CHAR_WIDTH: f64 = 0.6;

/// Space kept clear around a label's box, px.
const PAD: f64 = 2.0;

/// Distance between the baselines of a label's lines, as a share of the font size.
pub const LINE_GAP: f64 = 1.2;

/// The box of `text` drawn at `(x, y)` (`y` the first line's baseline) with `anchor` and font
/// size `font` px, its lines (split at `\n`) [`LINE_GAP`] apart: the ascent above the baseline
/// is 0.8 of the font size, the descent 0.25.
pub fn text_box((x, y): (f64, f64), anchor: Anchor, text: &str, font: f64) -> Rect {
    let chars = text.lines().map(|l| l.chars().count()).max().unwrap_or(0);
    let lines = text.lines().count().max(1) as f64;
    let w = CHAR_WIDTH * font * chars as f64;
    let left = match anchor {
        Anchor::Start => x,
        Anchor::Middle => x - 0.5 * w,
        Anchor::End => x - w,
    };
    Rect {
        x: left,
        y: y - 0.8 * font,
        w,
        h: 1.05 * font + (lines - 1.0) * LINE_GAP * font,
    }
}

/// Whether `p` lies inside the closed polygon through `points` (even-odd rule).
pub fn inside(points: &[(f64, f64)], p: (f64, f64)) -> bool {
    let n = points.len();
    let mut within = false;
    for i in 0..n {
        let (a, b) = (points[i], points[(i + 1) % n]);
        if (a.1 > p.1) != (b.1 > p.1) && p.0 < a.0 + (p.1 - a.1) / (b.1 - a.1) * (b.0 - a.0) {
            within = !within;
        }
    }
    within
}

/// `r` grown by `d` on every side.
fn grown(r: &Rect, d: f64) -> Rect {
    Rect {
        x: r.x - d,
        y: r.y - d,
        w: r.w + 2.0 * d,
        h: r.h + 2.0 * d,
    }
}

/// Does the segment from `a` to `b` meet the rectangle `r` (cross it, or lie inside it)? The
/// segment is clipped to the rectangle's slab in x, then in y (Liang-Barsky).
pub fn segment_meets(r: &Rect, a: (f64, f64), b: (f64, f64)) -> bool {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in [
        (-dx, a.0 - r.x),
        (dx, r.x + r.w - a.0),
        (-dy, a.1 - r.y),
        (dy, r.y + r.h - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return false;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    t0 <= t1
}

/// A segment of a picture's outlines, px.
pub type Segment = ((f64, f64), (f64, f64));

/// The closed polygon through `points` as its edges.
pub fn edges(points: &[(f64, f64)]) -> Vec<Segment> {
    let n = points.len();
    (0..n).map(|i| (points[i], points[(i + 1) % n])).collect()
}

/// The labels placed so far and the outlines they keep off.
pub struct Placer {
    /// Boxes taken: placed labels and marks.
    taken: Vec<Rect>,
    /// Outline segments no label may cross.
    lines: Vec<Segment>,
    /// The canvas every label stays within, if any.
    canvas: Option<Rect>,
}

/// What a position outside the canvas counts as: more than anything it could meet inside.
const OFF_CANVAS: usize = 1_000_000;

/// One label to place: its text, font size, anchor, and the point it belongs at.
pub struct Label<'a> {
    /// The text.
    pub text: &'a str,
    /// Font size, px.
    pub font: f64,
    /// How the text hangs on its position.
    pub anchor: Anchor,
    /// Where it belongs (its position when nothing is in the way), px.
    pub at: (f64, f64),
}

/// Step between tried positions, px.
const STEP: f64 = 4.0;

/// Tried distances: up to this many steps from where a label belongs.
const STEPS: usize = 120;

impl Placer {
    /// A placer that keeps labels off `lines`.
    pub fn new(lines: Vec<Segment>) -> Placer {
        Placer {
            taken: Vec::new(),
            lines,
            canvas: None,
        }
    }

    /// Keep every label within `canvas` too.
    pub fn within(mut self, canvas: Rect) -> Placer {
        self.canvas = Some(canvas);
        self
    }

    /// Keep labels off the segments `lines` too (an axis, an arrow).
    pub fn keep_off(&mut self, lines: &[Segment]) {
        self.lines.extend_from_slice(lines);
    }

    /// Keep labels off `r` too (a dot, an arrowhead).
    pub fn block(&mut self, r: Rect) {
        self.taken.push(r);
    }

    /// How many outlines and taken boxes the box `r` (padded) meets, and of `areas` it lies
    /// in; [`OFF_CANVAS`] more where it leaves the canvas.
    fn hits(&self, r: &Rect, areas: &[&[(f64, f64)]]) -> usize {
        let off = self.canvas.is_some_and(|c| {
            r.x < c.x || r.y < c.y || r.x + r.w > c.x + c.w || r.y + r.h > c.y + c.h
        });
        let r = grown(r, PAD);
        let boxes = self.taken.iter().filter(|t| t.intersects(&r)).count();
        let lines = self
            .lines
            .iter()
            .filter(|(a, b)| segment_meets(&r, *a, *b))
            .count();
        let centre = (r.x + 0.5 * r.w, r.y + 0.5 * r.h);
        let within = areas.iter().filter(|a| inside(a, centre)).count();
        boxes + lines + within + if off { OFF_CANVAS } else { 0 }
    }

    /// The position of `label`: the nearest to where it belongs along `directions` (unit
    /// vectors in page px, tried in turn at each distance) whose box meets nothing, or, when
    /// every tried position meets something, the one that meets least (the nearest of those).
    /// The label's box is then taken.
    pub fn place(&mut self, label: &Label<'_>, directions: &[(f64, f64)]) -> (f64, f64) {
        self.place_off(label, directions, &[])
    }

    /// [`Placer::place`], the label's box kept out of `areas` too (closed polygons, px: a box
    /// that crosses none of their edges is out of one when its centre is).
    pub fn place_off(
        &mut self,
        label: &Label<'_>,
        directions: &[(f64, f64)],
        areas: &[&[(f64, f64)]],
    ) -> (f64, f64) {
        let mut best = (label.at, usize::MAX);
        'search: for k in 0..=STEPS {
            let d = STEP * k as f64;
            for dir in directions {
                let p = (label.at.0 + d * dir.0, label.at.1 + d * dir.1);
                let hits = self.hits(&text_box(p, label.anchor, label.text, label.font), areas);
                if hits < best.1 {
                    best = (p, hits);
                }
                if hits == 0 {
                    break 'search;
                }
                if k == 0 {
                    // Every direction starts at the same point.
                    break;
                }
            }
        }
        self.taken
            .push(text_box(best.0, label.anchor, label.text, label.font));
        best.0
    }
}

/// The point of `r` nearest to `p`: where a leader from `p` meets a label's box.
pub fn nearest_on(r: &Rect, p: (f64, f64)) -> (f64, f64) {
    (p.0.clamp(r.x, r.x + r.w), p.1.clamp(r.y, r.y + r.h))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_meet_boxes_they_cross_or_lie_in() {
        let r = Rect {
            x: 0.0,
            y: 0.0,
            w: 10.0,
            h: 5.0,
        };
        assert!(segment_meets(&r, (-5.0, 2.0), (15.0, 2.0)));
        assert!(segment_meets(&r, (1.0, 1.0), (2.0, 2.0)));
        assert!(!segment_meets(&r, (-5.0, 7.0), (15.0, 7.0)));
        assert!(!segment_meets(&r, (-5.0, -1.0), (-1.0, 10.0)));
        assert!(segment_meets(&r, (-5.0, -5.0), (15.0, 10.0)));
    }

    #[test]
    fn a_label_moves_off_a_line_and_off_another_label() {
        // A horizontal line through where both labels belong.
        let mut placer = Placer::new(vec![((0.0, 100.0), (400.0, 100.0))]);
        let label = Label {
            text: "driver tooth 0",
            font: 13.0,
            anchor: Anchor::Start,
            at: (100.0, 105.0),
        };
        let up = [(0.0, -1.0)];
        let first = placer.place(&label, &up);
        let b1 = text_box(first, Anchor::Start, label.text, 13.0);
        assert!(b1.y + b1.h < 100.0, "{b1:?}");
        let second = placer.place(&label, &up);
        let b2 = text_box(second, Anchor::Start, label.text, 13.0);
        assert!(!b1.intersects(&b2), "{b1:?} {b2:?}");
        assert!(second.1 < first.1);
    }
}
