//! The paper's kind of contact test, as a model to experiment with: two ideal gears as polygons,
//! in contact when the **area** of their intersection exceeds a tolerance.
//!
//! The paper's Python program "is based on detecting intersections between the areas of the
//! gears" and does not say how small an intersection it counted. An area test that ignores
//! overlaps up to `tolerance` mm² lets a tip sink into the flank it pushes until the sliver it
//! cuts off reaches that area: near the tips the teeth act slightly shorter. Blunt tips (every
//! tip cut flat `blunt` mm below its apex, the flanks unchanged) do the same by shape. This
//! module runs one ideal pair over one driver pitch under either, so an experiment can ask what
//! they do to the Theoretical Difference.
//!
//! Teeth are convex polygons (a triangle, or a quadrilateral when blunt); two teeth overlap when
//! no edge of either separates them, and their overlap area is one clipped against the other
//! (Sutherland-Hodgman). The gear bodies (inside the root circles) are not polygons: a tooth
//! corner inside the other gear's root circle counts as an infinite overlap. The driven angle
//! is found by bisection on the area, never by a fixed step. Frames are the crate's
//! ([`crate::place`]): the driver turns counter-clockwise about the origin, the driven
//! clockwise about `(D, 0)`.

use std::f64::consts::{PI, TAU};

use crate::{P2, polar};

/// Bisection tolerance on the driven angle, radians.
const ANGLE_TOL: f64 = 1e-10;

/// Teeth on either side of the line of centres that are tested: the teeth of a mesh touch
/// within a pitch or so of it (the tooth height is below a pitch), so two on each side cover
/// every contact with a tooth to spare.
const NEAR_TEETH: i64 = 2;

/// One ideal pair under an area contact test.
#[derive(Debug, Clone)]
pub struct AreaPair {
    /// Driver teeth.
    pub n1: usize,
    /// Driven teeth.
    pub n2: usize,
    /// Driver tip radius (of the sharp apex), mm.
    pub r1: f64,
    /// Driven tip radius, mm.
    pub r2: f64,
    /// Tooth height of both gears (apex to valley), mm.
    pub h: f64,
    /// Centre distance, mm.
    pub centre_distance: f64,
    /// Overlap area ignored by the contact test, mm² (0: any overlap is contact).
    pub tolerance: f64,
    /// Depth cut flat off every tip, mm (0: sharp tips).
    pub blunt: f64,
}

/// One driver pitch of an ideal pair, started in contact at driver angle 0.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PitchRun {
    /// Standard deviation of the driven gear's Theoretical Difference over the pitch, degrees.
    pub sigma_deg: f64,
    /// Whether the driven gear stood still at some sample (no tooth pushed it): lost contact.
    pub lost_contact: bool,
}

/// A tooth of a gear with `n` teeth, tip radius `r_tip`, root radius `r_tip - h`, tip `blunt`
/// mm flattened: its convex outline in the gear frame, tooth `k` centred on polar angle
/// `2 pi k / n`, counter-clockwise.
#[must_use]
pub fn tooth(n: usize, r_tip: f64, h: f64, blunt: f64, k: i64) -> Vec<P2> {
    let half = PI / n as f64;
    let c = TAU * k as f64 / n as f64;
    let apex = polar(r_tip, c);
    let right = polar(r_tip - h, c - half);
    let left = polar(r_tip - h, c + half);
    if blunt <= 0.0 {
        return vec![right, apex, left];
    }
    // The flat top is perpendicular to the tooth's axis, `blunt` below the apex along it: each
    // flank is cut where its distance along the axis has fallen by `blunt`.
    let cut = |valley: P2| {
        let axis = [c.cos(), c.sin()];
        let along = |p: P2| p[0] * axis[0] + p[1] * axis[1];
        let (a, v) = (along(apex), along(valley));
        let t = (blunt / (a - v)).clamp(0.0, 1.0);
        [
            apex[0] + t * (valley[0] - apex[0]),
            apex[1] + t * (valley[1] - apex[1]),
        ]
    };
    vec![right, cut(right), cut(left), left]
}

