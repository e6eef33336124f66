//! Proofs about a box of configurations: which tooth pairs cannot touch the driven gear while the
//! driver turns through a step, and, for those that can, whether their contact can only move the
//! driven gear forwards. The solver takes a step without searching it for roots when every pair
//! near the driven gear is proved harmless (`Certifier::proved` in `certified.rs`).
//!
//! # The contact functions
//!
//! Two straight-flanked teeth touch exactly when a vertex of one lies on a flank of the other.
//! Each such condition is the zero of a signed distance F(φ, θ), smooth in both angles:
//!
//! - **driver vertex P on a driven flank** (outward unit normal m, offset h, driven frame):
//!   `F = m(θ)·(R(φ)P − c2) − h` with `m(θ) = R(π − θ) m`. Then
//!   `F_θ = −(J m(θ))·(R(φ)P − c2)` and `F_φ = m(θ)·(J R(φ)P)`, J the quarter turn; so
//!   `|F_θ| ≤ |R(φ)P − c2|` (P's distance from the driven centre, a function of φ alone) and
//!   `|F_φ| ≤ |P|`; the second derivatives obey `|F_θθ| ≤ |R(φ)P − c2|` and
//!   `|F_θφ|, |F_φφ| ≤ |P|`.
//! - **driven vertex Q on a driver flank** (outward unit normal n, offset h, driver frame):
//!   `F = n(φ)·(c2 + R(π − θ)Q) − h` with `n(φ) = R(φ) n`. Then `F_φ = (J n(φ))·(c2 + R(π − θ)Q)`
//!   and `F_θ = −n(φ)·(J R(π − θ)Q)`; so `|F_φ| ≤ |c2 + R(π − θ)Q|` (Q's distance from the driver
//!   centre, a function of θ alone) and `|F_θ| ≤ |Q|`; `|F_φφ| ≤ |c2 + R(π − θ)Q|` and
//!   `|F_φθ|, |F_θθ| ≤ |Q|`.
//!
//! # The box and what is proved
//!
//! A box is `|φ − φc| ≤ dφ`, `|θ − θc| ≤ dθ`. Walking from the centre to any point first along
//! one angle, then along the other, with the first-derivative bounds above (taking, on the first
//! leg, the distance that depends only on the fixed angle, exactly at the centre):
//!
//! - type P: `|F − F_c| ≤ dθ·|R(φc)P − c2| + dφ·|P|`;
//! - type Q: `|F − F_c| ≤ dφ·|c2 + R(π − θc)Q| + dθ·|Q|`.
//!
//! So where `|F_c|` exceeds that bound the condition has **no root in the box**: the vertex is on
//! the same side of that flank's line throughout. A tooth pair none of whose conditions has a root
//! in the box never touches at any configuration in it: no end of its obstacle (which are roots,
//! `Mesh::obstacle`) lies in the box, so its obstacle never reaches the box's driven angles while
//! the driver turns through the box's driver angles. The same bounds on the second derivatives
//! give intervals for `F_φ` and `F_θ` over the whole box; where both keep one sign, every root
//! curve of that condition in the box is a smooth function θ(φ) (implicit functions) with slope
//! `−F_φ / F_θ` of that sign: the contact can only move the driven gear forwards (**rising**) or
//! only backwards (**falling**) there.
//!
//! Rounding: every bound is widened by [`ROUND`], far above the rounding of these few products
//! (millimetre-sized vectors, about 1e-14 mm).
//!
//! Curved flanks are not covered: a mesh with them is always bracketed.

use geometry::Vec2;

use crate::tooth::{ToothData, wrap_pi};

/// Absolute widening of every bound (mm of signed distance) against rounding, for meshes whose
/// centre distance is 1 to 1000 length units (every gearing's, in mm); see [`round_for`].
const ROUND: f64 = 1e-10;

/// The widening against rounding for a mesh at `centre_distance`: [`ROUND`] from 1 to 1000
/// length units, and in proportion to the size beyond (a pair file takes any unit), so that it
/// stays far above the rounding of the products (about 1e-16 of the size) without swamping
/// smaller gears' clearances: with a fixed 1e-10, gears of radius 1e-5 lost every certificate
/// and one driver pitch took seconds.
fn round_for(centre_distance: f64) -> f64 {
    ROUND * centre_distance.min(1.0).max(centre_distance / 1000.0)
}

