//! Triangular-tooth gear geometry: tip and valley vertices, straight flanks, eccentric rotation centre.
//!
//! A [`Gear`] is described in its own frame, centred on its *geometric* centre (the centre of the
//! tip circle). Tip `k` sits at polar angle `tips[k]` and radius `R`; valley `k` sits midway in
//! angle between tip `k` and tip `k + 1`, at radius `r`; flanks are straight. The gear turns about
//! its *rotation* centre, which may be offset from the geometric centre (an eccentric gear turns
//! like a cam). All angles are radians. [`Gear::with_valleys`] places each valley explicitly
//! instead (asymmetric teeth), anywhere strictly between its two tips, and [`Gear::with_radii`]
//! gives each tip and each valley its own radius (a gear that is not round); `R` and `r` then
//! remain the designed values. [`Gear::with_flank_sagitta`] curves every flank into a circular
//! arc through its two vertices (convex or concave teeth); see [`Flank`] and [`Arc`].

use std::f64::consts::TAU;

use nalgebra::Vector2;
use serde::{Deserialize, Serialize};

/// The most teeth a gear may have: 10^5. The mechanism's largest gear has 223; a larger count
/// is refused (naming this limit) rather than attempted, as every tooth is stored and simulated.
pub const MAX_TEETH: usize = 100_000;

/// The smallest length an input may give (a radius, a centre distance), in its own unit: 10^-9.
/// With [`MAX_LENGTH`] it keeps every product the contact conditions form (up to the eighth
/// power of a length) far inside a double's range, so that a pair's answer is the same in any
/// unit: at 10^150 the squares overflowed and at 10^-160 they vanished, and the answer changed.
pub const MIN_LENGTH: f64 = 1.0e-9;

/// The largest length an input may give, in its own unit: 10^9 (see [`MIN_LENGTH`]).
pub const MAX_LENGTH: f64 = 1.0e9;

/// The smallest share of the larger tip radius a length that decides contacts may be (a tooth
/// height R - r, a clearance): 10^-8, 400 times the 2.5·10^-11 rad to which the solver places a
/// contact. Below it, rounding decides whether teeth touch: a tooth 10^-13 high on a radius of
/// 200 counted 50 jams of noise.
pub const MIN_DECIDING_SHARE: f64 = 1.0e-8;

/// A point or vector in a plane, in millimetres (or any consistent length unit).
pub type Vec2 = Vector2<f64>;

/// Why a gear could not be built: the field and the rule it broke.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field}: {rule}")]
pub struct GeometryError {
    /// The offending field, e.g. `teeth`, `root_radius`, `tips[3]`.
    pub field: String,
    /// The rule that was broken, in words.
    pub rule: String,
}

impl GeometryError {
    fn new(field: impl Into<String>, rule: impl Into<String>) -> Self {
        Self {
            field: field.into(),
            rule: rule.into(),
        }
    }
}

/// A gear with straight-flanked triangular teeth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Gear {
    tip_radius: f64,
    root_radius: f64,
    /// Tip angles in the gear frame, strictly increasing, spanning less than one turn.
    tips: Vec<f64>,
    /// Valley angles: valley k strictly between tip k and tip k+1 (the last one wraps round);
    /// midway unless built by [`Gear::with_valleys`].
    valleys: Vec<f64>,
    /// Rotation centre relative to the geometric centre, in the gear frame.
    rotation_centre: Vec2,
    /// Radius of each tip when they differ (a gear that is not round); empty: all `tip_radius`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    tip_radii: Vec<f64>,
    /// Radius of each valley when they differ; empty: all `root_radius`.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    root_radii: Vec<f64>,
    /// Signed sagitta of every flank (mm): 0 straight, > 0 convex, < 0 concave. Omitted from the
    /// serialized form when 0, so straight-flanked gears serialize as before.
    #[serde(default, skip_serializing_if = "is_zero")]
    flank_sagitta: f64,
}

/// Whether `x` is exactly 0 (serde: a straight-flanked gear omits its sagitta).
#[expect(
    clippy::trivially_copy_pass_by_ref,
    reason = "serde's skip_serializing_if passes a reference"
)]
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

fn too_many(teeth: usize) -> GeometryError {
    GeometryError::new(
        "teeth",
        format!("must be at most {MAX_TEETH} (the limit on teeth; got {teeth})"),
    )
}

