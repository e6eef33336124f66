//! Edmunds' error model as the paper applies it (section 4), shared by several hypotheses, and
//! [`manufacture`], the checked way every hypothesis builds its gear.

use std::f64::consts::TAU;

use geometry::{Gear, GeometryError, Vec2, polar};
use rand::Rng;
use rand_distr::{Distribution, StandardNormal};

use registry::fmt_number;

use crate::{About, HypothesisError, Kind, Param, Params, Plugin};

/// Random and systematic errors of one gear, after Edmunds (2011) as the paper adapts them.
///
/// - *Random*: each tip is displaced by an independent normal draw with standard deviation
///   `random × pitch` (pitch = 360°/N).
/// - *Systematic*, amplitude `A = systematic_deg`: `split · A` degrees go to a sinusoid of tip
///   position (tip k moves by `split·A·sin(t_k + phase)` degrees, `t_k` its designed angle) and
///   `(1 − split) · A` to an eccentric rotation centre at distance `R·tan((1 − split)·A)` from the
///   geometric centre, in a uniformly random direction. The paper's split is 0.5: 5° gives a 2.5°
///   sinusoid and an axis shift of 100 mm · tan 2.5° ≈ 4.37 mm on a 100 mm gear.
///
/// Draws, in this order whatever the values: the phase (uniform in [0, 2π), used unless
/// `phase_deg` is given), the eccentricity direction (uniform in [0, 2π)), then one standard
/// normal per tip in tip order. So one stream gives the same gear shape for any amplitudes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EdmundsErrors {
    /// Standard deviation of each tip's displacement, as a fraction of the pitch.
    pub random: f64,
    /// Systematic amplitude A, degrees.
    pub systematic_deg: f64,
    /// Share of A put on the sinusoid (the rest goes to the eccentricity), from 0 to 1.
    pub split: f64,
    /// Phase of the sinusoid in degrees; `None`: drawn uniformly.
    pub phase_deg: Option<f64>,
}

/// The largest random tooth error accepted: 0.1 of the pitch (the paper studies 0.035-0.065).
/// Neighbouring tips then cross (a refused gear) with probability about 10^-12 per tooth, so
/// a value is accepted or refused whatever the number of trials; at 0.2 it is 2·10^-4 per tooth,
/// and a run of 50 trials was refused where a run of 2 passed.
pub const MAX_RANDOM: f64 = 0.1;

/// Distance of the rotation centre from the geometric centre for an eccentricity error of
/// `angle_deg` degrees on a gear of tip radius `tip_radius`: `R·tan(angle)`.
pub fn eccentricity(tip_radius: f64, angle_deg: f64) -> f64 {
    tip_radius * angle_deg.to_radians().tan()
}

impl EdmundsErrors {
    /// Checks the values; an error names `source` (e.g. the hypothesis) and the field.
    pub fn check(&self, source: &str) -> Result<(), HypothesisError> {
        let bad = |field: &str, rule: String| {
            Err(HypothesisError::new(format!("{source}: {field}"), rule))
        };
        if !(self.random.is_finite() && self.random >= 0.0) {
            return bad(
                "random",
                format!(
                    "must be a finite number >= 0 (got {})",
                    fmt_number(self.random)
                ),
            );
        }
        if self.random > MAX_RANDOM {
            return bad(
                "random",
                format!(
                    "must be at most {MAX_RANDOM} of the pitch (got {}): with a larger spread neighbouring tips cross in some draws, so whether a run fails would depend on how many trials it draws",
                    fmt_number(self.random)
                ),
            );
        }
        if !(self.systematic_deg.is_finite() && self.systematic_deg >= 0.0) {
            return bad(
                "systematic",
                format!(
                    "must be a finite number of degrees >= 0 (got {})",
                    fmt_number(self.systematic_deg)
                ),
            );
        }
        if !(0.0..=1.0).contains(&self.split) {
            return bad(
                "split",
                format!("must be between 0 and 1 (got {})", fmt_number(self.split)),
            );
        }
        let eccentric = (1.0 - self.split) * self.systematic_deg;
        if eccentric >= 90.0 {
            return bad(
                "systematic",
                format!(
                    "its eccentric share (1 - split)·A = {}° must be less than 90° (R·tan of it is the axis shift)",
                    fmt_number(eccentric)
                ),
            );
        }
        if let Some(p) = self.phase_deg
            && !(p.is_finite() && p.abs() <= registry::MAX_ANGLE_DEG)
        {
            return bad(
                "phase",
                format!(
                    "must be a finite number of degrees, at most {} either way (beyond, a double holds the angle too coarsely to mean one; got {})",
                    fmt_number(registry::MAX_ANGLE_DEG),
                    fmt_number(p)
                ),
            );
        }
        Ok(())
    }

