//! The exact core's run: its state (the driven gear's [`Drive`], the events waiting to be
//! sized), the main loop that walks the driver through its steps (`Mesh::walk`, `Run::advance`),
//! and the bookkeeping of events (recorded, sized when the drive resumes). The crate's documentation says where each event is decided; `step.rs` takes a step,
//! `cover.rs` finds the next free position, `held.rs` (beside this module) lets a held gear go.

use std::f64::consts::TAU;

use smallvec::SmallVec;

use crate::closing;
use crate::held;
use crate::mesh::{End, Mesh, Obstacle, PairMemo};

mod cover;
mod search;
pub(crate) mod shortcut;
mod step;
mod trajectory;

pub(crate) use crate::stats::count;
use search::{bisect, bracket, golden_max};
#[cfg(feature = "speed")]
pub(crate) use shortcut::Stand;
pub(crate) use shortcut::{ExactOnly, Shortcut};
pub use trajectory::{Answered, Event, EventKind, Motion, Segment, Start, StopAt, Trajectory};

/// Relative tolerance (radians) when deciding on which side of θ an obstacle lies.
pub(crate) const SIDE_TOL: f64 = 1e-10;
/// How near (radians of driven angle, relative to 1 + |θ|) an obstacle's end must be to θ to
/// count as a contact when an event is classified: located events are far closer than this.
const CONTACT_TOL: f64 = 1e-9;
/// Event location accuracy in driver angle (radians): far below the required 1e-6°.
const LOCATE_TOL: f64 = 1e-13;
/// How closely the angle where a new obstacle appeared is located to tell on which side of θ
/// it appeared (radians of driver angle).
const SIDE_LOCATE_TOL: f64 = 1e-10;
/// How far past a first touch from rest a step ends (radians of driver angle).
const TOUCH_STEP: f64 = 1e-8;
/// Steps per driver pitch: how far apart the exact step looks at the tooth pairs together.
pub(crate) const STEPS_PER_PITCH: f64 = 4.0;

/// When a run may end before its last driver angle.
#[derive(Clone, Copy)]
pub(crate) enum Stop<'s> {
    /// Never: the run goes to its end.
    Never,
    /// At the first event for which this holds, as it is recorded.
    AtEvent(&'s StopAt<'s>),
    /// Once this holds for the events so far, none of them waiting to be sized.
    Answered(&'s Answered<'s>),
}

/// How the core walks a run: where it may end, the steps per driver pitch, and whether every
/// segment is kept (else only the last).
pub(crate) type Walk<'s> = (Stop<'s>, f64, bool);

/// Which side of the driven gear a tooth pair's obstacle lies on.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Side {
    Behind,
    Ahead,
}

/// A tooth pair whose obstacle is near θ.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Tracked {
    pub(crate) pair: (i64, i64),
    pub(crate) side: Side,
    /// Upper end of the obstacle at the current driver angle.
    pub(crate) hi: f64,
}

impl Tracked {
    /// Whether the pair pushes the driven gear at θ: behind it, its upper end at θ.
    pub(crate) fn pushes(&self, theta: f64) -> bool {
        self.side == Side::Behind && (self.hi - theta).abs() <= SIDE_TOL
    }
}

/// A few tooth pairs (pushers, pairs born or gone in a step): kept inline, as every step of a
/// run makes several such lists and a heap allocation costs as much as the rest of the list's use.
pub(crate) type Pairs = SmallVec<[(i64, i64); 4]>;

/// One end of an evaluated tooth pair's obstacle: (driver angle, (driver tooth, driven tooth),
/// which end, where it is).
type Memo = (f64, (i64, i64), End, Option<f64>);

/// The driven gear's state between steps, which decides how the next step is taken.
#[derive(Debug)]
pub(crate) enum Drive {
    /// Pushed by the pairs touching it from behind (`Run::pushers`): the speed layer is offered
    /// the step first.
    Pushed,
    /// At rest, free: no pair touches it from behind.
    AtRest,
    /// Held: jammed with no free position ahead, until one appears (`Run::held_step`).
    /// `links`: the tooth pairs of the chain that the last step proved to hold it through its end
    /// (`held.rs`), where the next step starts; empty if none.
    Held { links: Vec<(i64, i64)> },
}

