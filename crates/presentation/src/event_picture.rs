//! The picture of a mesh at one event (`event-<n>-<kind>.svg`, the paper's Figures V_A and
//! V_B): both outlines at the event's own angles, zoomed on where it happens, its contacts as
//! rings with their normals, and a caption naming the run, the event and what is drawn.

use std::fmt::Write as _;

use contact::Trajectory;
use geometry::Vec2;

use crate::common::wrap_at_spaces;
use crate::escape_xml as escape;
use crate::pair_html::{
    DRIVEN_COLOUR, DRIVEN_FILL, DRIVER_COLOUR, DRIVER_FILL, Teeth, contacts_at_event, first_lock,
    is_idle_start, moves_pointer, nearest_approach, points, release_text, size_text,
};

/// The most event pictures a run writes (`event-1-...svg` to `event-500-...svg`); `pair.html`
/// draws any event, and the outputs say where the pictures stop.
pub const MAX_EVENT_PICTURES: usize = 500;

/// The teeth an event picture draws and where it is centred: the event's two teeth (at an
/// idle start, the nearest two: no pair touches), its contacts, and the gap where the gears come
/// nearest when it has no contact to draw.
struct Scene {
    contacts: Vec<crate::pair_html::Contact>,
    gap: Option<(Vec2, Vec2)>,
    /// The teeth drawn, the solver's numbers within one turn.
    teeth: (i64, i64),
    /// Their tips, world frame.
    tips: (Vec2, Vec2),
    centre: Vec2,
}

impl Scene {
    fn of(traj: &Trajectory, e: &contact::Event) -> Scene {
        let mesh = traj.mesh();
        let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
        let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
        let contacts = contacts_at_event(traj, e);
        // An event whose teeth have no contact to draw keeps its own teeth, with the gap shown.
        let (gap, (j, k)) = if is_idle_start(e) {
            let (p1, p2, j, k) = nearest_approach(mesh, e.phi, e.theta);
            (Some((p1, p2)), (j, k))
        } else if contacts.is_empty() {
            let (p1, p2, _, _) = nearest_approach(mesh, e.phi, e.theta);
            (Some((p1, p2)), (e.driver_tooth, e.driven_tooth))
        } else {
            (None, (e.driver_tooth, e.driven_tooth))
        };
        let (j, k) = (j.rem_euclid(n1), k.rem_euclid(n2));
        // Outlines alternate tip, valley: tooth j's tip is vertex 2j.
        let tips = (driver[2 * j as usize], driven[2 * k as usize]);
        let centre = match (contacts.first(), gap) {
            (Some(c), _) => c.point,
            (None, Some((p1, p2))) => (p1 + p2) * 0.5,
            (None, None) => (tips.0 + tips.1) * 0.5,
        };
        Scene {
            contacts,
            gap,
            teeth: (j, k),
            tips,
            centre,
        }
    }
}

