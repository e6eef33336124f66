//! `pair-check.svg`, the picture `pair` draws of a user's pair as its file describes it: both
//! gears at φ = 0 and θ = 0 with the axes, arbors and tip-circle centres, each zero ray, the
//! first teeth of each gear, the turning senses, insets that show an eccentricity at a visible
//! size, and in words the conventions read from the file. Presentation only: the pair and its
//! run come from `study::pair_file` and the solver.

use geometry::{Vec2, polar, rotate};
use registry::fmt_f64;
use std::f64::consts::PI;
use study::pair_file::{Prepared, Role, Sense, StartSpec};

use crate::common::{deg, wrap_at_spaces};
use crate::escape_xml as escape;
use crate::label_place::{Anchor, LINE_GAP, Label, Placer, Segment, edges, nearest_on, text_box};
use crate::pair_html::{DRIVEN_COLOUR, DRIVEN_FILL, DRIVER_COLOUR, DRIVER_FILL};

/// Page directions (y grows downwards) in which a label that does not fit where it belongs is
/// moved.
const UP: (f64, f64) = (0.0, -1.0);
/// See [`UP`].
const DOWN: (f64, f64) = (0.0, 1.0);
/// See [`UP`].
const LEFT: (f64, f64) = (-1.0, 0.0);
/// See [`UP`].
const RIGHT: (f64, f64) = (1.0, 0.0);

/// The tips `pair-check.svg` labels: (gear, the user's tooth number, world position at φ = 0 and
/// θ = 0), teeth 0 and 1 of each gear, so that the picture shows where the numbering starts and
/// which way it runs.
pub fn labelled_tips(p: &Prepared) -> Vec<(Role, i64, Vec2)> {
    let (driver, driven) = p.mesh.world_outlines(0.0, 0.0);
    let mut out = Vec::new();
    for (role, outline, numbering) in [
        (Role::Driver, &driver, p.driver),
        (Role::Driven, &driven, p.driven),
    ] {
        for user in [0, 1] {
            // The outline alternates tip and valley, in the solver's tooth order.
            let k = numbering.solver(user) as usize;
            if let Some(&tip) = outline.get(2 * k) {
                out.push((role, user, tip));
            }
        }
    }
    out
}

/// Height of the eccentricity insets of `pair-check.svg`, px.
const INSET_HEIGHT: f64 = 230.0;

/// The factor the insets of `pair-check.svg` draw each arbor's offset from its tip-circle
/// centre by: of 1, 2 and 5 times a power of ten, the largest that draws the larger offset (as
/// a share of its gear's tip radius) at most 0.6 of the inset's circle; 1 when there is none
/// or it is visible as it is.
pub fn exaggeration(offsets: &[(f64, f64)]) -> f64 {
    let share = offsets.iter().map(|(e, r)| e / r).fold(0.0, f64::max);
    if share <= 0.0 || share >= 0.6 {
        return 1.0;
    }
    let raw = 0.6 / share;
    let decade = 10f64.powf(raw.log10().floor());
    [5.0, 2.0, 1.0]
        .into_iter()
        .map(|m| m * decade)
        .find(|&f| f <= raw)
        .unwrap_or(decade)
        .max(1.0)
}

/// The insets of `pair-check.svg`: for each gear, its tip circle (a schematic circle), the
/// tip-circle centre (o), the arbor (+) at its offset drawn [`exaggeration`] times its size,
/// and the axes of the gear's tips frame (x along its zero ray, y 90 deg from it in the sense
/// of its tips_deg), as the gears lie at φ = 0 and θ = 0: an eccentricity of a few tenths of a
/// millimetre, invisible at the picture's scale, shown in the frame it was entered in.
fn eccentricity_insets(svg: &mut String, p: &Prepared, margin: f64, width: f64, top: f64) {
    let gears = [
        (Role::Driver, p.mesh.driver(), p.driver, DRIVER_COLOUR),
        (Role::Driven, p.mesh.driven(), p.driven, DRIVEN_COLOUR),
    ];
    let offsets: Vec<(f64, f64)> = gears
        .iter()
        .map(|(role, g, ..)| (arbor_in_view(*role, g).norm(), g.max_tip_radius()))
        .collect();
    let factor = exaggeration(&offsets);
    let box_w = (width - 2.0 * margin - 20.0) / 2.0;
    svg.push_str(&format!(
        "<g class=\"inset\" data-exaggeration=\"{factor}\">\n<text x=\"{margin}\" y=\"{:.1}\" font-size=\"13\" font-weight=\"bold\">{}</text>\n",
        top + 4.0,
        escape(&format!(
            "Insets: arbor (+) against tip-circle centre (o) in each gear's tips frame (x along its zero ray), offsets exaggerated x{}",
            fmt_f64(factor, 0),
        ))
    ));
    for (i, (gear, offset)) in gears.iter().zip(&offsets).enumerate() {
        let x0 = margin + i as f64 * (box_w + 20.0);
        gear_inset(svg, *gear, *offset, factor, (x0, top + 14.0, box_w));
    }
    svg.push_str("</g>\n");
}

