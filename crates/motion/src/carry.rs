//! The driven gear carried at the nominal ratio N1/N2 between contacts and stopped, forward or
//! back, by whichever flank it meets, solved on the exact obstacles of [`Mesh::obstacle`].
//!
//! At driver angle φ the obstacles behind the driven gear (upper ends `hi` at or below θ) and
//! ahead of it (lower ends `lo` at or above θ) bound a free interval `[L(φ), U(φ)]`. The gear
//! is **carried**, θ' = N1/N2, while it is strictly inside; **pushed**, θ = hi of a pair behind,
//! from when that end reaches it until the end rises more slowly than the ratio (its slope falls
//! to N1/N2); **held back**, θ = lo of a pair ahead, from when it runs into that end until the end
//! runs away faster than the ratio. Where the interval closes - a pair ahead reaching a pushed
//! gear, or a pair behind reaching a held-back one - the gear is pinched from both sides: a
//! **lock**, after which it is let go to the next free position ahead ([`Mesh::next_free`]), as
//! the push model does; with none over a whole turn it is stuck until one appears.
//!
//! **How a transition is found.** Every transition is a root of an exact function of φ: an
//! obstacle end minus the gear's rule (`hi − θ` behind, `θ − lo` ahead), or an end's slope minus
//! the ratio, the slope from the contact's point p and common normal n (`Mesh::contact_normal`),
//! dθ/dφ = −(p × n) / ((p − c2) × n), a central difference where the contact has no normal (tip
//! on tip). The driver is walked in steps of [`STEPS_PER_PITCH`] per pitch **only to bracket**
//! these roots: a sign change of a function between a step's ends, or, for an end that may rise
//! into the gear and fall back within a step, its slope changing sign (a peak, located by
//! bisection on the slope's sign, then checked); each root is then located by bisection to
//! [`LOCATE_TOL`] rad of driver angle. A contact must reach [`GRAZE`] rad into the gear's path
//! to count: an end that only grazes the gear (a flat top at its exact level, as every tooth of
//! an ideal pair gives once the gear rides at the top of the push curve) moves nothing and is
//! not drive. A transition missed by the bracketing would have to begin and end within one
//! step with the slope's sign unchanged at both ends.

use contact::{Event, Mesh, Obstacle};

use crate::log::Log;
use crate::path::{Piece, Rule, rule_at};

/// Steps per driver pitch that bracket the transitions (no result depends on it beyond
/// rounding: the transitions are roots, located to [`LOCATE_TOL`]).
pub const STEPS_PER_PITCH: f64 = 16.0;

/// How closely a transition is located (radians of driver angle).
pub const LOCATE_TOL: f64 = 1e-13;

/// How far an obstacle end must reach into the gear's path (radians of driven angle) to be a
/// contact, not a graze.
pub const GRAZE: f64 = 1e-12;

/// How many times the ratio an obstacle end's slope may be at most, for skipping pairs far from
/// the gear: a contact's slope is the ratio of its lever arms about the two centres, which are
/// comparable for teeth of one module.
const SLOPE_BOUND: f64 = 8.0;

/// An end moving more than this many times its rate at the step's start (its slope plus the
/// ratio), plus [`JUMP_TOL`], within part of a step has jumped.
const JUMP_RATE: f64 = 4.0;

/// How far (radians of driven angle) an obstacle end may be from the gear where it is taken to
/// meet it, and the least jump of an end.
const JUMP_TOL: f64 = 1e-7;

/// How far before a switch of contact conditions (radians of driver angle) the old one's slope
/// is read: far enough that the new contact is not the nearer, too near to matter.
const SWITCH_PROBE: f64 = 1e-8;

/// Within this (radians of driven angle) an obstacle end is at the gear: on which side of it an
/// obstacle lies is read with it.
const SIDE_TOL: f64 = 1e-10;

/// Most transitions within one step before the gear is declared stuck for the rest of it (a
/// guard against rounding that would hand a contact back and forth for ever; counted in
/// [`Run::overruns`]).
const MAX_IN_A_STEP: usize = 64;

/// Which side of the driven gear an obstacle lies on: the flank of the driver that meets it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Side {
    /// Behind the gear: a driver tooth's front flank, which pushes it.
    Behind,
    /// Ahead of the gear: a driver tooth's back flank, which holds it back.
    Ahead,
}

/// Where the driven gear starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Placement {
    /// As the push model starts ([`Start::Touching`](contact::Start::Touching) from 0): pushed clear if it overlaps,
    /// otherwise turned back until it rests against a driver tooth behind.
    Touching,
    /// At this angle; where that overlaps a driver tooth, at the nearest free position either
    /// way (the correction of a program that turns the driven gear both ways).
    At(f64),
}

