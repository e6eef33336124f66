//! The paper's kind of contact test on manufactured gears, run the paper's way: the driver is
//! turned by a fixed step, and after each step the driven gear is turned forward from where it
//! was until the teeth's overlap **area** is at most a tolerance. A jam is a step after which no
//! driven position within a reach ahead (one driven pitch by default) gets the area down to the
//! tolerance.
//!
//! [`crate::area`] does this for ideal pairs only (every tooth alike, so it can place one
//! template); here every tooth has its own tip and valley angles and radii and the gears turn
//! about offset rotation centres, all given as plain numbers, so this crate stays free of the
//! contact solver it is meant to check.
//!
//! A gear's outline (tip 0, valley 0, tip 1, ...) is cut into convex pieces: each tooth's
//! triangle (valley k-1, tip k, valley k) and, under it, a band of the body one tooth height
//! deep (the trapezoid between valleys k-1 and k and the same rays one h further in). The pieces
//! tile the outline down to that depth, so the overlap area of two outlines is the sum of their
//! pieces' pairwise overlaps (Sutherland-Hodgman, [`crate::area::convex_overlap_area`]); a
//! tooth sunk deeper than a tooth height is far past any tolerance anyway. Only the teeth near
//! the line of centres are tested. Frames are the crate's ([`crate::place`]): the driver turns
//! counter-clockwise about the origin, the driven clockwise about `(D, 0)`.

use std::f64::consts::{PI, TAU};

use crate::area::twice_area;
use crate::{P2, polar};

/// Bisection tolerance on the driven angle, radians (well below any tolerance's effect).
const ANGLE_TOL: f64 = 1e-9;

/// How close to the tolerance the overlap area at the driven position found is: within this
/// share of it (or the bracket below [`ANGLE_TOL`]).
const AREA_REL: f64 = 0.05;

/// How far ahead (driven pitches) a jammed driven gear is looked for a free position to be let
/// go to: beyond the teeth in mesh (a few pitches) nothing can hold it, so a gear with nothing
/// free that far stays where it is until a position frees.
const RELEASE_PITCHES: f64 = 4.0;

/// Teeth on either side of the line of centres whose pieces are tested: contact happens within
/// about a pitch of it, and tip errors and eccentricities move teeth by a fraction of a pitch,
/// so three cover every contact with teeth to spare.
const NEAR_TEETH: i64 = 3;

/// A manufactured gear as numbers: tooth `k`'s tip at polar angle `tips[k]` and radius
/// `tip_radii[k]`, valley `k` (between tips `k` and `k + 1`) at `valleys[k]` and
/// `root_radii[k]`, about the geometric centre; the gear turns about `rotation_centre` (gear
/// frame, relative to the geometric centre).
#[derive(Debug, Clone, PartialEq)]
pub struct GearOutline {
    /// Tip angles, increasing, within one turn of the first (radians).
    pub tips: Vec<f64>,
    /// Valley angles, valley `k` between tips `k` and `k + 1` (radians).
    pub valleys: Vec<f64>,
    /// Radius of each tip (mm).
    pub tip_radii: Vec<f64>,
    /// Radius of each valley (mm).
    pub root_radii: Vec<f64>,
    /// Rotation centre relative to the geometric centre, gear frame (mm).
    pub rotation_centre: P2,
}

impl GearOutline {
    /// An ideal gear: `n` tips at `2 pi k / n`, valleys midway, concentric.
    #[must_use]
    pub fn ideal(n: usize, r_tip: f64, r_root: f64) -> Self {
        let pitch = TAU / n as f64;
        Self {
            tips: (0..n).map(|k| pitch * k as f64).collect(),
            valleys: (0..n).map(|k| pitch * (k as f64 + 0.5)).collect(),
            tip_radii: vec![r_tip; n],
            root_radii: vec![r_root; n],
            rotation_centre: [0.0, 0.0],
        }
    }

    /// Number of teeth.
    #[must_use]
    pub fn teeth(&self) -> usize {
        self.tips.len()
    }

    /// Valley `k` for any integer `k` (taken modulo the teeth), gear frame.
    fn valley(&self, k: i64) -> P2 {
        let i = k.rem_euclid(self.teeth() as i64) as usize;
        polar(self.root_radii[i], self.valleys[i])
    }
}

