//! Two binomial counts compared: Fisher's exact test and Newcombe's hybrid-score interval of the
//! difference of two proportions.
//!
//! Both answer the question the per-mesh jam tables ask when they set our count of jamming
//! trials beside the paper's: the paper's count is a sample too (of 200 trials), so the two
//! counts are compared as two samples, not one count against the other's interval.
//!
//! [`sign_test`] compares two settings run on the same trials (paired): the trials that failed
//! under one setting only, against those that failed under the other only.

use statrs::function::factorial::ln_factorial;

use crate::wilson95;

/// Relative tolerance under which a table counts as "as probable as" the observed one in
/// [`fisher_exact_two_sided`]: R's `fisher.test` uses the same `1 + 1e-7`. It absorbs the
/// rounding of probabilities that are equal in exact arithmetic (the mirror image of a table
/// with equal row totals), which would otherwise be left out at random.
pub const FISHER_RELATIVE_TOLERANCE: f64 = 1e-7;

/// Two-sided p-value of Fisher's exact test for `a` successes of `n1` against `b` of `n2`.
///
/// The 2×2 table `[[a, n1 − a], [b, n2 − b]]` has fixed margins; under the null hypothesis of
/// one common rate the top-left cell X is hypergeometric: with N = n1 + n2 and k = a + b,
///
/// ```text
/// P(X = x) = C(k, x) · C(N − k, n1 − x) / C(N, n1),   max(0, k − n2) ≤ x ≤ min(k, n1).
/// ```
///
/// The p-value is the sum of P(X = x) over every x with P(X = x) ≤ P(X = a) (the standard
/// "sum of probabilities no larger than the observed" definition, as `scipy.stats.fisher_exact`
/// and R's `fisher.test`), with the comparison made to a relative tolerance of
/// [`FISHER_RELATIVE_TOLERANCE`].
///
/// Computed in log space: ln P(X = x) from `ln_factorial` (exact table below 171, Lanczos
/// ln Γ above), each term scaled by the observed table's probability before it is summed, so
/// nothing overflows or underflows for n up to 10^6 and beyond (one pass over the support, at
/// most min(k, n1) + 1 terms). Accuracy: the ln-factorials of numbers near N are held to about
/// N·ln N·2⁻⁵³ absolute, so the p-value is good to about 1e-13 relative for n in the hundreds
/// and 2e-9 relative at n = 10^6 (against SciPy), far below any decision at 5 %. The result is
/// clamped to [0, 1]; a p-value below ~1e-308 underflows to 0.
///
/// With n1 = 0 or n2 = 0 there is nothing to compare and the p-value is 1.
///
/// # Panics
/// If `a > n1` or `b > n2`.
#[must_use]
pub fn fisher_exact_two_sided(a: u64, n1: u64, b: u64, n2: u64) -> f64 {
    assert!(a <= n1, "fisher_exact_two_sided: a = {a} > n1 = {n1}");
    assert!(b <= n2, "fisher_exact_two_sided: b = {b} > n2 = {n2}");
    if n1 == 0 || n2 == 0 {
        return 1.0;
    }
    let total = n1 + n2;
    let k = a + b;
    // ln P(X = x) up to the constant −ln C(N, n1), which cancels in the ratio to P(X = a).
    let ln_term = |x: u64| {
        ln_factorial(k) - ln_factorial(x) - ln_factorial(k - x) + ln_factorial(total - k)
            - ln_factorial(n1 - x)
            // total - n1 - (k - x) = n2 - (k - x), summed so as not to go below 0 on the way
            // (x >= k - n2 over the support, so the result is >= 0).
            - ln_factorial(n2 + x - k)
    };
    let lo = k.saturating_sub(n2);
    let hi = k.min(n1);
    let ln_observed = ln_term(a);
    let ln_limit = ln_observed + FISHER_RELATIVE_TOLERANCE.ln_1p();
    // Σ P(x)/P(a) over the tables no more probable than the observed one (each term ≤ 1 + tol),
    // and Σ P(x)/P(a) over all tables, which is 1/P(a).
    let (mut tail, mut all) = (0.0_f64, 0.0_f64);
    for x in lo..=hi {
        let ln_x = ln_term(x);
        let r = (ln_x - ln_observed).exp();
        all += r;
        if ln_x <= ln_limit {
            tail += r;
        }
    }
    (tail / all).clamp(0.0, 1.0)
}

