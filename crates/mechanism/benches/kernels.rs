//! Kernel benchmarks: one full turn of the larger gear of m2-n1, b2-c1 and m3-e3, ideal
//! and with Edmunds' Case B errors; one year (one turn of b) of the Lunar train; and the floor,
//! one bare evaluation of the contact closed forms of a tooth pair. Gears are sized by
//! `crates/train` from the Freeth 2006 gearing, h = 1.1 mm, G = 40 %.
//!
//! `cargo bench -p mechanism --bench kernels` (or `cargo xtask bench --kernels`).
#![allow(
    missing_docs,
    clippy::unwrap_used,
    reason = "criterion_group! generates an undocumented function; a bench may panic"
)]

use std::f64::consts::TAU;
use std::hint::black_box;

use contact::{Solve, Start};
use criterion::{Criterion, criterion_group, criterion_main};
use hypotheses::Params;
use mechanism::Mechanism;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use train::Gearing;

const H: f64 = 1.1;
const G: f64 = 40.0;
const MESHES: [&str; 3] = ["m2-n1", "b2-c1", "m3-e3"];

/// A generator for the benches (the studies draw from `registry::Streams`; a mechanism only
/// takes the generator it is handed).
fn trial_rng(seed: u64, trial: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(trial);
    rng
}

/// Edmunds' Case B (systematic 0.5°, random 0.04, split 50/50), or the ideal gears.
fn mechanism(case_b: bool) -> Mechanism {
    let g = Gearing::freeth2006();
    if !case_b {
        return Mechanism::ideal(&g, H, G).unwrap();
    }
    let hyp = hypotheses::lookup("edmunds-split").unwrap();
    let params = Params::new(
        hyp,
        &[
            ("systematic".into(), "0.5".into()),
            ("random".into(), "0.04".into()),
            ("split".into(), "0.5".into()),
        ],
    )
    .unwrap();
    let mut rng = trial_rng(2025, 0);
    Mechanism::build(&g, H, G, |name, ideal| {
        hyp.apply(&ideal, name, &params, &mut rng)
            .map_err(|e| e.to_string())
    })
    .unwrap()
}

fn kernels(c: &mut Criterion) {
    for (label, case_b) in [("ideal", false), ("case-B", true)] {
        let mech = mechanism(case_b);
        for name in MESHES {
            let mesh = mech.mesh(name).unwrap();
            let (n1, n2) = (mesh.driver().teeth(), mesh.driven().teeth());
            // One full turn of the gear with more teeth, in driver angle.
            let range = TAU * n1.max(n2) as f64 / n1 as f64;
            let e0 = contact::tooth_pair_evaluations();
            let t = mesh.solve(0.1..=0.1 + range, Start::Touching(0.0), Solve::path());
            let evals = contact::tooth_pair_evaluations() - e0;
            eprintln!(
                "turn/{name}/{label}: {} engagements, {} tooth-pair evaluations ({:.0} per engagement), {} jams, {} disengagements",
                n1.max(n2),
                evals,
                evals as f64 / n1.max(n2) as f64,
                t.jams(),
                t.disengagements()
            );
            c.bench_function(&format!("turn/{name}/{label}"), |b| {
                b.iter(|| {
                    black_box(mesh).solve(
                        0.1..=0.1 + black_box(range),
                        Start::Touching(0.0),
                        Solve::path(),
                    )
                });
            });
        }
        c.bench_function(&format!("lunar-year/{label}"), |b| {
            b.iter(|| {
                let mut rng = trial_rng(7, 1);
                black_box(&mech).run_pointer("Lunar", 1.0, &mut rng)
            });
        });
    }
    // The floor: one bare evaluation of the closed-form contact roots of the tooth pair in
    // contact on the line of centres of m3-e3.
    let mech = mechanism(false);
    let mesh = mech.mesh("m3-e3").unwrap();
    let mut rng = trial_rng(7, 2);
    let phi: f64 = rng.random::<f64>() * 0.01;
    c.bench_function("tooth-pair/m3-e3", |b| {
        b.iter(|| black_box(mesh).obstacle(black_box(phi), 0, 0));
    });
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10);
    targets = kernels
}
criterion_main!(benches);
