//! Proofs that a held driven gear stays held while the driver turns through a range of angles,
//! so that the bisection locating its release need not re-check the whole cover at every probe.
//!
//! # What is proved
//!
//! A held gear at θ is one with no free position ahead: the obstacles at φ, swept in order of
//! their lower ends (`cover_from` in `solver.rs`: one joins the cover when its lower end is within
//! the side tolerance `tol` of the top so far, or, while the top is still θ, below θ − tol), close
//! up from θ past a threshold more than a turn on. Take the **chain** c_1 … c_m of obstacles that
//! lifted the top, and these **joints**:
//!
//! - joint 0: lo_1 < θ − tol;
//! - joint i (0 < i < m): lo_{i+1} ≤ hi_i + tol and hi_i > θ;
//! - joint m: hi_m ≥ the threshold.
//!
//! Wherever every joint holds, the sweep closes up past the threshold. By induction over the
//! links in order of their lower ends: a link below θ − tol joins whatever the top is. Any other
//! c_i has an earlier link c_k with lo_k < lo_i (c_1 is one); take the last. It was swept before
//! c_i, so the top is at least hi_k > θ, and the links between have lower ends at or above lo_i,
//! so lo_i ≤ lo_{k+1} ≤ hi_k + tol: c_i joins, and the top reaches hi_i. Hence the top reaches
//! hi_m, past the threshold; more obstacles only cover more.
//!
//! A joint is **fixed** over a range of driver angles by points its links hold there: joint 0 by
//! t_0 < θ − tol inside c_1; joint i by u > θ inside c_i and u + tol inside c_{i+1}; joint m by a
//! point past the threshold inside c_m. A link holds a point over the range when its tooth pair has
//! **no contact root** on the segment {φ ∈ range, θ = the point} (`ConfigBox::pair` over a box of
//! zero height is `Clear`): an obstacle's ends are contact roots, so neither crosses the point,
//! and the point, inside the obstacle where the proof was made, stays inside (the argument of
//! `certify.rs`). The other joints are **open**: at each probe their links are evaluated and the
//! joint checked as stated; after a probe that holds, each open joint is tried again with points
//! in its links' overlap there, over what is left of the range (a shorter segment, nearer the
//! release, is proved clear more often).
//!
//! So the proof only ever answers "held", and only where the scan would: the bisection's answer
//! is the same, bit for bit.

use smallvec::SmallVec;

use crate::certify::{ConfigBox, Verdict};
use crate::mesh::{Mesh, Obstacle};

/// A proof that the driven gear at `theta` is held at every driver angle of `range` where its
/// open joints hold (see the module's docs).
#[derive(Debug, Clone)]
pub(crate) struct HeldProof {
    theta: f64,
    threshold: f64,
    tol: f64,
    range: (f64, f64),
    /// The chain's tooth pairs, in the order the sweep took them.
    links: Vec<(i64, i64)>,
    /// The joints (0 to the number of links) not fixed over the range: the likeliest to fail
    /// first.
    open: Vec<usize>,
    /// The links evaluated at the last probe that held: (index, obstacle).
    seen: Vec<(usize, Obstacle)>,
}

impl HeldProof {
    /// The proof from `chain`, the obstacles at `phi_lo` that closed up from θ past `threshold`
    /// (in the order the sweep took them, each lifting the top), over driver angles
    /// `[phi_lo, phi_hi]`; None where the chain does not close up as the joints ask, or the mesh
    /// has curved flanks (no certificates).
    pub(crate) fn build(
        mesh: &Mesh,
        (phi_lo, phi_hi): (f64, f64),
        theta: f64,
        threshold: f64,
        tol: f64,
        chain: &[Obstacle],
    ) -> Option<Self> {
        if mesh.curved || phi_hi <= phi_lo {
            return None;
        }
        let m = chain.iter().position(|c| c.hi >= threshold)? + 1;
        let chain = &chain[..m];
        let mut proof = Self {
            theta,
            threshold,
            tol,
            range: (phi_lo, phi_hi),
            links: chain
                .iter()
                .map(|c| (c.driver_tooth, c.driven_tooth))
                .collect(),
            open: Vec::with_capacity(m + 1),
            seen: Vec::new(),
        };
        let base = proof.segments(mesh);
        for joint in 0..=m {
            if !proof.joint_holds(joint, |i| Some(chain[i])) {
                return None;
            }
            if !proof.fix(mesh, &base, joint, |i| Some(chain[i])) {
                proof.open.push(joint);
            }
        }
        Some(proof)
    }

    /// Whether any joint is fixed over the range (for the tests: a proof that fixes none
    /// evaluates every link at each probe).
    #[cfg(test)]
    pub(crate) fn has_fixed_joints(&self) -> bool {
        self.open.len() <= self.links.len()
    }

