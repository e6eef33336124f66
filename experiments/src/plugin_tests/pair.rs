//! The `pair` experiment's tests: the `tests` module of `plugins/pair.rs`, kept beside the
//! plugins so that the plugin file holds the experiment alone.
#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;
use contact::{Solve, Start};
use geometry::Gear;
use std::f64::consts::TAU;
use study::pair_file::load;

use geometry::{Vec2, polar, rotate};
use std::f64::consts::PI;
use study::pair_file::Role;

use presentation::label_place::{Anchor, Segment, edges, segment_meets, text_box};
use presentation::pair_svg::{exaggeration, labelled_tips};

/// `help pair` states the proportions the loader refuses with the loader's own limits.
#[test]
fn the_help_states_the_loaders_proportion_limits() {
    use study::pair_file::{MAX_HEIGHT_RATIO, MAX_PITCH_RATIO, MAX_TOOTH_HEIGHT_SHARE};
    assert!((MAX_TOOTH_HEIGHT_SHARE - 0.5).abs() < f64::EPSILON);
    assert!(CONFIG_HELP.contains("teeth taller than half their tip radius"));
    for (ratio, what) in [(MAX_PITCH_RATIO, "pitches"), (MAX_HEIGHT_RATIO, "heights")] {
        let words = format!("more than {ratio} times apart");
        let at = CONFIG_HELP.find(&words).unwrap();
        assert!(
            CONFIG_HELP[..at]
                .rsplit("tooth ")
                .next()
                .unwrap()
                .starts_with(what)
        );
    }
}

#[test]
fn example_loads() {
    assert!(load("x.ron", EXAMPLE).is_ok());
}

#[test]
fn errors_name_file_field_and_rule() {
    let bad = |text: &str| load("m.ron", text).unwrap_err().to_string();
    let base = |driver: &str, extra: &str| {
        format!(
            "(driver: {driver}, driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), {extra})"
        )
    };
    let ok_driver = "(teeth: 20, tip_radius: 10.0, root_radius: 9.0)";
    assert_eq!(
        bad(&base(
            "(teeth: 2, tip_radius: 10.0, root_radius: 9.0)",
            "clearance_percent: Some(40.0)"
        )),
        "m.ron: driver.teeth: must be at least 3 (got 2)"
    );
    assert!(
        bad(&base(
            "(teeth: 20, tip_radius: 10.0, root_radius: 10.0)",
            "clearance_percent: Some(40.0)"
        ))
        .starts_with("m.ron: driver.root_radius: must be less than tip_radius")
    );
    assert!(
        bad(&base(ok_driver, "centre_distance: Some(15.0)"))
            .starts_with("m.ron: centre_distance: must exceed")
    );
    assert!(bad(&base(ok_driver, "")).contains("give exactly one of"));
    assert!(
        bad(&base(ok_driver, "clearance_percent: Some(140.0)"))
            .starts_with("m.ron: clearance_percent:")
    );
    assert!(bad("(driver: (teeth: 20,").starts_with("m.ron: line 1, column"));
    assert_eq!(
        bad(&base(
            "(teeth: 1000000000, tip_radius: 10.0, root_radius: 9.0)",
            "clearance_percent: Some(40.0)"
        )),
        "m.ron: driver.teeth: must be at most 100000 (the limit on teeth; got 1000000000)"
    );
    assert_eq!(train::MAX_TEETH as usize, geometry::MAX_TEETH);
    assert!(
        bad(&base(
            "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([0.0, 10.0]))",
            "clearance_percent: Some(40.0)"
        ))
        .starts_with("m.ron: driver.tips_deg: must list exactly")
    );
}

/// A gear known in the world at φ = 0 and θ = 0, built without the loader: its arbor, its
/// tip-circle centre and its tips (all at `radius` from that centre).
struct Known {
    teeth: usize,
    radius: f64,
    root: f64,
    arbor: Vec2,
    centre: Vec2,
    tips: Vec<Vec2>,
}

/// Irregular tips (up to ±0.03 of a pitch off their place) about an offset centre: `first` is
/// the world angle of tip 0 seen from the centre.
fn known(teeth: usize, radius: f64, arbor: Vec2, centre: Vec2, first: f64) -> Known {
    let pitch = 360.0 / teeth as f64;
    let tips = (0..teeth)
        .map(|k| {
            let jitter = 0.03 * pitch * (2.3 * k as f64 + 0.4).sin();
            centre + polar(radius, (first + pitch * k as f64 + jitter).to_radians())
        })
        .collect();
    Known {
        teeth,
        radius,
        root: radius - 1.8,
        arbor,
        centre,
        tips,
    }
}

