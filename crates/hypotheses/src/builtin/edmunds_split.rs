//! `edmunds-split`: the paper's model (section 4); also the shared code of `eccentric-only` and
//! `sinusoid-only`, which fix the split.

use geometry::Gear;

use crate::{EdmundsErrors, Hypothesis, HypothesisError, ParamSpec, Params, Registration};

/// Parameter `random`.
pub(super) const RANDOM: ParamSpec = ParamSpec {
    name: "random",
    default: 0.04,
    unit: "pitch",
    help: "sd of each tip's displacement, as a fraction of the pitch 360/N",
};

/// Parameter `systematic`.
pub(super) const SYSTEMATIC: ParamSpec = ParamSpec {
    name: "systematic",
    default: 0.5,
    unit: "deg",
    help: "systematic amplitude A",
};

/// Parameter `split`.
const SPLIT: ParamSpec = ParamSpec {
    name: "split",
    default: 0.5,
    unit: "",
    help: "share of A on the sinusoid of tip positions; the rest is an axis shift R·tan((1-split)·A)",
};

/// Edmunds' random and systematic errors with the split either a parameter or fixed.
pub(super) struct EdmundsVariant {
    /// Registered name.
    pub name: &'static str,
    /// One-line summary.
    pub summary: &'static str,
    /// Parameters: `random`, `systematic` and, when `split` is `None`, `split`.
    pub params: &'static [ParamSpec],
    /// `Some`: the split, fixed; `None`: the `split` parameter.
    pub split: Option<f64>,
}

impl Hypothesis for EdmundsVariant {
    fn name(&self) -> &'static str {
        self.name
    }

    fn summary(&self) -> &'static str {
        self.summary
    }

    fn params(&self) -> &'static [ParamSpec] {
        self.params
    }

    fn check(&self, params: &Params) -> Result<(), HypothesisError> {
        self.errors(params).check(self.name)
    }

    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        let errors = self.errors(params);
        errors.check(self.name)?;
        errors.apply(gear, gear_name, rng)
    }
}

impl EdmundsVariant {
    /// Edmunds' errors as `params` set them.
    fn errors(&self, params: &Params) -> EdmundsErrors {
        EdmundsErrors {
            random: params.get(RANDOM.name),
            systematic_deg: params.get(SYSTEMATIC.name),
            split: self.split.unwrap_or_else(|| params.get(SPLIT.name)),
            phase_deg: None,
        }
    }
}

inventory::submit! {
    Registration(&EdmundsVariant {
        name: "edmunds-split",
        summary: "the paper's model: random tip error plus systematic amplitude A, split between a sinusoid of tip positions (random phase) and an eccentric axis (random direction)",
        params: &[RANDOM, SYSTEMATIC, SPLIT],
        split: None,
    })
}