/// The events waiting for the drive to resume to be sized, and what sizes them.
#[derive(Debug, Default)]
struct Sizing {
    /// Tooth phase (driver tooth + driven tooth) of the last known driving pair.
    phase: Option<i64>,
    /// Events whose size waits for the drive to resume: (index in `events`, phase before).
    pending: Vec<(usize, Option<i64>)>,
    /// The idle-start candidate (its index in `events`) while no driver tooth has moved the
    /// driven gear yet: see [`Run::record_idle_start`].
    idle_start: Option<usize>,
    /// Whether an idle-start candidate was dropped since the last [`Run::stops`]: the driven
    /// gear moved within a driver pitch of the start.
    dropped_idle_start: bool,
}

/// Working state of one run.
pub(crate) struct Run<'m> {
    mesh: &'m Mesh,
    phi: f64,
    theta: f64,
    drive: Drive,
    /// Driver angle of the last jam check that found nothing holding the driven gear.
    unheld_at: Option<f64>,
    /// Known tooth pairs, their side of θ and their upper end at the current φ.
    sides: Vec<Tracked>,
    /// The segments so far; only the last one when they are not kept.
    segments: Vec<Segment>,
    /// Whether to keep every segment (for θ at any φ) or only the events.
    keep_segments: bool,
    events: Vec<Event>,
    sizing: Sizing,
    scratch: Vec<Obstacle>,
}

impl Mesh {
    /// Runs the push model over driver angles `phi_start..phi_end` from `start`, walking the
    /// driver in steps (`Run::advance`), each offered to `speed` where it may spare the core
    /// work (`shortcut.rs`): the main loop. Returns the segments (only the last where they are
    /// not kept) and the events.
    pub(crate) fn walk(
        &self,
        (phi_start, phi_end): (f64, f64),
        start: Start,
        (stop, steps_per_pitch, keep_segments): Walk<'_>,
        speed: &mut dyn Shortcut,
    ) -> (Vec<Segment>, Vec<Event>) {
        let mut run = Run {
            mesh: self,
            phi: phi_start,
            theta: 0.0,
            drive: Drive::AtRest,
            unheld_at: None,
            sides: Vec::new(),
            segments: Vec::new(),
            keep_segments,
            events: Vec::new(),
            sizing: Sizing::default(),
            scratch: Vec::new(),
        };
        run.start(start);
        let mut seen = 0;
        let step = self.driver.max_gap.min(TAU / self.driver.tips.len() as f64) / steps_per_pitch;
        // A run that keeps no trajectory may end at a stopping event of the start itself (a
        // blocked start); one that keeps it takes its first step first, as it always has.
        let stopped_at_start = !keep_segments && run.stops(stop, &mut seen);
        while run.phi < phi_end && !stopped_at_start {
            // No sliver of a step at the end: it would only gather rounding noise.
            let next = if run.phi + step * (1.0 + 1e-6) >= phi_end {
                phi_end
            } else {
                run.phi + step
            };
            run.advance(next, speed);
            if run.stops(stop, &mut seen) {
                break;
            }
        }
        if run.segments.is_empty() {
            run.rest_to(phi_end);
        }
        run.close_pending();
        (run.segments, run.events)
    }

    /// Where the pushers' upper envelope `env` peaks, refined from `phi_pk` (a golden-section
    /// search's answer, within `range`): where the pair on top peaks smoothly - its contact's
    /// normal passing through the driver's centre, so that dθ/dφ = 0 - golden-section search can
    /// only tell values apart to the rounding of a flat top, about 1e-8 rad of driver angle; the
    /// slope changes sign there, and bisection on its sign locates it to `LOCATE_TOL`. Along a
    /// contact (point p, unit normal n, the driven centre c2) the slope is
    /// dθ/dφ = −(p × n) / ((p − c2) × n), whose sign does not depend on which way n points. A
    /// peak at a kink (tip on tip, no normal; or a hand-over between pairs) is left as found.
    fn smooth_peak(
        &self,
        phi_pk: f64,
        (phi0, phi1): (f64, f64),
        pushers: &[(i64, i64)],
        env: impl Fn(f64) -> f64,
    ) -> f64 {
        let c2 = self.c2();
        let Some(pair) = self.top_pair(phi_pk, pushers) else {
            return phi_pk;
        };
        let rising = |phi: f64| -> Option<bool> {
            let theta = self.hi(phi, pair);
            if self.top_pair(phi, pushers) != Some(pair) || env(phi) != theta {
                return None;
            }
            let (p, n) = self.contact_normal(phi, theta, pair.0, pair.1)?;
            let (arm1, arm2) = (p.perp(&n), (p - c2).perp(&n));
            (arm1 != 0.0 && arm2 != 0.0).then_some(arm1 * arm2 < 0.0)
        };
        // Ten times the flat top's width that golden-section search leaves: the peak lies within.
        let reach = 1e-7 * (1.0 + phi_pk.abs());
        let (a, b) = ((phi_pk - reach).max(phi0), (phi_pk + reach).min(phi1));
        if rising(a) == Some(true) && rising(b) == Some(false) {
            bisect(a, b, |p| rising(p) != Some(false))
        } else {
            phi_pk
        }
    }

