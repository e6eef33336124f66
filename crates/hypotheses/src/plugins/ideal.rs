//! `ideal`: no manufacturing error.

use geometry::Gear;
use rand::RngCore;

use crate::{About, Manufactured, Params, Plugin};

/// The gear exactly as designed.
struct Ideal;

impl Plugin for Ideal {
    const ABOUT: About = About {
        name: "ideal",
        summary: "no manufacturing error: the gear exactly as designed",
        details: "",
    };

    fn apply(gear: &Gear, _: &str, _: &Params, _: &mut dyn RngCore) -> Manufactured {
        Ok(gear.clone())
    }
}

crate::register!(Ideal);
