//! The push model, solved exactly: the driven gear stays put until a driver tooth pushes it, then
//! moves only as far as it must to stay clear.
//!
//! At a driver angle φ every driver tooth j makes, for every driven tooth k, an obstacle: a closed
//! interval `[lo, hi]` of driven angles at which the two teeth overlap (see [`Mesh::obstacle`]).
//! The driven angle θ never lies strictly inside one. Obstacles *behind* θ (hi ≤ θ) push it: θ is
//! the running maximum of their upper ends. Obstacles *ahead* (lo ≥ θ) are driver teeth the driven
//! tooth is moving towards. Hence the events, each classified from the contact motion:
//!
//! - an obstacle ahead reaches θ: a **lock** if a pair touches behind at that moment (held on both
//!   sides), a **strike** if nothing does (the push model would have to turn it backwards);
//! - the pushing obstacle stops rising (its tips slip past each other) while no other driver tooth
//!   touches: a **gap**, sized when drive resumes and called a **slip** if it lasted a driver
//!   pitch or more or moved the tooth phase;
//! - no free driven position at the start: **blocked at start**.
//!
//! After a lock or strike the driven gear is let go to the next free position ahead; where there
//! is none it is **held** until one appears, at the first root where the obstacles that close up
//! over its turn may give way (`held.rs`, on the exact conditions of `meet.rs`).
//!
//! Which of these a table counts as a jam or a disengagement is an event rule's call (the `rules`
//! crate), not the solver's.
//!
//! Between events θ(φ) is the maximum of closed-form contact curves, so it is exact at every φ;
//! events are located by bisection or golden-section search on those curves to 1e-13 rad (where
//! a continuous function changes sign - a backlash closing, a curve rising to θ - bisection is
//! replayed after secant steps, to the same angle: `bisect_sign`; where a pushing curve peaks
//! smoothly, by bisection on the sign of its closed-form slope: `Mesh::smooth_peak`).
//!
//! The driver angle is advanced in steps of a quarter of the driver's pitch. A step is first
//! tried on a **certificate** (`certified_step`, straight flanks): bounds on the contact functions
//! over the box of the step's driver angles and the driven angles it can reach (`certify.rs`)
//! prove that every tooth pair near the driven gear either stays clear of it or, behind it, only
//! pushes it forwards; then no event lies in the step, by construction, and it ends where the
//! pushing curves end, with no sampling and no search; a step with no certificate is tried again
//! as two half steps (`certified_halves`: both or neither). Where no certificate is found (an
//! obstacle ahead close by, a pusher about to slip, curved flanks) the step is **bracketed**:
//! the path is planned from the pairs behind, and the backlash ahead along it is searched for
//! its first closing (`Closing::first`). Each stretch of the step is either proved free of
//! contact - the pairs ahead have no contact root in the box, or the tube about the path's chord,
//! that holds the path over it (`certify.rs`) - or halved, the left half first, down to a
//! resolution of 1e-8 rad (a stretch holding a sign change has it located, and the stretch
//! before it proved likewise): no closing wider than that, however brief (a tip grazing a tip),
//! is stepped over, by construction. (Curved flanks have no certificates: there the backlash is
//! sampled at the middle and at finer halvings only where the samples say it could close in
//! between.) `tests/differential.rs` checks that certified steps find exactly the events
//! bracketing finds, and that a finer step finds the same first events.

use std::cell::RefCell;
use std::f64::consts::TAU;

use serde::Serialize;
use smallvec::SmallVec;

use crate::certify::{ConfigBox, PlacedTooth, Verdict, vertex_meeting};
use crate::held;
use crate::mesh::{End, Mesh, Obstacle, PairMemo};

/// Relative tolerance (radians) when deciding on which side of θ an obstacle lies.
const SIDE_TOL: f64 = 1e-10;
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
/// Steps per driver pitch used to bracket events (finer halvings are taken where needed).
const STEPS_PER_PITCH: f64 = 4.0;
/// How far a certified step's first box reaches above the pushers' end, as a share of their rise
/// over the step (a performance choice only: any box holding the path is sound; 0.1 judged the
/// fewest boxes again on `examples/turns`, 0.25 and 0.5 more pairs in taller boxes).
const BOX_HEADROOM: f64 = 0.1;

/// What happened at an event: its mechanical kind, read off the contact motion alone.
///
/// Which kinds a table counts as a "jam" or a "disengagement" is not decided here: that is an
/// event rule's job (the `rules` crate). [`Trajectory::jams`] and [`Trajectory::disengagements`]
/// give the `strict` reading (every lock, strike and blocked start is a jam; every gap and slip
/// a disengagement).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
pub enum EventKind {
    /// Held from both sides at once: the driven gear is pushed by one driver tooth (a contact
    /// behind) into another driver tooth ahead (a contact ahead), so no forward position is
    /// free - the paper's Figure V_A.
    Lock,
    /// One-sided: with nothing pushing the driven gear, an incoming driver tooth meets the front
    /// of a lagging driven tooth, which the push model would have to turn backwards.
    Strike,
    /// Hand-over gap: the pushing contact ended (its tips slipped past each other) before another
    /// driver tooth took over, and drive resumed within one driver pitch, in step.
    Gap,
    /// Drive lost for a whole driver pitch or more, or resumed with the driven gear's tooth phase
    /// against the driver moved by a tooth: synchronisation lost. Also an **idle start**
    /// ([`Event::idle_start`]): a driven gear first pushed a driver pitch or more after the start
    /// of the run, or never in it, turned idle from the start.
    Slip,
    /// No free driven position at the start: the teeth overlap wherever the driven gear is put.
    BlockedAtStart,
}

impl EventKind {
    /// Every kind, in the order above.
    pub const ALL: [EventKind; 5] = [
        EventKind::Lock,
        EventKind::Strike,
        EventKind::Gap,
        EventKind::Slip,
        EventKind::BlockedAtStart,
    ];

    /// Short name, as the event log prints it (`lock`, `strike`, `gap`, `slip`, `blocked`).
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Lock => "lock",
            EventKind::Strike => "strike",
            EventKind::Gap => "gap",
            EventKind::Slip => "slip",
            EventKind::BlockedAtStart => "blocked",
        }
    }

    /// A contact that stops the driver in the push model (lock, strike, blocked start).
    pub fn is_contact_stop(self) -> bool {
        matches!(
            self,
            EventKind::Lock | EventKind::Strike | EventKind::BlockedAtStart
        )
    }

    /// A loss of drive (gap or slip).
    pub fn is_loss(self) -> bool {
        matches!(self, EventKind::Gap | EventKind::Slip)
    }
}

/// One event of a run: its kind and its size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Event {
    /// Driver angle of the event (radians).
    pub phi: f64,
    /// Driven angle at the event, before any release (radians).
    pub theta: f64,
    /// What happened.
    pub kind: EventKind,
    /// Unwrapped driver tooth of the contact that closed (lock, strike) or was lost (gap, slip).
    pub driver_tooth: i64,
    /// Unwrapped driven tooth of that contact.
    pub driven_tooth: i64,
    /// Driven angle to which the gear was released after a lock or strike (equal to `theta`
    /// otherwise): the push model lets it go to the next free position, as the paper's program
    /// let the driven gear "rotate freely ... until movement was possible again".
    pub theta_after: f64,
    /// Lost motion: driver angle from the event until a driver tooth drives the driven gear
    /// again, in driver pitches (to the end of the run if drive never resumed).
    pub lost_motion: f64,
    /// Whether drive resumed before the end of the run.
    pub resumed: bool,
    /// The tooth pair (driver, driven; unwrapped) that drove the driven gear again, if known.
    pub resumed_by: Option<(i64, i64)>,
    /// Change of the tooth phase (driver tooth + driven tooth of the driving pair, constant while
    /// the gears run in step) from the drive before the event to the drive after it: 0 in step,
    /// ±1 for a tooth lost or gained. 0 when either drive is unknown.
    pub phase_shift: i64,
    /// Lag left: how far the driven gear fell behind the ideal ratio between the event and the
    /// resumed drive, `(N1/N2)·Δφ − Δθ` (radians of driven angle; negative if a release carried it
    /// ahead).
    pub lag: f64,
    /// At a lock or strike, the angle (radians, 0 to π/2) between the line of action at the
    /// closing contact (its common normal) and the line from the contact point to the driven
    /// gear's rotation centre: a force along the normal passes this close to the driven arbor.
    /// None for the other kinds, and where the normal is not defined (tip on tip).
    pub wedge_angle: Option<f64>,
    /// A slip that is the run's idle start: no driver tooth moved the driven gear within a
    /// driver pitch of the start, or at all in the run. `phi` and `theta` are the start's, the
    /// teeth those of the nearest pair behind the driven gear there ((0, 0) when nothing was
    /// behind), and `lost_motion` runs from the start to the first push that moves it.
    pub idle_start: bool,
}

impl Event {
    /// The event's name for a reader: its kind's ([`EventKind::name`]), or `idle start` for the
    /// slip of a driven gear not pushed from the start of the run.
    pub fn label(&self) -> &'static str {
        if self.idle_start && self.kind == EventKind::Slip {
            "idle start"
        } else {
            self.kind.name()
        }
    }

    /// An event of `kind` at (φ, θ) on tooth pair `pair`, with no size yet.
    fn new(kind: EventKind, phi: f64, theta: f64, pair: (i64, i64)) -> Self {
        Self {
            phi,
            theta,
            kind,
            driver_tooth: pair.0,
            driven_tooth: pair.1,
            theta_after: theta,
            lost_motion: 0.0,
            resumed: false,
            resumed_by: None,
            phase_shift: 0,
            lag: 0.0,
            wedge_angle: None,
            idle_start: false,
        }
    }
}

/// How the driven gear moves over one segment of driver angle.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// Standing still.
    Rest,
    /// Pushed: θ is the largest upper end of these (driver tooth, driven tooth) obstacles.
    Push(Vec<(i64, i64)>),
    /// Jammed with no free position nearby: the driven gear is held where it is.
    Held,
}

/// A stretch of driver angle over which the driven angle follows one closed-form rule.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// First driver angle.
    pub phi_start: f64,
    /// Last driver angle.
    pub phi_end: f64,
    /// Driven angle at `phi_start`.
    pub theta_start: f64,
    /// Driven angle at `phi_end`.
    pub theta_end: f64,
    /// The rule.
    pub motion: Motion,
}

/// Which events end a run early ([`Mesh::run_until`]).
pub type StopAt<'a> = dyn Fn(&Event) -> bool + 'a;

/// Whether the events of a run so far, every one of them sized, answer the caller's question
/// for good (see [`Mesh::run_events_until_answered`]).
pub type Answered<'a> = dyn Fn(&[Event]) -> bool + 'a;

/// When a run may end before its last driver angle.
#[derive(Clone, Copy)]
enum Stop<'s, 'a> {
    /// Never: the run goes to its end.
    Never,
    /// At the first event for which this holds, as it is recorded.
    AtEvent(&'s StopAt<'a>),
    /// Once this holds for the events so far, none of them waiting to be sized.
    Answered(&'s Answered<'a>),
}

impl<'s, 'a> From<Option<&'s StopAt<'a>>> for Stop<'s, 'a> {
    fn from(stop: Option<&'s StopAt<'a>>) -> Self {
        stop.map_or(Self::Never, Self::AtEvent)
    }
}

/// How the driven gear starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Start {
    /// Put the driven gear at this angle; if that overlaps, it is pushed clear first.
    At(f64),
    /// Start touching the driver: from the given guess, pushed clear if it overlaps, otherwise
    /// turned back until a driven tooth rests against a driver tooth (the paper's initial contact).
    Touching(f64),
}

/// The exact run of one mesh over a range of driver angle.
#[derive(Debug, Clone)]
pub struct Trajectory {
    mesh: Mesh,
    segments: Vec<Segment>,
    events: Vec<Event>,
}

impl Trajectory {
    /// Driven angle at driver angle φ (clamped to the simulated range), exact.
    pub fn theta_at(&self, phi: f64) -> f64 {
        let i = self
            .segments
            .partition_point(|s| s.phi_end < phi)
            .min(self.segments.len() - 1);
        let s = &self.segments[i];
        match &s.motion {
            Motion::Rest | Motion::Held => s.theta_start,
            Motion::Push(pairs) => {
                if phi <= s.phi_start {
                    return s.theta_start;
                }
                if phi >= s.phi_end {
                    return s.theta_end;
                }
                pairs
                    .iter()
                    .filter_map(|&(j, k)| self.mesh.obstacle_end(phi, j, k, End::Upper))
                    .fold(s.theta_start, f64::max)
            }
        }
    }

