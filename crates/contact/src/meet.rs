//! Where contact conditions hold, solved exactly: the roots the solver's events are made of.
//!
//! Every contact condition of two teeth - a vertex of one gear on a straight flank of the other,
//! a vertex on a flank arc, two arcs tangent, an arc tangent to a straight flank - reads
//! `F(φ, θ) = 0` with F bilinear in (1, cos φ, sin φ) and (1, cos θ, sin θ): a point of the
//! driver turns with φ, a point of the driven gear with θ, and each condition is a dot product or
//! a squared distance of the two (see [`Condition`]). So:
//!
//! - with θ fixed (the driven gear at rest or held), a condition is `a + b·cos φ + c·sin φ = 0`,
//!   solved in closed form ([`Condition::roots_at_theta`]);
//! - where two conditions hold at once (two contacts meeting: a pair taking over from another, a
//!   driver tooth closing on the driven gear, a gap opening between two obstacles), Cramer's rule
//!   gives (cos θ, sin θ) and cos² + sin² = 1 leaves one polynomial of degree 8 in
//!   t = tan((φ − φc)/2); over an interval of φ its Bernstein coefficients either share a sign
//!   (no meeting there: proved) or its roots are isolated by subdivision ([`meetings`]).
//!
//! The roots are where the conditions hold, not yet where the teeth touch: a condition holds on
//! the whole line or circle of a flank, and the caller checks each root against the contact it
//! stands for.

use geometry::Vec2;
use smallvec::SmallVec;

use crate::tooth::wrap_pi;

/// A contact condition `F(φ, θ) = 0`: `k[j][i]` is the coefficient of `u_i(φ)·w_j(θ)`, with
/// u = (1, cos φ, sin φ) and w = (1, cos θ, sin θ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Condition {
    k: [[f64; 3]; 3],
}

/// A world-frame quantity that depends on φ only: coefficients of (1, cos φ, sin φ).
type PhiForm = [f64; 3];
/// A world-frame quantity that depends on θ only: coefficients of (1, cos θ, sin θ).
type ThetaForm = [f64; 3];

/// A driver point `p` (gear frame, from its rotation centre) in the world: R(φ)p.
fn driver_point(p: Vec2) -> [PhiForm; 2] {
    [[0.0, p.x, -p.y], [0.0, p.y, p.x]]
}

/// A driven point `q` (gear frame) in the world: c2 + R(π − θ)q, c2 = (D, 0).
fn driven_point(q: Vec2, d: f64) -> [ThetaForm; 2] {
    [[d, -q.x, -q.y], [0.0, -q.y, q.x]]
}

/// A driven direction `m` in the world: R(π − θ)m.
fn driven_direction(m: Vec2) -> [ThetaForm; 2] {
    driven_point(m, 0.0)
}

impl Condition {
    fn zero() -> Self {
        Self { k: [[0.0; 3]; 3] }
    }

    /// `f(φ)·g(θ)` added to the condition.
    fn add_product(&mut self, f: PhiForm, g: ThetaForm) {
        for (row, gj) in self.k.iter_mut().zip(g) {
            for (c, fi) in row.iter_mut().zip(f) {
                *c += fi * gj;
            }
        }
    }

    /// The dot product of a driver and a driven world vector added to the condition.
    fn add_dot(&mut self, a: [PhiForm; 2], b: [ThetaForm; 2]) {
        self.add_product(a[0], b[0]);
        self.add_product(a[1], b[1]);
    }

    fn add_theta(&mut self, g: ThetaForm, scale: f64) {
        for (row, gj) in self.k.iter_mut().zip(g) {
            row[0] += scale * gj;
        }
    }

    /// Driver point `p` on the driven gear's line `m·y = h` (`m` a unit normal, gear frame),
    /// shifted by `offset` along `m` (an arc's centre at its radius from the line).
    pub(crate) fn driver_point_on_line(p: Vec2, m: Vec2, h: f64, d: f64) -> Self {
        // (R m)·(R(φ)p − c2) = h, and (R m)·c2 = D (R m)_x.
        let mut c = Self::zero();
        let n = driven_direction(m);
        c.add_dot(driver_point(p), n);
        c.add_theta(n[0], -d);
        c.k[0][0] -= h;
        c
    }

    /// Driven point `q` on the driver's line `n·x = h` (`n` a unit normal, gear frame).
    pub(crate) fn driven_point_on_line(q: Vec2, n: Vec2, h: f64, d: f64) -> Self {
        let mut c = Self::zero();
        c.add_dot(driver_point(n), driven_point(q, d));
        c.k[0][0] -= h;
        c
    }

    /// Driver point `p` at distance `r` from driven point `q` (both gear frame):
    /// |p|² + |Y|² − 2 X·Y = r², with |Y|² = D² + |q|² + 2D·(R q)_x.
    pub(crate) fn points_apart(p: Vec2, q: Vec2, r: f64, d: f64) -> Self {
        let mut c = Self::zero();
        let y = driven_point(q, d);
        c.add_dot(driver_point(p * -2.0), y);
        c.add_theta([d * d + q.norm_squared(), 0.0, 0.0], 1.0);
        c.add_theta(driven_point(q, 0.0)[0], 2.0 * d);
        c.k[0][0] += p.norm_squared() - r * r;
        c
    }

