//! Independent polygon oracle: gear outlines, placement, penetration depth and brute-force push angles.
//!
//! Everything here works on plain `[f64; 2]` points and uses only point-in-polygon (winding
//! number), point-segment distances and segment-crossing tests. There is deliberately no
//! circle/line root solving, so that this crate can check closed-form or iterative contact
//! solvers without sharing their mathematics.
//!
//! Gears with circular-arc flanks ([`CurvedShape`], [`CurvedMesh`]) are checked the same way:
//! whether a point lies inside is decided exactly (the polygon of vertices, plus or minus the
//! circular segments between each flank's chord and its arc: a distance to the arc's centre and
//! a side of the chord), and the arcs' points are parametrised densely and refined by a
//! golden-section search, never intersected.
//!
//! World frame of a mesh (shared with the solver): the driver's rotation centre is at the
//! origin and the driven's at `(D, 0)`. A driver gear-frame point `p` (relative to the driver's
//! geometric centre, whose rotation centre is at gear-frame offset `e1`) at driver angle `phi`
//! is at `Rot(phi) (p - e1)`; a driven gear-frame point `q` at driven angle `theta` is at
//! `(D, 0) + Rot(pi - theta) (q - e2)`. Angles are in radians.

pub mod area;
mod curved;
pub mod stepped;

pub use curved::{ArcFlank, CurvedMesh, CurvedShape, FLANK_SAMPLES, tooth_contains};

use std::f64::consts::{PI, TAU};

/// A point or vector in the plane, `[x, y]`.
pub type P2 = [f64; 2];

/// Which of the two world transforms of a mesh to apply in [`place`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sense {
    /// Driver: `origin + Rot(angle) (p - e)`; the gear turns counter-clockwise.
    Driver,
    /// Driven: `origin + Rot(pi - angle) (p - e)`; the gear turns clockwise and at
    /// `angle = 0` its gear-frame `+x` axis points towards the driver (the `-x` world direction).
    Driven,
}

/// Outline of an ideal gear: `n` tips at polar angles `2 pi k / n` and radius `r_tip`, valleys
/// midway in angle at radius `r_root`, as the CCW star polygon `tip0, valley0, tip1, ...`.
#[must_use]
pub fn ideal_outline(n: usize, r_tip: f64, r_root: f64) -> Vec<P2> {
    let tips: Vec<f64> = (0..n).map(|k| TAU * k as f64 / n as f64).collect();
    outline_from_tips(&tips, r_tip, r_root)
}

/// Outline from explicit tip angles (increasing, spanning less than one turn): tip `k` at
/// `tips[k]` and radius `r_tip`, valley `k` midway in angle between tip `k` and tip `k + 1` at
/// radius `r_root`; the last valley lies between the last tip and `tips[0] + 2 pi`.
#[must_use]
pub fn outline_from_tips(tips: &[f64], r_tip: f64, r_root: f64) -> Vec<P2> {
    let n = tips.len();
    let mut out = Vec::with_capacity(2 * n);
    for (k, &t) in tips.iter().enumerate() {
        let next = if k + 1 < n {
            tips[k + 1]
        } else {
            tips[0] + TAU
        };
        let v = 0.5 * (t + next);
        out.push(polar(r_tip, t));
        out.push(polar(r_root, v));
    }
    out
}

/// Outline from explicit tip and valley angles (asymmetric teeth): tip `k` at `tips[k]` and
/// radius `r_tip`, valley `k` at `valleys[k]` and radius `r_root`, as `tip0, valley0, tip1, ...`.
/// The angles are taken as given; valley `k` should lie between tip `k` and tip `k + 1`.
#[must_use]
pub fn outline_from_angles(tips: &[f64], valleys: &[f64], r_tip: f64, r_root: f64) -> Vec<P2> {
    tips.iter()
        .zip(valleys)
        .flat_map(|(&t, &v)| [polar(r_tip, t), polar(r_root, v)])
        .collect()
}

/// Outline from explicit polar vertices (a gear that is not round): tip `k` at radius
/// `tip_radii[k]` and angle `tips[k]`, valley `k` at radius `root_radii[k]` and angle
/// `valleys[k]`, as `tip0, valley0, tip1, ...`.
#[must_use]
pub fn outline_from_polar(
    tips: &[f64],
    tip_radii: &[f64],
    valleys: &[f64],
    root_radii: &[f64],
) -> Vec<P2> {
    tips.iter()
        .zip(tip_radii)
        .zip(valleys.iter().zip(root_radii))
        .flat_map(|((&t, &rt), (&v, &rv))| [polar(rt, t), polar(rv, v)])
        .collect()
}