/// What happens next in a step.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Transition {
    /// The pair's end reaches the gear from `side`.
    Contact((i64, i64), Side),
    /// The pair moving the gear lets it go (its end's slope passes the ratio, or its obstacle
    /// ends).
    Depart,
    /// A stuck gear finds a free position.
    Release,
    /// The end of the pair moving the gear jumps (its obstacle is the hull of the teeth's
    /// overlap, which can gain or lose a part at once); the gear stood at this angle just
    /// before.
    Jump(f64),
}

/// A run of the carried motion.
pub struct Carried<'m> {
    mesh: &'m Mesh,
    ratio: f64,
    pitch: f64,
    /// How far either side of θ obstacles are looked at: a driven gap, more than the backlash.
    window: f64,
    /// The driven gear's centre, for the contact slopes.
    c2: geometry::Vec2,
    phi: f64,
    theta: f64,
    rule: Rule,
    /// The pairs whose obstacles lie near θ, with their side.
    sides: Vec<((i64, i64), Side)>,
    /// Their obstacles at the current driver angle.
    near: Vec<Obstacle>,
    /// The pieces so far, the current one's start.
    pieces: Vec<Piece>,
    piece_start: f64,
    log: Log,
    scratch: Vec<Obstacle>,
    /// The first drive: where, and from which side (a lock counts as met from behind).
    first: Option<FirstFlank>,
    /// Steps cut short by [`MAX_IN_A_STEP`].
    overruns: usize,
}

/// Where a carried gear was first moved by a tooth, and from which side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstFlank {
    /// Driver angle.
    pub phi: f64,
    /// Driven angle.
    pub theta: f64,
    /// The side of the tooth that moved it.
    pub side: Side,
}

/// The events of a run (and its pieces, where asked).
pub struct Run {
    /// Jams and losses of drive.
    pub events: Vec<Event>,
    /// The pieces of θ(φ), in order.
    pub pieces: Vec<Piece>,
    /// Steps in which more transitions came than a step can hold, the gear held where it was
    /// for the rest of the step: none in a sound run (the tests hold it to none).
    pub overruns: usize,
}

impl<'m> Carried<'m> {
    /// Runs the carried motion on `mesh` from `phi0` to `phi_end`, the driven gear placed as
    /// `placement` says, ending early once `answered` holds for the events (asked where every
    /// event is sized).
    pub fn run(
        mesh: &'m Mesh,
        phi0: f64,
        phi_end: f64,
        placement: Placement,
        answered: Option<&contact::Answered<'_>>,
    ) -> Run {
        Self::run_while(mesh, phi0, phi_end, placement, STEPS_PER_PITCH, |run| {
            answered.is_none_or(|answered| !(run.log.settled() && answered(run.log.events())))
        })
        .0
    }

    /// [`Carried::run`] of the whole range with the bracketing step set to `1 / steps_per_pitch`
    /// of the driver's pitch: the result must not depend on it beyond rounding (the transitions
    /// are roots); the differential test runs them against each other.
    #[doc(hidden)]
    pub fn run_with_steps(
        mesh: &'m Mesh,
        phi0: f64,
        phi_end: f64,
        placement: Placement,
        steps_per_pitch: f64,
    ) -> Run {
        Self::run_while(mesh, phi0, phi_end, placement, steps_per_pitch, |_| true).0
    }

    /// Where the carried gear, placed as `placement` says at `phi0`, is first moved by a tooth
    /// before `phi_end`, and from which side; `None` if no tooth moves it (or the start is
    /// blocked, or it is pinched as soon as placed).
    pub fn first_flank(
        mesh: &'m Mesh,
        phi0: f64,
        phi_end: f64,
        placement: Placement,
    ) -> Option<FirstFlank> {
        Self::run_while(mesh, phi0, phi_end, placement, STEPS_PER_PITCH, |run| {
            run.first.is_none()
        })
        .1
    }

