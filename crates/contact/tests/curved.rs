//! Curved (circular-arc) flanks against closed forms: the straight-flank limit as the sagitta
//! goes to 0 (the straight solver is itself checked against Thorndike in `ideal.rs`), the
//! direction in which the sagitta moves a contact, and one vertex-on-arc contact worked out by
//! hand.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::{PI, TAU};

use contact::{Mesh, Solve, Start};
use geometry::{Gear, Vec2};

/// The paper's N = 8 example (R = 200, r = 100, D = 310), the driver with flank sagitta
/// `s_driver` and the driven gear with `s_driven`.
fn curved_paper_example(s_driver: f64, s_driven: f64) -> Mesh {
    let g = |s: f64| {
        Gear::ideal(8, 200.0, 100.0)
            .unwrap()
            .with_flank_sagitta(s)
            .unwrap()
    };
    Mesh::new(g(s_driver), g(s_driven), 310.0).unwrap()
}

/// A mechanism-sized mesh (27 on 223 teeth, h = 1.1 mm, G = 40 %) with tooth errors, both gears
/// with flank sagitta `s`.
fn small_mesh(s: f64) -> Mesh {
    let (n1, n2) = (27, 223);
    let (r2, h) = (51.95, 1.1);
    let r1 = r2 * n1 as f64 / n2 as f64;
    // Deterministic, uneven tips: the limit must hold off the ideal geometry too.
    let tips = |n: usize| -> Vec<f64> {
        (0..n)
            .map(|k| TAU * (k as f64 + 0.04 * (k as f64 * 2.3).sin()) / n as f64)
            .collect()
    };
    let driver = Gear::new(r1, r1 - h, tips(n1), Vec2::new(0.05, 0.0))
        .unwrap()
        .with_flank_sagitta(s)
        .unwrap();
    let driven = Gear::new(r2, r2 - h, tips(n2), Vec2::zeros())
        .unwrap()
        .with_flank_sagitta(s)
        .unwrap();
    Mesh::new(driver, driven, geometry::centre_distance(r1, r2, h, 40.0)).unwrap()
}

#[test]
fn vanishing_sagitta_gives_the_straight_trajectory() {
    let straight = small_mesh(0.0);
    let span = 3.0 * TAU / 27.0;
    let reference = straight.solve(0.0..=span, Start::Touching(0.0), Solve::path());
    for s in [1e-9, -1e-9] {
        let curved = small_mesh(s).solve(0.0..=span, Start::Touching(0.0), Solve::path());
        assert_eq!(curved.jams(), reference.jams(), "s = {s}");
        for i in 0..=300 {
            let phi = span * f64::from(i) / 300.0;
            let (a, b) = (curved.theta_at(phi), reference.theta_at(phi));
            // An arc of sagitta 1e-9 mm on a 1.5 mm chord has a radius of about 3e8 mm: its
            // roots carry rounding of about 1e-16 of that, some 1e-9 rad here.
            assert!((a - b).abs() < 1e-7, "s = {s}, phi = {phi}: {a} vs {b}");
        }
    }
}

#[test]
fn convex_teeth_touch_earlier_and_push_further() {
    // The driven gear stands 0.002 rad ahead of where the straight driver pushes it at φ = 0,
    // clear of every driver tooth for all these sagittas (checked); the driver turns forwards
    // until a tooth touches. A convex flank stands proud of the straight one, so the first
    // touch comes sooner the larger the sagitta; and at a fixed φ the same pair pushes the
    // driven gear further.
    let sagittas = [-3.0, -1.5, -0.5, 0.0, 0.5, 1.5, 3.0];
    let theta = small_mesh(0.0)
        .solve(0.0..=0.0, Start::Touching(0.0), Solve::path())
        .theta_at(0.0)
        + 0.002;
    let mut obstacles = Vec::new();
    let touches: Vec<f64> = sagittas
        .iter()
        .map(|&s| {
            let m = small_mesh(s * 1e-2);
            m.obstacles(0.0, theta, theta, &mut obstacles);
            assert!(obstacles.is_empty(), "s = {s}: {obstacles:?}");
            m.first_touch(theta, 0.0, 0.2).unwrap()
        })
        .collect();
    let pushes: Vec<f64> = sagittas
        .iter()
        .map(|&s| curved_paper_example(s, s).obstacle(0.0, 0, 0).unwrap().hi)
        .collect();
    for w in touches.windows(2) {
        assert!(w[1] < w[0], "first touch not earlier: {touches:?}");
    }
    for w in pushes.windows(2) {
        assert!(w[1] > w[0], "push not further: {pushes:?}");
    }
}

#[test]
fn driver_tip_on_a_driven_arc_matches_the_law_of_cosines() {
    // Paper example at φ = 0: driver tip 0 sits at (200, 0), 110 mm from the driven centre, and
    // pushes driven tooth 0 on its flank from tip 0 (200, 0) to valley 0 (100 at 22.5°). In the
    // driven frame the driver tip stands at 110∠θ (the driven gear turns by π − θ). The driver's
    // flanks stay straight, so that its tip is the only part of it that can touch.
    let (t, v) = (Vec2::new(200.0, 0.0), geometry::polar(100.0, PI / 8.0));
    let chord = (v - t).norm();
    for s in [-4.0, 2.0, 6.0] {
        // The arc's centre by hand: on the perpendicular bisector of the chord, (c²/4 − s²)/(2s)
        // from the chord, away from the bulge (the bulge is to the right of t → v, out of the
        // tooth, for s > 0); its radius (c²/4 + s²)/(2|s|).
        let d = (v - t) / chord;
        let out = Vec2::new(d.y, -d.x);
        let centre = 0.5 * (t + v) - out * ((chord * chord / 4.0 - s * s) / (2.0 * s));
        let radius = (chord * chord / 4.0 + s * s) / (2.0 * s.abs());
        // Law of cosines in the triangle (driven centre, arc centre, contact): the contact is
        // 110 from the driven centre and `radius` from the arc centre.
        let (rho, dist) = (110.0, centre.norm());
        let gamma = ((rho * rho + dist * dist - radius * radius) / (2.0 * rho * dist)).acos();
        let base = centre.y.atan2(centre.x);
        // Of the two crossings, the contact lies on the flank, between tip (0°) and valley (22.5°).
        let want = [base - gamma, base + gamma]
            .into_iter()
            .find(|a| (0.0..PI / 8.0).contains(a))
            .unwrap();
        let got = curved_paper_example(0.0, s).obstacle(0.0, 0, 0).unwrap().hi;
        assert!(
            (got - want).abs() < 1e-12,
            "s = {s}: solver {} deg, closed form {} deg",
            got.to_degrees(),
            want.to_degrees()
        );
    }
    // And the straight limit is Thorndike's θ'(0) = 17.955 387 657 7°.
    let straight = curved_paper_example(0.0, 0.0)
        .obstacle(0.0, 0, 0)
        .unwrap()
        .hi;
    assert!((straight.to_degrees() - 17.955_387_657_7).abs() < 1e-9);
}
