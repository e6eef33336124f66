//! The contact roots of a tooth pair when a gear has curved flanks: every condition is a
//! crossing of two known curves (a vertex on an arc is two circles crossing; a convex arc on a
//! straight flank is the arc's centre reaching the flank offset by its radius; two arcs touch
//! when their centres are the sum or difference of the radii apart), and a root counts only where
//! its touching point lies on both flanks. Pairs of straight-flanked gears never come here.

use geometry::{Arc, Vec2};

use super::{EVALS, FirstAfter, Mesh, conj, pseudo_angle};
use crate::roots::{circle_circle, circle_segment};
use crate::tooth::ToothData;

/// The flanks of a tooth as pairs of its vertices (valley k−1, tip k, valley k).
const FLANKS: [(usize, usize); 2] = [(0, 1), (1, 2)];

/// A tooth's three vertices and its two flank arcs (None where a flank is straight).
type Outline = ([Vec2; 3], [Option<Arc>; 2]);

impl Mesh {
    /// [`Mesh::first_touch`] when a gear has curved flanks. With θ fixed every contact condition
    /// is again a crossing of two known curves: a driver vertex (on a circle about the origin) on
    /// a driven flank; a driven vertex (a circle in the driver's frame) on a driver flank; and a
    /// driver arc touching a driven flank, where the arc's centre, on a circle about the origin,
    /// reaches a segment offset by the arc's radius or a circle about the other arc's centre.
    pub(super) fn first_touch_curved(&self, theta: f64, phi0: f64, phi1: f64) -> Option<f64> {
        let (d1, d2) = (&self.driver, &self.driven);
        let rest = self.resting(theta, phi0, phi1);
        let ((lo_j, hi_j), ks) = (rest.drivers, rest.ks.clone());
        let place = |v: Vec2| rest.place(v);
        let mut first = FirstAfter::new(phi0, phi1);
        let mut take = |phi: f64| first.take(phi);
        for k in ks {
            let b = (d2.tooth(k).map(place), d2.flank_arcs(k, place));
            for j in lo_j..=hi_j {
                let a = (d1.tooth(j), d1.flank_arcs(j, |v| v));
                vertices_at_rest(a, b, &mut take);
                flanks_at_rest(a, b, &mut take);
            }
        }
        first.get()
    }

    /// [`Mesh::tooth_pair`] when a gear has curved flanks: the driver tooth `a` and its flank arcs
    /// `fa` are placed in the world. The roots are those of straight flanks (vertex on flank, now
    /// on an arc where a flank is one: two circles crossing) and flank on flank: a convex arc on a
    /// straight flank (its centre, on a circle about its gear's centre, meets the flank offset by
    /// the radius), two convex arcs (their centres `r_a + r_b` apart) and a convex arc inside a
    /// concave one of larger radius (`r_concave − r_convex` apart); each is kept only when the
    /// touching point lies on both flanks. Two concave arcs, or a concave arc and a straight
    /// flank, cannot touch at points inside both: they meet first at a vertex.
    ///
    /// The obstacle is still the hull of the roots: every root is a configuration in which the
    /// teeth touch, and the driven angles at which two teeth overlap or touch form one interval,
    /// as for straight flanks, because the allowed arcs (under a half circle, inside the rules of
    /// [`Gear::with_flank_sagitta`]) keep each tooth a single lobe that one passage of the other
    /// tooth enters and leaves once; its ends, being touching configurations, are among the roots.
    #[inline]
    pub(super) fn tooth_pair_curved(
        &self,
        a: [Vec2; 3],
        fa: [Option<Arc>; 2],
        da: &ToothData,
        k: i64,
    ) -> Option<(Vec2, Vec2)> {
        EVALS.with(|c| c.set(c.get() + 1));
        let c2 = self.c2();
        let (db, _) = self.driven.data(k);
        let fb = self.driven.flank_arcs(k, |v| v);
        let mut ends = Extremes::new(db.tip_dir);
        vertex_roots(c2, (a, fa), da, (db.v, fb), db, &mut ends);
        flank_roots(c2, (a, fa), da, (db.v, fb), db, &mut ends);
        ends.get()
    }
}

