//! The ideal 20:30 pair (h = 1.1) the presentation modules' tests run: one mesh, its looseness
//! the only setting.
#![allow(clippy::unwrap_used, reason = "tests")]

/// The ideal 20- and 30-tooth gears (tip radii 20 and 30, h = 1.1) with their centres `gap`
/// beyond the distance at which the tips reach the opposite roots: 0.44 is the paper's 40 %,
/// 1.09 so loose that the tips slip past each other.
pub fn ideal_20_30(gap: f64) -> contact::Mesh {
    contact::Mesh::new(
        geometry::Gear::ideal(20, 20.0, 18.9).unwrap(),
        geometry::Gear::ideal(30, 30.0, 28.9).unwrap(),
        20.0 + 30.0 - 1.1 + gap,
    )
    .unwrap()
}
