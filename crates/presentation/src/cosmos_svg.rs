//! The picture of a cosmos train (`cosmos`), drawn from its stored plan
//! ([`study::cosmos::TrainPlan`]): the fixed gears at b's axis inside b1, the arbors b1
//! carries, each gear drawn at its pitch radius, each mesh a line between the two axes coloured
//! by the mesh's largest tolerable random error in the grades of the 2006 train's picture
//! ([`crate::train_picture::Margin`]).
//!
//! The plan is a schematic: every arbor at its true centre distance from the arbor that drives
//! it, the directions chosen for legibility. The caption says so.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use crate::escape_xml as esc;
use crate::train_picture::Margin;
use study::cosmos::{GearingResults, MeshTolerance, PlannedArbor, TrainPlan};

/// Pixels per millimetre.
const SCALE: f64 = 4.0;

/// The grades of a mesh by its largest tolerable random error (fraction of the pitch), each
/// with its legend: below Edmunds' Cases A-C (0.04) the mesh fails his gentlest measurements;
/// from 0.08 (Case D) it tolerates his roughest.
const GRADES: [(Margin, &str); 3] = [
    (
        Margin::Failing,
        "below 0.04 of the pitch: fails the random error of Edmunds' Cases A-C",
    ),
    (
        Margin::Near,
        "0.04 to 0.08: tolerates Cases A-C's random error, not Case D's",
    ),
    (
        Margin::Clear,
        "0.08 or more: tolerates Case D's random error",
    ),
];

/// The grade of a mesh with largest tolerable random error `e` (None: below the grid).
fn grade(e: Option<f64>) -> Margin {
    match e {
        Some(x) if x >= 0.08 => Margin::Clear,
        Some(x) if x >= 0.04 => Margin::Near,
        _ => Margin::Failing,
    }
}

/// The drawing's extent (mm) as (left, right, bottom, top): b1 and every gear's circle.
fn bounds(plan: &TrainPlan) -> (f64, f64, f64, f64) {
    let b1 = plan.carrier_radius;
    let mut b = (-b1, b1, -b1, b1);
    for a in &plan.arbors {
        for gear in &a.gears {
            let r = gear.pitch_radius + 6.0;
            b = (
                b.0.min(a.x - r),
                b.1.max(a.x + r),
                b.2.min(a.y - r),
                b.3.max(a.y + r),
            );
        }
    }
    b
}

/// The SVG picture of one gearing's cosmos train with its meshes' tolerances, at clearance G
/// (% of h).
pub fn train_picture(r: &GearingResults, clearance: f64) -> String {
    let plan = &r.plan;
    let tolerance: BTreeMap<&str, &MeshTolerance> =
        r.meshes.iter().map(|m| (m.mesh.as_str(), m)).collect();
    let bounds = bounds(plan);
    let (w, top) = (((bounds.1 - bounds.0) * SCALE).max(900.0), 60.0);
    let drawing = (bounds.3 - bounds.2) * SCALE;
    let height = drawing + top + 40.0 + 22.0 * (GRADES.len() + 1) as f64;
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
    let b1 = plan.carrier_radius * SCALE;
    let _ = write!(
        svg,
        r##"<circle cx="{cx:.1}" cy="{cy:.1}" r="{b1:.1}" fill="none" stroke="#999" stroke-dasharray="6 4"/><text x="{:.1}" y="{:.1}" fill="#777">b1 (carrier)</text>"##,
        cx + b1 * 0.72,
        cy - b1 * 0.72
    );
    meshes_svg(&mut svg, plan, &tolerance, &px);
    for a in &plan.arbors {
        arbor_svg(&mut svg, a, &px);
    }
    legend_svg(&mut svg, drawing + top + 20.0);
    svg.push_str("</svg>\n");
    svg
}

