//! `ratio-mismatch`: each gear cut with its own module, so two meshing gears' radii no longer
//! stand in the ratio of their tooth counts (the paper's assumption (5), section 6).
//! The model in words is [`DETAILS`] (what `cargo xtask help` prints).

use geometry::Gear;
use rand::RngCore;
use rand_distr::{Distribution, StandardNormal};

use crate::{About, HypothesisError, Kind, Manufactured, Param, Params, Plugin};

const MODULE_SPREAD: Param = Param::new("module_spread", "3.3", "standard deviation of each gear's module about the design (3.3 % makes meshing gears differ by 3.7 % on average, as Freeth et al. 2021 measured)", Kind::ANY_NUMBER).unit("%");

/// The model in words, printed by `cargo xtask help`.
const DETAILS: &str = "Freeth et al. (2021) report the modules of meshing gears differing by 3.7 % on average and by up to 7.6 %. Here each gear's module is the designed one times (1 + m·z), z a standard normal draw, so tip radius and tooth height scale together and the tip angles stay. Two gears' modules then differ by about 1.13·m on average: m = 3.3 % gives the reported 3.7 %. The arbors stay where the design puts them, so the clearance of the mesh changes with the radii (a larger gear reaches deeper).";

/// The hypothesis.
struct RatioMismatch;

impl Plugin for RatioMismatch {
    const ABOUT: About = About {
        name: "ratio-mismatch",
        summary: "each gear cut with its own module (radius and tooth height scaled together), so R1/R2 != N1/N2 (assumption 5)",
        details: DETAILS,
    };
    const PARAMS: &[Param] = &[MODULE_SPREAD];

    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
        let spread = params.value(&MODULE_SPREAD);
        if !(0.0..50.0).contains(&spread) {
            return Err(HypothesisError::parameter(
                "ratio-mismatch",
                &MODULE_SPREAD,
                format!(
                    "must be at least 0 and below 50 % (got {})",
                    registry::fmt_number(spread)
                ),
            ));
        }
        let z: f64 = StandardNormal.sample(rng);
        // A module cannot shrink to nothing: beyond four standard deviations is not a gear.
        let scale = 1.0 + spread / 100.0 * z.clamp(-4.0, 4.0);
        let tip = gear.tip_radius() * scale;
        let root = tip - gear.tooth_height() * scale;
        Gear::new(
            tip,
            root,
            gear.tip_angles().to_vec(),
            gear.rotation_centre(),
        )
        .map_err(|e| HypothesisError::gear(gear_name, e))
    }
}

crate::register!(RatioMismatch);

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    #[test]
    fn modules_spread_as_stated_and_the_teeth_keep_their_angles() {
        let (h, p) = crate::test_support::with_defaults("ratio-mismatch");
        let g = Gear::ideal(60, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let n = 4000;
        let mut diffs = 0.0;
        for _ in 0..n {
            let a = h.apply(&g, "a1", &p, &mut rng).unwrap();
            let b = h.apply(&g, "b1", &p, &mut rng).unwrap();
            assert_eq!(a.tip_angles(), g.tip_angles());
            let (sa, sb) = (a.tip_radius() / 15.0, b.tip_radius() / 15.0);
            assert!(
                (a.tooth_height() / 1.1 - sa).abs() < 1e-12,
                "height scales with radius"
            );
            diffs += (sa - sb).abs();
        }
        // Mean |difference| of two modules: 2 m / sqrt(pi) = 3.72 % for m = 3.3 %.
        let mean = diffs / f64::from(n) * 100.0;
        assert!(
            (mean - 3.72).abs() < 0.15,
            "mean module difference {mean} %"
        );
        let bad = Params::new(h, &[("module_spread".into(), "60".into())]).unwrap();
        let e = h.apply(&g, "a1", &bad, &mut rng).unwrap_err();
        assert!(e.to_string().contains("below 50 %"), "{e}");
    }
}
