#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;

/// The mirror image is the reflected outline, renumbered, and a valid gear by every rule of
/// its constructors; mirrored twice it is the gear again.
#[test]
fn a_mirrored_gear_is_the_reflected_outline() {
    let tips = vec![0.1, 1.9, 4.2, 5.0];
    let valleys = vec![0.7, 3.5, 4.5, 5.9];
    let g = Gear::with_valleys(10.0, 9.0, tips, valleys, Vec2::new(0.3, 0.2))
        .unwrap()
        .with_radii(vec![10.1, 9.9, 10.0, 10.2], vec![9.0, 8.9, 9.1, 8.8])
        .unwrap()
        .with_flank_sagitta(0.05)
        .unwrap();
    let m = g.mirrored();
    let reflect = |v: Vec2| Vec2::new(v.x, -v.y);
    let n = g.teeth() as i64;
    for k in 0..n {
        assert!(
            (m.tip(k) - reflect(g.tip(n - 1 - k))).norm() < 1e-12,
            "tip {k}"
        );
        assert!(
            (m.valley(k) - reflect(g.valley((2 * n - 2 - k) % n))).norm() < 1e-12,
            "valley {k}"
        );
    }
    assert_eq!(m.rotation_centre(), Vec2::new(0.3, -0.2));
    assert_eq!(m.flank_sagitta(), 0.05);
    // Every rule the constructors check holds for the image.
    let rebuilt = Gear::with_valleys(
        m.tip_radius(),
        m.root_radius(),
        m.tip_angles().to_vec(),
        m.valley_angles().to_vec(),
        m.rotation_centre(),
    )
    .unwrap()
    .with_radii(
        (0..n).map(|k| m.tip_radius_of(k)).collect(),
        (0..n).map(|k| m.root_radius_of(k)).collect(),
    )
    .unwrap()
    .with_flank_sagitta(m.flank_sagitta())
    .unwrap();
    assert_eq!(rebuilt, m);
    let back = m.mirrored();
    assert_eq!(back.tip_angles(), g.tip_angles());
    for (a, b) in back.valley_angles().iter().zip(g.valley_angles()) {
        assert!((a - b).abs() < 1e-12);
    }
    let ideal = Gear::ideal(8, 200.0, 100.0).unwrap().mirrored();
    assert!((ideal.tip(0) - polar(200.0, -7.0 * TAU / 8.0)).norm() < 1e-12);
}

#[test]
fn ideal_gear_has_valleys_midway() {
    let g = Gear::ideal(8, 200.0, 100.0).unwrap();
    assert_eq!(g.teeth(), 8);
    assert!((g.valley_angles()[7] - (7.5 * TAU / 8.0)).abs() < 1e-15);
    assert!((g.tip(9) - g.tip(1)).norm() < 1e-12);
    assert!((g.tip_angle(9) - g.tip_angle(1) - TAU).abs() < 1e-15);
}

#[test]
fn constructors_name_the_rule() {
    let e = Gear::ideal(2, 10.0, 9.0).unwrap_err();
    assert_eq!(e.field, "teeth");
    let e = Gear::ideal(8, 10.0, 10.0).unwrap_err();
    assert_eq!(e.field, "root_radius");
    assert!(e.rule.contains("less than tip_radius"));
    let e = Gear::ideal(8, f64::NAN, 1.0).unwrap_err();
    assert_eq!(e.field, "tip_radius");
    let e = Gear::new(10.0, 9.0, vec![0.0, 2.0, 1.0], Vec2::zeros()).unwrap_err();
    assert_eq!(e.field, "tips[2]");
    let e = Gear::new(10.0, 9.0, vec![0.0, 2.0, 6.5], Vec2::zeros()).unwrap_err();
    assert!(e.rule.contains("one turn"));
    let e = Gear::new(10.0, 9.0, vec![0.0, 2.0, 4.0], Vec2::new(9.5, 0.0)).unwrap_err();
    assert_eq!(e.field, "rotation_centre");
}

