//! `pair.html`: one self-contained page (no network, works from `file://`) on which a run of one
//! mesh moves: both gears drawn from their real outlines at the centre distance, a slider over the
//! driver angle and a play button, θ and the Theoretical Difference beneath with a cursor, and the
//! events listed, each a link that jumps there and zooms on the mesh.
//!
//! Each outline is written once, in its gear's frame at φ = 0 (θ = 0); moving the slider only
//! changes two `rotate` transforms (the driver about its arbor at the origin by φ, the driven gear
//! about its arbor at (D, 0) by −θ, as `contact::Mesh::world_outlines` places them), so a
//! 223-tooth gear stays smooth. `#phi=X` in the address (X: φ − φ0 in degrees, as in `pair.csv`)
//! opens the page there.

use std::fmt::Write as _;

use contact::Trajectory;
use geometry::Vec2;

/// The note under the event tables of `pair` and `replay`: the two kinds of angle, named apart.
pub const ANGLES_NOTE: &str = "phi - phi0 and theta - theta0: angles from the start of the run (pair.csv's phi_deg and theta_deg, pair.html's slider); phi and theta: absolute angles, as replay prints them (pair.csv's phi_abs_deg and theta_abs_deg)";

/// Most samples of θ(φ) carried by the page (the slider's steps).
const MAX_SAMPLES: usize = 4000;

/// The samples of the page: (φ − φ0, θ absolute, TD), degrees, at `n` equal steps over the run.
fn samples(traj: &Trajectory, n: usize) -> Vec<(f64, f64, f64)> {
    let (a, b) = (traj.phi_start(), traj.phi_end());
    let mesh = traj.mesh();
    let ratio = mesh.driver().teeth() as f64 / mesh.driven().teeth() as f64;
    let theta0 = traj.theta_at(a);
    (0..=n)
        .map(|i| {
            let phi = a + (b - a) * i as f64 / n as f64;
            let theta = traj.theta_at(phi);
            let td = (theta - theta0) - ratio * (phi - a);
            ((phi - a).to_degrees(), theta.to_degrees(), td.to_degrees())
        })
        .collect()
}

