//! Where two contact conditions hold at once, exactly: the building block an event-predicting
//! solver would use in place of bounds (BENCHMARKS.md, "Where an engagement's work goes,
//! counted; what the next solver core must do"), measured:
//! `cargo run --release -p contact --example meetings`. (`src/meet.rs` is this, in the crate.)
//!
//! Every straight-flank contact condition (a vertex on a flank line) reads
//! `A(u)·cos θ + B(u)·sin θ = H(u)` with A, B, H affine in u = (cos φ, sin φ). Two of them fix
//! (cos θ, sin θ) by Cramer's rule wherever their determinant is not zero, and cos² + sin² = 1
//! leaves one equation in φ: with t = tan(ψ/2), ψ = φ − φc, a polynomial of degree 8 in t. Over a
//! driver pitch its Bernstein coefficients either share a sign (no meeting in the pitch: proved)
//! or the roots are isolated by subdivision. The example checks the roots against a brute-force
//! scan of the same two conditions and times the exclusion test and the isolation.
#![allow(missing_docs, clippy::unwrap_used, reason = "measurement harness")]

use std::f64::consts::TAU;
use std::hint::black_box;
use std::time::Instant;

use geometry::Vec2;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

mod support;

use support::{MESHES, gear};

/// `A·cos θ + B·sin θ = H`, each of A, B, H as [constant, coefficient of cos φ, of sin φ].
#[derive(Debug, Clone, Copy)]
struct Cond {
    a: [f64; 3],
    b: [f64; 3],
    h: [f64; 3],
}

/// Driver vertex `p` (driver frame) on the line `m·x = h` of a driven flank (driven frame): the
/// driven vertex frame is placed at c2 + R(π − θ)x, the driver's at R(φ)x.
fn driver_vertex(p: Vec2, m: Vec2, h: f64, d: f64) -> Cond {
    let dot = m.x * p.x + m.y * p.y;
    let cross = m.x * p.y - m.y * p.x;
    Cond {
        a: [m.x * d, -dot, cross],
        b: [m.y * d, cross, dot],
        h: [h, 0.0, 0.0],
    }
}

/// Driven vertex `q` (driven frame) on the line `n·x = h` of a driver flank (driver frame).
fn driven_vertex(q: Vec2, n: Vec2, h: f64, d: f64) -> Cond {
    let dot = n.x * q.x + n.y * q.y;
    let cross = n.y * q.x - n.x * q.y;
    Cond {
        a: [0.0, -dot, cross],
        b: [0.0, cross, dot],
        h: [h, -d * n.x, d * n.y],
    }
}

impl Cond {
    /// The residual at (φ, θ).
    fn at(&self, phi: f64, theta: f64) -> f64 {
        let f = |v: [f64; 3]| v[0] + v[1] * phi.cos() + v[2] * phi.sin();
        f(self.a) * theta.cos() + f(self.b) * theta.sin() - f(self.h)
    }
}

type Poly = [f64; 9];

/// An affine form in (cos φ, sin φ) about φc, times (1 + t²), t = tan((φ − φc)/2): degree 2.
fn quad(v: [f64; 3], (s, c): (f64, f64)) -> [f64; 3] {
    // cos φ = cos φc cos ψ − sin φc sin ψ, sin φ = sin φc cos ψ + cos φc sin ψ.
    let (k, cc, ss) = (v[0], v[1] * c + v[2] * s, -v[1] * s + v[2] * c);
    // k(1 + t²) + cc(1 − t²) + ss·2t.
    [k + cc, 2.0 * ss, k - cc]
}

fn mul<const N: usize, const M: usize, const K: usize>(p: [f64; N], q: [f64; M]) -> [f64; K] {
    let mut r = [0.0; K];
    for (i, a) in p.iter().enumerate() {
        for (j, b) in q.iter().enumerate() {
            r[i + j] += a * b;
        }
    }
    r
}

fn sub<const N: usize>(p: [f64; N], q: [f64; N]) -> [f64; N] {
    std::array::from_fn(|i| p[i] - q[i])
}