fn check_finite(field: &str, x: f64) -> Result<(), GeometryError> {
    if x.is_finite() {
        Ok(())
    } else {
        Err(GeometryError::new(field, "must be a finite number"))
    }
}

impl Gear {
    /// An ideal gear: `teeth` tips evenly spaced at `360°·k/N`, rotating about its geometric centre.
    pub fn ideal(teeth: usize, tip_radius: f64, root_radius: f64) -> Result<Self, GeometryError> {
        if teeth < 3 {
            return Err(GeometryError::new(
                "teeth",
                format!("must be at least 3 (got {teeth})"),
            ));
        }
        if teeth > MAX_TEETH {
            return Err(too_many(teeth));
        }
        let pitch = TAU / teeth as f64;
        let tips = (0..teeth).map(|k| pitch * k as f64).collect();
        Self::new(tip_radius, root_radius, tips, Vec2::zeros())
    }

    /// A gear with explicit tip angles (radians, gear frame) and rotation centre offset.
    ///
    /// Rules: at least 3 tips and at most [`MAX_TEETH`]; `0 < root_radius < tip_radius`; every value finite; tips strictly
    /// increasing and all within one turn of the first (`tips[N-1] < tips[0] + 2π`); the rotation
    /// centre inside the root circle (otherwise the gear could not sit on an arbor).
    pub fn new(
        tip_radius: f64,
        root_radius: f64,
        tips: Vec<f64>,
        rotation_centre: Vec2,
    ) -> Result<Self, GeometryError> {
        check_finite("tip_radius", tip_radius)?;
        check_finite("root_radius", root_radius)?;
        if tips.len() < 3 {
            return Err(GeometryError::new(
                "teeth",
                format!("must be at least 3 (got {})", tips.len()),
            ));
        }
        if tips.len() > MAX_TEETH {
            return Err(too_many(tips.len()));
        }
        if root_radius <= 0.0 {
            return Err(GeometryError::new("root_radius", "must be greater than 0"));
        }
        if root_radius >= tip_radius {
            return Err(GeometryError::new(
                "root_radius",
                format!("must be less than tip_radius ({root_radius} >= {tip_radius})"),
            ));
        }
        // The field is named only for a tip that fails: a gear is built for every trial, and
        // naming every tip cost about 1 % of a table's time.
        if let Some(k) = tips.iter().position(|t| !t.is_finite()) {
            check_finite(&format!("tips[{k}]"), tips[k])?;
        }
        for k in 1..tips.len() {
            if tips[k] <= tips[k - 1] {
                return Err(GeometryError::new(
                    format!("tips[{k}]"),
                    "tip angles must be strictly increasing",
                ));
            }
        }
        if tips[tips.len() - 1] >= tips[0] + TAU {
            return Err(GeometryError::new(
                format!("tips[{}]", tips.len() - 1),
                "all tips must lie within one turn of tips[0]",
            ));
        }
        check_finite("rotation_centre.x", rotation_centre.x)?;
        check_finite("rotation_centre.y", rotation_centre.y)?;
        if rotation_centre.norm() >= root_radius {
            return Err(GeometryError::new(
                "rotation_centre",
                "must lie inside the root circle (eccentricity smaller than the valley radius)",
            ));
        }
        let n = tips.len();
        let valleys = (0..n)
            .map(|k| {
                let next = if k + 1 == n {
                    tips[0] + TAU
                } else {
                    tips[k + 1]
                };
                0.5 * (tips[k] + next)
            })
            .collect();
        Ok(Self {
            tip_radius,
            root_radius,
            tips,
            valleys,
            rotation_centre,
            tip_radii: Vec::new(),
            root_radii: Vec::new(),
            flank_sagitta: 0.0,
        })
    }

