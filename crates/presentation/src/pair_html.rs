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

use crate::escape_xml as escape;
pub use crate::pair_events::{
    Contact, MOTION_NOTE, PROTOCOL_NOTE, RELEASE_NOTE, Release, Teeth, ahead_pitches,
    contacts_at_event, first_lock, is_idle_start, motion_word, moves_pointer, nearest_approach,
    release_of, release_text, releases_note, size_text, solver_teeth,
};

/// The driver's colour in the pictures of a mesh (its outline, its tooth's dot), and its fill.
pub const DRIVER_COLOUR: &str = "#1f4e9c";
/// See [`DRIVER_COLOUR`].
pub const DRIVER_FILL: &str = "#d5e0f3";
/// The driven gear's colour in the pictures of a mesh: a green that no reader takes for the
/// driver's blue, and apart from the red and orange of the contacts.
pub const DRIVEN_COLOUR: &str = "#1b7837";
/// See [`DRIVEN_COLOUR`].
pub const DRIVEN_FILL: &str = "#d5ecd0";

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

/// Said beside the gears on the page wherever the slider or a link is past the first lock.
const PROTOCOL_WORDS: &str = "(after the first lock: the paper's protocol, the gear let go and driven on, not a physical motion)";

/// What an event's links need of the run: where it starts, and its Theoretical Difference at
/// any (φ, θ).
struct Linker<'a> {
    traj: &'a Trajectory,
    phi0: f64,
    theta0: f64,
    ratio: f64,
}

impl<'a> Linker<'a> {
    fn of(traj: &'a Trajectory) -> Self {
        let mesh = traj.mesh();
        let phi0 = traj.phi_start();
        Linker {
            traj,
            phi0,
            theta0: traj.theta_at(phi0),
            ratio: mesh.driver().teeth() as f64 / mesh.driven().teeth() as f64,
        }
    }

    /// A link of event `i` (`class` `event` or `release`) drawing the gears at (φ, θ) with
    /// `contacts` (or, an event with none, where the gears come nearest), saying `place` (and
    /// `protocol`, after the first lock) beside the gears.
    fn link(
        &self,
        (i, class): (usize, &str),
        (phi, theta): (f64, f64),
        contacts: &[Contact],
        (text, place, protocol): (&str, &str, &str),
    ) -> String {
        let gap = if class == "event" && contacts.is_empty() {
            let (p1, p2, _, _) = nearest_approach(self.traj.mesh(), phi, theta);
            format!(
                " data-gap=\"{:.9},{:.9},{:.9},{:.9}\"",
                p1.x, p1.y, p2.x, p2.y
            )
        } else {
            String::new()
        };
        let td = ((theta - self.theta0) - self.ratio * (phi - self.phi0)).to_degrees();
        let place = if protocol.is_empty() {
            place.to_owned()
        } else {
            format!("{place} {protocol}")
        };
        format!(
            "<a class=\"{class}\" href=\"#event={}{}\" data-phi=\"{:.12}\" data-theta=\"{:.12}\" data-td=\"{td:.12}\" data-contacts=\"{}\"{gap} data-where=\"{}\">{text}</a>",
            i + 1,
            if class == "release" { "-release" } else { "" },
            (phi - self.phi0).to_degrees(),
            theta.to_degrees(),
            contacts_attr(contacts),
            escape(&place),
        )
    }

    /// Event `i`'s release link, where it has a release.
    fn release(&self, i: usize, e: &contact::Event, protocol: &str) -> Option<String> {
        let r = release_of(self.traj, e)?;
        let at = if r.phi == e.phi {
            String::new()
        } else {
            format!(
                " at phi - phi0 = {:.4} deg",
                (r.phi - self.phi0).to_degrees()
            )
        };
        let text = format!(
            "its release{at}: the driven gear let go to the next free position, theta = {:.4} deg; {}",
            r.theta.to_degrees(),
            release_text(e, self.traj.mesh().driven().teeth())
        );
        let place = "(its release: the driven gear let go to the next free position; the Theoretical Difference includes every earlier release's jump)";
        Some(self.link(
            (i, "release"),
            (r.phi, r.theta),
            &r.contacts,
            (&text, place, protocol),
        ))
    }
}

