//! `eccentric-only`: `edmunds-split` with the whole systematic error on the axis (split 0).

use super::edmunds_split::{EdmundsVariant, RANDOM, SYSTEMATIC};
use crate::Registration;

inventory::submit! {
    Registration(&EdmundsVariant {
        name: "eccentric-only",
        summary: "edmunds-split with split 0: random tip error, all of A as an axis shift R·tan(A) (the paper's Figure 5 A)",
        params: &[RANDOM, SYSTEMATIC],
        split: Some(0.0),
    })
}