/// A picture of the mesh at event `e` of run `traj`, titled `title` (the run and the event:
/// a trial, a figure of the paper), like the paper's Figures V_A (a jam) and V_B (a
/// decoupling): both outlines at (φ, θ) of the event, zoomed on its contacts (at a lock both:
/// the closing one and the pushing one) drawn as rings with their normals, the two teeth's tips
/// as dots drawn over them (the driver's blue, the driven gear's green), a scale bar in
/// millimetres, and a caption in a band of its own beneath the teeth. An idle start has no
/// contact: the picture shows where the two gears come nearest instead, dashed, with the gap.
/// `counted` is what the event rule counts it as, `teeth` the tooth numbers the caption gives
/// (the user's numbering; the outlines are indexed by the solver's).
pub fn event_svg(
    title: &str,
    traj: &Trajectory,
    e: &contact::Event,
    counted: &str,
    teeth: Teeth<'_>,
) -> String {
    let mesh = traj.mesh();
    let scene = Scene::of(traj, e);
    let shown = {
        let mut at = *e;
        (at.driver_tooth, at.driven_tooth) = scene.teeth;
        teeth(&at)
    };
    let h = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    let half = 2.5 * h;
    let lines = caption(title, traj, e, counted, shown, (&scene.contacts, scene.gap));
    // The picture is 600 × 600 of the mesh, and beneath it a band for the caption.
    let (width, picture) = (600.0, 600.0);
    let band = 18.0 + 19.0 * lines.len() as f64;
    let scale = 2.0 * half / width;
    let (x0, y0) = (scene.centre.x - half, -scene.centre.y - half);
    let sw = half / 200.0;
    let total = (picture + band) * scale;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{}\" viewBox=\"{x0:.6} {y0:.6} {w:.6} {total:.6}\" font-family=\"sans-serif\">\n<title>{}</title>\n<rect x=\"{x0:.6}\" y=\"{y0:.6}\" width=\"{w:.6}\" height=\"{total:.6}\" fill=\"white\"/>\n",
        picture + band,
        escape(title),
        w = 2.0 * half,
    );
    svg.push_str(&teeth_svg(mesh, e, &scene, (half, sw)));
    let band_top = y0 + picture * scale;
    svg.push_str(&scale_bar_svg((x0, band_top), half, scale));
    svg.push_str(&caption_svg(
        &lines,
        (x0, band_top),
        (half, band, scale, sw),
    ));
    svg.push_str("</svg>\n");
    svg
}

/// The outlines at the event, its contacts as rings with their normals (drawn first, so that
/// the tips' dots stay visible on them), the nearest approach dashed where there is no contact,
/// and the two teeth's tips as dots; in the world frame, flipped to the page's.
fn teeth_svg(
    mesh: &contact::Mesh,
    e: &contact::Event,
    scene: &Scene,
    (half, sw): (f64, f64),
) -> String {
    let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
    let h = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    let mut svg = format!(
        "<g transform=\"scale(1,-1)\">\n<polygon points=\"{}\" fill=\"{DRIVER_FILL}\" stroke=\"{DRIVER_COLOUR}\" stroke-width=\"{sw:.6}\"/>\n<polygon points=\"{}\" fill=\"{DRIVEN_FILL}\" stroke=\"{DRIVEN_COLOUR}\" stroke-width=\"{sw:.6}\"/>\n",
        points(&driver),
        points(&driven),
    );
    let dot = half / 60.0;
    for c in &scene.contacts {
        let colour = if c.role == "pushing" { "#e80" } else { "#c00" };
        let _ = writeln!(
            svg,
            "<circle class=\"contact {}\" cx=\"{:.6}\" cy=\"{:.6}\" r=\"{:.6}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"{:.6}\"/>",
            c.role,
            c.point.x,
            c.point.y,
            2.2 * dot,
            1.5 * sw
        );
        if let Some(n) = c.normal {
            let end = c.point + n * (0.6 * h);
            let _ = writeln!(
                svg,
                "<line x1=\"{:.6}\" y1=\"{:.6}\" x2=\"{:.6}\" y2=\"{:.6}\" stroke=\"{colour}\" stroke-width=\"{:.6}\"/>",
                c.point.x,
                c.point.y,
                end.x,
                end.y,
                2.0 * sw
            );
        }
    }
    if let Some((p1, p2)) = scene.gap {
        let _ = writeln!(
            svg,
            "<line class=\"nearest\" x1=\"{:.6}\" y1=\"{:.6}\" x2=\"{:.6}\" y2=\"{:.6}\" stroke=\"#000\" stroke-width=\"{:.6}\" stroke-dasharray=\"{:.6} {:.6}\"/>",
            p1.x,
            p1.y,
            p2.x,
            p2.y,
            1.5 * sw,
            4.0 * sw,
            3.0 * sw
        );
    }
    for (p, colour, who) in [
        (scene.tips.0, DRIVER_COLOUR, "driver-tip"),
        (scene.tips.1, DRIVEN_COLOUR, "driven-tip"),
    ] {
        let _ = writeln!(
            svg,
            "<circle class=\"{who}\" cx=\"{:.6}\" cy=\"{:.6}\" r=\"{dot:.6}\" fill=\"{colour}\" stroke=\"white\" stroke-width=\"{:.6}\"/>",
            p.x,
            p.y,
            0.6 * sw
        );
    }
    svg.push_str("</g>\n");
    svg
}

