//! Ideal gears: the paper's N = 8 example and the exact tooth ratio after whole driver teeth.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::TAU;

use contact::{Mesh, Solve, Start};
use geometry::Gear;

fn paper_example() -> Mesh {
    let g = Gear::ideal(8, 200.0, 100.0).unwrap();
    Mesh::new(g.clone(), g, 310.0).unwrap()
}

#[test]
fn initial_contact_is_thorndike_theta_prime_zero() {
    let m = paper_example();
    let t = m.solve(0.0..=0.0, Start::Touching(0.0), Solve::path());
    let deg = t.theta_at(0.0).to_degrees();
    assert!((deg - 17.96).abs() < 0.005, "theta'(0) = {deg}");
}

#[test]
fn whole_driver_teeth_give_exact_ratio() {
    for (n1, n2, r1, r2, g) in [
        (8, 8, 200.0, 200.0, 10.0),
        (27, 223, 27.0 * 0.23, 223.0 * 0.23, 40.0),
        (15, 53, 3.9, 13.78, 40.0),
        (64, 38, 15.3, 15.3 * 38.0 / 64.0, 60.0),
    ] {
        let h = if n1 == 8 { 100.0 } else { 1.1 };
        let d = geometry::centre_distance(r1, r2, h, g);
        let m = Mesh::new(
            Gear::ideal(n1, r1, r1 - h).unwrap(),
            Gear::ideal(n2, r2, r2 - h).unwrap(),
            d,
        )
        .unwrap();
        let p1 = TAU / n1 as f64;
        let phi0 = 0.3 * p1;
        let t = m.solve(phi0..=phi0 + TAU, Start::Touching(0.0), Solve::path());
        assert_eq!(
            t.jams(),
            0,
            "{n1}:{n2} jams {:?}",
            &t.events()[..t.events().len().min(3)]
        );
        assert_eq!(t.disengagements(), 0);
        let th0 = t.theta_at(phi0);
        for m_teeth in 1..=n1 {
            let phi = phi0 + m_teeth as f64 * p1;
            let want = th0 + (n1 as f64 / n2 as f64) * (phi - phi0);
            let got = t.theta_at(phi);
            assert!(
                (got - want).abs().to_degrees() < 1e-9,
                "{n1}:{n2} after {m_teeth}: {} vs {}",
                got.to_degrees(),
                want.to_degrees()
            );
        }
    }
}

#[test]
fn paper_example_matches_appendix_closed_forms_every_hundredth_of_a_degree() {
    let m = paper_example();
    let pair = thorndike::Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 310.0).unwrap();
    let t = m.solve(0.0..=TAU, Start::Touching(0.0), Solve::path());
    let mut worst: f64 = 0.0;
    let mut phases = std::collections::BTreeSet::new();
    for i in 0..=36_000 {
        let phi = (i as f64 * 0.01).to_radians();
        worst = worst.max((t.theta_at(phi) - thorndike::theta_prime(&pair, phi)).abs());
        phases.insert(format!("{:?}", thorndike::contact(&pair, phi).phase));
    }
    assert_eq!(phases.len(), 2, "both contact phases visited");
    assert!(
        worst.to_degrees() < 1e-9,
        "max |sim - closed| = {} deg",
        worst.to_degrees()
    );
}

/// Tip circles that only just touch (D = R1 + R2, G = 100 % of h) or miss: the driven gear is
/// never moved, and the run says so - an idle start, never a clean run. At exactly tangent tip
/// circles the tips touch at the start, yet fall away without lifting the driven gear.
#[test]
fn gears_whose_tips_cannot_engage_are_never_driven() {
    let g = Gear::ideal(8, 200.0, 100.0).unwrap();
    let p1 = TAU / 8.0;
    // Exactly tangent tip circles are judged by the speed layer's bounds (the touching tips
    // part where their vertices meet, at the start). The exact core alone sees the tips touch,
    // within the slack a flank's end is given against rounding (1e-12 of its length), for
    // another 7e-7 rad of driver angle, and the driven gear lifted by as much.
    let clearances: &[f64] = if cfg!(feature = "speed") {
        &[400.0, 400.01, 450.0]
    } else {
        &[400.01, 450.0]
    };
    for &d in clearances {
        let m = Mesh::new(g.clone(), g.clone(), d).unwrap();
        let t = m.solve(0.0..=3.0 * p1, Start::Touching(0.0), Solve::path());
        assert!(t.never_driven(), "D = {d}: {:?}", t.events());
        let e = t.events()[0];
        assert!(e.idle_start && !e.resumed && e.phi == 0.0, "D = {d}: {e:?}");
        assert!((e.lost_motion - 3.0).abs() < 1e-12, "D = {d}: {e:?}");
    }
    // Just inside, the tips engage and drive for a moment, then slip: driven, with a slip.
    let m = Mesh::new(g.clone(), g, 399.99).unwrap();
    let t = m.solve(0.0..=3.0 * p1, Start::Touching(0.0), Solve::path());
    assert!(!t.never_driven(), "{:?}", t.events());
    assert!(t.events().iter().all(|e| !e.idle_start), "{:?}", t.events());
}