/// A measuring convention: the sense of the tip angles, the frame of the offset, and whether
/// the offset is written as `eccentricity` or `arbor`.
#[derive(Debug, Clone, Copy)]
struct Convention {
    own: bool,
    world: bool,
    polar: bool,
}

/// Circumcentre of three points: the tip-circle centre fitted as one would on a scan.
fn circumcentre(a: Vec2, b: Vec2, c: Vec2) -> Vec2 {
    let (b, c) = (b - a, c - a);
    let d = 2.0 * (b.x * c.y - b.y * c.x);
    let (b2, c2) = (b.norm_squared(), c.norm_squared());
    a + Vec2::new(c.y * b2 - b.y * c2, b.x * c2 - c.x * b2) / d
}

/// Measures `g` as the help text tells a user to: about the fitted tip-circle centre, from
/// the zero ray `zero` (the gear's direction along the line of centres towards the other
/// gear), counter-clockwise in the view when `ccw`. Returns the gear's RON text and, for each
/// of the user's tooth numbers, the index of that tip in `g.tips`.
fn measure(g: &Known, zero: Vec2, ccw: bool, c: Convention) -> (String, Vec<usize>) {
    let n = g.teeth;
    let centre = circumcentre(g.tips[0], g.tips[n / 3], g.tips[2 * n / 3]);
    let sign = if ccw { 1.0 } else { -1.0 };
    let angle = |v: Vec2| {
        let a = (zero.x * v.y - zero.y * v.x).atan2(zero.dot(&v));
        (sign * a).to_degrees().rem_euclid(360.0)
    };
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&i, &j| angle(g.tips[i] - centre).total_cmp(&angle(g.tips[j] - centre)));
    let tips: Vec<f64> = order.iter().map(|&i| angle(g.tips[i] - centre)).collect();
    let e = g.arbor - centre;
    let offset = if c.world {
        e
    } else {
        // y is 90° from the zero ray in the sense the tips are measured in.
        let y_axis = Vec2::new(-zero.y, zero.x) * sign;
        Vec2::new(e.dot(&zero), e.dot(&y_axis))
    };
    let sense = if c.own { "own" } else { "driver" };
    let frame = if c.world { "world" } else { "tips" };
    let offset = if c.polar {
        format!(
            "arbor: Some((offset: {:?}, angle_deg: {:?}))",
            offset.norm(),
            offset.y.atan2(offset.x).to_degrees()
        )
    } else {
        format!("eccentricity: Some(({:?}, {:?}))", offset.x, offset.y)
    };
    (
        format!(
            "(teeth: {n}, tip_radius: {:?}, root_radius: {:?}, sense: {sense}, tips_deg: Some({tips:?}), {offset}, eccentricity_frame: {frame})",
            g.radius, g.root
        ),
        order,
    )
}

/// The known pair: 17 and 23 irregular teeth, both eccentric, G = 40 % of h = 1.8.
fn known_pair() -> (Known, Known, f64) {
    let d = geometry::centre_distance(20.0, 26.0, 1.8, 40.0);
    let driver = known(17, 20.0, Vec2::zeros(), Vec2::new(-0.3, 0.2), 5.0);
    let driven = known(
        23,
        26.0,
        Vec2::new(d, 0.0),
        Vec2::new(d + 0.25, -0.4),
        183.0,
    );
    (driver, driven, d)
}

/// The pair file for the known pair measured in `c` (both gears), with `start`.
fn measured_file(c: Convention, start: &str) -> (String, Vec<usize>, Vec<usize>) {
    let (g1, g2, d) = known_pair();
    let (t1, m1) = measure(&g1, Vec2::new(1.0, 0.0), true, c);
    // The driven gear turns clockwise in the view: its own sense is clockwise.
    let (t2, m2) = measure(&g2, Vec2::new(-1.0, 0.0), !c.own, c);
    let text = format!(
        "(driver: {t1}, driven: {t2}, centre_distance: Some({d:?}), start_deg: 0.0, run_deg: Some(400.0), {start})"
    );
    (text, m1, m2)
}

fn conventions() -> Vec<Convention> {
    let mut out = Vec::new();
    for own in [false, true] {
        for world in [false, true] {
            for polar in [false, true] {
                out.push(Convention { own, world, polar });
            }
        }
    }
    out
}

/// θ every 0.2° of φ over the run, and the events with the known tips' indices.
type Motion = (
    Vec<f64>,
    Vec<(f64, f64, f64, contact::EventKind, usize, usize)>,
);