    /// A gear with explicit tip *and* valley angles (asymmetric teeth): like [`Gear::new`], but
    /// valley `k` sits at `valleys[k]` instead of midway between tip `k` and tip `k + 1`.
    ///
    /// Rules: those of [`Gear::new`]; one valley per tooth; every valley finite and strictly
    /// between its tips, `tips[k] < valleys[k] < tips[k+1]` (for the last valley,
    /// `tips[N-1] < valleys[N-1] < tips[0] + 2π`).
    pub fn with_valleys(
        tip_radius: f64,
        root_radius: f64,
        tips: Vec<f64>,
        valleys: Vec<f64>,
        rotation_centre: Vec2,
    ) -> Result<Self, GeometryError> {
        let mut gear = Self::new(tip_radius, root_radius, tips, rotation_centre)?;
        let n = gear.teeth();
        if valleys.len() != n {
            return Err(GeometryError::new(
                "valleys",
                format!(
                    "must have one valley per tooth ({n} teeth, {} valleys)",
                    valleys.len()
                ),
            ));
        }
        for (k, &v) in valleys.iter().enumerate() {
            // Named only where it fails (a gear may be built for every trial).
            let field = || format!("valleys[{k}]");
            if !v.is_finite() {
                check_finite(&field(), v)?;
            }
            let (lo, hi) = (gear.tip_angle(k as i64), gear.tip_angle(k as i64 + 1));
            if !(lo < v && v < hi) {
                let next = if k + 1 == n {
                    "tips[0] + 2π".to_owned()
                } else {
                    format!("tips[{}]", k + 1)
                };
                return Err(GeometryError::new(
                    field(),
                    format!(
                        "must lie strictly between tips[{k}] and {next} ({lo} < valley < {hi}; got {v})"
                    ),
                ));
            }
        }
        gear.valleys = valleys;
        Ok(gear)
    }

    /// This gear with its own radius for every tip and every valley (a gear that is not round:
    /// radial cutting errors, an out-of-round blank). [`Gear::tip_radius`] and
    /// [`Gear::root_radius`] keep the designed values; [`Gear::max_tip_radius`] and
    /// [`Gear::min_root_radius`] give the extremes.
    ///
    /// Rules: one radius per tip and one per valley; every radius finite and positive; each
    /// valley below both of its tips (`root_radii[k] < tip_radii[k]` and
    /// `root_radii[k] < tip_radii[k+1]`, the last wrapping to `tip_radii[0]`); the rotation centre
    /// inside the smallest valley radius.
    pub fn with_radii(
        mut self,
        tip_radii: Vec<f64>,
        root_radii: Vec<f64>,
    ) -> Result<Self, GeometryError> {
        let n = self.teeth();
        for (field, radii) in [("tip_radii", &tip_radii), ("root_radii", &root_radii)] {
            if radii.len() != n {
                return Err(GeometryError::new(
                    field,
                    format!(
                        "must have one radius per tooth ({n} teeth, {} radii)",
                        radii.len()
                    ),
                ));
            }
            for (k, &r) in radii.iter().enumerate() {
                // Named only where it fails (a gear may be built for every trial).
                let field = || format!("{field}[{k}]");
                if !r.is_finite() {
                    check_finite(&field(), r)?;
                }
                if r <= 0.0 {
                    return Err(GeometryError::new(
                        field(),
                        format!("must be greater than 0 (got {r})"),
                    ));
                }
            }
        }
        for (k, &r) in root_radii.iter().enumerate() {
            let next = (k + 1) % n;
            let lowest_tip = tip_radii[k].min(tip_radii[next]);
            if r >= lowest_tip {
                return Err(GeometryError::new(
                    format!("root_radii[{k}]"),
                    format!(
                        "a valley must lie below both its tips, tip_radii[{k}] and tip_radii[{next}] ({r} >= {lowest_tip})"
                    ),
                ));
            }
        }
        let min_root = root_radii.iter().copied().fold(f64::INFINITY, f64::min);
        if self.rotation_centre.norm() >= min_root {
            return Err(GeometryError::new(
                "rotation_centre",
                format!(
                    "must lie inside the smallest valley radius ({min_root}; eccentricity {})",
                    self.rotation_centre.norm()
                ),
            ));
        }
        self.tip_radii = tip_radii;
        self.root_radii = root_radii;
        // Curved flanks were checked against the old vertices: check them again.
        let s = self.flank_sagitta;
        self.flank_sagitta = 0.0;
        self.with_flank_sagitta(s)
    }