/// Most vertices of a piece (the body band is a quadrilateral).
const MAX_VERTS: usize = 4;

/// Most vertices of one convex piece clipped by another: each clipping edge adds at most one.
const MAX_CLIPPED: usize = 2 * MAX_VERTS + 2;

/// A convex piece of an outline, relative to the rotation centre, with its bounding circle.
/// Fixed-size, as the test places and clips pieces millions of times per run.
#[derive(Debug, Clone, Copy)]
struct Piece {
    verts: [P2; MAX_VERTS],
    len: usize,
    centre: P2,
    radius: f64,
}

impl Piece {
    fn new(given: &[P2]) -> Self {
        let mut verts = [[0.0; 2]; MAX_VERTS];
        let len = given.len().min(MAX_VERTS);
        verts[..len].copy_from_slice(&given[..len]);
        let n = len as f64;
        let (x, y) = given[..len]
            .iter()
            .fold((0.0, 0.0), |(x, y), v| (x + v[0], y + v[1]));
        let centre = [x / n, y / n];
        let radius = given[..len]
            .iter()
            .map(|v| (v[0] - centre[0]).hypot(v[1] - centre[1]))
            .fold(0.0, f64::max);
        Self {
            verts,
            len,
            centre,
            radius,
        }
    }

    fn verts(&self) -> &[P2] {
        &self.verts[..self.len]
    }
}

/// Area of the intersection of two convex polygons (either orientation): Sutherland-Hodgman,
/// as [`crate::area::convex_overlap_area`], in fixed buffers.
fn clipped_area(a: &[P2], b: &[P2]) -> f64 {
    let ccw = twice_area(b) >= 0.0;
    let mut cur = [[0.0; 2]; MAX_CLIPPED];
    let mut next = [[0.0; 2]; MAX_CLIPPED];
    let mut n = a.len().min(MAX_CLIPPED);
    cur[..n].copy_from_slice(&a[..n]);
    for i in 0..b.len() {
        if n == 0 {
            return 0.0;
        }
        let (e0, e1) = if ccw {
            (b[i], b[(i + 1) % b.len()])
        } else {
            (b[(i + 1) % b.len()], b[i])
        };
        let side = |p: P2| (e1[0] - e0[0]) * (p[1] - e0[1]) - (e1[1] - e0[1]) * (p[0] - e0[0]);
        let mut m = 0;
        let mut push = |v: P2| {
            if m < MAX_CLIPPED {
                next[m] = v;
                m += 1;
            }
        };
        for j in 0..n {
            let (p, q) = (cur[j], cur[(j + 1) % n]);
            let (sp, sq) = (side(p), side(q));
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                push([p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])]);
            }
            if sq >= 0.0 {
                push(q);
            }
        }
        std::mem::swap(&mut cur, &mut next);
        n = m;
    }
    0.5 * twice_area(&cur[..n]).abs()
}

/// A gear cut into pieces: per tooth, its triangle and the body band under it.
#[derive(Debug, Clone)]
struct Pieces {
    per_tooth: Vec<[Piece; 2]>,
    first_tip: f64,
}

impl Pieces {
    fn of(g: &GearOutline, depth: f64) -> Self {
        let e = g.rotation_centre;
        let rel = |p: P2| [p[0] - e[0], p[1] - e[1]];
        let inward = |p: P2| {
            let r = p[0].hypot(p[1]);
            let s = ((r - depth) / r).max(0.0);
            [p[0] * s, p[1] * s]
        };
        let per_tooth = (0..g.teeth() as i64)
            .map(|k| {
                let i = k as usize;
                let (v0, v1) = (g.valley(k - 1), g.valley(k));
                let tip = polar(g.tip_radii[i], g.tips[i]);
                let tooth = Piece::new(&[rel(v0), rel(tip), rel(v1)]);
                let band = Piece::new(&[rel(inward(v0)), rel(inward(v1)), rel(v1), rel(v0)]);
                [tooth, band]
            })
            .collect();
        Self {
            per_tooth,
            first_tip: g.tips.first().copied().unwrap_or(0.0),
        }
    }