    /// Whether the proof answers "held" at driver angle `phi` for the gear at `theta`: φ in its
    /// range, and every open joint holding there (its links evaluated; the first that fails is
    /// tried first next time, as it is the likeliest to fail again).
    pub(crate) fn holds_at(&mut self, mesh: &Mesh, phi: f64, theta: f64) -> bool {
        if theta != self.theta || phi < self.range.0 || phi > self.range.1 {
            return false;
        }
        let mut seen: SmallVec<[(usize, Option<Obstacle>); 8]> = SmallVec::new();
        let mut at = |i: usize| {
            if let Some(&(_, o)) = seen.iter().find(|s| s.0 == i) {
                return o;
            }
            let (j, k) = self.links[i];
            let o = mesh.obstacle(phi, j, k);
            seen.push((i, o));
            o
        };
        let failed = self
            .open
            .iter()
            .position(|&joint| !self.joint_holds(joint, &mut at));
        if let Some(f) = failed {
            self.open.swap(0, f);
            return false;
        }
        self.seen.clear();
        self.seen
            .extend(seen.iter().filter_map(|&(i, o)| o.map(|o| (i, o))));
        true
    }

    /// After [`HeldProof::holds_at`] answered "held" at `phi`: the proof over `[phi, phi_hi]`
    /// (within its range), each open joint tried again with points in its links' overlap at `phi`.
    pub(crate) fn narrow(&mut self, mesh: &Mesh, phi: f64, phi_hi: f64) {
        let range = (phi.max(self.range.0), phi_hi.min(self.range.1));
        if range.1 <= range.0 {
            return;
        }
        self.range = range;
        let base = self.segments(mesh);
        let seen = std::mem::take(&mut self.seen);
        let open = std::mem::take(&mut self.open);
        let at = |i: usize| seen.iter().find(|s| s.0 == i).map(|s| s.1);
        for joint in open {
            if !self.fix(mesh, &base, joint, at) {
                self.open.push(joint);
            }
        }
        self.seen = seen;
    }

    /// The box of zero height over the proof's range of driver angles, at θ (segments at other
    /// driven angles are taken from it).
    fn segments(&self, mesh: &Mesh) -> ConfigBox {
        ConfigBox::new(
            self.range.0,
            self.range.1,
            self.theta,
            self.theta,
            mesh.centre_distance,
        )
    }

    /// Whether `joint` holds for the links' obstacles given by `at` (None: the pair does not
    /// touch, and the joint does not hold).
    fn joint_holds(&self, joint: usize, mut at: impl FnMut(usize) -> Option<Obstacle>) -> bool {
        let m = self.links.len();
        if joint == 0 {
            return at(0).is_some_and(|c| c.lo < self.theta - self.tol);
        }
        if joint == m {
            return at(m - 1).is_some_and(|c| c.hi >= self.threshold);
        }
        let (Some(c), Some(next)) = (at(joint - 1), at(joint)) else {
            return false;
        };
        c.hi > self.theta && next.lo <= c.hi + self.tol
    }

    /// Whether `joint` is fixed over the proof's range by points inside its links' obstacles
    /// `at` the range's start (see the module's docs); not where a link's obstacle is not given.
    fn fix(
        &self,
        mesh: &Mesh,
        base: &ConfigBox,
        joint: usize,
        at: impl Fn(usize) -> Option<Obstacle>,
    ) -> bool {
        let m = self.links.len();
        let holds = |c: Obstacle, i: usize, t: f64| {
            c.lo < t && t < c.hi && segment_clear(mesh, base, self.links[i], t)
        };
        if joint == 0 {
            let Some(c) = at(0) else { return false };
            let t = 0.5 * (c.lo + self.theta - self.tol);
            return t < self.theta - self.tol && holds(c, 0, t);
        }
        if joint == m {
            let Some(c) = at(m - 1) else { return false };
            let t = 0.5 * (c.lo.max(self.threshold) + c.hi);
            return t >= self.threshold && holds(c, m - 1, t);
        }
        // u inside c_i, above θ, and u + tol inside c_{i+1}.
        let (Some(c), Some(next)) = (at(joint - 1), at(joint)) else {
            return false;
        };
        let low = c.lo.max(self.theta).max(next.lo - self.tol);
        let high = c.hi.min(next.hi - self.tol);
        let u = 0.5 * (low + high);
        low < u && u < high && holds(c, joint - 1, u) && holds(next, joint, u + self.tol)
    }
}

/// Whether tooth pair `pair` has no contact root at driven angle `t` while the driver turns
/// through the driver angles of `base` (a box of zero height there).
fn segment_clear(mesh: &Mesh, base: &ConfigBox, (j, k): (i64, i64), t: f64) -> bool {
    let cell = base.with_driven(t, t);
    let a = cell.place_driver(mesh.driver.cert(j));
    let b = cell.place_driven(mesh.driven.cert(k));
    cell.pair(&a, &b).0 == Verdict::Clear
}
