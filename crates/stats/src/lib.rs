//! Statistics that carry their uncertainty: pointer-error summaries, streaming moments, Student-t and binomial 95 % intervals.

// Contents: `pointer_stats` / `Accumulator` (Table 1's σ, Dm, P, batch or streaming),
// `mean_ci95` (Student-t interval), `wilson95` / `clopper_pearson95` (binomial counts),
// `DAYS_PER_YEAR` / `days_per_degree` (degrees of pointer error to days); in `two_sample.rs`,
// two binomial counts compared (`fisher_exact_two_sided`, `newcombe95`, `consistent`) and
// paired ones (`sign_test`, McNemar's exact test); in
// `survival.rs`, times to an event (`median`, `kaplan_meier` with its exact band). Quantiles come from
// `statrs` (`StudentsT`, `Beta`) without default features: it pulls in only `approx` and
// `num-traits`.

use statrs::distribution::{Beta, ContinuousCDF, StudentsT};

mod rank;
mod survival;
mod two_sample;

pub use rank::{Spearman, spearman};
pub use survival::{Step, kaplan_meier, median, step_points, survival_at};

pub use two_sample::{
    Difference, FISHER_RELATIVE_TOLERANCE, consistent, fisher_exact_two_sided, newcombe95,
    sign_test,
};

// ---------------------------------------------------------------------------------------------
// Pointer statistics (batch).
// ---------------------------------------------------------------------------------------------

/// Summary of a Theoretical Difference (TD) series, as in the paper's Table 1.
///
/// All three fields are in the units of the series (degrees of pointer error in the paper).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointerStats {
    /// Population standard deviation σ = sqrt( Σ (xᵢ − P)² / N ).
    pub sigma: f64,
    /// Largest absolute value Dm = maxᵢ |xᵢ|.
    pub dm: f64,
    /// Signed mean P = Σ xᵢ / N (the oscillation mean; take `abs()` when averaging across
    /// trials, as the paper's "average absolute value of the oscillation mean" does).
    pub mean: f64,
}

impl PointerStats {
    /// All fields NaN: the summary of an empty series.
    pub const NAN: Self = Self {
        sigma: f64::NAN,
        dm: f64::NAN,
        mean: f64::NAN,
    };
}

/// Summarise a TD series sampled uniformly in driver angle.
///
/// Formulas (N = `td.len()`):
/// * mean P = Σ xᵢ / N,
/// * sigma σ = sqrt( Σ (xᵢ − P)² / N )  (population, divisor N),
/// * dm Dm = maxᵢ |xᵢ|.
///
/// Computed by the corrected two-pass algorithm: with the first-pass mean m = Σ xᵢ / N and
/// dᵢ = xᵢ − m, P = m + Σ dᵢ / N and σ² = (Σ dᵢ² − (Σ dᵢ)² / N) / N, which removes the
/// rounding of the first sum (it matters for a small oscillation on a large offset).
///
/// Because the samples are meant to be uniform in driver angle, these are the angle-averages
/// of the error over the sampled range. For a periodic series sample a half-open range (e.g.
/// `[0°, 360°)`), not both end points, or the repeated end point is counted twice.
///
/// An empty series gives [`PointerStats::NAN`]. A NaN sample makes all three fields NaN.
#[must_use]
pub fn pointer_stats(td: &[f64]) -> PointerStats {
    if td.is_empty() {
        return PointerStats::NAN;
    }
    let n = td.len() as f64;
    let m = td.iter().sum::<f64>() / n;
    let (sd, sd2) = td.iter().fold((0.0, 0.0), |(s, s2), &x| {
        let d = x - m;
        (s + d, s2 + d * d)
    });
    let mean = m + sd / n;
    let var = (sd2 - sd * sd / n) / n;
    // Clamp rounding-negative variance to 0, but let NaN through (`f64::max` would drop it).
    let var = if var < 0.0 { 0.0 } else { var };
    let mut dm = 0.0_f64;
    for &x in td {
        dm = nan_max(dm, x.abs());
    }
    PointerStats {
        sigma: var.sqrt(),
        dm,
        mean,
    }
}

/// `max` that propagates NaN (unlike `f64::max`, which ignores it).
fn nan_max(a: f64, b: f64) -> f64 {
    if a.is_nan() || b.is_nan() {
        f64::NAN
    } else {
        a.max(b)
    }
}

// ---------------------------------------------------------------------------------------------
// Streaming moments.
// ---------------------------------------------------------------------------------------------