    /// The pieces of the teeth nearest gear-frame angle `facing`, with their bounding
    /// circles' centres placed in the world (turned by `turn`, moved to `origin`); vertices
    /// are placed later, only for pieces whose circles meet (see [`Placed::verts`]).
    fn near(&self, facing: f64, turn: f64, origin: P2) -> Placed<'_> {
        let n = self.per_tooth.len() as i64;
        let k0 = ((facing - self.first_tip) / TAU * n as f64).round() as i64;
        let mut out = Placed {
            pieces: [None; NEAR_PIECES],
            centres: [[0.0; 2]; NEAR_PIECES],
            placed: [None; NEAR_PIECES],
            rot: turn.sin_cos(),
            origin,
        };
        let mut i = 0;
        for k in k0 - NEAR_TEETH..=k0 + NEAR_TEETH {
            for p in &self.per_tooth[k.rem_euclid(n) as usize] {
                out.pieces[i] = Some(p);
                out.centres[i] = out.world(p.centre);
                i += 1;
            }
        }
        out
    }
}

/// Pieces tested per gear: two for each near tooth.
const NEAR_PIECES: usize = 2 * (2 * NEAR_TEETH as usize + 1);

/// The near pieces of one gear at one angle, placed in the world as needed.
struct Placed<'a> {
    pieces: [Option<&'a Piece>; NEAR_PIECES],
    centres: [P2; NEAR_PIECES],
    placed: [Option<[P2; MAX_VERTS]>; NEAR_PIECES],
    /// (sin, cos) of the turn.
    rot: (f64, f64),
    origin: P2,
}

impl Placed<'_> {
    fn world(&self, v: P2) -> P2 {
        let (s, c) = self.rot;
        [
            self.origin[0] + c * v[0] - s * v[1],
            self.origin[1] + s * v[0] + c * v[1],
        ]
    }

    /// Piece `i`'s vertices in the world, placed once.
    fn verts(&mut self, i: usize) -> Option<([P2; MAX_VERTS], usize)> {
        let p = self.pieces[i]?;
        if self.placed[i].is_none() {
            let mut w = [[0.0; 2]; MAX_VERTS];
            for (o, v) in w.iter_mut().zip(p.verts()) {
                *o = self.world(*v);
            }
            self.placed[i] = Some(w);
        }
        self.placed[i].map(|w| (w, p.len))
    }
}

/// A mesh of two manufactured gears under the area test.
#[derive(Debug, Clone)]
pub struct SteppedPair {
    driver: Pieces,
    driven: Pieces,
    driven_teeth: usize,
    driver_teeth: usize,
    centre_distance: f64,
    tolerance: f64,
}

/// How a run is stepped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stepping {
    /// Driver steps per driver pitch (the driver turns by a fixed step).
    pub steps_per_pitch: usize,
    /// How far ahead a free driven position is looked for, in driven pitches: none within it
    /// is a jam.
    pub reach: f64,
    /// Steps per driven pitch of the forward search (the free position found is then located
    /// by bisection): a free window narrower than this step may be missed, as by the paper's
    /// kind of search.
    pub search_steps: usize,
}

impl Default for Stepping {
    fn default() -> Self {
        Self {
            steps_per_pitch: 20,
            reach: 1.0,
            search_steps: 64,
        }
    }
}

/// Which way the driven gear may be turned after a driver step, and from where. [`SteppedPair::run`]
/// is [`Correction::Forward`]; the others are read by [`SteppedPair::trace`] only.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Correction {
    /// The paper's kind of program as [`SteppedPair::run`] runs it: the driven gear stays where
    /// it was and, where the test finds contact, is turned forward to the first free position.
    #[default]
    Forward,
    /// The driven gear stays where it was and, where the test finds contact, is turned to the
    /// nearest free position either way: forward when a driver tooth behind has caught it up,
    /// back when one ahead has closed on it.
    Nearest,
    /// The driven gear is first carried by the nominal ratio (driver teeth over driven teeth)
    /// of the driver's step, then, where the test finds contact, turned to the nearest free
    /// position either way.
    CarriedNearest,
}

