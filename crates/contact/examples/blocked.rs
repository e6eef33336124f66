//! Full turns of an ideal m3-e3 mesh at small clearances, where the driven gear jams at every
//! tooth or cannot turn at all (the clearance-limit searches run such meshes):
//! `cargo run --release -p contact --example blocked`.
#![allow(missing_docs, clippy::unwrap_used, reason = "profiling harness")]

use std::f64::consts::TAU;
use std::time::Instant;

use contact::{Mesh, Solve, Start};
use geometry::{Gear, Vec2};

fn main() {
    let (n1, n2, r1, r2) = (27usize, 223usize, 27.0 / 223.0 * 51.95, 51.95);
    let gear = |n: usize, r: f64| {
        let tips = (0..n).map(|k| TAU * k as f64 / n as f64).collect();
        Gear::new(r, r - 1.1, tips, Vec2::zeros()).unwrap()
    };
    for g in [3.0, 6.0, 9.0, 12.0] {
        let d = geometry::centre_distance(r1, r2, 1.1, g);
        let m = Mesh::new(gear(n1, r1), gear(n2, r2), d).unwrap();
        let evals0 = contact::tooth_pair_evaluations();
        let t0 = Instant::now();
        let events = m.solve(
            0.0..=TAU * n2 as f64 / n1 as f64,
            Start::Touching(0.0),
            Solve::events(),
        );
        println!(
            "G {g} %: {} events, {:.1} ms, {} tooth-pair evaluations",
            events.len(),
            t0.elapsed().as_secs_f64() * 1e3,
            contact::tooth_pair_evaluations() - evals0
        );
    }
}