    /// `gear` (named `gear_name`) with these errors drawn from `rng`; see the type's docs.
    ///
    /// Errors: values breaking [`EdmundsErrors::check`]; a draw that would put the tips out of
    /// order or an axis shift outside the root circle (naming the gear and the rule).
    pub fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        self.check(&format!("gear `{gear_name}`: error values"))?;
        let drawn_phase = rng.random::<f64>() * TAU;
        let direction = rng.random::<f64>() * TAU;
        let phase = self.phase_deg.map_or(drawn_phase, f64::to_radians);
        let amplitude = (self.split * self.systematic_deg).to_radians();
        let sd = self.random * gear.pitch();
        let mut tips = Vec::with_capacity(gear.teeth());
        for &t in gear.tip_angles() {
            let z: f64 = StandardNormal.sample(rng);
            tips.push(t + sd * z + amplitude * (t + phase).sin());
        }
        let shift = eccentricity(gear.tip_radius(), (1.0 - self.split) * self.systematic_deg);
        let centre = gear.rotation_centre() + polar(shift, direction);
        manufacture(gear, gear_name, tips, centre)
    }
}

/// `gear` with new tip angles (radians) and rotation centre, radii unchanged: the checked way a
/// hypothesis builds its result.
///
/// Tips are not sorted: displaced tips that are no longer strictly increasing (or that pass the
/// first tip one turn on) are an error naming the gear, the tip and the rule, as is a changed
/// tooth count or anything [`Gear::new`] refuses (e.g. an axis outside the root circle).
pub fn manufacture(
    gear: &Gear,
    gear_name: &str,
    tips: Vec<f64>,
    rotation_centre: Vec2,
) -> Result<Gear, HypothesisError> {
    let n = tips.len();
    if n != gear.teeth() {
        return Err(HypothesisError::new(
            format!("gear `{gear_name}`: tips"),
            format!(
                "a manufacturing error must keep the number of teeth ({} designed, {n} made)",
                gear.teeth()
            ),
        ));
    }
    for (k, t) in tips.iter().enumerate() {
        if !t.is_finite() {
            return Err(HypothesisError::new(
                format!("gear `{gear_name}`: tips[{k}]"),
                format!("must be a finite angle (got {})", fmt_number(*t)),
            ));
        }
    }
    for k in 1..n {
        if tips[k] <= tips[k - 1] {
            return Err(HypothesisError::new(
                format!("gear `{gear_name}`: tips[{k}]"),
                format!(
                    "displaced tips must stay strictly increasing (tip {k} at {:.4}° is not after tip {} at {:.4}°); the errors are too large for {n} teeth",
                    tips[k].to_degrees(),
                    k - 1,
                    tips[k - 1].to_degrees()
                ),
            ));
        }
    }
    if n > 0 && tips[n - 1] >= tips[0] + TAU {
        return Err(HypothesisError::new(
            format!("gear `{gear_name}`: tips[{}]", n - 1),
            format!(
                "displaced tips must stay strictly increasing round the gear (the last tip at {:.4}° reaches the first one a turn on, {:.4}°); the errors are too large for {n} teeth",
                tips[n - 1].to_degrees(),
                (tips[0] + TAU).to_degrees()
            ),
        ));
    }
    Gear::new(gear.tip_radius(), gear.root_radius(), tips, rotation_centre)
        .map_err(|e| HypothesisError::gear(gear_name, e))
}

/// `gear` with its valleys at `valleys` (radians), its tips, nominal radii and rotation centre
/// kept: what [`Gear::with_valleys`] refuses is refused.
pub(crate) fn with_valleys_at(gear: &Gear, valleys: Vec<f64>) -> Result<Gear, GeometryError> {
    Gear::with_valleys(
        gear.tip_radius(),
        gear.root_radius(),
        gear.tip_angles().to_vec(),
        valleys,
        gear.rotation_centre(),
    )
}

