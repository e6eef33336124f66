//! Exact gear ratios as reduced fractions: [`Ratio`] (non-negative, a train's ratio with every
//! angle positive in its own gear's direction) and [`Rate`] (signed, a rate in one fixed sense,
//! for epicyclic trains where a rate relative to the carrier is added to the carrier's).

use std::fmt;

use serde::{Deserialize, Serialize};

/// An exact non-negative ratio `num/den`, kept reduced by their greatest common divisor.
///
/// Build it with [`Ratio::new`] so that equal ratios compare equal field by field.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Ratio {
    /// Numerator.
    pub num: u128,
    /// Denominator.
    pub den: u128,
}

/// Greatest common divisor (`gcd(0, 0) == 0`).
fn gcd(mut a: u128, mut b: u128) -> u128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

impl Ratio {
    /// The ratio one (`1/1`).
    pub const ONE: Ratio = Ratio { num: 1, den: 1 };

    /// `num/den` reduced by their gcd (`0/0` is kept as it is).
    #[must_use]
    pub fn new(num: u128, den: u128) -> Ratio {
        let g = gcd(num, den);
        if g <= 1 {
            Ratio { num, den }
        } else {
            Ratio {
                num: num / g,
                den: den / g,
            }
        }
    }

    /// The exact product `self * other`, reduced, or `None` if it does not fit in `u128`.
    #[must_use]
    pub fn checked_mul(self, other: Ratio) -> Option<Ratio> {
        // Cross-reduce first so that the products stay as small as possible.
        let g1 = gcd(self.num, other.den).max(1);
        let g2 = gcd(other.num, self.den).max(1);
        let num = (self.num / g1).checked_mul(other.num / g2)?;
        let den = (self.den / g2).checked_mul(other.den / g1)?;
        Some(Ratio::new(num, den))
    }

    /// The ratio as a float (`num / den`).
    #[must_use]
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }
}

impl fmt::Display for Ratio {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.num, self.den)
    }
}

/// An exact signed rate `num/den` (`den > 0`), kept reduced: turns of an arbor per turn of a
/// reference, counted in one fixed sense (positive the way the reference turns).
///
/// Build it with [`Rate::new`] or from a [`Ratio`] so that equal rates compare equal field by
/// field. Arithmetic is checked: `None` where a result does not fit in `i128`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Rate {
    /// Numerator, carrying the sign.
    pub num: i128,
    /// Denominator, positive.
    pub den: i128,
}

impl Rate {
    /// The rate zero.
    pub const ZERO: Rate = Rate { num: 0, den: 1 };
    /// The rate one (the reference itself).
    pub const ONE: Rate = Rate { num: 1, den: 1 };

    /// `num/den` reduced with a positive denominator; `None` for `den == 0` (or `i128::MIN`,
    /// whose negation does not fit).
    #[must_use]
    pub fn new(num: i128, den: i128) -> Option<Rate> {
        if den == 0 || num == i128::MIN || den == i128::MIN {
            return None;
        }
        let g = gcd(num.unsigned_abs(), den.unsigned_abs()).max(1);
        let g = i128::try_from(g).ok()?;
        let (num, den) = (num / g, den / g);
        Some(if den < 0 {
            Rate {
                num: -num,
                den: -den,
            }
        } else {
            Rate { num, den }
        })
    }

    /// The ratio `r` as a rate, positive (`-r` with `negative`); `None` if it does not fit.
    #[must_use]
    pub fn from_ratio(r: Ratio, negative: bool) -> Option<Rate> {
        let num = i128::try_from(r.num).ok()?;
        Rate::new(
            if negative { -num } else { num },
            i128::try_from(r.den).ok()?,
        )
    }

    /// The exact sum, reduced.
    #[must_use]
    pub fn checked_add(self, other: Rate) -> Option<Rate> {
        let g = i128::try_from(gcd(self.den.unsigned_abs(), other.den.unsigned_abs())).ok()?;
        let (a, b) = (self.den / g, other.den / g);
        let num = self
            .num
            .checked_mul(b)?
            .checked_add(other.num.checked_mul(a)?)?;
        Rate::new(num, self.den.checked_mul(b)?)
    }

    /// The exact difference `self - other`, reduced.
    #[must_use]
    pub fn checked_sub(self, other: Rate) -> Option<Rate> {
        self.checked_add(-other)
    }

    /// The exact product, reduced.
    #[must_use]
    pub fn checked_mul(self, other: Rate) -> Option<Rate> {
        let g1 =
            i128::try_from(gcd(self.num.unsigned_abs(), other.den.unsigned_abs()).max(1)).ok()?;
        let g2 =
            i128::try_from(gcd(other.num.unsigned_abs(), self.den.unsigned_abs()).max(1)).ok()?;
        let num = (self.num / g1).checked_mul(other.num / g2)?;
        let den = (self.den / g2).checked_mul(other.den / g1)?;
        Rate::new(num, den)
    }

    /// The size of the rate, as a [`Ratio`].
    #[must_use]
    pub fn abs(self) -> Ratio {
        Ratio::new(self.num.unsigned_abs(), self.den.unsigned_abs())
    }

    /// The rate as a float (`num / den`).
    #[must_use]
    pub fn to_f64(self) -> f64 {
        self.num as f64 / self.den as f64
    }
}

impl std::ops::Neg for Rate {
    type Output = Rate;

    /// `-self` (the numerator is never `i128::MIN`: [`Rate::new`] refuses it).
    fn neg(self) -> Rate {
        Rate {
            num: -self.num,
            den: self.den,
        }
    }
}

impl fmt::Display for Rate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}/{}", self.num, self.den)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reduces_and_multiplies() {
        assert_eq!(Ratio::new(64, 38), Ratio { num: 32, den: 19 });
        assert_eq!(Ratio::new(0, 5), Ratio { num: 0, den: 1 });
        assert_eq!(
            Ratio::new(2, 3).checked_mul(Ratio::new(9, 4)),
            Some(Ratio::new(3, 2))
        );
        assert_eq!(Ratio::new(u128::MAX, 1).checked_mul(Ratio::new(2, 1)), None);
        assert_eq!(Ratio::new(254, 19).to_string(), "254/19");
        assert!((Ratio::new(1, 4).to_f64() - 0.25).abs() < 1e-15);
    }

    #[test]
    fn signed_rates_add_and_multiply_exactly() {
        let r = |n, d| Rate::new(n, d).unwrap_or(Rate::ZERO);
        assert_eq!(r(4, -6), Rate { num: -2, den: 3 });
        assert_eq!(Rate::new(1, 0), None);
        // Mars (Freeth 2021): 1 - 133/284 = 151/284.
        assert_eq!(Rate::ONE.checked_sub(r(133, 284)), Some(r(151, 284)));
        // The nodes: 1 - (49/62)(64/48) = -5/93.
        let rel = r(49, 62).checked_mul(r(64, 48));
        assert_eq!(rel.and_then(|x| Rate::ONE.checked_sub(x)), Some(r(-5, 93)));
        assert_eq!(r(-1, 2).checked_mul(r(-2, 3)), Some(r(1, 3)));
        assert_eq!(
            Rate::from_ratio(Ratio::new(254, 19), true),
            Some(r(-254, 19))
        );
        assert_eq!(r(-235, 19).abs(), Ratio::new(235, 19));
        assert_eq!(r(-235, 19).to_string(), "-235/19");
        assert_eq!(r(i128::MAX, 1).checked_add(r(1, 1)), None);
        assert!((r(-1, 4).to_f64() + 0.25).abs() < 1e-15);
    }
}