/// The length of an event picture's scale bar, mm: of 1, 2 and 5 times a power of ten, the
/// largest at most a fifth of the picture's width `span` (mm).
pub fn scale_bar_mm(span: f64) -> f64 {
    let most = span / 5.0;
    let decade = 10f64.powf(most.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&l| l <= most)
        .unwrap_or(decade)
}

/// The scale bar at the picture's lower left, just above the caption's band (whose top-left is
/// `(x0, band_top)`, page frame), on a white ground: a bar [`scale_bar_mm`] long with end ticks
/// and its length in millimetres (the gearing's lengths are millimetres).
fn scale_bar_svg((x0, band_top): (f64, f64), half: f64, scale: f64) -> String {
    let mm = scale_bar_mm(2.0 * half);
    let (left, y) = (x0 + 16.0 * scale, band_top - 16.0 * scale);
    let tick = 5.0 * scale;
    let size = 13.0 * scale;
    let label = format!("{} mm", registry::fmt_f64(mm, if mm < 1.0 { 2 } else { 0 }));
    format!(
        "<g class=\"scale-bar\" data-mm=\"{mm}\">\n<rect x=\"{:.6}\" y=\"{:.6}\" width=\"{:.6}\" height=\"{:.6}\" fill=\"white\" fill-opacity=\"0.85\"/>\n<path d=\"M{left:.6} {:.6}V{y:.6}H{:.6}V{:.6}\" fill=\"none\" stroke=\"black\" stroke-width=\"{:.6}\"/>\n<line class=\"bar\" x1=\"{left:.6}\" y1=\"{y:.6}\" x2=\"{:.6}\" y2=\"{y:.6}\" stroke=\"black\" stroke-width=\"{:.6}\"/>\n<text x=\"{:.6}\" y=\"{:.6}\" font-size=\"{size:.6}\" text-anchor=\"middle\">{label}</text>\n</g>\n",
        left - 6.0 * scale,
        y - tick - size - 6.0 * scale,
        mm + 12.0 * scale,
        tick + size + 12.0 * scale,
        y - tick,
        left + mm,
        y - tick,
        1.5 * scale,
        left + mm,
        2.5 * scale,
        left + 0.5 * mm,
        y - tick - 4.0 * scale,
    )
}

/// The caption's band beneath the picture (top-left `(x0, band_top)`, `band` px tall at
/// `scale` mm a pixel), over anything of the gears that reaches below the picture, and its
/// lines, the first in bold.
fn caption_svg(
    lines: &[String],
    (x0, band_top): (f64, f64),
    (half, band, scale, sw): (f64, f64, f64, f64),
) -> String {
    let mut svg = format!(
        "<rect x=\"{x0:.6}\" y=\"{band_top:.6}\" width=\"{:.6}\" height=\"{:.6}\" fill=\"white\"/>\n<line x1=\"{x0:.6}\" y1=\"{band_top:.6}\" x2=\"{:.6}\" y2=\"{band_top:.6}\" stroke=\"#999\" stroke-width=\"{sw:.6}\"/>\n",
        2.0 * half,
        band * scale,
        x0 + 2.0 * half
    );
    let size = 14.0 * scale;
    for (i, line) in lines.iter().enumerate() {
        let weight = if i == 0 { " font-weight=\"bold\"" } else { "" };
        let _ = writeln!(
            svg,
            "<text x=\"{:.6}\" y=\"{:.6}\" font-size=\"{size:.6}\"{weight}>{}</text>",
            x0 + 8.0 * scale,
            band_top + (20.0 + 19.0 * i as f64) * scale,
            escape(line)
        );
    }
    svg
}

