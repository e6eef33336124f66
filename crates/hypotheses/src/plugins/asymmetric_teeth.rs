//! `asymmetric-teeth`: each valley cut off-centre between its two tips, so a tooth's two flanks
//! differ in slope (the paper assumes symmetric teeth, assumption (3)).
//! The model in words is [`DETAILS`] (what `cargo xtask help` prints).

use geometry::Gear;
use rand::RngCore;
use rand_distr::{Distribution, StandardNormal};

use crate::edmunds::with_valleys_at;
use crate::{About, HypothesisError, Kind, Manufactured, Param, Params, Plugin};

const VALLEY_SHIFT: Param = Param::new("valley_shift", "0.05", "standard deviation of each valley's displacement from midway between its tips, as a fraction of that tip gap (the valley is clamped to 0.05 .. 0.95 of the gap)", Kind::ANY_NUMBER).unit("gap");

/// The valley's position in its gap is clamped to `[LOWEST, 1 - LOWEST]`.
const LOWEST: f64 = 0.05;

/// The model in words, printed by `cargo xtask help`.
const DETAILS: &str = "Valley k is placed at the fraction `0.5 + s·z` of the angular gap from tip k to tip k + 1, z a standard normal draw and s the parameter `valley_shift`; the fraction is clamped to 0.05 ..= 0.95 so that the valley stays strictly between its tips (no flank degenerates). Tips, radii and rotation centre are unchanged.";

/// The hypothesis.
struct AsymmetricTeeth;

impl Plugin for AsymmetricTeeth {
    const ABOUT: About = About {
        name: "asymmetric-teeth",
        summary: "each valley displaced from midway between its tips, so the teeth lean (assumption 3); tips unchanged",
        details: DETAILS,
    };
    const PARAMS: &[Param] = &[VALLEY_SHIFT];

    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
        let shift = params.value(&VALLEY_SHIFT);
        if !(0.0..=1.0).contains(&shift) {
            return Err(HypothesisError::parameter(
                "asymmetric-teeth",
                &VALLEY_SHIFT,
                format!(
                    "must be between 0 and 1 (a fraction of the tip gap; got {})",
                    registry::fmt_number(shift)
                ),
            ));
        }
        let valleys = (0..gear.teeth() as i64)
            .map(|k| {
                let (lo, hi) = (gear.tip_angle(k), gear.tip_angle(k + 1));
                let z: f64 = StandardNormal.sample(rng);
                let at = (0.5 + shift * z).clamp(LOWEST, 1.0 - LOWEST);
                lo + at * (hi - lo)
            })
            .collect();
        with_valleys_at(gear, valleys).map_err(|e| HypothesisError::gear(gear_name, e))
    }
}

crate::register!(AsymmetricTeeth);

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    /// Where each valley of `g` sits in its tip gap, 0 at tip k and 1 at tip k + 1.
    fn fractions(g: &Gear) -> Vec<f64> {
        (0..g.teeth())
            .map(|k| {
                let (lo, hi) = (g.tip_angle(k as i64), g.tip_angle(k as i64 + 1));
                (g.valley_angles()[k] - lo) / (hi - lo)
            })
            .collect()
    }

    #[test]
    fn valleys_spread_as_stated_and_tips_stay() {
        let (h, p) = crate::test_support::with_defaults("asymmetric-teeth");
        // Uneven tips: the shift is a fraction of each gap, not of the nominal pitch.
        let designed = Gear::new(
            15.0,
            13.9,
            (0..60)
                .map(|k| std::f64::consts::TAU * (f64::from(k) + 0.3 * f64::from(k % 2)) / 60.0)
                .collect(),
            geometry::Vec2::new(0.1, 0.0),
        )
        .unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(8);
        let mut shifts = Vec::new();
        for _ in 0..200 {
            let g = h.apply(&designed, "b1", &p, &mut rng).unwrap();
            assert_eq!(g.tip_angles(), designed.tip_angles());
            assert_eq!(g.tip_radius(), designed.tip_radius());
            assert_eq!(g.root_radius(), designed.root_radius());
            assert_eq!(g.rotation_centre(), designed.rotation_centre());
            shifts.extend(fractions(&g).iter().map(|f| f - 0.5));
        }
        crate::test_support::assert_spread(&shifts, 0.05, 0.003, "shift");
    }

    #[test]
    fn large_shifts_are_clamped_inside_the_gap_and_zero_is_midway() {
        let h = crate::lookup("asymmetric-teeth").unwrap();
        let g = Gear::ideal(30, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(3);
        let wild = Params::new(h, &[("valley_shift".into(), "1".into())]).unwrap();
        let f = fractions(&h.apply(&g, "a1", &wild, &mut rng).unwrap());
        assert!(
            f.iter().all(|f| (0.05 - 1e-12..=0.95 + 1e-12).contains(f)),
            "{f:?}"
        );
        assert!(
            f.iter().any(|f| (f - 0.05).abs() < 1e-9),
            "some clamp low: {f:?}"
        );
        assert!(
            f.iter().any(|f| (f - 0.95).abs() < 1e-9),
            "some clamp high: {f:?}"
        );
        let none = Params::new(h, &[("valley_shift".into(), "0".into())]).unwrap();
        assert_eq!(h.apply(&g, "a1", &none, &mut rng).unwrap(), g);
        let bad = Params::new(h, &[("valley_shift".into(), "1.5".into())]).unwrap();
        let e = h.apply(&g, "a1", &bad, &mut rng).unwrap_err();
        assert!(e.to_string().contains("between 0 and 1"), "{e}");
    }
}