fn points(outline: &[Vec2]) -> String {
    let mut s = String::new();
    for v in outline {
        let _ = write!(s, "{:.5},{:.5} ", v.x, v.y);
    }
    s.trim_end().to_owned()
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// The tooth numbers an output shows for an event, (driver tooth, driven tooth): the numbering
/// of the user's file, which for a driven gear measured in its own sense is the solver's
/// mirrored.
pub type Teeth<'a> = &'a dyn Fn(&contact::Event) -> (i64, i64);

/// The solver's own tooth numbers of an event, each within one turn (0 to N - 1): the numbering
/// of a file whose tips run the driver's way, as `replay`'s `pair.ron` does.
pub fn solver_teeth(mesh: &contact::Mesh) -> impl Fn(&contact::Event) -> (i64, i64) + use<> {
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    move |e: &contact::Event| (e.driver_tooth.rem_euclid(n1), e.driven_tooth.rem_euclid(n2))
}

/// The page for `traj` (one mesh's run), titled `title`; `counted(e)` says what the event rule
/// counts an event as (`jam`, `disengagement` or `-`), `teeth(e)` the tooth numbers it shows.
pub fn page(
    title: &str,
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    teeth: Teeth<'_>,
) -> String {
    let mesh = traj.mesh();
    let (driver, driven) = mesh.world_outlines(0.0, 0.0);
    let d = mesh.centre_distance();
    let (r1, r2) = (
        mesh.driver().max_tip_radius(),
        mesh.driven().max_tip_radius(),
    );
    let n = MAX_SAMPLES;
    let data = samples(traj, n);
    let phi0 = traj.phi_start();
    let mut json = String::from("[");
    for (i, (p, t, td)) in data.iter().enumerate() {
        let _ = write!(
            json,
            "{}[{p:.9},{t:.9},{td:.9}]",
            if i == 0 { "" } else { "," }
        );
    }
    json.push(']');
    let mut events = String::new();
    for e in traj.events() {
        let at = (e.phi - phi0).to_degrees();
        let (p, n) = contact_of(traj, e);
        let (j, k) = teeth(e);
        let _ = writeln!(
            events,
            "<li class=\"{kind}\"><a href=\"#phi={at:.9}\" data-phi=\"{at:.9}\" data-x=\"{:.9}\" data-y=\"{:.9}\" data-nx=\"{:.9}\" data-ny=\"{:.9}\">{at:.4} deg: {label} ({counted}), driver tooth {j}, driven tooth {k}</a></li>",
            p.x,
            p.y,
            n.x,
            n.y,
            kind = e.kind.name(),
            label = e.label(),
            counted = counted(e),
        );
    }
    if events.is_empty() {
        events.push_str("<li>no event: the driven gear was driven throughout</li>\n");
    }
    // The whole mesh in view; the zoom frames the region where the teeth meet.
    let (x0, x1) = (-1.05 * r1, d + 1.05 * r2);
    let half = 1.05 * r1.max(r2);
    let mesh_x = d * r1 / (r1 + r2);
    let zoom = 3.0
        * (mesh
            .driver()
            .tooth_height()
            .max(mesh.driven().tooth_height()));
    format!(
        r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; }}
#mesh {{ border: 1px solid #ccc; width: 900px; height: 480px; }}
#plot {{ border: 1px solid #ccc; width: 900px; height: 200px; }}
li.lock a, li.strike a, li.blocked a {{ color: #b00; }}
li.gap a, li.slip a {{ color: #06c; }}
</style></head>
<body>
<h1>{title}</h1>
<p><input id="slider" type="range" min="0" max="{n}" value="0" step="1" style="width: 900px">
<br><button id="play">play</button> <button id="zoom">zoom on the mesh</button>
phi - phi0 = <span id="phi">0</span> deg, theta = <span id="theta"></span> deg,
TD = <span id="td"></span> deg</p>
<svg id="mesh" viewBox="{vx:.5} {vy:.5} {vw:.5} {vh:.5}" data-full="{vx:.5} {vy:.5} {vw:.5} {vh:.5}" data-zoom="{zx:.5} {zy:.5} {zw:.5} {zw:.5}">
<g transform="scale(1,-1)">
<g id="driver" transform="rotate(0 0 0)"><polygon points="{driver}" fill="#dde" stroke="#226" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<g id="driven" transform="rotate(0 {d:.9} 0)" data-theta-deg=""><polygon points="{driven}" fill="#ede" stroke="#626" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<circle cx="0" cy="0" r="{dot:.5}" fill="#226"/><circle cx="{d:.9}" cy="0" r="{dot:.5}" fill="#626"/>
<g id="contact" visibility="hidden"><circle id="contact-point" cx="0" cy="0" r="{cdot:.5}" fill="#c00"/><line id="contact-normal" x1="0" y1="0" x2="0" y2="0" stroke="#c00" stroke-width="2" vector-effect="non-scaling-stroke"/></g>
</g></svg>
<svg id="plot" viewBox="0 0 900 200"><polyline id="td-line" fill="none" stroke="#333" stroke-width="1" points=""/>
<line id="cursor" x1="0" y1="0" x2="0" y2="200" stroke="#c00"/></svg>
<h2>Events</h2>
<ol id="events">
{events}</ol>
<p id="status">loading</p>
<p id="selftest-slider"></p><p id="selftest-event"></p>
<script>
"use strict";
// Any error after this point is written on the page (a test reads it back).
window.addEventListener("error", e => {{ document.getElementById("status").textContent = "error: " + e.message; }});
const S = {json};
const slider = document.getElementById("slider");
const driver = document.getElementById("driver");
const driven = document.getElementById("driven");
const cursor = document.getElementById("cursor");
const meshSvg = document.getElementById("mesh");
const tdMin = Math.min(...S.map(s => s[2])), tdMax = Math.max(...S.map(s => s[2]));
const phiMax = S[S.length - 1][0] || 1;
const px = p => 900 * p / phiMax;
const py = t => tdMax > tdMin ? 190 - 180 * (t - tdMin) / (tdMax - tdMin) : 100;
document.getElementById("td-line").setAttribute("points", S.map(s => px(s[0]).toFixed(2) + "," + py(s[2]).toFixed(2)).join(" "));
function show(i) {{
  const s = S[i];
  // Driver about its arbor (the origin) by phi; driven about (D, 0) by -theta.
  driver.setAttribute("transform", "rotate(" + (s[0] + {phi0_deg:.12}) + " 0 0)");
  driven.setAttribute("transform", "rotate(" + (-s[1]) + " {d:.9} 0)");
  driven.setAttribute("data-theta-deg", String(s[1]));
  driven.setAttribute("data-phi-deg", String(s[0]));
  document.getElementById("phi").textContent = s[0].toFixed(4);
  document.getElementById("theta").textContent = s[1].toFixed(4);
  document.getElementById("td").textContent = s[2].toFixed(5);
  cursor.setAttribute("x1", px(s[0])); cursor.setAttribute("x2", px(s[0]));
}}
function nearest(phi) {{
  let best = 0;
  for (let i = 1; i < S.length; i++) if (Math.abs(S[i][0] - phi) < Math.abs(S[best][0] - phi)) best = i;
  return best;
}}
const contact = document.getElementById("contact");
// Jump to an event: the slider to its angle, the view zoomed on its contact point (the teeth
// involved), the contact point and its normal drawn until the slider moves again.
function jumpTo(phi, a) {{
  slider.value = nearest(phi);
  show(Number(slider.value));
  if (!a) {{ meshSvg.setAttribute("viewBox", meshSvg.dataset.zoom); return; }}
  const x = parseFloat(a.dataset.x), y = parseFloat(a.dataset.y);
  const nx = parseFloat(a.dataset.nx), ny = parseFloat(a.dataset.ny);
  const z = parseFloat(meshSvg.dataset.zoom.split(" ")[2]);
  meshSvg.setAttribute("viewBox", (x - z / 2) + " " + (-y - z / 2) + " " + z + " " + z);
  document.getElementById("contact-point").setAttribute("cx", x);
  document.getElementById("contact-point").setAttribute("cy", y);
  const line = document.getElementById("contact-normal");
  line.setAttribute("x1", x); line.setAttribute("y1", y);
  line.setAttribute("x2", x + nx * z / 4); line.setAttribute("y2", y + ny * z / 4);
  contact.setAttribute("visibility", "visible");
}}
function fromHash() {{
  const m = /phi=(-?[0-9.eE+-]+)/.exec(location.hash);
  if (m) jumpTo(parseFloat(m[1])); else show(Number(slider.value));
}}
for (const a of document.querySelectorAll("#events a")) {{
  a.addEventListener("click", () => jumpTo(parseFloat(a.dataset.phi), a));
}}
// `#selftest`: drive the page as a reader would - move the slider, click the first event - and
// write down what it then draws, for a headless browser to read back.
function record(id) {{
  const p = document.getElementById(id);
  p.dataset.phi = driven.dataset.phiDeg;
  p.dataset.theta = driven.dataset.thetaDeg;
  p.dataset.transform = driven.getAttribute("transform");
}}
function selftest() {{
  slider.value = Math.floor(S.length / 3);
  slider.dispatchEvent(new Event("input"));
  record("selftest-slider");
  const link = document.querySelector("#events a");
  if (link) {{ link.click(); record("selftest-event"); }}
}}
slider.addEventListener("input", () => {{ contact.setAttribute("visibility", "hidden"); show(Number(slider.value)); }});
window.addEventListener("hashchange", fromHash);
let timer = null;
document.getElementById("play").addEventListener("click", () => {{
  if (timer) {{ clearInterval(timer); timer = null; return; }}
  timer = setInterval(() => {{
    const i = (Number(slider.value) + 1) % S.length;
    slider.value = i; show(i);
  }}, 30);
}});
document.getElementById("zoom").addEventListener("click", () => {{
  const full = meshSvg.dataset.full;
  meshSvg.setAttribute("viewBox", meshSvg.getAttribute("viewBox") === full ? meshSvg.dataset.zoom : full);
}});
fromHash();
if (location.hash.includes("selftest")) selftest();
if (document.getElementById("status").textContent === "loading") document.getElementById("status").textContent = "ok";
</script>
</body></html>
"##,
        title = escape(title),
        vx = x0,
        vy = -half,
        vw = x1 - x0,
        vh = 2.0 * half,
        zx = mesh_x - zoom,
        zy = -zoom,
        zw = 2.0 * zoom,
        driver = points(&driver),
        driven = points(&driven),
        dot = 0.01 * r1.min(r2),
        cdot = 0.025 * zoom,
        phi0_deg = phi0.to_degrees(),
    )
}

/// Where event `e` happens: the contact point of its two teeth and the unit normal there (world
/// frame), or, where the contact has no normal (a vertex on a vertex), the point half-way between
/// the two tips and the line of centres' direction.
fn contact_of(traj: &Trajectory, e: &contact::Event) -> (Vec2, Vec2) {
    let mesh = traj.mesh();
    if let Some(c) = mesh.contact_normal(e.phi, e.theta, e.driver_tooth, e.driven_tooth) {
        return c;
    }
    let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    let tip1 = driver[2 * e.driver_tooth.rem_euclid(n1) as usize];
    let tip2 = driven[2 * e.driven_tooth.rem_euclid(n2) as usize];
    ((tip1 + tip2) * 0.5, Vec2::new(1.0, 0.0))
}

/// A picture of the mesh at event `e`, zoomed on the two teeth involved (driver tooth
/// `e.driver_tooth`, driven tooth `e.driven_tooth`), like the paper's Figures V_A (a jam) and
/// V_B (a decoupling): both outlines at (φ, θ) of the event, the contact point and its normal
/// where the contact has one. `counted` is what the event rule counts it as, `shown` the tooth
/// numbers its caption gives (the user's numbering; the outlines are indexed by the solver's).
pub fn event_svg(
    traj: &Trajectory,
    e: &contact::Event,
    counted: &str,
    shown: (i64, i64),
) -> String {
    let mesh = traj.mesh();
    let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    let (j, k) = (e.driver_tooth.rem_euclid(n1), e.driven_tooth.rem_euclid(n2));
    // Outlines alternate tip, valley: tooth j's tip is vertex 2j.
    let tip1 = driver[2 * j as usize];
    let tip2 = driven[2 * k as usize];
    let contact = mesh.contact_normal(e.phi, e.theta, e.driver_tooth, e.driven_tooth);
    let centre = contact.map_or((tip1 + tip2) * 0.5, |(p, _)| p);
    let h = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    let half = 2.5 * h;
    let (x0, y0) = (centre.x - half, -centre.y - half);
    let sw = half / 200.0;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"600\" height=\"640\" viewBox=\"{x0:.6} {y0:.6} {w:.6} {hh:.6}\" font-family=\"sans-serif\">\n<rect x=\"{x0:.6}\" y=\"{y0:.6}\" width=\"{w:.6}\" height=\"{hh:.6}\" fill=\"white\"/>\n<g transform=\"scale(1,-1)\">\n<polygon points=\"{}\" fill=\"#dde\" stroke=\"#226\" stroke-width=\"{sw:.6}\"/>\n<polygon points=\"{}\" fill=\"#ede\" stroke=\"#626\" stroke-width=\"{sw:.6}\"/>\n",
        points(&driver),
        points(&driven),
        w = 2.0 * half,
        hh = 2.0 * half * 640.0 / 600.0,
    );
    let dot = half / 60.0;
    for (p, colour) in [(tip1, "#226"), (tip2, "#626")] {
        let _ = writeln!(
            svg,
            "<circle cx=\"{:.6}\" cy=\"{:.6}\" r=\"{dot:.6}\" fill=\"{colour}\"/>",
            p.x, p.y
        );
    }
    if let Some((p, n)) = contact {
        let end = p + n * (0.6 * h);
        let _ = writeln!(
            svg,
            "<circle cx=\"{:.6}\" cy=\"{:.6}\" r=\"{:.6}\" fill=\"#c00\"/>\n<line x1=\"{:.6}\" y1=\"{:.6}\" x2=\"{:.6}\" y2=\"{:.6}\" stroke=\"#c00\" stroke-width=\"{:.6}\"/>",
            p.x,
            p.y,
            1.5 * dot,
            p.x,
            p.y,
            end.x,
            end.y,
            2.0 * sw
        );
    }
    svg.push_str("</g>\n");
    let label = format!(
        "{} ({counted}) at phi - phi0 = {:.4} deg: driver tooth {} (dot, blue), driven tooth {} (dot, purple){}",
        e.label(),
        (e.phi - traj.phi_start()).to_degrees(),
        shown.0,
        shown.1,
        if contact.is_some() {
            "; red: contact point and normal"
        } else {
            ""
        }
    );
    let _ = writeln!(
        svg,
        "<text x=\"{:.6}\" y=\"{:.6}\" font-size=\"{:.6}\">{}</text>\n</svg>",
        x0 + 0.02 * half,
        y0 + 2.0 * half * 640.0 / 600.0 - 0.03 * half,
        half / 34.0,
        escape(&label)
    );
    svg
}

/// The event pictures of a run, for its first `most` events: `(file name, SVG)`, named
/// `event-<n>-<kind>.svg` in event order.
pub fn event_pictures(
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    teeth: Teeth<'_>,
    most: usize,
) -> Vec<(String, String)> {
    traj.events()
        .iter()
        .take(most)
        .enumerate()
        .map(|(i, e)| {
            (
                format!("event-{}-{}.svg", i + 1, e.kind.name()),
                event_svg(traj, e, counted(e), teeth(e)),
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use contact::{Mesh, Start};
    use geometry::Gear;

    #[test]
    fn the_page_turns_the_gears_as_the_mesh_places_them() {
        let mesh = Mesh::new(
            Gear::ideal(20, 20.0, 18.9).unwrap(),
            Gear::ideal(30, 30.0, 28.9).unwrap(),
            20.0 + 30.0 - 1.1 + 0.44,
        )
        .unwrap();
        // The page rotates the θ = 0 outline by −θ about (D, 0): what world_outlines draws.
        let (_, at0) = mesh.world_outlines(0.0, 0.0);
        let theta: f64 = 0.3;
        let (_, at) = mesh.world_outlines(0.0, theta);
        let c = Vec2::new(mesh.centre_distance(), 0.0);
        for (a, b) in at0.iter().zip(&at) {
            let r = a - c;
            let turned = c + Vec2::new(
                r.x * theta.cos() + r.y * theta.sin(),
                -r.x * theta.sin() + r.y * theta.cos(),
            );
            assert!((turned - b).norm() < 1e-9);
        }
        let traj = mesh.run(0.1, 1.0, Start::Touching(0.0));
        let html = page("a <test>", &traj, &|_| "-", &solver_teeth(&mesh));
        assert!(html.contains("<title>a &lt;test&gt;</title>"));
        assert!(html.contains("id=\"driven\"") && html.contains("id=\"status\""));
        // Nothing is fetched: no address of any kind in the page.
        assert!(!html.contains("http"), "the page must work offline");
    }

    #[test]
    fn an_event_picture_shows_both_teeth_and_the_contact() {
        // Gears so far apart that the tips slip past each other: the run loses drive.
        let mesh = Mesh::new(
            Gear::ideal(20, 20.0, 18.9).unwrap(),
            Gear::ideal(30, 30.0, 28.9).unwrap(),
            20.0 + 30.0 - 1.1 + 1.09,
        )
        .unwrap();
        let traj = mesh.run(0.0, std::f64::consts::TAU * 1.5, Start::Touching(0.0));
        let pictures = event_pictures(&traj, &|_| "jam", &solver_teeth(&mesh), 5);
        assert!(!pictures.is_empty(), "the close mesh must have an event");
        let (name, svg) = &pictures[0];
        let e = &traj.events()[0];
        assert_eq!(name, &format!("event-1-{}.svg", e.kind.name()));
        assert_eq!(svg.matches("<polygon").count(), 2);
        assert!(svg.contains(&format!("{} (jam)", e.kind.name())), "{svg}");
        if mesh
            .contact_normal(e.phi, e.theta, e.driver_tooth, e.driven_tooth)
            .is_some()
        {
            assert!(svg.contains("contact point and normal"));
        }
    }
}