/// The polynomial in t whose roots are where `c1` and `c2` hold at once (for some θ).
fn meeting_poly(c1: &Cond, c2: &Cond, phi_c: f64) -> Poly {
    let sc = phi_c.sin_cos();
    let (a1, b1, h1) = (quad(c1.a, sc), quad(c1.b, sc), quad(c1.h, sc));
    let (a2, b2, h2) = (quad(c2.a, sc), quad(c2.b, sc), quad(c2.h, sc));
    let cos_num: [f64; 5] = sub(mul(h1, b2), mul(h2, b1));
    let sin_num: [f64; 5] = sub(mul(a1, h2), mul(a2, h1));
    let det: [f64; 5] = sub(mul(a1, b2), mul(a2, b1));
    let x: Poly = mul(cos_num, cos_num);
    let y: Poly = mul(sin_num, sin_num);
    let z: Poly = mul(det, det);
    std::array::from_fn(|i| x[i] + y[i] - z[i])
}

/// Bernstein coefficients of `p` over t in [t0, t1].
fn bernstein(p: &Poly, t0: f64, t1: f64) -> Poly {
    const N: usize = 8;
    // Taylor shift to t0, then scale by w: q(x) = p(t0 + w x).
    let mut q = *p;
    for i in 0..N {
        for j in (i..N).rev() {
            q[j] += t0 * q[j + 1];
        }
    }
    let w = t1 - t0;
    let mut s = 1.0;
    for c in &mut q {
        *c *= s;
        s *= w;
    }
    // Power to Bernstein: b_i = sum_{j <= i} C(i, j) / C(N, j) q_j.
    let binom = |n: usize, k: usize| -> f64 {
        (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
    };
    std::array::from_fn(|i| (0..=i).map(|j| binom(i, j) / binom(N, j) * q[j]).sum())
}

/// Whether the Bernstein coefficients prove no root (all of one sign, beyond their rounding).
fn no_root(b: &Poly) -> bool {
    let scale = b.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let eps = 1e-12 * scale;
    b.iter().all(|&x| x > eps) || b.iter().all(|&x| x < -eps)
}

/// Roots of `p` in [t0, t1], isolated by subdivision and refined by bisection.
fn roots(p: &Poly, t0: f64, t1: f64, out: &mut Vec<f64>) {
    if no_root(&bernstein(p, t0, t1)) {
        return;
    }
    let v = |t: f64| p.iter().rev().fold(0.0, |acc, c| acc * t + c);
    if t1 - t0 < 1e-6 {
        let (mut a, mut b) = (t0, t1);
        if v(a).signum() == v(b).signum() {
            // A double root or none at this resolution: report the middle.
            out.push(0.5 * (a + b));
            return;
        }
        for _ in 0..60 {
            let m = 0.5 * (a + b);
            if v(m).signum() == v(a).signum() {
                a = m;
            } else {
                b = m;
            }
        }
        out.push(0.5 * (a + b));
        return;
    }
    let m = 0.5 * (t0 + t1);
    roots(p, t0, m, out);
    roots(p, m, t1, out);
}

/// Every condition of driver tooth `a` and driven tooth `b` (vertices on the other's flank
/// lines), with the vertex and flank for the beside test.
fn conditions(a: [Vec2; 3], b: [Vec2; 3], d: f64) -> Vec<Cond> {
    let line = |t: [Vec2; 3], f: usize| {
        let e = t[f + 1] - t[f];
        let n = Vec2::new(e.y, -e.x) / e.norm();
        (n, n.dot(&t[f]))
    };
    let mut out = Vec::new();
    for f in 0..2 {
        let (m, h) = line(b, f);
        // The tip only: at G > 0 the valleys never reach the other gear.
        out.push(driver_vertex(a[1], m, h, d));
        let (n, h) = line(a, f);
        out.push(driven_vertex(b[1], n, h, d));
    }
    out
}

fn main() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    // m3-e3, random tip errors σ = 0.04 pitch.
    let (_, n1, n2, r1, r2) = MESHES[0];
    let (g1, g2) = (gear(n1, r1, 0.04, &mut rng), gear(n2, r2, 0.04, &mut rng));
    let d = geometry::centre_distance(r1, r2, 1.1, 40.0);
    let pitch = TAU / n1 as f64;
    // Pairs of conditions of teeth near the mesh: driver teeth 0..3 and driven teeth about the
    // line of centres, each against every other, over a driver pitch about φc.
    let mut cases = Vec::new();
    for _ in 0..400 {
        let j = rng.random_range(0..3_i64);
        let k1 = rng.random_range(-3..3_i64);
        let k2 = rng.random_range(-3..3_i64);
        let j2 = rng.random_range(0..3_i64);
        let c1 = conditions(g1.tooth(j), g2.tooth(k1), d);
        let c2 = conditions(g1.tooth(j2), g2.tooth(k2), d);
        let phi_c = -g1.tip_angle(j) + pitch * (rng.random::<f64>() - 0.5);
        for (ix, x) in c1.iter().enumerate() {
            for (iy, y) in c2.iter().enumerate() {
                // A condition met with itself is no meeting (the polynomial is zero).
                if (j, k1, ix) != (j2, k2, iy) {
                    cases.push((*x, *y, phi_c));
                }
            }
        }
    }
    // Half a pitch either side of φc, in t = tan(ψ/2).
    let t_half = (0.5 * pitch / 2.0).tan();
    // Check the roots against a scan: along a fine grid of φ, condition 1 solved for θ (both
    // branches) and condition 2's sign watched.
    let (mut found, mut scanned, mut excluded, mut disagree) = (0, 0, 0, 0);
    let mut worst: f64 = 0.0;
    for (c1, c2, phi_c) in &cases {
        let p = meeting_poly(c1, c2, *phi_c);
        let mut rs = Vec::new();
        roots(&p, -t_half, t_half, &mut rs);
        excluded += usize::from(rs.is_empty());
        found += rs.len();
        for &t in &rs {
            let phi = phi_c + 2.0 * t.atan();
            // θ from Cramer's rule, both conditions' residuals at it.
            let f = |v: [f64; 3]| v[0] + v[1] * phi.cos() + v[2] * phi.sin();
            let (a1, b1, h1, a2, b2, h2) = (f(c1.a), f(c1.b), f(c1.h), f(c2.a), f(c2.b), f(c2.h));
            let det = a1 * b2 - a2 * b1;
            let theta = ((a1 * h2 - a2 * h1) / det).atan2((h1 * b2 - h2 * b1) / det);
            worst = worst
                .max(c1.at(phi, theta).abs())
                .max(c2.at(phi, theta).abs());
        }
        // The scan: condition 1's θ branches at each φ, condition 2's residual there.
        let scanned_before = scanned;
        let steps = 4000;
        let mut last: [Option<f64>; 2] = [None, None];
        for i in 0..=steps {
            let phi = phi_c - 0.5 * pitch + pitch * i as f64 / steps as f64;
            let f = |v: [f64; 3]| v[0] + v[1] * phi.cos() + v[2] * phi.sin();
            let (a, b, h) = (f(c1.a), f(c1.b), f(c1.h));
            let r = a.hypot(b);
            if h.abs() > r {
                last = [None, None];
                continue;
            }
            let base = b.atan2(a);
            let spread = (h / r).acos();
            for (s, branch) in [1.0, -1.0].into_iter().enumerate() {
                let theta = base + branch * spread;
                let g = c2.at(phi, theta);
                if let Some(prev) = last[s]
                    && prev.signum() != g.signum()
                {
                    scanned += 1;
                }
                last[s] = Some(g);
            }
        }
        disagree += usize::from(scanned - scanned_before != rs.len());
    }
    println!(
        "{} pairs of conditions over a driver pitch: {} with no meeting (proved), {} meetings found \
         ({} sign changes seen by a 4000-point scan, {} pairs where the counts differ); largest \
         residual at a meeting {:.1e} mm",
        cases.len(),
        excluded,
        found,
        scanned,
        disagree,
        worst
    );
    // Timing: the polynomial and its Bernstein test alone, and with the isolation.
    let reps = 200;
    let t0 = Instant::now();
    let mut n_excl = 0;
    for _ in 0..reps {
        for (c1, c2, phi_c) in &cases {
            let p = meeting_poly(black_box(c1), black_box(c2), *phi_c);
            n_excl += usize::from(no_root(&bernstein(&p, -t_half, t_half)));
        }
    }
    let per_test = t0.elapsed().as_secs_f64() / (reps * cases.len()) as f64;
    let t0 = Instant::now();
    let mut rs = Vec::new();
    for _ in 0..reps {
        for (c1, c2, phi_c) in &cases {
            rs.clear();
            let p = meeting_poly(black_box(c1), black_box(c2), *phi_c);
            roots(&p, -t_half, t_half, &mut rs);
            black_box(&rs);
        }
    }
    let per_solve = t0.elapsed().as_secs_f64() / (reps * cases.len()) as f64;
    println!(
        "per pair of conditions: polynomial and exclusion test {:.0} ns ({} of {} excluded), \
         with the isolation of every root {:.0} ns",
        per_test * 1e9,
        n_excl / reps,
        cases.len(),
        per_solve * 1e9
    );
}