fn motion(p: &Prepared, m1: &[usize], m2: &[usize]) -> Motion {
    let traj = p
        .mesh
        .solve(0.0..=400f64.to_radians(), p.start, Solve::path());
    let thetas = (0..=2000)
        .map(|i| traj.theta_at((0.2 * f64::from(i)).to_radians()))
        .collect();
    let events = traj
        .events()
        .iter()
        .map(|e| {
            let j = m1[p.driver.user(e.driver_tooth) as usize];
            let k = m2[p.driven.user(e.driven_tooth) as usize];
            (e.phi, e.theta, e.theta_after, e.kind, j, k)
        })
        .collect();
    (thetas, events)
}

fn assert_same_motion(a: &Motion, b: &Motion, what: &str) {
    let tol = 1e-9f64.to_radians();
    for (i, (x, y)) in a.0.iter().zip(&b.0).enumerate() {
        assert!(
            (x - y).abs() < tol,
            "{what}: theta at row {i}: {x} against {y}"
        );
    }
    assert_eq!(
        a.1.len(),
        b.1.len(),
        "{what}: events {:?} against {:?}",
        a.1,
        b.1
    );
    for (e, f) in a.1.iter().zip(&b.1) {
        assert!(
            (e.0 - f.0).abs() < tol,
            "{what}: event phi {e:?} against {f:?}"
        );
        assert!(
            (e.1 - f.1).abs() < tol,
            "{what}: event theta {e:?} against {f:?}"
        );
        assert!(
            (e.2 - f.2).abs() < tol,
            "{what}: event theta after {e:?} against {f:?}"
        );
        assert_eq!(
            (e.3, e.4, e.5),
            (f.3, f.4, f.5),
            "{what}: event {e:?} against {f:?}"
        );
    }
}

#[test]
fn every_convention_recovers_the_known_gears_and_the_same_motion() {
    let (g1, g2, _) = known_pair();
    let mut reference: Option<(Motion, Motion)> = None;
    let mut events = 0;
    for c in conventions() {
        let (text, m1, m2) = measured_file(c, "");
        let p = prepare("rt.ron", &text).unwrap_or_else(|e| panic!("{c:?}: {e}\n{text}"));
        // The loaded gears stand where the known ones do, tooth for tooth in the user's
        // numbering.
        let (w1, w2) = p.mesh.world_outlines(0.0, 0.0);
        for (outline, numbering, map, g) in [(&w1, p.driver, &m1, &g1), (&w2, p.driven, &m2, &g2)] {
            for (user, &i) in map.iter().enumerate() {
                let k = numbering.solver(user as i64) as usize;
                let miss = (outline[2 * k] - g.tips[i]).norm();
                assert!(miss < 1e-9, "{c:?}: tooth {user} is {miss} off");
            }
        }
        for (role, user, at) in labelled_tips(&p) {
            let (g, map) = match role {
                Role::Driver => (&g1, &m1),
                Role::Driven => (&g2, &m2),
            };
            assert!(
                (at - g.tips[map[user as usize]]).norm() < 1e-9,
                "{c:?}: {role:?} {user}"
            );
        }
        assert!(
            (g2.centre - g2.arbor - rotate(-p.mesh.driven().rotation_centre(), PI)).norm() < 1e-9
        );
        // The same motion from the touching start, and from the resting pair of that start
        // named by tooth numbers in this convention.
        let touching = motion(&p, &m1, &m2);
        let traj = p.mesh.solve(0.0..=0.1, p.start, Solve::path());
        let theta0 = traj.theta_at(0.0);
        let mut obs = Vec::new();
        p.mesh
            .obstacles(0.0, theta0 - 1e-6, theta0 + 1e-6, &mut obs);
        let resting = obs
            .iter()
            .find(|o| (o.hi - theta0).abs() < 1e-12)
            .unwrap_or_else(|| panic!("{c:?}: nothing touches at the start"));
        let (j, k) = (
            p.driver.user(resting.driver_tooth),
            p.driven.user(resting.driven_tooth),
        );
        let (text, ..) = measured_file(c, &format!("start: teeth(driver: {j}, driven: {k})"));
        let by_teeth = motion(&prepare("rt.ron", &text).unwrap(), &m1, &m2);
        assert_same_motion(&touching, &by_teeth, &format!("{c:?}: teeth({j}, {k})"));
        events = events.max(touching.1.len());
        match &reference {
            None => reference = Some((touching, by_teeth)),
            Some((t, b)) => {
                assert_same_motion(t, &touching, &format!("{c:?}: touching"));
                assert_same_motion(b, &by_teeth, &format!("{c:?}: teeth"));
            }
        }
    }
    // The pair must have events, or their tooth numbers would go unchecked.
    assert!(events > 0, "the known pair ran without an event");
}

