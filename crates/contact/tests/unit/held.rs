//! Unit tests of `src/held.rs`, compiled as its `tests` module (they read its private items):
//! the conditions each end of an obstacle is a root of, checked on random meshes of every kind
//! the solver takes.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::TAU;

use geometry::{Gear, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::*;

fn gear(n: usize, r_tip: f64, rng: &mut ChaCha8Rng) -> Gear {
    let pitch = TAU / n as f64;
    let jitter = [0.0, 0.1, 0.3][rng.random_range(0..3)];
    let tips: Vec<f64> = (0..n)
        .map(|k| pitch * k as f64 + jitter * pitch * (rng.random::<f64>() - 0.5))
        .collect();
    let ecc = [0.0, 0.2][rng.random_range(0..2)];
    let a = rng.random::<f64>() * TAU;
    let centre = Vec2::new(ecc * a.cos(), ecc * a.sin());
    let root = r_tip - 1.1;
    let mut g = if rng.random_bool(0.3) {
        // Asymmetric teeth: each valley off the middle of its gap.
        let valleys = (0..n)
            .map(|k| {
                let next = if k + 1 == n {
                    tips[0] + TAU
                } else {
                    tips[k + 1]
                };
                tips[k] + (next - tips[k]) * (0.35 + 0.3 * rng.random::<f64>())
            })
            .collect();
        Gear::with_valleys(r_tip, root, tips, valleys, centre).unwrap()
    } else {
        Gear::new(r_tip, root, tips, centre).unwrap()
    };
    if rng.random_bool(0.3) {
        let tip_radii = (0..n).map(|_| r_tip + 0.05 * rng.random::<f64>()).collect();
        let root_radii = (0..n).map(|_| root - 0.05 * rng.random::<f64>()).collect();
        g = g.with_radii(tip_radii, root_radii).unwrap();
    }
    if rng.random_bool(0.3) {
        g = g
            .with_flank_sagitta(0.05 * (rng.random::<f64>() - 0.5))
            .unwrap();
    }
    g
}

#[test]
fn every_obstacle_end_is_a_root_of_its_ends_conditions() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let (mut ends, mut narrow) = (0, 0);
    for _ in 0..300 {
        let n1 = rng.random_range(8..40);
        let n2 = rng.random_range(n1..90);
        let (r1, r2) = (0.5 * n1 as f64, 0.5 * n2 as f64);
        let g = 2.0 + 98.0 * rng.random::<f64>();
        let d = geometry::centre_distance(r1, r2, 1.1, g);
        let Ok(mesh) = Mesh::new(gear(n1, r1, &mut rng), gear(n2, r2, &mut rng), d) else {
            continue;
        };
        for _ in 0..20 {
            let phi = rng.random::<f64>() * TAU;
            let mut obs = Vec::new();
            let theta = rng.random::<f64>() * TAU;
            mesh.obstacles(phi, theta - 1.0, theta + 1.0, &mut obs);
            for o in obs {
                // An obstacle only just met (a tip crossing a flank's corner twice) may have
                // both ends on one side of the teeth.
                narrow += usize::from(o.hi - o.lo < 0.01);
                for (end, at) in [(End::Lower, o.lo), (End::Upper, o.hi)] {
                    let cs = mesh.conditions_of_both_sides(o.driver_tooth, o.driven_tooth);
                    let residual = cs
                        .iter()
                        .map(|c| c.at(phi, at).abs())
                        .fold(f64::INFINITY, f64::min);
                    // A length, or for a distance to an arc's centre a squared length (mm²).
                    assert!(
                        residual < 1e-7,
                        "{end:?} end of {o:?} at φ {phi}: {residual}; curved {}, {} conditions, G {g}",
                        mesh.curved,
                        cs.len()
                    );
                    ends += 1;
                }
            }
        }
    }
    assert!(
        ends > 10_000 && narrow > 100,
        "{ends} ends, {narrow} narrow"
    );
}
