//! The ways a caller runs a mesh: each solves the push model with the exact core (`solver/`),
//! with the speed layer (`speed/`) on top wherever it applies. The one module above both: the
//! core never names the speed layer, and the speed layer never names this.

use crate::mesh::Mesh;
use crate::solver::{Answered, Event, Shortcut, Solve, Start, Stop, StopAt, Trajectory};

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
        let how = Solve::default();
        self.solve(
            (phi_start, phi_end),
            start,
            stop.into(),
            how,
            speed_layer(self),
        )
        .into_trajectory()
    }

    /// [`Mesh::run_until`] with the step set to `1 / steps_per_pitch` of the driver's pitch, and,
    /// with `certify` unset (or the crate built without its `speed` feature), the exact core
    /// alone: every step exact, no proof of the speed layer tried. The result must depend on
    /// neither (events are roots either way); the differential tests run them against each other.
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
            ..Solve::default()
        };
        let speed = if certify { speed_layer(self) } else { None };
        self.solve((phi_start, phi_end), start, stop.into(), how, speed)
            .into_trajectory()
    }

    /// The jams and disengagements of [`Mesh::run`] over the same range, without its segments:
    /// all that jam statistics need, in memory that does not grow with the range.
    pub fn run_events(&self, phi_start: f64, phi_end: f64, start: Start) -> Vec<Event> {
        self.events_only((phi_start, phi_end), start, Stop::Never)
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
        self.events_only((phi_start, phi_end), start, Stop::AtEvent(stop))
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
        self.events_only((phi_start, phi_end), start, Stop::Answered(answered))
    }

    /// The events of a run that keeps no segments (cheaper), ending at `stop` if given.
    fn events_only(&self, range: (f64, f64), start: Start, stop: Stop<'_, '_>) -> Vec<Event> {
        let how = Solve {
            keep_segments: false,
            ..Solve::default()
        };
        self.solve(range, start, stop, how, speed_layer(self))
            .into_events()
    }
}

/// The speed layer for one run on `mesh`, where it applies (straight flanks) and the crate is
/// built with it (the `speed` feature, on by default).
fn speed_layer(mesh: &Mesh) -> Option<Box<dyn Shortcut>> {
    #[cfg(feature = "speed")]
    if let Some(certifier) = crate::speed::Certifier::new(mesh) {
        return Some(Box::new(certifier));
    }
    #[cfg(not(feature = "speed"))]
    let _ = mesh;
    None
}
