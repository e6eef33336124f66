//! `measured`: per-gear values from a table; registered with the embedded example table, whose
//! values are INVENTED. An experiment with a user's file uses [`crate::MeasuredTable::hypothesis`].

use std::sync::LazyLock;

use geometry::Gear;

use crate::measured::{MEASURED_PARAMS, MEASURED_SUMMARY};
use crate::{
    Hypothesis, HypothesisError, MEASURED_EXAMPLE, MeasuredTable, ParamSpec, Params, Registration,
    measured_from_ron,
};

/// The embedded example table, read once.
static EXAMPLE: LazyLock<Result<MeasuredTable, HypothesisError>> =
    LazyLock::new(|| measured_from_ron("measured-example.ron", MEASURED_EXAMPLE));

/// `measured` over the embedded example table.
struct MeasuredExample;

impl Hypothesis for MeasuredExample {
    fn name(&self) -> &'static str {
        "measured"
    }

    fn summary(&self) -> &'static str {
        MEASURED_SUMMARY
    }

    fn params(&self) -> &'static [ParamSpec] {
        MEASURED_PARAMS
    }

    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        match &*EXAMPLE {
            Ok(table) => table.apply_scaled(gear, gear_name, params, rng),
            Err(e) => Err(e.clone()),
        }
    }
}

inventory::submit! { Registration(&MeasuredExample) }
