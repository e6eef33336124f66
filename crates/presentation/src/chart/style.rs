//! How each series of a chart is drawn: a colour, a dash pattern and a marker, chosen so that no
//! two series of one chart share all three.

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