/// One driver step of [`SteppedPair::trace`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Driver angle after the step (radians).
    pub phi: f64,
    /// Driven angle after the step and its correction (radians); after a jam, where the driven
    /// gear was let go (or, with nothing free, where it stays).
    pub theta: f64,
    /// Whether the test found contact after the step, so that the driven gear was turned (a
    /// correction, or a jam): a tooth met it.
    pub met: bool,
    /// Whether no free position lay within the reach (either way where the correction turns
    /// both ways): a jam.
    pub jam: bool,
    /// Driven angle at the jam, before the driven gear was let go (equal to `theta` otherwise).
    pub jam_theta: f64,
}

/// What [`SteppedPair::trace`] gave besides its steps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Traced {
    /// The driven angle the run started at (the guess where the start was blocked).
    pub theta0: f64,
    /// No free driven position near the guess at the start.
    pub blocked_at_start: bool,
    /// Driver steps taken (fewer than the run's when `visit` ended it).
    pub steps: usize,
}

/// What a stepped run gave.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteppedRun {
    /// Driver angle of the first jam (radians), if any; the run ends there.
    pub jam: Option<f64>,
    /// Whether that jam was at the start: no free driven position near the guess.
    pub blocked_at_start: bool,
    /// Driver steps taken.
    pub steps: usize,
}

impl SteppedPair {
    /// The pair `driver`, `driven` at centre distance `centre_distance` (mm), in contact when
    /// the overlap area exceeds `tolerance` (mm²). `depth` (mm) is how deep under the valleys
    /// the body is tiled (a tooth height is plenty).
    #[must_use]
    pub fn new(
        driver: &GearOutline,
        driven: &GearOutline,
        centre_distance: f64,
        tolerance: f64,
        depth: f64,
    ) -> Self {
        Self {
            driver: Pieces::of(driver, depth),
            driven: Pieces::of(driven, depth),
            driver_teeth: driver.teeth(),
            driven_teeth: driven.teeth(),
            centre_distance,
            tolerance,
        }
    }

    /// The overlap area at driver angle `phi`, driven angle `theta` (mm²), summed only until
    /// it exceeds `stop` (pass infinity for the whole area).
    #[must_use]
    pub fn overlap_area_until(&self, phi: f64, theta: f64, stop: f64) -> f64 {
        // The driver faces the driven along world +x: gear-frame angle -phi; the driven faces
        // the driver (world pi) at gear-frame angle theta.
        let mut a = self.driver.near(-phi, phi, [0.0, 0.0]);
        let mut b = self
            .driven
            .near(theta, PI - theta, [self.centre_distance, 0.0]);
        let mut area = 0.0;
        for i in 0..NEAR_PIECES {
            let Some(p) = a.pieces[i] else { continue };
            for j in 0..NEAR_PIECES {
                let Some(q) = b.pieces[j] else { continue };
                let (dx, dy) = (
                    a.centres[i][0] - b.centres[j][0],
                    a.centres[i][1] - b.centres[j][1],
                );
                let reach = p.radius + q.radius;
                if dx * dx + dy * dy >= reach * reach {
                    continue;
                }
                let (Some((pv, pn)), Some((qv, qn))) = (a.verts(i), b.verts(j)) else {
                    continue;
                };
                area += clipped_area(&pv[..pn], &qv[..qn]);
                if area > stop {
                    return area;
                }
            }
        }
        area
    }

    /// The whole overlap area at `(phi, theta)`, mm².
    #[must_use]
    pub fn overlap_area(&self, phi: f64, theta: f64) -> f64 {
        self.overlap_area_until(phi, theta, f64::INFINITY)
    }

    /// Whether the test reports contact at `(phi, theta)`: the area exceeds the tolerance.
    #[must_use]
    pub fn in_contact(&self, phi: f64, theta: f64) -> bool {
        self.overlap_area_until(phi, theta, self.tolerance) > self.tolerance
    }

    fn driven_pitch(&self) -> f64 {
        TAU / self.driven_teeth as f64
    }

