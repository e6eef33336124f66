//! Random meshes of a wider class than `hard_meshes.rs` for the differential checks
//! (`tests/differential.rs` and `examples/differential.rs` include this file): systematic and
//! random tip errors, asymmetric and out-of-round teeth, eccentricity, straight or curved flanks,
//! each mesh from its own seed.
#![allow(dead_code, reason = "each includer uses a part")]

/// One mesh of the wider class, where its run starts and ends, and its clearance.
pub struct WideMesh {
    pub mesh: contact::Mesh,
    pub phi0: f64,
    pub end: f64,
    /// Per cent of the tooth height.
    pub clearance: f64,
    /// The mesh in words, for messages.
    pub what: String,
}

/// A wider class of meshes than `hard_mesh`: systematic (sinusoidal) and random tip errors,
/// asymmetric teeth (valleys off the midway angle),
/// gears that are not round (a radius per tip and valley), eccentricity and clearances from 5 to
/// 95 %; None where the drawn gears cannot be placed.
/// (The documents name meshes of the class so: `wide_mesh(242)`.)
pub fn wide_mesh(case: u64) -> Option<WideMesh> {
    wide_mesh_drawn(case, (5.0, 95.0), false)
}

/// The meshes of the first `cases` cases that can be placed, as [`wide_mesh_drawn`] draws them.
pub fn wide_meshes(
    cases: u64,
    clearances: (f64, f64),
    curved: bool,
) -> impl Iterator<Item = WideMesh> {
    (0..cases).filter_map(move |case| wide_mesh_drawn(case, clearances, curved))
}

/// [`wide_mesh`] with its clearance drawn from `clearances` (per cent of h), everything else
/// drawn alike, and with `curved` set, both gears' flanks circular arcs of a sagitta
/// drawn from -0.05 to 0.05 mm (convex or concave; None where the teeth cannot take it).
pub fn wide_mesh_drawn(case: u64, clearances: (f64, f64), curved: bool) -> Option<WideMesh> {
    use std::f64::consts::TAU;

    use geometry::{Gear, Vec2};
    use rand::{Rng, SeedableRng};

    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1_000_000 + case);
    let gear = |n: usize, r_tip: f64, rng: &mut rand_chacha::ChaCha8Rng| -> Option<Gear> {
        let pitch = TAU / n as f64;
        let sigma = [0.0, 0.04, 0.12, 0.25][rng.random_range(0..4)];
        // A sinusoidal (systematic) error of up to half a pitch, as Edmunds' larger Cases.
        let (amp, phase) = (
            [0.0, 0.2, 0.5][rng.random_range(0..3)],
            TAU * rng.random::<f64>(),
        );
        let tips: Vec<f64> = (0..n)
            .map(|k| {
                let a = TAU * k as f64 / n as f64;
                a + amp * pitch * (a + phase).sin() + sigma * pitch * (rng.random::<f64>() - 0.5)
            })
            .collect();
        let lean = 0.3 * (rng.random::<f64>() - 0.5);
        let valleys = (0..n)
            .map(|k| {
                let next = if k + 1 == n {
                    tips[0] + TAU
                } else {
                    tips[k + 1]
                };
                tips[k] + (next - tips[k]) * (0.5 + lean)
            })
            .collect();
        let ecc = [0.0, 0.1, 0.3][rng.random_range(0..3)];
        let a = rng.random::<f64>() * TAU;
        let g = Gear::with_valleys(
            r_tip,
            r_tip - 1.1,
            tips,
            valleys,
            Vec2::new(ecc * a.cos(), ecc * a.sin()),
        )
        .ok()?;
        let g = if rng.random::<bool>() {
            let wobble = 0.1 * rng.random::<f64>();
            let tip_radii = (0..n)
                .map(|_| r_tip + wobble * (rng.random::<f64>() - 0.5))
                .collect();
            let root_radii = (0..n)
                .map(|_| r_tip - 1.1 + wobble * (rng.random::<f64>() - 0.5))
                .collect();
            g.with_radii(tip_radii, root_radii).ok()?
        } else {
            g
        };
        if curved {
            g.with_flank_sagitta(0.1 * (rng.random::<f64>() - 0.5)).ok()
        } else {
            Some(g)
        }
    };
    let n1 = rng.random_range(12..40);
    let n2 = rng.random_range(n1..(n1 * 4).min(120));
    let module = 0.5 + rng.random::<f64>();
    let (r1, r2) = (n1 as f64 * module / 2.0, n2 as f64 * module / 2.0);
    let g = clearances.0 + (clearances.1 - clearances.0) * rng.random::<f64>();
    let d = geometry::centre_distance(r1, r2, 1.1, g);
    let mesh = contact::Mesh::new(gear(n1, r1, &mut rng)?, gear(n2, r2, &mut rng)?, d).ok()?;
    let phi0 = rng.random::<f64>();
    let end = phi0 + TAU * n2 as f64 / n1 as f64;
    Some(WideMesh {
        mesh,
        phi0,
        end,
        clearance: g,
        what: format!("wide case {case}: {n1}:{n2} teeth, G {g:.1} %"),
    })
}
