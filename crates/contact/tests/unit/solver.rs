//! Unit tests of `src/solver/mod.rs`, compiled as its `tests` module (they read its private
//! items).

#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;
use geometry::{Gear, Vec2};
use rand::{Rng, SeedableRng};

/// Meshes of a pinion and a large wheel with tip angles scattered by up to 0.1 pitch, at
/// clearances where they are blocked or jam at many teeth (the held-gear regime).
fn tight_mesh(rng: &mut rand_chacha::ChaCha8Rng) -> Mesh {
    let (n1, n2) = (rng.random_range(12..40), rng.random_range(40..240));
    let module = 0.24;
    let (r1, r2) = (module * n1 as f64, module * n2 as f64);
    let gear = |n: usize, r: f64, rng: &mut rand_chacha::ChaCha8Rng| {
        let pitch = TAU / n as f64;
        let tips = (0..n)
            .map(|k| pitch * (k as f64 + rng.random_range(-0.1..0.1)))
            .collect();
        Gear::new(r, r - 1.1, tips, Vec2::zeros()).unwrap()
    };
    let (a, b) = (gear(n1, r1, rng), gear(n2, r2, rng));
    let g = rng.random_range(0.0..12.0);
    Mesh::new(a, b, geometry::centre_distance(r1, r2, 1.1, g)).unwrap()
}
/// Obstacles taken from a memo (a scan's widening windows, a cover's links a turn apart) are
/// the ones a fresh evaluation gives, bit for bit, and no pair is evaluated twice.
#[test]
fn remembered_obstacles_are_evaluated_ones() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
    let bits = |o: &Obstacle| {
        (
            o.driver_tooth,
            o.driven_tooth,
            o.lo.to_bits(),
            o.hi.to_bits(),
        )
    };
    for _ in 0..20 {
        let mesh = tight_mesh(&mut rng);
        let (phi, theta) = (rng.random_range(0.0..TAU), rng.random_range(0.0..TAU));
        let gap = mesh.driven.max_gap;
        let mut memo = PairMemo::new(&mesh, phi);
        let (mut fresh, mut remembered) = (Vec::new(), Vec::new());
        let mut reach = 3.0 * gap;
        let mut window = (theta - gap, theta + reach);
        // Widening windows as the scan takes them, until past one that lies wholly a turn on.
        let mut beyond = 0;
        while window.0 < theta + 2.0 * TAU + 2.0 * gap {
            mesh.obstacles(phi, window.0, window.1, &mut fresh);
            let before = crate::mesh::tooth_pair_evaluations();
            mesh.obstacles_with(phi, window.0, window.1, &mut remembered, Some(&mut memo));
            let evaluated = crate::mesh::tooth_pair_evaluations() - before;
            assert_eq!(
                fresh.iter().map(bits).collect::<Vec<_>>(),
                remembered.iter().map(bits).collect::<Vec<_>>()
            );
            if window.0 > theta + TAU + gap {
                beyond += remembered.len();
                assert_eq!(
                    evaluated, 0,
                    "a tooth met again a turn on was evaluated again"
                );
            }
            window = (theta + reach, theta + 2.0 * reach);
            reach *= 2.0;
        }
        assert!(beyond > 0, "no obstacles a turn on");
    }
}