/// The example's mesh and its touching start angle.
fn example_start() -> (Prepared, f64) {
    let p = prepare("x.ron", EXAMPLE).unwrap();
    let theta0 = p
        .mesh
        .solve(0.0..=0.01, p.start, Solve::path())
        .theta_at(0.0);
    (p, theta0)
}

/// The example with `start` added.
fn example_with(start: &str) -> String {
    let end = EXAMPLE.rfind(')').unwrap();
    format!("{}    {start},\n)", &EXAMPLE[..end])
}

#[test]
fn start_touching_is_todays_start() {
    let (p, theta0) = example_start();
    assert_eq!(p.start, Start::Touching(0.0));
    // At rest against a driver tooth: one obstacle ends exactly there, and nothing overlaps.
    let mut obs = Vec::new();
    p.mesh.obstacles(0.0, theta0 - 0.1, theta0 + 0.1, &mut obs);
    assert!(obs.iter().any(|o| o.hi == theta0), "{obs:?}");
    assert_eq!(p.mesh.next_free(0.0, theta0, false), Some(theta0));
    // A file written before the conventions existed keeps its meaning, bit for bit: the
    // example's gears are the ones the loader built then.
    let ideal: Vec<f64> = (0..50).map(|k| TAU * f64::from(k) / 50.0).collect();
    let then = |e: Vec2| Gear::new(200.0, 180.0, ideal.clone(), e).unwrap();
    assert_eq!(p.mesh.driver(), &then(Vec2::zeros()));
    assert_eq!(p.mesh.driven(), &then(Vec2::new(1.5, 0.5)));
    assert_eq!(p.driven.user(7), 7);
    // Written out, `touching` is the default.
    let q = prepare("x.ron", &example_with("start: touching")).unwrap();
    assert_eq!(q.start, Start::Touching(0.0));
}

#[test]
fn start_at_rest_stands_still_until_the_driver_arrives() {
    let (p, touching) = example_start();
    // A little ahead of the touching position: free, with the pushing tooth behind it.
    let theta_deg = deg(touching) + 0.2;
    let q = prepare(
        "x.ron",
        &example_with(&format!("start: at_rest(theta_deg: {theta_deg:?})")),
    )
    .unwrap();
    let theta0 = theta_deg.to_radians();
    assert_eq!(q.start, Start::At(theta0));
    let traj = q.mesh.solve(0.0..=0.2, q.start, Solve::path());
    let arrives = p.mesh.first_touch(theta0, 0.0, 0.2).unwrap();
    assert!(arrives > 1e-4, "{arrives}");
    assert_eq!(traj.theta_at(0.0), theta0);
    assert_eq!(traj.theta_at(0.999 * arrives), theta0);
    assert!(traj.theta_at(arrives + 1e-3) > theta0 + 1e-6);
    // Behind the touching position it would overlap the pushing tooth: refused.
    let behind = deg(touching) - 0.5;
    let e = prepare(
        "m.ron",
        &example_with(&format!("start: at_rest(theta_deg: {behind:?})")),
    )
    .err()
    .unwrap()
    .to_string();
    assert!(
        e.starts_with("m.ron: start.theta_deg: the driven gear at rest at theta = ")
            && e.contains("overlaps a driver tooth at start_deg = 0"),
        "{e}"
    );
    let e = prepare("m.ron", &example_with("start: at_rest(theta_deg: inf)"))
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        e,
        "m.ron: start.theta_deg: must be a finite number of degrees"
    );
}

