//! `sinusoid-only`: `edmunds-split` with the whole systematic error on the tip positions (split 1).

use crate::edmunds::{EdmundsVariant, RANDOM, SYSTEMATIC};
use crate::{About, Param};

/// Edmunds' errors, all of A on the tips.
struct SinusoidOnly;

impl EdmundsVariant for SinusoidOnly {
    const ABOUT: About = About {
        name: "sinusoid-only",
        summary: "edmunds-split with split 1: random tip error, all of A as a sinusoid of tip positions (the paper's Figure 5 C)",
        details: "",
    };
    const PARAMS: &[Param] = &[RANDOM, SYSTEMATIC];
    const SPLIT: Option<f64> = Some(1.0);
}

crate::register!(SinusoidOnly);