/// Parameter `random`.
pub const RANDOM: Param = Param::new(
    "random",
    "0.04",
    "sd of each tip's displacement, as a fraction of the pitch 360/N",
    Kind::ANY_NUMBER,
)
.unit("pitch");

/// Parameter `systematic`.
pub const SYSTEMATIC: Param = Param::new(
    "systematic",
    "0.5",
    "systematic amplitude A",
    Kind::ANY_NUMBER,
)
.unit("deg");

/// Parameter `split`.
pub const SPLIT: Param = Param::new(
    "split",
    "0.5",
    "share of A on the sinusoid of tip positions; the rest is an axis shift R·tan((1-split)·A)",
    Kind::ANY_NUMBER,
);

/// Edmunds' random and systematic errors with the split a parameter or fixed: what
/// `edmunds-split`, `eccentric-only` and `sinusoid-only` are. Each is a unit struct implementing
/// this, which differs from the others only in its split (and so in its parameters); each is
/// then a [`Plugin`], registered as any other.
pub(crate) trait EdmundsVariant: 'static {
    /// Its name, summary and details.
    const ABOUT: About;
    /// `random`, `systematic` and, when [`EdmundsVariant::SPLIT`] is `None`, `split`.
    const PARAMS: &'static [Param];
    /// `Some`: the split, fixed; `None`: the `split` parameter.
    const SPLIT: Option<f64>;

    /// Edmunds' errors as `params` set them.
    fn errors(params: &Params) -> EdmundsErrors {
        EdmundsErrors {
            random: params.value(&RANDOM),
            systematic_deg: params.value(&SYSTEMATIC),
            split: Self::SPLIT.unwrap_or_else(|| params.value(&SPLIT)),
            phase_deg: None,
        }
    }
}

impl<V: EdmundsVariant> Plugin for V {
    const ABOUT: About = <V as EdmundsVariant>::ABOUT;
    const PARAMS: &'static [Param] = <V as EdmundsVariant>::PARAMS;

    fn check(params: &Params) -> Result<(), HypothesisError> {
        V::errors(params).check(<V as EdmundsVariant>::ABOUT.name)
    }

    fn apply(
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn rand::RngCore,
    ) -> Result<Gear, HypothesisError> {
        let errors = V::errors(params);
        errors.check(<V as EdmundsVariant>::ABOUT.name)?;
        errors.apply(gear, gear_name, rng)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn paper_example_axis_shift() {
        // Section 4: 5° split 50/50 gives about 4 mm of axis shift on a 10 cm gear.
        let d = eccentricity(100.0, 2.5);
        assert!((d - 4.366).abs() < 1e-3, "{d}");
    }

    #[test]
    fn manufacture_refuses_out_of_order_tips() {
        let g = Gear::ideal(4, 10.0, 9.0).unwrap();
        let e = manufacture(&g, "x1", vec![0.0, 2.0, 1.9, 4.0], Vec2::zeros()).unwrap_err();
        assert_eq!(e.what, "gear `x1`: tips[2]");
        assert!(e.rule.contains("strictly increasing"), "{e}");
        let e = manufacture(&g, "x1", vec![0.1, 2.0, 3.0, 6.4], Vec2::zeros()).unwrap_err();
        assert_eq!(e.what, "gear `x1`: tips[3]");
        let e = manufacture(&g, "x1", vec![0.0, 1.0, 2.0], Vec2::zeros()).unwrap_err();
        assert!(e.rule.contains("number of teeth"), "{e}");
        let e = manufacture(&g, "x1", g.tip_angles().to_vec(), Vec2::new(9.5, 0.0)).unwrap_err();
        assert_eq!(e.what, "gear `x1`: rotation_centre");
    }

    #[test]
    fn check_names_the_field() {
        let ok = EdmundsErrors {
            random: 0.04,
            systematic_deg: 0.5,
            split: 0.5,
            phase_deg: None,
        };
        assert!(ok.check("h").is_ok());
        let e = EdmundsErrors { split: 1.5, ..ok }.check("h").unwrap_err();
        assert_eq!(e.what, "h: split");
        let e = EdmundsErrors { random: -0.1, ..ok }.check("h").unwrap_err();
        assert_eq!(e.what, "h: random");
        let e = EdmundsErrors {
            systematic_deg: 200.0,
            ..ok
        }
        .check("h")
        .unwrap_err();
        assert_eq!(e.what, "h: systematic");
    }
}