/// A gear's arbor minus its tip-circle centre in the view's frame (see [`check_svg`]).
fn arbor_in_view(role: Role, g: &geometry::Gear) -> Vec2 {
    match role {
        Role::Driver => g.rotation_centre(),
        Role::Driven => -g.rotation_centre(),
    }
}

/// A gear of the insets: its role, the gear, its numbering and its colour.
type InsetGear<'a> = (
    Role,
    &'a geometry::Gear,
    study::pair_file::Numbering,
    &'static str,
);

/// One gear's inset at `(x0, y0)`, `box_w` wide: its tip circle, its tips frame's axes, its
/// arbor drawn at its `offset` from the tip-circle centre times `factor` (against a tip radius
/// `tip_r`), and the offset in words.
fn gear_inset(
    svg: &mut String,
    (role, g, numbering, colour): InsetGear<'_>,
    (offset, tip_r): (f64, f64),
    factor: f64,
    (x0, y0, box_w): (f64, f64, f64),
) {
    let (offset, tip_r) = (&offset, &tip_r);
    let radius = 70.0;
    let h = INSET_HEIGHT - 14.0;
    let (cx, cy) = (x0 + 20.0 + radius + 20.0, y0 + h / 2.0);
    let at = |v: Vec2| (cx + v.x, cy - v.y);
    svg.push_str(&format!(
        "<rect x=\"{x0:.1}\" y=\"{y0:.1}\" width=\"{box_w:.1}\" height=\"{h:.1}\" fill=\"#fbfbfb\" stroke=\"#999999\"/>\n"
    ));
    // The tips frame's axes in the view: x along the zero ray (towards the other gear), y
    // 90 deg from it the way the gear's tips_deg run.
    let x_axis = match role {
        Role::Driver => Vec2::new(1.0, 0.0),
        Role::Driven => Vec2::new(-1.0, 0.0),
    };
    let ccw = match role {
        Role::Driver => true,
        Role::Driven => !numbering.mirrored,
    };
    let y_axis = if ccw {
        Vec2::new(-x_axis.y, x_axis.x)
    } else {
        Vec2::new(x_axis.y, -x_axis.x)
    };
    svg.push_str(&format!(
        "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"{radius}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\"/>\n"
    ));
    inset_axes(svg, (cx, cy), radius, (x_axis, y_axis));
    let e = arbor_in_view(role, g);
    let drawn = e * (factor * radius / tip_r);
    let (ax, ay) = at(drawn);
    if *offset > 0.0 {
        // The components along the frame's axes, dotted, and the offset itself.
        let along = x_axis * drawn.dot(&x_axis);
        let (px_, py_) = at(along);
        svg.push_str(&format!(
            "<polyline points=\"{cx:.1},{cy:.1} {px_:.1},{py_:.1} {ax:.1},{ay:.1}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1\" stroke-dasharray=\"2 3\"/>\n<line x1=\"{cx:.1}\" y1=\"{cy:.1}\" x2=\"{ax:.1}\" y2=\"{ay:.1}\" stroke=\"{colour}\" stroke-width=\"2.5\"/>\n"
        ));
    }
    svg.push_str(&format!(
        "<circle cx=\"{cx:.1}\" cy=\"{cy:.1}\" r=\"4\" fill=\"white\" stroke=\"{colour}\" stroke-width=\"1.5\"/>\n<path d=\"M{:.1} {ay:.1}H{:.1}M{ax:.1} {:.1}V{:.1}\" stroke=\"{colour}\" stroke-width=\"2\"/>\n",
        ax - 6.0,
        ax + 6.0,
        ay - 6.0,
        ay + 6.0
    ));
    let text_x = cx + radius + 40.0;
    inset_words(
        svg,
        (role, g, numbering, colour),
        (e, *offset, *tip_r),
        factor,
        (text_x, x0 + box_w, y0),
    );
}

