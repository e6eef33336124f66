use super::*;

use std::f64::consts::TAU;

fn close(a: f64, b: f64, tol: f64) -> bool {
    (a - b).abs() <= tol * (1.0 + b.abs())
}

/// A smooth periodic TD-like series sampled uniformly on [0°, 360°) with an offset.
fn series(n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| {
            let t = TAU * i as f64 / n as f64;
            0.3 + 0.1 * t.sin() - 0.02 * (7.0 * t + 0.4).sin() + 0.005 * (113.0 * t).cos()
        })
        .collect()
}

/// Deterministic SplitMix64 uniform in (0, 1), no external crates.
struct Rng(u64);
impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        ((z >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn normal(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

// ----- pointer_stats -----

#[test]
fn pointer_stats_of_a_sinusoid() {
    // A·sin θ over a full period, sampled uniformly: P = 0, σ = A/√2, Dm = A (N divisible by 4).
    let a = 0.25;
    let n = 3600;
    let td: Vec<f64> = (0..n)
        .map(|i| a * (TAU * i as f64 / n as f64).sin())
        .collect();
    let s = pointer_stats(&td);
    assert!(s.mean.abs() < 1e-15, "{s:?}");
    assert!(close(s.sigma, a / 2f64.sqrt(), 1e-13), "{s:?}");
    assert!(close(s.dm, a, 1e-15), "{s:?}");
}

#[test]
fn pointer_stats_small_hand_example() {
    // [-3, 1, 2]: mean 0, population variance (9 + 1 + 4)/3, Dm = 3; mean stays signed.
    let s = pointer_stats(&[-3.0, 1.0, 2.0]);
    assert_eq!(s.mean, 0.0);
    assert!(close(s.sigma, (14.0_f64 / 3.0).sqrt(), 1e-15));
    assert_eq!(s.dm, 3.0);
    let s = pointer_stats(&[-1.0, -2.0]);
    assert_eq!(s.mean, -1.5);
    assert_eq!(s.sigma, 0.5);
    assert_eq!(s.dm, 2.0);
}

#[test]
fn pointer_stats_edge_cases() {
    let e = pointer_stats(&[]);
    assert!(e.sigma.is_nan() && e.dm.is_nan() && e.mean.is_nan());
    let one = pointer_stats(&[-0.7]);
    assert_eq!(
        one,
        PointerStats {
            sigma: 0.0,
            dm: 0.7,
            mean: -0.7
        }
    );
    let nan = pointer_stats(&[1.0, f64::NAN, 2.0]);
    assert!(nan.sigma.is_nan() && nan.dm.is_nan() && nan.mean.is_nan());
}

// ----- Accumulator -----

#[test]
fn accumulator_matches_batch() {
    for n in [1usize, 2, 3, 17, 1000, 100_000] {
        let td = series(n);
        let b = pointer_stats(&td);
        let acc: Accumulator = td.iter().copied().collect();
        assert_eq!(acc.count(), n as u64);
        assert!(close(acc.mean(), b.mean, 1e-12), "n={n}");
        assert!(close(acc.sigma(), b.sigma, 1e-12), "n={n}");
        assert_eq!(acc.max_abs(), b.dm, "n={n}");
        let s = acc.stats();
        assert_eq!(
            (s.mean, s.sigma, s.dm),
            (acc.mean(), acc.sigma(), acc.max_abs())
        );
    }
}

#[test]
fn accumulator_large_offset_is_stable() {
    // Naive Σx² − (Σx)²/N would lose everything here; neither the corrected two-pass batch
    // nor the shifted Welford accumulator may (plain Welford loses ~1e-6 relative here).
    let td: Vec<f64> = series(10_000).iter().map(|x| 1e8 + x).collect();
    let b = pointer_stats(&td);
    let acc: Accumulator = td.iter().copied().collect();
    let want = pointer_stats(&series(10_000)).sigma;
    assert!(close(b.sigma, want, 1e-7), "{} vs {want}", b.sigma);
    assert!(close(acc.sigma(), want, 1e-7), "{} vs {want}", acc.sigma());
    assert!(close(acc.mean(), b.mean, 1e-15));
    // Merged chunks with different shifts agree as well.
    let mut merged = Accumulator::new();
    for c in td.chunks(999) {
        merged.merge(&c.iter().copied().collect());
    }
    assert!(close(merged.sigma(), want, 1e-7), "{}", merged.sigma());
    assert!(close(merged.mean(), b.mean, 1e-15));
}

#[test]
fn accumulator_merge_order() {
    let td = series(10_007);
    let batch = pointer_stats(&td);
    let chunks: Vec<Accumulator> = td
        .chunks(1234)
        .map(|c| c.iter().copied().collect())
        .collect();

    let fold = |order: &[usize]| {
        let mut acc = Accumulator::new();
        for &i in order {
            acc.merge(&chunks[i]);
        }
        acc
    };
    let forward: Vec<usize> = (0..chunks.len()).collect();
    let reverse: Vec<usize> = forward.iter().rev().copied().collect();
    let shuffled: Vec<usize> = (0..chunks.len())
        .map(|i| (i * 5 + 3) % chunks.len())
        .collect();
    assert_eq!(chunks.len(), 9);

    let a = fold(&forward);
    // Same order twice: bit-identical (determinism).
    assert_eq!(a, fold(&forward));
    for acc in [a, fold(&reverse), fold(&shuffled)] {
        assert_eq!(acc.count(), td.len() as u64);
        assert!(close(acc.mean(), batch.mean, 1e-12));
        assert!(close(acc.sigma(), batch.sigma, 1e-12));
        assert_eq!(acc.max_abs(), batch.dm);
    }

    // Tree merge (pairs, then pairs of pairs) agrees too.
    let mut level = chunks.clone();
    while level.len() > 1 {
        level = level
            .chunks(2)
            .map(|p| {
                let mut x = p[0];
                if let Some(y) = p.get(1) {
                    x.merge(y);
                }
                x
            })
            .collect();
    }
    assert!(close(level[0].sigma(), batch.sigma, 1e-12));
    assert!(close(level[0].mean(), batch.mean, 1e-12));
}

#[test]
fn accumulator_edge_cases() {
    let empty = Accumulator::new();
    assert_eq!(empty, Accumulator::default());
    assert_eq!(empty.count(), 0);
    assert!(empty.mean().is_nan() && empty.sigma().is_nan() && empty.max_abs().is_nan());

    let mut one = Accumulator::new();
    one.push(-2.5);
    assert_eq!((one.mean(), one.sigma(), one.max_abs()), (-2.5, 0.0, 2.5));

    // Merging with empty on either side is exact.
    let full: Accumulator = series(100).into_iter().collect();
    let mut x = full;
    x.merge(&Accumulator::new());
    assert_eq!(x, full);
    let mut y = Accumulator::new();
    y.merge(&full);
    assert_eq!(y, full);

    // Constant series: zero spread, exactly.
    let c: Accumulator = std::iter::repeat_n(0.125, 1000).collect();
    assert_eq!((c.mean(), c.sigma()), (0.125, 0.0));

    // NaN propagates.
    let mut n = full;
    n.push(f64::NAN);
    assert!(n.mean().is_nan() && n.sigma().is_nan() && n.max_abs().is_nan());
    n.push(1.0);
    assert!(n.max_abs().is_nan());
}

// ----- Student t and mean_ci95 -----

#[test]
fn t_quantiles_match_tables() {
    // Standard two-sided 95 % table values.
    for (dof, t) in [
        (1.0, 12.706_204_736),
        (2.0, 4.302_652_730),
        (5.0, 2.570_581_836),
        (10.0, 2.228_138_852),
        (29.0, 2.045_229_642),
        (100.0, 1.983_971_519),
    ] {
        assert!(close(t975(dof), t, 1e-8), "dof {dof}: {} vs {t}", t975(dof));
    }
    // The values as printed, rounded, in the t tables a reader checks them against.
    assert!((t975(29.0) - 2.0452).abs() < 5e-5);
    assert!((t975(1.0) - 12.706).abs() < 5e-4);
    assert!((t975(f64::INFINITY) - 1.95996).abs() < 5e-6);
    assert_eq!(t975(f64::INFINITY), Z975);
    // Large but finite dof: continuous across the switch to the expansion, decreasing, and
    // approaching z from above (statrs alone drifts below z past ~1e5 dof).
    let below = t975(T_EXPANSION_DOF);
    let above = t975(T_EXPANSION_DOF.next_up());
    assert!((below - above).abs() < 1e-11, "{below} vs {above}");
    let mut prev = t975(100.0);
    for dof in [300.0, 1e3, 3e3, 1e4, 1e5, 1e6, 1e7, 1e9, 1e12] {
        let t = t975(dof);
        assert!(Z975 <= t && t < prev, "dof {dof}: {t}");
        prev = t;
    }
    assert!((t975(1e6) - 1.959_966_357).abs() < 1e-9);
    assert!(t975(0.0).is_nan() && t975(-1.0).is_nan() && t975(f64::NAN).is_nan());
}

#[test]
fn z975_matches_statrs_normal() {
    use statrs::distribution::Normal;
    let z = Normal::new(0.0, 1.0).map_or(f64::NAN, |d| d.inverse_cdf(0.975));
    assert!((z - Z975).abs() < 1e-12, "{z}");
}

#[test]
fn mean_ci95_hand_example() {
    // 1..=5: mean 3, s = √2.5, half = t₀.₉₇₅,₄ · s / √5 with t₀.₉₇₅,₄ = 2.776445105.
    let e = mean_ci95(&[1.0, 2.0, 3.0, 4.0, 5.0]);
    let half = 2.776_445_105 * 2.5_f64.sqrt() / 5f64.sqrt();
    assert_eq!(e.n, 5);
    assert_eq!(e.mean, 3.0);
    assert!(
        close(e.lo, 3.0 - half, 1e-9) && close(e.hi, 3.0 + half, 1e-9),
        "{e:?}"
    );
    assert!(close(e.half_width(), half, 1e-9));
    assert!(e.contains(3.0) && e.contains(1.04) && !e.contains(1.03) && !e.contains(5.0));
}

#[test]
fn mean_ci95_edge_cases() {
    let e = mean_ci95(&[]);
    assert_eq!(e.n, 0);
    assert!(e.mean.is_nan() && e.lo.is_nan() && e.hi.is_nan());
    let one = mean_ci95(&[0.42]);
    assert_eq!(
        one,
        Estimate {
            mean: 0.42,
            lo: 0.42,
            hi: 0.42,
            n: 1
        }
    );
    let same = mean_ci95(&[2.0; 7]);
    assert_eq!((same.lo, same.mean, same.hi), (2.0, 2.0, 2.0));
}

#[test]
fn mean_ci95_covers_about_95_percent() {
    // 4000 samples of size 5 from N(1, 2²), fixed seed: coverage ≈ 0.95
    // (binomial sd ≈ 0.0034, so ±0.015 is > 4 sd).
    let mut rng = Rng(12345);
    let trials = 4000;
    let mut hits = 0;
    for _ in 0..trials {
        let xs: Vec<f64> = (0..5).map(|_| 1.0 + 2.0 * rng.normal()).collect();
        if mean_ci95(&xs).contains(1.0) {
            hits += 1;
        }
    }
    let cov = f64::from(hits) / f64::from(trials);
    assert!((cov - 0.95).abs() < 0.015, "coverage {cov}");
}

// ----- Binomial intervals -----

/// Independent Wilson check: the roots of (p̂ − p)² = z² p(1 − p)/n, found by bisection.
fn wilson_by_bisection(k: u64, n: u64) -> (f64, f64) {
    let p_hat = k as f64 / n as f64;
    let z = 1.959_963_984_540_054;
    let f = |p: f64| (p_hat - p).powi(2) - z * z * p * (1.0 - p) / n as f64;
    // f > 0 outside the interval, ≤ 0 inside; p̂ is inside.
    let root = |mut outside: f64, mut inside: f64| {
        for _ in 0..200 {
            let mid = 0.5 * (outside + inside);
            if f(mid) > 0.0 {
                outside = mid;
            } else {
                inside = mid;
            }
        }
        0.5 * (outside + inside)
    };
    let lo = if k == 0 { 0.0 } else { root(0.0, p_hat) };
    let hi = if k == n { 1.0 } else { root(1.0, p_hat) };
    (lo, hi)
}

/// Independent binomial CDF P(X ≤ k) by summing the pmf with the ratio recurrence.
/// For p > 1/2 it uses P(X ≤ k; p) = 1 − P(X ≤ n − k − 1; 1 − p) so (1 − p)ⁿ cannot underflow.
fn binom_cdf(k: u64, n: u64, p: f64) -> f64 {
    if k >= n {
        return 1.0;
    }
    if p > 0.5 {
        return 1.0 - binom_cdf(n - k - 1, n, 1.0 - p);
    }
    let q = 1.0 - p;
    let mut term = q.powf(n as f64);
    let mut sum = term;
    for i in 0..k {
        term *= (n - i) as f64 / (i + 1) as f64 * p / q;
        sum += term;
    }
    sum
}

/// Independent Clopper–Pearson check by bisection on the binomial tails.
fn cp_by_bisection(k: u64, n: u64) -> (f64, f64) {
    let bisect = |g: &dyn Fn(f64) -> f64| {
        // g increasing in p, find g(p) = 0.
        let (mut a, mut b) = (0.0_f64, 1.0_f64);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if g(m) < 0.0 {
                a = m;
            } else {
                b = m;
            }
        }
        0.5 * (a + b)
    };
    // lo: P(X ≥ k; p) = 0.025, i.e. 1 − P(X ≤ k−1) − 0.025 = 0 (increasing in p).
    let lo = if k == 0 {
        0.0
    } else {
        bisect(&|p| 1.0 - binom_cdf(k - 1, n, p) - 0.025)
    };
    // hi: P(X ≤ k; p) = 0.025 (decreasing in p).
    let hi = if k == n {
        1.0
    } else {
        bisect(&|p| 0.025 - binom_cdf(k, n, p))
    };
    (lo, hi)
}

#[test]
fn wilson_reference_values() {
    let w = wilson95(0, 200);
    assert_eq!((w.k, w.n, w.lo), (0, 200, 0.0));
    assert!((w.hi - 0.0188).abs() < 5e-5, "{w:?}");
    // Closed form for k = 0: hi = z²/(n + z²).
    assert!(close(w.hi, Z975 * Z975 / (200.0 + Z975 * Z975), 1e-14));

    let w = wilson95(2, 200);
    assert!((w.lo - 0.00275).abs() < 5e-6, "{w:?}");
    // 0.0358 is sometimes quoted for this bound; the formula and the bisection below both give
    // 0.035722.
    assert!((w.hi - 0.035_72).abs() < 5e-6, "{w:?}");

    let w = wilson95(200, 200);
    assert_eq!(w.hi, 1.0);
    assert!(close(w.lo, 200.0 / (200.0 + Z975 * Z975), 1e-14));
}

#[test]
fn wilson_matches_bisection() {
    for (k, n) in [
        (0, 1),
        (1, 1),
        (0, 200),
        (1, 200),
        (2, 200),
        (17, 200),
        (100, 200),
        (199, 200),
        (200, 200),
        (3, 10),
        (5000, 100_000),
    ] {
        let w = wilson95(k, n);
        let (lo, hi) = wilson_by_bisection(k, n);
        assert!((w.lo - lo).abs() < 1e-12, "{k}/{n}: {w:?} vs {lo}");
        assert!((w.hi - hi).abs() < 1e-12, "{k}/{n}: {w:?} vs {hi}");
        assert!(0.0 <= w.lo && w.lo <= w.rate() && w.rate() <= w.hi && w.hi <= 1.0);
    }
}

#[test]
fn clopper_pearson_exact_ends() {
    let c = clopper_pearson95(0, 200);
    assert_eq!(c.lo, 0.0);
    assert_eq!(c.hi, 1.0 - 0.025_f64.powf(1.0 / 200.0));
    let c = clopper_pearson95(200, 200);
    assert_eq!(c.hi, 1.0);
    assert_eq!(c.lo, 0.025_f64.powf(1.0 / 200.0));
    // 0/200 upper ≈ 0.01827 (the "rule of three" gives ≈ 3.69/200 at 97.5 %).
    assert!((clopper_pearson95(0, 200).hi - 0.018_27).abs() < 1e-5);
}

#[test]
fn clopper_pearson_matches_bisection() {
    for (k, n) in [
        (1, 200),
        (2, 200),
        (17, 200),
        (100, 200),
        (199, 200),
        (1, 2),
        (3, 10),
        (9, 10),
        (0, 1),
        (1, 1),
    ] {
        let c = clopper_pearson95(k, n);
        let (lo, hi) = cp_by_bisection(k, n);
        assert!((c.lo - lo).abs() < 1e-9, "{k}/{n}: {c:?} vs {lo}");
        assert!((c.hi - hi).abs() < 1e-9, "{k}/{n}: {c:?} vs {hi}");
        // Symmetry k ↔ n − k.
        let m = clopper_pearson95(n - k, n);
        assert!((c.lo - (1.0 - m.hi)).abs() < 1e-12 && (c.hi - (1.0 - m.lo)).abs() < 1e-12);
        // The interval holds the point estimate. (It is not always wider than Wilson's at
        // both ends: 1/200 has CP hi 0.02754 < Wilson hi 0.02777, and 199/200 mirrors it.)
        assert!(c.lo <= c.rate() && c.rate() <= c.hi, "{c:?}");
    }
    // Published value: 2/200 → [0.00121, 0.0357].
    let c = clopper_pearson95(2, 200);
    assert!(
        (c.lo - 0.001_21).abs() < 5e-6 && (c.hi - 0.0357).abs() < 5e-5,
        "{c:?}"
    );
}

#[test]
fn proportion_contains_count() {
    let w = wilson95(2, 200); // [0.00275, 0.0358] → counts 1..=7 inside.
    assert!(!w.contains_count(0));
    for k in 1..=7 {
        assert!(w.contains_count(k), "{k}");
    }
    assert!(!w.contains_count(8));
    assert!(!w.contains_count(201));
    let z = wilson95(0, 200);
    assert!(z.contains_count(0) && z.contains_count(3) && !z.contains_count(4));
    let all = clopper_pearson95(200, 200);
    assert!(all.contains_count(200) && !all.contains_count(190));
}

#[test]
fn proportion_edge_cases() {
    for p in [wilson95(0, 0), clopper_pearson95(0, 0)] {
        assert_eq!((p.lo, p.hi), (0.0, 1.0));
        assert!(p.rate().is_nan());
        assert!(p.contains_count(0));
    }
    assert_eq!(wilson95(3, 12).rate(), 0.25);
}

#[test]
#[should_panic(expected = "k = 3 > n = 2")]
fn wilson_rejects_k_above_n() {
    let _ = wilson95(3, 2);
}

#[test]
#[should_panic(expected = "k = 3 > n = 2")]
fn clopper_pearson_rejects_k_above_n() {
    let _ = clopper_pearson95(3, 2);
}

// ----- Units -----

#[test]
fn units() {
    assert_eq!(DAYS_PER_YEAR, 365.25);
    assert_eq!(days_per_degree(1.0), 365.25 / 360.0);
    assert!(close(days_per_degree(1.0), 1.014_583_333_333_333, 1e-15));
    // A pointer turning 4 times a year: 4× fewer days per degree.
    assert!(close(
        days_per_degree(4.0),
        days_per_degree(1.0) / 4.0,
        1e-15
    ));
    // 360° of error on a once-a-year pointer is a whole year.
    assert!(close(360.0 * days_per_degree(1.0), DAYS_PER_YEAR, 1e-15));
}
