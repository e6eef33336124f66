//! The events of a run in the solver's terms ([`contact::Event`]), for models other than the
//! push model: jams as they happen, and each loss of drive sized when a tooth moves the driven
//! gear again, so that every event rule counts them as it counts the exact solver's.
//!
//! Drive here is a tooth *moving* the driven gear (pushing it, holding it back, or jamming it):
//! a graze that moves nothing is not drive. A loss runs from the end of one drive to the start of
//! the next; one lasting a driver pitch or more is a slip, a shorter one a gap. A driven gear no
//! tooth moves within a driver pitch of the start, or at all, has an idle start: a slip at the
//! start sized to the first drive, as the solver reports it.

use contact::{Event, EventKind};

/// The events of one run so far.
#[derive(Debug, Clone)]
pub(crate) struct Log {
    /// First driver angle of the run.
    phi0: f64,
    /// The driver's pitch (radians): what lost motion is measured in.
    pitch: f64,
    /// The ratio N1/N2: what the lag left by a loss is measured against.
    ratio: f64,
    events: Vec<Event>,
    /// A loss waiting to be sized: its index in `events`.
    pending: Option<usize>,
    /// Whether a tooth has moved the driven gear yet.
    driven_yet: bool,
    /// Where the driven gear stood at the start.
    theta0: f64,
}

impl Log {
    /// An empty log of a run from `phi0`, the driven gear at `theta0`.
    pub(crate) fn new(phi0: f64, theta0: f64, pitch: f64, ratio: f64) -> Self {
        Self {
            phi0,
            pitch,
            ratio,
            events: Vec::new(),
            pending: None,
            driven_yet: false,
            theta0,
        }
    }

    /// The events so far.
    pub(crate) fn events(&self) -> &[Event] {
        &self.events
    }

    /// Whether every event so far is sized and the idle start is decided: what a caller's
    /// early answer may be asked on.
    pub(crate) fn settled(&self) -> bool {
        self.pending.is_none() && self.driven_yet
    }

    /// The start had no free driven position: a blocked start.
    /// No tooth moved it, but it never turned idle either: the solver reports no idle start
    /// for a blocked one.
    pub(crate) fn blocked(&mut self, phi: f64, theta: f64, pair: (i64, i64)) {
        self.driven_yet = true;
        self.events
            .push(event(EventKind::BlockedAtStart, phi, theta, pair));
    }

    /// A tooth starts moving the driven gear at (φ, θ): a loss waiting is sized, and the idle
    /// start decided.
    pub(crate) fn drive(&mut self, phi: f64, theta: f64, pair: (i64, i64)) {
        if let Some(i) = self.pending.take() {
            let e = &mut self.events[i];
            e.lost_motion = (phi - e.phi) / self.pitch;
            e.resumed = true;
            e.resumed_by = Some(pair);
            e.lag = self.ratio * (phi - e.phi) - (theta - e.theta);
            if e.lost_motion >= 1.0 {
                e.kind = EventKind::Slip;
            }
        }
        if !self.driven_yet {
            self.driven_yet = true;
            let lost = (phi - self.phi0) / self.pitch;
            if lost >= 1.0 {
                let mut e = event(EventKind::Slip, self.phi0, self.theta0, pair);
                e.idle_start = true;
                e.lost_motion = lost;
                e.resumed = true;
                e.resumed_by = Some(pair);
                e.lag = self.ratio * (phi - self.phi0) - (theta - self.theta0);
                self.events.insert(0, e);
            }
        }
    }

    /// The tooth that moved the driven gear leaves it at (φ, θ): a loss begins.
    pub(crate) fn lose(&mut self, phi: f64, theta: f64, pair: (i64, i64)) {
        if self.pending.is_some() || !self.driven_yet {
            return;
        }
        self.pending = Some(self.events.len());
        self.events.push(event(EventKind::Gap, phi, theta, pair));
    }

    /// The driven gear is pinched at (φ, θ) by `pair` closing on it, and let go to `after`: a
    /// lock, which is drive too (a tooth moved it).
    pub(crate) fn lock(&mut self, phi: f64, theta: f64, after: f64, pair: (i64, i64)) {
        self.drive(phi, theta, pair);
        let mut e = event(EventKind::Lock, phi, theta, pair);
        e.theta_after = after;
        self.events.push(e);
    }

    /// The run ends at `phi_end`: a loss still waiting lasted to the end, and a gear never moved
    /// turned idle from the start.
    pub(crate) fn finish(mut self, phi_end: f64, theta_end: f64) -> Vec<Event> {
        if let Some(i) = self.pending.take() {
            let e = &mut self.events[i];
            e.lost_motion = (phi_end - e.phi) / self.pitch;
            e.lag = self.ratio * (phi_end - e.phi) - (theta_end - e.theta);
            if e.lost_motion >= 1.0 {
                e.kind = EventKind::Slip;
            }
        }
        if !self.driven_yet {
            let mut e = event(EventKind::Slip, self.phi0, self.theta0, (0, 0));
            e.idle_start = true;
            e.lost_motion = (phi_end - self.phi0) / self.pitch;
            self.events.insert(0, e);
        }
        self.events
    }
}

/// An event of `kind` at (φ, θ) on `pair`, not yet sized.
fn event(kind: EventKind, phi: f64, theta: f64, pair: (i64, i64)) -> Event {
    Event::new(kind, phi, theta, pair)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn a_loss_is_sized_by_the_next_drive_and_an_idle_start_by_the_first() {
        let mut log = Log::new(0.0, 0.5, 0.1, 0.5);
        log.drive(0.25, 0.6, (1, 2));
        log.lose(0.3, 0.62, (1, 2));
        log.drive(0.35, 0.64, (2, 2));
        log.lose(0.4, 0.66, (2, 2));
        let events = log.finish(0.6, 0.7);
        // The first drive came 2.5 pitches after the start: an idle start, first of all.
        assert!(events[0].idle_start && events[0].kind == EventKind::Slip);
        assert!((events[0].lost_motion - 2.5).abs() < 1e-12);
        // Half a pitch lost and resumed: a gap; two pitches lost to the end: a slip.
        assert_eq!(events[1].kind, EventKind::Gap);
        assert!(events[1].resumed && (events[1].lost_motion - 0.5).abs() < 1e-12);
        assert_eq!(events[2].kind, EventKind::Slip);
        assert!(!events[2].resumed && (events[2].lost_motion - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_gear_never_moved_turned_idle_throughout() {
        let log = Log::new(1.0, 0.0, 0.1, 1.0);
        let events = log.finish(1.05, 0.05);
        assert_eq!(events.len(), 1);
        assert!(events[0].idle_start && !events[0].resumed);
        assert!((events[0].lost_motion - 0.5).abs() < 1e-12);
    }
}