/// Streaming mean / population standard deviation / largest absolute value (Welford).
///
/// The first sample pushed becomes a shift K, and Welford's recurrence runs on dᵢ = xᵢ − K
/// (so a small oscillation on a large offset keeps its precision). After N samples the state
/// is N, the running mean M_N of the dᵢ and S_N = Σ (dᵢ − M_N)², updated per sample as
///
/// ```text
/// N ← N + 1,  d = x − K,  δ = d − M,  M ← M + δ / N,  S ← S + δ · (d − M)
/// ```
///
/// so that mean = K + M and `sigma = sqrt(S / N)` match [`pointer_stats`] without keeping
/// the series. Two accumulators combine with [`Accumulator::merge`]. Results are
/// deterministic for a fixed push / merge order; a different order changes only the last
/// few bits.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Accumulator {
    n: u64,
    shift: f64,
    mean: f64,
    m2: f64,
    max_abs: f64,
}

impl Accumulator {
    /// An empty accumulator.
    #[must_use]
    pub const fn new() -> Self {
        Self {
            n: 0,
            shift: 0.0,
            mean: 0.0,
            m2: 0.0,
            max_abs: 0.0,
        }
    }

    /// Add one sample (Welford's update, see the type's documentation).
    pub fn push(&mut self, x: f64) {
        if self.n == 0 {
            self.shift = x;
        }
        self.n += 1;
        let d = x - self.shift;
        let delta = d - self.mean;
        self.mean += delta / self.n as f64;
        self.m2 += delta * (d - self.mean);
        self.max_abs = nan_max(self.max_abs, x.abs());
    }

    /// Fold `other` into `self` (Chan et al.'s pairwise combination), keeping `self`'s shift:
    ///
    /// ```text
    /// N = Nₐ + N_b,  δ = (K_b − Kₐ) + (M_b − Mₐ)  (= difference of the two means),
    /// M = Mₐ + δ · N_b / N,  S = Sₐ + S_b + δ² · Nₐ · N_b / N,  max_abs = max(maxₐ, max_b)
    /// ```
    ///
    /// Merging an empty accumulator on either side is exact. Merging chunks in a fixed order
    /// is deterministic; other orders agree to rounding (≈1e-15 relative).
    pub fn merge(&mut self, other: &Self) {
        if other.n == 0 {
            return;
        }
        if self.n == 0 {
            *self = *other;
            return;
        }
        let na = self.n as f64;
        let nb = other.n as f64;
        let n = na + nb;
        let delta = (other.shift - self.shift) + (other.mean - self.mean);
        self.mean += delta * (nb / n);
        self.m2 += other.m2 + delta * delta * (na * nb / n);
        self.n += other.n;
        self.max_abs = nan_max(self.max_abs, other.max_abs);
    }

    /// Number of samples pushed (including merged ones).
    #[must_use]
    pub const fn count(&self) -> u64 {
        self.n
    }

    /// Mean Σ xᵢ / N; NaN when empty.
    #[must_use]
    pub fn mean(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            self.shift + self.mean
        }
    }

    /// Population standard deviation sqrt(S / N); NaN when empty.
    #[must_use]
    pub fn sigma(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            // Clamp rounding-negative S to 0, but let NaN through (`f64::max` would drop it).
            let m2 = if self.m2 < 0.0 { 0.0 } else { self.m2 };
            (m2 / self.n as f64).sqrt()
        }
    }

    /// Largest absolute value maxᵢ |xᵢ| (Dm); NaN when empty.
    #[must_use]
    pub fn max_abs(&self) -> f64 {
        if self.n == 0 { f64::NAN } else { self.max_abs }
    }

    /// The same summary as [`pointer_stats`] on the pushed samples.
    #[must_use]
    pub fn stats(&self) -> PointerStats {
        PointerStats {
            sigma: self.sigma(),
            dm: self.max_abs(),
            mean: self.mean(),
        }
    }
}

impl Extend<f64> for Accumulator {
    fn extend<I: IntoIterator<Item = f64>>(&mut self, iter: I) {
        for x in iter {
            self.push(x);
        }
    }
}

impl FromIterator<f64> for Accumulator {
    fn from_iter<I: IntoIterator<Item = f64>>(iter: I) -> Self {
        let mut acc = Self::new();
        acc.extend(iter);
        acc
    }
}

// ---------------------------------------------------------------------------------------------
// Mean with a Student-t interval.
// ---------------------------------------------------------------------------------------------

/// Two-sided 95 % standard-normal quantile z = Φ⁻¹(0.975).
pub const Z975: f64 = 1.959_963_984_540_054;

/// Degrees of freedom above which [`t975`] uses the Cornish–Fisher expansion instead of
/// `statrs` (whose inverse loses accuracy past ~1e4 dof and falls below z past ~1e5).
const T_EXPANSION_DOF: f64 = 1000.0;

