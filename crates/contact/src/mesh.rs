//! A mesh: driver, driven gear and centre distance, placed in the world frame; and the exact
//! configuration-space obstacle of one driver tooth against one driven tooth.
//!
//! World frame: the driver's rotation centre is the origin, the driven gear's is `(D, 0)`. The
//! driver turns counter-clockwise by φ, the driven gear clockwise by θ, so both angles are
//! positive in the gear's own direction of rotation, as in the paper. At φ = 0 the driver's
//! gear-frame +x axis points at the driven gear; at θ = 0 the driven gear's +x axis points at the
//! driver. So driver tip `j` stands `t_j + φ` from the line of centres and driven tip `k` stands
//! `θ − t_k` from it (the paper's φ' and θ' of Appendix I for tooth pair (0, 0)).
//!
//! Flanks are straight unless a gear has curved flanks ([`Gear::with_flank_sagitta`]); then every
//! contact root of a pair that involves an arc is solved by the curved path (`tooth_pair_curved`,
//! `first_touch_curved`), and pairs of straight-flanked gears keep the straight path unchanged.

use std::f64::consts::{PI, TAU};

use geometry::{Arc, Flank, Gear, Vec2, rotate};
use smallvec::SmallVec;

use crate::certify::CertTooth;
use crate::meet::Condition;
use crate::roots::{circle_circle, circle_segment};
use crate::tooth::{ToothData, wrap_pi};

/// Why a mesh cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field}: {rule}")]
pub struct MeshError {
    /// The offending field.
    pub field: String,
    /// The broken rule.
    pub rule: String,
}

/// One gear as the solver sees it: vertices relative to the rotation centre, cached.
#[derive(Debug, Clone)]
pub(crate) struct Placed {
    pub gear: Gear,
    /// Tip k − rotation centre.
    pub tips: Vec<Vec2>,
    /// Valley k − rotation centre.
    pub valleys: Vec<Vec2>,
    /// Largest distance of any vertex from the rotation centre.
    pub reach: f64,
    /// Largest angular gap between consecutive tips.
    pub max_gap: f64,
    /// Largest angle from a tip to either of its valleys: half a tooth, at least half of
    /// `max_gap` (more when the valleys are off-centre, asymmetric teeth).
    pub max_half: f64,
    /// Angular window either side of the line of centres in which a tooth can touch the other gear.
    pub window: f64,
    /// Whether tip k can ever touch the other gear (it comes within the other gear's reach).
    pub tip_reaches: Vec<bool>,
    /// Whether valley k can ever touch the other gear.
    pub valley_reaches: Vec<bool>,
    /// Per-tooth data for the contact roots (filled in by [`Placed::mark_reaching`]).
    pub teeth: Vec<ToothData>,
    /// Per tooth, its two flank arcs relative to the rotation centre (gear frame); empty for
    /// straight flanks.
    pub arcs: Vec<[Arc; 2]>,
    /// Per tooth, what the step certificates need (`certify.rs`); empty for curved flanks, which
    /// are always bracketed.
    pub cert: Vec<CertTooth>,
}

impl Placed {
    fn new(gear: Gear) -> Self {
        let e = gear.rotation_centre();
        let n = gear.teeth() as i64;
        let tips: Vec<Vec2> = (0..n).map(|k| gear.tip(k) - e).collect();
        let valleys: Vec<Vec2> = (0..n).map(|k| gear.valley(k) - e).collect();
        let sagitta = gear.flank_sagitta();
        let arcs: Vec<[Arc; 2]> = if sagitta == 0.0 {
            Vec::new()
        } else {
            (0..n as usize)
                .map(|k| {
                    let prev = (k + n as usize - 1) % n as usize;
                    let (v0, t, v1) = (valleys[prev], tips[k], valleys[k]);
                    [Arc::through(v0, t, sagitta), Arc::through(t, v1, sagitta)]
                })
                .collect()
        };
        // A convex flank may bulge beyond its vertices: its exact farthest point counts too.
        let reach = tips
            .iter()
            .chain(&valleys)
            .map(|v| v.norm())
            .chain(
                arcs.iter()
                    .flatten()
                    .map(|a| a.distance_range(Vec2::zeros()).1),
            )
            .fold(0.0, f64::max);
        let max_gap = (0..n)
            .map(|k| gear.tip_angle(k + 1) - gear.tip_angle(k))
            .fold(0.0, f64::max);
        let valley_angle = |k: i64| {
            let a = gear.valley_angles();
            a[k.rem_euclid(n) as usize] + TAU * k.div_euclid(n) as f64
        };
        let max_half = (0..n)
            .map(|k| {
                let t = gear.tip_angle(k);
                (t - valley_angle(k - 1)).max(valley_angle(k) - t)
            })
            .fold(0.5 * max_gap, f64::max);
        // A convex flank may also bulge past its valley's angle: take the arcs' exact angular
        // extremes (seen from the geometric centre, like the tip and valley angles).
        let max_half = (0..n)
            .filter(|_| sagitta != 0.0)
            .map(|k| {
                let t = gear.tip_angle(k);
                (0..2)
                    .filter_map(|f| match gear.flank(k, f) {
                        Flank::Arc(arc) => Some(arc),
                        Flank::Segment { .. } => None,
                    })
                    .flat_map(|arc| grazing_points(&arc))
                    .map(|p| wrap_pi(p.y.atan2(p.x) - t).abs())
                    .fold(0.0, f64::max)
            })
            .fold(max_half, f64::max);
        Self {
            gear,
            tips,
            valleys,
            reach,
            max_gap,
            max_half,
            window: 0.0,
            tip_reaches: Vec::new(),
            valley_reaches: Vec::new(),
            teeth: Vec::new(),
            arcs,
            cert: Vec::new(),
        }
    }

    /// The two flanks of tooth `k`, turned by `turn`: `None` for a straight flank.
    #[inline]
    fn flank_arcs(&self, k: i64, turn: impl Fn(Vec2) -> Vec2) -> [Option<Arc>; 2] {
        if self.arcs.is_empty() {
            return [None, None];
        }
        self.arcs[self.idx(k)].map(|a| {
            Some(Arc {
                start: turn(a.start),
                end: turn(a.end),
                centre: turn(a.centre),
                ..a
            })
        })
    }

