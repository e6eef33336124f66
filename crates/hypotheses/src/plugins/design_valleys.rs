//! `design-valleys`: every valley put back at its design angle, so that a tooth error moves the
//! tip alone - a reading of the paper's section 4 ("the position of the tooth tips was assigned
//! the normalized random variation"), against its own next sentence, that "the valleys were
//! positioned symmetrically between the two tip positions, already affected by the error".
//! Stacked after the paper's model: `edmunds-split+design-valleys`.
//! The model in words is [`DETAILS`] (what `cargo xtask help` prints).

use std::f64::consts::TAU;

use geometry::Gear;
use rand::RngCore;

use crate::edmunds::with_valleys_at;
use crate::{About, HypothesisError, Manufactured, Params, Plugin};

/// The model in words, printed by `cargo xtask help`.
const DETAILS: &str = "Valley k is put at its design angle 360·(k + 1/2)/N degrees of the gear frame (midway between the design tips), whatever the hypotheses before it did to the tips; tips, radii and rotation centre are kept. After `edmunds-split` this reads the paper's tooth error as moving the tip alone, the flanks pivoting about fixed valleys, instead of the whole tooth (valleys midway between the displaced tips, the paper's own sentence and the default). A valley must stay strictly between its tips: a tip moved by half a pitch or more is refused, naming the gear.";

/// The hypothesis.
struct DesignValleys;

impl Plugin for DesignValleys {
    const ABOUT: About = About {
        name: "design-valleys",
        summary: "every valley at its design angle, so that a tooth error moves the tip alone (a reading of section 4; stack it after the errors: edmunds-split+design-valleys)",
        details: DETAILS,
    };

    fn apply(gear: &Gear, gear_name: &str, _: &Params, _: &mut dyn RngCore) -> Manufactured {
        let n = gear.teeth();
        let valleys = (0..n).map(|k| TAU * (k as f64 + 0.5) / n as f64).collect();
        with_valleys_at(gear, valleys).map_err(|e| {
            HypothesisError::new(
                format!("design-valleys: gear `{gear_name}`"),
                format!(
                    "a tip has moved past its design valley ({}: {})",
                    e.field, e.rule
                ),
            )
        })
    }
}

crate::register!(DesignValleys);

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::test_support::with_defaults;

    /// `design-valleys` (as registered) applied to `moved`, a gear named `name`.
    fn put_back(moved: &Gear, name: &str) -> Manufactured {
        let (h, params) = with_defaults("design-valleys");
        h.apply(moved, name, &params, &mut ChaCha8Rng::seed_from_u64(1))
    }

    #[test]
    fn valleys_go_back_to_their_design_angles_and_tips_stay() {
        let n = 30;
        let pitch = TAU / n as f64;
        // Tips moved by up to a fifth of a pitch, valleys midway between them.
        let tips: Vec<f64> = (0..n)
            .map(|k| pitch * k as f64 + 0.2 * pitch * ((k as f64) * 1.7).sin())
            .collect();
        let moved = Gear::new(10.0, 8.9, tips.clone(), geometry::Vec2::zeros()).unwrap();
        let g = put_back(&moved, "x").unwrap();
        assert_eq!(g.tip_angles(), tips.as_slice());
        for (k, v) in g.valley_angles().iter().enumerate() {
            assert!(
                (v - pitch * (k as f64 + 0.5)).abs() < 1e-12,
                "valley {k}: {v}"
            );
        }
    }

    #[test]
    fn a_tip_past_its_design_valley_is_refused_naming_the_gear() {
        let n = 10;
        let pitch = TAU / n as f64;
        let mut tips: Vec<f64> = (0..n).map(|k| pitch * k as f64).collect();
        tips[3] += 0.6 * pitch;
        let moved = Gear::new(10.0, 8.9, tips, geometry::Vec2::zeros()).unwrap();
        let e = put_back(&moved, "b1").unwrap_err().to_string();
        assert!(e.contains("gear `b1`"), "{e}");
    }
}
