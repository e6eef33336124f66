//! Differential check: the same random meshes run with different bracketing steps must give the
//! same events. `cargo run --release -p contact --example differential -- 300 4`
#![allow(missing_docs, clippy::unwrap_used, reason = "harness")]

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

fn main() {
    let mut args = std::env::args().skip(1);
    let cases: u64 = args.next().map_or(200, |s| s.parse().unwrap());
    let steps: f64 = args.next().map_or(4.0, |s| s.parse().unwrap());
    let reference: f64 = args.next().map_or(16.0, |s| s.parse().unwrap());
    let g_fixed: Option<f64> = args.next().map(|s| s.parse().unwrap());
    let (mut diffs, mut events, mut first_diffs) = (0, 0, 0);
    for s in 0..cases {
        let mut rng = ChaCha8Rng::seed_from_u64(s);
        let n1 = rng.random_range(12..40);
        let n2 = rng.random_range(n1..(n1 * 4).min(120));
        let module = 0.5 + rng.random::<f64>();
        let (r1, r2) = (n1 as f64 * module / 2.0, n2 as f64 * module / 2.0);
        let sigma = [0.0, 0.04, 0.08, 0.12][rng.random_range(0..4)];
        let ecc = [0.0, 0.05, 0.15, 0.3][rng.random_range(0..4)];
        let g = [10.0, 25.0, 40.0, 55.0, 70.0, 85.0][rng.random_range(0..6)];
        let g = g_fixed.unwrap_or(g);
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
        let a = m.run_with_steps(phi0, end, Start::Touching(0.0), false, reference);
        let b = m.run_with_steps(phi0, end, Start::Touching(0.0), false, steps);
        events += a.events().len();
        let same = a.events().len() == b.events().len()
            && a.events().iter().zip(b.events()).all(|(x, y)| {
                x.kind == y.kind && (x.phi - y.phi).abs() < 1e-9 && (x.theta - y.theta).abs() < 1e-9
            });
        if !same {
            diffs += 1;
            if (a.jams() > 0) != (b.jams() > 0)
                || (a.disengagements() > 0) != (b.disengagements() > 0)
            {
                first_diffs += 1;
            }
            let first = a.events().iter().zip(b.events()).position(|(x, y)| {
                !(x.kind == y.kind
                    && (x.phi - y.phi).abs() < 1e-9
                    && (x.theta - y.theta).abs() < 1e-9)
            });
            if let Some(i) = first {
                println!(
                    "  first diff at event {i}: ref: {:?}\n   other: {:?}",
                    a.events()[i],
                    b.events()[i]
                );
            }
            println!(
                "case {s}: n {n1}:{n2} sigma {sigma} ecc {ecc} G {g}: {reference} steps {} jams {} dis; {steps} steps {} jams {} dis",
                a.jams(),
                a.disengagements(),
                b.jams(),
                b.disengagements()
            );
        }
    }
    println!(
        "{diffs} of {cases} cases differ ({first_diffs} in the first event or in jammed/disengaged at all); {events} events at 16 steps"
    );
}