/// An inset's axes from its centre `(cx, cy)`: its gear's tips frame, x along the zero ray and
/// y 90 deg from it the way the gear's tips_deg run, each an arrow named at its end.
fn inset_axes(svg: &mut String, (cx, cy): (f64, f64), radius: f64, (x_axis, y_axis): (Vec2, Vec2)) {
    let at = |v: Vec2| (cx + v.x, cy - v.y);
    for (axis, name) in [(x_axis, "x"), (y_axis, "y")] {
        let end = at(axis * (radius + 18.0));
        let base = axis * (radius + 10.0);
        let n = Vec2::new(-axis.y, axis.x) * 4.0;
        let (a, b) = (at(base + n), at(base - n));
        svg.push_str(&format!(
            "<line x1=\"{cx:.1}\" y1=\"{cy:.1}\" x2=\"{:.1}\" y2=\"{:.1}\" stroke=\"#555555\" stroke-width=\"1\"/>\n<polygon points=\"{:.1},{:.1} {:.1},{:.1} {:.1},{:.1}\" fill=\"#555555\"/>\n",
            end.0, end.1, end.0, end.1, a.0, a.1, b.0, b.1
        ));
        let label =
            at(axis * (radius + 24.0) + Vec2::new(0.0, if axis.y.abs() > 0.5 { 0.0 } else { 6.0 }));
        let anchor = if axis.x > 0.5 {
            "start"
        } else if axis.x < -0.5 {
            "end"
        } else {
            "middle"
        };
        svg.push_str(&format!(
            "<text x=\"{:.1}\" y=\"{:.1}\" text-anchor=\"{anchor}\" font-size=\"11\" fill=\"#555555\">{}</text>\n",
            label.0,
            label.1 + if axis.y < -0.5 { 10.0 } else { 0.0 },
            escape(name)
        ));
    }
}

/// An inset's words, from `text_x` to `right` below `y0`: the gear and the factor its offset is
/// drawn by, and its arbor minus its tip-circle centre `e` (view's frame) in both frames.
fn inset_words(
    svg: &mut String,
    (role, g, numbering, colour): InsetGear<'_>,
    (e, offset, tip_r): (Vec2, f64, f64),
    factor: f64,
    (text_x, right, y0): (f64, f64, f64),
) {
    let tips = if numbering.mirrored {
        Vec2::new(g.rotation_centre().x, -g.rotation_centre().y)
    } else {
        g.rotation_centre()
    };
    let xy = |v: Vec2| format!("({}, {})", fmt_f64(v.x, 4), fmt_f64(v.y, 4));
    let words = if offset > 0.0 {
        format!(
            "arbor minus tip-circle centre: {} in the tips frame (offset {}, angle_deg {}), {} in the view's frame; drawn {} times its size against a tip radius of {}.",
            xy(tips),
            fmt_f64(tips.norm(), 4),
            fmt_f64(deg(tips.y.atan2(tips.x)), 3),
            xy(e),
            fmt_f64(factor, 0),
            fmt_f64(tip_r, 4)
        )
    } else {
        "no eccentricity: the arbor is at the tip-circle centre.".to_string()
    };
    svg.push_str(&format!(
        "<text x=\"{text_x:.1}\" y=\"{:.1}\" font-size=\"13\" fill=\"{colour}\" font-weight=\"bold\">{}</text>\n",
        y0 + 22.0,
        escape(&format!("{}, offset x{}", role.name(), fmt_f64(factor, 0)))
    ));
    let chars = ((right - text_x - 8.0) / 6.6).max(12.0) as usize;
    for (l, line) in wrap_at_spaces(&words, chars).iter().enumerate() {
        svg.push_str(&format!(
            "<text x=\"{text_x:.1}\" y=\"{:.1}\" font-size=\"11\">{}</text>\n",
            y0 + 42.0 + 15.0 * l as f64,
            escape(line)
        ));
    }
}

/// Room kept clear beside the gears of `pair-check.svg` for their labels, px: the driver's to
/// its left, the driven gear's to its right, whatever the gears' sizes (a 27-tooth pinion on a
/// 223-tooth wheel leaves no room beside the pinion otherwise).
const LABEL_ROOM: f64 = 190.0;

/// The drawing of `pair-check.svg`: where its world (the view's frame, length units) lands on
/// the page, and the page's size above the insets.
struct Canvas {
    /// Pixels per length unit.
    k: f64,
    /// The world x at the drawing's left edge, and the world y at its top.
    x_min: f64,
    y_max: f64,
    /// The world x at the drawing's right edge.
    x_max: f64,
    /// Page width, left margin, and the drawing's top, px.
    width: f64,
    margin: f64,
    top: f64,
}