    /// The pair of `pairs` whose obstacle reaches highest at φ (None if there are none).
    fn top_pair(&self, phi: f64, pairs: &[(i64, i64)]) -> Option<(i64, i64)> {
        pairs
            .iter()
            .copied()
            .max_by(|&a, &b| self.hi(phi, a).total_cmp(&self.hi(phi, b)))
    }

    /// Upper end of the (j, k) obstacle at φ, or −∞ when it does not exist.
    pub(crate) fn hi(&self, phi: f64, pair: (i64, i64)) -> f64 {
        self.obstacle_end(phi, pair.0, pair.1, End::Upper)
            .unwrap_or(f64::NEG_INFINITY)
    }
}

impl<'m> Run<'m> {
    /// Whether the run ends here by `stop`, given that the events before `seen` were asked
    /// about already (`seen` is moved past those asked about now).
    fn stops(&mut self, stop: Stop<'_>, seen: &mut usize) -> bool {
        match stop {
            Stop::Never => false,
            Stop::AtEvent(stop) => {
                // An idle-start candidate, asked about as it was recorded (first of all events),
                // has gone since: the rest moved down by one.
                if std::mem::take(&mut self.sizing.dropped_idle_start) {
                    *seen = seen.saturating_sub(1);
                }
                let stops = self.events[*seen..].iter().any(stop);
                *seen = self.events.len();
                stops
            }
            // Only where every event is sized: a gap waiting for the drive may yet become a
            // slip, and its lost motion and phase shift are not known.
            Stop::Answered(answered) => {
                let waiting = !self.sizing.pending.is_empty() || self.sizing.idle_start.is_some();
                if waiting || self.events.len() == *seen {
                    return false;
                }
                *seen = self.events.len();
                answered(&self.events)
            }
        }
    }

    fn start(&mut self, start: Start) {
        let (guess, touching) = match start {
            Start::At(t) => (t, false),
            Start::Touching(t) => (t, true),
        };
        let phi = self.phi;
        let mut memo = PairMemo::new(self.mesh, phi);
        let free = self
            .mesh
            .free_or_cover_in(phi, guess, false, None, &mut memo)
            .ok();
        self.theta = match free {
            Some(t) if t > guess => t,
            Some(_) if touching => {
                // Free: turn back until a driver tooth is met (highest upper end below the guess).
                let gap = self.mesh.driven.max_gap;
                self.mesh
                    .obstacles(phi, guess - 2.0 * gap, guess, &mut self.scratch);
                self.scratch
                    .iter()
                    .map(|o| o.hi)
                    .filter(|&h| h <= guess)
                    .fold(f64::NEG_INFINITY, f64::max)
                    .max(guess - 2.0 * gap)
            }
            Some(t) => t,
            None => {
                // No free position: the gears cannot turn from here. Always an event, so that a
                // mesh too tight to start is never silently counted as running.
                self.drive = Drive::Held { links: Vec::new() };
                let gap = self.mesh.driven.max_gap;
                self.mesh
                    .obstacles(phi, guess - gap, guess + gap, &mut self.scratch);
                let pair = self
                    .scratch
                    .iter()
                    .find(|o| o.lo <= guess && guess <= o.hi)
                    .map_or((0, 0), |o| (o.driver_tooth, o.driven_tooth));
                self.events
                    .push(Event::new(EventKind::BlockedAtStart, phi, guess, pair));
                guess
            }
        };
        self.classify_all(phi, &mut memo);
        self.sizing.phase = self
            .touching_behind(phi, self.theta, None, &mut memo)
            .map(|p| p.0 + p.1);
        if !self.is_held() {
            self.record_idle_start();
        }
        self.settle();
    }