/// The 0.975 quantile of Student's t with `dof` degrees of freedom, t₀.₉₇₅,ᵥ.
///
/// * `dof ≤ 1000`: `statrs`' `StudentsT::inverse_cdf` (an inverse regularised incomplete beta).
/// * `dof > 1000` (including ∞): the Cornish–Fisher expansion in 1/ν around z = [`Z975`]
///   (Abramowitz & Stegun 26.7.5),
///
///   ```text
///   t ≈ z + (z³ + z)/(4ν) + (5z⁵ + 16z³ + 3z)/(96ν²) + (3z⁷ + 19z⁵ + 17z³ − 15z)/(384ν³)
///         + (79z⁹ + 776z⁷ + 1482z⁵ − 1920z³ − 945z)/(92160ν⁴),
///   ```
///
///   which agrees with the exact quantile to ~1e-12 there and tends to z as ν → ∞.
///
/// Known values: t₀.₉₇₅,₁ = 12.706, t₀.₉₇₅,₂₉ = 2.0452, t₀.₉₇₅,∞ = 1.95996.
/// NaN for `dof <= 0` or NaN.
#[must_use]
pub fn t975(dof: f64) -> f64 {
    if dof > T_EXPANSION_DOF {
        let z = Z975;
        let (z2, v) = (z * z, dof);
        let z3 = z2 * z;
        let z5 = z3 * z2;
        let z7 = z5 * z2;
        let z9 = z7 * z2;
        return z
            + (z3 + z) / (4.0 * v)
            + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * v * v)
            + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * v.powi(3))
            + (79.0 * z9 + 776.0 * z7 + 1482.0 * z5 - 1920.0 * z3 - 945.0 * z)
                / (92160.0 * v.powi(4));
    }
    StudentsT::new(0.0, 1.0, dof).map_or(f64::NAN, |t| t.inverse_cdf(0.975))
}

/// A sample mean with its 95 % confidence interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// Sample mean x̄ = Σ xᵢ / n.
    pub mean: f64,
    /// Lower end of the interval.
    pub lo: f64,
    /// Upper end of the interval.
    pub hi: f64,
    /// Number of values the estimate was made from.
    pub n: usize,
}

impl Estimate {
    /// Half-width (hi − lo) / 2.
    #[must_use]
    pub fn half_width(&self) -> f64 {
        0.5 * (self.hi - self.lo)
    }

    /// Is `x` inside [lo, hi]?
    #[must_use]
    pub fn contains(&self, x: f64) -> bool {
        self.lo <= x && x <= self.hi
    }
}