/// A difference of two proportions p̂1 − p̂2 with a 95 % interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Difference {
    /// p̂1 − p̂2 = a/n1 − b/n2 (NaN when either n is 0).
    pub diff: f64,
    /// Lower end of the interval, in [−1, 1].
    pub lo: f64,
    /// Upper end of the interval, in [−1, 1].
    pub hi: f64,
}

impl Difference {
    /// Does the interval contain 0, i.e. are the two rates not separated?
    #[must_use]
    pub fn contains_zero(&self) -> bool {
        self.lo <= 0.0 && 0.0 <= self.hi
    }
}

/// Newcombe's hybrid-score 95 % interval for p1 − p2 (Newcombe 1998, Stat. Med. 17:873, method
/// 10), from `a` successes of `n1` and `b` of `n2`.
///
/// With p̂1 = a/n1, p̂2 = b/n2 and the Wilson score intervals [l1, u1], [l2, u2] of each
/// ([`wilson95`], no continuity correction, z = [`crate::Z975`]):
///
/// ```text
/// lo = (p̂1 − p̂2) − sqrt( (p̂1 − l1)² + (u2 − p̂2)² )
/// hi = (p̂1 − p̂2) + sqrt( (u1 − p̂1)² + (p̂2 − l2)² )
/// ```
///
/// Newcombe's worked example 56/70 − 48/80 gives 0.0524 to 0.3339. The ends stay within
/// [−1, 1] (each Wilson end lies in [0, 1]); they are clamped there against rounding. With
/// n1 = 0 or n2 = 0 the difference is NaN and the interval [−1, 1] (no information).
///
/// # Panics
/// If `a > n1` or `b > n2`.
#[must_use]
pub fn newcombe95(a: u64, n1: u64, b: u64, n2: u64) -> Difference {
    assert!(a <= n1, "newcombe95: a = {a} > n1 = {n1}");
    assert!(b <= n2, "newcombe95: b = {b} > n2 = {n2}");
    if n1 == 0 || n2 == 0 {
        return Difference {
            diff: f64::NAN,
            lo: -1.0,
            hi: 1.0,
        };
    }
    let (w1, w2) = (wilson95(a, n1), wilson95(b, n2));
    let (p1, p2) = (w1.rate(), w2.rate());
    let diff = p1 - p2;
    let lo = diff - ((p1 - w1.lo).powi(2) + (w2.hi - p2).powi(2)).sqrt();
    let hi = diff + ((w1.hi - p1).powi(2) + (p2 - w2.lo).powi(2)).sqrt();
    Difference {
        diff,
        lo: lo.clamp(-1.0, 1.0),
        hi: hi.clamp(-1.0, 1.0),
    }
}

/// Are `a` of `n1` and `b` of `n2` consistent, i.e. not separated at the 5 % level by Fisher's
/// exact test ([`fisher_exact_two_sided`] ≥ 0.05)?
///
/// Fisher's test, being exact, is the one used; [`newcombe95`] gives the interval of the
/// difference, and the two agree on most tables but can part at the margin (the interval is
/// an approximation). With n1 = 0 or n2 = 0 nothing separates them: `true`.
///
/// # Panics
/// If `a > n1` or `b > n2`.
#[must_use]
pub fn consistent(a: u64, n1: u64, b: u64, n2: u64) -> bool {
    fisher_exact_two_sided(a, n1, b, n2) >= 0.05
}