    /// Every run that can turn starts with a candidate idle start, a gap waiting for the first
    /// push that moves the driven gear ([`Run::first_lift`]), whether or not a tooth touches it
    /// at the start (a touching pair may fall away without lifting it): sized then like any
    /// loss of drive, it is dropped if that came within a driver pitch, and is a slip - an idle
    /// start - if it came later or never.
    fn record_idle_start(&mut self) {
        let nearest_behind = self
            .sides
            .iter()
            .filter(|t| t.side == Side::Behind)
            .max_by(|a, b| a.hi.total_cmp(&b.hi))
            .map_or((0, 0), |t| t.pair);
        let mut e = Event::new(EventKind::Gap, self.phi, self.theta, nearest_behind);
        e.idle_start = true;
        self.sizing.idle_start = Some(self.events.len());
        self.events.push(e);
    }

    /// A driver tooth (of `pairs`) moves the driven gear for the first time, at the current
    /// (φ, θ): the idle-start candidate is sized, and dropped if this came within a driver pitch.
    fn first_lift(&mut self, pairs: &[(i64, i64)]) {
        let Some(i) = self.sizing.idle_start.take() else {
            return;
        };
        let (phi, theta) = (self.phi, self.theta);
        self.events[i].resumed_by = self.mesh.top_pair(phi, pairs);
        self.size_event(i, phi, theta, true, 0);
        if self.events[i].kind == EventKind::Gap {
            self.events.remove(i);
            for (j, _) in &mut self.sizing.pending {
                if *j > i {
                    *j -= 1;
                }
            }
            self.sizing.dropped_idle_start = true;
        }
    }

    /// A tooth pair touching the driven gear from behind at (φ, θ) (its obstacle's upper end is
    /// at θ), other than `except`: what drives, or would drive, the driven gear there.
    /// The pairs already evaluated at φ are taken from `memo`, a memo at φ, and those it
    /// evaluates left there.
    fn touching_behind(
        &self,
        phi: f64,
        theta: f64,
        except: Option<(i64, i64)>,
        memo: &mut PairMemo,
    ) -> Option<(i64, i64)> {
        let gap = self.mesh.driven.max_gap;
        let mut obs = Vec::new();
        self.mesh
            .obstacles_with(phi, theta - gap, theta + gap, &mut obs, Some(memo));
        obs.iter()
            .filter(|o| Some((o.driver_tooth, o.driven_tooth)) != except)
            .filter(|o| (o.hi - theta).abs() <= CONTACT_TOL * (1.0 + theta.abs()))
            .map(|o| (o.driver_tooth, o.driven_tooth))
            .next()
    }

    /// Records an event; every kind but a blocked start is sized when the drive resumes.
    fn record(&mut self, e: Event, phase_before: Option<i64>) {
        if e.kind != EventKind::BlockedAtStart {
            self.sizing.pending.push((self.events.len(), phase_before));
        }
        self.events.push(e);
    }

    /// Drive resumed at the current (φ, θ), by the pair among `pairs` carrying the driven gear:
    /// size the events waiting for it (lost motion, phase shift, lag) and tell a gap from a slip.
    fn resume_drive(&mut self, pairs: &[(i64, i64)]) {
        let (phi, theta) = (self.phi, self.theta);
        let by = pairs
            .iter()
            .copied()
            .map(|p| (self.mesh.hi(phi, p), p))
            .filter(|(h, _)| h.is_finite())
            .max_by(|a, b| a.0.total_cmp(&b.0))
            .map(|(_, p)| p);
        let phase = by.map(|p| p.0 + p.1);
        for (i, before) in std::mem::take(&mut self.sizing.pending) {
            let shift = match (before, phase) {
                (Some(b), Some(a)) => a - b,
                _ => 0,
            };
            self.events[i].resumed_by = by;
            self.size_event(i, phi, theta, true, shift);
        }
        if phase.is_some() {
            self.sizing.phase = phase;
        }
    }