    /// The condition with the driven angle read `tau` lower: G(φ, θ) = F(φ, θ − τ), so that G
    /// holds a driven angle τ above where F does.
    pub(crate) fn shifted(&self, tau: f64) -> Self {
        let (s, c) = tau.sin_cos();
        let [k0, k1, k2] = self.k;
        Self {
            k: [
                k0,
                std::array::from_fn(|i| k1[i] * c - k2[i] * s),
                std::array::from_fn(|i| k1[i] * s + k2[i] * c),
            ],
        }
    }

    /// The residual F(φ, θ) (a length, or a squared length for distance conditions).
    pub(crate) fn at(&self, phi: f64, theta: f64) -> f64 {
        let (a, b, h) = self.abh(phi);
        let (s, c) = theta.sin_cos();
        a * c + b * s - h
    }

    /// (A, B, H) of `A cos θ + B sin θ = H` at φ.
    fn abh(&self, phi: f64) -> (f64, f64, f64) {
        let (s, c) = phi.sin_cos();
        let f = |row: [f64; 3]| row[0] + row[1] * c + row[2] * s;
        (f(self.k[1]), f(self.k[2]), -f(self.k[0]))
    }

    /// The driven angles at which the condition holds at φ (none, or two, nearest `near` first
    /// and each within π of it).
    pub(crate) fn thetas(&self, phi: f64, near: f64) -> SmallVec<[f64; 2]> {
        let (a, b, h) = self.abh(phi);
        let r = a.hypot(b);
        let mut out = SmallVec::new();
        if r == 0.0 || h.abs() > r {
            return out;
        }
        let base = b.atan2(a);
        let spread = (h / r).clamp(-1.0, 1.0).acos();
        for t in [base + spread, base - spread] {
            out.push(near + wrap_pi(t - near));
        }
        if (out[1] - near).abs() < (out[0] - near).abs() {
            out.swap(0, 1);
        }
        out
    }

    /// The driver angles in `(phi0, phi1]` at which the condition holds with the driven gear at
    /// θ: `a + b cos φ + c sin φ = 0`, in closed form.
    pub(crate) fn roots_at_theta(&self, theta: f64, phi0: f64, phi1: f64) -> SmallVec<[f64; 2]> {
        let (s, c) = theta.sin_cos();
        let coef = |i: usize| self.k[0][i] + self.k[1][i] * c + self.k[2][i] * s;
        let (a, b, cc) = (coef(0), coef(1), coef(2));
        let r = b.hypot(cc);
        let mut out = SmallVec::new();
        if r == 0.0 || a.abs() > r {
            return out;
        }
        // b cos φ + c sin φ = r cos(φ − β) = −a.
        let beta = cc.atan2(b);
        let spread = (-a / r).clamp(-1.0, 1.0).acos();
        for x in [beta - spread, beta + spread] {
            let phi = phi0 + (x - phi0).rem_euclid(std::f64::consts::TAU);
            if phi > phi0 && phi <= phi1 {
                out.push(phi);
            }
        }
        out.sort_by(f64::total_cmp);
        out
    }
}

/// A polynomial of degree 8 in t, lowest coefficient first.
type Poly = [f64; 9];

