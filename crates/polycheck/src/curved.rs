//! Gears with circular-arc flanks: whether a point lies inside is decided exactly (the polygon of
//! vertices, plus or minus the circular segments between each flank's chord and its arc), and
//! the arcs' points are parametrised densely and refined by a golden-section search, never
//! intersected.

use crate::{P2, Sense, contains, cross, dot, place, point_segment_distance, rotate, sub};

/// A circular-arc flank from `start` to `end` bulging by the signed sagitta `sagitta`: positive
/// to the right of `start → end` (out of a counter-clockwise outline: convex), negative to the
/// left (concave). Built here from its definition, independently of the solver's geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ArcFlank {
    /// First end.
    pub start: P2,
    /// Second end.
    pub end: P2,
    /// Signed sagitta (non-zero).
    pub sagitta: f64,
    /// Centre of the arc's circle.
    pub centre: P2,
    /// Radius of the arc's circle.
    pub radius: f64,
}

impl ArcFlank {
    /// The arc through `start` and `end` whose middle lies `sagitta` to the right of the chord.
    #[must_use]
    pub fn new(start: P2, end: P2, sagitta: f64) -> Self {
        let d = sub(end, start);
        let c = d[0].hypot(d[1]);
        let right = [d[1] / c, -d[0] / c];
        // The arc's middle, and the centre found from it: the radius satisfies
        // (r − |s|)² + (c/2)² = r², so r = (c²/4 + s²) / (2|s|), measured back from the middle.
        let radius = (0.25 * c * c + sagitta * sagitta) / (2.0 * sagitta.abs());
        let mid = [
            0.5 * (start[0] + end[0]) + sagitta * right[0],
            0.5 * (start[1] + end[1]) + sagitta * right[1],
        ];
        let back = radius * sagitta.signum();
        Self {
            start,
            end,
            sagitta,
            centre: [mid[0] - back * right[0], mid[1] - back * right[1]],
            radius,
        }
    }

    /// Whether `p` is on the bulge side of the chord (or on it).
    fn beyond_chord(&self, p: P2) -> bool {
        let side = cross(sub(self.end, self.start), sub(p, self.start));
        if self.sagitta > 0.0 {
            side <= 0.0
        } else {
            side >= 0.0
        }
    }

    /// Whether `p` lies in the circular segment between the chord and the arc (boundary
    /// included).
    #[must_use]
    pub fn segment_contains(&self, p: P2) -> bool {
        let q = sub(p, self.centre);
        dot(q, q) <= self.radius * self.radius && self.beyond_chord(p)
    }

    /// The point a fraction `t` of the way along the arc, by angle (0: `start`, 1: `end`).
    #[must_use]
    pub fn point(&self, t: f64) -> P2 {
        let a = sub(self.start, self.centre);
        let b = sub(self.end, self.centre);
        // The arc is under a half circle: the angle between the two radii is its sweep.
        let sweep = cross(a, b).atan2(dot(a, b));
        let p = rotate(a, t * sweep);
        [self.centre[0] + p[0], self.centre[1] + p[1]]
    }

    /// Distance from `p` to the arc: to the circle where the ray from the centre through `p`
    /// meets the arc, otherwise to the nearer end.
    #[must_use]
    pub fn distance(&self, p: P2) -> f64 {
        let q = sub(p, self.centre);
        let len = q[0].hypot(q[1]);
        let ends = {
            let (a, b) = (sub(p, self.start), sub(p, self.end));
            a[0].hypot(a[1]).min(b[0].hypot(b[1]))
        };
        if len > 0.0 {
            let foot = [
                self.centre[0] + q[0] * self.radius / len,
                self.centre[1] + q[1] * self.radius / len,
            ];
            if self.beyond_chord(foot) {
                return (len - self.radius).abs().min(ends);
            }
        }
        ends
    }
}