    /// Marks the vertices that can come within `other_reach` of the other gear's centre, at
    /// centre distance `d`: a vertex at ρ from its own centre is never nearer it than d − ρ.
    fn mark_reaching(&mut self, d: f64, other_reach: f64) {
        // A little slack: a vertex exactly at the limit may graze (in proportion to gears
        // smaller than a length unit, which a pair file's unit may make them).
        let can = |v: &Vec2| d - v.norm() <= other_reach * (1.0 + 1e-9) + 1e-9 * d.min(1.0);
        self.tip_reaches = self.tips.iter().map(can).collect();
        self.valley_reaches = self.valleys.iter().map(can).collect();
        let n = self.tips.len() as i64;
        self.teeth = (0..n)
            .map(|k| {
                let v = self.tooth(k);
                let (s, c) = self.gear.tip_angle(k).sin_cos();
                ToothData {
                    v,
                    reaches: self.tooth_reaches(k),
                    inv_len2: [
                        1.0 / (v[1] - v[0]).norm_squared(),
                        1.0 / (v[2] - v[1]).norm_squared(),
                    ],
                    tip_dir: (c, s),
                    tip_angle: self.gear.tip_angle(k),
                }
            })
            .collect();
        if self.arcs.is_empty() {
            self.cert = self.teeth.iter().map(CertTooth::new).collect();
        }
    }

    /// Tooth k's certificate data (straight flanks only).
    #[inline]
    pub fn cert(&self, k: i64) -> &CertTooth {
        &self.cert[self.idx(k)]
    }

    /// Tooth k's cached data and the angle of the whole turns that separate k from its index
    /// in `0..n`.
    #[inline]
    pub fn data(&self, k: i64) -> (&ToothData, f64) {
        let n = self.teeth.len() as i64;
        let turns = k.div_euclid(n);
        (&self.teeth[(k - turns * n) as usize], TAU * turns as f64)
    }

    /// Which vertices of tooth k (as in [`Placed::tooth`]) can touch the other gear.
    #[inline]
    pub fn tooth_reaches(&self, k: i64) -> [bool; 3] {
        [
            self.valley_reaches[self.idx(k - 1)],
            self.tip_reaches[self.idx(k)],
            self.valley_reaches[self.idx(k)],
        ]
    }

    #[inline]
    fn idx(&self, k: i64) -> usize {
        k.rem_euclid(self.tips.len() as i64) as usize
    }

    /// Tooth k as (valley k−1, tip k, valley k), relative to the rotation centre.
    #[inline]
    pub fn tooth(&self, k: i64) -> [Vec2; 3] {
        [
            self.valleys[self.idx(k - 1)],
            self.tips[self.idx(k)],
            self.valleys[self.idx(k)],
        ]
    }

    /// Unwrapped tooth indices whose tip angle (gear frame) lies in `[lo, hi]`.
    pub fn teeth_between(&self, lo: f64, hi: f64) -> std::ops::RangeInclusive<i64> {
        let n = self.tips.len() as i64;
        let t = self.gear.tip_angles();
        // First unwrapped index with tip angle >= x.
        let first_at_least = |x: f64| -> i64 {
            let turns = ((x - t[0]) / TAU).floor();
            let within = x - TAU * turns;
            let i = t.partition_point(|&a| a < within) as i64;
            turns as i64 * n + i
        };
        first_at_least(lo)..=first_at_least(hi) - 1
    }
}

/// Two gears in mesh at a centre distance, ready for the contact solver.
#[derive(Debug, Clone)]
pub struct Mesh {
    pub(crate) driver: Placed,
    pub(crate) driven: Placed,
    pub(crate) centre_distance: f64,
    /// Whether either gear has curved flanks (the curved contact path).
    pub(crate) curved: bool,
}

/// The obstacle a driver tooth makes for the driven gear at one driver angle: the closed interval
/// of driven angles `[lo, hi]` at which the two teeth overlap or touch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Obstacle {
    /// Unwrapped driver tooth index.
    pub driver_tooth: i64,
    /// Unwrapped driven tooth index.
    pub driven_tooth: i64,
    /// Lowest driven angle of contact (the driven tooth touches this driver tooth from behind).
    pub lo: f64,
    /// Highest driven angle of contact (the driven tooth touches it from ahead: being pushed).
    pub hi: f64,
}

impl Mesh {
    /// Places `driver` and `driven` at centre distance `centre_distance` (between rotation centres).
    ///
    /// Refused: a non-finite or non-positive distance; gear bodies (root circles, allowing for
    /// eccentricity) that would overlap at every angle; and, for concentric gears, a non-positive
    /// clearance, where every tip reaches below the other gear's valleys. For a gear that is not
    /// round ([`Gear::with_radii`]) the body is its smallest valley radius and the clearance is
    /// taken from its largest tip and smallest valley, so that its deepest tooth still clears.
    pub fn new(driver: Gear, driven: Gear, centre_distance: f64) -> Result<Self, MeshError> {
        let bad = |rule: String| MeshError {
            field: "centre_distance".into(),
            rule,
        };
        if !centre_distance.is_finite() || centre_distance <= 0.0 {
            return Err(bad("must be a finite positive length".into()));
        }
        let e1 = driver.rotation_centre().norm();
        let e2 = driven.rotation_centre().norm();
        let bodies = driver.min_root_radius() + driven.min_root_radius() + e1 + e2;
        if centre_distance <= bodies {
            return Err(bad(format!(
                "must exceed r1 + r2 + |e1| + |e2| = {bodies}: the gear bodies would overlap at every angle"
            )));
        }
        if e1 == 0.0 && e2 == 0.0 {
            let deepest = (driver.max_tip_radius() + driven.min_root_radius())
                .max(driven.max_tip_radius() + driver.min_root_radius());
            if centre_distance <= deepest {
                return Err(bad(format!(
                    "must exceed {deepest} (clearance G > 0): the tips would reach below the other gear's valleys and the gears overlap at every tooth"
                )));
            }
        }
        let mut driver = Placed::new(driver);
        let mut driven = Placed::new(driven);
        let lens = |own: f64, other: f64| -> f64 {
            // Angle at this gear's centre to where the two reach circles cross.
            let c = (centre_distance.powi(2) + own * own - other * other)
                / (2.0 * centre_distance * own);
            c.clamp(-1.0, 1.0).acos()
        };
        let w1 = lens(driver.reach, driven.reach);
        let w2 = lens(driven.reach, driver.reach);
        // A tooth spans at most max_half either side of its tip: no more than max_gap for
        // straight flanks, possibly more for convex ones.
        let span = |p: &Placed| p.max_gap.max(p.max_half);
        driver.window = w1 + span(&driver) + (e1 / driver.gear.min_root_radius()).asin() + 1e-6;
        driven.window = w2 + span(&driven) + (e2 / driven.gear.min_root_radius()).asin() + 1e-6;
        driver.mark_reaching(centre_distance, driven.reach);
        driven.mark_reaching(centre_distance, driver.reach);
        let curved = !(driver.arcs.is_empty() && driven.arcs.is_empty());
        Ok(Self {
            driver,
            driven,
            centre_distance,
            curved,
        })
    }