/// One tooth as the certificate needs it, in its gear's frame about the rotation centre.
#[derive(Debug, Clone, Copy)]
pub(crate) struct CertTooth {
    /// (valley k−1, tip k, valley k).
    v: [Vec2; 3],
    /// Distances of the vertices from the rotation centre.
    rad: [f64; 3],
    /// Whether each vertex can ever touch the other gear.
    reaches: [bool; 3],
    /// Unit normals of the two flanks (valley k−1 → tip k, tip k → valley k).
    normal: [Vec2; 2],
    /// Offsets of the flank lines: `normal · x = offset` on the line.
    offset: [f64; 2],
    /// Where along its unit direction (its normal a quarter turn on) each flank starts, and
    /// their lengths: a point x is beside flank f when `0 ≤ dir[f]·x − start[f] ≤ len[f]`.
    start: [f64; 2],
    len: [f64; 2],
    /// Centre of a disc holding the tooth, and its radius.
    centre: Vec2,
    disc: f64,
    /// Farthest vertex from the rotation centre: no point of the tooth moves faster than this
    /// (per radian of its gear's turn).
    reach: f64,
}

impl CertTooth {
    pub(crate) fn new(t: &ToothData) -> Self {
        let v = t.v;
        let normal = [0, 1].map(|f| {
            let d = v[f + 1] - v[f];
            Vec2::new(d.y, -d.x) / d.norm()
        });
        let offset = [0, 1].map(|f| normal[f].dot(&v[f]));
        let len = [0, 1].map(|f| (v[f + 1] - v[f]).norm());
        let start = [0, 1].map(|f| quarter(normal[f]).dot(&v[f]));
        let centre = (v[0] + v[1] + v[2]) / 3.0;
        let disc = v.iter().map(|p| (p - centre).norm()).fold(0.0, f64::max);
        let rad = v.map(|p| p.norm());
        Self {
            v,
            rad,
            reaches: t.reaches,
            normal,
            offset,
            start,
            len,
            centre,
            disc,
            reach: rad.into_iter().fold(0.0, f64::max),
        }
    }
}

/// What a tooth pair can do within a box.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Verdict {
    /// The teeth touch nowhere in the box.
    Clear,
    /// Every contact in the box moves the driven angle forwards as the driver turns.
    Rising,
    /// Every contact in the box moves the driven angle backwards as the driver turns.
    Falling,
    /// Not proved either way.
    Unknown,
}

/// A box of configurations `|φ − φc| ≤ dφ`, `|θ − θc| ≤ dθ`, with the rotations at its centre.
pub(crate) struct ConfigBox {
    d_phi: f64,
    d_theta: f64,
    /// Whether the chord through the box falls (from its upper left corner to its lower right).
    falls: bool,
    /// (sin, cos) of φc: the driver's turn.
    driver_turn: (f64, f64),
    /// (sin, cos) of π − θc: the driven gear's turn.
    driven_turn: (f64, f64),
    c2: Vec2,
    /// The widening of every bound against rounding ([`round_for`] the centre distance).
    round: f64,
}