    /// The segments, in order of driver angle.
    pub fn segments(&self) -> &[Segment] {
        &self.segments
    }

    /// Every jam and disengagement, in order.
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// First simulated driver angle.
    pub fn phi_start(&self) -> f64 {
        self.segments[0].phi_start
    }

    /// Last simulated driver angle.
    pub fn phi_end(&self) -> f64 {
        self.segments[self.segments.len() - 1].phi_end
    }

    /// The mesh this run belongs to.
    pub fn mesh(&self) -> &Mesh {
        &self.mesh
    }

    /// Number of jams in the `strict` reading: locks, strikes and a blocked start.
    pub fn jams(&self) -> usize {
        self.events
            .iter()
            .filter(|e| e.kind.is_contact_stop())
            .count()
    }

    /// Number of disengagements in the `strict` reading: gaps and slips.
    pub fn disengagements(&self) -> usize {
        self.events.iter().filter(|e| e.kind.is_loss()).count()
    }

    /// Whether no driver tooth pushed the driven gear anywhere in the run (an idle start that
    /// never ended): it stood still throughout, so statistics of its motion describe nothing.
    pub fn never_driven(&self) -> bool {
        self.events.iter().any(|e| e.idle_start && !e.resumed)
    }

    /// Number of events of one kind.
    pub fn count(&self, kind: EventKind) -> usize {
        self.events.iter().filter(|e| e.kind == kind).count()
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Side {
    Behind,
    Ahead,
}

/// A tooth pair whose obstacle is near θ.
#[derive(Debug, Clone, Copy)]
struct Tracked {
    pair: (i64, i64),
    side: Side,
    /// Upper end of the obstacle at the current driver angle.
    hi: f64,
}

/// How a run is solved.
#[derive(Debug, Clone, Copy)]
struct Solve {
    /// The bracketing step is this fraction of the driver's pitch.
    steps_per_pitch: f64,
    /// Keep every segment (for θ at any φ) or only the events.
    keep_segments: bool,
    /// Take steps on certificates where they are found, check a held gear's last cover first,
    /// and locate jams by replayed bisection (else bracket every step, scan the turn at every
    /// check and bisect throughout: the plain solver the differential tests compare against).
    certify: bool,
}

impl Default for Solve {
    fn default() -> Self {
        Self {
            steps_per_pitch: STEPS_PER_PITCH,
            keep_segments: true,
            certify: true,
        }
    }
}

/// A tooth pair judged over a certified step.
#[derive(Debug, Clone, Copy)]
struct Judged {
    pair: (i64, i64),
    /// Upper end of its obstacle at the step's end (−∞ if gone, or not needed).
    hi: f64,
    /// Whether its contacts in the box rise (else they fall).
    rising: bool,
}

impl Judged {
    /// A pair behind the driven gear that does not carry it at the step's end.
    fn not_carrying(pair: (i64, i64)) -> Self {
        Self {
            pair,
            hi: f64::NEG_INFINITY,
            rising: false,
        }
    }
}

/// A tooth pair touching a certified step's box, and its role there.
type Boxed = ((i64, i64), Role);

/// The pairs touching a certified step's box (a dozen or so), kept inline.
type BoxedPairs = SmallVec<[Boxed; 16]>;

/// A tooth pair and the upper end of its obstacle at a step's end, if any.
type Evaluated = ((i64, i64), Option<f64>);

/// A few tooth pairs (pushers, pairs born or gone in a step): kept inline, as every step of a
/// run makes several such lists and a heap allocation costs as much as the rest of the list's use.
type Pairs = SmallVec<[(i64, i64); 4]>;

/// What a tooth pair touching a certified step's box may do there.
#[derive(Debug, Clone, Copy)]
enum Role {
    /// Behind the driven gear, its contact curves rising: it may push. `born`: not there at
    /// the step's start; `slopes`: the range of its contact curves' slopes dθ/dφ in the box.
    Rising { born: bool, slopes: (f64, f64) },
    /// Behind the driven gear, its contact curves falling: it never reaches it.
    Falling,
    /// Anything else: it must stay clear of the driven gear's path. `ahead`: an untracked pair
    /// whose contacts rise, found ahead of the driven gear (or gone) at the step's start.
    Suspect { ahead: bool },
}

/// The verdicts of a certified step: the pairs evaluated at its end, and which of them are born
/// or gone within it.
#[derive(Debug, Default)]
struct JudgedStep {
    pairs: SmallVec<[Judged; 8]>,
    /// Rising pairs not there at the step's start and there at its end.
    newborn: Pairs,
    /// Rising pairs there at the step's start and gone at its end.
    dead: Pairs,
    /// The driven angle at the step's end.
    theta1: f64,
    /// The range of slopes of the carriers' contact curves (the driven gear's path).
    slopes: (f64, f64),
    /// Untracked pairs found ahead at the step's start and proved clear of the path: ahead of
    /// the driven gear (or gone) at its end.
    clear_ahead: Pairs,
}

/// One end of an evaluated tooth pair's obstacle: (driver angle, (driver tooth, driven tooth),
/// which end, where it is).
type Memo = (f64, (i64, i64), End, Option<f64>);

/// Working state of one run.
struct Run<'m> {
    mesh: &'m Mesh,
    phi: f64,
    theta: f64,
    held: bool,
    /// While the driven gear is held: the tooth pairs of the chain that the last step proved to
    /// hold it through its end (`held.rs`), where the next step starts; empty if none.
    held_links: Vec<(i64, i64)>,
    /// Driver angle of the last jam check that found nothing holding the driven gear.
    unheld_at: Option<f64>,
    /// Known tooth pairs, their side of θ and their upper end at the current φ.
    sides: Vec<Tracked>,
    /// The segments so far; only the last one when they are not kept.
    segments: Vec<Segment>,
    /// Whether to keep every segment (for θ at any φ) or only the events.
    keep_segments: bool,
    events: Vec<Event>,
    scratch: Vec<Obstacle>,
    /// The driven teeth a certified step's box has placed, by index in its range: kept here
    /// and reused, as a fresh list of these 200-byte placements per step cost more to move
    /// about than to fill.
    placed: RefCell<Vec<Option<PlacedTooth<'m>>>>,
    /// Tooth phase (driver tooth + driven tooth) of the last known driving pair.
    drive_phase: Option<i64>,
    /// Events whose size waits for the drive to resume: (index in `events`, phase before).
    pending: Vec<(usize, Option<i64>)>,
    /// Whether steps may be taken on a certificate instead of bracketing (straight flanks), and
    /// jams located by replayed bisection (`bisect_sign`) instead of plain bisection.
    certify: bool,
    /// Untracked tooth pairs known to be ahead of the driven gear, or gone, at (φ, θ): the
    /// suspects the last certified step ending there proved clear of its path, so the next
    /// step need not evaluate them to find where they start.
    clear_ahead: (f64, f64, Pairs),
    /// The idle-start candidate (its index in `events`) while no driver tooth has moved the
    /// driven gear yet: see [`Run::record_idle_start`].
    idle_since: Option<usize>,
    /// Whether an idle-start candidate was dropped since the last [`Run::stops`]: the driven
    /// gear moved within a driver pitch of the start.
    dropped_idle_start: bool,
}

impl Mesh {
    /// Runs the push model from driver angle `phi_start` to `phi_end` (radians, `phi_end >=
    /// phi_start`).
    pub fn run(&self, phi_start: f64, phi_end: f64, start: Start) -> Trajectory {
        self.run_until(phi_start, phi_end, start, None)
    }

    /// Like [`Mesh::run`], but the run ends at the first event for which `stop` holds (a jammed
    /// train stops; which events jam is an event rule's call): the trajectory then ends there and
    /// holds its last angle beyond. `stop` sees an event as it is recorded, before a later drive
    /// sizes it (its kind is final except that a gap may still become a slip).
    pub fn run_until(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        stop: Option<&StopAt<'_>>,
    ) -> Trajectory {
        let run = self.solve(phi_start, phi_end, start, stop.into(), Solve::default());
        Trajectory {
            mesh: self.clone(),
            segments: run.segments,
            events: run.events,
        }
    }

    /// [`Mesh::run_until`] with the bracketing step set to `1 / steps_per_pitch` of the driver's
    /// pitch, and, with `certify` unset, the plain solver: every step bracketed, every check of a
    /// held gear a scan of the turn. The result must depend on neither (events are located
    /// exactly either way); the differential tests run them against each other.
    #[doc(hidden)]
    pub fn run_with_steps(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        stop_at_jam: bool,
        steps_per_pitch: f64,
        certify: bool,
    ) -> Trajectory {
        let contact_stop = |e: &Event| e.kind.is_contact_stop();
        let stop: Option<&StopAt<'_>> = if stop_at_jam {
            Some(&contact_stop)
        } else {
            None
        };
        let how = Solve {
            steps_per_pitch,
            certify,
            ..Solve::default()
        };
        let run = self.solve(phi_start, phi_end, start, stop.into(), how);
        Trajectory {
            mesh: self.clone(),
            segments: run.segments,
            events: run.events,
        }
    }

    /// The jams and disengagements of [`Mesh::run`] over the same range, without its segments:
    /// all that jam statistics need, in memory that does not grow with the range.
    pub fn run_events(&self, phi_start: f64, phi_end: f64, start: Start) -> Vec<Event> {
        self.events_only(phi_start, phi_end, start, Stop::Never)
    }

    /// [`Mesh::run_events`] that ends at the first event for which `stop` holds (checked from
    /// the start on, so a blocked start ends the run at once): the events up to and including
    /// it are those of the whole run. For a caller that needs only whether some event occurs.
    pub fn run_events_until(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        stop: &StopAt<'_>,
    ) -> Vec<Event> {
        self.events_only(phi_start, phi_end, start, Stop::AtEvent(stop))
    }

    /// [`Mesh::run_events`] that ends as soon as `answered` holds for the events so far, asked
    /// each time new events are sized and none waits to be (the drive has resumed after each),
    /// so that it sees every event as the whole run records it. For a caller whose answer, once
    /// found, more events cannot change (has each rule seen a jam and a disengagement?): the
    /// events returned are then the whole run's up to the cut, and the answer is the whole run's.
    pub fn run_events_until_answered(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        answered: &Answered<'_>,
    ) -> Vec<Event> {
        self.events_only(phi_start, phi_end, start, Stop::Answered(answered))
    }

    /// The events of a run that keeps no segments (cheaper), ending at `stop` if given.
    fn events_only(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        stop: Stop<'_, '_>,
    ) -> Vec<Event> {
        let how = Solve {
            keep_segments: false,
            ..Solve::default()
        };
        self.solve(phi_start, phi_end, start, stop, how).events
    }