/// Every point X of a flank - the segment `s → e` (`inv_len2` its inverse squared length), or
/// `arc` where the flank is one - with |X − `c`|² = `rho2`, into `found`.
#[inline]
fn circle_on_flank(
    (c, rho2): (Vec2, f64),
    (s, e): (Vec2, Vec2),
    inv_len2: f64,
    arc: Option<Arc>,
    mut found: impl FnMut(Vec2),
) {
    match arc {
        None => circle_segment(c, rho2, s, e, inv_len2, found),
        Some(arc) => circle_circle(c, rho2, arc.centre, arc.radius, |x| {
            if on_arc(&arc, x) {
                found(x);
            }
        }),
    }
}

/// The argument of `v`.
fn arg(v: Vec2) -> f64 {
    v.y.atan2(v.x)
}

/// [`Mesh::first_touch_curved`]'s vertex-on-flank roots: the driver angles (any turn) at which a
/// vertex of driver tooth `a` (gear frame, at φ = 0) meets a flank of driven tooth `b` (resting,
/// world frame), or a vertex of `b` a flank of `a`, into `take`.
fn vertices_at_rest((a, fa): Outline, (b, fb): Outline, take: &mut impl FnMut(f64)) {
    // Driver vertex (turning about the origin) on a fixed driven flank.
    for p in a {
        let base = arg(p);
        for (f, (u, v)) in FLANKS.into_iter().enumerate() {
            let circle = (Vec2::zeros(), p.norm_squared());
            let inv_len2 = 1.0 / (b[v] - b[u]).norm_squared();
            circle_on_flank(circle, (b[u], b[v]), inv_len2, fb[f], |x| {
                take(arg(x) - base);
            });
        }
    }
    // Fixed driven vertex on a driver flank: in the driver's frame it turns backwards.
    for q in b {
        let base = arg(q);
        for (f, (u, v)) in FLANKS.into_iter().enumerate() {
            let circle = (Vec2::zeros(), q.norm_squared());
            let inv_len2 = 1.0 / (a[v] - a[u]).norm_squared();
            circle_on_flank(circle, (a[u], a[v]), inv_len2, fa[f], |x| {
                take(base - arg(x));
            });
        }
    }
}

/// [`Mesh::first_touch_curved`]'s flank-on-flank roots, through an arc's centre (see
/// [`Mesh::tooth_pair_curved`]), into `take`.
fn flanks_at_rest((a, fa): Outline, (b, fb): Outline, take: &mut impl FnMut(f64)) {
    for (fi, (au, av)) in FLANKS.into_iter().enumerate() {
        for (fj, (bu, bv)) in FLANKS.into_iter().enumerate() {
            match (fa[fi], fb[fj]) {
                (Some(arc), None) if arc.is_convex() => {
                    let n = outward(b[bu], b[bv]) * arc.radius;
                    let base = arg(arc.centre);
                    circle_segment(
                        Vec2::zeros(),
                        arc.centre.norm_squared(),
                        b[bu] + n,
                        b[bv] + n,
                        1.0 / (b[bv] - b[bu]).norm_squared(),
                        |x| take(arg(x) - base),
                    );
                }
                (None, Some(arc)) if arc.is_convex() => {
                    let n = outward(a[au], a[av]) * arc.radius;
                    let base = arg(arc.centre);
                    circle_segment(
                        Vec2::zeros(),
                        arc.centre.norm_squared(),
                        a[au] + n,
                        a[av] + n,
                        1.0 / (a[av] - a[au]).norm_squared(),
                        |x| take(base - arg(x)),
                    );
                }
                (Some(fa), Some(fb)) => {
                    let Some(dist) = tangent_distance(&fa, &fb) else {
                        continue;
                    };
                    let ca = fa.centre;
                    let ca2 = ca.norm_squared();
                    // x: the driver arc's centre once the driver has turned to touch.
                    circle_circle(Vec2::zeros(), ca2, fb.centre, dist, |x| {
                        let t = tangent_point(&fa, &fb, x, fb.centre, dist);
                        // t turned back into the driver's frame at φ = 0:
                        // t·conj(x)·ca / |ca|², as x = ca turned.
                        let back = mul(mul(t, conj(x)), ca) / ca2;
                        if on_arc(&fb, t) && on_arc(&fa, back) {
                            take(arg(x) - arg(ca));
                        }
                    });
                }
                _ => {}
            }
        }
    }
}

