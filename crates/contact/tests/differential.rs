//! The bracketing step must not change what the solver finds: the same random meshes run with
//! the default step and with an eight times finer one give the same first event (kind and
//! driven angle) and the same answer to "jammed at all?" and "disengaged at all?", which is all
//! the jam statistics use. (Later events after a jam's release may differ in rare near-tangent
//! cases; `cargo run --release -p contact --example differential` reports them.)
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::TAU;

use contact::{Mesh, Start};
use geometry::{Gear, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

fn gear(n: usize, r_tip: f64, sigma: f64, ecc: f64, rng: &mut ChaCha8Rng) -> Gear {
    let pitch = TAU / n as f64;
    let normal = Normal::new(0.0, sigma * pitch).unwrap();
    let tips = (0..n)
        .map(|k| pitch * k as f64 + normal.sample(rng))
        .collect();
    let a: f64 = rng.random::<f64>() * TAU;
    Gear::new(
        r_tip,
        r_tip - 1.1,
        tips,
        Vec2::new(ecc * a.cos(), ecc * a.sin()),
    )
    .unwrap()
}

#[test]
fn first_events_do_not_depend_on_the_step() {
    let (mut checked, mut with_events) = (0, 0);
    for case in 0..120u64 {
        let mut rng = ChaCha8Rng::seed_from_u64(case);
        let n1 = rng.random_range(12..40);
        let n2 = rng.random_range(n1..(n1 * 4).min(120));
        let module = 0.5 + rng.random::<f64>();
        let (r1, r2) = (n1 as f64 * module / 2.0, n2 as f64 * module / 2.0);
        let sigma = [0.0, 0.04, 0.08, 0.12][rng.random_range(0..4)];
        let ecc = [0.0, 0.05, 0.15, 0.3][rng.random_range(0..4)];
        let g = [10.0, 25.0, 40.0, 55.0, 70.0, 85.0][rng.random_range(0..6)];
        let d = geometry::centre_distance(r1, r2, 1.1, g);
        let Ok(m) = Mesh::new(
            gear(n1, r1, sigma, ecc, &mut rng),
            gear(n2, r2, sigma, ecc, &mut rng),
            d,
        ) else {
            continue;
        };
        let phi0 = rng.random::<f64>();
        let end = phi0 + TAU * n2 as f64 / n1 as f64;
        let coarse = m.run(phi0, end, Start::Touching(0.0));
        let fine = m.run_with_steps(phi0, end, Start::Touching(0.0), false, 32.0);
        let what = format!("case {case}: {n1}:{n2} teeth, sigma {sigma}, ecc {ecc} mm, G {g} %");
        // The events-only run (no segments kept) finds exactly the same events.
        assert_eq!(
            m.run_events(phi0, end, Start::Touching(0.0)),
            coarse.events(),
            "{what}: run_events"
        );
        assert_eq!(coarse.jams() > 0, fine.jams() > 0, "{what}: jammed at all");
        assert_eq!(
            coarse.disengagements() > 0,
            fine.disengagements() > 0,
            "{what}: disengaged at all"
        );
        match (coarse.events().first(), fine.events().first()) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                with_events += 1;
                assert_eq!(a.kind, b.kind, "{what}: first event kind");
                assert!((a.theta - b.theta).abs() < 1e-9, "{what}: {a:?} vs {b:?}");
                // The angle of a disengagement is a flat maximum of θ: ill-conditioned in φ.
                assert!((a.phi - b.phi).abs() < 1e-6, "{what}: {a:?} vs {b:?}");
            }
            (a, b) => panic!("{what}: first events {a:?} vs {b:?}"),
        }
        checked += 1;
    }
    assert!(
        checked > 100 && with_events > 40,
        "{checked} cases, {with_events} with events"
    );
}