    fn solve(
        &self,
        phi_start: f64,
        phi_end: f64,
        start: Start,
        stop: Stop<'_, '_>,
        how: Solve,
    ) -> Run<'_> {
        let mut run = Run {
            mesh: self,
            phi: phi_start,
            theta: 0.0,
            held: false,
            held_links: Vec::new(),
            unheld_at: None,
            sides: Vec::new(),
            segments: Vec::new(),
            keep_segments: how.keep_segments,
            events: Vec::new(),
            scratch: Vec::new(),
            placed: RefCell::new(Vec::new()),
            drive_phase: None,
            pending: Vec::new(),
            certify: how.certify && !self.curved,
            clear_ahead: (f64::NAN, f64::NAN, Pairs::new()),
            idle_since: None,
            dropped_idle_start: false,
        };
        run.start(start);
        let mut seen = 0;
        let step =
            self.driver.max_gap.min(TAU / self.driver.tips.len() as f64) / how.steps_per_pitch;
        // A run that keeps no trajectory may end at a stopping event of the start itself (a
        // blocked start); one that keeps it takes its first step first, as it always has.
        let stopped_at_start = !how.keep_segments && run.stops(stop, &mut seen);
        while run.phi < phi_end && !stopped_at_start {
            // No sliver of a step at the end: it would only gather rounding noise.
            let next = if run.phi + step * (1.0 + 1e-6) >= phi_end {
                phi_end
            } else {
                run.phi + step
            };
            run.advance(next);
            if run.stops(stop, &mut seen) {
                break;
            }
        }
        if run.segments.is_empty() {
            run.rest_to(phi_end);
        }
        run.close_pending();
        run
    }

    /// Where two vertices of tooth pair (j, k) first meet (or, with `last`, meet last) while the
    /// driver turns from `phi0` to `phi1` (`certify::vertex_meeting`; straight flanks).
    pub(crate) fn vertex_meeting(
        &self,
        (j, k): (i64, i64),
        phi0: f64,
        phi1: f64,
        last: bool,
    ) -> Option<(f64, f64)> {
        vertex_meeting(
            self.driver.cert(j),
            self.driven.cert(k),
            phi0,
            phi1,
            self.centre_distance,
            last,
        )
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
    fn hi(&self, phi: f64, pair: (i64, i64)) -> f64 {
        self.obstacle_end(phi, pair.0, pair.1, End::Upper)
            .unwrap_or(f64::NEG_INFINITY)
    }

    /// The nearest driven angle ≥ θ that overlaps no driver tooth at φ, or None if the obstacles
    /// close up over more than a turn of the driven gear. An obstacle that only touches θ from
    /// behind does not move it; one that touches it from ahead does when `through` is set (the
    /// release after a jam: the driven gear is let go to the next position where it is free).
    pub fn next_free(&self, phi: f64, theta: f64, through: bool) -> Option<f64> {
        self.free_or_cover(phi, theta, through).ok()
    }

    /// [`Mesh::next_free`], but where there is no free position, the tooth pairs whose
    /// obstacles, one after another, close up over the turn: the proof of being blocked.
    fn free_or_cover(&self, phi: f64, theta: f64, through: bool) -> Result<f64, Vec<(i64, i64)>> {
        self.free_or_cover_with(phi, theta, through, None)
    }

    /// [`Mesh::free_or_cover`], and where there is no free position, the obstacles of the
    /// returned cover at φ into `links` (in the order the sweep took them), if given.
    fn free_or_cover_with(
        &self,
        phi: f64,
        theta: f64,
        through: bool,
        links: Option<&mut Vec<Obstacle>>,
    ) -> Result<f64, Vec<(i64, i64)>> {
        self.free_or_cover_in(phi, theta, through, links, &mut PairMemo::new(self, phi))
    }

    /// [`Mesh::free_or_cover_with`], taking the pairs already evaluated at φ from `memo` (a memo
    /// at φ) and leaving there those it evaluates.
    fn free_or_cover_in(
        &self,
        phi: f64,
        theta: f64,
        through: bool,
        links: Option<&mut Vec<Obstacle>>,
        memo: &mut PairMemo,
    ) -> Result<f64, Vec<(i64, i64)>> {
        let gap = self.driven.max_gap;
        let (mut obs, mut more) = (Vec::new(), Vec::new());
        let mut reach = 3.0 * gap;
        // The widening windows pass the same teeth again a turn on: each pair is evaluated once.
        self.obstacles_with(phi, theta - gap, theta + reach, &mut obs, Some(&mut *memo));
        loop {
            let (top, chain) = cover_from(theta, &mut obs, through);
            if top < theta + reach - gap {
                return Ok(top);
            }
            if reach > TAU + 3.0 * gap {
                if let Some(links) = links {
                    chain_links(theta, &obs, through, links);
                }
                return Err(chain);
            }
            // Widen the search by what lies beyond its reach: those that straddle it come twice,
            // which changes nothing in the sweep (a copy never reaches past the top its first
            // left).
            self.obstacles_with(
                phi,
                theta + reach,
                theta + 2.0 * reach,
                &mut more,
                Some(&mut *memo),
            );
            obs.append(&mut more);
            reach *= 2.0;
        }
    }

    /// How far above θ the obstacles must close up for the driven gear at θ to have no free
    /// position: the top of the widest search of [`Mesh::free_or_cover`] (which gives up there),
    /// less a driven gap.
    fn held_threshold(&self, theta: f64) -> f64 {
        let gap = self.driven.max_gap;
        let mut reach = 3.0 * gap;
        while reach <= TAU + 3.0 * gap {
            reach *= 2.0;
        }
        theta + reach - gap
    }
}

/// How far above θ the obstacles close up, swept in order of their lower ends (those that
/// extend the cover are kept, in order): an obstacle that only touches θ from behind does not
/// start it; one that touches it from ahead does when `through` is set.
fn cover_from(theta: f64, obs: &mut [Obstacle], through: bool) -> (f64, Vec<(i64, i64)>) {
    obs.sort_by(|a, b| a.lo.total_cmp(&b.lo));
    let mut chain = Vec::new();
    let top = sweep(theta, obs, through, |o| {
        chain.push((o.driver_tooth, o.driven_tooth));
    });
    (top, chain)
}

/// The obstacles [`cover_from`] took into its cover (those that lifted the top), in order, into
/// `links`, from `obs` as it left them (sorted).
fn chain_links(theta: f64, obs: &[Obstacle], through: bool, links: &mut Vec<Obstacle>) {
    links.clear();
    sweep(theta, obs, through, |o| links.push(*o));
}

/// [`cover_from`]'s sweep over obstacles sorted by their lower ends: the top reached, each
/// obstacle that lifted it passed to `take`.
fn sweep(theta: f64, obs: &[Obstacle], through: bool, mut take: impl FnMut(&Obstacle)) -> f64 {
    let mut top = theta;
    for o in obs {
        let carried = through || top > theta;
        let reaches = if carried {
            o.lo <= top + SIDE_TOL
        } else {
            o.lo < top - SIDE_TOL
        };
        if reaches && o.hi > top {
            top = o.hi;
            take(o);
        }
    }
    top
}