/// Whether `p` lies in the tooth (valley `v0`, tip `t`, valley `v1`) whose two flanks are arcs of
/// sagitta `sagitta` (0: the triangle): a convex tooth is the triangle and the circular segments
/// outside its flanks, a concave one the triangle less the segments inside them. Exact.
#[must_use]
pub fn tooth_contains(v0: P2, t: P2, v1: P2, sagitta: f64, p: P2) -> bool {
    let tri = contains(&[v0, t, v1], p);
    if sagitta == 0.0 {
        return tri;
    }
    let mut segments = [ArcFlank::new(v0, t, sagitta), ArcFlank::new(t, v1, sagitta)]
        .into_iter()
        .map(|f| f.segment_contains(p));
    if sagitta > 0.0 {
        tri || segments.any(|x| x)
    } else {
        tri && !segments.any(|x| x)
    }
}

/// A gear outline with circular-arc flanks, in its own frame: `vertices` as
/// `tip0, valley0, tip1, ...` (counter-clockwise, as from [`outline_from_polar`](crate::outline_from_polar)), every flank an
/// arc of `sagitta` between consecutive vertices, turning about `rotation_centre_offset`.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvedShape {
    /// Tip and valley vertices, gear frame.
    pub vertices: Vec<P2>,
    /// Signed sagitta of every flank (0: straight flanks).
    pub sagitta: f64,
    /// Rotation-centre offset `e` in the gear frame.
    pub rotation_centre_offset: P2,
}

/// Points tried along every flank by [`CurvedMesh`] before refining.
pub const FLANK_SAMPLES: usize = 48;

/// A placed gear with arc flanks: its vertices in the world and its flanks.
struct Placed {
    vertices: Vec<P2>,
    flanks: Vec<ArcFlank>,
    straight: bool,
    /// Rotation centre in the world, and the largest distance of the outline from it.
    centre: P2,
    reach: f64,
}

impl Placed {
    fn new(shape: &CurvedShape, angle: f64, origin: P2, sense: Sense) -> Self {
        let vertices = place(
            &shape.vertices,
            shape.rotation_centre_offset,
            angle,
            origin,
            sense,
        );
        let n = vertices.len();
        let s = shape.sagitta;
        let flanks: Vec<ArcFlank> = (0..n)
            .map(|i| {
                let (a, b) = (vertices[i], vertices[(i + 1) % n]);
                if s == 0.0 {
                    // A straight flank, as an arc of negligible sagitta for sampling only.
                    ArcFlank {
                        start: a,
                        end: b,
                        sagitta: 0.0,
                        centre: a,
                        radius: 0.0,
                    }
                } else {
                    ArcFlank::new(a, b, s)
                }
            })
            .collect();
        let reach = vertices
            .iter()
            .map(|&v| {
                let d = sub(v, origin);
                d[0].hypot(d[1])
            })
            .fold(0.0, f64::max)
            + s.max(0.0);
        Self {
            vertices,
            flanks,
            straight: s == 0.0,
            centre: origin,
            reach,
        }
    }

    fn point(&self, f: usize, t: f64) -> P2 {
        let fl = &self.flanks[f];
        if self.straight {
            [
                fl.start[0] + t * (fl.end[0] - fl.start[0]),
                fl.start[1] + t * (fl.end[1] - fl.start[1]),
            ]
        } else {
            fl.point(t)
        }
    }

    fn contains(&self, p: P2) -> bool {
        let poly = contains(&self.vertices, p);
        if self.straight {
            return poly;
        }
        let mut segments = self.flanks.iter().map(|f| f.segment_contains(p));
        if self.flanks[0].sagitta > 0.0 {
            poly || segments.any(|x| x)
        } else {
            poly && !segments.any(|x| x)
        }
    }

    fn boundary_distance(&self, p: P2) -> f64 {
        self.flanks
            .iter()
            .map(|f| {
                if self.straight {
                    point_segment_distance(p, f.start, f.end)
                } else {
                    f.distance(p)
                }
            })
            .fold(f64::INFINITY, f64::min)
    }