impl Canvas {
    /// The drawing of the gears of `p`: both whole, with [`LABEL_ROOM`] beside them and, beyond
    /// the driven gear, room for the labels that run outwards from it.
    fn of(p: &Prepared) -> Canvas {
        let (g1, g2) = (p.mesh.driver(), p.mesh.driven());
        let (c1, c2) = centres(p);
        let (r1, r2) = (g1.max_tip_radius(), g2.max_tip_radius());
        let (width, margin, top) = (1000.0, 30.0, 50.0);
        let drawn = width - 2.0 * margin;
        let (left, right) = (c1.x - 1.1 * r1, c2.x + 1.1 * r2);
        // World room on each side: LABEL_ROOM px at the scale that leaves it.
        let room = LABEL_ROOM * (right - left) / (drawn - 2.0 * LABEL_ROOM);
        let (x_min, x_max) = (left - room, right + room);
        Canvas {
            k: drawn / (x_max - x_min),
            x_min,
            x_max,
            y_max: 1.15 * r1.max(r2),
            width,
            margin,
            top,
        }
    }

    /// A world point on the page, px.
    fn at(&self, v: Vec2) -> (f64, f64) {
        (
            self.margin + (v.x - self.x_min) * self.k,
            self.top + (self.y_max - v.y) * self.k,
        )
    }

    /// A world point as an SVG `points` pair.
    fn pt(&self, v: Vec2) -> String {
        let (x, y) = self.at(v);
        format!("{x:.2},{y:.2}")
    }

    /// The bottom of the drawing, px.
    fn bottom(&self) -> f64 {
        self.top + 2.0 * self.y_max * self.k
    }

    /// The drawing's own rectangle, px, within which every label stays.
    fn area(&self) -> crate::chart::Rect {
        crate::chart::Rect {
            x: 2.0,
            y: 30.0,
            w: self.width - 4.0,
            h: self.bottom() + 12.0 - 30.0,
        }
    }
}

/// The tip-circle centres of the gears of `p` at φ = 0 and θ = 0: the arbors are at the origin
/// and (D, 0); at φ = 0 the driver's frame is the world's, at θ = 0 the driven gear's is the
/// world's turned by π.
fn centres(p: &Prepared) -> (Vec2, Vec2) {
    let (g1, g2) = (p.mesh.driver(), p.mesh.driven());
    (
        -g1.rotation_centre(),
        Vec2::new(p.mesh.centre_distance(), 0.0) + rotate(-g2.rotation_centre(), PI),
    )
}

/// Every direction a label may move in, nearest the ones given first.
fn and_the_rest(first: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    let mut all = first.to_vec();
    for d in [UP, DOWN, LEFT, RIGHT, (-h, -h), (h, -h), (-h, h), (h, h)] {
        if !all.contains(&d) {
            all.push(d);
        }
    }
    all
}

/// The labels of the drawing, placed clear of the teeth, the axes, the arrows and each other.
struct Labels {
    placer: Placer,
    /// The gears' outlines, px: tooth labels keep out of both.
    outlines: [Vec<(f64, f64)>; 2],
}

/// One label to write: the world point it belongs at, how it hangs there, its colour and text
/// (`\n` between lines), what it labels (`data-label`), and the page directions it may move in
/// first.
struct Say<'a> {
    at: Vec2,
    anchor: Anchor,
    colour: &'a str,
    text: &'a str,
    what: &'a str,
    dirs: &'a [(f64, f64)],
}