impl Run<'_> {
    /// Whether the run ends here by `stop`, given that the events before `seen` were asked
    /// about already (`seen` is moved past those asked about now).
    fn stops(&mut self, stop: Stop<'_, '_>, seen: &mut usize) -> bool {
        match stop {
            Stop::Never => false,
            Stop::AtEvent(stop) => {
                // An idle-start candidate, asked about as it was recorded (first of all events),
                // has gone since: the rest moved down by one.
                if std::mem::take(&mut self.dropped_idle_start) {
                    *seen = seen.saturating_sub(1);
                }
                let stops = self.events[*seen..].iter().any(stop);
                *seen = self.events.len();
                stops
            }
            // Only where every event is sized: a gap waiting for the drive may yet become a
            // slip, and its lost motion and phase shift are not known.
            Stop::Answered(answered) => {
                let waiting = !self.pending.is_empty() || self.idle_since.is_some();
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
                self.held = true;
                self.held_links.clear();
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
        self.drive_phase = self
            .touching_behind(phi, self.theta, None, &mut memo)
            .map(|p| p.0 + p.1);
        if !self.held {
            self.record_idle_start();
        }
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
        self.idle_since = Some(self.events.len());
        self.events.push(e);
    }

    /// A driver tooth (of `pairs`) moves the driven gear for the first time, at the current
    /// (φ, θ): the idle-start candidate is sized, and dropped if this came within a driver pitch.
    fn first_lift(&mut self, pairs: &[(i64, i64)]) {
        let Some(i) = self.idle_since.take() else {
            return;
        };
        let (phi, theta) = (self.phi, self.theta);
        self.events[i].resumed_by = self.mesh.top_pair(phi, pairs);
        self.size_event(i, phi, theta, true, 0);
        if self.events[i].kind == EventKind::Gap {
            self.events.remove(i);
            for (j, _) in &mut self.pending {
                if *j > i {
                    *j -= 1;
                }
            }
            self.dropped_idle_start = true;
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
            self.pending.push((self.events.len(), phase_before));
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
        for (i, before) in std::mem::take(&mut self.pending) {
            let shift = match (before, phase) {
                (Some(b), Some(a)) => a - b,
                _ => 0,
            };
            self.events[i].resumed_by = by;
            self.size_event(i, phi, theta, true, shift);
        }
        if phase.is_some() {
            self.drive_phase = phase;
        }
    }

    /// Events still waiting at the end of the run: drive never resumed.
    fn close_pending(&mut self) {
        let (phi, theta) = (self.phi, self.theta);
        for (i, _) in std::mem::take(&mut self.pending) {
            self.size_event(i, phi, theta, false, 0);
        }
        if let Some(i) = self.idle_since.take() {
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
        self.sides
            .iter()
            .filter(|t| t.side == Side::Behind && (t.hi - self.theta).abs() <= SIDE_TOL)
            .map(|t| t.pair)
            .collect()
    }

    /// Whether the last certified step proved `pair` ahead of the driven gear (or gone) at the
    /// current (φ, θ).
    fn known_clear_ahead(&self, pair: (i64, i64)) -> bool {
        let (phi, theta, pairs) = &self.clear_ahead;
        *phi == self.phi && *theta == self.theta && pairs.contains(&pair)
    }

    fn side_of(&self, pair: (i64, i64)) -> Option<Side> {
        self.sides.iter().find(|t| t.pair == pair).map(|t| t.side)
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
            && !self.pending.is_empty()
        {
            self.resume_drive(pairs);
        }
        if let Motion::Push(pairs) = &motion
            && theta_end > self.theta
            && self.idle_since.is_some()
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

    /// An empty list for the pairs of the next segment: the last segment's own when only the last
    /// is kept (it is about to be replaced), so that a step allocates nothing for it.
    fn spare_pairs(&mut self) -> Vec<(i64, i64)> {
        match self.segments.last_mut() {
            Some(Segment {
                motion: Motion::Push(pairs),
                ..
            }) if !self.keep_segments => {
                let mut spare = std::mem::take(pairs);
                spare.clear();
                spare
            }
            _ => Vec::new(),
        }
    }

    fn rest_to(&mut self, phi_end: f64) {
        let motion = if self.held {
            Motion::Held
        } else {
            Motion::Rest
        };
        self.push_segment(phi_end, self.theta, motion);
    }

    /// Takes the step to `phi1` on a certificate, if one is found, and returns whether it did
    /// (having changed nothing if not). The certificate (`certify.rs` has the bounds):
    ///
    /// - Over the **box** of the step's driver angles and the driven angles from θ0 (less the
    ///   side tolerance) to θ1, every tooth pair near the driven gear either touches nowhere, or
    ///   is behind it with contact curves that only rise (it may push) or only fall; any other
    ///   pair is a *suspect*.
    /// - The driven angle, the running maximum of the rising curves, one of which (a pusher)
    ///   starts at θ0, then rises throughout (no gap): its **path** from (φ0, θ0) to (φ1, θ1)
    ///   lies in a thin tube about the chord, as wide as the spread of the slopes of the curves
    ///   it follows. Every suspect must stay clear of that tube (nothing ahead meets the driven
    ///   gear: no lock, no strike), and a rising pair that stays clear of it never carries the
    ///   gear and needs no evaluating.
    /// - Only the **carriers** bound the tube: the pushers, every pair behind whose contacts rise
    ///   and which ends the step above them (it has taken the gear over: known from the start),
    ///   and every rising pair found to reach the tube (each widens it by its own slopes, and
    ///   then every pair is judged again). This is
    ///   sound: the running maximum P of the carriers' curves has their slopes, so lies in their
    ///   tube; a rising pair that stays clear of that tube never meets P, and, starting below
    ///   it, stays below; so P is the driven gear's path. Unrelated rising pairs (an incoming
    ///   tooth's tip, a pair long past) no longer widen the tube: on m3-e3 the pushers' slopes
    ///   span 0.08-0.15 where every rising pair in the box spans 0.03-0.41.
    /// - θ1 is the largest upper end at φ1 of the rising pairs that reach the tube. A rising pair
    ///   cannot pass above θ1 and come back within the step (it would fall through the box), nor
    ///   vanish above it; one found higher at φ1 moves θ1 (and, past the box, widens it).
    /// - Pairs born or gone within the step meet the conditions of `births_and_deaths_hold`.
    ///
    /// Then no event lies in the step, and it ends at θ1, exactly as bracketing would end it.
    // One copy of this large step for its three callers (a whole step and two halves): inlined
    // into each it made the program's resident code larger than before the halves.
    #[inline(never)]
    fn certified_step(&mut self, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        let Some(mut judged) = self.judge_step(phi1, pushers) else {
            return false;
        };
        // Every pusher is among the rising pairs (`judge_step` refuses a box where one is not):
        // one that fell would leave the driven gear.
        debug_assert!(
            pushers
                .iter()
                .all(|p| judged.pairs.iter().any(|m| m.pair == *p && m.rising)),
            "a pusher not judged rising"
        );
        if !self.births_and_deaths_hold(&judged, phi1) {
            return false;
        }
        self.clear_ahead = (phi1, judged.theta1, std::mem::take(&mut judged.clear_ahead));
        let mut rising = self.spare_pairs();
        rising.extend(judged.pairs.iter().filter(|m| m.rising).map(|m| m.pair));
        self.push_segment(phi1, judged.theta1, Motion::Push(rising));
        // Pairs whose driver tooth has left the window (teeth enter it at lower indices as the
        // driver turns, and leave it at higher ones) are done with.
        let last = *self.mesh.driver_teeth(phi1).end();
        self.sides.retain(|t| t.pair.0 <= last);
        // Sides stay (nothing crossed θ). Upper ends at φ1 are known for the evaluated pairs; a
        // pair behind that was not evaluated stayed clear of the path, so it is no pusher at φ1.
        for t in &mut self.sides {
            match judged.pairs.iter().find(|m| m.pair == t.pair) {
                Some(m) => t.hi = m.hi,
                None if t.side == Side::Behind => t.hi = f64::NEG_INFINITY,
                None => {}
            }
        }
        for m in &judged.pairs {
            if self.side_of(m.pair).is_none() {
                self.sides.push(Tracked {
                    pair: m.pair,
                    side: Side::Behind,
                    hi: m.hi,
                });
            }
        }
        true
    }

    /// Takes the step to `phi1` as two certified half steps when the whole step has no
    /// certificate (a thinner box and a thinner tube about the driven gear's path prove more), and
    /// returns whether it did. Only both halves together count: if the second finds none, the
    /// first is undone and the whole step is bracketed as before, over the same driver angles, so
    /// that no event is located differently. (Not tried while an event waits for the drive to
    /// resume and size it: a certified push would size it, and that is not undone.)
    fn certified_halves(&mut self, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        if !self.pending.is_empty() {
            return false;
        }
        let mid = 0.5 * (self.phi + phi1);
        let (phi0, theta0) = (self.phi, self.theta);
        let sides: SmallVec<[Tracked; 16]> = SmallVec::from_slice(&self.sides);
        let clear_ahead = self.clear_ahead.clone();
        let segments = self.segments.len();
        // A run that keeps no trajectory keeps only its last segment, which a step replaces: it
        // is set aside (not copied) until the halves are known to stand.
        let last = if self.keep_segments {
            None
        } else {
            self.segments.pop()
        };
        if !self.certified_step(mid, pushers) {
            self.segments.extend(last);
            return false;
        }
        let pushers = self.pushers();
        if !pushers.is_empty() && self.certified_step(phi1, &pushers) {
            return true;
        }
        (self.phi, self.theta) = (phi0, theta0);
        self.sides.clear();
        self.sides.extend_from_slice(&sides);
        self.clear_ahead = clear_ahead;
        if self.keep_segments {
            self.segments.truncate(segments);
        } else {
            self.segments.clear();
            self.segments.extend(last);
        }
        false
    }

    /// The verdicts of a certified step to `phi1` (see [`Run::certified_step`]), or None when a
    /// pair may meet the driven gear other than by pushing it.
    fn judge_step(&self, phi1: f64, pushers: &[(i64, i64)]) -> Option<JudgedStep> {
        let mesh = self.mesh;
        let (phi0, theta0) = (self.phi, self.theta);
        // Each pair is evaluated at φ1 once, however often the box grows or θ1 moves; only the
        // upper ends are asked for (where the pairs behind end).
        let mut at1: SmallVec<[Evaluated; 8]> = SmallVec::new();
        let mut end_of = |pair: (i64, i64)| -> Option<f64> {
            if let Some(&(_, o)) = at1.iter().find(|e| e.0 == pair) {
                return o;
            }
            let o = mesh.obstacle_end(phi1, pair.0, pair.1, End::Upper);
            at1.push((pair, o));
            o
        };
        let pushed = pushers
            .iter()
            .filter_map(|&p| end_of(p))
            .fold(theta0, f64::max);
        let mut theta1 = pushed;
        // A pair behind the driven gear that ends the step above the pushers has taken it over
        // within the step: it is a carrier from the start, so that the first box is tall enough
        // and the path's tube wide enough (else the box grows, and every pair is judged again,
        // once it is found). Only pairs near enough to overtake are evaluated: within twice the
        // pushers' rise below θ0.
        let mut overtakers: Pairs = SmallVec::new();
        for t in &self.sides {
            if t.side == Side::Behind
                && !pushers.contains(&t.pair)
                && t.hi > theta0 - 2.0 * (pushed - theta0)
                && let Some(hi) = end_of(t.pair)
                && hi > pushed
            {
                theta1 = theta1.max(hi);
                overtakers.push(t.pair);
            }
        }
        'grow: for grown in 0..4 {
            // The first box reaches a little above where the pushers end: the next pusher, taking
            // over within the step, often ends higher, and a box found too low is judged again.
            let top = if grown == 0 {
                theta1 + BOX_HEADROOM * (theta1 - theta0)
            } else {
                theta1
            };
            let cell = ConfigBox::new(phi0, phi1, theta0 - SIDE_TOL, top, mesh.centre_distance);
            let boxed = self.box_verdicts(&cell, phi1, top)?;
            // The path is bounded by the slopes of the pairs that may carry the driven gear:
            // the pushers, and each rising pair found to reach the path's tube (see above).
            let slopes_of = |carriers: &Pairs| {
                boxed
                    .iter()
                    .filter(|(pair, _)| carriers.contains(pair))
                    .fold(
                        (f64::INFINITY, f64::NEG_INFINITY),
                        |s, (_, role)| match role {
                            Role::Rising { slopes: r, .. } => (s.0.min(r.0), s.1.max(r.1)),
                            _ => s,
                        },
                    )
            };
            // A pusher whose contacts are not all rising cannot be followed: no certificate.
            if !pushers.iter().all(|p| {
                boxed
                    .iter()
                    .any(|(pair, role)| pair == p && matches!(role, Role::Rising { .. }))
            }) {
                return None;
            }
            let mut carriers: Pairs = SmallVec::from_slice(pushers);
            // An overtaker is a carrier where its contacts in the box rise (else it is judged
            // like any pair: a certificate needs them rising).
            for &o in &overtakers {
                if boxed
                    .iter()
                    .any(|(pair, role)| *pair == o && matches!(role, Role::Rising { .. }))
                {
                    carriers.push(o);
                }
            }
            // θ1 only rises, each time to a pair's upper end, and the carriers only grow: this
            // ends.
            'path: loop {
                let slopes = slopes_of(&carriers);
                let path = cell.with_driven(theta0, theta1);
                let clear = |(j, k): (i64, i64)| {
                    path.clear_along(
                        &path.place_driver(mesh.driver.cert(j)),
                        &path.place_driven(mesh.driven.cert(k)),
                        slopes,
                        SIDE_TOL,
                    )
                };
                let mut judged = JudgedStep {
                    theta1,
                    slopes,
                    ..JudgedStep::default()
                };
                for &(pair, role) in &boxed {
                    match role {
                        Role::Suspect { ahead } if clear(pair) => {
                            if ahead {
                                judged.clear_ahead.push(pair);
                            }
                        }
                        Role::Suspect { .. } => return None,
                        Role::Falling if pushed - theta0 > 2.0 * SIDE_TOL => {
                            // Falling from behind θ0: it never reaches θ, whatever becomes of
                            // it, and ends too far below θ1 to push at the next step.
                            judged.pairs.push(Judged::not_carrying(pair));
                        }
                        Role::Falling => judged.pairs.push(Judged {
                            pair,
                            hi: end_of(pair).unwrap_or(f64::NEG_INFINITY),
                            rising: false,
                        }),
                        // Never on the path: it carries nothing, wherever it ends. One that was
                        // behind at φ0 still is (tracked, as no pusher); one born in the step
                        // may be on either side of the driven gear (left untracked).
                        Role::Rising { born, .. } if !carriers.contains(&pair) && clear(pair) => {
                            if !born {
                                judged.pairs.push(Judged::not_carrying(pair));
                            }
                        }
                        Role::Rising { born, slopes: r } => {
                            // It reaches the tube: a carrier, whose slopes may widen the tube
                            // (and then every pair is judged again).
                            if !carriers.contains(&pair) {
                                carriers.push(pair);
                                if r.0 < slopes.0 || r.1 > slopes.1 {
                                    continue 'path;
                                }
                            }
                            match end_of(pair) {
                                Some(hi) if hi > theta1 => {
                                    theta1 = hi;
                                    if theta1 > top {
                                        continue 'grow;
                                    }
                                    continue 'path;
                                }
                                Some(hi) => {
                                    judged.pairs.push(Judged {
                                        pair,
                                        hi,
                                        rising: true,
                                    });
                                    if born {
                                        judged.newborn.push(pair);
                                    }
                                }
                                None if born => {
                                    // Neither at φ0 nor at φ1: a pair whose contacts only rise is
                                    // born and dies where two of its vertices meet; with no meeting
                                    // in the step it never touches.
                                    if mesh.vertex_meeting(pair, phi0, phi1, false).is_some() {
                                        return None;
                                    }
                                }
                                None => {
                                    judged.dead.push(pair);
                                    judged.pairs.push(Judged {
                                        pair,
                                        hi: f64::NEG_INFINITY,
                                        rising: true,
                                    });
                                }
                            }
                        }
                    }
                }
                return Some(judged);
            }
        }
        None
    }

    /// Every tooth pair that touches `cell`, the box of the step to `phi1` and driven angles
    /// from θ0 (less the side tolerance) to `top`, with its role (for a rising pair, with the range of
    /// slopes of its contact curves in the box); None when an untracked pair straddles the
    /// driven angle at the step's start.
    fn box_verdicts(&self, cell: &ConfigBox, phi1: f64, top: f64) -> Option<BoxedPairs> {
        let mesh = self.mesh;
        let (phi0, theta0) = (self.phi, self.theta);
        let (driver, driven) = (&mesh.driver, &mesh.driven);
        let bottom = theta0 - SIDE_TOL;
        let drivers = driver.teeth_between(-phi1 - driver.window, -phi0 + driver.window);
        let drivens = driven.teeth_between(bottom - driven.window, top + driven.window);
        // Each tooth is placed in the box once, and only if its disc comes near another's.
        let discs: SmallVec<[_; 16]> = drivens
            .clone()
            .map(|k| cell.driven_disc(driven.cert(k)))
            .collect();
        let mut placed = self.placed.borrow_mut();
        placed.clear();
        placed.resize(discs.len(), None);
        let mut boxed = SmallVec::new();
        for j in drivers {
            let disc = cell.driver_disc(driver.cert(j));
            let mut a = None;
            for (i, k) in drivens.clone().enumerate() {
                if cell.apart(disc, discs[i]) {
                    continue;
                }
                let a = a.get_or_insert_with(|| cell.place_driver(driver.cert(j)));
                let b = placed[i].get_or_insert_with(|| cell.place_driven(driven.cert(k)));
                let pair = (j, k);
                let (verdict, range) = cell.pair(a, b);
                let role = match (verdict, self.side_of(pair)) {
                    (Verdict::Clear, _) => continue,
                    (Verdict::Rising, Some(Side::Behind)) => Role::Rising {
                        born: false,
                        slopes: range,
                    },
                    (Verdict::Falling, Some(Side::Behind)) => Role::Falling,
                    // A pair not yet tracked whose contacts in the box only rise: behind if it is
                    // behind θ at φ0; if it is not there yet, it is born in the step, and where is
                    // judged by `births_and_deaths_hold`. It is classified (and then tracked)
                    // even when it stays clear of the path: left untracked, a later bracketed step
                    // would judge it as a pair new to the scan, which it is not. One already
                    // ahead at φ0 is an obstacle ahead like any other: it must stay clear of the
                    // path (untracked, as a bracketed step finds it ahead where it starts).
                    // One the last step proved ahead (or gone) here is taken as ahead: a
                    // suspect whatever it does, it must stay clear of the path.
                    (Verdict::Rising, None) if self.known_clear_ahead(pair) => {
                        Role::Suspect { ahead: true }
                    }
                    (Verdict::Rising, None) => match mesh.obstacle(phi0, j, k) {
                        None => Role::Rising {
                            born: true,
                            slopes: range,
                        },
                        Some(o) if o.hi <= theta0 + SIDE_TOL => Role::Rising {
                            born: false,
                            slopes: range,
                        },
                        Some(o) if o.lo >= theta0 - SIDE_TOL => Role::Suspect { ahead: true },
                        Some(_) => return None,
                    },
                    // Ahead of the driven gear, or not proved to rise or fall: it must stay
                    // clear of the driven gear's path.
                    _ => Role::Suspect { ahead: false },
                };
                boxed.push((pair, role));
            }
        }
        Some(boxed)
    }

    /// Whether the pairs born or gone in a judged step leave the drive continuous and nothing
    /// ahead: a pair whose contacts only rise is born, and dies, where two of its vertices meet
    /// (`certify::vertex_meeting`). A pair born above the driven gear would be an obstacle ahead;
    /// one that died while carrying it must hand it to another there.
    fn births_and_deaths_hold(&self, judged: &JudgedStep, phi1: f64) -> bool {
        let mesh = self.mesh;
        let (phi0, theta0) = (self.phi, self.theta);
        // The driven angle at φ without pair `except`: the largest upper end of the other rising
        // pairs, at least θ0.
        let others = |phi: f64, except: (i64, i64)| {
            judged
                .pairs
                .iter()
                .filter(|m| m.rising && m.pair != except)
                .map(|m| mesh.hi(phi, m.pair))
                .fold(theta0, f64::max)
        };
        let meeting = |pair: (i64, i64), last: bool| mesh.vertex_meeting(pair, phi0, phi1, last);

        // Where the driven gear is at least, by the path's tube (`ConfigBox::clear_along`): when
        // a pair is born below that, nothing need be evaluated.
        let (s_lo, s_hi) = judged.slopes;
        let chord = (judged.theta1 - theta0) / (phi1 - phi0);
        let width = (s_hi - s_lo).max(0.0) * (phi1 - phi0) / 4.0;
        let at_least = |phi: f64| (theta0 + chord * (phi - phi0) - width).max(theta0);
        // A pair that dies below where the driven gear is at least was not carrying it.
        let deaths_hand_over = judged.dead.iter().all(|&pair| {
            meeting(pair, true).is_some_and(|(phi_d, at)| {
                crate::mesh::wrap_pi(at - at_least(phi_d)) < -SIDE_TOL
                    || crate::mesh::wrap_pi(at - others(phi_d, pair)) <= SIDE_TOL
            })
        });
        let births_behind = judged.newborn.iter().all(|&pair| {
            meeting(pair, false).is_some_and(|(phi_b, at)| {
                crate::mesh::wrap_pi(at - at_least(phi_b)) <= SIDE_TOL
                    || crate::mesh::wrap_pi(at - others(phi_b, pair)) <= SIDE_TOL
            })
        });
        deaths_hand_over && births_behind
    }
    /// The driven gear is held at θ: it stays there until the driver angle where a free
    /// position first appears ahead of it, located exactly (`held.rs`: the first root at which
    /// the chain of obstacles that holds it may give way; there the turn is swept again, and the
    /// gear either let go to the free position or held by the new chain), or to `phi1`. A chain
    /// proved to hold through the step is taken up by the next one.
    fn held_step(&mut self, phi1: f64) {
        let mesh = self.mesh;
        let theta = self.theta;
        let threshold = mesh.held_threshold(theta);
        let past = |root: f64| (root + LOCATE_TOL * (1.0 + root.abs())).min(phi1);
        let mut phi = self.phi;
        let mut links = Vec::new();
        // The chain the last step proved to hold through its end: no scan of the turn needed.
        for (j, k) in std::mem::take(&mut self.held_links) {
            match mesh.obstacle(phi, j, k) {
                Some(o) => links.push(o),
                None => {
                    links.clear();
                    break;
                }
            }
        }
        loop {
            if links.is_empty() {
                let mut memo = PairMemo::new(mesh, phi);
                let found = mesh.free_or_cover_in(phi, theta, false, Some(&mut links), &mut memo);
                if let Ok(t) = found {
                    if phi > self.phi {
                        self.release(phi, t, &mut memo);
                        return;
                    }
                    // Free where the step starts: let go just after it.
                    let phi_r = (phi + LOCATE_TOL).min(phi1);
                    let mut memo = PairMemo::new(mesh, phi_r);
                    match mesh.free_or_cover_in(phi_r, theta, false, None, &mut memo) {
                        Ok(t) => self.release(phi_r, t, &mut memo),
                        Err(_) if phi_r < phi1 => {
                            phi = phi_r;
                            links.clear();
                            continue;
                        }
                        Err(_) => self.rest_to(phi1),
                    }
                    return;
                }
            }
            match held::first_change(mesh, &links, theta, threshold, SIDE_TOL, (phi, phi1)) {
                Some(root) if root < phi1 => {
                    phi = past(root);
                    links.clear();
                }
                found => {
                    if found.is_none() {
                        let m = links
                            .iter()
                            .position(|c| c.hi >= threshold)
                            .map_or(0, |i| i + 1);
                        self.held_links = links[..m]
                            .iter()
                            .map(|o| (o.driver_tooth, o.driven_tooth))
                            .collect();
                    }
                    self.rest_to(phi1);
                    return;
                }
            }
        }
    }

    /// The held gear let go at φ to the free position θ = `to`.
    fn release(&mut self, phi: f64, to: f64, memo: &mut PairMemo) {
        self.rest_to(phi);
        self.held = false;
        self.theta = to;
        self.classify_all(phi, memo);
    }

    /// Advance from `self.phi` to `phi1`, locating every event in between.
    fn advance(&mut self, mut phi1: f64) {
        let mesh = self.mesh;
        let phi0 = self.phi;
        let theta0 = self.theta;
        if self.held {
            self.held_step(phi1);
            return;
        }

        let pushers = self.pushers();
        if self.certify && !pushers.is_empty() && self.unheld_at != Some(phi0) {
            // The whole step on a certificate, or else bracketed.
            let e0 = crate::mesh::tooth_pair_evaluations();
            let certified =
                self.certified_step(phi1, &pushers) || self.certified_halves(phi1, &pushers);
            let spent = crate::mesh::tooth_pair_evaluations() - e0;
            count(|st| {
                if certified {
                    st.certified += 1;
                    st.certified_evaluations += spent;
                } else {
                    st.refused += 1;
                    st.refused_evaluations += spent;
                }
            });
            if certified {
                return;
            }
        }
        count(|st| st.bracketed += 1);
        // Standing still, the first touch of any driver tooth is found exactly; end the step just
        // after it, so that even a brief graze (a tip clipping a tip) is seen at the step's end.
        if pushers.is_empty()
            && let Some(t) = mesh.first_touch(theta0, phi0, phi1)
        {
            phi1 = phi1.min(t + TOUCH_STEP);
        }

        // Obstacles at the end of the step, with their values there cached.
        let gap = mesh.driven.max_gap;
        mesh.obstacles(
            phi1,
            theta0 - 0.4 * gap,
            theta0 + 0.6 * gap,
            &mut self.scratch,
        );
        let obs1 = std::mem::take(&mut self.scratch);
        let at1 = |pair: (i64, i64)| {
            obs1.iter()
                .find(|o| (o.driver_tooth, o.driven_tooth) == pair)
        };
        // The checks below ask for the same end of a pair at the same angle several times
        // (mid-step, just before the end): evaluate each once, and only the end asked for (the
        // upper end of a pair behind, the lower end of one ahead).
        let memo: RefCell<Vec<Memo>> = RefCell::new(Vec::new());
        let end_at = |p: f64, pair: (i64, i64), end: End| -> Option<f64> {
            if p == phi1 {
                return at1(pair).map(|o| match end {
                    End::Lower => o.lo,
                    End::Upper => o.hi,
                });
            }
            if let Some(&(.., o)) = memo
                .borrow()
                .iter()
                .find(|m| m.0 == p && m.1 == pair && m.2 == end)
            {
                return o;
            }
            let o = mesh.obstacle_end(p, pair.0, pair.1, end);
            let mut m = memo.borrow_mut();
            if m.len() >= 64 {
                m.clear();
            }
            m.push((p, pair, end, o));
            o
        };
        let hi = |p: f64, pair: (i64, i64)| -> f64 {
            end_at(p, pair, End::Upper).unwrap_or(f64::NEG_INFINITY)
        };
        let lo = |p: f64, pair: (i64, i64)| -> f64 {
            end_at(p, pair, End::Lower).unwrap_or(f64::INFINITY)
        };

        let mut behind: Vec<(i64, i64)> = pushers.to_vec();
        let mut ahead: Vec<(i64, i64)> = Vec::new();
        let mut unsure: Vec<Obstacle> = Vec::new();
        for o in &obs1 {
            let pair = (o.driver_tooth, o.driven_tooth);
            match self.side_of(pair) {
                Some(Side::Behind) => {
                    if !behind.contains(&pair) {
                        behind.push(pair);
                    }
                }
                Some(Side::Ahead) => ahead.push(pair),
                None if o.hi <= theta0 + SIDE_TOL => behind.push(pair),
                None => unsure.push(*o),
            }
        }
        // The pushers' upper envelope, and where it peaks in the step (a golden-section search,
        // made once: the side of a pair born in the step and the plan below both ask for it).
        let push_env = |p: f64| {
            pushers
                .iter()
                .map(|&b| hi(p, b))
                .fold(f64::NEG_INFINITY, f64::max)
        };
        let peak = std::cell::OnceCell::new();
        let push_peak = || {
            *peak.get_or_init(|| {
                let phi_pk = golden_max(phi0, phi1, push_env);
                let phi_pk = mesh.smooth_peak(phi_pk, (phi0, phi1), &pushers, push_env);
                (phi_pk, push_env(phi_pk))
            })
        };
        // A new obstacle not clearly behind: ahead if it lies above where the driven gear can get
        // to in this step, otherwise decide at the angle where it first appeared.
        for o in unsure {
            let pair = (o.driver_tooth, o.driven_tooth);
            let reach = behind.iter().map(|&p| hi(phi1, p)).fold(theta0, f64::max);
            // An obstacle that appeared below θ and rose past it within the step is behind (it
            // pushed), even though it lies above θ0 now: decide where it first appeared.
            let at_start = mesh.obstacle(phi0, pair.0, pair.1);
            let side = if o.lo >= reach + mesh.driven.max_gap {
                Side::Ahead
            } else if let Some(a0) = at_start.filter(|a0| a0.hi <= theta0 + SIDE_TOL) {
                // Already there at the start of the step, behind θ (it only came into the window
                // of the scan): obstacles do not pass through θ without a jam, so it is behind.
                let _ = a0;
                Side::Behind
            } else if at_start.is_some_and(|a0| a0.lo >= theta0 - SIDE_TOL) {
                // Already there and ahead at the start.
                Side::Ahead
            } else {
                // Where it appeared, closely enough to tell its side (not to LOCATE_TOL: the side
                // is all that is asked).
                let phi_a = bracket(phi0, phi1, SIDE_LOCATE_TOL, |p| {
                    mesh.obstacle(p, pair.0, pair.1).is_none()
                })
                .1;
                let at = mesh
                    .obstacle(phi_a, pair.0, pair.1)
                    .map_or(o.lo, |a| 0.5 * (a.lo + a.hi));
                let theta_a = behind
                    .iter()
                    .map(|&b| mesh.hi(phi_a, b))
                    .fold(theta0, f64::max);
                // The driven gear never turns back: where the pushers peaked before φ_a (they
                // lost contact there), it rests at least at their peak, which may lie above
                // where they are at φ_a.
                let rests_above = || {
                    let (phi_pk, theta_pk) = push_peak();
                    phi_pk <= phi_a && at <= theta_pk + SIDE_TOL
                };
                if at <= theta_a + SIDE_TOL || (!pushers.is_empty() && rests_above()) {
                    Side::Behind
                } else {
                    Side::Ahead
                }
            };
            match side {
                Side::Behind => behind.push(pair),
                Side::Ahead => ahead.push(pair),
            }
        }
        let all_behind = behind.clone();
        // Only obstacles that can reach θ within this step matter to the motion.
        behind.retain(|&p| pushers.contains(&p) || hi(phi1, p) >= theta0 - 0.25 * gap);
        let envelope = |p: f64| {
            behind
                .iter()
                .map(|&b| hi(p, b))
                .fold(f64::NEG_INFINITY, f64::max)
        };

        // Plan the step without the obstacles ahead: (phi_end, theta_end, motion, event).
        let mut plan: Vec<(f64, f64, Motion, Option<Event>)> = Vec::new();
        if !pushers.is_empty() {
            // Is the push continuous through the step? The pushers' envelope must not peak.
            let e1 = envelope(phi1);
            let p1 = push_env(phi1);
            // Rounding may put the pushers' curve a hair below θ at a step end: that is not a
            // lost contact.
            // A curve higher mid-step than at its end has peaked inside the step.
            // A curve higher mid-step, or just before the end, than at the end has peaked inside
            // the step.
            let dphi = 1e-6 * (phi1 - phi0);
            let mid = 0.5 * (phi0 + phi1);
            let pushers_hold = p1 >= theta0 - SIDE_TOL
                && push_env(mid) <= p1 + SIDE_TOL
                && push_env(phi1 - dphi) <= p1;
            let all_rising = envelope(mid) <= e1 + SIDE_TOL && envelope(phi1 - dphi) <= e1;
            if pushers_hold && all_rising {
                // Every obstacle behind takes part: another tooth pair may carry the driven gear
                // for part of the step (two pairs in contact at once).
                plan.push((phi1, e1.max(theta0), Motion::Push(behind.clone()), None));
            } else {
                // Where do the pushers stop rising (peak or vanish)?
                let (phi_pk, theta_pk) = push_peak();
                let theta_pk = theta_pk.max(theta0);
                // Did another behind obstacle take over before that?
                let others: Vec<(i64, i64)> = behind
                    .iter()
                    .copied()
                    .filter(|p| !pushers.contains(p))
                    .collect();
                let other_env = |p: f64| {
                    others
                        .iter()
                        .map(|&b| hi(p, b))
                        .fold(f64::NEG_INFINITY, f64::max)
                };
                if other_env(phi_pk) >= theta_pk - SIDE_TOL {
                    // Continuous handoff: one Push segment over the whole step with every behind pair.
                    plan.push((phi1, e1.max(theta0), Motion::Push(behind.clone()), None));
                } else if !self.pending.is_empty() && theta_pk <= theta0 + SIDE_TOL {
                    // The gear rests (drive lost) and the pair touching it from behind where the
                    // step starts falls away without lifting it: a graze, not drive resumed (a
                    // tip of the radius of the one that left the gear there passes it exactly).
                    rest_then_maybe_push(
                        &mut plan,
                        &others,
                        &hi,
                        (phi0, theta0, phi1),
                        self.certify,
                    );
                } else {
                    let lost = mesh.top_pair(phi_pk, &pushers).unwrap_or(pushers[0]);
                    plan.push((
                        phi_pk,
                        theta_pk,
                        Motion::Push(pushers.to_vec()),
                        Some(Event::new(EventKind::Gap, phi_pk, theta_pk, lost)),
                    ));
                    rest_then_maybe_push(
                        &mut plan,
                        &others,
                        &hi,
                        (phi_pk, theta_pk, phi1),
                        self.certify,
                    );
                }
            }
        } else {
            rest_then_maybe_push(&mut plan, &behind, &hi, (phi0, theta0, phi1), self.certify);
        }

        // Jam check against the obstacles ahead, along the planned path.
        // θ on the plan at φ = p, leaving out the pushing pairs `skip` (those proved below the
        // path where a closing is located: `locate` below).
        let theta_on_plan_without = |p: f64, skip: &[(i64, i64)]| -> f64 {
            let mut from = theta0;
            for (end, th, motion, _) in &plan {
                if p <= *end {
                    return match motion {
                        Motion::Push(pairs) => pairs
                            .iter()
                            .filter(|b| !skip.contains(b))
                            .map(|&b| hi(p, b))
                            .fold(from, f64::max)
                            .min(*th),
                        _ => from,
                    };
                }
                from = *th;
            }
            from
        };
        let theta_on_plan = |p: f64| theta_on_plan_without(p, &[]);
        let theta1 = theta_on_plan(phi1);
        ahead.retain(|&a| lo(phi1, a) <= theta1 + 0.5 * gap);
        // The backlash of pairs `ahead`: how far the nearest of their driver teeth is from the
        // driven gear (θ on the plan without the pairs behind `skip`).
        let backlash_of = |ahead: &[(i64, i64)], skip: &[(i64, i64)], p: f64| {
            let front = ahead
                .iter()
                .map(|&a| lo(p, a))
                .fold(f64::INFINITY, f64::min);
            front - theta_on_plan_without(p, skip)
        };
        // Whether pairs `pairs`, each open at `a`, are proved to stay clear of the driven
        // gear's path over driver angles [a, b] (a pair with no contact root on the path, open
        // where it starts, stays open: `certify.rs`). The path runs from (a, θ(a)) to
        // (b, θ(b)) and never turns back, so it lies in that box: a pair `Clear` in the box is
        // proved. Otherwise, where the slopes of the path are bounded (it rests, or is pushed by
        // pairs whose contacts in the box all rise), the thinner tube about its chord is tried
        // (`ConfigBox::clear_along`, second order: it proves a pair that runs a small backlash
        // ahead alongside the gear, which a box of any useful width does not).
        let proved_clear = |pairs: &[(i64, i64)], a: f64, b: f64| {
            let cell = ConfigBox::new(
                a,
                b,
                theta_on_plan(a),
                theta_on_plan(b),
                mesh.centre_distance,
            );
            let place = |(j, k): (i64, i64)| {
                (
                    cell.place_driver(mesh.driver.cert(j)),
                    cell.place_driven(mesh.driven.cert(k)),
                )
            };
            let slopes = std::cell::OnceCell::new();
            let path_slopes =
                || *slopes.get_or_init(|| plan_slopes(&plan, phi0, (a, b), &cell, place));
            pairs.iter().all(|&pair| {
                let (va, vb) = place(pair);
                cell.pair(&va, &vb).0 == Verdict::Clear
                    || path_slopes().is_some_and(|sl| cell.clear_along(&va, &vb, sl, SIDE_TOL))
            })
        };
        // The pairs that make the backlash of `pairs` where a closing is located in [a, b]: those
        // ahead that touch the box of the path there (from (a, θ(a)) to (b, θ(b)), as
        // `proved_clear` has it), and, left out, the pushing pairs of the plan that do not. A
        // pair ahead that touches no configuration of the box has its lower end above the path
        // throughout, so it is never the nearest where the backlash is not positive, and the
        // backlash of the rest has the sign of the whole one everywhere in [a, b]; a pair behind
        // that touches none is below the path throughout, never the one that carries it, and θ
        // on the plan without it is the same. Locating reads only the backlash's sign (replayed
        // bisection: its secant steps only aim the probes), so it finds the same angle,
        // evaluating at each probe only the pairs that can close and the one that pushes.
        let closing_pairs = |pairs: &[(i64, i64)], a: f64, b: f64| {
            let cell = ConfigBox::new(
                a,
                b,
                theta_on_plan(a),
                theta_on_plan(b),
                mesh.centre_distance,
            );
            let touches = |&(j, k): &(i64, i64)| {
                let (va, vb) = (
                    cell.place_driver(mesh.driver.cert(j)),
                    cell.place_driven(mesh.driven.cert(k)),
                );
                cell.pair(&va, &vb).0 != Verdict::Clear
            };
            let ahead: Pairs = pairs.iter().copied().filter(touches).collect();
            let mut below = Pairs::new();
            for (.., motion, _) in &plan {
                if let Motion::Push(pushing) = motion {
                    for pair in pushing {
                        if !below.contains(pair) && !touches(pair) {
                            below.push(*pair);
                        }
                    }
                }
            }
            (ahead, below)
        };
        // Where the backlash of pairs `pairs` ahead first closes in the step, if it does.
        let first_jam = |pairs: &[(i64, i64)]| {
            let gap = |p: f64| backlash_of(pairs, &[], p);
            let g0 = gap(phi0);
            if g0 < -SIDE_TOL {
                Some(phi0)
            } else {
                // Once a jam is known to lie in the step, locate first contact exactly: where the
                // backlash stops being positive (no tolerance).
                let clear = |a: f64, b: f64| proved_clear(pairs, a, b);
                let locate = |a: f64, b: f64| {
                    if !self.certify {
                        return bisect_sign(a, b, theta0, false, gap);
                    }
                    let (ahead, below) = closing_pairs(pairs, a, b);
                    bisect_sign(a, b, theta0, true, |p| backlash_of(&ahead, &below, p))
                };
                let search = Closing {
                    gap: &gap,
                    clear: &clear,
                    locate: &locate,
                    certified: !mesh.curved,
                };
                search.first(phi0, phi1, g0, gap(phi1), 0)
            }
        };
        // A pair ahead where the step starts may close on the driven gear and be gone by its
        // end (a tip passing a tip): it is not among the obstacles at φ1, so the backlash above
        // leaves it out. Each such pair near enough to close has its own backlash searched
        // alike (kept apart, so that the search of the others sees what it always saw), and the
        // first closing of all is the jam.
        let gone: Pairs = self
            .sides
            .iter()
            .filter(|t| {
                t.side == Side::Ahead
                    && at1(t.pair).is_none()
                    && lo(phi0, t.pair) <= theta0 + 0.5 * gap
            })
            .map(|t| t.pair)
            .collect();
        let jam_at = if self.unheld_at == Some(phi0) {
            None
        } else {
            let others = (!ahead.is_empty()).then(|| first_jam(&ahead)).flatten();
            gone.iter()
                .filter_map(|&pair| first_jam(&[pair]))
                .chain(others)
                .min_by(f64::total_cmp)
        };

        match jam_at {
            None => {
                for (end, th, motion, event) in plan {
                    self.push_segment(end, th, motion);
                    if let Some(e) = event {
                        self.record(e, Some(e.driver_tooth + e.driven_tooth));
                    }
                }
                // Sides for the next step, from the cached values at φ1.
                self.sides.clear();
                for o in &obs1 {
                    let pair = (o.driver_tooth, o.driven_tooth);
                    let side = if all_behind.contains(&pair) || o.hi <= theta1 + SIDE_TOL {
                        Side::Behind
                    } else {
                        Side::Ahead
                    };
                    self.sides.push(Tracked {
                        pair,
                        side,
                        hi: o.hi,
                    });
                }
            }
            Some(phi_j) => {
                let th_j = theta_on_plan(phi_j);
                for (end, th, motion, event) in plan {
                    if end < phi_j {
                        self.push_segment(end, th, motion);
                        if let Some(e) = event {
                            self.record(e, Some(e.driver_tooth + e.driven_tooth));
                        }
                    } else {
                        self.push_segment(phi_j, th_j, motion);
                        break;
                    }
                }
                let theta_j = self.theta;
                // Every scan at φ_j below evaluates a pair once (`PairMemo`).
                let mut memo = PairMemo::new(mesh, phi_j);
                let mut lo_j = |pair: (i64, i64)| {
                    mesh.obstacle_in(phi_j, pair.0, pair.1, &mut memo)
                        .map_or(f64::INFINITY, |o| o.lo)
                };
                let closing = ahead
                    .iter()
                    .chain(&gone)
                    .map(|&pair| (pair, lo_j(pair)))
                    .min_by(|a, b| a.1.total_cmp(&b.1))
                    .map_or((0, 0), |(pair, _)| pair);
                let release = mesh
                    .free_or_cover_in(phi_j, theta_j, true, None, &mut memo)
                    .ok();
                if release.is_some_and(|t| t <= theta_j + SIDE_TOL) {
                    // Nothing ahead actually holds the driven gear (the closing obstacle only
                    // touches, or vanished): no jam. Count the pair as behind and go on.
                    self.classify_all(phi_j, &mut memo);
                    for t in &mut self.sides {
                        if t.pair == closing {
                            t.side = Side::Behind;
                        }
                    }
                    // Guarantee progress: at most one such non-event per driver angle.
                    self.unheld_at = Some(phi_j);
                    self.scratch = obs1;
                    return;
                }
                self.held = release.is_none();
                self.held_links.clear();
                let after = release.unwrap_or(theta_j);
                // Held from both sides (a pair touching behind as the one ahead closes), or
                // struck from the front with nothing pushing.
                let behind_pair = self.touching_behind(phi_j, theta_j, Some(closing), &mut memo);
                let (kind, before) = match behind_pair {
                    Some(p) => (EventKind::Lock, Some(p.0 + p.1)),
                    None => (EventKind::Strike, self.drive_phase),
                };
                let mut e = Event::new(kind, phi_j, theta_j, closing);
                e.theta_after = after;
                e.wedge_angle = mesh
                    .contact_normal(phi_j, theta_j, closing.0, closing.1)
                    .map(|(p, n)| mesh.angle_to_driven_centre(p, n));
                self.record(e, before);
                self.theta = after;
                self.classify_all(phi_j, &mut memo);
            }
        }
        self.scratch = obs1;
    }
}

/// Deepest halving of a step when a mesh with curved flanks (no certificates) looks for a
/// closing backlash; with certificates, the halvings of a step after which a stretch known to
/// hold a closing has it located (not a matter of what is found - every stretch before it is
/// proved free of contact - but of where bisection starts: from the same stretches as before
/// certificates, it finds the same angles to the last bit, where a backlash flat at zero has
/// several).
const MAX_REFINE: u32 = 5;

/// The narrowest stretch of driver angle (radians, relative to 1 + |φ|) a certified search for a
/// closing backlash divides a step into. It is a resolution, not a step: every wider stretch is
/// proved free of contact or divided, so all that is left unproved is a stretch this narrow
/// where a pair ahead touches the driven gear to within the side tolerance and the sample at
/// its end finds the backlash not closed.
const CLOSING_RESOLUTION: f64 = 1e-8;

/// The search of a bracketed step for the first closing of a backlash `gap` (open where it is
/// positive, closed below −SIDE_TOL), and where it starts.
struct Closing<'a, G: Fn(f64) -> f64, C: Fn(f64, f64) -> bool, L: Fn(f64, f64) -> f64> {
    gap: &'a G,
    /// Proves a stretch of driver angles free of contact, for pairs open at its start.
    clear: &'a C,
    /// Where the backlash stops being positive in a stretch open at its start and closed at its
    /// end (`bisect_sign`: the last angle where it is positive, to `LOCATE_TOL`).
    locate: &'a L,
    /// Divide wherever `clear` proves nothing, down to `CLOSING_RESOLUTION` (else the plain
    /// sampling, `dip_possible`, to `MAX_REFINE` halvings).
    certified: bool,
}

impl<G, C, L> Closing<'_, G, C, L>
where
    G: Fn(f64) -> f64,
    C: Fn(f64, f64) -> bool,
    L: Fn(f64, f64) -> f64,
{
    /// Where the backlash first closes in `[a, b]` (the last angle before it where the backlash
    /// is positive), or None if it stays open; `ga`, `gb`: the backlash at `a` and `b`.
    ///
    /// Certified, a stretch is passed over only when the backlash is positive at its start and
    /// `clear` proves it free of contact: no closing lies in it, however brief. A stretch open
    /// at its start and closed at its end has its sign change located, and the stretch up to it
    /// is then proved free of contact piece by piece (`prove_up_to`): the change found is the
    /// first. Every other stretch is halved, the left half first, down to `CLOSING_RESOLUTION`.
    /// Plain (curved flanks, no certificates), the backlash is sampled at the ends and the
    /// middle, and both halves are examined only where the samples say it could dip to zero in
    /// between (`dip_possible`), down to `MAX_REFINE` halvings.
    fn first(&self, a: f64, b: f64, ga: f64, gb: f64, depth: u32) -> Option<f64> {
        let closed = |g: f64| g < -SIDE_TOL;
        let finest = if self.certified {
            b - a <= CLOSING_RESOLUTION * (1.0 + a.abs())
        } else {
            depth >= MAX_REFINE
        };
        if self.certified && ga > 0.0 {
            if closed(gb) && !finest && depth >= MAX_REFINE {
                let z = (self.locate)(a, b);
                if let Some(found) = self.prove_up_to(a, ga, z, depth) {
                    return Some(found);
                }
            } else if !closed(gb) && (self.clear)(a, b) {
                return None;
            }
        }
        if finest {
            if self.certified && !closed(gb) {
                count(|st| st.unproved += 1);
            }
            return closed(gb).then(|| (self.locate)(a, b));
        }
        let m = 0.5 * (a + b);
        let gm = (self.gap)(m);
        if closed(gm) {
            return self.first(a, m, ga, gm, depth + 1);
        }
        if self.certified || dip_possible(ga, gm, gb) {
            return self
                .first(a, m, ga, gm, depth + 1)
                .or_else(|| self.first(m, b, gm, gb, depth + 1));
        }
        if closed(gb) {
            return self.first(m, b, gm, gb, depth + 1);
        }
        None
    }

    /// With the backlash open at `a` and a sign change located at `z`: proves `[a, z]` free of
    /// contact in stretches, each ending short of `z` by a share of what is left: an eighth at
    /// first, a quarter as much after each stretch proved, four times as much again after each
    /// refusal. (Near a closing the backlash shrinks about linearly and the bounds' error with
    /// the square of the stretch, so the nearer `z`, the larger the share that can be proved.) A
    /// stretch refused at an eighth is searched as `first` does. The first closing: an earlier
    /// one found so, or `z`; None where the backlash is not positive short of `z` (a touch within
    /// the side tolerance before it), for the caller to halve the stretch instead.
    ///
    /// A stretch proved free of contact from an open start ends open (no contact root lies in
    /// between): the backlash is sampled only where a stretch is refused.
    fn prove_up_to(&self, a: f64, ga: f64, z: f64, depth: u32) -> Option<f64> {
        let (mut x, mut gx) = (a, Some(ga));
        let mut share: f64 = 1.0 / 8.0;
        while z - x > CLOSING_RESOLUTION * (1.0 + x.abs()) {
            let y = z - (z - x) * share;
            if (self.clear)(x, y) {
                (x, gx) = (y, None);
                share /= 4.0;
                continue;
            }
            if share < 1.0 / 8.0 {
                share = (share * 4.0).min(1.0 / 8.0);
                continue;
            }
            let gy = (self.gap)(y);
            if gy <= 0.0 {
                return None;
            }
            let open = gx.unwrap_or_else(|| (self.gap)(x));
            if let Some(earlier) = self.first(x, y, open, gy, depth + 1) {
                return Some(earlier);
            }
            (x, gx) = (y, Some(gy));
        }
        Some(z)
    }
}

/// Bounds on the slopes dθ/dφ of a planned path over driver angles `[a, b]` (the plan's
/// segments from `phi0`, each ending at its first element), read off `cell`, the box from
/// (a, θ(a)) to (b, θ(b)): 0 where it rests; where it is pushed, the slopes of every pushing
/// pair's contacts in the box (θ is the largest of their upper ends, each a contact); None when
/// a pushing pair touches the box other than rising (no bound).
fn plan_slopes<'t>(
    plan: &[(f64, f64, Motion, Option<Event>)],
    phi0: f64,
    (a, b): (f64, f64),
    cell: &ConfigBox,
    place: impl Fn((i64, i64)) -> (PlacedTooth<'t>, PlacedTooth<'t>),
) -> Option<(f64, f64)> {
    let mut from = phi0;
    let mut slopes = (f64::INFINITY, f64::NEG_INFINITY);
    for (end, _, motion, _) in plan {
        let overlaps = *end >= a && from <= b;
        from = *end;
        if !overlaps {
            continue;
        }
        match motion {
            Motion::Push(pairs) => {
                for &pair in pairs {
                    let (va, vb) = place(pair);
                    match cell.pair(&va, &vb) {
                        (Verdict::Clear, _) => {}
                        (Verdict::Rising, r) => slopes = (slopes.0.min(r.0), slopes.1.max(r.1)),
                        _ => return None,
                    }
                }
            }
            _ => slopes = (slopes.0.min(0.0), slopes.1.max(0.0)),
        }
    }
    // No pair that pushes touches the box: the path is level.
    Some(if slopes.0 > slopes.1 {
        (0.0, 0.0)
    } else {
        slopes
    })
}