/// [`Mesh::tooth_pair_curved`]'s vertex-on-flank roots, with driver tooth `a` placed in the
/// world and driven tooth `b` in its own frame, into `ends`.
fn vertex_roots(
    c2: Vec2,
    (a, fa): Outline,
    da: &ToothData,
    (b, fb): Outline,
    db: &ToothData,
    ends: &mut Extremes,
) {
    // Driver vertex P on a driven flank (driven frame): θ = arg X − arg(P − c2) + π.
    for (p, reaches) in a.into_iter().zip(da.reaches) {
        if !reaches {
            continue;
        }
        let rel = p - c2;
        let circle = (Vec2::zeros(), rel.norm_squared());
        for (f, (s, e)) in FLANKS.into_iter().enumerate() {
            circle_on_flank(circle, (b[s], b[e]), db.inv_len2[f], fb[f], |x| {
                ends.add(x, rel);
            });
        }
    }
    // Driven vertex Q on a driver flank (world): θ = arg Q + π − arg(X − c2).
    for (q, reaches) in b.into_iter().zip(db.reaches) {
        if !reaches {
            continue;
        }
        let circle = (c2, q.norm_squared());
        for (f, (s, e)) in FLANKS.into_iter().enumerate() {
            circle_on_flank(circle, (a[s], a[e]), da.inv_len2[f], fa[f], |x| {
                ends.add(q, x - c2);
            });
        }
    }
}

/// [`Mesh::tooth_pair_curved`]'s flank-on-flank roots, into `ends`.
fn flank_roots(
    c2: Vec2,
    (a, fa): Outline,
    da: &ToothData,
    (b, fb): Outline,
    db: &ToothData,
    ends: &mut Extremes,
) {
    for (fi, (as_, ae)) in FLANKS.into_iter().enumerate() {
        for (fj, (bs, be)) in FLANKS.into_iter().enumerate() {
            match (fa[fi], fb[fj]) {
                // The driver arc's centre W, seen from the driven gear, runs on the circle
                // |W − c2| and must reach the driven flank offset outwards by the radius; the
                // touching point, W's foot on the flank, lies on it exactly when W lies on the
                // offset segment.
                (Some(arc), None) if arc.is_convex() => {
                    let n = outward(b[bs], b[be]) * arc.radius;
                    let w = arc.centre - c2;
                    circle_segment(
                        Vec2::zeros(),
                        w.norm_squared(),
                        b[bs] + n,
                        b[be] + n,
                        db.inv_len2[fj],
                        |x| ends.add(x, w),
                    );
                }
                // The driven arc's centre C runs on the circle |C| about c2 and must reach the
                // driver flank offset outwards by the radius.
                (None, Some(arc)) if arc.is_convex() => {
                    let n = outward(a[as_], a[ae]) * arc.radius;
                    circle_segment(
                        c2,
                        arc.centre.norm_squared(),
                        a[as_] + n,
                        a[ae] + n,
                        da.inv_len2[fi],
                        |x| ends.add(arc.centre, x - c2),
                    );
                }
                (Some(fa), Some(fb)) => {
                    let Some(dist) = tangent_distance(&fa, &fb) else {
                        continue;
                    };
                    let cb = fb.centre;
                    let cb2 = cb.norm_squared();
                    // x: the driven arc's centre in the world once the gears touch.
                    circle_circle(c2, cb2, fa.centre, dist, |x| {
                        let t = tangent_point(&fa, &fb, fa.centre, x, dist);
                        // t in the driven frame: (t − c2)·cb·conj(x − c2) / |cb|², as x − c2 is
                        // cb turned.
                        let w = x - c2;
                        let own = mul(t - c2, mul(cb, conj(w))) / cb2;
                        if on_arc(&fa, t) && on_arc(&fb, own) {
                            ends.add(cb, w);
                        }
                    });
                }
                _ => {}
            }
        }
    }
}

/// The lowest and highest contact roots of one tooth pair, as in [`Mesh::tooth_pair`]: each root
/// is measured from the driven tooth's tip angle as the argument of a complex number, ordered by
/// a pseudo-angle.
struct Extremes {
    /// (cos, sin) of the driven tooth's tip angle.
    tip: (f64, f64),
    lo: Option<(f64, Vec2)>,
    hi: Option<(f64, Vec2)>,
}

