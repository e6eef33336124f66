//! What the profiling examples share: the two meshes they turn, and gears with random tip errors.

use std::f64::consts::TAU;

use geometry::{Gear, Vec2};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// (name, driver teeth, driven teeth, driver tip radius, driven tip radius) of m3-e3 and m2-n1
/// (Freeth 2006), tip radii in mm.
pub const MESHES: [(&str, usize, usize, f64, f64); 2] = [
    ("m3-e3", 27, 223, 27.0 / 223.0 * 51.95, 51.95),
    ("m2-n1", 15, 53, 3.85, 53.0 / 15.0 * 3.85),
];

/// A gear of `n` teeth 1.1 mm high, tip radius `r_tip`, each tip angle off its place by a normal
/// error of standard deviation `sigma` pitch, drawn from `rng`.
pub fn gear(n: usize, r_tip: f64, sigma: f64, rng: &mut ChaCha8Rng) -> Gear {
    let pitch = TAU / n as f64;
    let normal = Normal::new(0.0, sigma * pitch).unwrap();
    let tips = (0..n)
        .map(|k| pitch * k as f64 + normal.sample(rng))
        .collect();
    Gear::new(r_tip, r_tip - 1.1, tips, Vec2::zeros()).unwrap()
}
