//! What a run gives its caller: the events, each with its kind and size, and the trajectory
//! θ(φ) as segments of one closed-form rule each.

use serde::{Deserialize, Serialize};

use crate::mesh::{End, Mesh};

/// What happened at an event: its mechanical kind, read off the contact motion alone.
///
/// Which kinds a table counts as a "jam" or a "disengagement" is not decided here: that is an
/// event rule's job (the `rules` crate). [`Trajectory::jams`] and [`Trajectory::disengagements`]
/// give the `strict` reading (every lock, strike and blocked start is a jam; every gap and slip
/// a disengagement).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
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
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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

    /// An event of `kind` at (φ, θ) on tooth pair `pair`, with no size yet (a caller that
    /// finds events by a motion of its own, as `motion`'s models do, sizes them itself).
    pub fn new(kind: EventKind, phi: f64, theta: f64, pair: (i64, i64)) -> Self {
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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum Motion {
    /// Standing still.
    Rest,
    /// Pushed: θ is the largest upper end of these (driver tooth, driven tooth) obstacles.
    Push(Vec<(i64, i64)>),
    /// Jammed with no free position nearby: the driven gear is held where it is.
    Held,
}

/// A stretch of driver angle over which the driven angle follows one closed-form rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
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

/// Which events end a run early ([`Solve::stop_at`](crate::Solve::stop_at)).
pub type StopAt<'a> = dyn Fn(&Event) -> bool + 'a;

/// Whether the events of a run so far, every one of them sized, answer the caller's question
/// for good (see [`Solve::until_answered`](crate::Solve::until_answered)).
pub type Answered<'a> = dyn Fn(&[Event]) -> bool + 'a;

/// How the driven gear starts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Start {
    /// Put the driven gear at this angle; if that overlaps, it is pushed clear first.
    At(f64),
    /// Start touching the driver: from the given guess, pushed clear if it overlaps, otherwise
    /// turned back until a driven tooth rests against a driver tooth (the paper's initial contact).
    Touching(f64),
}

/// The exact run of one mesh over a range of driver angle.
///
/// Stored (serde) as its mesh, segments and events, so that what is drawn from a run (θ(φ),
/// the events and the contacts at them) is drawn again from stored results without running it.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Trajectory {
    pub(crate) mesh: Mesh,
    pub(crate) segments: Vec<Segment>,
    pub(crate) events: Vec<Event>,
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