/// Whether a function sampled as `ga`, `gm`, `gb` at the start, middle and end of an interval
/// could dip below zero inside it: the smallest sample is no larger than the change between the
/// samples (a kinked, tip-on-tip dip between them is as deep as that), or the parabola through
/// them reaches zero.
fn dip_possible(ga: f64, gm: f64, gb: f64) -> bool {
    let least = ga.min(gm).min(gb);
    if least <= (ga - gm).abs().max((gb - gm).abs()) {
        return true;
    }
    let c = 0.5 * (ga - 2.0 * gm + gb);
    if c > 0.0 {
        let x = -(gb - ga) / (4.0 * c);
        if x.abs() < 1.0 {
            return gm - (gb - ga) * (gb - ga) / (16.0 * c) <= 0.0;
        }
    }
    false
}

/// Plan a rest at θ from `phi_a`, re-engaging if an obstacle behind rises to θ before `phi1`.
fn rest_then_maybe_push(
    plan: &mut Vec<(f64, f64, Motion, Option<Event>)>,
    behind: &[(i64, i64)],
    hi: &impl Fn(f64, (i64, i64)) -> f64,
    (phi_a, theta, phi1): (f64, f64, f64),
    replay: bool,
) {
    let env = |p: f64| {
        behind
            .iter()
            .map(|&b| hi(p, b))
            .fold(f64::NEG_INFINITY, f64::max)
    };
    if env(phi1) > theta + SIDE_TOL {
        // Where the curve behind reaches θ: `env(p) < θ` up to there (see `bisect_sign`).
        let phi_r = bisect_sign(phi_a, phi1, theta, replay, |p| theta - env(p));
        plan.push((phi_r, theta, Motion::Rest, None));
        plan.push((phi1, env(phi1), Motion::Push(behind.to_vec()), None));
    } else {
        plan.push((phi1, theta, Motion::Rest, None));
    }
}

