//! Random hard meshes for the differential checks (`tests/differential.rs` and
//! `examples/differential.rs` include this file): tooth counts 12-120, random tip errors,
//! eccentricity and clearances from 10 to 85 %, each mesh from its own seed.

use std::f64::consts::TAU;

use contact::Mesh;
use geometry::{Gear, Vec2};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// One random mesh and where its run starts and ends.
pub struct HardMesh {
    pub mesh: Mesh,
    pub phi0: f64,
    pub end: f64,
    /// The mesh in words, for messages.
    pub what: String,
}

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

/// The mesh of seed `case` (clearance `g_fixed` % if given), run over one turn of the larger
/// gear from a random start; None where the drawn gears cannot be placed.
pub fn hard_mesh(case: u64, g_fixed: Option<f64>) -> Option<HardMesh> {
    let mut rng = ChaCha8Rng::seed_from_u64(case);
    let n1 = rng.random_range(12..40);
    let n2 = rng.random_range(n1..(n1 * 4).min(120));
    let module = 0.5 + rng.random::<f64>();
    let (r1, r2) = (n1 as f64 * module / 2.0, n2 as f64 * module / 2.0);
    let sigma = [0.0, 0.04, 0.08, 0.12][rng.random_range(0..4)];
    let ecc = [0.0, 0.05, 0.15, 0.3][rng.random_range(0..4)];
    let g = [10.0, 25.0, 40.0, 55.0, 70.0, 85.0][rng.random_range(0..6)];
    let g = g_fixed.unwrap_or(g);
    let d = geometry::centre_distance(r1, r2, 1.1, g);
    let mesh = Mesh::new(
        gear(n1, r1, sigma, ecc, &mut rng),
        gear(n2, r2, sigma, ecc, &mut rng),
        d,
    )
    .ok()?;
    let phi0 = rng.random::<f64>();
    let end = phi0 + TAU * n2 as f64 / n1 as f64;
    let what = format!("case {case}: {n1}:{n2} teeth, sigma {sigma}, ecc {ecc} mm, G {g} %");
    Some(HardMesh {
        mesh,
        phi0,
        end,
        what,
    })
}