/// The caption of [`event_svg`], in lines that fit the picture's width: the title, the event
/// and its angles, the teeth drawn and what the rings (or, at an idle start, the dashed gap)
/// are, and a lock's release.
fn caption(
    title: &str,
    traj: &Trajectory,
    e: &contact::Event,
    counted: &str,
    shown: (i64, i64),
    (contacts, gap): (&[crate::pair_html::Contact], Option<(Vec2, Vec2)>),
) -> Vec<String> {
    let mut said = vec![
        title.to_owned(),
        format!(
            "{} ({counted}) at phi - phi0 = {:.4} deg (phi = {:.4} deg), theta = {:.4} deg (absolute, before any release)",
            e.label(),
            (e.phi - traj.phi_start()).to_degrees(),
            e.phi.to_degrees(),
            e.theta.to_degrees()
        ),
    ];
    match gap {
        Some((p1, p2)) if is_idle_start(e) => {
            said.push(format!(
                "No contact: no driver tooth touches the driven gear, and none moves it {}.",
                if e.resumed {
                    "within a driver pitch of the start"
                } else {
                    "in the whole run"
                }
            ));
            said.push(format!(
                "Dashed: where the gears come nearest, {:.4} mm apart, driver tooth {} (dot, blue) and driven tooth {} (dot, green).",
                (p1 - p2).norm(),
                shown.0,
                shown.1
            ));
        }
        Some((p1, p2)) => {
            said.push(format!(
                "Driver tooth {} (dot, blue), driven tooth {} (dot, green): no contact of these teeth to draw at this instant.",
                shown.0, shown.1
            ));
            said.push(format!(
                "Dashed: where the gears come nearest, {:.4} mm apart.",
                (p1 - p2).norm()
            ));
        }
        None => {
            said.push(format!(
            "Driver tooth {} (dot, blue), driven tooth {} (dot, green); red ring: the contact of these teeth{}.",
            shown.0,
            shown.1,
            if contacts.first().is_some_and(|c| c.normal.is_some()) {
                ", with its normal"
            } else {
                " (tip on tip: no normal)"
            }
        ));
        }
    }
    if contacts.iter().any(|c| c.role == "pushing") {
        said.push("Orange ring: the driver tooth pushing the driven gear, with its normal.".into());
    }
    said.extend(motion_lines(traj, e));
    said.iter().flat_map(|l| wrap_at_spaces(l, 80)).collect()
}

/// The caption's lines on what the event did to the driven gear's motion: a release, in driven
/// pitches, or a change of tooth phase; and, after the trial's first lock, that the motion is
/// the paper's protocol.
fn motion_lines(traj: &Trajectory, e: &contact::Event) -> Vec<String> {
    let mut said = Vec::new();
    let n2 = traj.mesh().driven().teeth();
    if e.kind.is_contact_stop() && moves_pointer(e) {
        said.push(format!(
            "Released: the driven gear is let go to the next position ahead where no driver tooth overlaps it (\"allowing the driven gear to rotate freely ... until movement was possible again\"), {}.",
            release_text(e, n2)
        ));
    } else if e.phase_shift != 0 {
        said.push(format!(
            "Drive resumed with the tooth phase shifted: {}.",
            size_text(e, n2)
        ));
    }
    if let Some(f) = first_lock(traj.events()).map(|f| &traj.events()[f])
        && e.phi > f.phi
    {
        said.push(format!(
            "After the trial's first lock (phi - phi0 = {:.4} deg): the paper's protocol, the gear let go and driven on, not a physical motion.",
            (f.phi - traj.phi_start()).to_degrees()
        ));
    }
    said
}

/// The event pictures of run `traj`, one per event up to [`MAX_EVENT_PICTURES`]: `(file name,
/// SVG)`, named `event-<n>-<kind>.svg` in event order, each titled `name` and its event
/// (`<name>: event n of N`).
pub fn event_pictures(
    name: &str,
    traj: &Trajectory,
    counted: &dyn Fn(&contact::Event) -> &'static str,
    teeth: Teeth<'_>,
) -> Vec<(String, String)> {
    let all = traj.events().len();
    traj.events()
        .iter()
        .take(MAX_EVENT_PICTURES)
        .enumerate()
        .map(|(i, e)| {
            (
                format!("event-{}-{}.svg", i + 1, e.kind.name()),
                event_svg(
                    &format!("{name}: event {} of {all}", i + 1),
                    traj,
                    e,
                    counted(e),
                    teeth,
                ),
            )
        })
        .collect()
}

