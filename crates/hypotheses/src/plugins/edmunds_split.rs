//! `edmunds-split`: the paper's model (section 4), its split a parameter (`eccentric-only` and
//! `sinusoid-only` fix it; the code they share is [`crate::edmunds::EdmundsVariant`]).

use crate::edmunds::{EdmundsVariant, RANDOM, SPLIT, SYSTEMATIC};
use crate::{About, Param};

/// Edmunds' errors, the share of A on the sinusoid a parameter.
struct EdmundsSplit;

impl EdmundsVariant for EdmundsSplit {
    const ABOUT: About = About {
        name: "edmunds-split",
        summary: "the paper's model: random tip error plus systematic amplitude A, split between a sinusoid of tip positions (random phase) and an eccentric axis (random direction)",
        details: "",
    };
    const PARAMS: &[Param] = &[RANDOM, SYSTEMATIC, SPLIT];
    const SPLIT: Option<f64> = None;
}

crate::register!(EdmundsSplit);