/// The bracket `(good, bad)`, at most `tol` wide, around the boundary between where `good` holds
/// (at `a`) and where it fails (at `b`).
fn bracket(mut a: f64, mut b: f64, tol: f64, good: impl Fn(f64) -> bool) -> (f64, f64) {
    while b - a > tol {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if good(m) { a = m } else { b = m }
    }
    (a, b)
}

/// The boundary between where `good` holds (at `a`) and where it fails (at `b`), to LOCATE_TOL.
fn bisect(mut a: f64, mut b: f64, good: impl Fn(f64) -> bool) -> f64 {
    while b - a > LOCATE_TOL {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if good(m) { a = m } else { b = m }
    }
    a
}

/// [`bisect`] with `good(p) = gap(p) > 0`, for a continuous `gap` positive at `a` and not at `b`
/// (a backlash closing, a curve rising to θ) whose values are angles near `scale`: the same
/// driver angle, bit for bit, in about half the evaluations.
///
/// Bisection's answer is fixed by the signs of `gap` at its midpoints. Secant steps first close
/// in on the sign change (`close_in`), ending with `gap(l) > 0 ≥ gap(u)`, both evaluated;
/// bisection is then replayed from `[a, b]`, evaluating only the midpoints within a guard of
/// `[l, u]` - the sign of every other midpoint is that of `l` (below) or `u` (above) wherever
/// the sign changes once in `[a, b]`. The guard keeps the rounding of `gap` near its zero, where
/// its sign is noise, out of what is inferred: it is the driver angle over which `gap` changes by
/// [`REPLAY_NOISE`] roundings of `scale` at the slope found on the open side, and at least
/// [`REPLAY_GUARD`].
/// Where the sign changes more than once (a graze just before the closing), bisection finds one
/// of the changes and neither it nor this is sure to find the first: that is what the search
/// around it (`Closing::first`, which proves the stretch before the change found) is for. Without `replay` it bisects throughout: the plain solver
/// (`Solve::certify` unset) does, and the differential tests hold the two to the same events.
fn bisect_sign(a: f64, b: f64, scale: f64, replay: bool, gap: impl Fn(f64) -> f64) -> f64 {
    if !replay {
        return bisect(a, b, |p| gap(p) > 0.0);
    }
    let (ga, gb) = (gap(a), gap(b));
    let bracket = if ga > 0.0 && gb <= 0.0 {
        close_in((a, ga), (b, gb), &gap)
    } else {
        None
    };
    let Some((l, u, slope)) = bracket else {
        return bisect(a, b, |p| gap(p) > 0.0);
    };
    let noise = REPLAY_NOISE * f64::EPSILON * (1.0 + scale.abs());
    let guard = (noise / slope).max(REPLAY_GUARD);
    bisect(a, b, |p| {
        if p < l - guard {
            true
        } else if p > u + guard {
            false
        } else {
            gap(p) > 0.0
        }
    })
}