/// Sample mean with a 95 % Student-t confidence interval.
///
/// For n ≥ 2: x̄ = Σ xᵢ / n, s = sqrt( Σ (xᵢ − x̄)² / (n − 1) ) (sample standard deviation),
/// and `[lo, hi] = x̄ ∓ t₀.₉₇₅,ₙ₋₁ · s / √n` with [`t975`].
///
/// * n = 1: `lo = hi = mean`. One value says nothing about spread, so this degenerate
///   "interval" is **not** a confidence interval; callers should report it as such.
/// * n = 0: `mean`, `lo` and `hi` are NaN.
#[must_use]
pub fn mean_ci95(values: &[f64]) -> Estimate {
    let n = values.len();
    match n {
        0 => Estimate {
            mean: f64::NAN,
            lo: f64::NAN,
            hi: f64::NAN,
            n,
        },
        1 => Estimate {
            mean: values[0],
            lo: values[0],
            hi: values[0],
            n,
        },
        _ => {
            let nf = n as f64;
            let mean = values.iter().sum::<f64>() / nf;
            let ss = values.iter().map(|x| (x - mean) * (x - mean)).sum::<f64>();
            let s = (ss / (nf - 1.0)).sqrt();
            let half = t975(nf - 1.0) * s / nf.sqrt();
            Estimate {
                mean,
                lo: mean - half,
                hi: mean + half,
                n,
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Binomial proportions.
// ---------------------------------------------------------------------------------------------

/// A binomial count k out of n with a 95 % interval [lo, hi] for the underlying rate p.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Proportion {
    /// Number of successes (e.g. trials that jammed).
    pub k: u64,
    /// Number of trials.
    pub n: u64,
    /// Lower end of the interval for p, in [0, 1].
    pub lo: f64,
    /// Upper end of the interval for p, in [0, 1].
    pub hi: f64,
}

impl Proportion {
    /// Point estimate p̂ = k / n (NaN when n = 0).
    #[must_use]
    pub fn rate(&self) -> f64 {
        if self.n == 0 {
            f64::NAN
        } else {
            self.k as f64 / self.n as f64
        }
    }

    /// Is another count out of the same n inside the interval, i.e. `k_other / n ∈ [lo, hi]`?
    ///
    /// With n = 0 the interval is [0, 1] (no information) and this is `true`.
    #[must_use]
    pub fn contains_count(&self, k_other: u64) -> bool {
        if self.n == 0 {
            return true;
        }
        let p = k_other as f64 / self.n as f64;
        self.lo <= p && p <= self.hi
    }
}

/// Wilson score 95 % interval for k successes in n trials.
///
/// With p̂ = k / n and z = [`Z975`]:
///
/// ```text
/// centre = (p̂ + z²/(2n)) / (1 + z²/n)
/// half   = z / (1 + z²/n) · sqrt( p̂(1 − p̂)/n + z²/(4n²) )
/// [lo, hi] = centre ∓ half
/// ```
///
/// i.e. the set of p with |p̂ − p| ≤ z·sqrt(p(1 − p)/n). The ends are clamped to [0, 1] and
/// set exactly to 0 for k = 0 and to 1 for k = n. n = 0 gives [0, 1].
///
/// # Panics
/// If `k > n`.
#[must_use]
pub fn wilson95(k: u64, n: u64) -> Proportion {
    assert!(k <= n, "wilson95: k = {k} > n = {n}");
    if n == 0 {
        return Proportion {
            k,
            n,
            lo: 0.0,
            hi: 1.0,
        };
    }
    let nf = n as f64;
    let p = k as f64 / nf;
    let z2 = Z975 * Z975;
    let denom = 1.0 + z2 / nf;
    let centre = (p + z2 / (2.0 * nf)) / denom;
    let half = Z975 / denom * (p * (1.0 - p) / nf + z2 / (4.0 * nf * nf)).sqrt();
    let lo = if k == 0 {
        0.0
    } else {
        (centre - half).max(0.0)
    };
    let hi = if k == n {
        1.0
    } else {
        (centre + half).min(1.0)
    };
    Proportion { k, n, lo, hi }
}

/// Clopper–Pearson ("exact") 95 % interval for k successes in n trials.
///
/// The ends are Beta quantiles (equivalently, the p at which the binomial tails equal 2.5 %):
///
/// ```text
/// lo = B⁻¹(0.025; k, n − k + 1)      (lo = 0 for k = 0)
/// hi = B⁻¹(0.975; k + 1, n − k)      (hi = 1 for k = n)
/// ```
///
/// using `statrs`' `Beta::inverse_cdf`. The one-parameter cases have closed forms, used
/// exactly: k = 0 gives hi = 1 − 0.025^(1/n), k = n gives lo = 0.025^(1/n). n = 0 gives [0, 1].
///
/// # Panics
/// If `k > n`.
#[must_use]
pub fn clopper_pearson95(k: u64, n: u64) -> Proportion {
    assert!(k <= n, "clopper_pearson95: k = {k} > n = {n}");
    if n == 0 {
        return Proportion {
            k,
            n,
            lo: 0.0,
            hi: 1.0,
        };
    }
    let nf = n as f64;
    let kf = k as f64;
    let tail = 0.025_f64;
    let lo = if k == 0 {
        0.0
    } else if k == n {
        tail.powf(1.0 / nf)
    } else {
        Beta::new(kf, nf - kf + 1.0).map_or(f64::NAN, |b| b.inverse_cdf(tail))
    };
    let hi = if k == n {
        1.0
    } else if k == 0 {
        1.0 - tail.powf(1.0 / nf)
    } else {
        Beta::new(kf + 1.0, nf - kf).map_or(f64::NAN, |b| b.inverse_cdf(1.0 - tail))
    };
    Proportion { k, n, lo, hi }
}

// ---------------------------------------------------------------------------------------------
// Units.
// ---------------------------------------------------------------------------------------------

/// Days in a (Julian) year.
pub const DAYS_PER_YEAR: f64 = 365.25;

/// Days of calendar time per degree of a pointer that makes `turns_per_year` turns a year:
/// `DAYS_PER_YEAR / (360 · turns_per_year)`.
///
/// A pointer error of e degrees is therefore `e · days_per_degree(T)` days (e.g. the
/// once-a-year Sun pointer: ≈ 1.0146 days per degree).
#[must_use]
pub fn days_per_degree(turns_per_year: f64) -> f64 {
    DAYS_PER_YEAR / (360.0 * turns_per_year)
}

#[cfg(test)]
mod tests;
