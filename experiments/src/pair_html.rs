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
pub const ANGLES_NOTE: &str = "phi - phi0 and theta - theta0: angles from the start of the run (pair.csv's phi_minus_phi0_deg and theta_minus_theta0_deg, pair.html's slider); phi and theta: absolute angles, as replay prints them (pair.csv's phi_abs_deg and theta_abs_deg)";

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

pub(crate) fn points(outline: &[Vec2]) -> String {
    let mut s = String::new();
    for v in outline {
        let _ = write!(s, "{:.5},{:.5} ", v.x, v.y);
    }
    s.trim_end().to_owned()
}

pub(crate) fn escape(s: &str) -> String {
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

/// One contact drawn at an event: where the two teeth touch, the unit normal there (None where
/// the contact has none: a vertex on a vertex), and what it is.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// The contact point, world frame.
    pub point: Vec2,
    /// The unit common normal, where defined.
    pub normal: Option<Vec2>,
    /// `closing` (the contact of the event's two teeth: the one that closed at a lock or strike,
    /// the one lost at a gap or slip), `pushing` (the driver tooth pushing the driven gear when
    /// a lock closed) or `resumed` (the pair that drives it after a release).
    pub role: &'static str,
}

/// Whether driver tooth `j` pushes driven tooth `k` at (φ, θ): the upper end of their obstacle
/// is θ (to rounding).
fn pushes_at(mesh: &contact::Mesh, phi: f64, theta: f64, (j, k): (i64, i64)) -> bool {
    mesh.obstacle(phi, j, k)
        .is_some_and(|o| (o.hi - theta).abs() <= 1e-9 * (1.0 + theta.abs()))
}

/// The contact of driver tooth `j` and driven tooth `k` at (φ, θ), labelled `role`; where the
/// contact has no normal (tip on tip), the point half-way between the two tips, if they touch.
/// `None` where the two teeth do not touch at all: nothing to draw.
fn contact_at(
    mesh: &contact::Mesh,
    (phi, theta): (f64, f64),
    (j, k): (i64, i64),
    role: &'static str,
) -> Option<Contact> {
    if let Some((point, normal)) = mesh.contact_normal(phi, theta, j, k) {
        return Some(Contact {
            point,
            normal: Some(normal),
            role,
        });
    }
    let (driver, driven) = mesh.world_outlines(phi, theta);
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    let tip1 = driver[2 * j.rem_euclid(n1) as usize];
    let tip2 = driven[2 * k.rem_euclid(n2) as usize];
    // Tips that touch, to rounding of the tooth's size.
    let size = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    ((tip1 - tip2).norm() <= 1e-6 * size).then(|| Contact {
        point: (tip1 + tip2) * 0.5,
        normal: None,
        role,
    })
}

/// Is `e` an idle start (a slip from the start: no driver tooth moved the driven gear within a
/// driver pitch of it, or at all)? It has no contact: its teeth are the pair that would push
/// next, if any, which does not touch the gear.
pub fn is_idle_start(e: &contact::Event) -> bool {
    e.idle_start && e.kind == contact::EventKind::Slip
}

/// The contacts of event `e` at its own (φ, θ): the event's pair, and at a lock (or a strike
/// while pushed) the pair that was pushing, so that both sides of the driven tooth show. None
/// for an idle start, where no tooth touches the driven gear.
pub fn contacts_at_event(traj: &Trajectory, e: &contact::Event) -> Vec<Contact> {
    if is_idle_start(e) {
        return Vec::new();
    }
    let mesh = traj.mesh();
    let pair = (e.driver_tooth, e.driven_tooth);
    let mut out: Vec<Contact> = contact_at(mesh, (e.phi, e.theta), pair, "closing")
        .into_iter()
        .collect();
    if e.kind.is_contact_stop() {
        // The pushing pair: of the pairs pushing on the segment that ends at the event, the one
        // whose contact holds θ there.
        let pusher = traj
            .segments()
            .iter()
            .rev()
            .filter(|s| s.phi_start < e.phi && s.phi_end >= e.phi - 1e-12)
            .find_map(|s| match &s.motion {
                contact::Motion::Push(pairs) => pairs
                    .iter()
                    .copied()
                    .find(|&p| p != pair && pushes_at(mesh, e.phi, e.theta, p)),
                _ => None,
            });
        if let Some(p) = pusher {
            out.extend(contact_at(mesh, (e.phi, e.theta), p, "pushing"));
        }
    }
    out
}

