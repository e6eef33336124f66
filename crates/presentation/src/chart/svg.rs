//! The SVG elements a chart writes itself: numbers, escaped text, markers, limit brackets and
//! series lines.

use super::{LimitKind, Marker, Style};

/// Number formatting of the SVG's coordinates.
pub(super) fn px(v: f64) -> String {
    format!("{v:.1}")
}

/// A marker of `shape` centred at (x, y), `r` px in radius, in `colour`.
pub(super) fn marker_svg(shape: Marker, x: f64, y: f64, r: f64, colour: &str) -> String {
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
pub(super) fn bracket_svg(kind: LimitKind, x: f64, y: f64, h: f64, colour: &str) -> String {
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
pub(super) fn polyline_svg(pts: &[(f64, f64)], style: &Style, width: f64) -> String {
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
