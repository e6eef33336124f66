//! `stepped-carried`: the paper's kind of stepped area program, the driven gear carried by the
//! nominal ratio of each driver step, then turned to the nearest free position either way.

use crate::stepped::{Program, run as stepped};
use crate::{About, Outcome, Plugin, Trial, Want};
use polycheck::stepped::Correction;

/// The stepped area program turning both gears by their nominal steps, corrected either way.
struct SteppedCarried;

impl Plugin for SteppedCarried {
    const ABOUT: About = About {
        name: "stepped-carried",
        summary: "the paper's kind of stepped area program (driver steps of 1/20 pitch, overlap area up to 0.0001 mm^2 ignored), the driven gear carried by N1/N2 of each driver step and then turned to the nearest free position either way; a jam where none lies within a driven pitch either way",
        details: "The stepped reading of `carried`: a program that turns both gears by their nominal steps (the driver by 1/20 of its pitch, the driven gear by N1/N2 of that, equation [1]) and then, where the overlap area of the two outlines exceeds 0.0001 mm^2 (`polycheck::stepped`), turns the driven gear to the nearest position where it does not, forward or back (searched in steps of 1/64 of a driven pitch on both sides at once, then bisected). A jam is a step with no such position within a driven pitch either way; the driven gear is then let go to the first free position ahead. It starts touching, as the tables start. A step whose test finds contact is drive; steps without it are a loss of drive.",
    };

    fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
        stepped(trial, want, &Program::with(Correction::CarriedNearest))
    }
}

crate::register!(SteppedCarried);
