//! Exact gear ratios as reduced fractions.

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
}
