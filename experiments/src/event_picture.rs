//! The picture of a mesh at one event (`event-<n>-<kind>.svg`, the paper's Figures V_A and
//! V_B): both outlines at the event's own angles, zoomed on where it happens, its contacts as
//! rings with their normals, and a caption naming the run, the event and what is drawn.

use std::fmt::Write as _;

use contact::Trajectory;
use geometry::Vec2;

use crate::common::wrap_at_spaces;
use crate::pair_html::{Teeth, contacts_at_event, escape, is_idle_start, jump_text, points};

/// The most event pictures a run writes (`event-1-...svg` to `event-500-...svg`); `pair.html`
/// draws any event, and the outputs say where the pictures stop.
pub const MAX_EVENT_PICTURES: usize = 500;

/// Where the two gears' outlines come nearest at (φ, θ): the points on the driver and on the
/// driven gear, and the teeth whose tips are nearest them (the solver's numbers).
pub fn nearest_approach(mesh: &contact::Mesh, phi: f64, theta: f64) -> (Vec2, Vec2, i64, i64) {
    let (driver, driven) = mesh.world_outlines(phi, theta);
    let on_segment = |p: Vec2, a: Vec2, b: Vec2| {
        let ab = b - a;
        let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
        a + ab * t
    };
    let mut best = (f64::INFINITY, Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0));
    let mut consider = |from: &[Vec2], to: &[Vec2], swap: bool| {
        for &p in from {
            for (i, &a) in to.iter().enumerate() {
                let q = on_segment(p, a, to[(i + 1) % to.len()]);
                let d = (p - q).norm();
                if d < best.0 {
                    best = if swap { (d, q, p) } else { (d, p, q) };
                }
            }
        }
    };
    consider(&driver, &driven, false);
    consider(&driven, &driver, true);
    let nearest_tip = |outline: &[Vec2], p: Vec2| {
        (0..outline.len() / 2)
            .min_by(|&a, &b| {
                (outline[2 * a] - p)
                    .norm()
                    .total_cmp(&(outline[2 * b] - p).norm())
            })
            .unwrap_or(0) as i64
    };
    let (_, p1, p2) = best;
    (p1, p2, nearest_tip(&driver, p1), nearest_tip(&driven, p2))
}