impl Extremes {
    fn new(tip: (f64, f64)) -> Self {
        Self {
            tip,
            lo: None,
            hi: None,
        }
    }

    /// The root θ = arg v − arg w + π.
    #[inline]
    fn add(&mut self, v: Vec2, w: Vec2) {
        let (tc, ts) = self.tip;
        let (px, py) = (-(v.x * w.x + v.y * w.y), -(v.y * w.x - v.x * w.y));
        let u = Vec2::new(px * tc + py * ts, py * tc - px * ts);
        let p = pseudo_angle(u);
        if self.lo.is_none_or(|(q, _)| p < q) {
            self.lo = Some((p, u));
        }
        if self.hi.is_none_or(|(q, _)| p > q) {
            self.hi = Some((p, u));
        }
    }

    fn get(&self) -> Option<(Vec2, Vec2)> {
        Some((self.lo?.1, self.hi?.1))
    }
}

/// Slack, as a fraction of the chord, with which a point of an arc's circle just past the arc's
/// ends still counts as on the arc (so that a vertex-on-vertex contact is found from both flanks
/// despite rounding, as `roots::END_SLACK` does for segments).
const ARC_SLACK: f64 = 1e-12;

/// Whether `x`, a point of the arc's circle, lies on the arc. Its foot on the chord must fall
/// within the chord; of the circle's points with such a foot, the arc's lie within |s| ≤ c/4 of
/// the chord on the bulge side, the others at least 3c/4 from it on the far side (the centre is
/// at least 3c/8 from the chord when |s| ≤ c/4). So the side is judged with a margin of c/4, and
/// stays right for a sagitta far below the rounding of the circle's huge radius (s → 0).
#[inline]
fn on_arc(arc: &Arc, x: Vec2) -> bool {
    let d = arc.end - arc.start;
    let r = x - arc.start;
    let len2 = d.norm_squared();
    let along = r.dot(&d);
    if along < -ARC_SLACK * len2 || along > (1.0 + ARC_SLACK) * len2 {
        return false;
    }
    // A convex arc bulges to the right of start → end (negative cross product).
    let cross = d.x * r.y - d.y * r.x;
    let beyond = if arc.is_convex() { -cross } else { cross };
    beyond >= -0.25 * len2
}

/// Unit normal to the right of `a → b`: out of the tooth (flanks run counter-clockwise).
#[inline]
fn outward(a: Vec2, b: Vec2) -> Vec2 {
    let d = b - a;
    Vec2::new(d.y, -d.x) / d.norm()
}

/// Distance between the centres of two arcs when they touch at a point inside both, or `None`
/// if they cannot: two convex arcs touch from outside (`r_a + r_b`); a convex arc inside a
/// concave one of larger radius touches it from inside (`r_concave − r_convex`).
#[inline]
fn tangent_distance(a: &Arc, b: &Arc) -> Option<f64> {
    match (a.is_convex(), b.is_convex()) {
        (true, true) => Some(a.radius + b.radius),
        (true, false) if a.radius < b.radius => Some(b.radius - a.radius),
        (false, true) if b.radius < a.radius => Some(a.radius - b.radius),
        _ => None,
    }
}

/// Where arcs `a` (centre at `ca`) and `b` (centre at `cb`), `dist` apart as given by
/// [`tangent_distance`], touch: on the line of centres, `r_a` from `ca` towards `cb` unless `a`
/// is the convex arc inside a concave `b`, when it is `r_a` on the far side of `ca`.
#[inline]
fn tangent_point(a: &Arc, b: &Arc, ca: Vec2, cb: Vec2, dist: f64) -> Vec2 {
    let u = (cb - ca) / dist;
    if a.is_convex() && !b.is_convex() {
        ca - u * a.radius
    } else {
        ca + u * a.radius
    }
}

/// Complex product of `a` and `b`.
#[inline]
fn mul(a: Vec2, b: Vec2) -> Vec2 {
    Vec2::new(a.x * b.x - a.y * b.y, a.x * b.y + a.y * b.x)
}