    /// How deep `p` lies inside this gear (positive) or how far outside it (negative).
    fn signed_depth(&self, p: P2) -> f64 {
        let d = self.boundary_distance(p);
        if self.contains(p) { d } else { -d }
    }

    /// Whether flank `f` may come within `reach` of `centre` (an arc stays within |s| of its chord).
    fn flank_near(&self, f: usize, centre: P2, reach: f64) -> bool {
        let fl = &self.flanks[f];
        point_segment_distance(centre, fl.start, fl.end) <= reach + fl.sagitta.abs()
    }
}

/// The largest signed depth of a point of `a`'s outline in `b`: positive when they overlap (how
/// deep), negative when they do not (minus the gap). Each flank of `a` that may reach `b` is
/// tried at [`FLANK_SAMPLES`] + 1 points, and around its best one the depth is maximised by a
/// golden-section search on the arc's parameter.
fn deepest(a: &Placed, b: &Placed) -> f64 {
    let n = FLANK_SAMPLES;
    let mut best = f64::NEG_INFINITY;
    for f in 0..a.flanks.len() {
        if !a.flank_near(f, b.centre, b.reach) {
            continue;
        }
        let depth = |t: f64| b.signed_depth(a.point(f, t));
        let (mut top, mut at) = (f64::NEG_INFINITY, 0);
        for i in 0..=n {
            let d = depth(i as f64 / n as f64);
            if d > top {
                (top, at) = (d, i);
            }
        }
        let (mut lo, mut hi) = (
            at.saturating_sub(1) as f64 / n as f64,
            (at + 1).min(n) as f64 / n as f64,
        );
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut f1, mut f2) = (depth(x1), depth(x2));
        for _ in 0..80 {
            if f1 > f2 {
                hi = x2;
                (x2, f2) = (x1, f1);
                x1 = hi - g * (hi - lo);
                f1 = depth(x1);
            } else {
                lo = x1;
                (x1, f1) = (x2, f2);
                x2 = lo + g * (hi - lo);
                f2 = depth(x2);
            }
        }
        best = best.max(top).max(f1).max(f2);
    }
    best
}

/// Two gears with arc flanks in the world frame of a mesh (as [`Mesh`](crate::Mesh)).
#[derive(Debug, Clone, PartialEq)]
pub struct CurvedMesh {
    /// The driving gear (rotation centre at the world origin, turns CCW).
    pub driver: CurvedShape,
    /// The driven gear (rotation centre at `(centre_distance, 0)`, turns CW).
    pub driven: CurvedShape,
    /// Distance `D` between the rotation centres.
    pub centre_distance: f64,
}

impl CurvedMesh {
    fn placed(&self, phi: f64, theta: f64) -> (Placed, Placed) {
        (
            Placed::new(&self.driver, phi, [0.0, 0.0], Sense::Driver),
            Placed::new(
                &self.driven,
                theta,
                [self.centre_distance, 0.0],
                Sense::Driven,
            ),
        )
    }

    /// The largest signed depth of either outline in the other at `(phi, theta)`: positive when
    /// they overlap, minus their gap otherwise (`-inf` when no flank of either comes within the
    /// other's reach).
    #[must_use]
    pub fn signed_depth_at(&self, phi: f64, theta: f64) -> f64 {
        let (a, b) = self.placed(phi, theta);
        deepest(&a, &b).max(deepest(&b, &a))
    }

    /// How deeply the gears interpenetrate at `(phi, theta)` (0 if they do not).
    #[must_use]
    pub fn penetration_at(&self, phi: f64, theta: f64) -> f64 {
        self.signed_depth_at(phi, theta).max(0.0)
    }

    /// The gap between the gears at `(phi, theta)` (0 if they overlap).
    #[must_use]
    pub fn distance_at(&self, phi: f64, theta: f64) -> f64 {
        (-self.signed_depth_at(phi, theta)).max(0.0)
    }
}
