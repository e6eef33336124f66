//! Runs full turns of m3-e3 and m2-n1 with random tooth errors, for profiling:
//! `cargo build --release -p contact --example turns && perf record -g target/release/examples/turns 50`.
#![allow(missing_docs, clippy::unwrap_used, reason = "profiling harness")]

use std::f64::consts::TAU;
use std::time::Instant;

use contact::{Mesh, Solve, Start};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

mod support;

use support::{MESHES, gear};

fn main() {
    let turns: usize = std::env::args().nth(1).map_or(20, |s| s.parse().unwrap());
    for (name, n1, n2, r1, r2) in MESHES {
        let t0 = Instant::now();
        let evals0 = contact::tooth_pair_evaluations();
        let (stats0, speed0) = (contact::solver_stats(), contact::speed_stats());
        let (mut segs, mut events) = (0, 0);
        for s in 0..turns as u64 {
            let mut rng = ChaCha8Rng::seed_from_u64(s);
            let d = geometry::centre_distance(r1, r2, 1.1, 40.0);
            let m = Mesh::new(
                gear(n1, r1, 0.04, &mut rng),
                gear(n2, r2, 0.04, &mut rng),
                d,
            )
            .unwrap();
            let t = m.solve(
                0.0..=TAU * n2 as f64 / n1 as f64,
                Start::Touching(0.0),
                Solve::path(),
            );
            segs += t.segments().len();
            events += t.events().len();
        }
        let dt = t0.elapsed().as_secs_f64() / turns as f64;
        println!(
            "evaluations per driven tooth: {:.1}",
            (contact::tooth_pair_evaluations() - evals0) as f64 / turns as f64 / n2 as f64
        );
        let (st, sp) = (contact::solver_stats(), contact::speed_stats());
        let per = |x: u64| x as f64 / turns as f64 / n2 as f64;
        println!(
            "per driven tooth: {:.2} certified steps ({:.1} evaluations), {:.2} refused ({:.1}), {:.2} bracketed",
            per(sp.certified - speed0.certified),
            per(sp.certified_evaluations - speed0.certified_evaluations),
            per(sp.refused - speed0.refused),
            per(sp.refused_evaluations - speed0.refused_evaluations),
            per(st.bracketed - stats0.bracketed),
        );
        println!(
            "{name}: {:.3} ms per turn, {segs} segments, {events} events",
            dt * 1e3
        );
    }
}
