//! Benchmark: one full turn of the larger gear of two Antikythera meshes (m3-e3, m2-n1), ideal and
//! with random tooth errors, through the exact push-model solver.
#![allow(
    missing_docs,
    reason = "criterion_group! generates an undocumented function"
)]

use std::f64::consts::TAU;
use std::hint::black_box;

use contact::{Mesh, Solve, Start};
use criterion::{Criterion, criterion_group, criterion_main};
use geometry::{Gear, Vec2};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Tooth height, mm.
const H: f64 = 1.1;
/// Clearance, percent of the tooth height.
const G_PERCENT: f64 = 40.0;
/// Standard deviation of the tip-angle errors, in pitches.
const TOOTH_ERROR: f64 = 0.04;

/// A measured mesh: tooth counts and tip radii (mm) with `R1 / R2 = N1 / N2` exactly.
struct Pair {
    name: &'static str,
    n1: usize,
    n2: usize,
    r1: f64,
    r2: f64,
}

fn pairs() -> [Pair; 2] {
    // m3 is lost: both radii from e3 (measured 51.95 mm), R1 = (27 / 223) R2.
    let m3_e3 = Pair {
        name: "m3-e3",
        n1: 27,
        n2: 223,
        r1: 27.0 / 223.0 * 51.95,
        r2: 51.95,
    };
    // n1 is lost: both radii from m2 (measured 3.85 mm), R2 = (53 / 15) R1.
    let m2_n1 = Pair {
        name: "m2-n1",
        n1: 15,
        n2: 53,
        r1: 3.85,
        r2: 53.0 / 15.0 * 3.85,
    };
    [m3_e3, m2_n1]
}

/// A gear with `n` teeth; tip `k` at `2 pi k / n + sigma * pitch * z_k`, `z_k` standard normal.
fn gear(n: usize, r_tip: f64, sigma: f64, rng: &mut ChaCha8Rng) -> Gear {
    let pitch = TAU / n as f64;
    let normal = Normal::new(0.0, sigma * pitch).expect("finite standard deviation");
    let tips = (0..n)
        .map(|k| pitch * k as f64 + normal.sample(rng))
        .collect();
    Gear::new(r_tip, r_tip - H, tips, Vec2::zeros()).expect("valid gear")
}

fn mesh(p: &Pair, sigma: f64, seed: u64) -> Mesh {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let driver = gear(p.n1, p.r1, sigma, &mut rng);
    let driven = gear(p.n2, p.r2, sigma, &mut rng);
    let d = geometry::centre_distance(p.r1, p.r2, H, G_PERCENT);
    Mesh::new(driver, driven, d).expect("valid mesh")
}

fn turn(c: &mut Criterion) {
    for p in pairs() {
        // One full turn of the larger (driven) gear: N2 / N1 turns of the driver.
        let phi_end = TAU * p.n2 as f64 / p.n1 as f64;
        for (label, sigma) in [
            ("ideal".to_owned(), 0.0),
            (format!("tooth-error-{TOOTH_ERROR}"), TOOTH_ERROR),
        ] {
            let m = mesh(&p, sigma, 1);
            let t = m.solve(0.0..=phi_end, Start::Touching(0.0), Solve::path());
            eprintln!(
                "turn/{}/{label}: {} segments, {} jams, {} disengagements",
                p.name,
                t.segments().len(),
                t.jams(),
                t.disengagements()
            );
            c.bench_function(&format!("turn/{}/{label}", p.name), |b| {
                b.iter(|| {
                    black_box(&m).solve(
                        0.0..=black_box(phi_end),
                        Start::Touching(0.0),
                        Solve::path(),
                    )
                });
            });
        }
    }
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = turn
}
criterion_main!(benches);
