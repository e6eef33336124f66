//! `sync`: what a clockmaker calls failure - the train stops, or a pointer loses step.

use crate::{About, Event, EventKind, Params, Plugin};

/// Stops and lost synchronisation; brief gaps are lost motion, not failures.
struct Sync;

impl Plugin for Sync {
    const ABOUT: About = About {
        name: "sync",
        summary: "jam: lock or blocked start (the train stops); disengagement: a slip, or a strike that moved the tooth phase (a pointer out of step)",
        details: "A clockmaker's failure: the mechanism stops, or a pointer loses synchronisation. The train stops at a lock (the driven gear held from both sides) or a start with no free position. A strike is one-sided: a free driven gear is knocked back by the incoming tooth rather than stopping the train, so it fails only if the tooth phase moved by it (the driven gear a tooth out of step). A slip (drive lost for a driver pitch or more, or resumed out of step) is lost synchronisation. A hand-over gap that resumes in step within a pitch is lost motion, reported in the event log with its size, not a failure.",
    };
    const JAMS: &str = "lock, blocked start (the train stops)";
    const DISENGAGEMENTS: &str = "slip, or a strike that moved the tooth phase";

    fn is_jam(e: &Event, _: &Params) -> bool {
        matches!(e.kind, EventKind::Lock | EventKind::BlockedAtStart)
    }

    fn is_disengagement(e: &Event, _: &Params) -> bool {
        match e.kind {
            EventKind::Slip => true,
            EventKind::Strike => e.phase_shift != 0,
            _ => false,
        }
    }
}

crate::register!(Sync);
