//! `measured`: per-gear values from a table; registered with the embedded example table, whose
//! values are INVENTED. An experiment with a user's file uses [`crate::MeasuredTable::hypothesis`].

use std::sync::LazyLock;

use geometry::Gear;
use rand::RngCore;

use crate::measured::{MEASURED, MEASURED_PARAMS};
use crate::{
    About, HypothesisError, MEASURED_EXAMPLE, Manufactured, MeasuredTable, Param, Params, Plugin,
    measured_from_ron,
};

/// The embedded example table, read once.
static EXAMPLE: LazyLock<Result<MeasuredTable, HypothesisError>> =
    LazyLock::new(|| measured_from_ron("measured-example.ron", MEASURED_EXAMPLE));

/// `measured` over the embedded example table.
struct MeasuredExample;

impl Plugin for MeasuredExample {
    const ABOUT: About = MEASURED;
    const PARAMS: &[Param] = MEASURED_PARAMS;

    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
        match &*EXAMPLE {
            Ok(table) => table.apply_scaled(gear, gear_name, params, rng),
            Err(e) => Err(e.clone()),
        }
    }
}

crate::register!(MeasuredExample);
