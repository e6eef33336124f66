//! The mesh with its other gear driving ([`Mesh::other_driving`]) is the same two gears turning
//! the same ways, the picture reflected in the perpendicular bisector of the line of centres:
//! checked on random meshes of every kind (tooth errors, eccentricity, asymmetric and
//! out-of-round teeth, curved flanks) against the listed mesh's own outlines and obstacles.
#![allow(clippy::unwrap_used, reason = "tests")]

use contact::{Mesh, Motion, Obstacle, Solve};
use geometry::Vec2;
use proptest::prelude::*;
use proptest::test_runner::{Config as ProptestConfig, RngSeed};

#[path = "support/prop_cases.rs"]
#[allow(
    dead_code,
    reason = "the shared case generators; this file draws only some kinds"
)]
mod prop_cases;
use prop_cases::*;

fn config() -> ProptestConfig {
    ProptestConfig {
        cases: 48,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0x07e2_d21e),
        ..ProptestConfig::default()
    }
}

/// Every point of `a` has a point of `b` within `tol` (mm), and the other way round.
fn same_points(a: &[Vec2], b: &[Vec2], tol: f64) -> bool {
    let near = |p: &Vec2, q: &[Vec2]| q.iter().any(|x| (x - p).norm() < tol);
    a.len() == b.len() && a.iter().all(|p| near(p, b)) && b.iter().all(|p| near(p, a))
}

proptest! {
    #![proptest_config(config())]

    /// At any pair of angles, the reversed mesh's outlines are the listed mesh's outlines
    /// reflected in x = D/2, each gear at its own angle.
    #[test]
    fn the_other_gear_driving_is_the_reflected_picture(
        case in every_kind_of_case(2.0..100.0, 2..3),
        phi in -7.0..7.0f64,
        theta in -7.0..7.0f64,
    ) {
        let Some(listed) = case.mesh() else { return Ok(()) };
        let other = listed.other_driving().unwrap();
        let d = listed.centre_distance();
        let reflect = |ps: Vec<Vec2>| -> Vec<Vec2> {
            ps.into_iter().map(|p| Vec2::new(d - p.x, p.y)).collect()
        };
        let (driver, driven) = listed.world_outlines(phi, theta);
        let (new_driver, new_driven) = other.world_outlines(theta, phi);
        prop_assert!(same_points(&new_driver, &reflect(driven), 1e-9));
        prop_assert!(same_points(&new_driven, &reflect(driver), 1e-9));
        prop_assert_eq!(other.driver().teeth(), listed.driven().teeth());
    }

    /// Wherever the listed driven gear pushes, seen in the listed mesh it rests against a listed
    /// driver tooth from behind (the low end of their obstacle) and lies inside no obstacle: the
    /// motion is the listed gears', driven the other way round.
    #[test]
    fn the_other_gear_pushes_from_behind(case in every_kind_of_case(20.0..90.0, 2..4)) {
        let Some(listed) = case.mesh() else { return Ok(()) };
        let other = listed.other_driving().unwrap();
        let traj = case.run(&other);
        let mut obstacles: Vec<Obstacle> = Vec::new();
        for s in traj.segments().iter().filter(|s| matches!(s.motion, Motion::Push(_))) {
            for i in 1..4 {
                let new_phi = s.phi_start + (s.phi_end - s.phi_start) * f64::from(i) / 4.0;
                let (phi, theta) = (traj.theta_at(new_phi), new_phi);
                listed.obstacles(phi, theta - 1.0, theta + 1.0, &mut obstacles);
                let touching = obstacles.iter().any(|o| (o.lo - theta).abs() < 1e-9);
                let inside = obstacles.iter().any(|o| o.lo + 1e-9 < theta && theta < o.hi - 1e-9);
                prop_assert!(touching, "not touching at new phi {new_phi}");
                prop_assert!(!inside, "inside an obstacle at new phi {new_phi}");
            }
        }
    }
}

/// The ideal pair of the paper's Figure 2 (N = 8, equal gears) runs alike whichever gear drives.
#[test]
fn equal_ideal_gears_run_alike_whichever_drives() {
    let g = geometry::Gear::ideal(8, 200.0, 100.0).unwrap();
    let listed = Mesh::new(g.clone(), g, 310.0).unwrap();
    let other = listed.other_driving().unwrap();
    let start = contact::Start::Touching(0.0);
    let (a, b) = (
        listed.solve(0.1..=6.0, start, Solve::path()),
        other.solve(0.1..=6.0, start, Solve::path()),
    );
    for i in 0..=100 {
        let phi = 0.1 + 5.9 * f64::from(i) / 100.0;
        assert!(
            (a.theta_at(phi) - b.theta_at(phi)).abs() < 1e-9,
            "phi {phi}"
        );
    }
}