/// Where a lock or strike lets the driven gear go, `(θ after, the contact that drives it
/// there)`, when it moves it at all.
pub fn release_of(traj: &Trajectory, e: &contact::Event) -> Option<(f64, Vec<Contact>)> {
    if !e.kind.is_contact_stop() || e.theta_after == e.theta {
        return None;
    }
    let mesh = traj.mesh();
    let contacts = e
        .resumed_by
        .filter(|&p| pushes_at(mesh, e.phi, e.theta_after, p))
        .and_then(|p| contact_at(mesh, (e.phi, e.theta_after), p, "resumed"))
        .into_iter()
        .collect();
    Some((e.theta_after, contacts))
}

/// Why a lock's release moves the driven gear on, in a sentence for the outputs that show a
/// release.
pub const RELEASE_NOTE: &str = "A lock's release: the driven gear, held from both sides, is let go to the next position ahead at which no driver tooth overlaps it, as the paper's program did (\"allowing the driven gear to rotate freely ... until movement was possible again\"); that is usually a fraction of a driven pitch, but where eccentricity brings the gears too close for the teeth to pass (Case D, large systematic errors) the next free position can be a pitch or many pitches ahead, so the Theoretical Difference jumps by as much. The jump changes no jam count (a trial that locked has jammed).";

/// A lock's release jump in words: `jump X deg (n driven pitches)` for a driven gear of `n2`
/// teeth.
pub fn jump_text(e: &contact::Event, n2: usize) -> String {
    let jump = (e.theta_after - e.theta).to_degrees();
    format!(
        "jump {jump:.3} deg ({:.2} driven pitches)",
        jump / (360.0 / n2 as f64)
    )
}

/// `x,y,nx,ny,role` per contact, `;` between them (no normal: `x,y,,,role`).
fn contacts_attr(contacts: &[Contact]) -> String {
    contacts
        .iter()
        .map(|c| {
            let (nx, ny) = c.normal.map_or((String::new(), String::new()), |n| {
                (format!("{:.9}", n.x), format!("{:.9}", n.y))
            });
            format!("{:.9},{:.9},{nx},{ny},{}", c.point.x, c.point.y, c.role)
        })
        .collect::<Vec<_>>()
        .join(";")
}

