//! The two exact primitives of the solver: where a circle crosses a straight segment, and where
//! two circles cross.
//!
//! Every contact condition of two straight-flanked gears is "a vertex of one gear lies on a flank
//! of the other". Seen from the gear that turns, the vertex runs on a circle about that gear's
//! rotation centre, so the contact angles are the crossings of that circle with the flank.
//! With circular-arc flanks a vertex meets an arc where its circle crosses the arc's circle, and
//! two arcs (or an arc and a straight flank) touch when the turning arc's centre, which also runs
//! on a circle, reaches a circle (or an offset segment) about the other: see `mesh/curved.rs`.

use geometry::Vec2;

/// Parameter slack at the ends of a segment, so a vertex-on-vertex contact is found from both
/// adjacent flanks despite rounding.
const END_SLACK: f64 = 1e-12;

/// Calls `found` with every point X = A + t(B − A), t ∈ [0, 1], with |X − C|² = `rho2`;
/// `inv_len2` is 1 / |B − A|² (cached by the caller: flanks keep their length as they turn).
#[inline]
pub(crate) fn circle_segment(
    c: Vec2,
    rho2: f64,
    a: Vec2,
    b: Vec2,
    inv_len2: f64,
    mut found: impl FnMut(Vec2),
) {
    let d = b - a;
    let f = a - c;
    let fd = f.dot(&d);
    let ff = f.dot(&f) - rho2;
    // Roots of |d|² t² + 2 fd t + ff = 0, scaled by 1/|d|².
    let p = fd * inv_len2;
    let disc = p * p - ff * inv_len2;
    if disc < 0.0 || !inv_len2.is_finite() {
        return;
    }
    let sq = disc.sqrt();
    // A root outside [0, 1] (with slack) is no contact; test before forming the point.
    for t in [-p - sq, -p + sq] {
        if (-END_SLACK..=1.0 + END_SLACK).contains(&t) {
            found(a + d * t.clamp(0.0, 1.0));
        }
    }
}

/// Calls `found` with every point X with |X − C|² = `rho2` and |X − `centre`| = `radius` (none
/// when the circles miss, are concentric or merely graze within rounding, as for a segment).
#[inline]
pub(crate) fn circle_circle(
    c: Vec2,
    rho2: f64,
    centre: Vec2,
    radius: f64,
    mut found: impl FnMut(Vec2),
) {
    let d = centre - c;
    let d2 = d.norm_squared();
    if d2 == 0.0 {
        return;
    }
    // X = C + a·d + h·d⊥ with |d| a = (ρ² − r² + |d|²) / (2|d|) along the line of centres;
    // here both a and h are fractions of d.
    let a = 0.5 * (rho2 - radius * radius + d2) / d2;
    let h2 = rho2 / d2 - a * a;
    if h2.is_nan() || h2 < 0.0 {
        return;
    }
    let h = h2.sqrt();
    let base = c + d * a;
    let perp = Vec2::new(-d.y, d.x);
    found(base + perp * h);
    found(base - perp * h);
}

#[cfg(test)]
#[path = "../tests/unit/roots.rs"]
mod tests;