/// The point at radius `r` and polar angle `a`.
#[must_use]
pub fn polar(r: f64, a: f64) -> P2 {
    [r * a.cos(), r * a.sin()]
}

/// Rotate `p` counter-clockwise by `a`.
#[must_use]
pub fn rotate(p: P2, a: f64) -> P2 {
    let (s, c) = a.sin_cos();
    [c * p[0] - s * p[1], s * p[0] + c * p[1]]
}

/// Place a gear-frame outline in the world frame of a mesh.
///
/// [`Sense::Driver`]: `origin + Rot(angle) (p - rotation_centre_offset)`;
/// [`Sense::Driven`]: `origin + Rot(pi - angle) (p - rotation_centre_offset)`.
/// For a mesh the driver's `origin` is `[0, 0]` and the driven's `[D, 0]`.
#[must_use]
pub fn place(
    outline: &[P2],
    rotation_centre_offset: P2,
    angle: f64,
    origin: P2,
    mirror_sense: Sense,
) -> Vec<P2> {
    let a = match mirror_sense {
        Sense::Driver => angle,
        Sense::Driven => PI - angle,
    };
    let (s, c) = a.sin_cos();
    outline
        .iter()
        .map(|p| {
            let x = p[0] - rotation_centre_offset[0];
            let y = p[1] - rotation_centre_offset[1];
            [origin[0] + c * x - s * y, origin[1] + s * x + c * y]
        })
        .collect()
}