    /// The boundary between `inside` (in contact) and `outside` (free) at `phi`; the free end
    /// is returned, so the result is always a free position. Under a tolerance the area
    /// crosses it with a slope, so a regula falsi (Illinois) gets there in a few evaluations,
    /// stopping once the free end's area is within [`AREA_REL`] of the tolerance; at
    /// tolerance 0 the free side's area is flat zero, so bisection.
    fn bisect(&self, phi: f64, mut inside: f64, mut outside: f64) -> f64 {
        if self.tolerance <= 0.0 {
            while (outside - inside).abs() > ANGLE_TOL {
                let mid = 0.5 * (inside + outside);
                if mid == inside || mid == outside {
                    break;
                }
                if self.in_contact(phi, mid) {
                    inside = mid;
                } else {
                    outside = mid;
                }
            }
            return outside;
        }
        let f = |x: f64| self.overlap_area(phi, x) - self.tolerance;
        let (mut f_in, mut f_out) = (f(inside), f(outside));
        let mut true_out = f_out;
        // Which end moved last: +1 the free end, -1 the end in contact.
        let mut last = 0;
        while (outside - inside).abs() > ANGLE_TOL && true_out < -AREA_REL * self.tolerance {
            let w = outside - inside;
            let x = (inside * f_out - outside * f_in) / (f_out - f_in);
            // Keep the guess strictly inside the bracket, away from its ends.
            let t = ((x - inside) / w).clamp(0.01, 0.99);
            let x = inside + t * w;
            let fx = f(x);
            if fx > 0.0 {
                (inside, f_in) = (x, fx);
                if last == -1 {
                    f_out *= 0.5;
                }
                last = -1;
            } else {
                (outside, f_out, true_out) = (x, fx, fx);
                if last == 1 {
                    f_in *= 0.5;
                }
                last = 1;
            }
        }
        outside
    }

    /// Where the driven gear at `theta` goes at driver angle `phi`: `Some(theta)` if it is free
    /// there (the driver moved away, so it stays), else the first free position ahead. The
    /// last push (`last`) predicts it, so a tight bracket around it is tried first (and, free
    /// ahead, shows contact at `theta` is to be checked only when the bracket's near end is
    /// free too); otherwise a march of `search_steps` per driven pitch up to `reach` pitches.
    /// None: nothing free within the reach (a jam).
    fn push(&self, phi: f64, theta: f64, last: f64, s: &Stepping) -> Option<f64> {
        if last > 0.0 {
            let (lo, hi) = (theta + 0.95 * last, theta + 1.05 * last);
            if !self.in_contact(phi, hi) {
                if self.in_contact(phi, lo) {
                    return Some(self.bisect(phi, lo, hi));
                }
                if !self.in_contact(phi, theta) {
                    return Some(theta);
                }
                return Some(self.bisect(phi, theta, lo));
            }
        } else if !self.in_contact(phi, theta) {
            return Some(theta);
        }
        let step = self.driven_pitch() / s.search_steps.max(1) as f64;
        let limit = s.reach * self.driven_pitch();
        let mut at = theta;
        while at - theta < limit {
            let next = at + step;
            if !self.in_contact(phi, next) {
                return Some(self.bisect(phi, at, next));
            }
            at = next;
        }
        None
    }

    /// The driven angle the run starts at, driver at `phi`, from `guess`: pushed forward if the
    /// guess is in contact, otherwise turned back until a tooth touches (as the exact solver
    /// starts). None: no free position ahead (blocked at the start). A guess free for `reach`
    /// pitches back stays where it is (the teeth do not meet).
    #[must_use]
    pub fn start(&self, phi: f64, guess: f64, s: &Stepping) -> Option<f64> {
        if self.in_contact(phi, guess) {
            return self.push(phi, guess, 0.0, s);
        }
        let step = self.driven_pitch() / s.search_steps.max(1) as f64;
        let limit = s.reach * self.driven_pitch();
        let mut at = guess;
        while guess - at < limit {
            let next = at - step;
            if self.in_contact(phi, next) {
                return Some(self.bisect(phi, next, at));
            }
            at = next;
        }
        Some(guess)
    }

    /// Runs the driver from `phi0` through `turn` radians by fixed steps, the driven gear
    /// started in contact from `guess`, until the first jam or the end.
    #[must_use]
    pub fn run(&self, phi0: f64, turn: f64, guess: f64, s: &Stepping) -> SteppedRun {
        let Some(mut theta) = self.start(phi0, guess, s) else {
            return SteppedRun {
                jam: Some(phi0),
                blocked_at_start: true,
                steps: 0,
            };
        };
        let dphi = TAU / self.driver_teeth as f64 / s.steps_per_pitch.max(1) as f64;
        let steps = (turn / dphi).ceil() as usize;
        let mut last = 0.0;
        for i in 1..=steps {
            let phi = phi0 + (i as f64 * dphi).min(turn);
            match self.push(phi, theta, last, s) {
                Some(next) => {
                    last = next - theta;
                    theta = next;
                }
                None => {
                    return SteppedRun {
                        jam: Some(phi),
                        blocked_at_start: false,
                        steps: i,
                    };
                }
            }
        }
        SteppedRun {
            jam: None,
            blocked_at_start: false,
            steps,
        }
    }

