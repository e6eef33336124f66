//! A mesh is the same mesh in any length unit: scaled by a power of ten (a pair file takes any
//! unit), it gives the same driven angles for about the same work. The solver's allowances
//! against rounding follow the size outside 1 to 1000 units; with a fixed 1e-10 a pair of radius
//! 1e-5 and a clearance of 1e-6 of its tooth height lost every certificate, and one driver pitch
//! took seconds where the same pair in millimetres takes a millisecond.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::TAU;

use contact::{Mesh, Solve, Start, tooth_pair_evaluations};
use geometry::{Gear, Vec2};

/// A 15-tooth driver and an eccentric 8-tooth driven gear of teeth half their radius tall, at a
/// clearance of `g` of the taller tooth's height, all lengths times `scale`.
fn mesh(scale: f64, g: f64) -> Mesh {
    let (r1, r2) = (0.8 * scale, 1.25 * scale);
    let driver = Gear::ideal(15, r1, 0.5 * r1).unwrap();
    let tips = (0..8).map(|k| TAU * f64::from(k) / 8.0).collect();
    let driven = Gear::new(r2, 0.5 * r2, tips, Vec2::new(1e-3 * scale, 0.0)).unwrap();
    let d = r2 + 0.5 * r1 + 1e-3 * scale + g * 0.5 * r2;
    Mesh::new(driver, driven, d).unwrap()
}

/// The driven angle after `pitches` driver pitches and the tooth-pair evaluations it took.
fn run(m: &Mesh, pitches: f64) -> (f64, u64) {
    let end = pitches * TAU / 15.0;
    let before = tooth_pair_evaluations();
    let traj = m.solve(0.0..=end, Start::Touching(0.0), Solve::path());
    (traj.theta_at(end), tooth_pair_evaluations() - before)
}

#[test]
fn any_length_unit_gives_the_same_angles_for_about_the_same_work() {
    for g in [0.4, 1e-6] {
        let (theta, work) = run(&mesh(1.0, g), 3.0);
        for scale in [1e-12, 1e-9, 1e-5, 1e-2, 1e3, 1e9, 1e15] {
            let (t, w) = run(&mesh(scale, g), 3.0);
            assert!(
                (t - theta).abs() <= 1e-12 * (1.0 + theta.abs()),
                "G {g}, scale {scale}: theta {t}, at scale 1 {theta}"
            );
            assert!(
                w <= 2 * work + 100,
                "G {g}, scale {scale}: {w} evaluations, at scale 1 {work}"
            );
        }
    }
}