/// The note of a run with more events than pictures, or `None`.
pub fn pictures_note(events: usize) -> Option<String> {
    (events > MAX_EVENT_PICTURES).then(|| {
        format!(
            "{events} events: pictures event-1 to event-{MAX_EVENT_PICTURES} (one per event, in order) are written; pair.html draws any event."
        )
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::pair_html::solver_teeth;
    use contact::{Solve, Start};

    /// The caption's text, its wrapped lines joined by spaces.
    fn caption_text(svg: &str) -> String {
        svg.split("<text ")
            .skip(1)
            .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
            .map(|(text, _)| text)
            .collect::<Vec<_>>()
            .join(" ")
    }

    #[test]
    fn an_event_picture_shows_both_teeth_and_the_contact() {
        // Gears so far apart that the tips slip past each other: the run loses drive.
        let mesh = crate::test_pair::ideal_20_30(1.09);
        let traj = mesh.solve(
            0.0..=std::f64::consts::TAU * 1.5,
            Start::Touching(0.0),
            Solve::path(),
        );
        let pictures = event_pictures("a run", &traj, &|_| "jam", &solver_teeth(&mesh));
        assert_eq!(pictures.len(), traj.events().len(), "one picture per event");
        let (name, svg) = &pictures[0];
        let e = &traj.events()[0];
        assert_eq!(name, &format!("event-1-{}.svg", e.kind.name()));
        assert_eq!(svg.matches("<polygon").count(), 2);
        assert!(
            svg.contains(&format!("a run: event 1 of {}", traj.events().len())),
            "{svg}"
        );
        let text = caption_text(svg);
        assert!(text.contains(&format!("{} (jam)", e.label())), "{svg}");
        if !is_idle_start(e) {
            assert!(
                text.contains("red ring: the contact of these teeth"),
                "{svg}"
            );
            // The tips' dots come after the contact rings: nothing hides them.
            let last_ring = svg.rfind("class=\"contact").unwrap();
            assert!(svg.find("class=\"driven-tip\"").unwrap() > last_ring);
        }
    }

    /// An idle start has no contact: no ring is drawn, the caption says so, and the dashed line
    /// joins the two gears where they come nearest, between the two teeth the caption names
    /// (their tips are the dots, each on its own gear's outline near the gap).
    #[test]
    fn an_idle_start_is_drawn_as_the_gap_it_is() {
        // Gears too far apart for any tip to reach the other gear: never driven.
        let mesh = crate::test_pair::ideal_20_30(1.3);
        let traj = mesh.solve(
            0.0..=std::f64::consts::TAU,
            Start::Touching(0.0),
            Solve::path(),
        );
        let e = traj.events().iter().find(|e| is_idle_start(e)).unwrap();
        assert!(contacts_at_event(&traj, e).is_empty());
        let svg = event_svg("idle", &traj, e, "disengagement", &solver_teeth(&mesh));
        assert!(!svg.contains("class=\"contact"), "{svg}");
        let text = caption_text(&svg);
        assert!(
            text.contains("No contact: no driver tooth touches the driven gear"),
            "{svg}"
        );
        let (p1, p2, j, k) = nearest_approach(&mesh, e.phi, e.theta);
        // The tip circles are 0.2 mm apart; the outlines no nearer, and within a tooth of it.
        let gap = (p1 - p2).norm();
        assert!((0.2 - 1e-9..1.1).contains(&gap), "{gap}");
        assert!(text.contains(&format!("{gap:.4} mm apart")), "{svg}");
        assert!(text.contains(&format!(
            "driver tooth {j} (dot, blue) and driven tooth {k}"
        )));
        let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
        assert!((driver[2 * j as usize] - p1).norm() < 1.0);
        assert!((driven[2 * k as usize] - p2).norm() < 1.0);
    }
}