impl Labels {
    /// Writes `say` where it fits nearest to its point (out of both gears' bodies too, with
    /// `off_gears`), on a thin leader where it had to move.
    fn write(&mut self, svg: &mut String, c: &Canvas, say: &Say<'_>, off_gears: bool) {
        let label = Label {
            text: say.text,
            font: 13.0,
            anchor: say.anchor,
            at: c.at(say.at),
        };
        let dirs = and_the_rest(say.dirs);
        let (x, y) = if off_gears {
            let areas: [&[(f64, f64)]; 2] = [&self.outlines[0], &self.outlines[1]];
            self.placer.place_off(&label, &dirs, &areas)
        } else {
            self.placer.place(&label, &dirs)
        };
        let (from, to) = (
            label.at,
            nearest_on(&text_box((x, y), say.anchor, say.text, 13.0), label.at),
        );
        if (to.0 - from.0).hypot(to.1 - from.1) > 8.0 {
            svg.push_str(&format!(
                "<line class=\"leader\" x1=\"{:.2}\" y1=\"{:.2}\" x2=\"{:.2}\" y2=\"{:.2}\" stroke=\"{}\" stroke-width=\"0.75\"/>\n",
                from.0, from.1, to.0, to.1, say.colour
            ));
        }
        let lines: Vec<String> = say
            .text
            .lines()
            .enumerate()
            .map(|(i, l)| {
                format!(
                    "<tspan x=\"{x:.2}\" dy=\"{}\">{}</tspan>",
                    if i == 0 {
                        "0".to_owned()
                    } else {
                        format!("{LINE_GAP}em")
                    },
                    escape(l)
                )
            })
            .collect();
        svg.push_str(&format!(
            "<text class=\"label\" data-label=\"{}\" x=\"{x:.2}\" y=\"{y:.2}\" text-anchor=\"{}\" fill=\"{}\" stroke=\"white\" stroke-width=\"3\" paint-order=\"stroke\">{}</text>\n",
            say.what,
            say.anchor.svg(),
            say.colour,
            lines.concat()
        ));
    }
}

/// An SVG line between two world points, with extra attributes.
fn line(svg: &mut String, c: &Canvas, (a, b): (Vec2, Vec2), colour: &str, extra: &str) {
    let ((x1, y1), (x2, y2)) = (c.at(a), c.at(b));
    svg.push_str(&format!(
        "<line x1=\"{x1:.2}\" y1=\"{y1:.2}\" x2=\"{x2:.2}\" y2=\"{y2:.2}\" stroke=\"{colour}\" {extra}/>\n"
    ));
}

/// An arrowhead at world point `tip` pointing along the unit vector `u`, `size` long (world
/// lengths).
fn head(svg: &mut String, c: &Canvas, (tip, u): (Vec2, Vec2), size: f64, colour: &str) {
    let n = Vec2::new(-u.y, u.x) * (0.45 * size);
    let base = tip - u * size;
    svg.push_str(&format!(
        "<polygon points=\"{} {} {}\" fill=\"{colour}\"/>\n",
        c.pt(tip),
        c.pt(base + n),
        c.pt(base - n)
    ));
}

/// The axes: x along the line of centres across the drawing, y through the driver's arbor, as
/// tall as the driver (a taller one would cut through the labels beside a small driver); each
/// kept clear by the labels placed after it.
fn axes(svg: &mut String, c: &Canvas, labels: &mut Labels, p: &Prepared, size: f64) {
    let x_end = Vec2::new(c.x_max, 0.0);
    let x_axis = (Vec2::new(c.x_min, 0.0), x_end);
    line(svg, c, x_axis, "black", "class=\"axis\" stroke-width=\"1\"");
    head(svg, c, (x_end, Vec2::new(1.0, 0.0)), size, "black");
    let reach = (1.3 * p.mesh.driver().max_tip_radius()).min(0.95 * c.y_max);
    let y_end = Vec2::new(0.0, reach);
    let y_axis = (Vec2::new(0.0, -reach), y_end);
    line(svg, c, y_axis, "black", "class=\"axis\" stroke-width=\"1\"");
    head(svg, c, (y_end, Vec2::new(0.0, 1.0)), size, "black");
    labels.placer.keep_off(&[(c.at(y_axis.0), c.at(y_axis.1))]);
    for (at, anchor, text, dirs) in [
        (
            x_end + Vec2::new(0.0, 1.2 * size),
            Anchor::End,
            "x",
            &[UP, DOWN][..],
        ),
        (
            y_end + Vec2::new(size, -size),
            Anchor::Start,
            "y",
            &[RIGHT, UP][..],
        ),
    ] {
        let say = Say {
            at,
            anchor,
            colour: "black",
            text,
            what: text,
            dirs,
        };
        labels.write(svg, c, &say, false);
    }
}

