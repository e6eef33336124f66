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

use crate::roots::circle_segment;
use crate::tooth::{ToothData, wrap_pi};

mod conditions;
mod curved;

pub(crate) use conditions::ConditionSet;

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
    pub(crate) fn idx(&self, k: i64) -> usize {
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
///
/// Stored (serde) as its two gears and the centre distance, and placed again by [`Mesh::new`]
/// when read back: a stored run ([`crate::Trajectory`]) is drawn again without running it.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
#[serde(into = "MeshParts", try_from = "MeshParts")]
pub struct Mesh {
    pub(crate) driver: Placed,
    pub(crate) driven: Placed,
    pub(crate) centre_distance: f64,
    /// Whether either gear has curved flanks (the curved contact path).
    pub(crate) curved: bool,
}

/// A [`Mesh`] as stored: what [`Mesh::new`] places it from.
#[derive(serde::Serialize, serde::Deserialize)]
struct MeshParts {
    /// The driving gear.
    driver: Gear,
    /// The driven gear.
    driven: Gear,
    /// Centre distance D between the rotation centres.
    centre_distance: f64,
}

impl From<Mesh> for MeshParts {
    fn from(m: Mesh) -> Self {
        MeshParts {
            driver: m.driver.gear,
            driven: m.driven.gear,
            centre_distance: m.centre_distance,
        }
    }
}

impl TryFrom<MeshParts> for Mesh {
    type Error = MeshError;
    fn try_from(p: MeshParts) -> Result<Self, MeshError> {
        Mesh::new(p.driver, p.driven, p.centre_distance)
    }
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

    /// The same two gears at the same centre distance with the driven gear driving, both gears
    /// still turning their own way: the new driver's front flanks now push the old driver's
    /// back flanks. Each gear keeps its own angle (the new φ is the old driven gear's θ, the new
    /// θ the old driver's φ), because the picture is the old one reflected in the perpendicular
    /// bisector of the line of centres: each gear is seen from its other face
    /// ([`Gear::mirrored`]), so its tooth k is tooth N − 1 − k of the gear as listed.
    ///
    /// Errors: those of [`Mesh::new`] (the same bodies overlap whichever gear drives).
    pub fn other_driving(&self) -> Result<Mesh, MeshError> {
        Mesh::new(
            self.driven().mirrored(),
            self.driver().mirrored(),
            self.centre_distance,
        )
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
        let rest = self.resting(theta, phi0, phi1);
        let ((lo_j, hi_j), ks) = (rest.drivers, rest.ks.clone());
        let place = |v: Vec2| rest.place(v);
        let mut first = FirstAfter::new(phi0, phi1);
        let mut take = |phi: f64| first.take(phi);
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
        first.get()
    }

    /// What a search for the first touch on a driven gear resting at θ over driver angles
    /// `(phi0, phi1]` reads: the driver teeth that pass the line of centres, the driven teeth
    /// near it, and where a point of the driven gear's frame stands in the world.
    pub(super) fn resting(&self, theta: f64, phi0: f64, phi1: f64) -> Resting {
        let d2 = &self.driven;
        let c2 = self.c2();
        Resting {
            drivers: (
                *self.driver_teeth(phi1).start(),
                *self.driver_teeth(phi0).end(),
            ),
            ks: d2.teeth_between(theta - d2.window, theta + d2.window),
            c2,
            sin_cos: (PI - theta).sin_cos(),
        }
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

/// A driven gear resting at θ as [`Mesh::resting`] gives it.
pub(super) struct Resting {
    /// The first and last driver tooth that pass the line of centres over the range.
    pub(super) drivers: (i64, i64),
    /// Driven teeth near the line of centres while the gear stands at θ.
    pub(super) ks: std::ops::RangeInclusive<i64>,
    /// The driven gear's centre.
    c2: Vec2,
    /// Sine and cosine of the driven frame's turn, π − θ.
    sin_cos: (f64, f64),
}

impl Resting {
    /// Where the point `v` of the driven gear's frame stands in the world.
    pub(super) fn place(&self, v: Vec2) -> Vec2 {
        let (s, c) = self.sin_cos;
        self.c2 + Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
    }
}

/// The first driver angle after `phi0` among the roots offered: each is taken as the angle after
/// `phi0` (the driver turns forwards only), and the least in `(phi0, phi1]` is kept.
pub(super) struct FirstAfter {
    phi0: f64,
    phi1: f64,
    best: f64,
}

impl FirstAfter {
    pub(super) fn new(phi0: f64, phi1: f64) -> Self {
        Self {
            phi0,
            phi1,
            best: f64::INFINITY,
        }
    }

    /// Offers the root `phi` (of any turn).
    pub(super) fn take(&mut self, phi: f64) {
        let t = self.phi0 + (phi - self.phi0).rem_euclid(TAU);
        if t > self.phi0 + 1e-12 && t <= self.phi1 && t < self.best {
            self.best = t;
        }
    }

    /// The first root offered in the range, if any.
    pub(super) fn get(&self) -> Option<f64> {
        self.best.is_finite().then_some(self.best)
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