/// A picture of the mesh at event `e` of run `traj`, titled `title` (the run and the event:
/// a trial, a figure of the paper), like the paper's Figures V_A (a jam) and V_B (a
/// decoupling): both outlines at (φ, θ) of the event, zoomed on its contacts (at a lock both:
/// the closing one and the pushing one) drawn as rings with their normals, the two teeth's tips
/// as dots drawn over them, and a caption in a band of its own beneath the teeth. An idle start
/// has no contact: the picture shows where the two gears come nearest instead, dashed, with the
/// gap. `counted` is what the event rule counts it as, `teeth` the tooth numbers the caption
/// gives (the user's numbering; the outlines are indexed by the solver's).
pub fn event_svg(
    title: &str,
    traj: &Trajectory,
    e: &contact::Event,
    counted: &str,
    teeth: Teeth<'_>,
) -> String {
    let mesh = traj.mesh();
    let (driver, driven) = mesh.world_outlines(e.phi, e.theta);
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    let contacts = contacts_at_event(traj, e);
    let idle = is_idle_start(e);
    // The teeth drawn: the event's; at an idle start, the nearest two (no pair touches).
    // An event whose teeth have no contact to draw keeps its own teeth, with the gap shown.
    let (gap, (j, k)) = if idle {
        let (p1, p2, j, k) = nearest_approach(mesh, e.phi, e.theta);
        (Some((p1, p2)), (j, k))
    } else if contacts.is_empty() {
        let (p1, p2, _, _) = nearest_approach(mesh, e.phi, e.theta);
        (Some((p1, p2)), (e.driver_tooth, e.driven_tooth))
    } else {
        (None, (e.driver_tooth, e.driven_tooth))
    };
    let (j, k) = (j.rem_euclid(n1), k.rem_euclid(n2));
    let shown = {
        let mut at = *e;
        at.driver_tooth = j;
        at.driven_tooth = k;
        teeth(&at)
    };
    // Outlines alternate tip, valley: tooth j's tip is vertex 2j.
    let tip1 = driver[2 * j as usize];
    let tip2 = driven[2 * k as usize];
    let centre = match (contacts.first(), gap) {
        (Some(c), _) => c.point,
        (None, Some((p1, p2))) => (p1 + p2) * 0.5,
        (None, None) => (tip1 + tip2) * 0.5,
    };
    let h = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    let half = 2.5 * h;
    let lines = caption(title, traj, e, counted, shown, (&contacts, gap));
    // The picture is 600 × 600 of the mesh, and beneath it a band for the caption.
    let (width, picture) = (600.0, 600.0);
    let band = 18.0 + 19.0 * lines.len() as f64;
    let scale = 2.0 * half / width;
    let (x0, y0) = (centre.x - half, -centre.y - half);
    let sw = half / 200.0;
    let total = (picture + band) * scale;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{}\" viewBox=\"{x0:.6} {y0:.6} {w:.6} {total:.6}\" font-family=\"sans-serif\">\n<title>{}</title>\n<rect x=\"{x0:.6}\" y=\"{y0:.6}\" width=\"{w:.6}\" height=\"{total:.6}\" fill=\"white\"/>\n<g transform=\"scale(1,-1)\">\n<polygon points=\"{}\" fill=\"#dde\" stroke=\"#226\" stroke-width=\"{sw:.6}\"/>\n<polygon points=\"{}\" fill=\"#ede\" stroke=\"#626\" stroke-width=\"{sw:.6}\"/>\n",
        picture + band,
        escape(title),
        points(&driver),
        points(&driven),
        w = 2.0 * half,
    );
    let dot = half / 60.0;
    // Contacts first, as rings, so that the tips' dots drawn next stay visible on them.
    for c in &contacts {
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
    if let Some((p1, p2)) = gap {
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
    for (p, colour, who) in [(tip1, "#226", "driver-tip"), (tip2, "#626", "driven-tip")] {
        let _ = writeln!(
            svg,
            "<circle class=\"{who}\" cx=\"{:.6}\" cy=\"{:.6}\" r=\"{dot:.6}\" fill=\"{colour}\"/>",
            p.x, p.y
        );
    }
    svg.push_str("</g>\n");
    // The caption's band, over anything of the gears that reaches below the picture.
    let band_top = y0 + picture * scale;
    let _ = writeln!(
        svg,
        "<rect x=\"{x0:.6}\" y=\"{band_top:.6}\" width=\"{:.6}\" height=\"{:.6}\" fill=\"white\"/>\n<line x1=\"{x0:.6}\" y1=\"{band_top:.6}\" x2=\"{:.6}\" y2=\"{band_top:.6}\" stroke=\"#999\" stroke-width=\"{sw:.6}\"/>",
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
    svg.push_str("</svg>\n");
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
                "Dashed: where the gears come nearest, {:.4} mm apart, driver tooth {} (dot, blue) and driven tooth {} (dot, purple).",
                (p1 - p2).norm(),
                shown.0,
                shown.1
            ));
        }
        Some((p1, p2)) => {
            said.push(format!(
                "Driver tooth {} (dot, blue), driven tooth {} (dot, purple): no contact of these teeth to draw at this instant.",
                shown.0, shown.1
            ));
            said.push(format!(
                "Dashed: where the gears come nearest, {:.4} mm apart.",
                (p1 - p2).norm()
            ));
        }
        None => {
            said.push(format!(
            "Driver tooth {} (dot, blue), driven tooth {} (dot, purple); red ring: the contact of these teeth{}.",
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
    if e.kind.is_contact_stop() && e.theta_after != e.theta {
        said.push(format!(
            "Released: the driven gear is let go to the next position ahead where no driver tooth overlaps it, {} (\"allowing the driven gear to rotate freely ... until movement was possible again\").",
            jump_text(e, traj.mesh().driven().teeth())
        ));
    }
    said.iter().flat_map(|l| wrap_at_spaces(l, 80)).collect()
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