    /// The nearest free position to `theta` either way at driver angle `phi`, or None if none
    /// lies within the reach on either side (a jam). Marches outward by the search step on both
    /// sides at once, then bisects the first bracket found on each side and keeps the nearer
    /// free end.
    fn nearest(&self, phi: f64, theta: f64, s: &Stepping) -> Option<f64> {
        if !self.in_contact(phi, theta) {
            return Some(theta);
        }
        let step = self.driven_pitch() / s.search_steps.max(1) as f64;
        let limit = s.reach * self.driven_pitch();
        let (mut ahead, mut behind) = (theta, theta);
        while ahead - theta < limit {
            let (next_ahead, next_behind) = (ahead + step, behind - step);
            let free_ahead = !self.in_contact(phi, next_ahead);
            let free_behind = !self.in_contact(phi, next_behind);
            let found_ahead = free_ahead.then(|| self.bisect(phi, ahead, next_ahead));
            let found_behind = free_behind.then(|| self.bisect(phi, behind, next_behind));
            match (found_ahead, found_behind) {
                (Some(a), Some(b)) => {
                    return Some(if a - theta <= theta - b { a } else { b });
                }
                (Some(a), None) => return Some(a),
                (None, Some(b)) => return Some(b),
                (None, None) => {}
            }
            (ahead, behind) = (next_ahead, next_behind);
        }
        None
    }

    /// The first free position ahead of `theta` within [`RELEASE_PITCHES`] driven pitches,
    /// marched by the search step and bisected: where a jammed driven gear is let go ("allowing
    /// the driven gear to rotate freely if a jam ... was detected until movement was possible
    /// again"). None: the teeth overlap all that way, and the gear stays where it is.
    fn release(&self, phi: f64, theta: f64, s: &Stepping) -> Option<f64> {
        let step = self.driven_pitch() / s.search_steps.max(1) as f64;
        let limit = RELEASE_PITCHES * self.driven_pitch();
        let mut at = theta;
        while at - theta < limit {
            let next = at + step;
            if !self.in_contact(phi, next) {
                return Some(self.bisect(phi, at, next));
            }
            at = next;
        }
        None
    }

