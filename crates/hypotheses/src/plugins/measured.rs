//! `measured`: per-gear values from a table; registered with the embedded example table, whose
//! values are INVENTED. An experiment with a user's file uses [`crate::MeasuredTable::hypothesis`].

use std::sync::LazyLock;

use geometry::Gear;
use rand::RngCore;

use crate::measured::{MEASURED_PARAMS, MEASURED_SUMMARY};
use crate::{
    HypothesisError, MEASURED_EXAMPLE, Manufactured, MeasuredTable, Params, measured_from_ron,
};

/// The embedded example table, read once.
static EXAMPLE: LazyLock<Result<MeasuredTable, HypothesisError>> =
    LazyLock::new(|| measured_from_ron("measured-example.ron", MEASURED_EXAMPLE));

crate::hypothesis! {
    /// `measured` over the embedded example table.
    struct MeasuredExample;
    name: "measured",
    summary: MEASURED_SUMMARY,
    params: MEASURED_PARAMS,
    apply,
}

fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
    match &*EXAMPLE {
        Ok(table) => table.apply_scaled(gear, gear_name, params, rng),
        Err(e) => Err(e.clone()),
    }
}