    /// The driving gear.
    pub fn driver(&self) -> &Gear {
        &self.driver.gear
    }

    /// The driven gear.
    pub fn driven(&self) -> &Gear {
        &self.driven.gear
    }

    /// Centre distance D between the rotation centres.
    pub fn centre_distance(&self) -> f64 {
        self.centre_distance
    }

    /// Whether the gears can ever touch (their reach circles cross).
    pub fn can_touch(&self) -> bool {
        self.driver.reach + self.driven.reach > self.centre_distance
    }

    pub(crate) fn c2(&self) -> Vec2 {
        Vec2::new(self.centre_distance, 0.0)
    }

    /// World position of a driver vertex given relative to its rotation centre.
    #[inline]
    pub(crate) fn driver_world(&self, rel: Vec2, phi: f64) -> Vec2 {
        rotate(rel, phi)
    }

    /// World position of a driven vertex given relative to its rotation centre.
    #[inline]
    pub(crate) fn driven_world(&self, rel: Vec2, theta: f64) -> Vec2 {
        self.c2() + rotate(rel, PI - theta)
    }

    /// World outlines (closed polygons of the tip and valley vertices) of both gears at (φ, θ);
    /// curved flanks are drawn as their chords.
    pub fn world_outlines(&self, phi: f64, theta: f64) -> (Vec<Vec2>, Vec<Vec2>) {
        let outline = |p: &Placed, f: &dyn Fn(Vec2) -> Vec2| -> Vec<Vec2> {
            p.tips
                .iter()
                .zip(&p.valleys)
                .flat_map(|(&t, &v)| [f(t), f(v)])
                .collect()
        };
        (
            outline(&self.driver, &|v| self.driver_world(v, phi)),
            outline(&self.driven, &|v| self.driven_world(v, theta)),
        )
    }

    /// The contact of driver tooth `j` with driven tooth `k` at (φ, θ), where they touch: the
    /// contact point (world frame) and the unit common normal there, or None where the normal is
    /// not defined (a vertex on a vertex: tip on tip, or tip in a valley's corner).
    ///
    /// The touching features are the vertex-flank pair at the least distance (every vertex of
    /// each tooth against every flank of the other, arcs as circles); the normal is the flank's.
    pub fn contact_normal(&self, phi: f64, theta: f64, j: i64, k: i64) -> Option<(Vec2, Vec2)> {
        let a = self.driver.tooth(j).map(|v| self.driver_world(v, phi));
        let b = self.driven.tooth(k).map(|v| self.driven_world(v, theta));
        let fa = self.driver.flank_arcs(j, |v| self.driver_world(v, phi));
        let fb = self.driven.flank_arcs(k, |v| self.driven_world(v, theta));
        // (distance, contact point, normal or None at a flank's end)
        let mut best: (f64, Vec2, Option<Vec2>) = (f64::INFINITY, Vec2::zeros(), None);
        let mut consider = |p: Vec2, flank: (Vec2, Vec2), arc: Option<Arc>| {
            let found = match arc {
                Some(arc) => {
                    let r = p - arc.centre;
                    let d = (r.norm() - arc.radius).abs();
                    let on = arc.holds(arc.centre + r * (arc.radius / r.norm()), 1e-9);
                    (d, on.then(|| r / r.norm()))
                }
                None => {
                    let (u, v) = flank;
                    let e = v - u;
                    let t = (p - u).dot(&e) / e.norm_squared();
                    let foot = u + e * t.clamp(0.0, 1.0);
                    let inside = t > 1e-9 && t < 1.0 - 1e-9;
                    (
                        (p - foot).norm(),
                        inside.then(|| Vec2::new(-e.y, e.x) / e.norm()),
                    )
                }
            };
            if found.0 < best.0 {
                best = (found.0, p, found.1);
            }
        };
        for f in 0..2 {
            let flank_a = (a[f], a[f + 1]);
            let flank_b = (b[f], b[f + 1]);
            for &q in &b {
                consider(q, flank_a, fa[f]);
            }
            for &p in &a {
                consider(p, flank_b, fb[f]);
            }
        }
        best.2.map(|n| (best.1, n))
    }

    /// The angle (0 to π/2) between a line of action through `point` along `normal` and the line
    /// from `point` to the driven gear's rotation centre.
    pub fn angle_to_driven_centre(&self, point: Vec2, normal: Vec2) -> f64 {
        let to_centre = self.c2() - point;
        let c = normal.dot(&to_centre).abs() / (normal.norm() * to_centre.norm());
        c.clamp(0.0, 1.0).acos()
    }

    /// Driver teeth near the line of centres at driver angle φ.
    pub(crate) fn driver_teeth(&self, phi: f64) -> std::ops::RangeInclusive<i64> {
        self.driver
            .teeth_between(-phi - self.driver.window, -phi + self.driver.window)
    }

