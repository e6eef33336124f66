//! One tooth as the contact roots read it (and the speed layer builds its certificates from), and
//! the angle reduction both use: below `mesh/` and `speed/`, so neither depends on the other's
//! internals for it.

use std::f64::consts::{PI, TAU};

use geometry::Vec2;

/// One tooth as the contact roots need it, cached so that a tooth-pair evaluation does no
/// index arithmetic and no trigonometry beyond its two `atan2`s.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ToothData {
    /// (valley k−1, tip k, valley k), relative to the rotation centre.
    pub v: [Vec2; 3],
    /// Whether each vertex can ever touch the other gear.
    pub reaches: [bool; 3],
    /// 1 / squared length of the flanks (valley k−1 → tip k, tip k → valley k).
    pub inv_len2: [f64; 2],
    /// (cos, sin) of the tip angle.
    pub tip_dir: (f64, f64),
    /// Tip angle in [first tip angle, first tip angle + 2π).
    pub tip_angle: f64,
}

/// `x` reduced to (−π, π].
#[inline]
pub(crate) fn wrap_pi(x: f64) -> f64 {
    let y = x.rem_euclid(TAU);
    if y > PI { y - TAU } else { y }
}