    /// Events still waiting at the end of the run: drive never resumed.
    fn close_pending(&mut self) {
        let (phi, theta) = (self.phi, self.theta);
        for (i, _) in std::mem::take(&mut self.sizing.pending) {
            self.size_event(i, phi, theta, false, 0);
        }
        if let Some(i) = self.sizing.idle_start.take() {
            self.size_event(i, phi, theta, false, 0);
            // A driven gear never moved in the whole run turned idle throughout, however short
            // the run: never a mere hand-over gap.
            self.events[i].kind = EventKind::Slip;
        }
    }

    fn size_event(&mut self, i: usize, phi: f64, theta: f64, resumed: bool, shift: i64) {
        let n1 = self.mesh.driver.tips.len() as f64;
        let n2 = self.mesh.driven.tips.len() as f64;
        let e = &mut self.events[i];
        e.lost_motion = (phi - e.phi) * n1 / TAU;
        e.resumed = resumed;
        e.phase_shift = shift;
        e.lag = n1 / n2 * (phi - e.phi) - (theta - e.theta);
        // A whole driver pitch without drive, or a tooth out of step: synchronisation lost.
        if e.kind == EventKind::Gap && (e.lost_motion >= 1.0 || shift != 0) {
            e.kind = EventKind::Slip;
        }
    }

    /// Re-derive every nearby obstacle's side from scratch, relative to the current θ.
    /// (The pairs already evaluated at φ are taken from `memo`, a memo at φ, and those it
    /// evaluates left there.)
    fn classify_all(&mut self, phi: f64, memo: &mut PairMemo) {
        let gap = self.mesh.driven.max_gap;
        self.mesh.obstacles_with(
            phi,
            self.theta - gap,
            self.theta + gap,
            &mut self.scratch,
            Some(memo),
        );
        self.sides.clear();
        for o in &self.scratch {
            let side = if o.hi <= self.theta + SIDE_TOL {
                Side::Behind
            } else {
                Side::Ahead
            };
            self.sides.push(Tracked {
                pair: (o.driver_tooth, o.driven_tooth),
                side,
                hi: o.hi,
            });
        }
    }

    /// The pushing pairs: those behind the driven gear whose upper end is at θ.
    fn pushers(&self) -> Pairs {
        self.stand().pushers()
    }

    /// The side of the driven gear `pair` is known to lie on, if it is tracked.
    fn side_of(&self, pair: (i64, i64)) -> Option<Side> {
        self.stand().side_of(pair)
    }

    fn push_segment(&mut self, phi_end: f64, theta_end: f64, motion: Motion) {
        if phi_end <= self.phi && !self.segments.is_empty() {
            self.theta = theta_end;
            return;
        }
        if !self.keep_segments {
            self.segments.clear();
        }
        if let Motion::Push(pairs) = &motion
            && !self.sizing.pending.is_empty()
        {
            self.resume_drive(pairs);
        }
        if let Motion::Push(pairs) = &motion
            && theta_end > self.theta
            && self.sizing.idle_start.is_some()
        {
            self.first_lift(pairs);
        }
        self.segments.push(Segment {
            phi_start: self.phi,
            phi_end,
            theta_start: self.theta,
            theta_end,
            motion,
        });
        self.phi = phi_end;
        self.theta = theta_end;
    }

    fn rest_to(&mut self, phi_end: f64) {
        let motion = if self.is_held() {
            Motion::Held
        } else {
            Motion::Rest
        };
        self.push_segment(phi_end, self.theta, motion);
    }

    /// The driven gear is held at θ: it stays there until the driver angle where a free
    /// position first appears ahead of it, located exactly (`held.rs`: the first root at which
    /// the chain of obstacles that holds it may give way; there the turn is swept again, and the
    /// gear either let go to the free position or held by the new chain), or to `phi1`. A chain
    /// proved to hold through the step is taken up by the next one; the joints of a chain the
    /// speed layer proves to hold are not searched (`Shortcut::held_joints`).
    fn held_step(&mut self, phi1: f64, speed: &mut dyn Shortcut) {
        let mesh = self.mesh;
        let theta = self.theta;
        let threshold = mesh.held_threshold(theta);
        // Where the chain broke, the turn is swept again a little past the root (see
        // `held::ChainBreak`), within the step.
        let past = |change: held::ChainBreak| {
            let least = change.root + LOCATE_TOL * (1.0 + change.root.abs());
            change.look_at.max(least).min(phi1)
        };
        let mut phi = self.phi;
        // The chain the last step proved to hold through its end: no sweep of the turn needed.
        let carried = match &mut self.drive {
            Drive::Held { links } => std::mem::take(links),
            _ => Vec::new(),
        };
        let mut chain = (!carried.is_empty()).then(|| held::Chain::carried(mesh, phi, carried));
        loop {
            let mut held = match chain.take() {
                Some(held) => held,
                None => match self.sweep_held(&mut phi, phi1, threshold) {
                    Some(held) => held,
                    None => return,
                },
            };
            let joints = speed.held_joints(&mut held, theta, phi1);
            let tols = (theta, threshold, SIDE_TOL);
            match held::first_change(&mut held, tols, phi1, joints.as_deref()) {
                // A link's teeth parted where the step starts: the turn is swept there.
                Err(held::LinkGone) => {}
                Ok(Some(change)) if change.root < phi1 => phi = past(change),
                Ok(found) => {
                    if found.is_none() {
                        self.drive = Drive::Held {
                            links: held.into_pairs(),
                        };
                    }
                    self.rest_to(phi1);
                    return;
                }
            }
        }
    }