#[test]
fn start_on_named_teeth_puts_them_in_contact() {
    // At φ = 0 driver tooth 0 points at the driven gear and driven tooth 0 at the driver.
    let q = prepare("x.ron", &example_with("start: teeth(driver: 0, driven: 0)")).unwrap();
    let Start::At(theta0) = q.start else {
        panic!("{:?}", q.start)
    };
    let o = q.mesh.obstacle(0.0, 0, 0).unwrap();
    assert_eq!(theta0, o.hi);
    assert!(theta0.abs() < PI);
    // Driver tooth 0 pushes driven tooth 0 as the driver turns.
    let traj = q.mesh.solve(0.0..=0.05, q.start, Solve::path());
    assert_eq!(traj.theta_at(0.0), theta0);
    match &traj.segments()[0].motion {
        contact::Motion::Push(pairs) => assert!(pairs.contains(&(0, 0)), "{pairs:?}"),
        other => panic!("{other:?}"),
    }
    assert!(traj.theta_at(0.05) > theta0);
    // Any driven tooth can be turned onto driver tooth 0: tooth 20 is 20 pitches further on
    // (give or take the driven gear's eccentricity), within half a turn of θ = 0.
    let r = prepare(
        "x.ron",
        &example_with("start: teeth(driver: 0, driven: 20)"),
    )
    .unwrap();
    let Start::At(other) = r.start else {
        panic!("{:?}", r.start)
    };
    assert!(
        (other - theta0 - 20.0 * TAU / 50.0).abs() < 0.03 && other.abs() < PI,
        "{other} {theta0}"
    );
    assert_eq!(other, r.mesh.obstacle(0.0, 0, 20).unwrap().hi);
    let bad = |start: &str| match prepare("m.ron", &example_with(start)) {
        Ok(p) => panic!("{start} accepted: {:?}", p.start),
        Err(e) => e.to_string(),
    };
    assert_eq!(
        bad("start: teeth(driver: 50, driven: 0)"),
        "m.ron: start.driver: must be a driver tooth, 0 to 49 (got 50)"
    );
    assert_eq!(
        bad("start: teeth(driver: 0, driven: 70)"),
        "m.ron: start.driven: must be a driven tooth, 0 to 49 (got 70)"
    );
    // Tooth 25 is on the far side of the driver.
    let e = bad("start: teeth(driver: 25, driven: 0)");
    assert!(
        e.starts_with("m.ron: start: driver tooth 25 cannot touch driven tooth 0 at start_deg = 0 (driver teeth that can touch there: 0, 1,"),
        "{e}"
    );
    // Tooth 1 has passed the line of centres: driven tooth 0 resting on it would overlap
    // tooth 0.
    let e = bad("start: teeth(driver: 1, driven: 0)");
    assert!(
        e.starts_with("m.ron: start: driven tooth 0 resting against driver tooth 1 overlaps a driver tooth at start_deg = 0: the nearest free driven angle ahead is "),
        "{e}"
    );
    assert!(bad("start: teeth(driver: 0)").starts_with("m.ron: line "));
    assert!(bad("start: sideways").starts_with("m.ron: line "));
}

#[test]
fn conventions_are_refused_with_the_field_and_rule() {
    let bad = |driven: &str| {
        let text = format!(
            "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: {driven}, clearance_percent: Some(40.0))"
        );
        prepare("m.ron", &text).err().unwrap().to_string()
    };
    assert_eq!(
        bad(
            "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, eccentricity: Some((0.1, 0.0)), arbor: Some((offset: 0.1, angle_deg: 0.0)))"
        ),
        "m.ron: driven.arbor: give at most one of eccentricity and arbor (they are the same offset)"
    );
    assert_eq!(
        bad(
            "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: -0.1, angle_deg: 0.0)))"
        ),
        "m.ron: driven.arbor.offset: must be a finite length >= 0 (got -0.1)"
    );
    assert_eq!(
        bad(
            "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: 0.1, angle_deg: NaN)))"
        ),
        "m.ron: driven.arbor.angle_deg: must be a finite number of degrees"
    );
    assert!(
        bad("(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: 9.5, angle_deg: 30.0)))")
            .starts_with("m.ron: driven.arbor: must lie inside the root circle")
    );
    assert!(
        bad("(teeth: 20, tip_radius: 10.0, root_radius: 9.0, sense: backwards)")
            .starts_with("m.ron: line 1")
    );
    assert!(
        bad("(teeth: 20, tip_radius: 10.0, root_radius: 9.0, eccentricity_frame: scan)")
            .starts_with("m.ron: line 1")
    );
    assert!(
        bad("(teeth: 20, tip_radius: 10.0, root_radius: 9.0, arbor: Some((offset: 0.1, angel_deg: 3.0)))")
            .starts_with("m.ron: line 1")
    );
    // Out of order in the user's own list: named by the user's index, whatever the sense.
    assert_eq!(
        bad(
            "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, sense: own, tips_deg: Some([0.0, 200.0, 100.0]))"
        ),
        "m.ron: driven.tips_deg[2]: tip angles must be strictly increasing"
    );
}

