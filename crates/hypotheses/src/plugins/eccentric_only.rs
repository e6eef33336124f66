//! `eccentric-only`: `edmunds-split` with the whole systematic error on the axis (split 0).

use crate::edmunds::{EdmundsVariant, RANDOM, SYSTEMATIC};
use crate::{About, Param};

/// Edmunds' errors, all of A on the axis.
struct EccentricOnly;

impl EdmundsVariant for EccentricOnly {
    const ABOUT: About = About {
        name: "eccentric-only",
        summary: "edmunds-split with split 0: random tip error, all of A as an axis shift R·tan(A) (the paper's Figure 5 A)",
        details: "",
    };
    const PARAMS: &[Param] = &[RANDOM, SYSTEMATIC];
    const SPLIT: Option<f64> = Some(0.0);
}

crate::register!(EccentricOnly);