#[test]
fn explicit_valleys_are_kept_and_checked() {
    let tips = vec![0.0, 2.0, 4.0];
    let g =
        Gear::with_valleys(10.0, 9.0, tips.clone(), vec![0.5, 3.9, 6.0], Vec2::zeros()).unwrap();
    assert_eq!(g.valley_angles(), [0.5, 3.9, 6.0]);
    assert!((g.valley(-1) - polar(9.0, 6.0 - TAU)).norm() < 1e-12);
    assert_eq!(g.outline()[3], polar(9.0, 3.9));
    let mid = Gear::new(10.0, 9.0, tips.clone(), Vec2::zeros()).unwrap();
    let same = Gear::with_valleys(
        10.0,
        9.0,
        tips.clone(),
        mid.valley_angles().to_vec(),
        Vec2::zeros(),
    )
    .unwrap();
    assert_eq!(same, mid);
    let bad = |valleys: Vec<f64>| {
        Gear::with_valleys(10.0, 9.0, tips.clone(), valleys, Vec2::zeros()).unwrap_err()
    };
    let e = bad(vec![0.5, 3.9]);
    assert_eq!(e.field, "valleys");
    assert!(e.rule.contains("one valley per tooth"), "{e}");
    let e = bad(vec![0.5, 2.0, 5.0]);
    assert_eq!(e.field, "valleys[1]");
    assert!(
        e.rule.contains("strictly between tips[1] and tips[2]"),
        "{e}"
    );
    let e = bad(vec![0.5, 3.0, 6.3]);
    assert_eq!(e.field, "valleys[2]");
    assert!(e.rule.contains("tips[0] + 2π"), "{e}");
    assert_eq!(bad(vec![-0.1, 3.0, 5.0]).field, "valleys[0]");
    assert_eq!(bad(vec![0.5, f64::NAN, 5.0]).field, "valleys[1]");
    // Tip rules come first, as in `Gear::new`.
    let e = Gear::with_valleys(10.0, 9.0, vec![0.0, 2.0, 1.0], vec![1.0; 3], Vec2::zeros())
        .unwrap_err();
    assert_eq!(e.field, "tips[2]");
}

#[test]
fn explicit_valleys_survive_serialization() {
    let g = Gear::with_valleys(
        10.0,
        9.0,
        vec![0.0, 2.0, 4.0],
        vec![0.5, 3.9, 6.0],
        Vec2::zeros(),
    )
    .unwrap();
    let json = serde_json::to_string(&g).unwrap();
    let back: Gear = serde_json::from_str(&json).unwrap();
    assert_eq!(back, g);
}

#[test]
fn per_tooth_radii_are_kept_and_checked() {
    let g = Gear::new(10.0, 9.0, vec![0.0, 2.0, 4.0], Vec2::new(0.5, 0.0)).unwrap();
    assert_eq!((g.max_tip_radius(), g.min_root_radius()), (10.0, 9.0));
    assert_eq!(g.tip_radius_of(4), 10.0);
    let r = g
        .clone()
        .with_radii(vec![10.0, 10.5, 9.8], vec![9.1, 8.7, 9.0])
        .unwrap();
    assert_eq!((r.tip_radius(), r.root_radius()), (10.0, 9.0));
    assert_eq!((r.max_tip_radius(), r.min_root_radius()), (10.5, 8.7));
    assert_eq!((r.tip_radius_of(4), r.root_radius_of(-1)), (10.5, 9.0));
    assert_eq!(r.outline()[2], polar(10.5, 2.0));
    assert_eq!(r.valley(1), polar(8.7, 3.0));
    let back: Gear = serde_json::from_str(&serde_json::to_string(&r).unwrap()).unwrap();
    assert_eq!(back, r);
    // A round gear serializes as before (no radii lists).
    assert!(!serde_json::to_string(&g).unwrap().contains("radii"));
    let bad = |tips: Vec<f64>, roots: Vec<f64>| g.clone().with_radii(tips, roots).unwrap_err();
    let e = bad(vec![10.0; 2], vec![9.0; 3]);
    assert_eq!(e.field, "tip_radii");
    assert!(e.rule.contains("one radius per tooth"), "{e}");
    assert_eq!(
        bad(vec![10.0; 3], vec![9.0, f64::NAN, 9.0]).field,
        "root_radii[1]"
    );
    assert_eq!(
        bad(vec![10.0, -1.0, 10.0], vec![9.0; 3]).field,
        "tip_radii[1]"
    );
    let e = bad(vec![10.0, 10.0, 8.9], vec![9.0, 9.0, 8.95]);
    assert_eq!(e.field, "root_radii[1]");
    assert!(e.rule.contains("tip_radii[2]"), "{e}");
    let e = bad(vec![8.9, 10.0, 10.0], vec![9.0, 8.0, 8.0]);
    assert_eq!(e.field, "root_radii[0]");
    let e = bad(vec![10.0; 3], vec![9.0, 0.4, 9.0]);
    assert_eq!(e.field, "rotation_centre");
}