    /// This gear with every flank a circular arc through its two vertices, bulging by the signed
    /// sagitta `s` (mm, the arc's greatest distance from its chord): `s > 0` convex (the arc bulges
    /// out of the tooth), `s < 0` concave (hollowed into it), `s = 0` straight. Tips, valleys,
    /// radii and rotation centre are kept.
    ///
    /// Rules, each checked on every flank with the angle `α = 2·atan(2|s|/c)` between a flank's
    /// chord (of length c) and the arc's tangent at its ends:
    /// - `s` finite, and `|s| <= c/4` on every flank, so every arc is well under a half circle
    ///   (α ≤ 2·atan ½ ≈ 53°);
    /// - concave: each arc stays inside its tooth's triangle (valley k−1, tip k, valley k), and
    ///   the two flanks of a tooth meet only at the tip: at the tip the two α's together are less
    ///   than the tooth's angle, and at each valley α is less than the triangle's angle there;
    /// - convex: the two flanks bulging into the gap at valley k (of teeth k and k + 1) meet
    ///   only at the valley: their two α's together are less than the gap's opening angle there.
    ///
    /// The arc between its chord and its tangents at both ends lies in the triangle those three
    /// lines bound (a circular segment is convex), so these angle rules keep the outline simple.
    pub fn with_flank_sagitta(mut self, s: f64) -> Result<Self, GeometryError> {
        const FIELD: &str = "flank_sagitta";
        check_finite(FIELD, s)?;
        if s == 0.0 {
            self.flank_sagitta = 0.0;
            return Ok(self);
        }
        let n = self.teeth() as i64;
        // The tangent-chord angle of flank (valley or tip) `a` -> `b`.
        let alpha = |a: Vec2, b: Vec2| 2.0 * (2.0 * s.abs() / (b - a).norm()).atan();
        // Unsigned angle at `at` between the directions to `p` and `q`.
        let angle = |at: Vec2, p: Vec2, q: Vec2| {
            let (u, w) = (p - at, q - at);
            (u.x * w.y - u.y * w.x).abs().atan2(u.dot(&w))
        };
        let degrees = |x: f64| format!("{:.3}°", x.to_degrees());
        for k in 0..n {
            let (v0, t, v1) = (self.valley(k - 1), self.tip(k), self.valley(k));
            for (f, (a, b)) in [(v0, t), (t, v1)].into_iter().enumerate() {
                let c = (b - a).norm();
                if s.abs() > 0.25 * c {
                    return Err(GeometryError::new(
                        FIELD,
                        format!(
                            "|s| must be at most a quarter of every flank's chord (tooth {k}, flank {f}: chord {c}, |s| = {})",
                            s.abs()
                        ),
                    ));
                }
            }
            let (a0, a1) = (alpha(v0, t), alpha(t, v1));
            if s < 0.0 {
                let at_tip = angle(t, v0, v1);
                if a0 + a1 >= at_tip {
                    return Err(GeometryError::new(
                        FIELD,
                        format!(
                            "concave flanks of tooth {k} would cross each other: their tangent angles at the tip ({} + {}) must be less than the tooth's angle there ({})",
                            degrees(a0),
                            degrees(a1),
                            degrees(at_tip)
                        ),
                    ));
                }
                for (f, a, at, other) in [(0, a0, v0, v1), (1, a1, v1, v0)] {
                    let base = angle(at, t, other);
                    if a >= base {
                        return Err(GeometryError::new(
                            FIELD,
                            format!(
                                "concave flank {f} of tooth {k} would cross the tooth's base: its tangent angle at the valley ({}) must be less than the tooth's base angle there ({})",
                                degrees(a),
                                degrees(base)
                            ),
                        ));
                    }
                }
            } else {
                let t_next = self.tip(k + 1);
                let (u, w) = (t - v1, t_next - v1);
                // The gap's opening: from the next tip clockwise round to this tip, outside the gear.
                let gap = (w.x * u.y - w.y * u.x).atan2(w.dot(&u));
                let gap = TAU - gap.rem_euclid(TAU);
                let both = a1 + alpha(v1, t_next);
                if both >= gap {
                    return Err(GeometryError::new(
                        FIELD,
                        format!(
                            "convex flanks at valley {k} would cross each other: their tangent angles there ({}) must be less than the gap's opening ({})",
                            degrees(both),
                            degrees(gap)
                        ),
                    ));
                }
            }
        }
        self.flank_sagitta = s;
        Ok(self)
    }

    /// Signed sagitta of every flank (mm): 0 for straight flanks (see
    /// [`Gear::with_flank_sagitta`]).
    pub fn flank_sagitta(&self) -> f64 {
        self.flank_sagitta
    }

