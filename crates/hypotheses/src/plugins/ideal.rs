//! `ideal`: no manufacturing error.

use geometry::Gear;

use crate::{Hypothesis, HypothesisError, ParamSpec, Params, Registration};

/// The gear exactly as designed.
struct Ideal;

impl Hypothesis for Ideal {
    fn name(&self) -> &'static str {
        "ideal"
    }

    fn summary(&self) -> &'static str {
        "no manufacturing error: the gear exactly as designed"
    }

    fn params(&self) -> &'static [ParamSpec] {
        &[]
    }

    fn apply(
        &self,
        gear: &Gear,
        _gear_name: &str,
        _params: &Params,
        _rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        Ok(gear.clone())
    }
}

inventory::submit! { Registration(&Ideal) }