fn sub(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn cross(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Euclidean distance from `p` to the closed segment `[a, b]`.
#[must_use]
pub fn point_segment_distance(p: P2, a: P2, b: P2) -> f64 {
    let ab = sub(b, a);
    let ap = sub(p, a);
    let len2 = dot(ab, ab);
    let t = if len2 > 0.0 {
        (dot(ap, ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let d = [ap[0] - t * ab[0], ap[1] - t * ab[1]];
    d[0].hypot(d[1])
}

/// Winding number of the closed polygon `poly` around `p` (non-zero means inside).
///
/// Points exactly on the boundary may get either answer; callers that care measure the
/// distance to the boundary as well.
#[must_use]
pub fn winding_number(p: P2, poly: &[P2]) -> i32 {
    let n = poly.len();
    let mut w = 0;
    for i in 0..n {
        let a = poly[i];
        let b = poly[(i + 1) % n];
        let side = cross(sub(b, a), sub(p, a));
        if a[1] <= p[1] {
            if b[1] > p[1] && side > 0.0 {
                w += 1;
            }
        } else if b[1] <= p[1] && side < 0.0 {
            w -= 1;
        }
    }
    w
}

/// Whether `p` is inside `poly` by the winding-number rule.
#[must_use]
pub fn contains(poly: &[P2], p: P2) -> bool {
    winding_number(p, poly) != 0
}

/// Distance from `p` to the boundary of the closed polygon `poly` (`+inf` if it is empty).
#[must_use]
pub fn boundary_distance(p: P2, poly: &[P2]) -> f64 {
    let n = poly.len();
    (0..n)
        .map(|i| point_segment_distance(p, poly[i], poly[(i + 1) % n]))
        .fold(f64::INFINITY, f64::min)
}

/// Axis-aligned bounding box `[min_x, min_y, max_x, max_y]`.
fn bbox(poly: &[P2]) -> [f64; 4] {
    poly.iter().fold(
        [
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ],
        |b, p| {
            [
                b[0].min(p[0]),
                b[1].min(p[1]),
                b[2].max(p[0]),
                b[3].max(p[1]),
            ]
        },
    )
}

fn in_box(b: &[f64; 4], p: P2) -> bool {
    p[0] >= b[0] && p[0] <= b[2] && p[1] >= b[1] && p[1] <= b[3]
}

fn seg_box_meets(b: &[f64; 4], p: P2, q: P2) -> bool {
    p[0].max(q[0]) >= b[0]
        && p[0].min(q[0]) <= b[2]
        && p[1].max(q[1]) >= b[1]
        && p[1].min(q[1]) <= b[3]
}

/// Largest boundary distance of a vertex of `a` lying strictly inside `b` (0 if none).
fn vertex_depth(a: &[P2], b: &[P2], bb: &[f64; 4]) -> f64 {
    a.iter()
        .filter(|&&p| in_box(bb, p) && contains(b, p))
        .map(|&p| boundary_distance(p, b))
        .fold(0.0, f64::max)
}

/// Parameter `t` along `[p1, p2]` where it crosses `[q1, q2]` properly (each strictly
/// separates the other's endpoints).
fn proper_crossing(p1: P2, p2: P2, q1: P2, q2: P2) -> Option<f64> {
    let dp = sub(p2, p1);
    let dq = sub(q2, q1);
    let o1 = cross(dp, sub(q1, p1));
    let o2 = cross(dp, sub(q2, p1));
    let o3 = cross(dq, sub(p1, q1));
    let o4 = cross(dq, sub(p2, q1));
    let strictly = |x: f64, y: f64| (x > 0.0 && y < 0.0) || (x < 0.0 && y > 0.0);
    if !(strictly(o1, o2) && strictly(o3, o4)) {
        return None;
    }
    Some(o3 / (o3 - o4))
}

/// Depth from proper edge crossings: every edge of `a` that crosses `b`'s boundary is cut at
/// the crossings; the midpoint of each piece lying inside `b` contributes its distance to
/// `b`'s boundary. Returns `None` if no edge of `a` crosses `b` properly.
fn crossing_depth(a: &[P2], b: &[P2], bb: &[f64; 4]) -> Option<f64> {
    let (na, nb) = (a.len(), b.len());
    let mut found = false;
    let mut depth: f64 = 0.0;
    let mut ts = Vec::new();
    for i in 0..na {
        let (p1, p2) = (a[i], a[(i + 1) % na]);
        if !seg_box_meets(bb, p1, p2) {
            continue;
        }
        ts.clear();
        for j in 0..nb {
            if let Some(t) = proper_crossing(p1, p2, b[j], b[(j + 1) % nb]) {
                ts.push(t);
            }
        }
        if ts.is_empty() {
            continue;
        }
        found = true;
        ts.push(0.0);
        ts.push(1.0);
        ts.sort_by(f64::total_cmp);
        for w in ts.windows(2) {
            let t = 0.5 * (w[0] + w[1]);
            let m = [p1[0] + t * (p2[0] - p1[0]), p1[1] + t * (p2[1] - p1[1])];
            if contains(b, m) {
                depth = depth.max(boundary_distance(m, b));
            }
        }
    }
    found.then_some(depth)
}

/// How deeply two simple closed polygons interpenetrate.
///
/// `0.0` when they do not overlap (touching counts as `0.0`). Otherwise a positive measure:
/// the largest distance from a vertex of one polygon lying strictly inside the other to the
/// other's boundary; if no vertex is inside but edges cross properly, the largest boundary
/// distance of the midpoints of the edge pieces (between crossings) that lie inside the other
/// polygon, and at least `f64::MIN_POSITIVE`. A vertex lying on the other's boundary contributes (about) zero, so exact
/// contact gives a value at the level of rounding errors.
#[must_use]
pub fn penetration(a: &[P2], b: &[P2]) -> f64 {
    if a.len() < 3 || b.len() < 3 {
        return 0.0;
    }
    let ba = bbox(a);
    let bb = bbox(b);
    let depth = vertex_depth(a, b, &bb).max(vertex_depth(b, a, &ba));
    if depth > 0.0 {
        return depth;
    }
    match (crossing_depth(a, b, &bb), crossing_depth(b, a, &ba)) {
        (None, None) => 0.0,
        (x, y) => x
            .unwrap_or(0.0)
            .max(y.unwrap_or(0.0))
            .max(f64::MIN_POSITIVE),
    }
}

/// Minimum boundary distance between two polygons that do not overlap: the minimum over the
/// vertices of each of the distance to the other's edges. `0.0` if they overlap
/// (`penetration(a, b) > 0`).
#[must_use]
pub fn distance(a: &[P2], b: &[P2]) -> f64 {
    if penetration(a, b) > 0.0 {
        return 0.0;
    }
    let one_way = |a: &[P2], b: &[P2]| {
        a.iter()
            .map(|&p| boundary_distance(p, b))
            .fold(f64::INFINITY, f64::min)
    };
    one_way(a, b).min(one_way(b, a))
}

/// A gear outline in its own frame with the offset of its rotation centre from its
/// geometric centre (gear-frame coordinates).
#[derive(Debug, Clone, PartialEq)]
pub struct GearShape {
    /// Closed CCW outline, gear frame.
    pub outline: Vec<P2>,
    /// Rotation-centre offset `e` in the gear frame.
    pub rotation_centre_offset: P2,
}

impl GearShape {
    /// An ideal gear (see [`ideal_outline`]) rotating about its geometric centre.
    #[must_use]
    pub fn ideal(n: usize, r_tip: f64, r_root: f64) -> Self {
        Self {
            outline: ideal_outline(n, r_tip, r_root),
            rotation_centre_offset: [0.0, 0.0],
        }
    }
}

/// A driver/driven pair at a centre distance, in the world frame of a mesh.
#[derive(Debug, Clone, PartialEq)]
pub struct Mesh {
    /// The driving gear (rotation centre at the world origin, turns CCW).
    pub driver: GearShape,
    /// The driven gear (rotation centre at `(centre_distance, 0)`, turns CW).
    pub driven: GearShape,
    /// Distance `D` between the rotation centres.
    pub centre_distance: f64,
}

/// Number of scan steps of [`push_theta_bruteforce`] before bisection.
pub const PUSH_SCAN_STEPS: usize = 512;

/// Angular tolerance of the bisection in [`push_theta_bruteforce`], radians.
pub const PUSH_TOL: f64 = 1e-13;

impl Mesh {
    /// Two ideal gears rotating about their geometric centres.
    #[must_use]
    pub fn ideal(
        n1: usize,
        r_tip1: f64,
        r_root1: f64,
        n2: usize,
        r_tip2: f64,
        r_root2: f64,
        centre_distance: f64,
    ) -> Self {
        Self {
            driver: GearShape::ideal(n1, r_tip1, r_root1),
            driven: GearShape::ideal(n2, r_tip2, r_root2),
            centre_distance,
        }
    }

    /// Driver outline in the world frame at driver angle `phi`.
    #[must_use]
    pub fn driver_at(&self, phi: f64) -> Vec<P2> {
        place(
            &self.driver.outline,
            self.driver.rotation_centre_offset,
            phi,
            [0.0, 0.0],
            Sense::Driver,
        )
    }

    /// Driven outline in the world frame at driven angle `theta`.
    #[must_use]
    pub fn driven_at(&self, theta: f64) -> Vec<P2> {
        place(
            &self.driven.outline,
            self.driven.rotation_centre_offset,
            theta,
            [self.centre_distance, 0.0],
            Sense::Driven,
        )
    }

    /// [`penetration`] of the two gears at `(phi, theta)`.
    #[must_use]
    pub fn penetration_at(&self, phi: f64, theta: f64) -> f64 {
        penetration(&self.driver_at(phi), &self.driven_at(theta))
    }

    /// [`distance`] between the two gears at `(phi, theta)` (0 if they overlap).
    #[must_use]
    pub fn distance_at(&self, phi: f64, theta: f64) -> f64 {
        distance(&self.driver_at(phi), &self.driven_at(theta))
    }

    /// Whether the gears at `(phi, theta)` touch: penetration at most `tol` and boundary
    /// distance at most `tol` (same length unit as the outlines).
    #[must_use]
    pub fn is_touching(&self, phi: f64, theta: f64, tol: f64) -> bool {
        let a = self.driver_at(phi);
        let b = self.driven_at(theta);
        let pen = penetration(&a, &b);
        pen <= tol && (pen > 0.0 || distance(&a, &b) <= tol)
    }
}

/// Brute-force push angle: the smallest `theta` in `[theta_lo, theta_hi]` such that the
/// driven does not overlap the driver anywhere on `[theta, theta_hi]`, at driver angle `phi`.
///
/// The window is scanned downwards from `theta_hi` in [`PUSH_SCAN_STEPS`] steps until an
/// overlapping sample is found, then the transition is bisected on [`penetration`] to
/// [`PUSH_TOL`] radians; the returned angle is the clear end of the final bracket. `None` if
/// the gears overlap at `theta_hi` (the window does not reach a free position) or if no sample
/// of the window overlaps (the driver does not push within the window). Overlap intervals
/// narrower than the scan step may be missed: keep the window a small fraction of a pitch.
#[must_use]
pub fn push_theta_bruteforce(mesh: &Mesh, phi: f64, theta_lo: f64, theta_hi: f64) -> Option<f64> {
    if theta_hi.is_nan() || theta_lo.is_nan() || theta_hi < theta_lo {
        return None;
    }
    let driver = mesh.driver_at(phi);
    let overlaps = |theta: f64| penetration(&driver, &mesh.driven_at(theta)) > 0.0;
    if overlaps(theta_hi) {
        return None;
    }
    let step = (theta_hi - theta_lo) / PUSH_SCAN_STEPS as f64;
    let mut clear = theta_hi;
    let mut hit = None;
    for i in 1..=PUSH_SCAN_STEPS {
        let t = if i == PUSH_SCAN_STEPS {
            theta_lo
        } else {
            theta_hi - step * i as f64
        };
        if overlaps(t) {
            hit = Some(t);
            break;
        }
        clear = t;
    }
    let mut lo = hit?;
    let mut hi = clear;
    while hi - lo > PUSH_TOL {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if overlaps(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An axis-aligned square, counter-clockwise (also used by `area`'s tests).
    pub(crate) fn square(x0: f64, y0: f64, s: f64) -> Vec<P2> {
        vec![[x0, y0], [x0 + s, y0], [x0 + s, y0 + s], [x0, y0 + s]]
    }

    #[test]
    fn point_segment_distance_cases() {
        assert!((point_segment_distance([0.5, 1.0], [0.0, 0.0], [1.0, 0.0]) - 1.0).abs() < 1e-15);
        assert!((point_segment_distance([2.0, 0.0], [0.0, 0.0], [1.0, 0.0]) - 1.0).abs() < 1e-15);
        assert!((point_segment_distance([3.0, 4.0], [0.0, 0.0], [0.0, 0.0]) - 5.0).abs() < 1e-15);
    }

    #[test]
    fn winding_number_square_and_star() {
        let sq = square(0.0, 0.0, 1.0);
        assert_eq!(winding_number([0.5, 0.5], &sq), 1);
        assert_eq!(winding_number([1.5, 0.5], &sq), 0);
        let mut cw = sq.clone();
        cw.reverse();
        assert_eq!(winding_number([0.5, 0.5], &cw), -1);
        let star = ideal_outline(8, 200.0, 100.0);
        assert!(contains(&star, [0.0, 0.0]));
        assert!(contains(&star, [190.0, 0.0]));
        // Between two tips, outside the valley.
        assert!(!contains(&star, polar(150.0, PI / 8.0)));
        assert!(contains(&star, polar(95.0, PI / 8.0)));
    }

    #[test]
    fn outline_layout() {
        let o = ideal_outline(4, 2.0, 1.0);
        assert_eq!(o.len(), 8);
        assert!((o[0][0] - 2.0).abs() < 1e-15 && o[0][1].abs() < 1e-15);
        let v = polar(1.0, PI / 4.0);
        assert!((o[1][0] - v[0]).abs() < 1e-15 && (o[1][1] - v[1]).abs() < 1e-15);
        let o2 = outline_from_tips(&[0.0, 1.0, 2.0], 2.0, 1.0);
        let last = polar(1.0, 0.5 * (2.0 + TAU));
        assert!((o2[5][0] - last[0]).abs() < 1e-15 && (o2[5][1] - last[1]).abs() < 1e-15);
        let valleys: Vec<f64> = (0..3).map(|k| 0.5 + f64::from(k)).collect();
        assert_eq!(
            outline_from_angles(&[0.0, 1.0, 2.0], &valleys, 2.0, 1.0)[3],
            polar(1.0, 1.5)
        );
        let mid = [0.5, 1.5, 0.5 * (2.0 + TAU)];
        assert_eq!(outline_from_angles(&[0.0, 1.0, 2.0], &mid, 2.0, 1.0), o2);
        assert_eq!(
            outline_from_polar(&[0.0, 1.0, 2.0], &[2.0; 3], &mid, &[1.0; 3]),
            o2
        );
        let bumpy = outline_from_polar(&[0.0, 1.0, 2.0], &[2.0, 2.5, 2.0], &mid, &[1.0, 0.9, 1.0]);
        assert_eq!((bumpy[2], bumpy[3]), (polar(2.5, 1.0), polar(0.9, 1.5)));
    }

    #[test]
    fn place_transforms() {
        let pts = [[1.0, 0.0]];
        let d = place(&pts, [0.0, 0.0], PI / 2.0, [0.0, 0.0], Sense::Driver);
        assert!(d[0][0].abs() < 1e-15 && (d[0][1] - 1.0).abs() < 1e-15);
        // Driven at theta = 0: +x axis points at the driver.
        let q = place(&pts, [0.0, 0.0], 0.0, [10.0, 0.0], Sense::Driven);
        assert!((q[0][0] - 9.0).abs() < 1e-15 && q[0][1].abs() < 1e-15);
        // Driven turns clockwise: a point on its left side moves up.
        let q = place(&pts, [0.0, 0.0], 0.1, [10.0, 0.0], Sense::Driven);
        assert!(q[0][1] > 0.0);
        // Rotation-centre offset: the offset point maps to the origin.
        let e = [0.3, -0.2];
        let d = place(&[e], e, 1.2, [5.0, 1.0], Sense::Driver);
        assert!((d[0][0] - 5.0).abs() < 1e-15 && (d[0][1] - 1.0).abs() < 1e-15);
    }

    #[test]
    fn squares() {
        let a = square(0.0, 0.0, 1.0);
        // Separate.
        let b = square(2.0, 0.0, 1.0);
        assert_eq!(penetration(&a, &b), 0.0);
        assert!((distance(&a, &b) - 1.0).abs() < 1e-15);
        // Sharing an edge: touching.
        let b = square(1.0, 0.0, 1.0);
        assert!(penetration(&a, &b) < 1e-15);
        assert!(distance(&a, &b) < 1e-15);
        // Overlap by 0.25 in x: corners inside at depth 0.25 (distance to the nearest edge).
        let b = square(0.75, 0.25, 1.0);
        assert!((penetration(&a, &b) - 0.25).abs() < 1e-15);
        assert_eq!(distance(&a, &b), 0.0);
        // Containment.
        let b = square(0.25, 0.25, 0.5);
        assert!((penetration(&a, &b) - 0.25).abs() < 1e-15);
        // Symmetric.
        assert!((penetration(&b, &a) - 0.25).abs() < 1e-15);
    }

    #[test]
    fn crossing_without_vertex_inside() {
        // A cross made of two thin rectangles: no vertex of one inside the other.
        let h = vec![[-2.0, -0.1], [2.0, -0.1], [2.0, 0.1], [-2.0, 0.1]];
        let v = vec![[-0.1, -2.0], [0.1, -2.0], [0.1, 2.0], [-0.1, 2.0]];
        let p = penetration(&h, &v);
        assert!((p - 0.1).abs() < 1e-15, "{p}");
        assert_eq!(distance(&h, &v), 0.0);
    }

    #[test]
    fn triangles() {
        let a = vec![[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        // Vertex (1, 1) inside a: distance to the nearest edge (x = 0 or y = 0) is 1.
        let b = vec![[1.0, 1.0], [5.0, 5.0], [1.0, 5.0]];
        assert!((penetration(&a, &b) - 1.0).abs() < 1e-15);
        // Vertex touching the hypotenuse x + y = 4 from outside.
        let b = vec![[2.0, 2.0], [5.0, 2.0], [5.0, 5.0]];
        assert!(penetration(&a, &b) < 1e-15);
        assert!(distance(&a, &b) < 1e-15);
        // Vertex just outside: distance is the gap to the hypotenuse.
        let b = vec![[2.5, 2.5], [5.0, 2.5], [5.0, 5.0]];
        assert!((distance(&a, &b) - 1.0 / 2f64.sqrt()).abs() < 1e-14);
    }

    #[test]
    fn paper_example_overlap_and_clear() {
        // N1 = N2 = 8, R = 200, r = 100, D = 310. At phi = 0 the driver tip 0 is at (200, 0),
        // 110 from the driven centre.
        let m = Mesh::ideal(8, 200.0, 100.0, 8, 200.0, 100.0, 310.0);
        // theta = 0: the driven tip 0 points at the driver tip 0: overlap (deep).
        let p = m.penetration_at(0.0, 0.0);
        assert!(p > 20.0, "{p}");
        // theta = pi/8: the driven valley 0 faces the driver tip 0, which is 110 from the
        // driven centre while the valley is at 100: clear.
        assert_eq!(m.penetration_at(0.0, PI / 8.0), 0.0);
        assert!(m.distance_at(0.0, PI / 8.0) > 1.0);
        // The push angle lies between; the Thorndike value is 17.955 387 657 7 degrees.
        let t = push_theta_bruteforce(&m, 0.0, 0.0, PI / 8.0);
        let t = t.map(f64::to_degrees);
        assert!(
            t.is_some_and(|t| (t - 17.955_387_657_7).abs() < 1e-8),
            "{t:?}"
        );
        if let Some(t) = t {
            let t = t.to_radians();
            assert!(m.is_touching(0.0, t, 1e-9));
            assert!(m.penetration_at(0.0, t - 1e-7) > 0.0);
        }
    }

    #[test]
    fn push_window_edge_cases() {
        let m = Mesh::ideal(8, 200.0, 100.0, 8, 200.0, 100.0, 310.0);
        // Overlap at the top of the window.
        assert_eq!(push_theta_bruteforce(&m, 0.0, -0.1, 0.0), None);
        // No overlap anywhere in the window.
        assert_eq!(push_theta_bruteforce(&m, 0.0, 0.33, 0.39), None);
    }

    #[test]
    fn arc_flank_and_tooth_membership() {
        // Chord (0,0) -> (4,0), sagitta 1 to the right (y < 0): radius 2.5, centre (2, 1.5).
        let f = ArcFlank::new([0.0, 0.0], [4.0, 0.0], 1.0);
        assert!((f.radius - 2.5).abs() < 1e-15);
        assert!((f.centre[0] - 2.0).abs() < 1e-15 && (f.centre[1] - 1.5).abs() < 1e-15);
        let mid = f.point(0.5);
        assert!(
            (mid[0] - 2.0).abs() < 1e-14 && (mid[1] + 1.0).abs() < 1e-14,
            "{mid:?}"
        );
        assert!(f.segment_contains([2.0, -0.9]));
        assert!(!f.segment_contains([2.0, -1.1]));
        assert!(!f.segment_contains([2.0, 0.1]));
        assert!((f.distance([2.0, -3.0]) - 2.0).abs() < 1e-14);
        assert!((f.distance([-1.0, 0.0]) - 1.0).abs() < 1e-14);
        // A tooth (valley (-1,0), tip (0,3), valley (1,0)), counter-clockwise: the triangle's
        // flanks bulge outwards (convex) or inwards (concave) by 0.2 at their middles.
        let (v0, t, v1) = ([1.0, 0.0], [0.0, 3.0], [-1.0, 0.0]);
        let mid0 = [0.5, 1.5];
        let out = [3.0 / 10f64.sqrt(), 1.0 / 10f64.sqrt()];
        let at = |d: f64| [mid0[0] + d * out[0], mid0[1] + d * out[1]];
        assert!(tooth_contains(v0, t, v1, 0.2, at(0.19)));
        assert!(!tooth_contains(v0, t, v1, 0.2, at(0.21)));
        assert!(!tooth_contains(v0, t, v1, 0.0, at(0.01)));
        assert!(tooth_contains(v0, t, v1, 0.0, at(-0.01)));
        assert!(!tooth_contains(v0, t, v1, -0.2, at(-0.19)));
        assert!(tooth_contains(v0, t, v1, -0.2, at(-0.21)));
    }

    #[test]
    fn curved_mesh_depth_is_exact_for_a_bulge_against_a_flat() {
        // Two "gears" that are single squares facing each other: the driver's right side bulges
        // by s, so at a gap g between the squares' sides the outlines' gap is g − s (g if s < 0:
        // the corners still face each other).
        let square = |x0: f64| vec![[x0, -0.5], [x0 + 1.0, -0.5], [x0 + 1.0, 0.5], [x0, 0.5]];
        for (s, g) in [(0.02, 0.1), (0.1, 0.05), (-0.1, 0.1)] {
            let m = CurvedMesh {
                driver: CurvedShape {
                    vertices: square(0.0),
                    sagitta: s,
                    rotation_centre_offset: [0.0, 0.0],
                },
                driven: CurvedShape {
                    vertices: square(0.0),
                    sagitta: 0.0,
                    rotation_centre_offset: [0.0, 0.0],
                },
                // The driven square, turned by pi, spans x in [D - 1, D].
                centre_distance: 2.0 + g,
            };
            let d = m.signed_depth_at(0.0, 0.0);
            // The driven square spans x in [1 + g, 2 + g]: the gap is g less a convex bulge.
            let want = s.max(0.0) - g;
            assert!((d - want).abs() < 1e-9, "s {s}, g {g}: {d} vs {want}");
        }
    }
}