    /// The first driver angle in `(phi0, phi1]` at which a driver tooth touches the driven gear
    /// standing still at θ, or None. Exact: with θ fixed every contact is a driver vertex (on a
    /// circle about the driver centre) meeting a driven flank, or a driven vertex meeting a driver
    /// flank (a circle in the driver's frame), solved like the obstacles.
    pub fn first_touch(&self, theta: f64, phi0: f64, phi1: f64) -> Option<f64> {
        if self.curved {
            return self.first_touch_curved(theta, phi0, phi1);
        }
        let (d1, d2) = (&self.driver, &self.driven);
        let c2 = self.c2();
        let lo_j = *self.driver_teeth(phi1).start();
        let hi_j = *self.driver_teeth(phi0).end();
        // Driven teeth near the line of centres while the gear stands at θ.
        let ks = d2.teeth_between(theta - d2.window, theta + d2.window);
        let (s, c) = (PI - theta).sin_cos();
        let place = |v: Vec2| c2 + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y);
        let mut best = f64::INFINITY;
        let mut take = |phi: f64| {
            // The root as an angle after phi0 (the driver turns forwards only).
            let t = phi0 + (phi - phi0).rem_euclid(TAU);
            if t > phi0 + 1e-12 && t <= phi1 && t < best {
                best = t;
            }
        };
        const FLANKS: [(usize, usize); 2] = [(0, 1), (1, 2)];
        // Each tooth's vertices and their arguments, taken once (not once per pair of teeth).
        let with_args = |t: [Vec2; 3]| (t, t.map(|p| p.y.atan2(p.x)));
        let drivers: SmallVec<[([Vec2; 3], [f64; 3]); 8]> =
            (lo_j..=hi_j).map(|j| with_args(d1.tooth(j))).collect();
        for k in ks {
            let (b, b_args) = with_args(d2.tooth(k).map(place));
            for &(a, a_args) in &drivers {
                // Driver vertex (turning about the origin) on a fixed driven flank.
                for (p, base) in a.into_iter().zip(a_args) {
                    for (u, v) in FLANKS {
                        circle_segment(
                            Vec2::zeros(),
                            p.norm_squared(),
                            b[u],
                            b[v],
                            1.0 / (b[v] - b[u]).norm_squared(),
                            |x| take(x.y.atan2(x.x) - base),
                        );
                    }
                }
                // Fixed driven vertex on a driver flank: in the driver's frame it turns backwards.
                for (q, base) in b.into_iter().zip(b_args) {
                    for (u, v) in FLANKS {
                        circle_segment(
                            Vec2::zeros(),
                            q.norm_squared(),
                            a[u],
                            a[v],
                            1.0 / (a[v] - a[u]).norm_squared(),
                            |x| take(base - x.y.atan2(x.x)),
                        );
                    }
                }
            }
        }
        best.is_finite().then_some(best)
    }

    /// The exact obstacle of driver tooth `j` against driven tooth `k` at driver angle φ, or
    /// `None` if no driven angle brings them into contact.
    ///
    /// Its ends are contact roots: a vertex of one tooth on a flank of the other (tip on flank is
    /// the paper's Phase 1 or 2; tip on tip is the shared end of both), each solved in closed form.
    pub fn obstacle(&self, phi: f64, j: i64, k: i64) -> Option<Obstacle> {
        self.pair_args(phi, j, k)
            .map(|args| self.placed(j, k, args))
    }

    /// One end of the (j, k) obstacle at φ, or `None` if there is none: the `lo` or `hi` of
    /// [`Mesh::obstacle`], bit for bit, for the price of one `atan2` instead of two (most callers
    /// ask for one end only: the upper end of a pair behind the driven gear, the lower end of one
    /// ahead).
    pub(crate) fn obstacle_end(&self, phi: f64, j: i64, k: i64, end: End) -> Option<f64> {
        let (ul, uh) = self.pair_dirs(phi, j, k)?;
        Some(
            self.tip_reference(k)
                + match end {
                    End::Lower => arg(ul),
                    End::Upper => arg(uh),
                },
        )
    }

    /// Driven tooth k's tip angle, whole turns included: what the arguments of its obstacles'
    /// ends are measured from.
    fn tip_reference(&self, k: i64) -> f64 {
        let (db, turns) = self.driven.data(k);
        db.tip_angle + turns
    }

    /// The arguments, measured from driven tooth k's tip angle, of the ends of the (j, k)
    /// obstacle at φ (see [`Mesh::placed`]): the same for k and k plus whole turns.
    fn pair_args(&self, phi: f64, j: i64, k: i64) -> Option<(f64, f64)> {
        self.pair_dirs(phi, j, k).map(|(ul, uh)| (arg(ul), arg(uh)))
    }

    /// The ends of the (j, k) obstacle at φ as directions whose arguments are
    /// [`Mesh::pair_args`]'s (see [`Mesh::tooth_pair`]).
    fn pair_dirs(&self, phi: f64, j: i64, k: i64) -> Option<(Vec2, Vec2)> {
        let (s, c) = sin_cos_of(phi);
        let (da, _) = self.driver.data(j);
        let a =
            da.v.map(|v| Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y));
        if self.curved {
            let fa = self
                .driver
                .flank_arcs(j, |v| Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y));
            return self.tooth_pair_curved(a, fa, da, k);
        }
        self.tooth_pair(a, da, k)
    }

    /// The (j, k) obstacle whose ends have the arguments `args` (from [`Mesh::pair_args`]).
    #[inline]
    fn placed(&self, j: i64, k: i64, (lo, hi): (f64, f64)) -> Obstacle {
        let reference = self.tip_reference(k);
        Obstacle {
            driver_tooth: j,
            driven_tooth: k,
            lo: reference + lo,
            hi: reference + hi,
        }
    }

    /// The (j, k) obstacle at φ, its arguments taken from `memo` (a memo at φ) where remembered
    /// there and left there when evaluated: [`Mesh::obstacle`], bit for bit.
    pub(crate) fn obstacle_in(
        &self,
        phi: f64,
        j: i64,
        k: i64,
        memo: &mut PairMemo,
    ) -> Option<Obstacle> {
        if memo.phi != phi {
            return self.obstacle(phi, j, k);
        }
        let n = self.driven.tips.len() as i64;
        let args = match memo.of_driver(j).get_mut(k.rem_euclid(n) as usize) {
            Some(m) => *m.get_or_insert_with(|| self.pair_args(phi, j, k)),
            None => self.pair_args(phi, j, k),
        };
        args.map(|args| self.placed(j, k, args))
    }

    /// The obstacle of driver tooth `j`, already placed in the world as `a`, against driven tooth `k`.
    ///
    /// Every contact root is a point on a circle; its driven angle is the argument of a complex
    /// product, compared through a pseudo-angle (monotone in the argument, no trigonometry) so
    /// that only the lowest and highest roots cost an `atan2`: they are returned as directions,
    /// and each caller takes the argument of the ends it needs.
    #[inline]
    fn tooth_pair(&self, a: [Vec2; 3], da: &ToothData, k: i64) -> Option<(Vec2, Vec2)> {
        EVALS.with(|c| c.set(c.get() + 1));
        let c2 = self.c2();
        let (db, _) = self.driven.data(k);
        let b = db.v;
        // The obstacle of tooth k sits near θ = t_k: every root is measured from there, as the
        // argument of u = e^{i(θ − t_k)}, which unwraps it to (t_k − π, t_k + π].
        let (tc, ts) = db.tip_dir;
        let mut lo: Option<(f64, Vec2)> = None;
        let mut hi: Option<(f64, Vec2)> = None;
        // e^{iθ} is proportional to −v·conj(w) for a vertex v and its root w (see below).
        let mut add = |v: Vec2, w: Vec2| {
            let (px, py) = (-(v.x * w.x + v.y * w.y), -(v.y * w.x - v.x * w.y));
            let u = Vec2::new(px * tc + py * ts, py * tc - px * ts);
            let p = pseudo_angle(u);
            if lo.is_none_or(|(q, _)| p < q) {
                lo = Some((p, u));
            }
            if hi.is_none_or(|(q, _)| p > q) {
                hi = Some((p, u));
            }
        };
        // Only flanks bound a tooth: the base chord between its valleys lies inside the gear body,
        // where a contact would already be an overlap of a neighbouring tooth's flanks.
        const FLANKS: [(usize, usize); 2] = [(0, 1), (1, 2)];
        // Driver vertex P on a driven flank: in the driven frame P runs on the circle |P − c2|
        // and meets the flank at X when θ = arg X − arg(P − c2) + π.
        for (p, reaches) in a.into_iter().zip(da.reaches) {
            if !reaches {
                continue;
            }
            let rel = p - c2;
            let rho2 = rel.norm_squared();
            for (f, (s, e)) in FLANKS.into_iter().enumerate() {
                circle_segment(Vec2::zeros(), rho2, b[s], b[e], db.inv_len2[f], |x| {
                    add(x, rel);
                });
            }
        }
        // Driven vertex Q on a driver flank: in the world Q runs on the circle |Q| about c2 and
        // meets the flank at X when θ = arg Q + π − arg(X − c2).
        for (q, reaches) in b.into_iter().zip(db.reaches) {
            if !reaches {
                continue;
            }
            let rho2 = q.norm_squared();
            for (f, (s, e)) in FLANKS.into_iter().enumerate() {
                circle_segment(c2, rho2, a[s], a[e], da.inv_len2[f], |x| add(q, x - c2));
            }
        }
        let (Some((_, ul)), Some((_, uh))) = (lo, hi) else {
            return None;
        };
        Some((ul, uh))
    }

    /// All tooth-pair obstacles at driver angle φ that can reach driven angles in `[lo, hi]`.
    pub fn obstacles(&self, phi: f64, lo: f64, hi: f64, out: &mut Vec<Obstacle>) {
        self.obstacles_with(phi, lo, hi, out, None);
    }

    /// [`Mesh::obstacles`], taking the arguments of pairs already evaluated at φ from `memo` (a
    /// scan over several windows at one driver angle, where the later windows pass the same teeth
    /// whole turns on) and leaving there those it evaluates.
    pub(crate) fn obstacles_with(
        &self,
        phi: f64,
        lo: f64,
        hi: f64,
        out: &mut Vec<Obstacle>,
        mut memo: Option<&mut PairMemo>,
    ) {
        out.clear();
        let c2 = self.c2();
        let (d1, d2) = (&self.driver, &self.driven);
        // Half a driven tooth plus the eccentric shift of its angles about the rotation centre.
        let half_k = d2.max_half
            + (d2.gear.rotation_centre().norm() / d2.gear.min_root_radius()).asin()
            + 1e-9;
        let (s, c) = phi.sin_cos();
        for j in self.driver_teeth(phi) {
            let (da, _) = d1.data(j);
            let world =
                da.v.map(|v| Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y));
            let tooth = world.map(|v| v - c2);
            // A driver tooth farther from the driven centre than any driven vertex cannot touch.
            let chords =
                segment_distance(tooth[0], tooth[1]).min(segment_distance(tooth[1], tooth[2]));
            let fa = d1.flank_arcs(j, |v| Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y));
            // Curved flanks: their exact nearest points; and, as every point of an arc lies
            // within |s| of its chord, an arc strays at most asin(|s| / chords) in angle from it.
            let (near, widen) = match fa {
                [Some(f0), Some(f1)] => (
                    [f0, f1]
                        .map(|f| f.distance_range(c2).0)
                        .into_iter()
                        .fold(f64::INFINITY, f64::min),
                    (d1.gear.flank_sagitta().abs() / chords).min(1.0).asin(),
                ),
                _ => (chords, 0.0),
            };
            if near > d2.reach {
                continue;
            }
            // The driver tooth as seen from the driven centre, as driven angles measured like θ − t_k:
            // tooth k can only touch it when θ − t_k falls within that span widened by half_k.
            let tip = wrap_pi(PI - tooth[1].y.atan2(tooth[1].x));
            let (mut a_lo, mut a_hi) = (tip, tip);
            for v in [tooth[0], tooth[2]] {
                let a = tip + wrap_pi(PI - v.y.atan2(v.x) - tip);
                a_lo = a_lo.min(a);
                a_hi = a_hi.max(a);
            }
            let (a_lo, a_hi) = (a_lo - widen, a_hi + widen);
            let ks = d2.teeth_between(lo - a_hi - half_k, hi - a_lo + half_k);
            // A window of more than a turn meets tooth k again whole turns on: its obstacle is
            // then placed from the arguments already found.
            let n = d2.tips.len() as i64;
            let mut args_of: Vec<Option<Option<(f64, f64)>>> = Vec::new();
            let remembered = match memo.as_deref_mut() {
                Some(m) if m.phi == phi => m.of_driver(j),
                _ => {
                    if ks.end() - ks.start() >= n {
                        args_of.resize(n as usize, None);
                    }
                    &mut args_of[..]
                }
            };
            for k in ks {
                let evaluate = || {
                    if self.curved {
                        self.tooth_pair_curved(world, fa, da, k)
                    } else {
                        self.tooth_pair(world, da, k)
                    }
                    .map(|(ul, uh)| (arg(ul), arg(uh)))
                };
                let args = match remembered.get_mut(k.rem_euclid(n) as usize) {
                    Some(memo) => *memo.get_or_insert_with(evaluate),
                    None => evaluate(),
                };
                if let Some(o) = args.map(|args| self.placed(j, k, args))
                    && o.hi >= lo
                    && o.lo <= hi
                {
                    out.push(o);
                }
            }
        }
    }
}