/// The event list of the page: each event a link drawing the gears at its own φ and θ, with its
/// contacts, and a lock's or strike's release a second link drawing them where the gear was let
/// go; the events after the first lock greyed as the paper's protocol. With it, whether any
/// release was drawn.
fn event_list(
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    teeth: Teeth<'_>,
) -> (String, bool) {
    let linker = Linker::of(traj);
    let n2 = traj.mesh().driven().teeth();
    let protocol_from = first_lock(traj.events());
    let mut events = String::new();
    let mut released = false;
    for (i, e) in traj.events().iter().enumerate() {
        let after = protocol_from.is_some_and(|f| i > f);
        let protocol = if after { PROTOCOL_WORDS } else { "" };
        let release = linker.release(i, e, protocol);
        let place = if release.is_some() {
            "(the event, before its release)"
        } else {
            "(the event)"
        };
        let words = event_words(traj, e, counted(e), teeth);
        let main = linker.link(
            (i, "event"),
            (e.phi, e.theta),
            &contacts_at_event(traj, e),
            (&words, place, protocol),
        );
        released |= release.is_some();
        let release = release.map_or_else(String::new, |r| format!(" - {r}"));
        let shift = if e.kind.is_loss() && e.phase_shift != 0 {
            format!(" - {}", escape(&size_text(e, n2)))
        } else {
            String::new()
        };
        let class = if after {
            format!("{} protocol", e.kind.name())
        } else {
            e.kind.name().to_owned()
        };
        let _ = writeln!(events, "<li class=\"{class}\">{main}{release}{shift}</li>");
    }
    if events.is_empty() {
        events.push_str("<li>no event: the driven gear was driven throughout</li>\n");
    }
    (events, released)
}

/// An event's link text: where it is, what it is, what the rule counts it as, and its teeth.
fn event_words(traj: &Trajectory, e: &contact::Event, counted: &str, teeth: Teeth<'_>) -> String {
    let at = (e.phi - traj.phi_start()).to_degrees();
    let (j, k) = teeth(e);
    let what = if is_idle_start(e) {
        if e.resumed {
            "no driver tooth touches the driven gear: none moves it within a driver pitch of the start".to_string()
        } else {
            "no driver tooth touches the driven gear: none moves it in the whole run".to_string()
        }
    } else {
        format!("driver tooth {j}, driven tooth {k}")
    };
    format!(
        "phi - phi0 = {at:.4} deg (phi = {:.4} deg, theta = {:.4} deg): {} ({counted}), {what}",
        e.phi.to_degrees(),
        e.theta.to_degrees(),
        e.label(),
    )
}

/// The mesh's view boxes: the whole mesh in view, and the zoom framing where the teeth meet.
struct View {
    whole: [f64; 4],
    zoom: [f64; 4],
    /// Radius of the arbors' dots.
    dot: f64,
    /// Radius of a contact's ring.
    ring: f64,
}

impl View {
    fn of(mesh: &contact::Mesh) -> View {
        let d = mesh.centre_distance();
        let (r1, r2) = (
            mesh.driver().max_tip_radius(),
            mesh.driven().max_tip_radius(),
        );
        let (x0, x1) = (-1.05 * r1, d + 1.05 * r2);
        let half = 1.05 * r1.max(r2);
        let mesh_x = d * r1 / (r1 + r2);
        let zoom = 3.0
            * (mesh
                .driver()
                .tooth_height()
                .max(mesh.driven().tooth_height()));
        View {
            whole: [x0, -half, x1 - x0, 2.0 * half],
            zoom: [mesh_x - zoom, -zoom, 2.0 * zoom, 2.0 * zoom],
            dot: 0.01 * r1.min(r2),
            ring: 0.025 * zoom,
        }
    }
}