    /// Runs from `phi0` while `go_on` holds after each step, up to `phi_end`.
    fn run_while(
        mesh: &'m Mesh,
        phi0: f64,
        phi_end: f64,
        placement: Placement,
        steps_per_pitch: f64,
        go_on: impl Fn(&Carried<'_>) -> bool,
    ) -> (Run, Option<FirstFlank>) {
        let n1 = mesh.driver().teeth() as f64;
        let n2 = mesh.driven().teeth() as f64;
        let pitch = std::f64::consts::TAU / n1;
        let gap = (0..mesh.driven().teeth() as i64)
            .map(|k| mesh.driven().tip_angle(k + 1) - mesh.driven().tip_angle(k))
            .fold(0.0, f64::max);
        let d = mesh.centre_distance();
        let mut run = Carried {
            mesh,
            ratio: n1 / n2,
            pitch,
            window: gap,
            c2: geometry::Vec2::new(d, 0.0),
            phi: phi0,
            theta: 0.0,
            rule: Rule::Stuck(0.0),
            sides: Vec::new(),
            near: Vec::new(),
            pieces: Vec::new(),
            piece_start: phi0,
            log: Log::new(phi0, 0.0, pitch, n1 / n2),
            scratch: Vec::new(),
            first: None,
            overruns: 0,
        };
        run.start(placement);
        let step = pitch / steps_per_pitch;
        while run.phi < phi_end {
            let next = if run.phi + step * (1.0 + 1e-6) >= phi_end {
                phi_end
            } else {
                run.phi + step
            };
            run.advance(next);
            if !go_on(&run) {
                break;
            }
        }
        let end = run.phi;
        run.close_piece(end);
        let (theta, first, overruns) = (run.theta, run.first, run.overruns);
        let done = Run {
            events: run.log.finish(end, theta),
            pieces: run.pieces,
            overruns,
        };
        (done, first)
    }

    /// Places the driven gear at the start and reads its first rule.
    fn start(&mut self, placement: Placement) {
        let phi = self.phi;
        let guess = match placement {
            Placement::Touching => 0.0,
            Placement::At(t) => t,
        };
        let Some(free) = self.mesh.next_free(phi, guess, false) else {
            // No free position: the gears cannot turn from here, always an event.
            self.theta = guess;
            self.rule = Rule::Stuck(guess);
            self.log = Log::new(phi, guess, self.pitch, self.ratio);
            let pair = self.overlapping_pair(phi, guess);
            self.log.blocked(phi, guess, pair);
            self.refresh();
            return;
        };
        self.theta = match placement {
            Placement::Touching if free <= guess => {
                // Free at the guess: turned back until it rests on a driver tooth behind, as
                // the push model starts (`Start::Touching`).
                let gap = self.window;
                self.mesh
                    .obstacles(phi, guess - 2.0 * gap, guess, &mut self.scratch);
                self.scratch
                    .iter()
                    .map(|o| o.hi)
                    .filter(|&h| h <= guess)
                    .fold(f64::NEG_INFINITY, f64::max)
                    .max(guess - 2.0 * gap)
            }
            Placement::At(t) if free > t => match self.free_below(phi, t) {
                Some(below) if t - below < free - t => below,
                _ => free,
            },
            _ => free,
        };
        self.log = Log::new(phi, self.theta, self.pitch, self.ratio);
        self.refresh();
        self.settle(phi);
    }

    /// The nearest driven angle at or below θ that overlaps no driver tooth at φ: the obstacles
    /// within two driven gaps below θ swept down from it by their upper ends; None if they close
    /// up over that range.
    fn free_below(&mut self, phi: f64, theta: f64) -> Option<f64> {
        let reach = 2.0 * self.window;
        self.mesh
            .obstacles(phi, theta - reach, theta, &mut self.scratch);
        self.scratch.sort_by(|a, b| b.hi.total_cmp(&a.hi));
        let mut bottom = theta;
        for o in &self.scratch {
            if o.hi >= bottom - SIDE_TOL && o.lo < bottom {
                bottom = o.lo;
            }
        }
        (bottom > theta - reach).then_some(bottom)
    }

    /// The pair whose obstacle holds θ at φ, for a blocked start ((0, 0) if none is found).
    fn overlapping_pair(&mut self, phi: f64, theta: f64) -> (i64, i64) {
        let w = self.window;
        self.mesh
            .obstacles(phi, theta - w, theta + w, &mut self.scratch);
        self.scratch
            .iter()
            .find(|o| o.lo <= theta && theta <= o.hi)
            .map_or((0, 0), |o| (o.driver_tooth, o.driven_tooth))
    }

    /// The driven angle under the current rule at φ (None where its pair has no obstacle).
    fn theta_at(&self, phi: f64) -> Option<f64> {
        rule_at(self.mesh, self.rule, phi, self.ratio)
    }

    /// The obstacle end of `pair` that faces the gear from `side`, at φ.
    fn end(&self, phi: f64, pair: (i64, i64), side: Side) -> Option<f64> {
        self.mesh.obstacle(phi, pair.0, pair.1).map(|o| match side {
            Side::Behind => o.hi,
            Side::Ahead => o.lo,
        })
    }

    /// dθ/dφ along the contact of `pair` at the end facing `side`, at φ: from the contact's
    /// point and normal, or by a central difference where there is no normal.
    fn slope(&self, phi: f64, pair: (i64, i64), side: Side) -> Option<f64> {
        self.slope_with(phi, pair, side, self.end(phi, pair, side)?)
    }

    /// [`Carried::slope`], the end already known to be at `theta`.
    fn slope_with(&self, phi: f64, pair: (i64, i64), side: Side, theta: f64) -> Option<f64> {
        if let Some((p, n)) = self.mesh.contact_normal(phi, theta, pair.0, pair.1) {
            let (arm1, arm2) = (p.perp(&n), (p - self.c2).perp(&n));
            if arm2.abs() > 1e-12 * (p - self.c2).norm() {
                return Some(-arm1 / arm2);
            }
        }
        let h = 1e-7;
        let (a, b) = (
            self.end(phi - h, pair, side)?,
            self.end(phi + h, pair, side)?,
        );
        Some((b - a) / (2.0 * h))
    }

    /// The driven angle under the current rule at φ, or, where its pair's obstacle has just
    /// ended, its last value before φ (located by bisection from the current angle).
    fn theta_before(&self, phi: f64) -> f64 {
        if let Some(theta) = self.theta_at(phi) {
            return theta;
        }
        let (mut lo, mut hi) = (self.phi, phi);
        let Some(mut theta) = self.theta_at(lo) else {
            return self.theta;
        };
        while hi - lo > LOCATE_TOL {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            match self.theta_at(mid) {
                Some(t) => (lo, theta) = (mid, t),
                None => hi = mid,
            }
        }
        theta
    }

    /// Whether `pair` touches by the same contact condition at (φa, θa) and (φb, θb): the
    /// common normal the same line in one gear's frame (a flank of that gear), up to its sign.
    /// Curved flanks, and contacts without a normal, count as the same.
    fn same_contact(&self, (pa, ta): (f64, f64), (pb, tb): (f64, f64), pair: (i64, i64)) -> bool {
        if self.mesh.driver().flank_sagitta() != 0.0 || self.mesh.driven().flank_sagitta() != 0.0 {
            return true;
        }
        let frames = |phi: f64, theta: f64| {
            self.mesh
                .contact_normal(phi, theta, pair.0, pair.1)
                .map(|(_, n)| {
                    (
                        geometry::rotate(n, -phi),
                        geometry::rotate(n, theta - std::f64::consts::PI),
                    )
                })
        };
        let (Some((da, na)), Some((db, nb))) = (frames(pa, ta), frames(pb, tb)) else {
            return true;
        };
        da.perp(&db).abs() < 1e-9 || na.perp(&nb).abs() < 1e-9
    }

    /// The slope of the current rule at φ.
    fn rule_slope(&self, phi: f64) -> Option<f64> {
        match self.rule {
            Rule::Carried { .. } => Some(self.ratio),
            Rule::Pushed(j, k) => self.slope(phi, (j, k), Side::Behind),
            Rule::HeldBack(j, k) => self.slope(phi, (j, k), Side::Ahead),
            Rule::Stuck(_) => Some(0.0),
        }
    }

    /// How far `pair`'s end reaches into the gear's path at φ (positive: past it), from `side`.
    fn reach(&self, phi: f64, pair: (i64, i64), side: Side) -> Option<f64> {
        let theta = self.theta_at(phi)?;
        let end = self.end(phi, pair, side)?;
        Some(match side {
            Side::Behind => end - theta,
            Side::Ahead => theta - end,
        })
    }

    /// d/dφ of [`Carried::reach`].
    fn reach_slope(&self, phi: f64, pair: (i64, i64), side: Side) -> Option<f64> {
        let (s, r) = (self.slope(phi, pair, side)?, self.rule_slope(phi)?);
        Some(match side {
            Side::Behind => s - r,
            Side::Ahead => r - s,
        })
    }

    /// The pair that moves the gear under the current rule, with the side it moves it from.
    fn mover(&self) -> Option<((i64, i64), Side)> {
        match self.rule {
            Rule::Pushed(j, k) => Some(((j, k), Side::Behind)),
            Rule::HeldBack(j, k) => Some(((j, k), Side::Ahead)),
            Rule::Carried { .. } | Rule::Stuck(_) => None,
        }
    }

    /// Walks the driver to `b`, taking every transition on the way.
    fn advance(&mut self, b: f64) {
        let mut taken = 0;
        while self.phi < b {
            let a = self.phi;
            match self.next_transition(a, b) {
                None => {
                    self.phi = b;
                    self.theta = self.theta_at(b).unwrap_or(self.theta);
                    // The obstacles the step read at b are those near the gear there.
                    std::mem::swap(&mut self.near, &mut self.scratch);
                    self.classify();
                }
                Some((phi, what)) => {
                    taken += 1;
                    if taken > MAX_IN_A_STEP {
                        if std::env::var_os("CARRY_DEBUG").is_some() {
                            eprintln!(
                                "overrun at {phi}: {what:?} rule {:?} theta {}",
                                self.rule, self.theta
                            );
                        }
                        self.overruns += 1;
                        self.stick(phi, self.theta);
                        self.close_piece(b);
                        self.phi = b;
                        self.refresh();
                        continue;
                    }
                    self.take(phi, what);
                }
            }
        }
    }

    /// The first transition in `(a, b]`, if any. The obstacles near the gear are read once at
    /// `b` (those at `a` are known), each pair's end there taken from that list; only a
    /// bracketed transition evaluates pairs again, to locate it.
    fn next_transition(&mut self, a: f64, b: f64) -> Option<(f64, Transition)> {
        if let Rule::Stuck(theta) = self.rule {
            let free = |phi: f64| self.mesh.next_free(phi, theta, true).is_some();
            return free(b).then(|| (bisect(a, b, free), Transition::Release));
        }
        let mover_b = self.theta_at(b);
        let mut first = self.mover_transition(a, b, mover_b);
        let theta_b = mover_b.unwrap_or(self.theta + self.ratio * (b - a));
        let w = self.window;
        let mut at_b = std::mem::take(&mut self.scratch);
        self.mesh.obstacles(b, theta_b - w, theta_b + w, &mut at_b);
        // Earlier phases win ties, as the order they are looked at.
        for found in [
            self.known_pairs_contact((a, b), theta_b, &at_b),
            self.new_pairs_contact((a, b), theta_b, &at_b),
        ] {
            first = earliest(first, found);
        }
        self.scratch = at_b;
        first
    }

    /// The first transition of the pair moving the gear within `(a, b]`, if one moves it: where
    /// its end jumps, and where it lets go (before a jump). `mover_b`: its end at `b`.
    fn mover_transition(&self, a: f64, b: f64, mover_b: Option<f64>) -> Option<(f64, Transition)> {
        let (pair, side) = self.mover()?;
        let theta_a = self.theta;
        let mut first: Option<(f64, Transition)> = None;
        let mut offer = |phi: f64, what: Transition| first = earliest(first, Some((phi, what)));
        let exists = |phi: f64| self.end(phi, pair, side).is_some();
        let lets_go_with = |phi: f64, end: Option<f64>| match end
            .and_then(|e| self.slope_with(phi, pair, side, e))
        {
            None => true,
            Some(s) => match side {
                Side::Behind => s <= self.ratio,
                Side::Ahead => s >= self.ratio,
            },
        };
        let lets_go = |phi: f64| lets_go_with(phi, self.end(phi, pair, side));
        let rate = self
            .slope_with(a, pair, side, theta_a)
            .map_or(self.ratio, f64::abs)
            + self.ratio;
        let jumped = |phi: f64, end: Option<f64>| {
            end.is_some_and(|e| (e - theta_a).abs() > JUMP_RATE * rate * (phi - a) + JUMP_TOL)
        };
        let mut until = (b, mover_b);
        if jumped(b, mover_b) {
            let (before, at) = bracket(a, b, |phi| jumped(phi, self.end(phi, pair, side)));
            match self.end(before, pair, side) {
                Some(t) => offer(at, Transition::Jump(t)),
                None => offer(at, Transition::Depart),
            }
            until = (before, self.end(before, pair, side));
        }
        let (mut b_mover, mut end_b) = until;
        // The end's contact changes where two contact conditions cross (a kink: the paper's
        // switch from Phase 1 to Phase 2, or tip on tip): the slope may fall below the ratio
        // just before one and rise above it after. Such a switch within the step is located,
        // and the gear let go before it if the slope fell there.
        if let Some(e) = end_b
            && !self.same_contact((a, theta_a), (b_mover, e), pair)
        {
            let (before, _) = bracket(a, b_mover, |phi| {
                self.end(phi, pair, side)
                    .is_none_or(|e| !self.same_contact((a, theta_a), (phi, e), pair))
            });
            // Just short of the switch, where the old contact is still the nearest.
            let probe = (before - SWITCH_PROBE).max(a);
            if self.end(probe, pair, side).is_some() && lets_go(probe) {
                (b_mover, end_b) = (probe, self.end(probe, pair, side));
            }
        }
        if lets_go_with(a, Some(theta_a)) {
            offer(a, Transition::Depart);
        } else if end_b.is_none() {
            let gone = bisect(a, b_mover, |phi| !exists(phi));
            offer(bisect(a, gone, lets_go), Transition::Depart);
        } else if lets_go_with(b_mover, end_b) {
            offer(bisect(a, b_mover, lets_go), Transition::Depart);
        }
        first
    }

    /// The first contact within `(a, b)` of a pair already beside the gear (other than the one
    /// moving it): where its end reaches into the gear's path. `at_b`: the obstacles at `b`.
    fn known_pairs_contact(
        &self,
        (a, b): (f64, f64),
        theta_b: f64,
        at_b: &[Obstacle],
    ) -> Option<(f64, Transition)> {
        let mover = self.mover().map(|m| m.0);
        let end_in = |list: &[Obstacle], pair: (i64, i64), side: Side| {
            list.iter()
                .find(|o| (o.driver_tooth, o.driven_tooth) == pair)
                .map(|o| match side {
                    Side::Behind => o.hi,
                    Side::Ahead => o.lo,
                })
        };
        let mut first = None;
        for &(pair, side) in &self.sides {
            if Some(pair) == mover {
                continue;
            }
            let ends = (end_in(&self.near, pair, side), end_in(at_b, pair, side));
            if let Some(phi) = self.contact_in((a, b), (self.theta, theta_b), ends, pair, side) {
                first = earliest(first, Some((phi, Transition::Contact(pair, side))));
            }
        }
        first
    }

    /// The first contact within `(a, b]` of a pair that comes near the gear within the step: one
    /// found straddling its path at `b` met it on the side where its obstacle was born.
    fn new_pairs_contact(
        &self,
        (a, b): (f64, f64),
        theta_b: f64,
        at_b: &[Obstacle],
    ) -> Option<(f64, Transition)> {
        let mut first = None;
        for o in at_b {
            let pair = (o.driver_tooth, o.driven_tooth);
            let straddles = o.hi > theta_b + SIDE_TOL && o.lo < theta_b - SIDE_TOL;
            if !straddles || self.sides.iter().any(|(p, _)| *p == pair) {
                continue;
            }
            let exists = |phi: f64| self.mesh.obstacle(phi, pair.0, pair.1).is_some();
            let born = if exists(a) { a } else { bisect(a, b, exists) };
            let side = match (
                self.mesh.obstacle(born, pair.0, pair.1),
                self.theta_at(born),
            ) {
                (Some(o), Some(t)) if 0.5 * (o.lo + o.hi) <= t => Side::Behind,
                _ => Side::Ahead,
            };
            let reaches = |phi: f64| self.reach(phi, pair, side).is_some_and(|r| r >= GRAZE);
            let phi = if reaches(born) {
                born
            } else {
                bisect(born, b, reaches)
            };
            first = earliest(first, Some((phi, Transition::Contact(pair, side))));
        }
        first
    }

    /// Where in `(a, b]` `pair`'s end, from `side`, first reaches [`GRAZE`] into the gear's
    /// path, given the gear's angle and the end at `a` and `b` (`None`: no obstacle): a sign
    /// change over the step, or a peak within it (the end's reach rising at `a` and falling at
    /// `b`, located by bisection on the sign of its slope) that reaches it.
    fn contact_in(
        &self,
        (a, b): (f64, f64),
        (theta_a, theta_b): (f64, f64),
        (end_a, end_b): (Option<f64>, Option<f64>),
        pair: (i64, i64),
        side: Side,
    ) -> Option<f64> {
        let reaches = |phi: f64| self.reach(phi, pair, side).is_some_and(|r| r >= GRAZE);
        let reach = |theta: f64, end: Option<f64>| {
            end.map_or(f64::NEG_INFINITY, |e| match side {
                Side::Behind => e - theta,
                Side::Ahead => theta - e,
            })
        };
        let (ra, rb) = (reach(theta_a, end_a), reach(theta_b, end_b));
        if rb >= GRAZE {
            return Some(if ra >= GRAZE {
                a
            } else {
                bisect(a, b, reaches)
            });
        }
        // Far from the gear at both ends: an obstacle end moves at a few times the ratio at
        // most (the contact's lever arms about the two centres are comparable), so within a
        // step it cannot come back from farther than this.
        let slack = (b - a) * SLOPE_BOUND * self.ratio;
        if ra.max(rb) < -slack {
            return None;
        }
        let slope_of = |phi: f64, theta: f64, end: Option<f64>| -> Option<f64> {
            let s = self.slope_with(phi, pair, side, end?)?;
            let r = match self.mover() {
                Some((p, ms)) => self.slope_with(phi, p, ms, theta)?,
                None => self.rule_slope(phi)?,
            };
            Some(match side {
                Side::Behind => s - r,
                Side::Ahead => r - s,
            })
        };
        let (sa, sb) = (slope_of(a, theta_a, end_a)?, slope_of(b, theta_b, end_b)?);
        if !(sa > 0.0 && sb < 0.0) {
            return None;
        }
        let falling = |phi: f64| self.reach_slope(phi, pair, side).is_none_or(|s| s <= 0.0);
        let peak = bisect(a, b, falling);
        reaches(peak).then(|| bisect(a, peak, reaches))
    }

    /// Takes the transition `what` at φ.
    fn take(&mut self, phi: f64, what: Transition) {
        let theta = self.theta_before(phi);
        self.close_piece(phi);
        self.phi = phi;
        self.theta = theta;
        match what {
            Transition::Depart => {
                if let Some((pair, _)) = self.mover() {
                    self.log.lose(phi, theta, pair);
                }
                self.rule = Rule::Carried { phi, theta };
                self.refresh();
            }
            Transition::Contact(pair, side) => {
                // An end that reaches the gear by a jump (see [`Transition::Jump`]) has closed
                // over it: no flank meets it, the pair's teeth hold it from both sides.
                let jumped = self
                    .end(phi, pair, side)
                    .is_none_or(|e| (e - theta).abs() > JUMP_TOL);
                let pinched = jumped
                    || matches!(
                        (self.rule, side),
                        (Rule::Pushed(..), Side::Ahead) | (Rule::HeldBack(..), Side::Behind)
                    );
                if pinched {
                    self.lock(phi, theta, pair);
                } else {
                    self.log.drive(phi, theta, pair);
                    self.met(phi, theta, side);
                    self.rule = match side {
                        Side::Behind => Rule::Pushed(pair.0, pair.1),
                        Side::Ahead => Rule::HeldBack(pair.0, pair.1),
                    };
                    self.refresh();
                }
            }
            Transition::Jump(before) => {
                let Some((pair, side)) = self.mover() else {
                    return;
                };
                self.theta = before;
                let away = self.end(phi, pair, side).is_none_or(|e| match side {
                    Side::Behind => e < before,
                    Side::Ahead => e > before,
                });
                if away {
                    self.log.lose(phi, before, pair);
                    self.rule = Rule::Carried { phi, theta: before };
                    self.refresh();
                } else {
                    self.lock(phi, before, pair);
                }
            }
            Transition::Release => {
                if let Some(free) = self.mesh.next_free(phi, theta, true) {
                    self.theta = free;
                    self.refresh();
                    self.settle(phi);
                }
            }
        }
    }

    /// Notes the first drive.
    fn met(&mut self, phi: f64, theta: f64, side: Side) {
        if self.first.is_none() {
            self.first = Some(FirstFlank { phi, theta, side });
        }
    }

    /// The gear pinched at (φ, θ) by `pair`: a lock, then let go to the next free position
    /// ahead (stuck where there is none).
    fn lock(&mut self, phi: f64, theta: f64, pair: (i64, i64)) {
        // Pinched while pushed or held back: the first drive was met before.
        self.met(phi, theta, Side::Behind);
        match self.mesh.next_free(phi, theta, true) {
            Some(free) => {
                self.log.lock(phi, theta, free, pair);
                self.theta = free;
                self.refresh();
                self.settle(phi);
            }
            None => {
                self.log.lock(phi, theta, theta, pair);
                self.stick(phi, theta);
            }
        }
    }

    /// The gear stuck at θ from φ on, until a free position appears.
    fn stick(&mut self, phi: f64, theta: f64) {
        self.close_piece(phi);
        self.phi = phi;
        self.theta = theta;
        self.rule = Rule::Stuck(theta);
        self.refresh();
    }

    /// Reads the rule of a gear just placed at θ (started, released): pushed by a pair behind
    /// touching it whose end rises faster than the ratio, held back by one ahead that runs
    /// slower, carried otherwise; pinched by both, a lock.
    fn settle(&mut self, phi: f64) {
        let theta = self.theta;
        let touching = |side: Side| {
            self.sides
                .iter()
                .filter(|(_, s)| *s == side)
                .filter_map(|&(pair, s)| {
                    let end = self.end(phi, pair, s)?;
                    let slope = self.slope(phi, pair, s)?;
                    ((end - theta).abs() <= SIDE_TOL).then_some((pair, slope))
                })
                .collect::<Vec<_>>()
        };
        let pusher = touching(Side::Behind)
            .into_iter()
            .filter(|&(_, s)| s > self.ratio)
            .max_by(|x, y| x.1.total_cmp(&y.1));
        let holder = touching(Side::Ahead)
            .into_iter()
            .filter(|&(_, s)| s < self.ratio)
            .min_by(|x, y| x.1.total_cmp(&y.1));
        self.rule = match (pusher, holder) {
            (Some((p, _)), None) => {
                self.log.drive(phi, theta, p);
                self.met(phi, theta, Side::Behind);
                Rule::Pushed(p.0, p.1)
            }
            (None, Some((h, _))) => {
                self.log.drive(phi, theta, h);
                self.met(phi, theta, Side::Ahead);
                Rule::HeldBack(h.0, h.1)
            }
            (Some(_), Some((h, _))) => {
                // Pinched as soon as placed: no room to move either way.
                self.log.lock(phi, theta, theta, h);
                Rule::Stuck(theta)
            }
            (None, None) => Rule::Carried { phi, theta },
        };
    }

    /// The pairs near the gear at (φ, θ) and their sides: by where their obstacles lie, the
    /// pair moving the gear on the side it moves it from, a pair straddling θ (only after
    /// rounding) on the side it was on.
    fn refresh(&mut self) {
        let (phi, theta, w) = (self.phi, self.theta, self.window);
        self.mesh
            .obstacles(phi, theta - w, theta + w, &mut self.near);
        self.classify();
    }

    /// The sides of the pairs of `near` (see [`Carried::refresh`]).
    fn classify(&mut self) {
        let theta = self.theta;
        let mover = self.mover();
        let old = std::mem::take(&mut self.sides);
        self.sides = self
            .near
            .iter()
            .map(|o| {
                let pair = (o.driver_tooth, o.driven_tooth);
                let side = match mover {
                    Some((p, s)) if p == pair => s,
                    _ => {
                        if o.hi <= theta + SIDE_TOL {
                            Side::Behind
                        } else if o.lo >= theta - SIDE_TOL {
                            Side::Ahead
                        } else {
                            old.iter()
                                .find(|(p, _)| *p == pair)
                                .map_or(Side::Ahead, |(_, s)| *s)
                        }
                    }
                };
                (pair, side)
            })
            .collect();
    }

    /// Ends the current piece at φ.
    fn close_piece(&mut self, phi: f64) {
        if phi > self.piece_start || self.pieces.is_empty() {
            self.pieces.push(Piece {
                phi_start: self.piece_start,
                phi_end: phi,
                rule: self.rule,
            });
        }
        self.piece_start = phi;
    }
}

/// The last point of `[lo, hi)` where `pred` does not hold and the first where it does, to
/// [`LOCATE_TOL`], given that it holds at `hi` and not at `lo`.
fn bracket(mut lo: f64, mut hi: f64, pred: impl Fn(f64) -> bool) -> (f64, f64) {
    while hi - lo > LOCATE_TOL {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    (lo, hi)
}

/// The first point of `(lo, hi]` where `pred` holds, to [`LOCATE_TOL`], given that it holds at
/// `hi` (and not at `lo`): bisection on its truth.
fn bisect(mut lo: f64, mut hi: f64, pred: impl Fn(f64) -> bool) -> f64 {
    while hi - lo > LOCATE_TOL {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if pred(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// A trial of the carried motion as a model's [`crate::Outcome`]: its events, and its path
/// where asked.
pub(crate) fn outcome(
    trial: &crate::Trial<'_>,
    want: crate::Want<'_>,
    placement: Placement,
) -> crate::Outcome {
    let answered = match want {
        crate::Want::Path => None,
        crate::Want::Events(answered) => Some(answered),
    };
    let run = Carried::run(trial.mesh, trial.phi0, trial.phi_end(), placement, answered);
    let path = answered.is_none().then(|| crate::Path::Carried {
        mesh: Box::new(trial.mesh.clone()),
        pieces: run.pieces,
    });
    crate::Outcome {
        events: run.events,
        path,
    }
}

/// The earlier of two found transitions; on a tie, the one found first (`a`).
fn earliest(
    a: Option<(f64, Transition)>,
    b: Option<(f64, Transition)>,
) -> Option<(f64, Transition)> {
    match (a, b) {
        (Some(x), Some(y)) => Some(if y.0 < x.0 { y } else { x }),
        (x, None) => x,
        (None, y) => y,
    }
}
