//! Unit tests of `src/meet.rs`, compiled as its `tests` module (they read its private items):
//! each contact condition is the geometry it names, and its roots - at a fixed driven angle, and
//! where two conditions meet - hold and match a fine scan.

use super::*;
use geometry::rotate;
use std::f64::consts::PI;

const D: f64 = 30.0;

fn driver_world(p: Vec2, phi: f64) -> Vec2 {
    rotate(p, phi)
}

fn driven_world(q: Vec2, theta: f64) -> Vec2 {
    Vec2::new(D, 0.0) + rotate(q, PI - theta)
}

#[test]
fn conditions_are_the_geometry_they_name() {
    let (p, q) = (Vec2::new(12.0, 1.5), Vec2::new(17.0, -2.0));
    let m = Vec2::new(0.6, 0.8);
    let (h, r) = (3.0, 5.5);
    let on_driven_line = Condition::driver_point_on_line(p, m, h, D);
    let on_driver_line = Condition::driven_point_on_line(q, m, h, D);
    let apart = Condition::points_apart(p, q, r, D);
    for (phi, theta) in [(0.3, 1.1), (-2.0, 0.4), (4.0, -3.0)] {
        let x = driver_world(p, phi);
        let y = driven_world(q, theta);
        let mw = rotate(m, PI - theta);
        let want = mw.dot(&(x - Vec2::new(D, 0.0))) - h;
        assert!((on_driven_line.at(phi, theta) - want).abs() < 1e-12);
        let want = rotate(m, phi).dot(&y) - h;
        assert!((on_driver_line.at(phi, theta) - want).abs() < 1e-12);
        let want = (x - y).norm_squared() - r * r;
        assert!((apart.at(phi, theta) - want).abs() < 1e-9);
    }
}

#[test]
fn roots_at_a_fixed_theta_hold_and_none_is_missed() {
    let c = Condition::points_apart(Vec2::new(12.0, 1.5), Vec2::new(17.0, -2.0), 20.0, D);
    let theta = 0.7;
    let roots = c.roots_at_theta(theta, -1.0, 5.0);
    assert!(!roots.is_empty());
    for &phi in &roots {
        assert!(c.at(phi, theta).abs() < 1e-9, "{phi}");
    }
    // A fine scan sees as many sign changes.
    let n = 200_000;
    let changes = (0..n)
        .filter(|&i| {
            let at = |i: i32| c.at(-1.0 + 6.0 * f64::from(i) / f64::from(n), theta);
            at(i).signum() != at(i + 1).signum()
        })
        .count();
    assert_eq!(changes, roots.len());
}

#[test]
fn meetings_hold_both_conditions_and_match_a_scan() {
    let c1 = Condition::driver_point_on_line(
        Vec2::new(15.0, 0.0),
        Vec2::new(0.2, 0.98).normalize(),
        2.0,
        D,
    );
    let c2 = Condition::driven_point_on_line(
        Vec2::new(16.0, 0.5),
        Vec2::new(-0.3, 0.95).normalize(),
        1.0,
        D,
    );
    let (phi0, phi1) = (-1.2, 1.2);
    let found = meetings(&c1, &c2, phi0, phi1, 0.0);
    assert!(!found.is_empty(), "the two conditions meet in the range");
    for &(phi, theta) in &found {
        assert!(c1.at(phi, theta).abs() < 1e-9 && c2.at(phi, theta).abs() < 1e-9);
    }
    // The scan: c1's θ branches along φ, c2's sign on each.
    let n = 100_000;
    let mut changes = 0;
    let mut last: [Option<f64>; 2] = [None, None];
    for i in 0..=n {
        let phi = phi0 + (phi1 - phi0) * f64::from(i) / f64::from(n);
        let (a, b, h) = c1.abh(phi);
        let r = a.hypot(b);
        if h.abs() > r {
            last = [None, None];
            continue;
        }
        let (base, spread) = (b.atan2(a), (h / r).acos());
        for (s, sign) in [1.0, -1.0].into_iter().enumerate() {
            let g = c2.at(phi, base + sign * spread);
            if last[s].is_some_and(|prev: f64| prev.signum() != g.signum()) {
                changes += 1;
            }
            last[s] = Some(g);
        }
    }
    assert_eq!(changes, found.len(), "{found:?}");
}

/// Two contacts that meet twice within 2e-5 rad (each branch of one condition meets the other
/// condition, on teeth of Table I's d2-e2 with tip errors and eccentricity, G = 70 %) leave
/// the polynomial a dip of about 1e-7 where its largest coefficient is 2e7: both meetings are
/// found, the first the lock the solver must see.
#[test]
fn two_meetings_close_together_are_both_found() {
    let pusher = Condition {
        k: [
            [-17.194381310932748, 33.80619291906659, 18.527921351786794],
            [0.0, -6.912863941017957, 3.5967653856236397],
            [0.0, 3.5967653856236397, 6.912863941017957],
        ],
    };
    let ahead = Condition {
        k: [
            [-4.064673218185938, 0.0, 0.0],
            [-8.58778587929386, -29.865519441986745, 8.121647389687459],
            [-37.58181053369496, 8.121647389687459, 29.865519441986745],
        ],
    };
    let found = meetings(
        &pusher,
        &ahead,
        1.4757316126840851,
        1.4881000876982182,
        5.33,
    );
    assert_eq!(found.len(), 2, "{found:?}");
    let (phi, theta) = found[0];
    assert!((phi - 1.487_193_744).abs() < 1e-8, "{found:?}");
    assert!(pusher.at(phi, theta).abs() < 1e-9 && ahead.at(phi, theta).abs() < 1e-9);
}