/// One gear's outline, zero ray, arbor and tip-circle centre, and turning sense, with their
/// labels: the driver's labels to its left, the driven gear's to its right.
fn gear_drawing(
    svg: &mut String,
    c: &Canvas,
    labels: &mut Labels,
    (role, outline): (Role, &[Vec2]),
    (arbor, centre, radius): (Vec2, Vec2, f64),
    size: f64,
) {
    let (colour, fill) = match role {
        Role::Driver => (DRIVER_COLOUR, DRIVER_FILL),
        Role::Driven => (DRIVEN_COLOUR, DRIVEN_FILL),
    };
    let points: Vec<String> = outline.iter().map(|&v| c.pt(v)).collect();
    svg.push_str(&format!(
        "<polygon id=\"{}-outline\" points=\"{}\" fill=\"{fill}\" fill-opacity=\"0.6\" stroke=\"{colour}\" stroke-width=\"1\"/>\n",
        role.name(),
        points.join(" ")
    ));
    // The zero ray, from the tip-circle centre towards the other gear.
    let towards = match role {
        Role::Driver => Vec2::new(1.0, 0.0),
        Role::Driven => Vec2::new(-1.0, 0.0),
    };
    let ray_end = centre + towards * radius;
    line(
        svg,
        c,
        (centre, ray_end),
        colour,
        "stroke-width=\"2\" stroke-dasharray=\"8 4\"",
    );
    head(svg, c, (ray_end, towards), size, colour);
    // The arbor (+) and the tip-circle centre (o).
    let arm = 0.6 * size;
    for d in [Vec2::new(arm, 0.0), Vec2::new(0.0, arm)] {
        line(svg, c, (arbor - d, arbor + d), colour, "stroke-width=\"2\"");
    }
    let (cx, cy) = c.at(centre);
    svg.push_str(&format!(
        "<circle cx=\"{cx:.2}\" cy=\"{cy:.2}\" r=\"4\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"1.5\"/>\n"
    ));
    let turn = turning_arrow(svg, c, role, (arbor, radius), size, colour);
    labels.placer.keep_off(&turn);
    let mid = c.world(turn[turn.len() / 2].0);
    gear_labels(svg, c, labels, role, (arbor, centre, radius, mid), size);
}

/// One gear's labels: its zero ray's beside the tip-circle centre, its arbor's and tip-circle
/// centre's below the arbor, its turning sense's at the middle of its arrow `mid` (world); the
/// driver's to its left, the driven gear's to its right.
fn gear_labels(
    svg: &mut String,
    c: &Canvas,
    labels: &mut Labels,
    role: Role,
    (arbor, centre, radius, mid): (Vec2, Vec2, f64, Vec2),
    size: f64,
) {
    let colour = match role {
        Role::Driver => DRIVER_COLOUR,
        Role::Driven => DRIVEN_COLOUR,
    };
    let towards = match role {
        Role::Driver => Vec2::new(1.0, 0.0),
        Role::Driven => Vec2::new(-1.0, 0.0),
    };
    let (outwards, anchor) = match role {
        Role::Driver => (LEFT, Anchor::End),
        Role::Driven => (RIGHT, Anchor::Start),
    };
    let name = role.name();
    let (angle, turns) = match role {
        Role::Driver => ("phi = 0", "driver turns this way:\nphi increases"),
        Role::Driven => ("theta = 0", "driven gear turns this way:\ntheta increases"),
    };
    let ray = format!("{name} zero ray: {angle}");
    let centres = format!("{name} arbor (+),\ntip-circle centre (o)");
    let sayings = [
        // Beside the centre, clear of the mesh, where the two rays meet.
        (
            centre - towards * (0.05 * radius) - Vec2::new(0.0, 1.8 * size),
            anchor,
            ray.as_str(),
            "zero-ray",
            [DOWN, UP, outwards],
        ),
        (
            arbor - Vec2::new(0.0, 3.8 * size),
            anchor,
            centres.as_str(),
            "arbor",
            [DOWN, outwards, UP],
        ),
        (mid, Anchor::Middle, turns, "turn", [UP, outwards, DOWN]),
    ];
    for (at, anchor, text, what, dirs) in sayings {
        let what = format!("{name}-{what}");
        let say = Say {
            at,
            anchor,
            colour,
            text,
            what: &what,
            dirs: &dirs,
        };
        labels.write(svg, c, &say, false);
    }
}

/// A gear's turning sense: an arc away from the mesh about its arbor, the arrowhead where the
/// turn goes. Its segments, px, for the labels to keep off (its own among them).
fn turning_arrow(
    svg: &mut String,
    c: &Canvas,
    role: Role,
    (arbor, radius): (Vec2, f64),
    size: f64,
    colour: &str,
) -> Vec<Segment> {
    let (from, to): (f64, f64) = match role {
        Role::Driver => (100.0, 150.0),
        Role::Driven => (80.0, 30.0),
    };
    let arc_r = 0.55 * radius;
    let steps = 24;
    let world: Vec<Vec2> = (0..=steps)
        .map(|i| {
            arbor
                + polar(
                    arc_r,
                    (from + (to - from) * f64::from(i) / f64::from(steps)).to_radians(),
                )
        })
        .collect();
    let arc: Vec<String> = world.iter().map(|&v| c.pt(v)).collect();
    svg.push_str(&format!(
        "<polyline class=\"turn\" points=\"{}\" fill=\"none\" stroke=\"{colour}\" stroke-width=\"2\"/>\n",
        arc.join(" ")
    ));
    let end = to.to_radians();
    let along = (to - from).signum();
    let u = Vec2::new(-end.sin(), end.cos()) * along;
    head(svg, c, (arbor + polar(arc_r, end), u), 1.5 * size, colour);
    world.windows(2).map(|w| (c.at(w[0]), c.at(w[1]))).collect()
}

