//! Spearman's rank correlation: whether one quantity tends to rise with another, whatever the
//! shape of the relation (the paper's "pairs with a large gear fail more").

use statrs::distribution::{ContinuousCDF, StudentsT};

/// Spearman's ρ between `x` and `y` (the Pearson correlation of their ranks, ties given their
/// average rank) and its two-sided p-value from Student's t with n − 2 degrees of freedom,
/// `t = ρ·√((n − 2)/(1 − ρ²))`. The t approximation is the usual one for n of about 10 or more.
///
/// `None` for fewer than three pairs, unequal lengths, a non-finite value, or a constant `x` or
/// `y` (no ranks to correlate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Spearman {
    /// ρ, from −1 to 1.
    pub rho: f64,
    /// Two-sided p-value of ρ = 0.
    pub p: f64,
}

/// See [`Spearman`].
pub fn spearman(x: &[f64], y: &[f64]) -> Option<Spearman> {
    let n = x.len();
    if n < 3 || y.len() != n || x.iter().chain(y).any(|v| !v.is_finite()) {
        return None;
    }
    let (rx, ry) = (ranks(x), ranks(y));
    let mean = (n as f64 + 1.0) / 2.0;
    let (mut sxy, mut sxx, mut syy) = (0.0, 0.0, 0.0);
    for (a, b) in rx.iter().zip(&ry) {
        sxy += (a - mean) * (b - mean);
        sxx += (a - mean) * (a - mean);
        syy += (b - mean) * (b - mean);
    }
    if sxx == 0.0 || syy == 0.0 {
        return None;
    }
    let rho = (sxy / (sxx * syy).sqrt()).clamp(-1.0, 1.0);
    let dof = n as f64 - 2.0;
    let p = if rho.abs() >= 1.0 {
        0.0
    } else {
        let t = rho * (dof / (1.0 - rho * rho)).sqrt();
        let dist = StudentsT::new(0.0, 1.0, dof).ok()?;
        (2.0 * (1.0 - dist.cdf(t.abs()))).clamp(0.0, 1.0)
    };
    Some(Spearman { rho, p })
}

/// 1-based ranks of `v`, ties given the average of the ranks they span.
fn ranks(v: &[f64]) -> Vec<f64> {
    let mut order: Vec<usize> = (0..v.len()).collect();
    order.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut i = 0;
    while i < order.len() {
        let mut j = i;
        while j + 1 < order.len() && v[order[j + 1]] == v[order[i]] {
            j += 1;
        }
        let average = (i + j) as f64 / 2.0 + 1.0;
        for &k in &order[i..=j] {
            r[k] = average;
        }
        i = j + 1;
    }
    r
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn a_rising_relation_of_any_shape_has_rho_one() {
        let x = [1.0, 2.0, 3.0, 4.0, 5.0];
        let y = [1.0, 4.0, 9.0, 100.0, 1e6];
        let s = spearman(&x, &y).unwrap();
        assert_eq!(s.rho, 1.0);
        assert_eq!(s.p, 0.0);
        let down: Vec<f64> = y.iter().map(|v| -v).collect();
        assert_eq!(spearman(&x, &down).unwrap().rho, -1.0);
    }

    #[test]
    fn ties_take_their_average_rank_and_match_a_worked_example() {
        assert_eq!(ranks(&[10.0, 20.0, 10.0, 30.0]), vec![1.5, 3.0, 1.5, 4.0]);
        // scipy.stats.spearmanr([1,2,3,4,5,6,7,8,9,10], [2,1,4,3,6,5,8,7,10,9]):
        // rho = 0.9393939..., p = 5.484e-05.
        let x: Vec<f64> = (1..=10).map(f64::from).collect();
        let y = [2.0, 1.0, 4.0, 3.0, 6.0, 5.0, 8.0, 7.0, 10.0, 9.0];
        let s = spearman(&x, &y).unwrap();
        assert!((s.rho - 0.939_393_939).abs() < 1e-8, "{s:?}");
        assert!((s.p - 5.484e-5).abs() < 1e-7, "{s:?}");
    }

    #[test]
    fn nothing_to_rank_is_none() {
        assert!(spearman(&[1.0, 2.0], &[1.0, 2.0]).is_none());
        assert!(spearman(&[1.0, 1.0, 1.0], &[1.0, 2.0, 3.0]).is_none());
        assert!(spearman(&[1.0, 2.0, f64::NAN], &[1.0, 2.0, 3.0]).is_none());
    }
}