/// Each mesh: a line between the two axes in its grade's colour, its E. max written beside it.
fn meshes_svg(
    svg: &mut String,
    plan: &TrainPlan,
    tolerance: &BTreeMap<&str, &MeshTolerance>,
    px: &dyn Fn(f64, f64) -> (f64, f64),
) {
    let axis = |name: &str| plan.arbors.iter().find(|a| a.name == name);
    for m in &plan.meshes {
        let (Some(a), Some(b)) = (axis(&m.from), axis(&m.to)) else {
            continue;
        };
        let e = tolerance.get(m.mesh.as_str()).and_then(|t| t.random);
        let colour = grade(e).colour();
        let ((u1, v1), (u2, v2)) = (px(a.x, a.y), px(b.x, b.y));
        let text = e.map_or_else(|| "< grid".into(), |x| registry::fmt_f64(x, 3));
        let _ = write!(
            svg,
            r#"<g class="mesh" data-mesh="{label}"><line x1="{u1:.1}" y1="{v1:.1}" x2="{u2:.1}" y2="{v2:.1}" stroke="{colour}" stroke-width="5" stroke-linecap="round" opacity="0.85"><title>{label}: E. max {text}</title></line><text x="{:.1}" y="{:.1}" font-size="10" font-weight="bold" fill="{colour}">{text}</text></g>"#,
            (u1 + u2) / 2.0 + 5.0,
            (v1 + v2) / 2.0 + 3.0,
            label = esc(&m.mesh),
        );
    }
}

/// One arbor: each of its gears at its pitch radius round the axis, named with its teeth; the
/// fixed gears dashed.
fn arbor_svg(svg: &mut String, a: &PlannedArbor, px: &dyn Fn(f64, f64) -> (f64, f64)) {
    let (u, v) = px(a.x, a.y);
    let dash = if a.fixed {
        r#" stroke-dasharray="3 3""#
    } else {
        ""
    };
    for (k, gear) in a.gears.iter().enumerate() {
        let r = gear.pitch_radius * SCALE;
        let _ = write!(
            svg,
            r##"<circle cx="{u:.1}" cy="{v:.1}" r="{r:.1}" fill="none" stroke="#333" stroke-width="1"{dash}/><text x="{:.1}" y="{:.1}" font-size="9" fill="#222">{} ({})</text>"##,
            u + 3.0,
            v + 11.0 + 10.0 * k as f64,
            esc(&gear.name),
            gear.teeth
        );
    }
    let _ = write!(
        svg,
        r##"<circle cx="{u:.1}" cy="{v:.1}" r="2" fill="#333"/>"##
    );
}

/// The grades' legend, from `y` down.
fn legend_svg(svg: &mut String, y: f64) {
    let _ = write!(
        svg,
        r#"<text x="10" y="{y:.1}">Mesh colour and number: its largest tolerable random error (Table 4's grid and rule; fraction of the pitch); gears named with their teeth</text>"#
    );
    for (k, (margin, label)) in GRADES.iter().enumerate() {
        let yy = y + 18.0 + 20.0 * k as f64;
        let _ = write!(
            svg,
            r#"<line x1="14" y1="{:.1}" x2="44" y2="{:.1}" stroke="{}" stroke-width="5"/><text x="52" y="{yy:.1}">{}</text>"#,
            yy - 4.0,
            yy - 4.0,
            margin.colour(),
            esc(label)
        );
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    /// The plan of the 2021 cosmos with every mesh given a tolerance, below the grid for the
    /// first.
    fn results() -> GearingResults {
        let g = train::Gearing::builtin("freeth2021-cosmos").unwrap();
        let plan = study::cosmos::plan(&g, 0.44, 1.1);
        let meshes = plan
            .meshes
            .iter()
            .enumerate()
            .map(|(k, m)| MeshTolerance {
                mesh: m.mesh.clone(),
                gears: Default::default(),
                pointers: Vec::new(),
                margin_mm: None,
                random: (k > 0).then_some(0.09),
                random_deg: None,
                random_mm: None,
                systematic: None,
                eccentricity_mm: None,
                cases: Vec::new(),
            })
            .collect();
        GearingResults {
            gearing: "freeth2021-cosmos".into(),
            outputs: Vec::new(),
            display: Vec::new(),
            meshes,
            failure: Vec::new(),
            plan,
        }
    }

    #[test]
    fn every_mesh_and_gear_is_drawn_in_its_grade() {
        let r = results();
        let svg = train_picture(&r, 40.0);
        for m in &r.plan.meshes {
            assert!(
                svg.contains(&format!(r#"data-mesh="{}""#, m.mesh)),
                "{}",
                m.mesh
            );
        }
        for a in &r.plan.arbors {
            for g in &a.gears {
                assert!(svg.contains(&format!(">{} ({})</text>", g.name, g.teeth)));
            }
        }
        assert!(svg.contains("< grid") && svg.contains(">0.090<"));
        assert!(svg.contains(Margin::Failing.colour()) && svg.contains(Margin::Clear.colour()));
        assert_eq!(grade(None), Margin::Failing);
        assert_eq!(grade(Some(0.05)), Margin::Near);
        assert_eq!(grade(Some(0.08)), Margin::Clear);
    }
}