    /// The turn swept at `phi` for the held gear: the chain that holds it there, or, where there
    /// is a free position, the gear let go to it (just after `phi` if that is where the step
    /// starts, `phi` moved there) and None, as None where it rests to `phi1` instead.
    fn sweep_held(&mut self, phi: &mut f64, phi1: f64, threshold: f64) -> Option<held::Chain<'m>> {
        let (mesh, theta) = (self.mesh, self.theta);
        loop {
            let mut links = Vec::new();
            let mut memo = PairMemo::new(mesh, *phi);
            let Ok(t) = mesh.free_or_cover_in(*phi, theta, true, Some(&mut links), &mut memo)
            else {
                return Some(held::Chain::swept(mesh, *phi, &links, threshold));
            };
            if *phi > self.phi {
                self.release(*phi, t, &mut memo);
                return None;
            }
            // Free where the step starts: let go just after it.
            let phi_r = (*phi + LOCATE_TOL).min(phi1);
            let mut memo = PairMemo::new(mesh, phi_r);
            match mesh.free_or_cover_in(phi_r, theta, true, None, &mut memo) {
                Ok(t) => self.release(phi_r, t, &mut memo),
                Err(_) if phi_r < phi1 => {
                    *phi = phi_r;
                    continue;
                }
                Err(_) => self.rest_to(phi1),
            }
            return None;
        }
    }

    /// The held gear let go at φ to the free position θ = `to`.
    fn release(&mut self, phi: f64, to: f64, memo: &mut PairMemo) {
        self.rest_to(phi);
        self.drive = Drive::AtRest;
        self.theta = to;
        self.classify_all(phi, memo);
    }

    /// Whether the driven gear is held.
    fn is_held(&self) -> bool {
        matches!(self.drive, Drive::Held { .. })
    }

    /// The driven gear's drive read off the pairs touching it from behind, where it is not held:
    /// where each step leaves it (and the start), for the next step to be taken by.
    fn settle(&mut self) {
        if !self.is_held() {
            let theta = self.theta;
            let pushed = self.sides.iter().any(|t| t.pushes(theta));
            self.drive = if pushed { Drive::Pushed } else { Drive::AtRest };
        }
    }

    /// Advance from `self.phi` to `phi1`, locating every event in between, by the driven gear's
    /// drive: a held gear waits for its release (`held_step`); a pushed one is first offered to
    /// the speed layer `speed` (`Shortcut::pushed_step`), and otherwise, as a gear at rest
    /// always, takes the exact step (`step.rs`).
    fn advance(&mut self, phi1: f64, speed: &mut dyn Shortcut) {
        match self.drive {
            Drive::Held { .. } => self.held_step(phi1, speed),
            Drive::Pushed => {
                let pushers = self.pushers();
                // Just after a closing that held nothing (`Run::jam`) the exact step takes the
                // rest of the step, asking only for the roots after its start.
                let offered = self.unheld_at != Some(self.phi);
                if !(offered && speed.pushed_step(self, phi1, &pushers)) {
                    self.exact_step(phi1, pushers, speed);
                }
            }
            Drive::AtRest => self.exact_step(phi1, Pairs::new(), speed),
        }
        self.settle();
    }
}

#[cfg(test)]
#[path = "../../tests/unit/solver.rs"]
mod tests;