    /// Flank `f` (0: valley k−1 → tip k, 1: tip k → valley k) of tooth `k` (any integer), gear
    /// frame, about the geometric centre; directed counter-clockwise round the gear, so the tooth
    /// lies on its left.
    pub fn flank(&self, k: i64, f: usize) -> Flank {
        let [v0, t, v1] = self.tooth(k);
        let (a, b) = if f == 0 { (v0, t) } else { (t, v1) };
        if self.flank_sagitta == 0.0 {
            Flank::Segment { start: a, end: b }
        } else {
            Flank::Arc(Arc::through(a, b, self.flank_sagitta))
        }
    }

    /// Points along the closed outline for drawing, gear frame: the vertices as in
    /// [`Gear::outline`], with `per_flank − 1` points added inside every curved flank (none for
    /// straight flanks). Only for pictures: the contact solver never samples an outline, it
    /// solves contacts with the arcs themselves.
    pub fn drawn_outline(&self, per_flank: usize) -> Vec<Vec2> {
        let mut out = Vec::new();
        let inside = |flank: Flank, out: &mut Vec<Vec2>| {
            if let Flank::Arc(arc) = flank {
                out.extend((1..per_flank).map(|i| arc.point(i as f64 / per_flank as f64)));
            }
        };
        for k in 0..self.teeth() as i64 {
            out.push(self.tip(k));
            inside(self.flank(k, 1), &mut out);
            out.push(self.valley(k));
            inside(self.flank(k + 1, 0), &mut out);
        }
        out
    }

    /// Number of teeth N.
    pub fn teeth(&self) -> usize {
        self.tips.len()
    }

    /// Outer (tip) radius R, as designed (see [`Gear::max_tip_radius`] for a gear that is not
    /// round).
    pub fn tip_radius(&self) -> f64 {
        self.tip_radius
    }

    /// Inner (valley) radius r, as designed (see [`Gear::min_root_radius`] for a gear that is
    /// not round).
    pub fn root_radius(&self) -> f64 {
        self.root_radius
    }

    /// Radius of tip `k` (any integer: taken modulo N): [`Gear::tip_radius`] unless set by
    /// [`Gear::with_radii`].
    pub fn tip_radius_of(&self, k: i64) -> f64 {
        if self.tip_radii.is_empty() {
            self.tip_radius
        } else {
            self.tip_radii[self.wrap(k).0]
        }
    }

    /// Radius of valley `k` (any integer: taken modulo N): [`Gear::root_radius`] unless set by
    /// [`Gear::with_radii`].
    pub fn root_radius_of(&self, k: i64) -> f64 {
        if self.root_radii.is_empty() {
            self.root_radius
        } else {
            self.root_radii[self.wrap(k).0]
        }
    }

    /// The largest tip radius (the designed one for a round gear).
    pub fn max_tip_radius(&self) -> f64 {
        if self.tip_radii.is_empty() {
            self.tip_radius
        } else {
            self.tip_radii
                .iter()
                .copied()
                .fold(f64::NEG_INFINITY, f64::max)
        }
    }

    /// The smallest valley radius (the designed one for a round gear).
    pub fn min_root_radius(&self) -> f64 {
        if self.root_radii.is_empty() {
            self.root_radius
        } else {
            self.root_radii
                .iter()
                .copied()
                .fold(f64::INFINITY, f64::min)
        }
    }

    /// Tooth height h = R − r.
    pub fn tooth_height(&self) -> f64 {
        self.tip_radius - self.root_radius
    }

    /// Nominal angular pitch 2π/N.
    pub fn pitch(&self) -> f64 {
        TAU / self.teeth() as f64
    }

    /// Tip angles in the gear frame.
    pub fn tip_angles(&self) -> &[f64] {
        &self.tips
    }

    /// Valley angles in the gear frame (valley `k` lies between tip `k` and tip `k+1`).
    pub fn valley_angles(&self) -> &[f64] {
        &self.valleys
    }

    /// Rotation centre relative to the geometric centre (zero for a concentric gear).
    pub fn rotation_centre(&self) -> Vec2 {
        self.rotation_centre
    }

    /// Tip `k` (any integer: taken modulo N) in the gear frame, about the geometric centre.
    pub fn tip(&self, k: i64) -> Vec2 {
        let (i, turns) = self.wrap(k);
        polar(self.tip_radius_of(k), self.tips[i] + TAU * turns as f64)
    }

    /// Valley `k` (between tip `k` and tip `k+1`) in the gear frame, about the geometric centre.
    pub fn valley(&self, k: i64) -> Vec2 {
        let (i, turns) = self.wrap(k);
        polar(self.root_radius_of(k), self.valleys[i] + TAU * turns as f64)
    }