/// A view box as the `viewBox` attribute writes it.
fn view_box(b: [f64; 4]) -> String {
    format!("{:.5} {:.5} {:.5} {:.5}", b[0], b[1], b[2], b[3])
}

/// The Theoretical Difference strip of the page: its scale (the largest φ − φ0 and the TD's
/// range, degrees) and its axes, with the stretch after the first lock greyed.
struct Strip {
    phi_max: f64,
    td_min: f64,
    td_max: f64,
    /// φ − φ0 of the first lock, degrees, where the paper's protocol starts.
    protocol_from: Option<f64>,
    /// Each event on the curve: φ − φ0 and the Theoretical Difference there (before any
    /// release), degrees, and what it is (a contact's stop or a loss of drive).
    events: Vec<(f64, f64, &'static str, bool)>,
}

impl Strip {
    fn of(traj: &Trajectory, data: &[(f64, f64, f64)]) -> Strip {
        let phi_max = data.last().map_or(1.0, |s| s.0).max(f64::MIN_POSITIVE);
        let (lo, hi) = data
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
                (a.min(s.2), b.max(s.2))
            });
        let (td_min, td_max) = if hi > lo {
            (lo, hi)
        } else {
            (lo - 1.0, lo + 1.0)
        };
        let phi0 = traj.phi_start();
        let protocol_from =
            first_lock(traj.events()).map(|i| (traj.events()[i].phi - phi0).to_degrees());
        let mesh = traj.mesh();
        let ratio = mesh.driver().teeth() as f64 / mesh.driven().teeth() as f64;
        let theta0 = traj.theta_at(phi0);
        let events = traj
            .events()
            .iter()
            .map(|e| {
                let td = (e.theta - theta0) - ratio * (e.phi - phi0);
                (
                    (e.phi - phi0).to_degrees(),
                    td.to_degrees(),
                    e.label(),
                    e.kind.is_contact_stop(),
                )
            })
            .collect();
        Strip {
            phi_max,
            td_min,
            td_max,
            protocol_from,
            events,
        }
    }

    /// Each event as a marker on the curve, numbered in its tooltip: red for a contact's stop
    /// (lock, strike), blue for a loss of drive (gap, slip), as the event list colours them.
    fn event_marks(&self) -> String {
        let (left, width, top, bottom) = PLOT;
        let mut s = String::new();
        for (i, &(phi, td, label, stop)) in self.events.iter().enumerate() {
            let x = left + width * phi / self.phi_max;
            let y = bottom - (bottom - top) * (td - self.td_min) / (self.td_max - self.td_min);
            let colour = if stop { "#b00" } else { "#06c" };
            let _ = writeln!(
                s,
                "<circle class=\"event-mark\" cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"3\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"1\"><title>event {}: {label}</title></circle>",
                i + 1
            );
        }
        s
    }

    /// The strip's SVG: the stretch after the first lock greyed and named, then the axes.
    fn svg(&self) -> String {
        let (left, width, top, bottom) = PLOT;
        let shade = self.protocol_from.map_or_else(String::new, |from| {
            let x = left + width * from / self.phi_max;
            format!(
                "<rect class=\"protocol\" x=\"{x:.2}\" y=\"{top}\" width=\"{:.2}\" height=\"{}\" fill=\"#000\" fill-opacity=\"0.1\"/>\n<text class=\"protocol\" x=\"{:.2}\" y=\"{}\" text-anchor=\"{}\" fill=\"#555\">after the first lock: the paper's protocol</text>\n",
                left + width - x,
                bottom - top,
                if from < 0.5 * self.phi_max { x + 4.0 } else { x - 4.0 },
                top + 12.0,
                if from < 0.5 * self.phi_max { "start" } else { "end" },
            )
        });
        shade + &td_axes(self.phi_max, self.td_min, self.td_max)
    }

    /// The script's constants of the strip's scale.
    fn constants(&self) -> String {
        let (left, width, top, bottom) = PLOT;
        format!(
            "const PX0 = {left}, PW = {width}, PHI_MAX = {:.12}, PY_BOTTOM = {bottom}, PH = {}, TD_MIN = {:.12}, TD_SPAN = {:.12};\nconst PROTOCOL_FROM = {};\nconst PROTOCOL_WORDS = \"{PROTOCOL_WORDS}\";\n",
            self.phi_max,
            bottom - top,
            self.td_min,
            self.td_max - self.td_min,
            self.protocol_from
                .map_or_else(|| "null".to_owned(), |p| format!("{p:.12}")),
        )
    }
}

