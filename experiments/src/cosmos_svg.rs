//! The picture of a cosmos train (`cosmos`): the fixed gears at b's axis inside b1, the arbors
//! b1 carries, each gear drawn at its pitch radius, each mesh a line between the two axes
//! coloured by the mesh's largest tolerable random error.
//!
//! The layout is a schematic: every arbor sits at its true centre distance from the arbor that
//! drives it (pitch radii plus the run's clearance G), but the directions are chosen for
//! legibility, trains fanned out from the centre; the output tubes that turn on b's axis are
//! drawn where their mesh puts them, not at the centre. The caption says so.

use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::fmt::Write as _;

use study::cosmos::{GearingResults, MeshTolerance};
use train::Gearing;

/// Pixels per millimetre.
const SCALE: f64 = 4.0;

/// Colour classes of a mesh by its largest tolerable random error (fraction of the pitch): the
/// upper bound of each class, its colour and its legend. Below Edmunds' Cases A-C (0.04) the
/// mesh fails his gentlest measurements; at 0.08 (Case D) it tolerates his roughest.
const CLASSES: [(f64, &str, &str); 4] = [
    (
        0.04,
        "#c0392b",
        "below 0.04 of the pitch (fails Cases A-C's random error)",
    ),
    (0.05, "#e67e22", "0.04 to 0.05"),
    (0.08, "#d4ac0d", "0.05 to 0.08"),
    (
        f64::INFINITY,
        "#1e8449",
        "0.08 or more (tolerates Case D's random error)",
    ),
];

/// Colour of a mesh with largest tolerable random error `e` (None: below the grid, red).
fn colour(e: Option<f64>) -> &'static str {
    let e = e.unwrap_or(0.0);
    CLASSES
        .iter()
        .find(|(up, _, _)| e < *up)
        .map_or("#1e8449", |c| c.1)
}

/// `s` with the characters XML gives meaning escaped.
fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// Each carried arbor's position (mm, b's axis at the origin), placed breadth-first from the
/// fixed arbor at its centre distance from the arbor that drives it; the first arbors fanned
/// evenly round, each later one turned from its parent's ray.
fn layout(g: &Gearing, clearance_mm: f64, h: f64) -> BTreeMap<String, (f64, f64, f64)> {
    let Some(e) = g.epicyclic() else {
        return BTreeMap::new();
    };
    // (x, y, direction of the ray that reached it)
    let mut at: BTreeMap<String, (f64, f64, f64)> = BTreeMap::new();
    at.insert(e.fixed.clone(), (0.0, 0.0, 0.0));
    let mut queue = std::collections::VecDeque::from([e.fixed.clone()]);
    while let Some(arbor) = queue.pop_front() {
        let (x, y, dir) = at[&arbor];
        let out: Vec<&train::MeshData> = g
            .meshes()
            .iter()
            .filter(|m| g.arbor_of(&m.driver) == Some(arbor.as_str()))
            .filter(|m| g.arbor_of(&m.driven).is_some_and(|a| !at.contains_key(a)))
            .collect();
        let n = out.len();
        for (k, m) in out.into_iter().enumerate() {
            let Some(next) = g.arbor_of(&m.driven) else {
                continue;
            };
            let pitch = |name: &str| g.tip_radius_at(name, h).map_or(0.0, |r| r - h / 2.0);
            let d = pitch(&m.driver) + pitch(&m.driven) + clearance_mm;
            let a = if arbor == e.fixed {
                TAU * k as f64 / n.max(1) as f64 + 0.3
            } else {
                dir + 1.1 * (k as f64 - (n as f64 - 1.0) / 2.0) + 0.3
            };
            at.insert(next.to_owned(), (x + d * a.cos(), y + d * a.sin(), a));
            queue.push_back(next.to_owned());
        }
    }
    at
}

/// The SVG picture of `g`'s cosmos train with the tolerances of `r` (at clearance G % of h).
pub fn train_picture(g: &Gearing, clearance: f64, h: f64, r: &GearingResults) -> String {
    let pos = layout(g, clearance / 100.0 * h, h);
    let pitch = |name: &str| g.tip_radius_at(name, h).map_or(0.0, |x| x - h / 2.0);
    let tolerance: BTreeMap<&str, &MeshTolerance> =
        r.meshes.iter().map(|m| (m.mesh.as_str(), m)).collect();
    // The drawing's extent (mm): every gear's circle and b1's.
    let b1 = g.fitted_radius("b1").unwrap_or(64.4);
    let mut bounds = (-b1, b1, -b1, b1);
    for (a, &(x, y, _)) in &pos {
        for n in g.arbor(a).map(|x| x.gears.clone()).unwrap_or_default() {
            let r = pitch(&n) + 6.0;
            bounds = (
                bounds.0.min(x - r),
                bounds.1.max(x + r),
                bounds.2.min(y - r),
                bounds.3.max(y + r),
            );
        }
    }
    let (w, top) = (((bounds.1 - bounds.0) * SCALE).max(900.0), 60.0);
    let drawing = (bounds.3 - bounds.2) * SCALE;
    let height = drawing + top + 40.0 + 22.0 * CLASSES.len() as f64;
    let px = |x: f64, y: f64| ((x - bounds.0) * SCALE, top + (bounds.3 - y) * SCALE);
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w:.0}" height="{height:.0}" viewBox="0 0 {w:.0} {height:.0}" font-family="sans-serif" font-size="11"><rect width="100%" height="100%" fill="white"/>"#
    );
    let _ = write!(
        svg,
        r#"<text x="10" y="20" font-size="14">{}: the cosmos train in b1's frame, meshes coloured by their largest tolerable random error</text><text x="10" y="38">Schematic: each arbor at its true centre distance (pitch radii + G = {} % of h) from the arbor driving it, directions for legibility; circles at pitch radius; b1 dashed.</text>"#,
        esc(&r.gearing),
        registry::fmt_f64(clearance, 0)
    );
    // b1, the carrier, round the centre.
    let (cx, cy) = px(0.0, 0.0);
    let _ = write!(
        svg,
        r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{:.1}" fill="none" stroke="#999" stroke-dasharray="6 4"/><text x="{:.1}" y="{:.1}" fill="#777">b1 (carrier)</text>"##,
        b1 * SCALE,
        cx + b1 * SCALE * 0.72,
        cy - b1 * SCALE * 0.72
    );
    meshes_svg(&mut svg, g, &pos, &tolerance, &px);
    gears_svg(&mut svg, g, &pos, &pitch, &px);
    legend_svg(&mut svg, drawing + top + 20.0);
    svg.push_str("</svg>\n");
    svg
}