impl Mesh {
    /// [`Mesh::first_touch`] when a gear has curved flanks. With θ fixed every contact condition
    /// is again a crossing of two known curves: a driver vertex (on a circle about the origin) on
    /// a driven flank; a driven vertex (a circle in the driver's frame) on a driver flank; and a
    /// driver arc touching a driven flank, where the arc's centre, on a circle about the origin,
    /// reaches a segment offset by the arc's radius or a circle about the other arc's centre.
    fn first_touch_curved(&self, theta: f64, phi0: f64, phi1: f64) -> Option<f64> {
        let (d1, d2) = (&self.driver, &self.driven);
        let c2 = self.c2();
        let lo_j = *self.driver_teeth(phi1).start();
        let hi_j = *self.driver_teeth(phi0).end();
        let ks = d2.teeth_between(theta - d2.window, theta + d2.window);
        let (s, c) = (PI - theta).sin_cos();
        let place = |v: Vec2| c2 + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y);
        let mut best = f64::INFINITY;
        let mut take = |phi: f64| {
            let t = phi0 + (phi - phi0).rem_euclid(TAU);
            if t > phi0 + 1e-12 && t <= phi1 && t < best {
                best = t;
            }
        };
        let arg = |v: Vec2| v.y.atan2(v.x);
        const FLANKS: [(usize, usize); 2] = [(0, 1), (1, 2)];
        for k in ks {
            let b = d2.tooth(k).map(place);
            let fb = d2.flank_arcs(k, place);
            for j in lo_j..=hi_j {
                let a = d1.tooth(j);
                let fa = d1.flank_arcs(j, |v| v);
                // Driver vertex (turning about the origin) on a fixed driven flank.
                for p in a {
                    let base = arg(p);
                    for (f, (u, v)) in FLANKS.into_iter().enumerate() {
                        let rho2 = p.norm_squared();
                        match fb[f] {
                            None => circle_segment(
                                Vec2::zeros(),
                                rho2,
                                b[u],
                                b[v],
                                1.0 / (b[v] - b[u]).norm_squared(),
                                |x| take(arg(x) - base),
                            ),
                            Some(arc) => {
                                circle_circle(Vec2::zeros(), rho2, arc.centre, arc.radius, |x| {
                                    if on_arc(&arc, x) {
                                        take(arg(x) - base);
                                    }
                                });
                            }
                        }
                    }
                }
                // Fixed driven vertex on a driver flank: in the driver's frame it turns backwards.
                for q in b {
                    let base = arg(q);
                    for (f, (u, v)) in FLANKS.into_iter().enumerate() {
                        let rho2 = q.norm_squared();
                        match fa[f] {
                            None => circle_segment(
                                Vec2::zeros(),
                                rho2,
                                a[u],
                                a[v],
                                1.0 / (a[v] - a[u]).norm_squared(),
                                |x| take(base - arg(x)),
                            ),
                            Some(arc) => {
                                circle_circle(Vec2::zeros(), rho2, arc.centre, arc.radius, |x| {
                                    if on_arc(&arc, x) {
                                        take(base - arg(x));
                                    }
                                });
                            }
                        }
                    }
                }
                // Flank on flank, through an arc's centre (see `tooth_pair_curved`).
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
        }
        best.is_finite().then_some(best)
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
    fn tooth_pair_curved(
        &self,
        a: [Vec2; 3],
        fa: [Option<Arc>; 2],
        da: &ToothData,
        k: i64,
    ) -> Option<(Vec2, Vec2)> {
        EVALS.with(|c| c.set(c.get() + 1));
        let c2 = self.c2();
        let (db, _) = self.driven.data(k);
        let b = db.v;
        let fb = self.driven.flank_arcs(k, |v| v);
        let mut ends = Extremes::new(db.tip_dir);
        const FLANKS: [(usize, usize); 2] = [(0, 1), (1, 2)];
        // Driver vertex P on a driven flank (driven frame): θ = arg X − arg(P − c2) + π.
        for (p, reaches) in a.into_iter().zip(da.reaches) {
            if !reaches {
                continue;
            }
            let rel = p - c2;
            let rho2 = rel.norm_squared();
            for (f, (s, e)) in FLANKS.into_iter().enumerate() {
                match fb[f] {
                    None => circle_segment(Vec2::zeros(), rho2, b[s], b[e], db.inv_len2[f], |x| {
                        ends.add(x, rel);
                    }),
                    Some(arc) => circle_circle(Vec2::zeros(), rho2, arc.centre, arc.radius, |x| {
                        if on_arc(&arc, x) {
                            ends.add(x, rel);
                        }
                    }),
                }
            }
        }
        // Driven vertex Q on a driver flank (world): θ = arg Q + π − arg(X − c2).
        for (q, reaches) in b.into_iter().zip(db.reaches) {
            if !reaches {
                continue;
            }
            let rho2 = q.norm_squared();
            for (f, (s, e)) in FLANKS.into_iter().enumerate() {
                match fa[f] {
                    None => circle_segment(c2, rho2, a[s], a[e], da.inv_len2[f], |x| {
                        ends.add(q, x - c2);
                    }),
                    Some(arc) => circle_circle(c2, rho2, arc.centre, arc.radius, |x| {
                        if on_arc(&arc, x) {
                            ends.add(q, x - c2);
                        }
                    }),
                }
            }
        }
        // Flank on flank.
        for (fi, (as_, ae)) in FLANKS.into_iter().enumerate() {
            for (fj, (bs, be)) in FLANKS.into_iter().enumerate() {
                match (fa[fi], fb[fj]) {
                    // The driver arc's centre W, seen from the driven gear, runs on the circle
                    // |W − c2| and must reach the driven flank offset outwards by the radius;
                    // the touching point, W's foot on the flank, lies on it exactly when W lies
                    // on the offset segment.
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
                            // t in the driven frame: (t − c2)·cb·conj(x − c2) / |cb|², as x − c2
                            // is cb turned.
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
        ends.get()
    }
}

/// Which end of an obstacle a caller asks for (see [`Mesh::obstacle_end`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum End {
    Lower,
    Upper,
}

/// The argument of a root's direction (see [`Mesh::tooth_pair`]).
#[inline]
fn arg(u: Vec2) -> f64 {
    u.y.atan2(u.x)
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

/// Complex conjugate of `a`.
#[inline]
fn conj(a: Vec2) -> Vec2 {
    Vec2::new(a.x, -a.y)
}

/// The points of `arc` whose bearing from the origin is extreme among its points: its ends, and
/// where a ray from the origin grazes its circle, if the arc holds those.
fn grazing_points(arc: &Arc) -> impl Iterator<Item = Vec2> + use<> {
    let d = arc.centre.norm();
    let mut out = vec![arc.start, arc.end];
    if d > arc.radius {
        // At the grazing point the radius is perpendicular to the ray: seen from the centre it
        // stands acos(r/d) either side of the direction back to the origin.
        let back = -arc.centre / d;
        let spread = (arc.radius / d).acos();
        for side in [spread, -spread] {
            let p = arc.centre + rotate(back, side) * arc.radius;
            if arc.holds(p, 0.0) {
                out.push(p);
            }
        }
    }
    out.into_iter()
}

/// Distance from the origin to the segment [a, b].
#[inline]
fn segment_distance(a: Vec2, b: Vec2) -> f64 {
    let d = b - a;
    let t = (-a.dot(&d) / d.dot(&d)).clamp(0.0, 1.0);
    (a + d * t).norm()
}

/// A number in (−2, 2] that orders directions like their argument in (−π, π], without
/// trigonometry (the "diamond angle").
#[inline]
fn pseudo_angle(u: Vec2) -> f64 {
    let t = u.x / (u.x.abs() + u.y.abs());
    if u.y >= 0.0 { 1.0 - t } else { t - 1.0 }
}

thread_local! {
    static EVALS: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
    /// The last driver angle whose sine and cosine were taken, with them.
    static LAST_SIN_COS: std::cell::Cell<(u64, f64, f64)> =
        const { std::cell::Cell::new((0, 0.0, 1.0)) };
}

/// `phi.sin_cos()`, remembered for the last angle asked on this thread: the solver evaluates
/// several tooth pairs at one driver angle in a row. The same bits either way.
#[inline]
fn sin_cos_of(phi: f64) -> (f64, f64) {
    LAST_SIN_COS.with(|last| {
        let (bits, s, c) = last.get();
        if bits == phi.to_bits() {
            return (s, c);
        }
        let (s, c) = phi.sin_cos();
        last.set((phi.to_bits(), s, c));
        (s, c)
    })
}

/// Tooth-pair obstacle evaluations (the closed-form contact roots of one driver tooth against
/// one driven tooth) made on this thread so far: the solver's unit of work, read by benchmarks.
pub fn tooth_pair_evaluations() -> u64 {
    EVALS.with(std::cell::Cell::get)
}

/// The arguments of the obstacles of every driver tooth near the line of centres at one driver
/// angle against every driven tooth (by its index in the turn), as far as evaluated: what
/// [`Mesh::obstacles_with`] remembers across the windows of one scan. An obstacle placed from
/// remembered arguments is the one [`Mesh::obstacle`] gives, bit for bit.
pub(crate) struct PairMemo {
    phi: f64,
    first_driver: i64,
    teeth: usize,
    args: Vec<Option<Option<(f64, f64)>>>,
}

impl PairMemo {
    /// An empty memo for the driver teeth of `mesh` near the line of centres at `phi`.
    pub(crate) fn new(mesh: &Mesh, phi: f64) -> Self {
        Self::over(phi, mesh.driver_teeth(phi), mesh.driven.tips.len())
    }

    /// An empty memo for driver teeth `drivers` at `phi`, against a driven gear of `teeth`.
    fn over(phi: f64, drivers: std::ops::RangeInclusive<i64>, teeth: usize) -> Self {
        // A few driver teeth at most touch the driven gear at once: a wider range (or none)
        // remembers nothing, and every pair is evaluated.
        let count = drivers
            .end()
            .checked_sub(*drivers.start())
            .and_then(|d| usize::try_from(d).ok())
            .filter(|&d| d < 64)
            .map_or(0, |d| d + 1);
        Self {
            phi,
            first_driver: *drivers.start(),
            teeth,
            args: vec![None; count * teeth],
        }
    }

    /// The remembered arguments of driver tooth `j` against each driven tooth (empty for a
    /// tooth outside the memo's range).
    fn of_driver(&mut self, j: i64) -> &mut [Option<Option<(f64, f64)>>] {
        let Ok(i) = usize::try_from(j - self.first_driver) else {
            return &mut [];
        };
        let start = i * self.teeth;
        self.args
            .get_mut(start..start + self.teeth)
            .unwrap_or(&mut [])
    }
}

/// One flank of a tooth as the contact conditions see it: a line (unit normal `n`, `n·x = h`,
/// gear frame from the rotation centre) or a circle (an arc's centre and radius).
#[derive(Debug, Clone, Copy)]
enum FlankShape {
    Line { n: Vec2, h: f64 },
    Circle { centre: Vec2, radius: f64 },
}

impl Placed {
    /// The shapes of tooth k's two flanks (gear frame).
    fn flank_shapes(&self, k: i64) -> [FlankShape; 2] {
        if !self.arcs.is_empty() {
            return self.arcs[self.idx(k)].map(|a| FlankShape::Circle {
                centre: a.centre,
                radius: a.radius,
            });
        }
        let v = self.tooth(k);
        [(v[0], v[1]), (v[1], v[2])].map(|(a, b)| {
            let e = b - a;
            let n = Vec2::new(e.y, -e.x) / e.norm();
            FlankShape::Line { n, h: n.dot(&a) }
        })
    }
}

impl Mesh {
    /// The contact conditions (`meet.rs`) of which one end of the obstacle of driver tooth `j`
    /// against driven tooth `k` is a root wherever the obstacle is wider than a just-met one: at
    /// the upper end the driver tooth's flank 1 (tip to the valley after it) meets the driven
    /// tooth's flank 1, at the lower end flank 0 meets flank 0; so an end of each tooth's flank
    /// of that end (that can reach the other gear) on the other tooth's flank, and, where flanks
    /// are arcs, every vertex on either flank and the two flanks tangent. An obstacle only just
    /// met - a tip crossing the corner of one flank twice - may have both ends on one side:
    /// [`Mesh::conditions_of_both_sides`] covers it.
    pub(crate) fn conditions(&self, j: i64, k: i64, end: End) -> SmallVec<[Condition; 8]> {
        let f = match end {
            End::Lower => 0,
            End::Upper => 1,
        };
        self.conditions_on(j, k, f..f + 1)
    }

    /// The conditions of both sides of the (j, k) obstacle: either end of it is always a root of
    /// one of these (a lock of the wider class was missed where the lower end of a just-met
    /// obstacle lay on the side of its upper end).
    pub(crate) fn conditions_of_both_sides(&self, j: i64, k: i64) -> SmallVec<[Condition; 8]> {
        self.conditions_on(j, k, 0..2)
    }

    /// [`Mesh::conditions`] for the flanks `sides` (0, 1 or both).
    fn conditions_on(
        &self,
        j: i64,
        k: i64,
        sides: std::ops::Range<usize>,
    ) -> SmallVec<[Condition; 8]> {
        let d = self.centre_distance;
        let (da, _) = self.driver.data(j);
        let (db, _) = self.driven.data(k);
        let (sa, sb) = (self.driver.flank_shapes(j), self.driven.flank_shapes(k));
        let mut out = SmallVec::new();
        // Straight flank g runs from vertex g to vertex g + 1, and only its ends touch the
        // other tooth's flank g; a curved flank may bulge past its ends: every vertex and both
        // flanks of each tooth are taken then.
        let sides = if self.curved { 0..2 } else { sides };
        for g in sides {
            let vertices = if self.curved { 0..3 } else { g..g + 2 };
            for i in vertices {
                if da.reaches[i] {
                    out.push(vertex_on(sb[g], da.v[i], d, true));
                }
                if db.reaches[i] {
                    out.push(vertex_on(sa[g], db.v[i], d, false));
                }
            }
        }
        let flanks = 0..2;
        for ga in flanks.clone() {
            for gb in flanks.clone() {
                flanks_tangent(sa[ga], sb[gb], d, &mut out);
            }
        }
        out
    }
}

/// A vertex of one gear (the driver's if `driver_vertex`) on a flank of the other.
fn vertex_on(flank: FlankShape, v: Vec2, d: f64, driver_vertex: bool) -> Condition {
    match (flank, driver_vertex) {
        (FlankShape::Line { n, h }, true) => Condition::driver_point_on_line(v, n, h, d),
        (FlankShape::Line { n, h }, false) => Condition::driven_point_on_line(v, n, h, d),
        (FlankShape::Circle { centre, radius }, true) => {
            Condition::points_apart(v, centre, radius, d)
        }
        (FlankShape::Circle { centre, radius }, false) => {
            Condition::points_apart(centre, v, radius, d)
        }
    }
}

/// A driver flank `a` tangent to a driven flank `b` where one is an arc: an arc's centre at its
/// radius from a line, or the two arcs' centres at the sum or difference of their radii.
fn flanks_tangent(a: FlankShape, b: FlankShape, d: f64, out: &mut SmallVec<[Condition; 8]>) {
    match (a, b) {
        (FlankShape::Line { .. }, FlankShape::Line { .. }) => {}
        (FlankShape::Circle { centre, radius }, FlankShape::Line { n, h }) => {
            for off in [radius, -radius] {
                out.push(Condition::driver_point_on_line(centre, n, h + off, d));
            }
        }
        (FlankShape::Line { n, h }, FlankShape::Circle { centre, radius }) => {
            for off in [radius, -radius] {
                out.push(Condition::driven_point_on_line(centre, n, h + off, d));
            }
        }
        (
            FlankShape::Circle {
                centre: ca,
                radius: ra,
            },
            FlankShape::Circle {
                centre: cb,
                radius: rb,
            },
        ) => {
            for r in [ra + rb, (ra - rb).abs()] {
                out.push(Condition::points_apart(ca, cb, r, d));
            }
        }
    }
}