/// The mean of a polygon's vertices.
fn vertex_mean(p: &[P2]) -> P2 {
    let n = p.len() as f64;
    let (x, y) = p.iter().fold((0.0, 0.0), |(x, y), v| (x + v[0], y + v[1]));
    [x / n, y / n]
}

/// The largest distance from a polygon's vertex mean to its vertices: the polygon lies in that
/// circle.
fn bounding_radius(p: &[P2]) -> f64 {
    let c = vertex_mean(p);
    p.iter()
        .map(|v| (v[0] - c[0]).hypot(v[1] - c[1]))
        .fold(0.0, f64::max)
}

/// Twice the signed area of a polygon (positive counter-clockwise).
pub(crate) fn twice_area(p: &[P2]) -> f64 {
    (0..p.len())
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % p.len()]);
            a[0] * b[1] - a[1] * b[0]
        })
        .sum()
}

/// Whether two convex polygons overlap with positive area (separating axis test; touching is
/// not overlapping).
#[must_use]
pub fn convex_overlap(a: &[P2], b: &[P2]) -> bool {
    let separated_by = |poly: &[P2]| {
        (0..poly.len()).any(|i| {
            let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
            let axis = [p[1] - q[1], q[0] - p[0]];
            let span = |s: &[P2]| {
                s.iter()
                    .map(|v| v[0] * axis[0] + v[1] * axis[1])
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), d| {
                        (lo.min(d), hi.max(d))
                    })
            };
            let ((alo, ahi), (blo, bhi)) = (span(a), span(b));
            ahi <= blo || bhi <= alo
        })
    };
    !(separated_by(a) || separated_by(b))
}

/// Area of the intersection of two convex polygons (either orientation).
#[must_use]
pub fn convex_overlap_area(a: &[P2], b: &[P2]) -> f64 {
    let mut clipper = b.to_vec();
    if twice_area(&clipper) < 0.0 {
        clipper.reverse();
    }
    let mut out = a.to_vec();
    for i in 0..clipper.len() {
        if out.is_empty() {
            return 0.0;
        }
        let (e0, e1) = (clipper[i], clipper[(i + 1) % clipper.len()]);
        let side = |p: P2| (e1[0] - e0[0]) * (p[1] - e0[1]) - (e1[1] - e0[1]) * (p[0] - e0[0]);
        let input = std::mem::take(&mut out);
        for j in 0..input.len() {
            let (p, q) = (input[j], input[(j + 1) % input.len()]);
            let (sp, sq) = (side(p), side(q));
            let crossing = || {
                let t = sp / (sp - sq);
                [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]
            };
            match (sp >= 0.0, sq >= 0.0) {
                (true, true) => out.push(q),
                (true, false) => out.push(crossing()),
                (false, true) => {
                    out.push(crossing());
                    out.push(q);
                }
                (false, false) => {}
            }
        }
    }
    0.5 * twice_area(&out).abs()
}

impl AreaPair {
    /// Total overlap area of the teeth near the line of centres at `(phi, theta)`, mm²;
    /// infinite when a tooth corner lies inside the other gear's root circle.
    #[must_use]
    pub fn overlap_area(&self, phi: f64, theta: f64) -> f64 {
        let d = self.centre_distance;
        let k0 = (-phi / TAU * self.n1 as f64).round() as i64;
        let j0 = (theta / TAU * self.n2 as f64).round() as i64;
        // Tooth k is tooth 0 turned by its pitch angle: one rotation per tooth, in the world.
        let placed = |template: &[P2], angle: f64, centre: f64| -> Vec<P2> {
            let (sn, cs) = angle.sin_cos();
            template
                .iter()
                .map(|p| [centre + cs * p[0] - sn * p[1], sn * p[0] + cs * p[1]])
                .collect()
        };
        let template1 = tooth(self.n1, self.r1, self.h, self.blunt, 0);
        let template2 = tooth(self.n2, self.r2, self.h, self.blunt, 0);
        let drivers: Vec<Vec<P2>> = (k0 - NEAR_TEETH..=k0 + NEAR_TEETH)
            .map(|k| placed(&template1, phi + TAU * k as f64 / self.n1 as f64, 0.0))
            .collect();
        let driven: Vec<Vec<P2>> = (j0 - NEAR_TEETH..=j0 + NEAR_TEETH)
            .map(|j| placed(&template2, PI - theta + TAU * j as f64 / self.n2 as f64, d))
            .collect();
        let (root1, root2) = (self.r1 - self.h, self.r2 - self.h);
        let in_root = drivers
            .iter()
            .flatten()
            .any(|v| (v[0] - d) * (v[0] - d) + v[1] * v[1] < root2 * root2)
            || driven
                .iter()
                .flatten()
                .any(|v| v[0] * v[0] + v[1] * v[1] < root1 * root1);
        if in_root {
            return f64::INFINITY;
        }
        // Two teeth whose bounding circles (about their vertex means) are apart cannot overlap.
        let apart = bounding_radius(&template1) + bounding_radius(&template2);
        let means: Vec<P2> = driven.iter().map(|b| vertex_mean(b)).collect();
        let mut area = 0.0;
        for a in &drivers {
            let ca = vertex_mean(a);
            for (b, cb) in driven.iter().zip(&means) {
                let (dx, dy) = (ca[0] - cb[0], ca[1] - cb[1]);
                if dx * dx + dy * dy >= apart * apart {
                    continue;
                }
                if convex_overlap(a, b) {
                    area += convex_overlap_area(a, b);
                }
            }
        }
        area
    }