impl Canvas {
    /// The world point at page point `(x, y)`.
    fn world(&self, (x, y): (f64, f64)) -> Vec2 {
        Vec2::new(
            self.x_min + (x - self.margin) / self.k,
            self.y_max - (y - self.top) / self.k,
        )
    }
}

/// Teeth 0 and 1 of each gear: a dot on the tip and a label, moved on a leader to the nearest
/// place out of both gears and clear of the rays, the axes and each other: the driver's to its
/// side (left), the driven gear's to its side (right), up above the line of centres and down
/// below it.
fn tooth_labels(svg: &mut String, c: &Canvas, labels: &mut Labels, p: &Prepared) {
    let h = std::f64::consts::FRAC_1_SQRT_2;
    for (role, user, tip) in labelled_tips(p) {
        let (colour, anchor, side) = match role {
            Role::Driver => (DRIVER_COLOUR, Anchor::End, -1.0),
            Role::Driven => (DRIVEN_COLOUR, Anchor::Start, 1.0),
        };
        let (x, y) = c.at(tip);
        svg.push_str(&format!(
            "<circle id=\"{}-tooth-{user}\" cx=\"{x:.2}\" cy=\"{y:.2}\" r=\"4\" fill=\"{colour}\"/>\n",
            role.name()
        ));
        let away = if tip.y >= 0.0 { -1.0 } else { 1.0 };
        let text = format!("{} tooth {user}", role.name());
        let what = format!("{}-tooth-{user}", role.name());
        let dirs = [(side * h, away * h), (side, 0.0), (0.0, away), (0.0, -away)];
        let say = Say {
            at: tip,
            anchor,
            colour,
            text: &text,
            what: &what,
            dirs: &dirs,
        };
        labels.write(svg, c, &say, true);
    }
}

/// `pair-check.svg`: both gears at φ = 0 and θ = 0 as the file describes them, with the axes, the
/// arbors and tip-circle centres, each zero ray, teeth 0 and 1 of each gear, the turning senses,
/// and in words the conventions read from the file and the start of the run. Every label stays
/// on the canvas and off the teeth, the axes, the arrows and the other labels (tooth labels off
/// both gears' bodies too), on a leader where it had to move.
pub fn check_svg(name: &str, p: &Prepared, (phi0, theta0): (f64, f64)) -> String {
    let mesh = &p.mesh;
    let (r1, r2) = (
        mesh.driver().max_tip_radius(),
        mesh.driven().max_tip_radius(),
    );
    let (out1, out2) = mesh.world_outlines(0.0, 0.0);
    let (c1, c2) = centres(p);
    let c = Canvas::of(p);
    let inset_top = c.bottom() + 20.0;
    let legend_top = inset_top + INSET_HEIGHT + 24.0;
    let height = legend_top + 12.0 * 18.0 + 10.0;
    let width = c.width;
    let mut svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{width}\" height=\"{height:.0}\" viewBox=\"0 0 {width} {height:.0}\" font-family=\"sans-serif\" font-size=\"13\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
    );
    // Every label keeps off both outlines, the line of centres (the x axis and both zero rays
    // lie on it) and the labels placed before it, within the drawing.
    let px = |o: &[Vec2]| o.iter().map(|&v| c.at(v)).collect::<Vec<_>>();
    let outlines = [px(&out1), px(&out2)];
    let centres_line = vec![(c.at(Vec2::new(c.x_min, 0.0)), c.at(Vec2::new(c.x_max, 0.0)))];
    let placer = Placer::new([edges(&outlines[0]), edges(&outlines[1]), centres_line].concat())
        .within(c.area());
    let mut labels = Labels { placer, outlines };
    let title = format!("Check of {name}: both gears at phi = 0 and theta = 0");
    labels
        .placer
        .block(text_box((c.margin, 24.0), Anchor::Start, &title, 16.0));
    svg.push_str(&format!(
        "<text x=\"{}\" y=\"24\" font-size=\"16\">{}</text>\n",
        c.margin,
        escape(&title)
    ));
    let size = 0.05 * r1.min(r2);
    axes(&mut svg, &c, &mut labels, p, size);
    let arbor2 = Vec2::new(mesh.centre_distance(), 0.0);
    gear_drawing(
        &mut svg,
        &c,
        &mut labels,
        (Role::Driver, &out1),
        (Vec2::zeros(), c1, r1),
        size,
    );
    gear_drawing(
        &mut svg,
        &c,
        &mut labels,
        (Role::Driven, &out2),
        (arbor2, c2, r2),
        size,
    );
    tooth_labels(&mut svg, &c, &mut labels, p);
    eccentricity_insets(&mut svg, p, c.margin, width, inset_top);
    conventions(&mut svg, p, (phi0, theta0), (c.margin, legend_top));
    svg.push_str("</svg>\n");
    svg
}