    /// Tip angle of unwrapped tooth index `k` (tooth k + N is tooth k one turn later).
    pub fn tip_angle(&self, k: i64) -> f64 {
        let (i, turns) = self.wrap(k);
        self.tips[i] + TAU * turns as f64
    }

    /// The closed outline: tip0, valley0, tip1, valley1, ... (counter-clockwise, gear frame).
    pub fn outline(&self) -> Vec<Vec2> {
        (0..self.teeth() as i64)
            .flat_map(|k| [self.tip(k), self.valley(k)])
            .collect()
    }

    /// Tooth `k` as the triangle (valley k−1, tip k, valley k), gear frame.
    pub fn tooth(&self, k: i64) -> [Vec2; 3] {
        [self.valley(k - 1), self.tip(k), self.valley(k)]
    }

    /// This gear seen from its other face: every point reflected in the gear frame's x axis
    /// (angle a -> -a, rotation centre (x, y) -> (x, -y)), its teeth renumbered so that the tip
    /// angles still increase: tooth k of the mirror image is tooth N - 1 - k of this gear, and
    /// valley k of the image is valley N - 2 - k (mod N).
    ///
    /// Why: the solver measures the driver's angles counter-clockwise and the driven gear's
    /// clockwise, each in its own direction of rotation. A gear moved from one role to the other
    /// while it keeps turning the same way (the listed driven gear made the driver) is seen from
    /// the other side, i.e. mirrored. Mirroring twice gives the gear back (to rounding of the
    /// last valley, which wraps by 2π).
    pub fn mirrored(&self) -> Gear {
        let n = self.teeth();
        // Old index of the tip that becomes tip k, and of the valley that becomes valley k.
        let tip_of = |k: usize| n - 1 - k;
        let valley_of = |k: usize| (2 * n - 2 - k) % n;
        let tips = (0..n).map(|k| -self.tips[tip_of(k)]).collect();
        let valleys = (0..n)
            .map(|k| {
                let v = -self.valleys[valley_of(k)];
                // Old valley N-1 lies past the last tip (it wraps round): mirrored, it lies
                // between the new last tip and the new first tip plus a turn.
                if k == n - 1 { v + TAU } else { v }
            })
            .collect();
        let pick = |radii: &[f64], of: &dyn Fn(usize) -> usize| -> Vec<f64> {
            if radii.is_empty() {
                Vec::new()
            } else {
                (0..n).map(|k| radii[of(k)]).collect()
            }
        };
        Gear {
            tip_radius: self.tip_radius,
            root_radius: self.root_radius,
            tips,
            valleys,
            rotation_centre: Vec2::new(self.rotation_centre.x, -self.rotation_centre.y),
            tip_radii: pick(&self.tip_radii, &tip_of),
            root_radii: pick(&self.root_radii, &valley_of),
            flank_sagitta: self.flank_sagitta,
        }
    }

    /// Split an unwrapped tooth index into (index in 0..N, whole turns).
    fn wrap(&self, k: i64) -> (usize, i64) {
        let n = self.teeth() as i64;
        (k.rem_euclid(n) as usize, k.div_euclid(n))
    }
}

/// One flank of a tooth: straight, or a circular arc (see [`Gear::with_flank_sagitta`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Flank {
    /// A straight flank from `start` to `end`.
    Segment {
        /// First vertex (counter-clockwise round the gear).
        start: Vec2,
        /// Second vertex.
        end: Vec2,
    },
    /// A circular-arc flank.
    Arc(Arc),
}

/// A circular-arc flank: the arc, under a half circle, of the circle about `centre` of radius
/// `radius` from `start` to `end`, on the side of its chord given by the sign of `sagitta`. The
/// tooth lies on the left of `start → end`; a positive sagitta bulges to the right (out of the
/// tooth, convex), a negative one to the left (into it, concave).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// First vertex (counter-clockwise round the gear).
    pub start: Vec2,
    /// Second vertex.
    pub end: Vec2,
    /// Centre of the arc's circle.
    pub centre: Vec2,
    /// Radius of the arc's circle, `(c²/4 + s²) / (2|s|)` for chord c and sagitta s.
    pub radius: f64,
    /// Signed greatest distance of the arc from its chord: > 0 convex, < 0 concave; never 0.
    pub sagitta: f64,
}

