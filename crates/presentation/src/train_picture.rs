//! A drawing of a gear train as its gearing file gives it: each arbor a box listing its gears
//! (name and teeth), each mesh a line from its driver's arbor to its driven gear's, coloured by
//! the mesh's margin and labelled with it, the limiting meshes named under the drawing.
//!
//! The layout is the train's own: arbors in columns by how many meshes separate them from the
//! input arbor (the first mesh's driver), in the order the meshes reach them. A gearing file
//! holds no positions, so the drawing is a map of what drives what, not a plan of the plates.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::escape_xml as escape;

/// How one mesh stands, for its colour and its label.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshMargin {
    /// The mesh, as the gearing labels it.
    pub label: String,
    /// Its verdict: comfortable, near the limit or failing (`None`: not measured).
    pub verdict: Option<Margin>,
    /// What the label under the mesh says (e.g. `B: 168/200 jams`).
    pub text: String,
}

/// A mesh's margin in three grades, each with its colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Margin {
    /// Within the rule with room to spare.
    Clear,
    /// Within the rule but near it.
    Near,
    /// Beyond the rule: a limiting mesh.
    Failing,
}

impl Margin {
    /// The colour a mesh of this grade is drawn in.
    pub fn colour(self) -> &'static str {
        match self {
            Margin::Clear => "#1a7f37",
            Margin::Near => "#b7791f",
            Margin::Failing => "#c62828",
        }
    }
}

const COLUMN: f64 = 165.0;
const BOX_W: f64 = 92.0;
const ROW_H: f64 = 15.0;
const GAP: f64 = 26.0;
const TOP: f64 = 56.0;
const LEFT: f64 = 16.0;
/// A white outline behind a label, so that it reads over the line it names.
const HALO: &str = r#"paint-order="stroke" stroke="white" stroke-width="3""#;

/// An arbor's box: where it stands and what it lists.
struct Placed<'a> {
    arbor: &'a train::Arbor,
    x: f64,
    y: f64,
    h: f64,
}

/// The drawing, titled `title`, with `legend` lines explaining the colours.
pub fn train_svg(
    g: &train::Gearing,
    margins: &[MeshMargin],
    title: &str,
    legend: &[(Margin, &str)],
) -> String {
    let placed = layout(g);
    let width = placed.values().map(|p| p.x + BOX_W).fold(0.0, f64::max) + LEFT + 60.0;
    let body_bottom = placed.values().map(|p| p.y + p.h).fold(TOP, f64::max);
    let failing: Vec<&str> = margins
        .iter()
        .filter(|m| m.verdict == Some(Margin::Failing))
        .map(|m| m.label.as_str())
        .collect();
    let height = body_bottom + 40.0 + 16.0 * legend.len() as f64 + 20.0;
    let mut svg = format!(
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="11">"#
    );
    let _ = write!(
        svg,
        r#"<rect width="100%" height="100%" fill="white"/><text x="{LEFT}" y="22" font-size="14" font-weight="bold">{}</text>"#,
        escape(title)
    );
    meshes(&mut svg, g, &placed, margins);
    for p in placed.values() {
        arbor_box(&mut svg, g, p);
    }
    legend_lines(&mut svg, body_bottom + 30.0, legend, &failing);
    svg.push_str("</svg>\n");
    svg
}

/// Each arbor's box, in columns by its distance (in meshes) from the input arbor.
fn layout(g: &train::Gearing) -> BTreeMap<String, Placed<'_>> {
    let mut depth: BTreeMap<&str, usize> = BTreeMap::new();
    let mut order: Vec<&str> = Vec::new();
    let arbor_of = |gear: &str| g.arbor_of(gear).unwrap_or(gear).to_owned();
    if let Some(first) = g.meshes().first() {
        let a = g.arbor_of(&first.driver).unwrap_or(&first.driver);
        depth.insert(a, 0);
        order.push(a);
    }
    // Meshes in file order, repeatedly, until no arbor is added: each driven arbor one column
    // right of its driver's.
    loop {
        let mut added = false;
        for m in g.meshes() {
            let (from, to) = (arbor_of(&m.driver), arbor_of(&m.driven));
            if let Some(&d) = depth.get(from.as_str())
                && !depth.contains_key(to.as_str())
                && let Some(a) = g.arbors().iter().find(|a| a.name == to)
            {
                depth.insert(a.name.as_str(), d + 1);
                order.push(a.name.as_str());
                added = true;
            }
        }
        if !added {
            break;
        }
    }
    let mut next_y: BTreeMap<usize, f64> = BTreeMap::new();
    let mut placed = BTreeMap::new();
    for name in order {
        let Some(arbor) = g.arbors().iter().find(|a| a.name == name) else {
            continue;
        };
        let d = depth[name];
        let y = *next_y.entry(d).or_insert(TOP);
        let h = ROW_H * (arbor.gears.len() as f64 + 1.0) + 6.0;
        next_y.insert(d, y + h + GAP);
        let x = LEFT + COLUMN * d as f64;
        placed.insert(name.to_owned(), Placed { arbor, x, y, h });
    }
    placed
}