    /// Whether the test reports contact at `(phi, theta)`.
    #[must_use]
    pub fn in_contact(&self, phi: f64, theta: f64) -> bool {
        self.overlap_area(phi, theta) > self.tolerance
    }

    /// The driven angle in `[lo, hi]` where contact ends (`lo` in contact, `hi` not), by
    /// bisection.
    fn bisect(&self, phi: f64, mut lo: f64, mut hi: f64) -> f64 {
        while hi - lo > ANGLE_TOL {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.in_contact(phi, mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        hi
    }

    /// The driven angle at driver angle 0 where the driver tooth behind it touches it: from the
    /// driven gear centred on the driver's tip (tip in valley), turned back until contact.
    /// None when it never touches within a driven pitch (no contact: decoupled) or the centred
    /// position is already in contact (jammed).
    fn start(&self) -> Option<f64> {
        let pitch = TAU / self.n2 as f64;
        let mut clear = 0.5 * pitch;
        if self.in_contact(0.0, clear) {
            return None;
        }
        // Once the pusher overlaps, turning further back keeps it overlapping for a whole
        // tooth width: a coarse scan cannot step over the first contact.
        let step = pitch / 64.0;
        for _ in 0..64 {
            let next = clear - step;
            if self.in_contact(0.0, next) {
                return Some(self.bisect(0.0, next, clear));
            }
            clear = next;
        }
        None
    }

    /// Where the driven gear at `theta`, in contact at driver angle `phi`, is pushed to: the
    /// first angle ahead free of contact. The last step (`guess`) predicts it, so the bracket
    /// is usually tight; otherwise it doubles from `scale` up to `limit`. None: no free angle
    /// within `limit` (a jam).
    fn push(&self, phi: f64, theta: f64, guess: f64, limit: f64, scale: f64) -> Option<f64> {
        let margin = 1e-3 * scale.max(guess.abs());
        let (lo, hi) = (theta + guess - margin, theta + guess + margin);
        if guess > 0.0 && lo > theta && self.in_contact(phi, lo) && !self.in_contact(phi, hi) {
            return Some(self.bisect(phi, lo, hi));
        }
        let mut reach = 2.0 * scale;
        while self.in_contact(phi, theta + reach) {
            reach *= 2.0;
            if reach > limit {
                return None;
            }
        }
        Some(self.bisect(phi, theta, theta + reach))
    }

    /// One driver pitch from driver angle 0, started in contact, sampled at `samples` driver
    /// angles: the driven angle at each is where the test stops reporting contact, pushed on
    /// from the last one. None when the pair does not start (see `start`) or jams (no
    /// position within half a driven pitch ahead is free of contact).
    #[must_use]
    pub fn run_pitch(&self, samples: usize) -> Option<PitchRun> {
        let samples = samples.max(2);
        let theta0 = self.start()?;
        let ratio = self.n1 as f64 / self.n2 as f64;
        let dphi = TAU / self.n1 as f64 / samples as f64;
        let half_pitch = PI / self.n2 as f64;
        let mut theta = theta0;
        let mut last_step = 0.0;
        let mut lost_contact = false;
        let mut acc = Vec::with_capacity(samples);
        for i in 0..samples {
            let phi = dphi * i as f64;
            if i > 0 {
                if self.in_contact(phi, theta) {
                    let next = self.push(phi, theta, last_step, half_pitch, ratio * dphi)?;
                    last_step = next - theta;
                    theta = next;
                } else {
                    lost_contact = true;
                    last_step = 0.0;
                }
            }
            acc.push((theta - theta0 - ratio * phi).to_degrees());
        }
        let n = acc.len() as f64;
        let mean = acc.iter().sum::<f64>() / n;
        let var = acc.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>() / (n - 1.0);
        Some(PitchRun {
            sigma_deg: var.sqrt(),
            lost_contact,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tests::square;

    #[test]
    fn overlap_area_of_squares_and_a_triangle_is_exact() {
        let a = square(0.0, 0.0, 2.0);
        assert!((convex_overlap_area(&a, &square(1.0, 1.0, 2.0)) - 1.0).abs() < 1e-14);
        assert!((convex_overlap_area(&a, &square(0.5, -1.0, 1.0)) - 0.0).abs() < 1e-14);
        // Clockwise clipper, triangle subject: the half of the unit square under the diagonal.
        let mut b = square(0.0, 0.0, 1.0);
        b.reverse();
        let tri = vec![[0.0, 0.0], [3.0, 0.0], [0.0, 3.0]];
        let got = convex_overlap_area(&tri, &b);
        assert!((got - 1.0).abs() < 1e-14, "{got}");
        assert!(
            !convex_overlap(&a, &square(2.0, 0.0, 1.0)),
            "touching edges"
        );
        assert!(convex_overlap(&a, &square(1.9, 1.9, 1.0)));
    }

    #[test]
    fn a_blunt_tooth_is_cut_flat_at_its_depth_along_the_axis() {
        let (n, r, h, b) = (20, 10.0, 1.1, 0.11);
        let t = tooth(n, r, h, b, 0);
        assert_eq!(t.len(), 4);
        // Tooth 0's axis is +x: both corners of the flat lie at x = r - b.
        assert!((t[1][0] - (r - b)).abs() < 1e-12 && (t[2][0] - (r - b)).abs() < 1e-12);
        assert!((t[1][1] + t[2][1]).abs() < 1e-12, "symmetric");
        assert_eq!(tooth(n, r, h, 0.0, 0).len(), 3);
    }

    fn pair(tolerance: f64, blunt: f64, g: f64) -> AreaPair {
        let (r1, r2, h) = (15.415_349_369_988_546, 9.152_863_688_430_7, 1.1);
        AreaPair {
            n1: 64,
            n2: 38,
            r1,
            r2,
            h,
            centre_distance: r1 + r2 - h + g * h,
            tolerance,
            blunt,
        }
    }

    #[test]
    fn a_tolerance_or_blunt_tips_let_the_driven_gear_lag_more_and_lose_contact_sooner() {
        // At 40 % of h every variant runs; with a tolerance or blunt tips the teeth act shorter,
        // so at 90 % the exact test still drives while the others lose contact.
        let sharp = pair(0.0, 0.0, 0.9).run_pitch(200).expect("runs");
        assert!(!sharp.lost_contact);
        for p in [pair(0.01, 0.0, 0.9), pair(0.0, 0.2, 0.9)] {
            assert!(p.run_pitch(200).is_none_or(|r| r.lost_contact), "{p:?}");
        }
        // The driven gear sits further back (the tip sinks in), never ahead.
        let exact = pair(0.0, 0.0, 0.4);
        let loose = pair(0.003, 0.0, 0.4);
        let (a, b) = (
            exact.start().expect("starts"),
            loose.start().expect("starts"),
        );
        assert!(b < a - 1e-6, "{b} vs {a}");
        // And the area it ignores is the tolerance: just below the push angle it exceeds it.
        assert!(loose.overlap_area(0.0, b) <= 0.003 + 1e-12);
        assert!(loose.overlap_area(0.0, b - 1e-6) > 0.003);
    }
}