/// The page's samples as the script's `S`: `[φ − φ0, θ, TD]` per sample, degrees.
fn samples_json(data: &[(f64, f64, f64)]) -> String {
    let mut json = String::from("[");
    for (i, (p, t, td)) in data.iter().enumerate() {
        let _ = write!(
            json,
            "{}[{p:.9},{t:.9},{td:.9}]",
            if i == 0 { "" } else { "," }
        );
    }
    json.push(']');
    json
}

/// The page's style sheet.
const STYLE: &str = "body { font-family: sans-serif; margin: 1em; }
#mesh { border: 1px solid #ccc; width: 900px; height: 480px; }
#plot { border: 1px solid #ccc; width: 900px; height: 230px; font-size: 12px; }
li.lock a, li.strike a, li.blocked a { color: #b00; }
li.gap a, li.slip a { color: #06c; }
li a.release { color: #555; }
li.protocol, li.protocol a { color: #888; }
#status { display: none; }
#status.error { display: block; color: #b00; }
";

/// The page for `traj` (one mesh's run), titled `title`; `counted(e)` says what the event rule
/// counts an event as (`jam`, `disengagement` or `-`), `teeth(e)` the tooth numbers it shows.
///
/// An event's link draws the gears at the event's own φ and θ (not at the nearest sample), with
/// its contacts - both of a lock - and a lock or strike that released the driven gear has a
/// second link, its release, drawn where the gear was let go. The motion after the first lock
/// is greyed as the paper's protocol, in the event list and in the Theoretical Difference.
pub fn page(
    title: &str,
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    teeth: Teeth<'_>,
) -> String {
    let mesh = traj.mesh();
    let data = samples(traj, MAX_SAMPLES);
    let strip = Strip::of(traj, &data);
    let (events, released) = event_list(traj, counted, teeth);
    let mut notes = String::new();
    if released {
        let _ = writeln!(
            notes,
            "<p class=\"release-note\">{}</p>",
            escape(RELEASE_NOTE)
        );
    }
    if strip.protocol_from.is_some() {
        let _ = writeln!(
            notes,
            "<p class=\"protocol-note\">{}</p>",
            escape(PROTOCOL_NOTE)
        );
    }
    if let Some(n) = releases_note(traj.events(), mesh.driven().teeth()) {
        let _ = writeln!(notes, "<p class=\"releases\">{}</p>", escape(&n));
    }
    let constants = format!(
        "const S = {};\nconst PHI0 = {:.12};\nconst D = {:.9};\nconst CDOT = {:.5};\n{}",
        samples_json(&data),
        traj.phi_start().to_degrees(),
        mesh.centre_distance(),
        View::of(mesh).ring,
        strip.constants()
    );
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>{title}</title>\n<style>\n{STYLE}</style></head>\n<body>\n<h1>{title}</h1>\n{}<h2>Events</h2>\n<p>Each link draws the gears at the event's own driver and driven angles, with its contacts (red: the teeth of the event; orange: the tooth pushing the driven gear when a lock closed; grey: the contact that drives it after its release).{greyed}</p>\n<ol id=\"events\">\n{events}</ol>\n{notes}<p id=\"status\">loading</p>\n<p id=\"selftest-slider\"></p><p id=\"selftest-event\"></p><ol id=\"selftest-events\"></ol>\n<script>\n\"use strict\";\n// Any error after this point is written on the page (a test reads it back).\nwindow.addEventListener(\"error\", e => {{ const s = document.getElementById(\"status\"); s.textContent = \"error: \" + e.message; s.className = \"error\"; }});\n{constants}{SCRIPT}</script>\n</body></html>\n",
        controls_and_views(mesh, &strip),
        title = escape(title),
        greyed = if strip.protocol_from.is_some() {
            " Greyed: the events after the first lock, in the paper's protocol (below)."
        } else {
            ""
        },
    )
}

/// The page's controls, the mesh's view and the Theoretical Difference strip.
fn controls_and_views(mesh: &contact::Mesh, strip: &Strip) -> String {
    let (driver, driven) = mesh.world_outlines(0.0, 0.0);
    let d = mesh.centre_distance();
    let view = View::of(mesh);
    let (left, _, top, bottom) = PLOT;
    format!(
        r##"<p><input id="slider" type="range" min="0" max="{n}" value="0" step="1" style="width: 900px">
<br><button id="play">play</button> <button id="zoom">zoom on the mesh</button>
phi - phi0 = <span id="phi">0</span> deg, theta = <span id="theta"></span> deg (absolute),
TD = <span id="td"></span> deg <span id="where"></span></p>
<svg id="mesh" viewBox="{whole}" data-full="{whole}" data-zoom="{zoom}">
<g transform="scale(1,-1)">
<g id="driver" transform="rotate(0 0 0)"><polygon points="{driver}" fill="{DRIVER_FILL}" stroke="{DRIVER_COLOUR}" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<g id="driven" transform="rotate(0 {d:.9} 0)" data-theta-deg=""><polygon points="{driven}" fill="{DRIVEN_FILL}" stroke="{DRIVEN_COLOUR}" stroke-width="1.2" vector-effect="non-scaling-stroke"/></g>
<circle cx="0" cy="0" r="{dot:.5}" fill="{DRIVER_COLOUR}"/><circle cx="{d:.9}" cy="0" r="{dot:.5}" fill="{DRIVEN_COLOUR}"/>
<g id="contacts"></g>
</g>
<text class="arbor-label" x="{dot:.5}" y="{below:.5}" fill="{DRIVER_COLOUR}" stroke="white" stroke-width="{halo:.5}" paint-order="stroke" font-size="{font:.5}">driver arbor</text>
<text class="arbor-label" x="{right_of:.5}" y="{below:.5}" fill="{DRIVEN_COLOUR}" stroke="white" stroke-width="{halo:.5}" paint-order="stroke" font-size="{font:.5}">driven arbor</text>
</svg>
<svg id="plot" viewBox="0 0 900 230">
{axes}<polyline id="td-line" fill="none" stroke="#333" stroke-width="1" points=""/>
{marks}<line id="cursor" x1="{left}" y1="{top}" x2="{left}" y2="{bottom}" stroke="#c00"/></svg>
"##,
        n = MAX_SAMPLES,
        whole = view_box(view.whole),
        zoom = view_box(view.zoom),
        driver = points(&driver),
        driven = points(&driven),
        dot = view.dot,
        below = 4.0 * view.dot,
        right_of = d + view.dot,
        font = view.whole[3] / 32.0,
        halo = view.whole[3] / 160.0,
        axes = strip.svg(),
        marks = strip.event_marks(),
    )
}

/// The page's script, after the constants [`page`] writes (`S`, `PHI0`, `D`, `CDOT` and the
/// strip's scale): the slider, the play and zoom buttons, the event links, `#phi=`, `#event=`
/// and `#selftest`.
const SCRIPT: &str = r##"const slider = document.getElementById("slider");
const driver = document.getElementById("driver");
const driven = document.getElementById("driven");
const cursor = document.getElementById("cursor");
const meshSvg = document.getElementById("mesh");
const zoomButton = document.getElementById("zoom");
const playButton = document.getElementById("play");
const contactsG = document.getElementById("contacts");
const SVGNS = meshSvg.namespaceURI;
const px = p => PX0 + PW * p / PHI_MAX;
const py = t => PY_BOTTOM - PH * (t - TD_MIN) / TD_SPAN;
document.getElementById("td-line").setAttribute("points", S.map(s => px(s[0]).toFixed(2) + "," + py(s[2]).toFixed(2)).join(" "));
// Draw the gears at phi - phi0 = phi (deg) and the absolute driven angle theta (deg).
function draw(phi, theta, td, where) {
  // Driver about its arbor (the origin) by phi; driven about (D, 0) by -theta.
  driver.setAttribute("transform", "rotate(" + (phi + PHI0) + " 0 0)");
  driven.setAttribute("transform", "rotate(" + (-theta) + " " + D + " 0)");
  driven.setAttribute("data-theta-deg", String(theta));
  driven.setAttribute("data-phi-deg", String(phi));
  document.getElementById("phi").textContent = phi.toFixed(4);
  document.getElementById("theta").textContent = theta.toFixed(4);
  document.getElementById("td").textContent = td.toFixed(5);
  document.getElementById("where").textContent = where;
  cursor.setAttribute("x1", px(phi)); cursor.setAttribute("x2", px(phi));
}
function show(i) {
  const s = S[i];
  contactsG.replaceChildren();
  draw(s[0], s[1], s[2], PROTOCOL_FROM !== null && s[0] > PROTOCOL_FROM ? PROTOCOL_WORDS : "");
}
function nearest(phi) {
  let best = 0;
  for (let i = 1; i < S.length; i++) if (Math.abs(S[i][0] - phi) < Math.abs(S[best][0] - phi)) best = i;
  return best;
}
function setView(box) {
  meshSvg.setAttribute("viewBox", box);
  zoomButton.textContent = box === meshSvg.dataset.full ? "zoom on the mesh" : "show the whole mesh";
  // The arbors' labels keep their size on the screen whatever the view.
  const h = parseFloat(box.split(" ")[3]);
  for (const t of meshSvg.querySelectorAll(".arbor-label")) {
    t.setAttribute("font-size", h / 32);
    t.setAttribute("stroke-width", h / 160);
  }
}
const COLOURS = { closing: "#c00", pushing: "#e80", resumed: "#666" };
// Jump to an event (or its release): the gears at its exact angles, the view zoomed on its
// first contact, every contact's point and normal drawn until the slider moves again.
function jumpTo(a) {
  const phi = parseFloat(a.dataset.phi), theta = parseFloat(a.dataset.theta);
  slider.value = nearest(phi);
  const contacts = a.dataset.contacts ? a.dataset.contacts.split(";").map(c => c.split(",")) : [];
  draw(phi, theta, parseFloat(a.dataset.td), a.dataset.where || "");
  contactsG.replaceChildren();
  const z = parseFloat(meshSvg.dataset.zoom.split(" ")[2]);
  for (const [xs, ys, nxs, nys, role] of contacts) {
    const x = parseFloat(xs), y = parseFloat(ys), colour = COLOURS[role] || "#c00";
    const dot = document.createElementNS(SVGNS, "circle");
    dot.setAttribute("cx", x); dot.setAttribute("cy", y); dot.setAttribute("r", CDOT);
    dot.setAttribute("fill", "none"); dot.setAttribute("stroke", colour); dot.setAttribute("stroke-width", "2");
    dot.setAttribute("vector-effect", "non-scaling-stroke"); dot.setAttribute("class", "contact " + role);
    contactsG.appendChild(dot);
    if (nxs !== "") {
      const line = document.createElementNS(SVGNS, "line");
      line.setAttribute("x1", x); line.setAttribute("y1", y);
      line.setAttribute("x2", x + parseFloat(nxs) * z / 4); line.setAttribute("y2", y + parseFloat(nys) * z / 4);
      line.setAttribute("stroke", colour); line.setAttribute("stroke-width", "2");
      line.setAttribute("vector-effect", "non-scaling-stroke");
      contactsG.appendChild(line);
    }
  }
  // An event with no contact (an idle start): where the two gears come nearest, dashed.
  const gap = a.dataset.gap ? a.dataset.gap.split(",").map(parseFloat) : null;
  if (gap) {
    const line = document.createElementNS(SVGNS, "line");
    line.setAttribute("x1", gap[0]); line.setAttribute("y1", gap[1]);
    line.setAttribute("x2", gap[2]); line.setAttribute("y2", gap[3]);
    line.setAttribute("stroke", "#000"); line.setAttribute("stroke-width", "2");
    line.setAttribute("stroke-dasharray", "6 4"); line.setAttribute("class", "nearest");
    line.setAttribute("vector-effect", "non-scaling-stroke");
    contactsG.appendChild(line);
  }
  if (contacts.length) {
    const x = parseFloat(contacts[0][0]), y = parseFloat(contacts[0][1]);
    setView((x - z / 2) + " " + (-y - z / 2) + " " + z + " " + z);
  } else if (gap) {
    const x = (gap[0] + gap[2]) / 2, y = (gap[1] + gap[3]) / 2;
    setView((x - z / 2) + " " + (-y - z / 2) + " " + z + " " + z);
  } else {
    setView(meshSvg.dataset.zoom);
  }
}
function fromHash() {
  const e = /event=([0-9]+)(-release)?/.exec(location.hash);
  if (e) {
    const li = document.querySelectorAll("#events > li")[Number(e[1]) - 1];
    const a = li && li.querySelector(e[2] ? "a.release" : "a.event");
    if (a) { jumpTo(a); return; }
  }
  const m = /phi=(-?[0-9.eE+-]+)/.exec(location.hash);
  if (m) { slider.value = nearest(parseFloat(m[1])); setView(meshSvg.dataset.zoom); }
  show(Number(slider.value));
}
for (const a of document.querySelectorAll("#events a")) {
  a.addEventListener("click", ev => { ev.preventDefault(); jumpTo(a); });
}
// `#selftest`: drive the page as a reader would - move the slider, click every event link - and
// write down what it then draws, for a headless browser to read back.
function record(p) {
  p.dataset.phi = driven.dataset.phiDeg;
  p.dataset.theta = driven.dataset.thetaDeg;
  p.dataset.transform = driven.getAttribute("transform");
  p.dataset.contacts = String(contactsG.querySelectorAll("circle").length);
}
function selftest() {
  slider.value = Math.floor(S.length / 3);
  slider.dispatchEvent(new Event("input"));
  record(document.getElementById("selftest-slider"));
  const links = document.querySelectorAll("#events a");
  const list = document.getElementById("selftest-events");
  links.forEach((link, i) => {
    link.click();
    if (i === 0) record(document.getElementById("selftest-event"));
    const li = document.createElement("li");
    li.dataset.link = link.getAttribute("href");
    li.dataset.expected = link.dataset.theta;
    li.dataset.wanted = String(link.dataset.contacts ? link.dataset.contacts.split(";").length : 0);
    record(li);
    list.appendChild(li);
  });
}
slider.addEventListener("input", () => show(Number(slider.value)));
window.addEventListener("hashchange", fromHash);
let timer = null;
playButton.addEventListener("click", () => {
  if (timer) { clearInterval(timer); timer = null; playButton.textContent = "play"; return; }
  playButton.textContent = "pause";
  timer = setInterval(() => {
    const i = (Number(slider.value) + 1) % S.length;
    slider.value = i; show(i);
  }, 30);
});
zoomButton.addEventListener("click", () => {
  const full = meshSvg.dataset.full;
  setView(meshSvg.getAttribute("viewBox") === full ? meshSvg.dataset.zoom : full);
});
fromHash();
if (location.hash.includes("selftest")) selftest();
if (document.getElementById("status").textContent === "loading") document.getElementById("status").textContent = "ok";
"##;

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
    let (xs, x_decimals) = nice_ticks(0.0, phi_max, 10);
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
    let (ys, y_decimals) = nice_ticks(td_min, td_max, 6);
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
