//! `eccentric-only`: `edmunds-split` with the whole systematic error on the axis (split 0).

use crate::Registration;
use crate::edmunds::{EdmundsVariant, RANDOM, SYSTEMATIC};

inventory::submit! {
    Registration(&EdmundsVariant {
        name: "eccentric-only",
        summary: "edmunds-split with split 0: random tip error, all of A as an axis shift R·tan(A) (the paper's Figure 5 A)",
        params: &[RANDOM, SYSTEMATIC],
        split: Some(0.0),
    })
}
