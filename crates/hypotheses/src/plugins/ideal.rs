//! `ideal`: no manufacturing error.

use geometry::Gear;
use rand::RngCore;

use crate::{Manufactured, Params};

crate::hypothesis! {
    /// The gear exactly as designed.
    struct Ideal;
    name: "ideal",
    summary: "no manufacturing error: the gear exactly as designed",
    params: &[],
    apply,
}

fn apply(gear: &Gear, _: &str, _: &Params, _: &mut dyn RngCore) -> Manufactured {
    Ok(gear.clone())
}
