//! `carried-drawn`: both initial angles drawn, the driven gear carried at the nominal ratio from
//! its own drawn angle and stopped by whichever flank it meets.

use crate::carry::Placement;
use crate::{About, Outcome, Plugin, Trial, Want};

/// The carried motion from the driven gear's own drawn angle.
struct CarriedDrawn;

impl Plugin for CarriedDrawn {
    const ABOUT: About = About {
        name: "carried-drawn",
        summary: "`carried` with the driven gear placed at its own drawn initial angle (not touching), moved to the nearest free position either way if it overlaps",
        details: "The paper draws 'the Initial Angle ... uniform ... within the angular pitch range of each driving gear' and says both Initial Angles θo and φo place the curve. Read as both gears placed at drawn angles, the driven gear does not start touching: it starts where its own angle puts it (uniform over its pitch, drawn by the caller from a stream of its own), moved to the nearest free position either way if that overlaps a driver tooth (as a program that corrects the driven gear both ways would place it), and is then carried at the nominal ratio and stopped by whichever flank it meets, exactly as under `carried`. A gear starting in the backlash meets nothing until a driver tooth behind catches it up or it runs into one ahead. Where the caller fixes the start (Figure 2's θ'o = θ'(0)) it is `carried`.",
    };

    fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
        let placement = trial.drawn.map_or(Placement::Touching, Placement::At);
        crate::carry::outcome(trial, want, placement)
    }
}

crate::register!(CarriedDrawn);