#[test]
fn enormous_tooth_counts_are_refused_before_allocating() {
    let e = Gear::ideal(1_000_000_000, 10.0, 9.0).unwrap_err();
    assert_eq!(e.field, "teeth");
    assert!(e.rule.contains("at most 100000"), "{e}");
    assert!(Gear::ideal(MAX_TEETH, 1e4, 9.9e3).is_ok());
    let tips: Vec<f64> = (0..=MAX_TEETH)
        .map(|k| TAU * k as f64 / (MAX_TEETH + 1) as f64)
        .collect();
    assert_eq!(
        Gear::new(1e4, 9.9e3, tips, Vec2::zeros())
            .unwrap_err()
            .field,
        "teeth"
    );
}

#[test]
fn arc_through_two_points_has_the_stated_sagitta() {
    let (a, b) = (Vec2::new(0.0, 0.0), Vec2::new(4.0, 0.0));
    for s in [0.5, -0.5, 1e-9, -1.0] {
        let arc = Arc::through(a, b, s);
        assert!(((arc.start - arc.centre).norm() - arc.radius).abs() < 1e-9 * arc.radius);
        assert!(((arc.end - arc.centre).norm() - arc.radius).abs() < 1e-9 * arc.radius);
        // The tooth is on the left of a -> b (y > 0): convex bulges to y < 0.
        let mid = arc.point(0.5);
        assert!(
            (mid - Vec2::new(2.0, -s)).norm() < 1e-9 * arc.radius.max(1.0),
            "{s}: {mid}"
        );
        assert!(arc.holds(mid, 0.0));
        // The circle's point opposite the arc's middle, and one past an end.
        assert!(!arc.holds(2.0 * arc.centre - mid, 0.0));
        let past = arc.centre + rotate(arc.start - arc.centre, -0.01 * arc.angular_extent().1);
        assert!(!arc.holds(past, 0.0), "{s}");
        assert_eq!(arc.is_convex(), s > 0.0);
    }
    // Chord 4, sagitta 1: radius (4 + 1)/2 = 2.5, centre 1.5 above the chord.
    let arc = Arc::through(a, b, 1.0);
    assert!((arc.radius - 2.5).abs() < 1e-15);
    assert!((arc.centre - Vec2::new(2.0, 1.5)).norm() < 1e-15);
    let (start, sweep) = arc.angular_extent();
    assert!((start - (-1.5f64).atan2(-2.0)).abs() < 1e-15);
    assert!((sweep - 2.0 * (0.8f64).asin()).abs() < 1e-12, "{sweep}");
    // Nearest and farthest points from the centre of the chord's far side.
    let (near, far) = arc.distance_range(Vec2::new(2.0, 10.0));
    assert!((near - 10.0f64.hypot(2.0)).abs() < 1e-12, "{near}");
    assert!((far - 11.0).abs() < 1e-12, "{far}");
}