/// A bracket `(l, u)` of the sign change of `gap`, with `gap(l) > 0 ≥ gap(u)` evaluated, and the
/// slope of `gap` on the open side, or None if a few steps do not bring it within
/// [`REPLAY_GUARD`]: `(l, gl)` and `(u, gu)` bracket it to start with.
///
/// Secant steps through the last two samples (through the last two on the open side when the
/// last sample is exactly 0: where a backlash has closed it is often flat, a pair's end exactly
/// at θ), a halving wherever the secant leaves the bracket; once an aim moves by less than a
/// quarter of the guard, one sample either side of it closes the bracket from both sides.
fn close_in(
    (mut l, mut gl): (f64, f64),
    (mut u, gu): (f64, f64),
    gap: &impl Fn(f64) -> f64,
) -> Option<(f64, f64, f64)> {
    // The last two samples, the latest second; and the one before the latest open-side sample.
    let mut last = [(l, gl), (u, gu)];
    let mut before_l: Option<(f64, f64)> = None;
    let mut last_aim = f64::NAN;
    for _ in 0..MAX_SECANT {
        let width = u - l;
        if width <= REPLAY_GUARD {
            let slope = before_l.map_or(gl / width, |(p, gp)| (gp - gl) / (l - p));
            return (slope > 0.0 && slope.is_finite()).then_some((l, u, slope));
        }
        let [(x1, g1), (x2, g2)] = match before_l {
            Some(b) if last[1].1 == 0.0 => [b, (l, gl)],
            _ => last,
        };
        let aim = x2 - g2 * (x2 - x1) / (g2 - g1);
        let probes = if !(aim > l && aim < u && aim.is_finite()) {
            [l + 0.5 * width, f64::NAN]
        } else if (aim - last_aim).abs() < 0.25 * REPLAY_GUARD {
            [aim - 0.25 * REPLAY_GUARD, aim + 0.25 * REPLAY_GUARD]
        } else {
            [aim, f64::NAN]
        };
        last_aim = aim;
        for m in probes {
            if !(m > l && m < u) {
                continue;
            }
            let gm = gap(m);
            last = [last[1], (m, gm)];
            if gm > 0.0 {
                before_l = Some((l, gl));
                (l, gl) = (m, gm);
            } else {
                u = m;
            }
        }
    }
    None
}