    /// Runs the driver from `phi0` through `turn` radians by fixed steps, the driven gear
    /// started in contact from `guess` ([`SteppedPair::start`]), turned after each step as
    /// `correction` says, and goes on past a jam: the driven gear is let go to the first free
    /// position ahead (`SteppedPair::release`; with none within a few pitches, it stays).
    /// `visit` sees every step in order and ends the run by returning false.
    ///
    /// With [`Correction::Forward`] every step up to the first jam is [`SteppedPair::run`]'s:
    /// the same driven angles, the same jam.
    pub fn trace(
        &self,
        phi0: f64,
        turn: f64,
        guess: f64,
        s: &Stepping,
        correction: Correction,
        mut visit: impl FnMut(&Step) -> bool,
    ) -> Traced {
        let Some(theta0) = self.start(phi0, guess, s) else {
            return Traced {
                theta0: guess,
                blocked_at_start: true,
                steps: 0,
            };
        };
        let mut theta = theta0;
        let dphi = TAU / self.driver_teeth as f64 / s.steps_per_pitch.max(1) as f64;
        let ratio = self.driver_teeth as f64 / self.driven_teeth as f64;
        let steps = (turn / dphi).ceil() as usize;
        let (mut last, mut phi_before) = (0.0, phi0);
        for i in 1..=steps {
            let phi = phi0 + (i as f64 * dphi).min(turn);
            let from = match correction {
                Correction::Forward | Correction::Nearest => theta,
                Correction::CarriedNearest => theta + ratio * (phi - phi_before),
            };
            phi_before = phi;
            let found = match correction {
                Correction::Forward => self.push(phi, from, last, s),
                Correction::Nearest | Correction::CarriedNearest => self.nearest(phi, from, s),
            };
            let step = match found {
                Some(next) => {
                    // Moved from where the step left it: a tooth met the driven gear.
                    let met = next != from;
                    last = next - theta;
                    theta = next;
                    Step {
                        phi,
                        theta,
                        met,
                        jam: false,
                        jam_theta: theta,
                    }
                }
                None => {
                    let jam_theta = from;
                    last = 0.0;
                    theta = self.release(phi, from, s).unwrap_or(from);
                    Step {
                        phi,
                        theta,
                        met: true,
                        jam: true,
                        jam_theta,
                    }
                }
            };
            if !visit(&step) {
                return Traced {
                    theta0,
                    blocked_at_start: false,
                    steps: i,
                };
            }
        }
        Traced {
            theta0,
            blocked_at_start: false,
            steps,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::area::AreaPair;

    /// b2-c1's sizes (64 and 38 teeth, h = 1.1 mm) at clearance `g` (share of h).
    fn b2_c1(g: f64) -> (GearOutline, GearOutline, f64) {
        let (r1, r2, h) = (15.415_349_369_988_546, 9.152_863_688_430_7, 1.1);
        (
            GearOutline::ideal(64, r1, r1 - h),
            GearOutline::ideal(38, r2, r2 - h),
            r1 + r2 - h + g * h,
        )
    }

    #[test]
    fn ideal_overlap_areas_match_the_ideal_area_test() {
        let (a, b, d) = b2_c1(0.4);
        let pair = SteppedPair::new(&a, &b, d, 0.0, 1.1);
        let ideal = AreaPair {
            n1: 64,
            n2: 38,
            r1: a.tip_radii[0],
            r2: b.tip_radii[0],
            h: 1.1,
            centre_distance: d,
            tolerance: 0.0,
            blunt: 0.0,
        };
        let mut touching = 0;
        for i in 0..40 {
            let (phi, theta) = (0.0123 * f64::from(i), 0.0371 * f64::from(i) - 0.3);
            let want = ideal.overlap_area(phi, theta);
            if !want.is_finite() {
                continue;
            }
            touching += usize::from(want > 0.0);
            let got = pair.overlap_area(phi, theta);
            assert!((got - want).abs() < 1e-9, "{phi} {theta}: {got} vs {want}");
        }
        assert!(touching > 5, "the sample should touch often: {touching}");
    }

    #[test]
    fn ideal_gears_run_at_forty_percent_and_jam_at_two() {
        let s = Stepping::default();
        let (a, b, d) = b2_c1(0.4);
        let turn = TAU;
        let run = SteppedPair::new(&a, &b, d, 0.001, 1.1).run(0.01, turn, 0.0, &s);
        assert_eq!(run.jam, None, "{run:?}");
        let exact = SteppedPair::new(&a, &b, d, 0.0, 1.1).run(0.01, turn, 0.0, &s);
        assert_eq!(exact.jam, None, "{exact:?}");
        let (a, b, d) = b2_c1(0.02);
        for t in [0.0, 0.001] {
            let run = SteppedPair::new(&a, &b, d, t, 1.1).run(0.01, turn, 0.0, &s);
            assert!(run.jam.is_some(), "T = {t}: {run:?}");
        }
    }

    #[test]
    fn a_start_touches_and_a_tolerance_lets_the_driven_gear_sit_further_back() {
        let s = Stepping::default();
        let (a, b, d) = b2_c1(0.4);
        let exact = SteppedPair::new(&a, &b, d, 0.0, 1.1);
        let loose = SteppedPair::new(&a, &b, d, 0.003, 1.1);
        let (t0, t1) = (
            exact.start(0.0, 0.0, &s).expect("starts"),
            loose.start(0.0, 0.0, &s).expect("starts"),
        );
        assert!(t1 < t0 - 1e-6, "{t1} vs {t0}");
        // Just behind the start the test reports contact; at it, not.
        assert!(exact.overlap_area(0.0, t0) == 0.0 && exact.overlap_area(0.0, t0 - 1e-6) > 0.0);
        // Under a tolerance the start is where the area has come down to it (within 5 %).
        let at = loose.overlap_area(0.0, t1);
        assert!((0.95 * 0.003..=0.003).contains(&at), "{at}");
    }

    #[test]
    fn a_forward_trace_is_the_forward_run_up_to_its_first_jam() {
        let s = Stepping::default();
        for (g, shift) in [(0.4, 0.0), (0.15, 3.0), (0.02, 0.0)] {
            let (a, mut b, d) = b2_c1(g);
            if shift > 0.0 {
                b.tips[5] += TAU / 38.0 / shift;
            }
            let pair = SteppedPair::new(&a, &b, d, 0.0, 1.1);
            let run = pair.run(0.0, TAU, 0.0, &s);
            let mut first_jam = None;
            let traced = pair.trace(0.0, TAU, 0.0, &s, Correction::Forward, |step| {
                if step.jam && first_jam.is_none() {
                    first_jam = Some(step.phi);
                }
                first_jam.is_none()
            });
            assert_eq!(first_jam, run.jam, "G {g}");
            assert_eq!(traced.blocked_at_start, run.blocked_at_start, "G {g}");
            if !run.blocked_at_start {
                assert_eq!(traced.steps, run.steps, "G {g}");
            }
        }
    }

    /// The driven gear put just past the end of its free interval, into the driver tooth
    /// ahead: the forward correction turns it on through that tooth, the two-sided one back to
    /// where it touches the tooth.
    #[test]
    fn a_two_sided_correction_turns_the_driven_gear_back_off_a_tooth_ahead() {
        let s = Stepping::default();
        let (a, b, d) = b2_c1(0.4);
        let pair = SteppedPair::new(&a, &b, d, 0.0, 1.1);
        let touching = pair.start(0.0, 0.0, &s).expect("starts");
        // The far end of the backlash: march forward to the first contact ahead.
        let step = TAU / 38.0 / 512.0;
        let mut ahead = touching + step;
        while !pair.in_contact(0.0, ahead) {
            ahead += step;
        }
        let end = pair.bisect(0.0, ahead, ahead - step);
        let into = end + 0.2 * step;
        assert!(pair.in_contact(0.0, into));
        let back = pair.nearest(0.0, into, &s).expect("free nearby");
        assert!((back - end).abs() < 1e-8, "{back} vs {end}");
        let on = pair.push(0.0, into, 0.0, &s).expect("free ahead");
        assert!(on > end + 0.1 * TAU / 38.0, "{on} vs {end}");
        // Free where it stands: neither correction moves it.
        let mid = 0.5 * (touching + end);
        assert_eq!(pair.nearest(0.0, mid, &s), Some(mid));
    }

    /// Carried by the ratio and corrected either way, an ideal pair's driven gear settles at the
    /// top of its push curve, where the teeth graze it by less than the tolerance: after the
    /// first pitches no tooth meets it for the rest of the turn.
    #[test]
    fn a_carried_ideal_pair_stops_meeting_teeth() {
        let s = Stepping::default();
        let (a, b, d) = b2_c1(0.4);
        let pair = SteppedPair::new(&a, &b, d, 0.0001, 1.1);
        let mut met_late = 0;
        let first_pitch = TAU / 64.0 * 3.0;
        pair.trace(0.0, TAU, 0.0, &s, Correction::CarriedNearest, |step| {
            assert!(!step.jam);
            met_late += usize::from(step.met && step.phi > first_pitch);
            true
        });
        assert_eq!(met_late, 0);
    }

    #[test]
    fn a_misplaced_tooth_jams_an_otherwise_free_mesh() {
        // One driven tip moved a third of a pitch towards its neighbour at a tight clearance:
        // the exact test (tolerance 0) jams where the ideal pair ran.
        let s = Stepping::default();
        let (a, mut b, d) = b2_c1(0.15);
        let free = SteppedPair::new(&a, &b, d, 0.0, 1.1).run(0.0, TAU, 0.0, &s);
        assert_eq!(free.jam, None, "{free:?}");
        b.tips[5] += TAU / 38.0 / 3.0;
        let jammed = SteppedPair::new(&a, &b, d, 0.0, 1.1).run(0.0, TAU, 0.0, &s);
        assert!(jammed.jam.is_some(), "{jammed:?}");
    }
}