#[test]
fn own_sense_mirrors_the_driven_gear_and_numbers_its_teeth_as_written() {
    let file = |driven: &str| {
        format!(
            "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: {driven}, clearance_percent: Some(40.0))"
        )
    };
    let own = prepare(
        "m.ron",
        &file("(teeth: 4, tip_radius: 10.0, root_radius: 9.0, sense: own, tips_deg: Some([10.0, 100.0, 185.0, 280.0]), eccentricity: Some((0.2, 0.1)))"),
    )
    .unwrap();
    // Mirrored: the same wheel with the angles negated, the list reversed.
    let driver = prepare(
        "m.ron",
        &file("(teeth: 4, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([-280.0, -185.0, -100.0, -10.0]), eccentricity: Some((0.2, -0.1)))"),
    )
    .unwrap();
    assert_eq!(own.mesh.driven(), driver.mesh.driven());
    // The user's tooth 0 (at 10° in its own sense) is the solver's last tooth.
    assert_eq!(own.driven.solver(0), 3);
    assert_eq!(own.driven.user(3), 0);
    assert_eq!(own.driven.user(-1), 0);
    assert_eq!(own.driven.user(4), 3);
    assert_eq!(driver.driven.user(-1), 3);
    assert_eq!(own.driver.user(21), 1);
    // The world frame: at θ = 0 the driven gear's frame is the world's turned by π.
    let world = prepare(
        "m.ron",
        &file("(teeth: 4, tip_radius: 10.0, root_radius: 9.0, sense: own, tips_deg: Some([10.0, 100.0, 185.0, 280.0]), eccentricity: Some((-0.2, 0.1)), eccentricity_frame: world)"),
    )
    .unwrap();
    assert_eq!(world.mesh.driven(), own.mesh.driven());
    // Polar: 0.5 at 90° in the own sense is (0, −0.5) in the solver's frame.
    let polar_form = prepare(
        "m.ron",
        &file("(teeth: 4, tip_radius: 10.0, root_radius: 9.0, sense: own, arbor: Some((offset: 0.5, angle_deg: 90.0)))"),
    )
    .unwrap();
    let e = polar_form.mesh.driven().rotation_centre();
    assert!((e - Vec2::new(0.0, -0.5)).norm() < 1e-15, "{e}");
}

#[test]
fn check_picture_labels_what_the_user_entered() {
    let (c, ..) = measured_file(
        Convention {
            own: true,
            world: false,
            polar: true,
        },
        "",
    );
    let p = prepare("rt.ron", &c).unwrap();
    let traj = p.mesh.solve(0.0..=0.1, p.start, Solve::path());
    let svg = check_svg("my <pair>.ron", &p, (0.0, traj.theta_at(0.0)));
    for words in [
        "Check of my &lt;pair&gt;.ron: both gears at phi = 0 and theta = 0",
        ">driver zero ray: phi = 0</tspan>",
        ">driven zero ray: theta = 0</tspan>",
        "(dashed: the direction of tips_deg = 0)",
        ">driver tooth 0</tspan>",
        ">driver tooth 1</tspan>",
        ">driven tooth 0</tspan>",
        ">driven tooth 1</tspan>",
        "id=\"driven-tooth-0\"",
        ">driver turns this way:</tspan>",
        ">phi increases</tspan>",
        ">driven gear turns this way:</tspan>",
        ">theta increases</tspan>",
        "x: line of centres, driver arbor -&gt; driven arbor",
        "y: 90 deg from x in the driver's turning sense",
        "driver: 17 teeth, tips_deg run counter-clockwise here (sense: own)",
        "driven: 23 teeth, tips_deg run clockwise here (sense: own)",
        "(start: touching)",
    ] {
        assert!(svg.contains(words), "{words} missing from\n{svg}");
    }
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert_eq!(svg.matches("<polygon id=").count(), 2);
    // The insets: the arbor against the tip-circle centre, exaggerated by a stated factor.
    let factor = exaggeration(&[
        (
            p.mesh.driver().rotation_centre().norm(),
            p.mesh.driver().max_tip_radius(),
        ),
        (
            p.mesh.driven().rotation_centre().norm(),
            p.mesh.driven().max_tip_radius(),
        ),
    ]);
    assert!(
        svg.contains(&format!(
            "<g class=\"inset\" data-exaggeration=\"{factor}\">"
        )),
        "{svg}"
    );
    assert!(
        svg.contains(&format!("offsets exaggerated x{factor}")),
        "{svg}"
    );
}

#[test]
fn insets_exaggerate_small_offsets_by_round_factors() {
    // 0.35 mm on a 13.2 mm wheel: 0.6 / 0.0265 = 22.6, so 20 times.
    assert_eq!(exaggeration(&[(0.35, 13.2), (0.0, 16.0)]), 20.0);
    assert_eq!(exaggeration(&[(0.1, 200.0)]), 1000.0);
    assert_eq!(exaggeration(&[(1.58, 200.0)]), 50.0);
    // None, or large enough to see: drawn as they are.
    assert_eq!(exaggeration(&[(0.0, 10.0), (0.0, 5.0)]), 1.0);
    assert_eq!(exaggeration(&[(4.0, 10.0)]), 1.0);
    assert_eq!(exaggeration(&[]), 1.0);
}