/// The narrowest guard [`bisect_sign`] keeps either side of its secant bracket (radians of
/// driver angle), and the bracket it aims for.
const REPLAY_GUARD: f64 = 4e-12;
/// How many roundings of the driven angle the backlash's sign is taken to be noise for, near its
/// zero, in [`bisect_sign`]'s guard. Measured, not derived: the backlash is a difference of
/// contact roots, and a root near a grazing contact carries more than the rounding of its angle.
/// On tight hard meshes (`tight_meshes_agree_with_the_plain_solver` with 1500 cases at G = 2-30
/// %, 9000 meshes), 64 roundings let 14 jams of the first 2400 meshes be located up to 1e-11 rad
/// from plain bisection's angle, 256 let 4, 1024 none; 4096, none of the 9000, and costs 2.5 %
/// more instructions at G = 10 % than 64 (the guard's midpoints are evaluated).
const REPLAY_NOISE: f64 = 4096.0;
/// Most secant steps [`bisect_sign`] takes before replaying bisection (or, failing, bisecting).
const MAX_SECANT: u32 = 12;

/// Where a function that rises and then falls (or ends, −∞) takes its largest value on [a, b].
///
/// Where the function ends (an obstacle vanishing as two tips slip apart) its last values may
/// flicker between finite and −∞ within rounding, as the contact roots graze: should the search
/// close in on −∞ there, the best finite point it evaluated is returned instead.
fn golden_max(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    const R: f64 = 0.618_033_988_749_894_8;
    let best = std::cell::Cell::new((f64::NAN, f64::NEG_INFINITY));
    let f = |x: f64| {
        let y = f(x);
        if y > best.get().1 {
            best.set((x, y));
        }
        y
    };
    let mut x1 = b - R * (b - a);
    let mut x2 = a + R * (b - a);
    let mut f1 = f(x1);
    let mut f2 = f(x2);
    while b - a > LOCATE_TOL {
        if f1 < f2 {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + R * (b - a);
            f2 = f(x2);
        } else {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - R * (b - a);
            f1 = f(x1);
        }
        if x1 >= x2 {
            break;
        }
    }
    // The end points may be better than the interior (monotone on the bracket).
    let mid = 0.5 * (a + b);
    let (top, value) = [a, mid, b]
        .into_iter()
        .map(|p| (p, f(p)))
        .max_by(|p, q| p.1.total_cmp(&q.1))
        .unwrap_or((mid, f64::NEG_INFINITY));
    match best.get() {
        (x, y) if value == f64::NEG_INFINITY && y > value => x,
        _ => top,
    }
}

/// How the steps of the runs on this thread were taken, for benchmarks and profiling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolverStats {
    /// Steps taken on a certificate.
    pub certified: u64,
    /// Tooth-pair evaluations made by certified steps.
    pub certified_evaluations: u64,
    /// Certificates tried and not found.
    pub refused: u64,
    /// Tooth-pair evaluations made by those attempts.
    pub refused_evaluations: u64,
    /// Steps bracketed (no certificate tried, or none found), while the driven gear was free.
    pub bracketed: u64,
    /// Stretches of a bracketed step at the finest resolution of the search for a closing
    /// backlash that were neither proved free of contact nor found closed (a touch within
    /// the side tolerance).
    pub unproved: u64,
}

thread_local! {
    static STATS: std::cell::Cell<SolverStats> = const {
        std::cell::Cell::new(SolverStats {
            certified: 0,
            certified_evaluations: 0,
            refused: 0,
            refused_evaluations: 0,
            bracketed: 0,
            unproved: 0,
        })
    };
}

/// The step counts of the runs on this thread so far.
pub fn solver_stats() -> SolverStats {
    STATS.with(std::cell::Cell::get)
}

/// Updates this thread's step counts.
fn count(update: impl FnOnce(&mut SolverStats)) {
    STATS.with(|c| {
        let mut st = c.get();
        update(&mut st);
        c.set(st);
    });
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use geometry::{Gear, Vec2};
    use rand::{Rng, SeedableRng};

    /// Meshes of a pinion and a large wheel with tip angles scattered by up to 0.1 pitch, at
    /// clearances where they are blocked or jam at many teeth (the held-gear regime).
    fn tight_mesh(rng: &mut rand_chacha::ChaCha8Rng) -> Mesh {
        let (n1, n2) = (rng.random_range(12..40), rng.random_range(40..240));
        let module = 0.24;
        let (r1, r2) = (module * n1 as f64, module * n2 as f64);
        let gear = |n: usize, r: f64, rng: &mut rand_chacha::ChaCha8Rng| {
            let pitch = TAU / n as f64;
            let tips = (0..n)
                .map(|k| pitch * (k as f64 + rng.random_range(-0.1..0.1)))
                .collect();
            Gear::new(r, r - 1.1, tips, Vec2::zeros()).unwrap()
        };
        let (a, b) = (gear(n1, r1, rng), gear(n2, r2, rng));
        let g = rng.random_range(0.0..12.0);
        Mesh::new(a, b, geometry::centre_distance(r1, r2, 1.1, g)).unwrap()
    }
    /// A backlash that is 0.05 but for a V-shaped dip to −0.01 of half-width `half` about
    /// `centre`, and, with `closing_at`, closed for good from there on.
    fn dipping_gap(centre: f64, half: f64, closing_at: Option<f64>) -> impl Fn(f64) -> f64 {
        move |p: f64| {
            let dip = 0.06 * (1.0 - (p - centre).abs() / half).max(0.0);
            let closed = closing_at.map_or(0.0, |c| if p >= c { 1.0 } else { 0.0 });
            0.05 - dip - closed
        }
    }

    /// The search for a closing of `dipping_gap(_, half, _)` over `[0, 1]`, certified (with a
    /// sound proof: the backlash falls at most 0.06 / half per radian, so over `[a, b]` it stays
    /// above the mean of its ends less half that times b − a) or plain.
    fn search_dipping(gap: &impl Fn(f64) -> f64, half: f64, certified: bool) -> Option<f64> {
        let clear = |a: f64, b: f64| 0.5 * (gap(a) + gap(b)) - 0.03 / half * (b - a) > 0.0;
        let locate = |a: f64, b: f64| bisect(a, b, |p| gap(p) > 0.0);
        let search = Closing {
            gap,
            clear: &clear,
            locate: &locate,
            certified,
        };
        search.first(0.0, 1.0, gap(0.0), gap(1.0), 0)
    }

    /// A closing between the samples the plain search takes (a dip at 0.3 between 9/32 and
    /// 10/32, where the backlash is 0.05 as everywhere it is sampled) is stepped over by it and
    /// found by the certified search, which passes over only what is proved clear. And a brief
    /// closing inside the finest stretch that holds a sign change (a dip at 0.91, closed for good
    /// from 0.93, both between 29/32 and 30/32) is found by the certified search, which proves the
    /// stretch before the sign change it locates, not the later one bisection leads to.
    #[test]
    fn the_certified_search_finds_a_closing_between_samples() {
        // The backlash falls to zero where a dip is 0.05 deep: a sixth of its half-width before
        // its centre.
        let brief = dipping_gap(0.3, 0.005, None);
        assert_eq!(
            search_dipping(&brief, 0.005, false),
            None,
            "the plain search misses it"
        );
        let found = search_dipping(&brief, 0.005, true).unwrap();
        assert!((found - (0.3 - 0.005 / 6.0)).abs() < 1e-12, "{found}");
        let then_closed = dipping_gap(0.91, 0.002, Some(0.93));
        let plain = search_dipping(&then_closed, 0.002, false).unwrap();
        assert!((plain - 0.93).abs() < 1e-12, "{plain}");
        let found = search_dipping(&then_closed, 0.002, true).unwrap();
        assert!((found - (0.91 - 0.002 / 6.0)).abs() < 1e-12, "{found}");
    }

    /// Replayed bisection lands on bisection's own driver angle, bit for bit, for gaps that change
    /// sign once: smooth, kinked where they close, flat at exactly 0 beyond the closing (a pair's
    /// end at θ), and infinite before it (no obstacle yet), over brackets from a step to 1e-9 rad.
    #[test]
    fn replayed_bisection_is_bisection() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(15);
        let mut secant_found = 0;
        for case in 0..20_000 {
            let a = rng.random_range(-30.0..30.0);
            let width = 10f64.powf(rng.random_range(-9.0..-0.5));
            let b = a + width;
            let root = a + width * rng.random_range(0.001..0.999);
            let (slope, curve) = (
                10f64.powf(rng.random_range(-3.0..1.0)),
                rng.random_range(-5.0..5.0),
            );
            let scale = rng.random_range(0.0..50.0);
            let kind = case % 4;
            let gap = |p: f64| {
                let d = root - p;
                let smooth = slope * d + curve * d * d;
                match kind {
                    0 => smooth,
                    1 if d < 0.0 => 3.0 * smooth,
                    2 if d < 0.0 => 0.0,
                    3 if d > 0.6 * (root - a) => f64::INFINITY,
                    _ => smooth,
                }
            };
            // Keep the gap monotone on the bracket (the curvature must not turn it).
            if (slope - 2.0 * curve.abs() * width) <= 0.0 {
                continue;
            }
            if close_in((a, gap(a)), (b, gap(b)), &gap).is_some() {
                secant_found += 1;
            }
            let want = bisect(a, b, |p| gap(p) > 0.0);
            let got = bisect_sign(a, b, scale, true, gap);
            assert_eq!(
                got.to_bits(),
                want.to_bits(),
                "case {case}: {got} vs {want}"
            );
        }
        assert!(
            secant_found > 5_000,
            "the secant bracket was found {secant_found} times"
        );
    }

    /// Obstacles taken from a memo (a scan's widening windows, a cover's links a turn apart) are
    /// the ones a fresh evaluation gives, bit for bit, and no pair is evaluated twice.
    #[test]
    fn remembered_obstacles_are_evaluated_ones() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(17);
        let bits = |o: &Obstacle| {
            (
                o.driver_tooth,
                o.driven_tooth,
                o.lo.to_bits(),
                o.hi.to_bits(),
            )
        };
        for _ in 0..20 {
            let mesh = tight_mesh(&mut rng);
            let (phi, theta) = (rng.random_range(0.0..TAU), rng.random_range(0.0..TAU));
            let gap = mesh.driven.max_gap;
            let mut memo = PairMemo::new(&mesh, phi);
            let (mut fresh, mut remembered) = (Vec::new(), Vec::new());
            let mut reach = 3.0 * gap;
            let mut window = (theta - gap, theta + reach);
            // Widening windows as the scan takes them, until past one that lies wholly a turn on.
            let mut beyond = 0;
            while window.0 < theta + 2.0 * TAU + 2.0 * gap {
                mesh.obstacles(phi, window.0, window.1, &mut fresh);
                let before = crate::mesh::tooth_pair_evaluations();
                mesh.obstacles_with(phi, window.0, window.1, &mut remembered, Some(&mut memo));
                let evaluated = crate::mesh::tooth_pair_evaluations() - before;
                assert_eq!(
                    fresh.iter().map(bits).collect::<Vec<_>>(),
                    remembered.iter().map(bits).collect::<Vec<_>>()
                );
                if window.0 > theta + TAU + gap {
                    beyond += remembered.len();
                    assert_eq!(
                        evaluated, 0,
                        "a tooth met again a turn on was evaluated again"
                    );
                }
                window = (theta + reach, theta + 2.0 * reach);
                reach *= 2.0;
            }
            assert!(beyond > 0, "no obstacles a turn on");
        }
    }
}
