//! The one way a caller runs a mesh, [`Mesh::solve`]: the push model solved by the exact core
//! (`solver/`), with the speed layer (`speed/`) passed to each step wherever it applies. The one
//! module above both: the core never names the speed layer, and the speed layer never names this.

use std::marker::PhantomData;
use std::ops::RangeInclusive;

use crate::mesh::Mesh;
use crate::solver::{
    Answered, Event, ExactOnly, STEPS_PER_PITCH, Segment, Start, Stop, StopAt, Trajectory,
};

/// What a run keeps, and so what [`Mesh::solve`] returns: [`Path`] or [`Events`].
pub trait Keep: sealed::Sealed {
    /// What the run returns.
    type Output;
    /// Whether every segment is kept.
    #[doc(hidden)]
    const SEGMENTS: bool;
    /// The run's segments (only the last where they are not kept) and events, handed over.
    #[doc(hidden)]
    fn output(mesh: &Mesh, segments: Vec<Segment>, events: Vec<Event>) -> Self::Output;
}

/// Keep every segment: the run returns its [`Trajectory`] (θ at any φ, and the events).
#[derive(Debug, Clone, Copy)]
pub struct Path;

/// Keep only the events: the run returns them, in memory that does not grow with its range
/// (all that jam statistics need).
#[derive(Debug, Clone, Copy)]
pub struct Events;

impl Keep for Path {
    type Output = Trajectory;
    const SEGMENTS: bool = true;
    fn output(mesh: &Mesh, segments: Vec<Segment>, events: Vec<Event>) -> Trajectory {
        Trajectory {
            mesh: mesh.clone(),
            segments,
            events,
        }
    }
}

impl Keep for Events {
    type Output = Vec<Event>;
    const SEGMENTS: bool = false;
    fn output(_: &Mesh, _: Vec<Segment>, events: Vec<Event>) -> Vec<Event> {
        events
    }
}

mod sealed {
    /// Only [`super::Path`] and [`super::Events`] are ways of keeping a run.
    pub trait Sealed {}
    impl Sealed for super::Path {}
    impl Sealed for super::Events {}
}

/// How [`Mesh::solve`] runs the push model: what it keeps ([`Solve::path`], [`Solve::events`]),
/// where it may end early, and, for the differential tests, the step and whether the speed layer
/// may take work. No result depends on the last two (events are roots either way).
#[derive(Clone, Copy)]
pub struct Solve<'s, K> {
    stop: Stop<'s>,
    steps_per_pitch: f64,
    #[cfg_attr(
        not(feature = "speed"),
        expect(dead_code, reason = "no speed layer to leave out")
    )]
    speed_layer: bool,
    keep: PhantomData<K>,
}

impl Solve<'_, Path> {
    /// The whole trajectory: every segment and every event.
    pub fn path() -> Self {
        Self::keeping()
    }
}

impl Solve<'_, Events> {
    /// The events alone, without the segments: cheaper, in memory that does not grow with the
    /// range.
    pub fn events() -> Self {
        Self::keeping()
    }
}

impl<'s, K> Solve<'s, K> {
    fn keeping() -> Self {
        Self {
            stop: Stop::Never,
            steps_per_pitch: STEPS_PER_PITCH,
            speed_layer: true,
            keep: PhantomData,
        }
    }

    /// The run ends at the first event for which `stop` holds (a jammed train stops; which
    /// events jam is an event rule's call): a trajectory then ends there and holds its last angle
    /// beyond. `stop` sees an event as it is recorded, before a later drive sizes it (its kind is
    /// final except that a gap may still become a slip). Where only the events are kept it is
    /// asked from the start on, so a blocked start ends the run at once; the events up to and
    /// including the stopping one are those of the whole run.
    pub fn stop_at(self, stop: &'s StopAt<'s>) -> Self {
        Self {
            stop: Stop::AtEvent(stop),
            ..self
        }
    }

    /// The run ends as soon as `answered` holds for the events so far, asked each time new events
    /// are sized and none waits to be (the drive has resumed after each), so that it sees every
    /// event as the whole run records it. For a caller whose answer, once found, more events
    /// cannot change (has each rule seen a jam and a disengagement?): the events returned are
    /// then the whole run's up to the cut, and the answer is the whole run's.
    pub fn until_answered(self, answered: &'s Answered<'s>) -> Self {
        Self {
            stop: Stop::Answered(answered),
            ..self
        }
    }

    /// The step set to `1 / steps` of the driver's pitch (a quarter by default): only how far
    /// apart the core looks at the tooth pairs together, which no result may depend on.
    #[doc(hidden)]
    pub fn steps_per_pitch(self, steps: f64) -> Self {
        Self {
            steps_per_pitch: steps,
            ..self
        }
    }

    /// The exact core alone: every step exact, no proof of the speed layer tried (as in a
    /// crate built without its `speed` feature). The differential tests run it against the
    /// default.
    #[doc(hidden)]
    pub fn exact_core(self) -> Self {
        Self {
            speed_layer: false,
            ..self
        }
    }
}

impl Mesh {
    /// Runs the push model over the driver angles `phi` (radians, start to end) from `start`,
    /// as `how` says ([`Solve`]): the trajectory ([`Solve::path`]) or the events
    /// ([`Solve::events`]). The speed layer, where it applies (straight flanks) and the crate is
    /// built with it (the `speed` feature, on by default), is made for the run and passed to its
    /// steps.
    pub fn solve<K: Keep>(
        &self,
        phi: RangeInclusive<f64>,
        start: Start,
        how: Solve<'_, K>,
    ) -> K::Output {
        let range = (*phi.start(), *phi.end());
        let core = (how.stop, how.steps_per_pitch, K::SEGMENTS);
        #[cfg(feature = "speed")]
        if how.speed_layer
            && let Some(mut layer) = crate::speed::Certifier::new(self)
        {
            let (segments, events) = self.walk(range, start, core, &mut layer);
            return K::output(self, segments, events);
        }
        let (segments, events) = self.walk(range, start, core, &mut ExactOnly);
        K::output(self, segments, events)
    }
}
