//! `stepped-nearest`: the paper's kind of stepped area program, the driven gear left where it was
//! after each driver step and turned to the nearest free position either way.

use crate::stepped::{Program, run as stepped};
use crate::{About, Outcome, Plugin, Trial, Want};
use polycheck::stepped::Correction;

/// The stepped area program whose correction may also turn the driven gear back.
struct SteppedNearest;

impl Plugin for SteppedNearest {
    const ABOUT: About = About {
        name: "stepped-nearest",
        summary: "the paper's kind of stepped area program (driver steps of 1/20 pitch, overlap area up to 0.0001 mm^2 ignored), the driven gear left where it was and turned to the nearest free position either way; a jam where none lies within a driven pitch either way",
        details: "The paper's program 'is based on detecting intersections between the areas of the gears' and lets the driven gear 'rotate freely ... until movement was possible again', without saying which way. `polycheck::stepped` (no code shared with the solver) turns the driver by fixed steps of 1/20 of its pitch; after each step the driven gear stays where it was and, where the overlap area of the two outlines exceeds 0.0001 mm^2, is turned to the nearest position where it does not, forward or back (searched in steps of 1/64 of a driven pitch on both sides at once, then bisected): a driver tooth behind that has caught it up turns it forward, as the forward-only program does, and one ahead that has closed on it (a strike, for the push model) turns it back. A jam is a step with no such position within a driven pitch either way; the driven gear is then let go to the first free position ahead. It starts touching, as the tables start. A step whose test finds contact is drive; steps without it are a loss of drive.",
    };

    fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
        stepped(trial, want, &Program::with(Correction::Nearest))
    }
}

crate::register!(SteppedNearest);