/// An affine form in (1, cos φ, sin φ) as a quadratic in t = tan(ψ/2), ψ = φ − φc, times 1 + t².
fn quad(v: [f64; 3], (s, c): (f64, f64)) -> [f64; 3] {
    // cos φ = cos φc cos ψ − sin φc sin ψ, sin φ = sin φc cos ψ + cos φc sin ψ; then
    // cos ψ (1 + t²) = 1 − t², sin ψ (1 + t²) = 2t.
    let (k, cc, ss) = (v[0], v[1] * c + v[2] * s, -v[1] * s + v[2] * c);
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

/// The polynomial in t whose roots are the driver angles where `c1` and `c2` hold at once:
/// (cos θ, sin θ) by Cramer's rule, then cos² θ + sin² θ = 1.
fn meeting_poly(c1: &Condition, c2: &Condition, phi_c: f64) -> Poly {
    let sc = phi_c.sin_cos();
    let t = |c: &Condition| {
        (
            quad(c.k[1], sc),
            quad(c.k[2], sc),
            quad(c.k[0].map(|x| -x), sc),
        )
    };
    let (a1, b1, h1) = t(c1);
    let (a2, b2, h2) = t(c2);
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
    // Taylor shift to t0, then scale by the width: q(x) = p(t0 + w x), x in [0, 1].
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
    // Power to Bernstein basis: b_i = Σ_{j ≤ i} C(i, j) / C(N, j) q_j.
    const TO_BERNSTEIN: [[f64; 9]; 9] = to_bernstein();
    std::array::from_fn(|i| (0..=i).map(|j| TO_BERNSTEIN[i][j] * q[j]).sum())
}

/// C(i, j) / C(8, j), for the change to the Bernstein basis of degree 8.
const fn to_bernstein() -> [[f64; 9]; 9] {
    let mut b = [[0.0; 9]; 9];
    let mut n = 0;
    while n < 9 {
        b[n][0] = 1.0;
        let mut k = 1;
        while k <= n {
            b[n][k] = b[n - 1][k - 1] + if k < n { b[n - 1][k] } else { 0.0 };
            k += 1;
        }
        n += 1;
    }
    let mut r = [[0.0; 9]; 9];
    let mut i = 0;
    while i < 9 {
        let mut j = 0;
        while j <= i {
            r[i][j] = b[i][j] / b[8][j];
            j += 1;
        }
        i += 1;
    }
    r
}

fn value(p: &Poly, t: f64) -> f64 {
    p.iter().rev().fold(0.0, |acc, c| acc * t + c)
}

/// Sign changes along the Bernstein coefficients (those within rounding of zero skipped): at
/// least the number of roots in the interval, and of the same parity (Descartes' rule).
fn sign_changes(b: &Poly, scale: f64) -> usize {
    let eps = 1e-13 * scale;
    let mut last = 0.0;
    let mut changes = 0;
    for &x in b.iter().filter(|x| x.abs() > eps) {
        if last * x < 0.0 {
            changes += 1;
        }
        last = x;
    }
    changes
}

/// The isolated roots of `p` in [t0, t1]: subdivision until the Bernstein coefficients show no
/// root or exactly one (one sign change) in a piece, or it is narrower than `WIDTH`; then
/// bisection on the sign. A narrow piece with no sign change at its ends holds a double root, a
/// tangency, or nothing: its middle is reported for the caller to check.
fn roots(p: &Poly, scale: f64, t0: f64, t1: f64, out: &mut SmallVec<[f64; 4]>) {
    const WIDTH: f64 = 1e-13;
    let (va, vb) = (value(p, t0), value(p, t1));
    let changes = sign_changes(&bernstein(p, t0, t1), scale);
    let single = changes == 1 && va * vb <= 0.0;
    if changes == 0 && !(va == 0.0 || vb == 0.0) {
        return;
    }
    if !single && t1 - t0 > WIDTH {
        let m = 0.5 * (t0 + t1);
        roots(p, scale, t0, m, out);
        roots(p, scale, m, t1, out);
        return;
    }
    let (mut a, mut b) = (t0, t1);
    if va == 0.0 || vb == 0.0 || va.signum() != vb.signum() {
        let sa = va.signum();
        loop {
            let m = 0.5 * (a + b);
            if m <= a || m >= b {
                break;
            }
            if value(p, m).signum() == sa && sa != 0.0 {
                a = m;
            } else {
                b = m;
            }
        }
    }
    let t = 0.5 * (a + b);
    // Neighbouring pieces may both report a root on their shared end.
    if out.last().is_none_or(|&last| t - last > 2.0 * WIDTH) {
        out.push(t);
    }
}

/// Every driver angle in `(phi0, phi1]` (less than a half turn apart) where `c1` and `c2` hold
/// at once, in order, with the driven angle there (of the two θ where `c1` holds, the one where
/// `c2` holds best). Roots of a double meeting (two contacts that touch without crossing) may
/// be reported where the two only come within rounding of each other.
pub(crate) fn meetings(
    c1: &Condition,
    c2: &Condition,
    phi0: f64,
    phi1: f64,
    near: f64,
) -> SmallVec<[(f64, f64); 4]> {
    let phi_c = 0.5 * (phi0 + phi1);
    let p = meeting_poly(c1, c2, phi_c);
    let half = 0.5 * (phi1 - phi0);
    let t1 = (0.5 * half).tan();
    // The size of the polynomial's terms over the interval, against which a Bernstein
    // coefficient counts as zero: not its largest coefficient, whose power of t is tiny over a
    // short interval (two contacts meeting twice a few 1e-5 rad apart leave the polynomial a
    // dip of 1e-7 where its largest coefficient is 1e7, and a sign change read against that
    // was lost).
    let scale: f64 = p.iter().rev().fold(0.0, |acc, c| acc * t1.abs() + c.abs());
    let mut out = SmallVec::new();
    if scale == 0.0 {
        return out;
    }
    let mut ts = SmallVec::new();
    roots(&p, scale, -t1, t1, &mut ts);
    for t in ts {
        let phi = phi_c + 2.0 * t.atan();
        if phi <= phi0 || phi > phi1 {
            continue;
        }
        let best = c1
            .thetas(phi, near)
            .into_iter()
            .min_by(|&x, &y| c2.at(phi, x).abs().total_cmp(&c2.at(phi, y).abs()));
        if let Some(theta) = best {
            out.push((phi, theta));
        }
    }
    out
}

#[cfg(test)]
#[path = "../tests/unit/meet.rs"]
mod tests;
