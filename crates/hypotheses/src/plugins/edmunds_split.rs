//! `edmunds-split`: the paper's model (section 4), its split a parameter (`eccentric-only` and
//! `sinusoid-only` fix it; the code they share is [`crate::edmunds::EdmundsVariant`]).

use crate::Registration;
use crate::edmunds::{EdmundsVariant, RANDOM, SPLIT, SYSTEMATIC};

inventory::submit! {
    Registration(&EdmundsVariant {
        name: "edmunds-split",
        summary: "the paper's model: random tip error plus systematic amplitude A, split between a sinusoid of tip positions (random phase) and an eccentric axis (random direction)",
        params: &[RANDOM, SYSTEMATIC, SPLIT],
        split: None,
    })
}