/// The file's conventions in words beneath the insets, and the start of the run.
fn conventions(
    svg: &mut String,
    p: &Prepared,
    (phi0, theta0): (f64, f64),
    (margin, top): (f64, f64),
) {
    let (g1, g2) = (p.mesh.driver(), p.mesh.driven());
    let mut lines = vec![
        "Axes: x: line of centres, driver arbor -> driven arbor; y: 90 deg from x in the driver's turning sense.".to_string(),
        "Seen from the side on which the driver turns counter-clockwise. Each zero ray (dashed: the direction of tips_deg = 0) starts at its gear's tip-circle centre (o) and, at phi = 0 and theta = 0, points along the line of centres at the other gear.".to_string(),
        "The gears may overlap in this picture: it shows your frames, not a meshing position. Teeth 0 and 1 show where your numbering starts and which way it runs.".to_string(),
    ];
    for (role, gear, spec, numbering) in [
        (Role::Driver, g1, &p.spec.driver, p.driver),
        (Role::Driven, g2, &p.spec.driven, p.driven),
    ] {
        lines.push(gear_words(role, gear, spec.sense, numbering));
    }
    let start = match p.spec.start {
        StartSpec::Touching => "start: touching".to_string(),
        StartSpec::AtRest { theta_deg } => format!("start: at_rest(theta_deg: {theta_deg})"),
        StartSpec::Teeth { driver, driven } => {
            format!("start: teeth(driver: {driver}, driven: {driven})")
        }
    };
    lines.push(format!(
        "The run starts at phi0 = {} deg, theta0 = {} deg ({start}); centre distance D = {}.",
        fmt_f64(deg(phi0), 6),
        fmt_f64(deg(theta0), 6),
        fmt_f64(p.mesh.centre_distance(), 4)
    ));
    let wrapped: Vec<String> = lines.iter().flat_map(|l| wrap_at_spaces(l, 150)).collect();
    for (i, l) in wrapped.iter().enumerate() {
        svg.push_str(&format!(
            "<text x=\"{margin}\" y=\"{:.0}\" font-size=\"12\">{}</text>\n",
            top + 18.0 * i as f64,
            escape(l)
        ));
    }
}

/// One gear's line of the conventions: its teeth, which way its tips_deg run, its sense, and
/// its arbor against its tip-circle centre in both frames.
fn gear_words(
    role: Role,
    gear: &geometry::Gear,
    sense: Sense,
    numbering: study::pair_file::Numbering,
) -> String {
    let ccw = match role {
        Role::Driver => true,
        Role::Driven => !numbering.mirrored,
    };
    let sense = match sense {
        Sense::Driver => "driver",
        Sense::Own => "own",
    };
    let e = gear.rotation_centre();
    let tips_frame = if numbering.mirrored {
        Vec2::new(e.x, -e.y)
    } else {
        e
    };
    let world = match role {
        Role::Driver => e,
        Role::Driven => -e,
    };
    let xy = |v: Vec2| format!("({}, {})", fmt_f64(v.x, 4), fmt_f64(v.y, 4));
    format!(
        "{}: {} teeth, tips_deg run {} here (sense: {sense}); arbor minus tip-circle centre {} in the world frame, {} in its tips frame = arbor (offset: {}, angle_deg: {}).",
        role.name(),
        gear.teeth(),
        if ccw {
            "counter-clockwise"
        } else {
            "clockwise"
        },
        xy(world),
        xy(tips_frame),
        fmt_f64(tips_frame.norm(), 4),
        fmt_f64(deg(tips_frame.y.atan2(tips_frame.x)), 3),
    )
}