#[inline]
fn turn((s, c): (f64, f64), v: Vec2) -> Vec2 {
    Vec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// The quarter turn J.
#[inline]
fn quarter(v: Vec2) -> Vec2 {
    Vec2::new(-v.y, v.x)
}

/// How the sign of a quantity known to lie in `value ± err` is proved: +1, −1 or 0 (unknown).
#[inline]
fn sign(value: f64, err: f64) -> i8 {
    if value - err > 0.0 {
        1
    } else if value + err < 0.0 {
        -1
    } else {
        0
    }
}

impl ConfigBox {
    /// The box over driver angles `[phi0, phi1]` and driven angles `[theta0, theta1]`, for a
    /// driven gear whose centre is at `(centre_distance, 0)`.
    pub(crate) fn new(
        phi0: f64,
        phi1: f64,
        theta0: f64,
        theta1: f64,
        centre_distance: f64,
    ) -> Self {
        let phi_c = 0.5 * (phi0 + phi1);
        Self {
            // Half-widths, a hair wider than the rounding of the midpoints.
            d_phi: 0.5 * (phi1 - phi0) * (1.0 + 1e-12) + 1e-15 * phi_c.abs(),
            driver_turn: phi_c.sin_cos(),
            c2: Vec2::new(centre_distance, 0.0),
            round: round_for(centre_distance),
            // Set by `with_driven` below.
            d_theta: 0.0,
            falls: false,
            driven_turn: (0.0, 1.0),
        }
        .with_driven(theta0, theta1)
    }

    /// The box over the same driver angles and driven angles between `theta0` and `theta1`
    /// (the driver's turn at the centre is this box's, not computed again). The box's chord,
    /// which [`ConfigBox::clear_along`] follows, runs from `theta0` at its first driver angle to
    /// `theta1` at its last: it falls where `theta1` is the lower.
    pub(crate) fn with_driven(&self, theta0: f64, theta1: f64) -> Self {
        let theta_c = 0.5 * (theta0 + theta1);
        Self {
            d_theta: 0.5 * (theta1 - theta0).abs() * (1.0 + 1e-12) + 1e-15 * theta_c.abs(),
            falls: theta1 < theta0,
            driven_turn: (std::f64::consts::PI - theta_c).sin_cos(),
            ..*self
        }
    }

    /// Driver tooth `a` placed at the box's centre.
    pub(crate) fn place_driver<'t>(&self, a: &'t CertTooth) -> PlacedTooth<'t> {
        PlacedTooth {
            tooth: a,
            at: Placement {
                disc: self.driver_disc(a),
                turned: a.v.map(|v| turn(self.driver_turn, v)),
                normal: a.normal.map(|n| turn(self.driver_turn, n)),
            },
        }
    }

    /// Driven tooth `b` placed at the box's centre.
    pub(crate) fn place_driven<'t>(&self, b: &'t CertTooth) -> PlacedTooth<'t> {
        PlacedTooth {
            tooth: b,
            at: Placement {
                disc: self.driven_disc(b),
                turned: b.v.map(|v| turn(self.driven_turn, v)),
                normal: b.normal.map(|n| turn(self.driven_turn, n)),
            },
        }
    }

    /// A disc that holds driver tooth `a` throughout the box: centre and radius.
    pub(crate) fn driver_disc(&self, a: &CertTooth) -> (Vec2, f64) {
        (
            turn(self.driver_turn, a.centre),
            a.disc + self.d_phi * a.reach,
        )
    }

    /// A disc that holds driven tooth `b` throughout the box.
    pub(crate) fn driven_disc(&self, b: &CertTooth) -> (Vec2, f64) {
        (
            self.c2 + turn(self.driven_turn, b.centre),
            b.disc + self.d_theta * b.reach,
        )
    }

    /// Whether two discs from [`ConfigBox::driver_disc`] and [`ConfigBox::driven_disc`] are
    /// apart: then the teeth touch nowhere in the box, and [`ConfigBox::pair`] is `Clear`.
    #[inline]
    pub(crate) fn apart(&self, a: (Vec2, f64), b: (Vec2, f64)) -> bool {
        let far = a.1 + b.1 + self.round;
        (a.0 - b.0).norm_squared() > far * far
    }

    /// Every contact condition of driver tooth `a` and driven tooth `b` whose vertex may lie
    /// beside the flank somewhere in the box (the rest have no root in it), with its values and
    /// bounds at the box's centre.
    fn conditions(
        &self,
        a: &PlacedTooth<'_>,
        b: &PlacedTooth<'_>,
        mut visit: impl FnMut(Condition),
    ) {
        let (dp, dt) = (self.d_phi, self.d_theta);
        // Driver vertex P on a driven flank.
        for i in 0..3 {
            if !a.tooth.reaches[i] {
                continue;
            }
            // P in the world, and relative to the driven centre (its distance is what a driven
            // turn moves it by).
            let pw = a.at.turned[i];
            let x = pw - self.c2;
            let dist = x.norm();
            let rp = a.tooth.rad[i];
            // How far P can move from x, seen from the driven gear, within the box.
            let moved = dt * (dist + rp * dp) + dp * rp + self.round;
            for f in 0..2 {
                // Both points are relative to the driven centre.
                // The flank's direction: its normal a quarter turn on (`CertTooth::new`).
                let e = &quarter(b.at.normal[f]);
                let along = e.dot(&x) - b.tooth.start[f];
                if along < -moved || along > b.tooth.len[f] + moved {
                    continue;
                }
                let m = &b.at.normal[f];
                visit(Condition {
                    bit: 2 * i + f,
                    value: m.dot(&x) - b.tooth.offset[f],
                    rate_phi: rp,
                    rate_theta: dist,
                    f_phi: m.dot(&quarter(pw)),
                    f_theta: -quarter(*m).dot(&x),
                    e_phi: (dt + dp) * rp + self.round,
                    e_theta: dt * (dist + rp * dp) + dp * rp + self.round,
                    beside: Beside {
                        along,
                        len: b.tooth.len[f],
                        a_phi: e.dot(&quarter(pw)),
                        a_theta: -quarter(*e).dot(&x),
                    },
                });
            }
        }
        // Driven vertex Q on a driver flank.
        for i in 0..3 {
            if !b.tooth.reaches[i] {
                continue;
            }
            let q = b.at.turned[i];
            let qw = q + self.c2;
            let dist = qw.norm();
            let rq = b.tooth.rad[i];
            // How far Q can move from qw, seen from the driver, within the box.
            let moved = dp * (dist + rq * dt) + dt * rq + self.round;
            for f in 0..2 {
                let e = &quarter(a.at.normal[f]);
                let along = e.dot(&qw) - a.tooth.start[f];
                if along < -moved || along > a.tooth.len[f] + moved {
                    continue;
                }
                let n = &a.at.normal[f];
                visit(Condition {
                    bit: 6 + 2 * i + f,
                    value: n.dot(&qw) - a.tooth.offset[f],
                    rate_phi: dist,
                    rate_theta: rq,
                    f_phi: quarter(*n).dot(&qw),
                    f_theta: -n.dot(&quarter(q)),
                    e_phi: dp * (dist + rq * dt) + dt * rq + self.round,
                    e_theta: (dp + dt) * rq + self.round,
                    beside: Beside {
                        along,
                        len: a.tooth.len[f],
                        a_phi: quarter(*e).dot(&qw),
                        a_theta: -e.dot(&quarter(q)),
                    },
                });
            }
        }
    }

    /// The contact conditions of driver tooth `a` and driven tooth `b` that may hold somewhere
    /// in the box, one bit each as `ConditionSet` numbers them (bit `2i + f` for driver vertex i
    /// on driven flank f, `6 + 2i + f` for driven vertex i on driver flank f): the others hold
    /// nowhere in it, or only where their vertex lies beyond the flank.
    pub(crate) fn conditions_in_box(&self, a: &PlacedTooth<'_>, b: &PlacedTooth<'_>) -> u16 {
        if self.apart(a.at.disc, b.at.disc) {
            return 0;
        }
        let (dp, dt) = (self.d_phi, self.d_theta);
        let mut set = 0;
        self.conditions(a, b, |c| {
            if c.value.abs() <= dt * c.rate_theta + dp * c.rate_phi + self.round {
                set |= 1 << c.bit;
            }
        });
        set
    }

    /// What driver tooth `a` and driven tooth `b`, placed by [`ConfigBox::place_driver`] and
    /// [`ConfigBox::place_driven`], can do within the box; for `Rising` and `Falling`, also the
    /// range of the slopes dθ/dφ of their contact curves there.
    pub(crate) fn pair(&self, a: &PlacedTooth<'_>, b: &PlacedTooth<'_>) -> (Verdict, (f64, f64)) {
        if self.apart(a.at.disc, b.at.disc) {
            return (Verdict::Clear, (0.0, 0.0));
        }
        let (dp, dt) = (self.d_phi, self.d_theta);
        let mut touched = false;
        let (mut rising, mut falling) = (true, true);
        let mut slopes = (f64::INFINITY, f64::NEG_INFINITY);
        self.conditions(a, b, |c| {
            if c.value.abs() > dt * c.rate_theta + dp * c.rate_phi + self.round {
                return;
            }
            touched = true;
            let f_phi = sign(c.f_phi, c.e_phi);
            let f_theta = sign(c.f_theta, c.e_theta);
            // θ' = −F_φ / F_θ.
            let slope = -f_phi * f_theta;
            rising &= slope > 0;
            falling &= slope < 0;
            if slope != 0 {
                // Over the corners of F_φ's and F_θ's ranges, both of one sign.
                for p in [c.f_phi - c.e_phi, c.f_phi + c.e_phi] {
                    for t in [c.f_theta - c.e_theta, c.f_theta + c.e_theta] {
                        let s = -p / t;
                        slopes = (slopes.0.min(s), slopes.1.max(s));
                    }
                }
            }
        });
        let verdict = match (touched, rising, falling) {
            (false, _, _) => Verdict::Clear,
            (true, true, _) => Verdict::Rising,
            (true, _, true) => Verdict::Falling,
            _ => Verdict::Unknown,
        };
        (verdict, slopes)
    }

    /// Whether teeth `a` and `b` stay apart, by `margin` of driven angle at least, along every
    /// path θ(φ) through the box between the ends of its chord, from (φ0, θ0) to (φ1, θ1) (see
    /// [`ConfigBox::with_driven`]), whose slope stays within `slopes`: the driven gear pushed by
    /// curves with those slopes, or a driven angle that moves with a held gear's links.
    ///
    /// Such a path stays within `w = (s_max − s_min)·(φ1 − φ0)/4` of the chord θ_d(φ) through the
    /// corners, whose slope is s̄. Along the chord G(φ) = F(φ, θ_d(φ)) changes at
    /// `G' = F_φ + s̄·F_θ`, bounded over the box by its value at the centre and the second
    /// derivatives; off the chord F changes by at most `w·max|F_θ|`. So F has no zero on the
    /// paths where `|F_c| > dφ·(|F_φc + s̄F_θc| + e_φ + s̄e_θ) + w·(|F_θc| + e_θ)`: second order
    /// in the step where the box test is first order, because the teeth ahead move with the
    /// driven gear.
    ///
    /// A condition is a contact only where its vertex lies beside the flank (`0 ≤ A ≤ len`, A
    /// the vertex's coordinate along the flank). A has the form of F with the flank's direction
    /// for its normal, so the same bound holds for it: where `A_c` plus or minus that bound
    /// stays below 0 or above `len`, the vertex is never beside the flank on these paths, and
    /// the condition is no contact whatever F does. This matters in longer steps, where a
    /// vertex passes near the line of a flank of the tooth ahead but beyond its end.
    pub(crate) fn clear_along(
        &self,
        a: &PlacedTooth<'_>,
        b: &PlacedTooth<'_>,
        slopes: (f64, f64),
        margin: f64,
    ) -> bool {
        let dp = self.d_phi;
        let rise = if self.falls {
            -self.d_theta
        } else {
            self.d_theta
        };
        let chord = if dp > 0.0 { rise / dp } else { 0.0 };
        let width = (slopes.1 - slopes.0).max(0.0) * dp / 2.0 + self.d_theta * 1e-12;
        let mut clear = true;
        // How far a function of the configuration with these derivatives at the centre (and
        // the condition's bounds on how they change) can move from its centre value on the tube.
        let reach = |f_phi: f64, f_theta: f64, c: &Condition| {
            let along = (f_phi + chord * f_theta).abs() + c.e_phi + chord.abs() * c.e_theta;
            let across = f_theta.abs() + c.e_theta;
            dp * along + (width + margin) * across + self.round
        };
        self.conditions(a, b, |c| {
            // The vertex never beside the flank on the tube: this condition is no contact there.
            let s = &c.beside;
            let slide = reach(s.a_phi, s.a_theta, &c);
            if s.along + slide < 0.0 || s.along - slide > s.len {
                return;
            }
            clear &= c.value.abs() > reach(c.f_phi, c.f_theta, &c);
        });
        clear
    }
}

