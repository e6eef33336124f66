//! `sinusoid-only`: `edmunds-split` with the whole systematic error on the tip positions (split 1).

use crate::Registration;
use crate::edmunds::{EdmundsVariant, RANDOM, SYSTEMATIC};

inventory::submit! {
    Registration(&EdmundsVariant {
        name: "sinusoid-only",
        summary: "edmunds-split with split 1: random tip error, all of A as a sinusoid of tip positions (the paper's Figure 5 C)",
        params: &[RANDOM, SYSTEMATIC],
        split: Some(1.0),
    })
}