/// Each mesh: a line between the two axes in its class's colour, its E. max written beside it.
fn meshes_svg(
    svg: &mut String,
    g: &Gearing,
    pos: &BTreeMap<String, (f64, f64, f64)>,
    tolerance: &BTreeMap<&str, &MeshTolerance>,
    px: &dyn Fn(f64, f64) -> (f64, f64),
) {
    for m in g.meshes() {
        let (Some(a), Some(b)) = (g.arbor_of(&m.driver), g.arbor_of(&m.driven)) else {
            continue;
        };
        let (Some(&(x1, y1, _)), Some(&(x2, y2, _))) = (pos.get(a), pos.get(b)) else {
            continue;
        };
        let e = tolerance.get(m.label.as_str()).and_then(|t| t.random);
        let ((u1, v1), (u2, v2)) = (px(x1, y1), px(x2, y2));
        let text = e.map_or_else(|| "< grid".into(), |x| registry::fmt_f64(x, 3));
        let _ = write!(
            svg,
            r#"<line x1="{u1:.1}" y1="{v1:.1}" x2="{u2:.1}" y2="{v2:.1}" stroke="{}" stroke-width="5" stroke-linecap="round" opacity="0.85"><title>{}: E. max {text}</title></line><text x="{:.1}" y="{:.1}" font-size="10" font-weight="bold" fill="{}">{text}</text>"#,
            colour(e),
            esc(&m.label),
            (u1 + u2) / 2.0 + 5.0,
            (v1 + v2) / 2.0 + 3.0,
            colour(e),
        );
    }
}

/// Each gear of the cosmos at its pitch radius round its arbor's axis, named with its teeth; the
/// fixed gears dashed.
fn gears_svg(
    svg: &mut String,
    g: &Gearing,
    pos: &BTreeMap<String, (f64, f64, f64)>,
    pitch: &dyn Fn(&str) -> f64,
    px: &dyn Fn(f64, f64) -> (f64, f64),
) {
    let fixed = g.epicyclic().map(|e| e.fixed.clone()).unwrap_or_default();
    for (arbor, &(x, y, _)) in pos {
        let Some(a) = g.arbor(arbor) else {
            continue;
        };
        let (u, v) = px(x, y);
        let dash = if *arbor == fixed {
            r#" stroke-dasharray="3 3""#
        } else {
            ""
        };
        for (k, name) in a.gears.iter().enumerate() {
            let teeth = g.gear(name).map_or(0, |d| d.teeth);
            let r = pitch(name) * SCALE;
            let _ = write!(
                svg,
                r##"<circle cx="{u:.1}" cy="{v:.1}" r="{r:.1}" fill="none" stroke="#333" stroke-width="1"{dash}/><text x="{:.1}" y="{:.1}" font-size="9" fill="#222">{} ({teeth})</text>"##,
                u + 3.0,
                v + 11.0 + 10.0 * k as f64,
                esc(name)
            );
        }
        let _ = write!(
            svg,
            r##"<circle cx="{u:.1}" cy="{v:.1}" r="2" fill="#333"/>"##
        );
    }
}

/// The colour classes' legend, from `y` down.
fn legend_svg(svg: &mut String, y: f64) {
    let _ = write!(
        svg,
        r#"<text x="10" y="{y:.1}">Mesh colour and number: its largest tolerable random error (Table 4's grid and rule; fraction of the pitch); gears named with their teeth</text>"#
    );
    for (k, (_, c, label)) in CLASSES.iter().enumerate() {
        let yy = y + 18.0 + 20.0 * k as f64;
        let _ = write!(
            svg,
            r#"<line x1="14" y1="{:.1}" x2="44" y2="{:.1}" stroke="{c}" stroke-width="5"/><text x="52" y="{:.1}">{}</text>"#,
            yy - 4.0,
            yy - 4.0,
            yy,
            esc(label)
        );
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn arbors_sit_at_their_centre_distances() {
        let g = Gearing::builtin("freeth2021-cosmos").unwrap();
        let (h, gmm) = (1.1, 0.44);
        let pos = layout(&g, gmm, h);
        // Every carried arbor and the fixed one are placed.
        assert_eq!(pos.len(), 1 + g.epicyclic().unwrap().arbors.len());
        // Each arbor is its mesh's centre distance from the arbor that drives it.
        let (a, b) = (pos["frame"], pos["ve1"]);
        let d = (a.0 - b.0).hypot(a.1 - b.1);
        let want = 0.25 * (51.0 + 44.0) + gmm;
        assert!((d - want).abs() < 1e-9, "{d} vs {want}");
        assert_eq!(colour(None), CLASSES[0].1);
        assert_eq!(colour(Some(0.1)), CLASSES[3].1);
        assert_eq!(esc("a<b&c"), "a&lt;b&amp;c");
    }
}