/// One contact condition (a vertex on a flank line) at a box's centre: its signed distance F,
/// the bounds on |F_φ| and |F_θ| used for the box test (each exact on the leg where the other
/// angle is held at the centre), and `F_φ`, `F_θ` there with how far they can change in the box.
struct Condition {
    /// Its bit in a `ConditionSet`.
    bit: usize,
    value: f64,
    rate_phi: f64,
    rate_theta: f64,
    f_phi: f64,
    f_theta: f64,
    e_phi: f64,
    e_theta: f64,
    beside: Beside,
}

/// Where a condition's vertex lies along its flank, at a box's centre: `A = e·x − start`, the
/// flank's unit direction e, beside the flank when `0 ≤ A ≤ len`. A is the signed distance F
/// with the flank's direction in place of its normal, so its derivatives `a_phi`, `a_theta`
/// take the same form and obey the same bounds on how they change in the box (`e_phi`,
/// `e_theta`: both use only that the vector turned with the flank is a unit vector).
struct Beside {
    along: f64,
    len: f64,
    a_phi: f64,
    a_theta: f64,
}

/// A tooth placed at a box's centre (world frame): what [`ConfigBox::pair`] reads, computed once
/// per tooth and box rather than once per pair.
#[derive(Clone, Copy)]
pub(crate) struct PlacedTooth<'t> {
    pub(crate) tooth: &'t CertTooth,
    pub(crate) at: Placement,
}