impl Arc {
    /// The arc from `start` to `end` with signed sagitta `sagitta` (non-zero, |s| at most half the
    /// chord for an arc no more than a half circle).
    pub fn through(start: Vec2, end: Vec2, sagitta: f64) -> Self {
        let d = end - start;
        let c2 = d.norm_squared();
        // Unit normal to the right of start → end: out of the tooth.
        let out = Vec2::new(d.y, -d.x) / c2.sqrt();
        let mid = 0.5 * (start + end);
        // The centre lies on the chord's perpendicular bisector, (c²/4 − s²)/(2s) from the
        // chord on the side away from the bulge (both signs of s).
        let centre = mid - out * ((0.25 * c2 - sagitta * sagitta) / (2.0 * sagitta));
        let radius = (0.25 * c2 + sagitta * sagitta) / (2.0 * sagitta.abs());
        Self {
            start,
            end,
            centre,
            radius,
            sagitta,
        }
    }

    /// Whether the arc bulges out of its tooth.
    pub fn is_convex(&self) -> bool {
        self.sagitta > 0.0
    }

    /// Angle (radians) of `start` seen from the centre, and the signed angle swept from there
    /// to `end`: counter-clockwise (positive) for a convex arc, clockwise for a concave one;
    /// its magnitude is `4·atan(2|s|/c)`, under π.
    pub fn angular_extent(&self) -> (f64, f64) {
        let r = self.start - self.centre;
        let half = 2.0 * (2.0 * self.sagitta.abs() / (self.end - self.start).norm()).atan();
        (r.y.atan2(r.x), 2.0 * half * self.sagitta.signum())
    }

    /// The point a fraction `t` (0 at `start`, 1 at `end`) of the way along the arc.
    pub fn point(&self, t: f64) -> Vec2 {
        let (a, sweep) = self.angular_extent();
        self.centre + polar(self.radius, a + t * sweep)
    }

    /// Whether `x`, a point of the arc's circle, lies on the arc: its foot on the chord falls
    /// within the chord (with `slack`, a length, for points just past the ends, lost to
    /// rounding), and it is not on the far side of the chord (the circle's other points with
    /// such a foot lie at least 3c/4 beyond it, as |s| ≤ c/4; the test allows c/4, so that it
    /// holds however small the sagitta).
    pub fn holds(&self, x: Vec2, slack: f64) -> bool {
        let d = self.end - self.start;
        let r = x - self.start;
        let len = d.norm();
        let along = r.dot(&d) / len;
        if along < -slack || along > len + slack {
            return false;
        }
        // cross(d, r) < 0: right of the chord, the convex side.
        let beyond = -(d.x * r.y - d.y * r.x) * self.sagitta.signum() / len;
        beyond >= -0.25 * len
    }

    /// The distances from `p` of the arc's nearest and farthest points (exact: along a circle
    /// the distance from `p` has one minimum and one maximum, on the line through `p` and the
    /// centre; where the arc misses one of them, that extreme is at an end).
    pub fn distance_range(&self, p: Vec2) -> (f64, f64) {
        let (ds, de) = ((self.start - p).norm(), (self.end - p).norm());
        let (mut near, mut far) = (ds.min(de), ds.max(de));
        let to_centre = self.centre - p;
        let dist = to_centre.norm();
        if dist > 0.0 {
            let u = to_centre / dist;
            if self.holds(self.centre + u * self.radius, 0.0) {
                far = far.max(dist + self.radius);
            }
            if self.holds(self.centre - u * self.radius, 0.0) {
                near = near.min((dist - self.radius).abs());
            }
        }
        (near, far)
    }
}

/// The point at `radius`, `angle` from the origin.
pub fn polar(radius: f64, angle: f64) -> Vec2 {
    let (s, c) = angle.sin_cos();
    Vec2::new(radius * c, radius * s)
}

/// Rotate `v` counter-clockwise by `angle`.
pub fn rotate(v: Vec2, angle: f64) -> Vec2 {
    let (s, c) = angle.sin_cos();
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// Centre distance D for two gears of tip radii `r_tip1`, `r_tip2` and common tooth height `h`
/// at clearance `g_percent` of h: `D = R1 + R2 − h + G` (the paper, section 3).
pub fn centre_distance(r_tip1: f64, r_tip2: f64, h: f64, g_percent: f64) -> f64 {
    r_tip1 + r_tip2 - h + h * g_percent / 100.0
}

#[cfg(test)]
mod tests;