/// The ```ron block after `marker` in the README, without its `driven: ` and final comma.
fn readme_block(marker: &str) -> String {
    let readme = include_str!("../../../README.md");
    let at = readme.find(marker).unwrap();
    let body = &readme[at..];
    let start = body.find("```ron\n").unwrap() + "```ron\n".len();
    let end = start + body[start..].find("```").unwrap();
    let block = body[start..end].trim();
    block
        .strip_prefix("driven: ")
        .unwrap()
        .strip_suffix(',')
        .unwrap()
        .to_string()
}

#[test]
fn the_readmes_measured_wheel_is_one_gear_in_both_spellings() {
    let file = |driven: String| {
        format!(
            "(driver: (teeth: 30, tip_radius: 26.4, root_radius: 25.3), driven: {driven}, clearance_percent: Some(40.0))"
        )
    };
    let own = prepare(
        "README.md",
        &file(readme_block("<!-- measured wheel: own sense -->")),
    )
    .unwrap();
    let driver = prepare(
        "README.md",
        &file(readme_block("<!-- measured wheel: driver sense -->")),
    )
    .unwrap();
    let (a, b) = (own.mesh.driven(), driver.mesh.driven());
    assert_eq!(a.tip_angles(), b.tip_angles());
    let gap = (a.rotation_centre() - b.rotation_centre()).norm();
    assert!(gap < 1e-6, "the arbors are {gap} apart");
    // The scan's tooth 0 is the driver-sense spelling's tooth 14.
    assert_eq!(own.driven.user(driver.driven.solver(14)), 0);
    assert_eq!(own.driven.user(driver.driven.solver(0)), 14);
}

/// `--set drive=other` runs the file's driven gear as the driver, both gears still turning their
/// own way: the run is the mirrored swap of the file's mesh, its teeth numbered as the file numbers
/// them; `either` and a start that rests the driven gear against its driver are refused.
#[test]
fn the_driven_gear_of_a_pair_file_can_drive() {
    let run = |sets: &[(&str, &str)]| {
        let (exp, ctx) = crate::context("pair", 2025, 1, sets).unwrap();
        (exp.run)(&ctx, ctx.engine()).map(|o| o.report)
    };
    let listed = run(&[]).unwrap();
    let other = run(&[("drive", "other")]).unwrap();
    assert!(
        other.tables[0].title.contains("drive: other"),
        "{}",
        other.tables[0].title
    );
    assert!(listed.tables[0].title.contains("drive: listed"));
    let p = prepare("x.ron", EXAMPLE).unwrap();
    let (n1, n2) = (p.mesh.driver().teeth(), p.mesh.driven().teeth());
    let q = prepare("x.ron", EXAMPLE)
        .unwrap()
        .other_driving("x.ron")
        .unwrap();
    assert_eq!(q.mesh.driver(), &p.mesh.driven().mirrored());
    assert_eq!(q.mesh.driven(), &p.mesh.driver().mirrored());
    // Each gear keeps the file's numbering: the solver's tooth k of the mirrored gear is the
    // file's tooth N - 1 - k (through the file's own numbering of that gear).
    for k in 0..n2 as i64 {
        assert_eq!(q.driver.user(k), p.driven.user(n2 as i64 - 1 - k));
    }
    for k in 0..n1 as i64 {
        assert_eq!(q.driven.user(k), p.driver.user(n1 as i64 - 1 - k));
    }
    let e = run(&[("drive", "either")]).err().unwrap();
    assert_eq!(e.exit_code(), 2);
    assert!(e.to_string().contains("drive"), "{e}");
    let at_rest = EXAMPLE.replacen(
        "start_deg:",
        "start: at_rest(theta_deg: 3.6),\n    start_deg:",
        1,
    );
    let e = prepare("x.ron", &at_rest)
        .unwrap()
        .other_driving("x.ron")
        .err()
        .unwrap();
    assert!(
        e.to_string().contains("x.ron: start: must be `touching`"),
        "{e}"
    );
}