/// The page for `traj` (one mesh's run), titled `title`; `counted(e)` says what the event rule
/// counts an event as (`jam`, `disengagement` or `-`), `teeth(e)` the tooth numbers it shows.
///
/// An event's link draws the gears at the event's own φ and θ (not at the nearest sample), with
/// its contacts - both of a lock - and a lock or strike that released the driven gear has a
/// second link, its release, drawn at the same φ and θ after.
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
    let theta0 = traj.theta_at(phi0);
    let ratio = mesh.driver().teeth() as f64 / mesh.driven().teeth() as f64;
    let mut json = String::from("[");
    for (i, (p, t, td)) in data.iter().enumerate() {
        let _ = write!(
            json,
            "{}[{p:.9},{t:.9},{td:.9}]",
            if i == 0 { "" } else { "," }
        );
    }
    json.push(']');
    let td_of = |phi: f64, theta: f64| ((theta - theta0) - ratio * (phi - phi0)).to_degrees();
    let mut events = String::new();
    let n2 = mesh.driven().teeth();
    let mut released = false;
    for (i, e) in traj.events().iter().enumerate() {
        let at = (e.phi - phi0).to_degrees();
        let (j, k) = teeth(e);
        let release = release_of(traj, e);
        let link = |class: &str, theta: f64, contacts: &[Contact], text: &str, place: &str| {
            format!(
                "<a class=\"{class}\" href=\"#event={}{}\" data-phi=\"{at:.12}\" data-theta=\"{:.12}\" data-td=\"{:.12}\" data-contacts=\"{}\" data-where=\"{}\">{text}</a>",
                i + 1,
                if class == "release" { "-release" } else { "" },
                theta.to_degrees(),
                td_of(e.phi, theta),
                contacts_attr(contacts),
                escape(place),
            )
        };
        let what = if is_idle_start(e) {
            if e.resumed {
                "no driver tooth touches the driven gear: none moves it within a driver pitch of the start".to_string()
            } else {
                "no driver tooth touches the driven gear: none moves it in the whole run"
                    .to_string()
            }
        } else {
            format!("driver tooth {j}, driven tooth {k}")
        };
        let main = link(
            "event",
            e.theta,
            &contacts_at_event(traj, e),
            &format!(
                "phi - phi0 = {at:.4} deg (phi = {:.4} deg, theta = {:.4} deg): {} ({}), {what}",
                e.phi.to_degrees(),
                e.theta.to_degrees(),
                e.label(),
                counted(e),
            ),
            if release.is_some() {
                "(the event, before its release)"
            } else {
                "(the event)"
            },
        );
        let release = release.map_or_else(String::new, |(after, contacts)| {
            released = true;
            format!(
                " - {}",
                link(
                    "release",
                    after,
                    &contacts,
                    &format!(
                        "its release: the driven gear let go to the next free position, theta = {:.4} deg, {}",
                        after.to_degrees(),
                        jump_text(e, n2)
                    ),
                    "(its release: the driven gear let go to the next free position; the Theoretical Difference includes every earlier release's jump)",
                )
            )
        });
        let _ = writeln!(
            events,
            "<li class=\"{kind}\">{main}{release}</li>",
            kind = e.kind.name(),
        );
    }
    let release_note = if released {
        format!("<p class=\"release-note\">{}</p>", escape(RELEASE_NOTE))
    } else {
        String::new()
    };
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
    // The TD strip: its axes in Rust, the curve and cursor drawn by the script on the same scale.
    let phi_max = data.last().map_or(1.0, |s| s.0).max(f64::MIN_POSITIVE);
    let (td_min, td_max) = data
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
            (a.min(s.2), b.max(s.2))
        });
    let (td_min, td_max) = if td_max > td_min {
        (td_min, td_max)
    } else {
        (td_min - 1.0, td_min + 1.0)
    };
    let axes = td_axes(phi_max, td_min, td_max);
    format!(
        r##"<!DOCTYPE html>
<html lang="en"><head><meta charset="utf-8"><title>{title}</title>
<style>
body {{ font-family: sans-serif; margin: 1em; }}
#mesh {{ border: 1px solid #ccc; width: 900px; height: 480px; }}
#plot {{ border: 1px solid #ccc; width: 900px; height: 230px; font-size: 12px; }}
li.lock a, li.strike a, li.blocked a {{ color: #b00; }}
li.gap a, li.slip a {{ color: #06c; }}
li a.release {{ color: #555; }}
#status {{ display: none; }}
#status.error {{ display: block; color: #b00; }}
</style></head>
<body>
<h1>{title}</h1>
<p><input id="slider" type="range" min="0" max="{n}" value="0" step="1" style="width: 900px">
<br><button id="play">play</button> <button id="zoom">zoom on the mesh</button>
phi - phi0 = <span id="phi">0</span> deg, theta = <span id="theta"></span> deg (absolute),
TD = <span id="td"></span> deg <span id="where"></span></p>
<svg id="mesh" viewBox="{vx:.5} {vy:.5} {vw:.5} {vh:.5}" data-full="{vx:.5} {vy:.5} {vw:.5} {vh:.5}" data-zoom="{zx:.5} {zy:.5} {zw:.5} {zw:.5}">
<g transform="scale(1,-1)">
<g id="driver" transform="rotate(0 0 0)"><polygon points="{driver}" fill="#dde" stroke="#226" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<g id="driven" transform="rotate(0 {d:.9} 0)" data-theta-deg=""><polygon points="{driven}" fill="#ede" stroke="#626" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<circle cx="0" cy="0" r="{dot:.5}" fill="#226"/><circle cx="{d:.9}" cy="0" r="{dot:.5}" fill="#626"/>
<g id="contacts"></g>
</g></svg>
<svg id="plot" viewBox="0 0 900 230">
{axes}<polyline id="td-line" fill="none" stroke="#333" stroke-width="1" points=""/>
<line id="cursor" x1="{px0}" y1="{py_top}" x2="{px0}" y2="{py_bottom}" stroke="#c00"/></svg>
<h2>Events</h2>
<p>Each link draws the gears at the event's own driver and driven angles, with its contacts (red: the teeth of the event; orange: the tooth pushing the driven gear when a lock closed; grey: the contact that drives it after its release).</p>
<ol id="events">
{events}</ol>
{release_note}
<p id="status">loading</p>
<p id="selftest-slider"></p><p id="selftest-event"></p><ol id="selftest-events"></ol>
<script>
"use strict";
// Any error after this point is written on the page (a test reads it back).
window.addEventListener("error", e => {{ const s = document.getElementById("status"); s.textContent = "error: " + e.message; s.className = "error"; }});
const S = {json};
const PHI0 = {phi0_deg:.12};
const slider = document.getElementById("slider");
const driver = document.getElementById("driver");
const driven = document.getElementById("driven");
const cursor = document.getElementById("cursor");
const meshSvg = document.getElementById("mesh");
const zoomButton = document.getElementById("zoom");
const playButton = document.getElementById("play");
const contactsG = document.getElementById("contacts");
const SVGNS = meshSvg.namespaceURI;
const px = p => {px0} + {pw} * p / {phi_max:.12};
const py = t => {py_bottom} - {ph} * (t - ({td_min:.12})) / ({td_span:.12});
document.getElementById("td-line").setAttribute("points", S.map(s => px(s[0]).toFixed(2) + "," + py(s[2]).toFixed(2)).join(" "));
// Draw the gears at phi - phi0 = phi (deg) and the absolute driven angle theta (deg).
function draw(phi, theta, td, where) {{
  // Driver about its arbor (the origin) by phi; driven about (D, 0) by -theta.
  driver.setAttribute("transform", "rotate(" + (phi + PHI0) + " 0 0)");
  driven.setAttribute("transform", "rotate(" + (-theta) + " {d:.9} 0)");
  driven.setAttribute("data-theta-deg", String(theta));
  driven.setAttribute("data-phi-deg", String(phi));
  document.getElementById("phi").textContent = phi.toFixed(4);
  document.getElementById("theta").textContent = theta.toFixed(4);
  document.getElementById("td").textContent = td.toFixed(5);
  document.getElementById("where").textContent = where;
  cursor.setAttribute("x1", px(phi)); cursor.setAttribute("x2", px(phi));
}}
function show(i) {{
  const s = S[i];
  contactsG.replaceChildren();
  draw(s[0], s[1], s[2], "");
}}
function nearest(phi) {{
  let best = 0;
  for (let i = 1; i < S.length; i++) if (Math.abs(S[i][0] - phi) < Math.abs(S[best][0] - phi)) best = i;
  return best;
}}
function setView(box) {{
  meshSvg.setAttribute("viewBox", box);
  zoomButton.textContent = box === meshSvg.dataset.full ? "zoom on the mesh" : "show the whole mesh";
}}
const COLOURS = {{ closing: "#c00", pushing: "#e80", resumed: "#666" }};
// Jump to an event (or its release): the gears at its exact angles, the view zoomed on its
// first contact, every contact's point and normal drawn until the slider moves again.
function jumpTo(a) {{
  const phi = parseFloat(a.dataset.phi), theta = parseFloat(a.dataset.theta);
  slider.value = nearest(phi);
  const contacts = a.dataset.contacts ? a.dataset.contacts.split(";").map(c => c.split(",")) : [];
  draw(phi, theta, parseFloat(a.dataset.td), a.dataset.where || "");
  contactsG.replaceChildren();
  const z = parseFloat(meshSvg.dataset.zoom.split(" ")[2]);
  for (const [xs, ys, nxs, nys, role] of contacts) {{
    const x = parseFloat(xs), y = parseFloat(ys), colour = COLOURS[role] || "#c00";
    const dot = document.createElementNS(SVGNS, "circle");
    dot.setAttribute("cx", x); dot.setAttribute("cy", y); dot.setAttribute("r", {cdot:.5});
    dot.setAttribute("fill", "none"); dot.setAttribute("stroke", colour); dot.setAttribute("stroke-width", "2");
    dot.setAttribute("vector-effect", "non-scaling-stroke"); dot.setAttribute("class", "contact " + role);
    contactsG.appendChild(dot);
    if (nxs !== "") {{
      const line = document.createElementNS(SVGNS, "line");
      line.setAttribute("x1", x); line.setAttribute("y1", y);
      line.setAttribute("x2", x + parseFloat(nxs) * z / 4); line.setAttribute("y2", y + parseFloat(nys) * z / 4);
      line.setAttribute("stroke", colour); line.setAttribute("stroke-width", "2");
      line.setAttribute("vector-effect", "non-scaling-stroke");
      contactsG.appendChild(line);
    }}
  }}
  if (contacts.length) {{
    const x = parseFloat(contacts[0][0]), y = parseFloat(contacts[0][1]);
    setView((x - z / 2) + " " + (-y - z / 2) + " " + z + " " + z);
  }} else {{
    setView(meshSvg.dataset.zoom);
  }}
}}
function fromHash() {{
  const e = /event=([0-9]+)(-release)?/.exec(location.hash);
  if (e) {{
    const li = document.querySelectorAll("#events > li")[Number(e[1]) - 1];
    const a = li && li.querySelector(e[2] ? "a.release" : "a.event");
    if (a) {{ jumpTo(a); return; }}
  }}
  const m = /phi=(-?[0-9.eE+-]+)/.exec(location.hash);
  if (m) {{ slider.value = nearest(parseFloat(m[1])); setView(meshSvg.dataset.zoom); }}
  show(Number(slider.value));
}}
for (const a of document.querySelectorAll("#events a")) {{
  a.addEventListener("click", ev => {{ ev.preventDefault(); jumpTo(a); }});
}}
// `#selftest`: drive the page as a reader would - move the slider, click every event link - and
// write down what it then draws, for a headless browser to read back.
function record(p) {{
  p.dataset.phi = driven.dataset.phiDeg;
  p.dataset.theta = driven.dataset.thetaDeg;
  p.dataset.transform = driven.getAttribute("transform");
  p.dataset.contacts = String(contactsG.querySelectorAll("circle").length);
}}
function selftest() {{
  slider.value = Math.floor(S.length / 3);
  slider.dispatchEvent(new Event("input"));
  record(document.getElementById("selftest-slider"));
  const links = document.querySelectorAll("#events a");
  const list = document.getElementById("selftest-events");
  links.forEach((link, i) => {{
    link.click();
    if (i === 0) record(document.getElementById("selftest-event"));
    const li = document.createElement("li");
    li.dataset.link = link.getAttribute("href");
    li.dataset.expected = link.dataset.theta;
    li.dataset.wanted = String(link.dataset.contacts ? link.dataset.contacts.split(";").length : 0);
    record(li);
    list.appendChild(li);
  }});
}}
slider.addEventListener("input", () => show(Number(slider.value)));
window.addEventListener("hashchange", fromHash);
let timer = null;
playButton.addEventListener("click", () => {{
  if (timer) {{ clearInterval(timer); timer = null; playButton.textContent = "play"; return; }}
  playButton.textContent = "pause";
  timer = setInterval(() => {{
    const i = (Number(slider.value) + 1) % S.length;
    slider.value = i; show(i);
  }}, 30);
}});
zoomButton.addEventListener("click", () => {{
  const full = meshSvg.dataset.full;
  setView(meshSvg.getAttribute("viewBox") === full ? meshSvg.dataset.zoom : full);
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
        px0 = PLOT.0,
        pw = PLOT.1,
        py_top = PLOT.2,
        py_bottom = PLOT.3,
        ph = PLOT.3 - PLOT.2,
        td_span = td_max - td_min,
    )
}

/// The TD strip's plot area in its 900 × 230 box: left edge, width, top, bottom.
const PLOT: (f64, f64, f64, f64) = (80.0, 800.0, 12.0, 180.0);

/// The TD strip's axes: φ − φ0 along the bottom and TD up the left, each with round ticks
/// labelled in degrees ([`crate::chart::nice_ticks`]), and each axis named with its unit.
fn td_axes(phi_max: f64, td_min: f64, td_max: f64) -> String {
    use crate::chart::{nice_ticks, tick_label};
    let (left, width, top, bottom) = PLOT;
    let mut s = format!(
        "<line x1=\"{left}\" y1=\"{bottom}\" x2=\"{}\" y2=\"{bottom}\" stroke=\"#000\"/>\n<line x1=\"{left}\" y1=\"{top}\" x2=\"{left}\" y2=\"{bottom}\" stroke=\"#000\"/>\n",
        left + width
    );
    let (xs, x_decimals) = nice_ticks(0.0, phi_max, 6);
    for v in xs {
        let x = left + width * v / phi_max;
        let _ = writeln!(
            s,
            "<line class=\"tick\" x1=\"{x:.2}\" y1=\"{bottom}\" x2=\"{x:.2}\" y2=\"{}\" stroke=\"#000\"/><text class=\"tick\" x=\"{x:.2}\" y=\"{}\" text-anchor=\"middle\">{}</text>",
            bottom + 5.0,
            bottom + 18.0,
            tick_label(v, x_decimals)
        );
    }
    let (ys, y_decimals) = nice_ticks(td_min, td_max, 4);
    for v in ys {
        let y = bottom - (bottom - top) * (v - td_min) / (td_max - td_min);
        let _ = writeln!(
            s,
            "<line class=\"tick\" x1=\"{}\" y1=\"{y:.2}\" x2=\"{left}\" y2=\"{y:.2}\" stroke=\"#000\"/><text class=\"tick\" x=\"{}\" y=\"{:.2}\" text-anchor=\"end\">{}</text>",
            left - 5.0,
            left - 8.0,
            y + 4.0,
            tick_label(v, y_decimals)
        );
    }
    let _ = writeln!(
        s,
        "<text x=\"{}\" y=\"{}\" text-anchor=\"middle\">driver angle from the start, phi - phi0 [deg]</text>\n<text x=\"14\" y=\"{}\" text-anchor=\"middle\" transform=\"rotate(-90 14 {})\">TD [deg]</text>",
        left + 0.5 * width,
        bottom + 40.0,
        0.5 * (top + bottom),
        0.5 * (top + bottom)
    );
    s
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use contact::{Solve, Start};

    #[test]
    fn the_page_turns_the_gears_as_the_mesh_places_them() {
        let mesh = crate::test_pair::ideal_20_30(0.44);
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
        let traj = mesh.solve(0.1..=1.0, Start::Touching(0.0), Solve::path());
        let html = page("a <test>", &traj, &|_| "-", &solver_teeth(&mesh));
        assert!(html.contains("<title>a &lt;test&gt;</title>"));
        assert!(html.contains("id=\"driven\"") && html.contains("id=\"status\""));
        // Nothing is fetched: no address of any kind in the page.
        assert!(!html.contains("http"), "the page must work offline");
    }
}