/// Two-sided exact sign test of `b` against `c` discordant pairs (McNemar's exact test): the
/// probability, with each pair going either way with probability 1/2, of a split at least as
/// uneven; 1 when there are none.
pub fn sign_test(b: u64, c: u64) -> f64 {
    let n = b + c;
    if n == 0 {
        return 1.0;
    }
    // ln of C(n, i) / 2^n, from i = 0 up.
    let mut ln_term = -(n as f64) * std::f64::consts::LN_2;
    let mut tail = ln_term.exp();
    for i in 1..=b.min(c) {
        ln_term += ((n - i + 1) as f64).ln() - (i as f64).ln();
        tail += ln_term.exp();
    }
    (2.0 * tail).min(1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative closeness.
    fn close(a: f64, b: f64, rel: f64) -> bool {
        (a - b).abs() <= rel * b.abs()
    }

    // Reference p-values: `scipy.stats.fisher_exact` (SciPy 1.17.1) on [[a, n1-a], [b, n2-b]];
    // for the tables with n ≤ 200 also an exact rational sum over the hypergeometric support
    // with Python's `fractions` and `math.comb`, which agrees to 1e-15 relative.
    const FISHER: &[(u64, u64, u64, u64, f64)] = &[
        (56, 70, 48, 80, 0.012_521_129_749_209_154),
        (9, 10, 3, 10, 0.019_766_611_097_880_443),
        (2, 200, 9, 200, 0.061_813_965_825_287_08),
        (0, 200, 5, 200, 0.060_939_502_408_413_97),
        (163, 200, 200, 200, 2.322_044_971_295_511_7e-12),
        (3, 200, 0, 200, 0.248_120_300_751_879_7),
        (168, 200, 99, 200, 2.066_358_828_197_817_4e-13),
        (7, 12, 2, 9, 0.184_234_341_509_883_27),
        (1, 3, 3, 3, 0.4),
        // n = 10^6 per sample.
        (500, 1_000_000, 560, 1_000_000, 0.069_835_428_587_410_47),
        (12, 1_000_000, 3, 1_000_000, 0.035_155_583_502_457_35),
        (
            499_000,
            1_000_000,
            500_000,
            1_000_000,
            0.157_714_504_869_766_57,
        ),
        (100, 1000, 30_000, 1_000_000, 6.143_297_638_849_312e-25),
        (400_000, 1_000_000, 500, 1000, 1.756_875_609_438_391_6e-10),
    ];

    #[test]
    fn a_count_of_every_trial_on_one_side_is_compared() {
        // 200 of 200 against 1 of 12: the support's last cell is n2 - (k - x) = 0.
        let p = fisher_exact_two_sided(1, 12, 200, 200);
        assert!((0.0..1e-10).contains(&p), "{p}");
        assert_eq!(fisher_exact_two_sided(12, 12, 200, 200), 1.0);
    }

    #[test]
    fn fisher_matches_scipy_and_exact_sums() {
        for &(a, n1, b, n2, p) in FISHER {
            let ours = fisher_exact_two_sided(a, n1, b, n2);
            // Measured: within 2e-13 for n <= 200, 2e-9 at n = 10^6 (see the function's note).
            let tol = if n1 + n2 > 10_000 { 1e-8 } else { 1e-12 };
            assert!(close(ours, p, tol), "{a}/{n1} vs {b}/{n2}: {ours} vs {p}");
        }
    }

    #[test]
    fn fisher_is_symmetric_in_the_two_samples_and_in_success_and_failure() {
        for &(a, n1, b, n2, _) in FISHER {
            let p = fisher_exact_two_sided(a, n1, b, n2);
            let swapped = fisher_exact_two_sided(b, n2, a, n1);
            let flipped = fisher_exact_two_sided(n1 - a, n1, n2 - b, n2);
            assert!(close(swapped, p, 1e-9), "{a}/{n1} vs {b}/{n2}");
            assert!(close(flipped, p, 1e-9), "{a}/{n1} vs {b}/{n2}");
        }
    }

    #[test]
    fn fisher_edge_cases() {
        // Equal counts of equal samples: the observed table is the mode, p = 1.
        assert_eq!(fisher_exact_two_sided(1, 200, 1, 200), 1.0);
        assert_eq!(fisher_exact_two_sided(0, 200, 0, 200), 1.0);
        assert_eq!(fisher_exact_two_sided(200, 200, 200, 200), 1.0);
        // Nothing to compare.
        assert_eq!(fisher_exact_two_sided(0, 0, 3, 10), 1.0);
        assert_eq!(fisher_exact_two_sided(3, 10, 0, 0), 1.0);
        // The most extreme tables of 200 against 200: p = 2 / C(400, 200), about 4.9e-119,
        // still representable.
        let p = fisher_exact_two_sided(200, 200, 0, 200);
        assert!(p > 0.0 && p < 1e-110, "{p}");
    }

    #[test]
    #[should_panic(expected = "a = 5 > n1 = 4")]
    fn fisher_refuses_a_count_above_its_trials() {
        let _ = fisher_exact_two_sided(5, 4, 0, 4);
    }

    // Newcombe 1998, Table II: 56/70 − 48/80 gives 0.0524 to 0.3339 (the paper's first example).
    // The other rows: an independent Python implementation of the same formulas (Wilson score
    // ends, z = 1.959963984540054), to 1e-12.
    const NEWCOMBE: &[(u64, u64, u64, u64, f64, f64)] = &[
        (
            9,
            10,
            3,
            10,
            0.170_522_723_934_503_02,
            0.809_017_973_535_488_1,
        ),
        (6, 7, 2, 7, 0.058_227_927_482_312_2, 0.806_249_637_524_227_7),
        (
            5,
            56,
            0,
            29,
            -0.038_137_147_903_536_88,
            0.192_560_013_855_111_62,
        ),
        (
            0,
            10,
            0,
            20,
            -0.161_125_158_052_819_38,
            0.277_532_799_862_889_2,
        ),
        (10, 10, 0, 20, 0.679_086_037_141_914_7, 1.0),
        (
            2,
            200,
            9,
            200,
            -0.073_977_538_475_828_14,
            -0.001_700_991_556_992_548_2,
        ),
        (
            163,
            200,
            200,
            200,
            -0.244_570_627_611_517_6,
            -0.133_714_013_627_549_34,
        ),
    ];

    #[test]
    fn newcombe_reproduces_the_worked_example() {
        let d = newcombe95(56, 70, 48, 80);
        assert!((d.diff - 0.2).abs() < 1e-15, "{d:?}");
        assert_eq!(format!("{:.4} {:.4}", d.lo, d.hi), "0.0524 0.3339");
    }

    #[test]
    fn newcombe_matches_an_independent_implementation() {
        for &(a, n1, b, n2, lo, hi) in NEWCOMBE {
            let d = newcombe95(a, n1, b, n2);
            assert!((d.lo - lo).abs() < 1e-12, "{a}/{n1} vs {b}/{n2}: {d:?}");
            assert!((d.hi - hi).abs() < 1e-12, "{a}/{n1} vs {b}/{n2}: {d:?}");
            // Swapping the samples mirrors the interval.
            let m = newcombe95(b, n2, a, n1);
            assert!(
                (m.lo + hi).abs() < 1e-12 && (m.hi + lo).abs() < 1e-12,
                "{m:?}"
            );
        }
    }

    #[test]
    fn newcombe_edge_cases() {
        let none = newcombe95(0, 0, 3, 10);
        assert!(none.diff.is_nan() && none.lo == -1.0 && none.hi == 1.0);
        let all = newcombe95(200, 200, 0, 200);
        assert!(all.hi == 1.0 && all.lo > 0.97, "{all:?}");
        assert!(newcombe95(1, 200, 1, 200).contains_zero());
    }

    #[test]
    fn consistent_follows_fisher_at_five_percent() {
        // 2 vs 9 of 200: p = 0.062, not separated; 0 vs 6 of 200: separated.
        assert!(consistent(2, 200, 9, 200));
        assert!(fisher_exact_two_sided(0, 200, 6, 200) < 0.05);
        assert!(!consistent(0, 200, 6, 200));
        assert!(!consistent(163, 200, 200, 200));
        assert!(consistent(0, 0, 200, 200));
        // They agree on most tables; Fisher's exact test is the more conservative at the margin:
        // 2 vs 9 of 200 has p = 0.062, while the Newcombe interval, -0.0740 to -0.0017, just
        // excludes 0.
        for (a, b) in [(0, 6), (163, 200), (3, 0), (99, 120)] {
            assert_eq!(
                consistent(a, 200, b, 200),
                newcombe95(a, 200, b, 200).contains_zero(),
                "{a} vs {b} of 200"
            );
        }
        assert!(!newcombe95(2, 200, 9, 200).contains_zero());
    }

    #[test]
    fn the_sign_test_matches_binomial_tails() {
        assert_eq!(sign_test(0, 0), 1.0);
        // 3 against 0: 2 * (1/2)^3.
        assert!((sign_test(3, 0) - 0.25).abs() < 1e-15);
        assert!((sign_test(0, 3) - 0.25).abs() < 1e-15);
        // 1 against 9: 2 * (1 + 10) / 1024.
        assert!((sign_test(1, 9) - 22.0 / 1024.0).abs() < 1e-15);
        // An even split: 1.
        assert_eq!(sign_test(5, 5), 1.0);
        // Large counts do not underflow: 0 against 2000 is tiny but 2 * 2^-2000 underflows to 0,
        // and 1000 against 1000 is 1.
        assert!(sign_test(0, 2000) < 1e-300);
        assert_eq!(sign_test(1000, 1000), 1.0);
    }
}