/// With its driven gear driving, a pair file's samples are of that gear's angle, and checked
/// against its own pitch: a step fine enough for the file's driver but not for its driven gear
/// is refused under `drive=other` only.
#[test]
fn the_driving_gears_pitch_bounds_the_samples() {
    let text = "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 60, tip_radius: 30.0, root_radius: 29.0), clearance_percent: Some(40.0), sample_deg: 4.0)";
    let p = prepare("x.ron", text).unwrap();
    let (n1, n2) = (p.mesh.driver().teeth(), p.mesh.driven().teeth());
    assert!(
        360.0 / n1 as f64 / 4.0 >= 4.0,
        "the file's driver takes 4 deg steps"
    );
    assert!(360.0 / n2 as f64 / 4.0 < 4.0, "its driven gear does not");
    let e = p.other_driving("x.ron").err().unwrap();
    assert!(
        e.to_string().contains("sample_deg: must be at most")
            && e.to_string().contains(&format!("360/{n2}")),
        "{e}"
    );
}

/// The labels of a check picture's drawing (above its insets): (x, y, anchor, font size, text).
fn drawing_labels(svg: &str) -> Vec<((f64, f64), Anchor, f64, String)> {
    let drawing = &svg[..svg.find("<g class=\"inset\"").unwrap()];
    let attr = |tag: &str, name: &str| -> Option<String> {
        let at = tag.find(&format!(" {name}=\""))? + name.len() + 3;
        Some(tag[at..at + tag[at..].find('"')?].to_owned())
    };
    let mut labels = Vec::new();
    for piece in drawing.split("<text").skip(1) {
        let (tag, rest) = piece.split_once('>').unwrap();
        // A label's lines are its tspans.
        let inner = &rest[..rest.find("</text>").unwrap()];
        let lines: Vec<&str> = inner
            .split("<tspan")
            .filter_map(|t| {
                t.split_once('>')
                    .map(|(_, l)| l.trim_end_matches("</tspan>"))
            })
            .filter(|l| !l.is_empty())
            .collect();
        let text = if lines.is_empty() {
            inner.to_owned()
        } else {
            lines.join("\n")
        }
        .replace("&gt;", ">")
        .replace("&lt;", "<")
        .replace("&amp;", "&");
        let num = |n: &str| attr(tag, n).map(|v| v.parse::<f64>().unwrap());
        let anchor = match attr(tag, "text-anchor").as_deref() {
            Some("middle") => Anchor::Middle,
            Some("end") => Anchor::End,
            _ => Anchor::Start,
        };
        let font = num("font-size").unwrap_or(13.0);
        labels.push(((num("x").unwrap(), num("y").unwrap()), anchor, font, text));
    }
    labels
}

/// A gear outline of the check picture as its edges, px.
fn outline_edges(svg: &str, id: &str) -> Vec<Segment> {
    let at = svg
        .find(&format!("<polygon id=\"{id}\" points=\""))
        .unwrap()
        + id.len()
        + 23;
    let points: Vec<(f64, f64)> = svg[at..at + svg[at..].find('"').unwrap()]
        .split(' ')
        .map(|p| {
            let (x, y) = p.split_once(',').unwrap();
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect();
    edges(&points)
}

#[test]
fn check_picture_labels_keep_off_the_teeth_and_each_other() {
    // The example (two 50-tooth gears), the known 17:23 eccentric pair, and a small pinion on a
    // large wheel, where the labels have least room.
    let (small_large, ..) = measured_file(
        Convention {
            own: false,
            world: false,
            polar: false,
        },
        "",
    );
    let pinion = EXAMPLE.replacen(
        "teeth: 50,\n        tip_radius: 200.0,   // R, any length unit\n        root_radius: 180.0,",
        "teeth: 15,\n        tip_radius: 60.0,\n        root_radius: 40.0,",
        1,
    );
    assert_ne!(pinion, EXAMPLE, "the pinion replaces the example's driver");
    for (name, text) in [
        ("example", EXAMPLE.to_owned()),
        ("17:23", small_large),
        ("pinion", pinion),
    ] {
        let p = prepare("x.ron", &text).unwrap();
        let svg = check_svg(name, &p, (0.0, 0.0));
        let labels = drawing_labels(&svg);
        assert!(labels.len() >= 11, "{name}: {} labels", labels.len());
        let boxes: Vec<_> = labels
            .iter()
            .map(|(at, anchor, font, t)| (text_box(*at, *anchor, t, *font), t))
            .collect();
        let teeth = [
            outline_edges(&svg, "driver-outline"),
            outline_edges(&svg, "driven-outline"),
        ]
        .concat();
        for (i, (b, t)) in boxes.iter().enumerate() {
            let crossed = teeth
                .iter()
                .filter(|(a, c)| segment_meets(b, *a, *c))
                .count();
            assert_eq!(
                crossed, 0,
                "{name}: label {t:?} crosses {crossed} tooth edges"
            );
            for (o, u) in &boxes[i + 1..] {
                assert!(!b.intersects(o), "{name}: labels {t:?} and {u:?} overlap");
            }
        }
    }
}
