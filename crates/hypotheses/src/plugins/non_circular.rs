//! `non-circular`: gears that are not round (the paper assumes circular gears, assumption (1)).
//! The model in words is [`DETAILS`] (what `cargo xtask help` prints).

use std::f64::consts::TAU;

use geometry::Gear;
use rand::{Rng, RngCore};
use rand_distr::{Distribution, StandardNormal};

use crate::{About, HypothesisError, Kind, Manufactured, Param, Params, Plugin};

const RADIAL_ERROR: Param = Param::new(
    "radial_error",
    "0.02",
    "standard deviation of each tip's and each valley's radius about the design",
    Kind::ANY_NUMBER,
)
.unit("mm");

const LOBE: Param = Param::new(
    "lobe",
    "0",
    "amplitude of a once-per-turn out-of-round (radius + lobe·cos(angle − α), α random per gear)",
    Kind::ANY_NUMBER,
)
.unit("mm");

/// The model in words, printed by `cargo xtask help`.
const DETAILS: &str = "Every tip and every valley gets its own radius: the designed one plus `radial_error · z` (z a standard normal draw, one per vertex, clamped to ±4) plus a once-per-turn out-of-round `lobe · cos(angle − α)` with α uniform over the turn (one per gear). Tip and valley angles and the rotation centre are unchanged; the designed radii stay the gear's nominal ones (Gear::tip_radius, Gear::root_radius). A draw that puts a valley above one of its tips, or the axis outside the smallest valley, is an error naming the gear.";

/// The hypothesis.
struct NonCircular;

impl Plugin for NonCircular {
    const ABOUT: About = About {
        name: "non-circular",
        summary: "each tip and valley at its own radius, optionally with a once-per-turn lobe (assumption 1); angles unchanged",
        details: DETAILS,
    };
    const PARAMS: &[Param] = &[RADIAL_ERROR, LOBE];

    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
        let sd = params.non_negative_length(&RADIAL_ERROR, "non-circular")?;
        let lobe = params.non_negative_length(&LOBE, "non-circular")?;
        let alpha = rng.random::<f64>() * TAU;
        let mut radius = |designed: f64, angle: f64| {
            let z: f64 = StandardNormal.sample(rng);
            designed + sd * z.clamp(-4.0, 4.0) + lobe * (angle - alpha).cos()
        };
        let tips: Vec<f64> = gear
            .tip_angles()
            .iter()
            .map(|&a| radius(gear.tip_radius(), a))
            .collect();
        let roots: Vec<f64> = gear
            .valley_angles()
            .iter()
            .map(|&a| radius(gear.root_radius(), a))
            .collect();
        // The gear's rule names its radii by index; said instead of the parameters the user
        // set, with what the draw did.
        gear.clone().with_radii(tips, roots).map_err(|e| {
            let param = match (sd > 0.0, lobe > 0.0) {
                (true, true) => "parameters `radial_error` and `lobe`",
                (false, true) => "parameter `lobe`",
                _ => "parameter `radial_error`",
            };
            let what = if e.field.starts_with("rotation_centre") {
                "the smallest valley radius drawn reaches the gear's axis".to_string()
            } else if e.field.starts_with("root_radii") {
                "a valley was drawn at or above one of its tips".to_string()
            } else {
                "a radius drawn is not above 0".to_string()
            };
            HypothesisError::new(
                format!("gear `{gear_name}`: non-circular: {param}"),
                format!(
                    "too large for teeth {} mm high (radial_error = {} mm, lobe = {} mm): {what}",
                    registry::fmt_f64(gear.tip_radius() - gear.root_radius(), 3),
                    registry::fmt_number(sd),
                    registry::fmt_number(lobe)
                ),
            )
        })
    }
}

crate::register!(NonCircular);

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    #[test]
    fn radii_spread_as_stated_and_angles_stay() {
        let (h, p) = crate::test_support::with_defaults("non-circular");
        let designed = Gear::ideal(60, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(11);
        let mut errors = Vec::new();
        for _ in 0..100 {
            let g = h.apply(&designed, "b1", &p, &mut rng).unwrap();
            assert_eq!(g.tip_angles(), designed.tip_angles());
            assert_eq!(g.valley_angles(), designed.valley_angles());
            assert_eq!((g.tip_radius(), g.root_radius()), (15.0, 13.9));
            for k in 0..60 {
                errors.extend([g.tip_radius_of(k) - 15.0, g.root_radius_of(k) - 13.9]);
            }
        }
        crate::test_support::assert_spread(&errors, 0.02, 0.001, "radial error");
    }

    #[test]
    fn a_lobe_alone_is_once_per_turn_and_bad_draws_name_the_gear() {
        let h = crate::lookup("non-circular").unwrap();
        let designed = Gear::ideal(40, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(4);
        let lobe = Params::new(
            h,
            &[
                ("radial_error".into(), "0".into()),
                ("lobe".into(), "0.1".into()),
            ],
        )
        .unwrap();
        let g = h.apply(&designed, "a1", &lobe, &mut rng).unwrap();
        let d: Vec<f64> = (0..40).map(|k| g.tip_radius_of(k) - 15.0).collect();
        // Opposite tips are off by opposite amounts, spanning the whole lobe.
        for k in 0..20 {
            assert!((d[k] + d[k + 20]).abs() < 1e-12, "{d:?}");
        }
        let span = d.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - d.iter().copied().fold(f64::INFINITY, f64::min);
        assert!((span - 0.2).abs() < 0.01, "{span}");
        let none = Params::new(h, &[("radial_error".into(), "0".into())]).unwrap();
        let round = h.apply(&designed, "a1", &none, &mut rng).unwrap();
        assert_eq!(round.outline(), designed.outline());
        let wild = Params::new(h, &[("radial_error".into(), "5".into())]).unwrap();
        let e = h.apply(&designed, "a1", &wild, &mut rng).unwrap_err();
        assert!(
            e.what
                .starts_with("gear `a1`: non-circular: parameter `radial_error`"),
            "{e}"
        );
        assert!(!e.to_string().contains("radii["), "{e}");
        let bad = Params::new(h, &[("lobe".into(), "-1".into())]).unwrap();
        let e = h.apply(&designed, "a1", &bad, &mut rng).unwrap_err();
        assert!(e.to_string().contains("`lobe`"), "{e}");
    }
}