/// Where a tooth stands at a box's centre: kept apart from the tooth, so that a step can keep
/// the placements it made in a list of its own.
#[derive(Clone, Copy)]
pub(crate) struct Placement {
    /// A disc holding the tooth throughout the box: centre and radius.
    disc: (Vec2, f64),
    /// Vertices turned about their gear's centre: in the world for the driver, relative to its
    /// own centre for the driven gear (the other frame is one vector sum away, computed where it
    /// is used: a placement is copied about more often than it is read, and is smaller so).
    turned: [Vec2; 3],
    /// Flank normals, turned (a flank's direction is its normal a quarter turn on, and a turn
    /// commutes with the quarter turn).
    normal: [Vec2; 2],
}

/// Where a vertex of driver tooth `a` meets a vertex of driven tooth `b` (tip on tip, or a tip in
/// a valley's corner) while the driver turns from `phi0` to `phi1`: the earliest such meeting
/// (`last` false) or the latest (`last` true) as (φ, θ), θ reduced to (−π, π], or None. A pair of teeth that first touch at a point where
/// every contact curve rises are born at such a meeting, and die at one: elsewhere a first or last
/// touch is a tangency of one contact, where `F_θ = 0`, and the box verdict would not be `Rising`.
///
/// Driver vertex P meets driven vertex Q when P is as far from the driven centre as Q:
/// `|R(φ)P − c2| = |Q|`, i.e. `|P| cos(φ + arg P) = (|P|² + D² − |Q|²) / 2D`; then θ turns Q
/// onto P: `θ = π + arg Q − arg(R(φ)P − c2)`.
pub(crate) fn vertex_meeting(
    a: &CertTooth,
    b: &CertTooth,
    phi0: f64,
    phi1: f64,
    centre_distance: f64,
    last: bool,
) -> Option<(f64, f64)> {
    let d = centre_distance;
    let mut best: Option<(f64, f64)> = None;
    for i in 0..3 {
        if !a.reaches[i] {
            continue;
        }
        let p = a.v[i];
        let rp = a.rad[i];
        let base = p.y.atan2(p.x);
        for l in 0..3 {
            if !b.reaches[l] {
                continue;
            }
            let q = b.v[l];
            let c = (rp * rp + d * d - b.rad[l] * b.rad[l]) / (2.0 * d * rp);
            if !(-1.0..=1.0).contains(&c) {
                continue;
            }
            let spread = c.acos();
            for root in [spread - base, -spread - base] {
                let tau = std::f64::consts::TAU;
                // The first angle ≥ phi0 with this cosine, or the last ≤ phi1.
                let phi = if last {
                    phi1 - (phi1 - root).rem_euclid(tau)
                } else {
                    phi0 + (root - phi0).rem_euclid(tau)
                };
                let better = |b: f64| if last { phi > b } else { phi < b };
                if phi > phi1 || phi < phi0 || best.is_some_and(|(b, _)| !better(b)) {
                    continue;
                }
                let (s, c) = phi.sin_cos();
                let x = Vec2::new(c * p.x - s * p.y - d, s * p.x + c * p.y);
                let theta = wrap_pi(std::f64::consts::PI + q.y.atan2(q.x) - x.y.atan2(x.x));
                best = Some((phi, theta));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    //! The certificates against the exact obstacles: on random meshes and random boxes near the
    //! running driven gear, what a verdict claims must hold at every sampled driver angle.
    #![allow(clippy::unwrap_used, reason = "tests")]

    use std::f64::consts::TAU;

    use geometry::Gear;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    use super::*;
    use crate::speed::Certifier;
    use crate::{Mesh, Obstacle, Solve, Start};

    fn gear(n: usize, r_tip: f64, sigma: f64, ecc: f64, rng: &mut ChaCha8Rng) -> Gear {
        let pitch = TAU / n as f64;
        let tips = (0..n)
            .map(|k| pitch * k as f64 + sigma * pitch * (rng.random::<f64>() - 0.5))
            .collect();
        let a = rng.random::<f64>() * TAU;
        Gear::new(
            r_tip,
            r_tip - 1.1,
            tips,
            Vec2::new(ecc * a.cos(), ecc * a.sin()),
        )
        .unwrap()
    }

    fn mesh(rng: &mut ChaCha8Rng) -> Option<Mesh> {
        let n1 = rng.random_range(12..40);
        let n2 = rng.random_range(n1..120);
        let module = 0.5 + rng.random::<f64>();
        let (r1, r2) = (n1 as f64 * module / 2.0, n2 as f64 * module / 2.0);
        let sigma = [0.0, 0.1, 0.3][rng.random_range(0..3)];
        let ecc = [0.0, 0.1, 0.3][rng.random_range(0..3)];
        let g = 5.0 + 90.0 * rng.random::<f64>();
        let d = geometry::centre_distance(r1, r2, 1.1, g);
        Mesh::new(
            gear(n1, r1, sigma, ecc, rng),
            gear(n2, r2, sigma, ecc, rng),
            d,
        )
        .ok()
    }

    /// `x` moved by whole turns to lie within half a turn of `near`.
    fn near(x: f64, near: f64) -> f64 {
        x + TAU * ((near - x) / TAU).round()
    }

    #[test]
    fn verdicts_hold_at_every_sampled_driver_angle() {
        let mut rng = ChaCha8Rng::seed_from_u64(15);
        let mut seen = [0usize; 4];
        for _ in 0..150 {
            let Some(m) = mesh(&mut rng) else { continue };
            let c = Certifier::new(&m).unwrap();
            let pitch = TAU / m.driver.tips.len() as f64;
            let phi0 = rng.random::<f64>() * TAU;
            let run = m.solve(
                phi0..=phi0 + 2.0 * pitch,
                Start::Touching(0.0),
                Solve::path(),
            );
            let phi0 = phi0 + rng.random::<f64>() * pitch;
            let phi1 = phi0 + pitch * 10f64.powf(-3.0 * rng.random::<f64>()) * 0.5;
            let theta = run.theta_at(phi0);
            let lo = theta - 0.02 * pitch * rng.random::<f64>();
            let hi = theta + pitch * rng.random::<f64>();
            let cell = ConfigBox::new(phi0, phi1, lo, hi, m.centre_distance);
            let drivers = m
                .driver
                .teeth_between(-phi1 - m.driver.window, -phi0 + m.driver.window);
            let drivens = m
                .driven
                .teeth_between(lo - m.driven.window, hi + m.driven.window);
            for j in drivers {
                for k in drivens.clone() {
                    let (verdict, _) = cell.pair(
                        &cell.place_driver(c.driver_tooth(j)),
                        &cell.place_driven(c.driven_tooth(k)),
                    );
                    seen[verdict as usize] += 1;
                    let mut last: Option<Obstacle> = None;
                    for i in 0..=200 {
                        let phi = phi0 + (phi1 - phi0) * i as f64 / 200.0;
                        let o = m.obstacle(phi, j, k);
                        let in_band = |x: f64| (lo..=hi).contains(&near(x, 0.5 * (lo + hi)));
                        if let Some(o) = o {
                            let what = format!(
                                "{verdict:?} pair ({j}, {k}) at φ {phi}: {o:?}, band [{lo}, {hi}]"
                            );
                            match verdict {
                                Verdict::Clear => {
                                    assert!(!in_band(o.lo) && !in_band(o.hi), "{what}");
                                }
                                Verdict::Rising | Verdict::Falling => {
                                    if let Some(p) = last {
                                        for (a, b) in [(p.lo, o.lo), (p.hi, o.hi)] {
                                            if in_band(a) && in_band(b) {
                                                let rise = near(b, a) - a;
                                                if verdict == Verdict::Rising {
                                                    assert!(
                                                        rise >= -1e-12,
                                                        "{what}: fell by {rise}"
                                                    );
                                                } else {
                                                    assert!(
                                                        rise <= 1e-12,
                                                        "{what}: rose by {rise}"
                                                    );
                                                }
                                            }
                                        }
                                    }
                                }
                                Verdict::Unknown => {}
                            }
                        }
                        last = o;
                    }
                }
            }
        }
        // Every verdict was put to the test.
        assert!(seen.iter().all(|&n| n > 20), "verdicts seen: {seen:?}");
    }

    #[test]
    fn pairs_clear_along_the_tube_miss_every_path_in_it() {
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let (mut clear, mut paths) = (0, 0);
        for _ in 0..200 {
            let Some(m) = mesh(&mut rng) else { continue };
            let c = Certifier::new(&m).unwrap();
            let pitch = TAU / m.driver.tips.len() as f64;
            let ratio = m.driver.tips.len() as f64 / m.driven.tips.len() as f64;
            let phi0 = rng.random::<f64>() * TAU;
            let run = m.solve(phi0..=phi0 + pitch, Start::Touching(0.0), Solve::path());
            let theta0 = run.theta_at(phi0);
            let span = pitch * (0.05 + 0.5 * rng.random::<f64>());
            let phi1 = phi0 + span;
            // Slopes about the ratio, the chord's among them; a third of them falling (a held
            // gear's links moving back).
            let slopes = (
                ratio * (0.5 + 0.5 * rng.random::<f64>()),
                ratio * (1.0 + rng.random::<f64>()),
            );
            let slopes = if rng.random_bool(1.0 / 3.0) {
                (-slopes.1, -slopes.0)
            } else {
                slopes
            };
            let chord = slopes.0 + (slopes.1 - slopes.0) * rng.random::<f64>();
            let theta1 = theta0 + chord * span;
            let margin = 1e-10;
            let path = ConfigBox::new(phi0, phi1, theta0, theta1, m.centre_distance);
            let drivers = m
                .driver
                .teeth_between(-phi1 - m.driver.window, -phi0 + m.driver.window);
            let (low, high) = (theta0.min(theta1), theta0.max(theta1));
            let drivens = m
                .driven
                .teeth_between(low - m.driven.window, high + m.driven.window);
            for j in drivers {
                for k in drivens.clone() {
                    let (a, b) = (
                        path.place_driver(c.driver_tooth(j)),
                        path.place_driven(c.driven_tooth(k)),
                    );
                    if !path.clear_along(&a, &b, slopes, margin) {
                        continue;
                    }
                    clear += 1;
                    // Paths of two straight pieces, slopes within range, through both corners.
                    for _ in 0..20 {
                        let t = span * rng.random::<f64>();
                        let s1 = slopes.0 + (slopes.1 - slopes.0) * rng.random::<f64>();
                        let s2 = (theta1 - theta0 - s1 * t) / (span - t);
                        if !(slopes.0..=slopes.1).contains(&s2) {
                            continue;
                        }
                        paths += 1;
                        for i in 0..=100 {
                            let phi = phi0 + span * f64::from(i) / 100.0;
                            let theta = if phi - phi0 <= t {
                                theta0 + s1 * (phi - phi0)
                            } else {
                                theta0 + s1 * t + s2 * (phi - phi0 - t)
                            };
                            if let Some(o) = m.obstacle(phi, j, k) {
                                let (lo, hi) = (near(o.lo, theta), near(o.hi, theta));
                                assert!(
                                    theta < lo - margin || theta > hi + margin,
                                    "pair ({j}, {k}) meets the path at ({phi}, {theta}): {o:?}"
                                );
                            }
                        }
                    }
                }
            }
        }
        assert!(
            clear > 200 && paths > 1000,
            "{clear} pairs clear, {paths} paths"
        );
    }

    #[test]
    fn vertex_meetings_are_vertices_meeting() {
        let mut rng = ChaCha8Rng::seed_from_u64(16);
        let mut met = 0;
        for _ in 0..100 {
            let Some(m) = mesh(&mut rng) else { continue };
            let c = Certifier::new(&m).unwrap();
            let phi0 = rng.random::<f64>() * TAU;
            let phi1 = phi0 + 0.3;
            for j in m
                .driver
                .teeth_between(-phi1 - m.driver.window, -phi0 + m.driver.window)
            {
                let k = rng.random_range(0..m.driven.tips.len() as i64);
                for last in [false, true] {
                    let Some((phi, theta)) = c.vertex_meeting(&m, (j, k), (phi0, phi1), last)
                    else {
                        continue;
                    };
                    assert!((phi0..=phi1).contains(&phi));
                    let a = m.driver.tooth(j).map(|v| m.driver_world(v, phi));
                    let b = m.driven.tooth(k).map(|v| m.driven_world(v, theta));
                    let gap = a
                        .iter()
                        .flat_map(|p| b.iter().map(move |q| (p - q).norm()))
                        .fold(f64::INFINITY, f64::min);
                    assert!(
                        gap < 1e-9,
                        "pair ({j}, {k}) at ({phi}, {theta}): {gap} mm apart"
                    );
                    met += 1;
                }
            }
        }
        assert!(met > 50, "{met} meetings");
    }
}
