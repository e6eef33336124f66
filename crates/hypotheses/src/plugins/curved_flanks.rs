//! `curved-flanks`: tooth flanks that are circular arcs instead of straight lines (the paper
//! assumes straight flanks, assumption (2)).
//! The model in words is [`DETAILS`] (what `cargo xtask help` prints).

use geometry::Gear;
use rand::RngCore;
use rand_distr::{Distribution, StandardNormal};

use crate::{About, HypothesisError, Kind, Manufactured, Param, Params, Plugin};

const SAGITTA: Param = Param::new("sagitta", "0.05", "signed sagitta of every flank (the arc's greatest distance from its chord): + convex (bulging out of the tooth), - concave, 0 straight", Kind::ANY_NUMBER).unit("mm");

const SAGITTA_SPREAD: Param = Param::new(
    "sagitta_spread",
    "0",
    "standard deviation of a random addition to the sagitta, drawn once per gear",
    Kind::ANY_NUMBER,
)
.unit("mm");

/// The model in words, printed by `cargo xtask help`.
const DETAILS: &str = "Every flank of a gear becomes the arc through its two vertices with one signed sagitta `s` (mm, the arc's greatest distance from the chord): `s > 0` bulges out of the tooth (convex, as a file rounds a tooth), `s < 0` hollows it (concave). Each gear gets `s = sagitta + sagitta_spread · z`, z a standard normal draw per gear (none is drawn when the spread is 0). Tips, valleys, radii and rotation centre are kept, so the hypothesis composes after the others (e.g. `edmunds-split`, then `curved-flanks`). A sagitta too large for a gear's teeth (see geometry::Gear::with_flank_sagitta) is an error naming the gear.";

/// The hypothesis.
struct CurvedFlanks;

impl Plugin for CurvedFlanks {
    const ABOUT: About = About {
        name: "curved-flanks",
        summary: "every flank a circular arc of a signed sagitta, convex or concave, instead of a straight line (assumption 2); vertices unchanged",
        details: DETAILS,
    };
    const PARAMS: &[Param] = &[SAGITTA, SAGITTA_SPREAD];

    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured {
        let sagitta = params.value(&SAGITTA);
        if !sagitta.is_finite() {
            return Err(HypothesisError::parameter(
                "curved-flanks",
                &SAGITTA,
                format!(
                    "must be a finite length in mm (got {})",
                    registry::fmt_number(sagitta)
                ),
            ));
        }
        let spread = params.non_negative_length(&SAGITTA_SPREAD, "curved-flanks")?;
        let s = if spread > 0.0 {
            let z: f64 = StandardNormal.sample(rng);
            sagitta + spread * z
        } else {
            sagitta
        };
        // The gear's rule, said of the parameter the user set (the drawn s is the sagitta's, or
        // the sagitta's plus the spread's draw).
        gear.clone().with_flank_sagitta(s).map_err(|e| {
            let param = if spread > 0.0 {
                "parameters `sagitta` and `sagitta_spread`"
            } else {
                "parameter `sagitta`"
            };
            HypothesisError::new(
                format!("gear `{gear_name}`: curved-flanks: {param}"),
                format!(
                    "the sagitta s = {} mm drawn for this gear is too large for its teeth: {}",
                    registry::fmt_number(s),
                    e.rule
                ),
            )
        })
    }
}

crate::register!(CurvedFlanks);

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    use super::*;

    fn set(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
        pairs
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect()
    }

    #[test]
    fn defaults_curve_every_flank_and_keep_the_vertices() {
        let (h, p) = crate::test_support::with_defaults("curved-flanks");
        assert_eq!((p.value(&SAGITTA), p.value(&SAGITTA_SPREAD)), (0.05, 0.0));
        let designed = Gear::ideal(60, 15.0, 13.9)
            .unwrap()
            .with_radii(vec![15.0; 60], vec![13.9; 60])
            .unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let g = h.apply(&designed, "b1", &p, &mut rng).unwrap();
        assert_eq!(g.flank_sagitta(), 0.05);
        assert_eq!(g.outline(), designed.outline());
        assert_eq!(g.rotation_centre(), designed.rotation_centre());
        assert_eq!(g.with_flank_sagitta(0.0).unwrap(), designed);
    }

    #[test]
    fn zero_is_the_gear_unchanged_and_the_spread_is_per_gear() {
        let h = crate::lookup("curved-flanks").unwrap();
        let designed = Gear::ideal(40, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let zero = Params::new(h, &set(&[("sagitta", "0")])).unwrap();
        assert_eq!(h.apply(&designed, "a1", &zero, &mut rng).unwrap(), designed);
        let spread =
            Params::new(h, &set(&[("sagitta", "-0.02"), ("sagitta_spread", "0.01")])).unwrap();
        let s: Vec<f64> = (0..400)
            .map(|_| {
                h.apply(&designed, "a1", &spread, &mut rng)
                    .unwrap()
                    .flank_sagitta()
            })
            .collect();
        let mean = s.iter().sum::<f64>() / 400.0;
        let sd = (s.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / 400.0).sqrt();
        assert!((mean + 0.02).abs() < 0.002, "mean sagitta {mean}");
        assert!((sd - 0.01).abs() < 0.0015, "sd of the sagitta {sd}");
    }

    #[test]
    fn bad_values_name_the_parameter_or_the_gear() {
        let h = crate::lookup("curved-flanks").unwrap();
        let designed = Gear::ideal(40, 15.0, 13.9).unwrap();
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let mut refused = |pairs: &[(&str, &str)]| {
            let p = Params::new(h, &set(pairs)).unwrap();
            h.apply(&designed, "a1", &p, &mut rng).unwrap_err()
        };
        let e = refused(&[("sagitta_spread", "-1")]);
        assert!(e.to_string().contains("`sagitta_spread`"), "{e}");
        // A non-finite sagitta is refused when the parameters are read.
        let e = Params::new(h, &set(&[("sagitta", "inf")])).unwrap_err();
        assert!(e.to_string().contains("`sagitta`"), "{e}");
        // Far more than a quarter of a 1.5 mm flank: the gear's rule, naming the gear.
        let e = refused(&[("sagitta", "1")]);
        assert!(
            e.what
                .starts_with("gear `a1`: curved-flanks: parameter `sagitta`"),
            "{e}"
        );
        assert!(!e.to_string().contains("flank_sagitta"), "{e}");
    }
}