#[test]
fn flank_sagitta_is_kept_checked_and_optional_in_serde() {
    let g = Gear::new(
        10.0,
        8.0,
        vec![0.0, 1.0, 2.0, 3.0, 4.0, 5.0],
        Vec2::new(0.3, 0.0),
    )
    .unwrap();
    assert_eq!(g.flank_sagitta(), 0.0);
    assert!(matches!(g.flank(2, 1), Flank::Segment { .. }));
    assert_eq!(g.drawn_outline(8), g.outline());
    let json = serde_json::to_string(&g).unwrap();
    assert!(!json.contains("sagitta"), "{json}");
    let c = g.clone().with_flank_sagitta(0.1).unwrap();
    assert_eq!(c.tip_angles(), g.tip_angles());
    assert_eq!(c.rotation_centre(), g.rotation_centre());
    assert_eq!(c.outline(), g.outline());
    let Flank::Arc(arc) = c.flank(2, 1) else {
        panic!("a curved flank")
    };
    assert_eq!((arc.start, arc.end), (c.tip(2), c.valley(2)));
    assert_eq!(c.drawn_outline(8).len(), 6 * 2 * 8);
    assert_eq!(c.drawn_outline(8)[8], c.valley(0));
    let back: Gear = serde_json::from_str(&serde_json::to_string(&c).unwrap()).unwrap();
    assert_eq!(back, c);
    assert_eq!(c.clone().with_flank_sagitta(0.0).unwrap(), g);
    // Per-tooth radii keep the sagitta, and check it again.
    let r = c.clone().with_radii(vec![10.0; 6], vec![7.5; 6]).unwrap();
    assert_eq!(r.flank_sagitta(), 0.1);
    let e = g.clone().with_flank_sagitta(f64::NAN).unwrap_err();
    assert_eq!(
        (e.field.as_str(), e.rule.as_str()),
        ("flank_sagitta", "must be a finite number")
    );
    let e = g.clone().with_flank_sagitta(2.0).unwrap_err();
    assert_eq!(e.field, "flank_sagitta");
    assert!(e.rule.contains("quarter of every flank's chord"), "{e}");
}

#[test]
fn sagitta_rules_name_what_would_cross() {
    // Slender teeth: 8 teeth, R = 200, r = 100. The tip angle is about 39°, the valley gap
    // about 84° and the base angles about 70°.
    let g = Gear::ideal(8, 200.0, 100.0).unwrap();
    let chord = (g.tip(0) - g.valley(0)).norm();
    let at_tip = {
        let (u, w) = (g.valley(-1) - g.tip(0), g.valley(0) - g.tip(0));
        (u.dot(&w) / (u.norm() * w.norm())).acos()
    };
    // Concave: the tip angle is the binding rule: 2·2·atan(2|s|/c) < tip angle.
    let limit = 0.5 * chord * (0.25 * at_tip).tan();
    assert!(g.clone().with_flank_sagitta(-0.99 * limit).is_ok());
    let e = g.clone().with_flank_sagitta(-1.01 * limit).unwrap_err();
    assert!(
        e.rule.contains("concave flanks of tooth 0 would cross"),
        "{e}"
    );
    // Convex: the gap is the binding rule, 2·2·atan(2s/c) < 84°.
    assert!(g.clone().with_flank_sagitta(0.15 * chord).is_ok());
    let e = g.clone().with_flank_sagitta(0.25 * chord).unwrap_err();
    assert!(
        e.rule.contains("convex flanks at valley 0 would cross"),
        "{e}"
    );
    // A low, wide tooth (3 teeth, R = 10, r = 9.5): base angles of 32.5°, chords of 9.76.
    let flat = Gear::ideal(3, 10.0, 9.5).unwrap();
    let e = flat.with_flank_sagitta(-2.0).unwrap_err();
    assert!(e.rule.contains("cross the tooth's base"), "{e}");
}

#[test]
fn centre_distance_matches_paper_example() {
    // N = 8, R = 200, r = 100, D = 310 is G = 10 % of h.
    assert!((centre_distance(200.0, 200.0, 100.0, 10.0) - 310.0).abs() < 1e-12);
}
