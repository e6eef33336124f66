//! `carried`: the driven gear carried at the nominal ratio between contacts, stopped forward or
//! back by whichever flank it meets, pinched from both sides a lock.

use crate::carry::Placement;
use crate::{About, Outcome, Plugin, Trial, Want};

/// The driven gear carried at the nominal ratio and stopped by either flank.
struct Carried;

impl Plugin for Carried {
    const ABOUT: About = About {
        name: "carried",
        summary: "carried at the nominal ratio N1/N2 between contacts, pushed by a driver tooth behind or held back by one ahead, a lock where both pinch it; let go to the next free position ahead after a jam",
        details: "Between contacts the driven gear turns at the nominal ratio, θ' = N1/N2 (equation [1]), as a program that turns both gears by their nominal steps would move it. It is stopped by whichever flank it meets: a driver tooth behind catching it up pushes it (θ follows the upper end of that pair's obstacle) until the end rises more slowly than the ratio; a driver tooth ahead that it runs into holds it back (θ follows the lower end, and the gear may turn backwards) until the end runs away faster than the ratio. Where the free interval between the two closes on it, it is pinched from both sides: a lock, after which it is let go to the next free position ahead, as the push model does. It starts as the push model starts, touching a driver tooth behind. Every transition is a root of the exact obstacle ends or of their slopes against the ratio (`motion::carry`). Drive is a tooth moving the gear; a graze that moves nothing is not.",
    };

    fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
        crate::carry::outcome(trial, want, Placement::Touching)
    }
}

crate::register!(Carried);