/// One arbor: its name, then each gear with its teeth.
fn arbor_box(svg: &mut String, g: &train::Gearing, p: &Placed<'_>) {
    let _ = write!(
        svg,
        r##"<g class="arbor"><rect x="{:.1}" y="{:.1}" width="{BOX_W}" height="{:.1}" rx="5" fill="#f4f6f8" stroke="#445"/><text x="{:.1}" y="{:.1}" font-weight="bold">{}</text>"##,
        p.x,
        p.y,
        p.h,
        p.x + 6.0,
        p.y + ROW_H,
        escape(&p.arbor.name)
    );
    for (i, gear) in p.arbor.gears.iter().enumerate() {
        let teeth = g.gear(gear).map_or(0, |d| d.teeth);
        let _ = write!(
            svg,
            r#"<text x="{:.1}" y="{:.1}">{} ({teeth})</text>"#,
            p.x + 12.0,
            p.y + ROW_H * (i as f64 + 2.0),
            escape(g.label_name(gear))
        );
    }
    svg.push_str("</g>");
}

/// Where gear `gear` sits on its arbor's box: its row's height, at the box's `side` edge.
fn gear_point(p: &Placed<'_>, gear: &str, right: bool) -> (f64, f64) {
    let row = p.arbor.gears.iter().position(|x| x == gear).unwrap_or(0);
    let x = if right { p.x + BOX_W } else { p.x };
    (x, p.y + ROW_H * (row as f64 + 2.0) - 4.0)
}

/// Each mesh as a line from its driver gear's row to its driven gear's, coloured and labelled.
fn meshes(
    svg: &mut String,
    g: &train::Gearing,
    placed: &BTreeMap<String, Placed<'_>>,
    margins: &[MeshMargin],
) {
    for m in g.meshes() {
        let at = |gear: &str| g.arbor_of(gear).and_then(|a| placed.get(a));
        let (Some(from), Some(to)) = (at(&m.driver), at(&m.driven)) else {
            continue;
        };
        let forward = to.x >= from.x;
        let (x1, y1) = gear_point(from, &m.driver, forward);
        let (x2, y2) = gear_point(to, &m.driven, !forward);
        let margin = margins.iter().find(|x| x.label == m.label);
        let colour = margin
            .and_then(|x| x.verdict)
            .map_or("#888", Margin::colour);
        let text = margin.map_or(String::new(), |x| x.text.clone());
        let (mx, my) = ((x1 + x2) / 2.0, (y1 + y2) / 2.0);
        let _ = write!(
            svg,
            r#"<g class="mesh" data-mesh="{label}"><line x1="{x1:.1}" y1="{y1:.1}" x2="{x2:.1}" y2="{y2:.1}" stroke="{colour}" stroke-width="3"/><text x="{mx:.1}" y="{:.1}" text-anchor="middle" fill="{colour}" font-weight="bold" {HALO}>{label}</text><text x="{mx:.1}" y="{:.1}" text-anchor="middle" fill="{colour}" font-size="9" {HALO}>{}</text></g>"#,
            my - 4.0,
            my + 8.0,
            escape(&text),
            label = escape(&m.label),
        );
    }
}

/// The colours explained, and the limiting meshes named.
fn legend_lines(svg: &mut String, y: f64, legend: &[(Margin, &str)], failing: &[&str]) {
    let mut y = y;
    for (margin, words) in legend {
        let _ = write!(
            svg,
            r#"<line x1="{LEFT}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="{}" stroke-width="3"/><text x="{:.1}" y="{y:.1}">{}</text>"#,
            y - 4.0,
            LEFT + 24.0,
            y - 4.0,
            margin.colour(),
            LEFT + 30.0,
            escape(words)
        );
        y += 16.0;
    }
    let named = if failing.is_empty() {
        "Limiting meshes: none".to_owned()
    } else {
        format!("Limiting meshes: {}", failing.join(", "))
    };
    let _ = write!(
        svg,
        r#"<text class="limiting" x="{LEFT}" y="{:.1}" font-weight="bold">{}</text>"#,
        y + 4.0,
        escape(&named)
    );
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn every_arbor_and_mesh_is_drawn_and_the_failing_ones_named() {
        let g = train::Gearing::freeth2006();
        let margins = vec![
            MeshMargin {
                label: "m3-e3".into(),
                verdict: Some(Margin::Failing),
                text: "B: 168/200".into(),
            },
            MeshMargin {
                label: "b2-c1".into(),
                verdict: Some(Margin::Clear),
                text: "B: 0/200".into(),
            },
        ];
        let svg = train_svg(&g, &margins, "The train", &[(Margin::Failing, "fails")]);
        for m in g.meshes() {
            assert!(
                svg.contains(&format!(r#"data-mesh="{}""#, m.label)),
                "{}",
                m.label
            );
        }
        for a in g.arbors() {
            assert!(
                svg.contains(&format!(">{}</text>", escape(&a.name))),
                "{}",
                a.name
            );
        }
        assert!(svg.contains("Limiting meshes: m3-e3"));
        assert!(svg.contains(Margin::Failing.colour()) && svg.contains(Margin::Clear.colour()));
        // The paper's name for the Games driver, n2, with its teeth.
        assert!(svg.contains(">n2 (57)</text>"));
    }

    #[test]
    fn arbors_stand_in_columns_by_their_distance_from_the_input() {
        let g = train::Gearing::freeth2006();
        let placed = layout(&g);
        assert_eq!(placed["b"].x, LEFT);
        assert!(placed["c"].x > placed["b"].x && placed["d"].x > placed["c"].x);
        // No two boxes of one column overlap.
        for a in placed.values() {
            for b in placed.values() {
                if a.arbor.name != b.arbor.name && a.x == b.x {
                    assert!(
                        a.y + a.h <= b.y || b.y + b.h <= a.y,
                        "{} {}",
                        a.arbor.name,
                        b.arbor.name
                    );
                }
            }
        }
    }
}
