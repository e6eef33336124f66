//! A held gear's joints proved to hold over stretches of driver angle, kept from step to step.
//!
//! The core searches each joint of a held gear's chain - links c_i and c_{i+1} - for the first
//! root where it may fail (`held.rs`). Here a joint is proved to hold from φa to φb by a driven
//! angle that moves with the links' overlap: a chord u(φ) above θ, from a driven angle inside
//! both links at φa (at first the middle of their overlap) on along the last chord's slope, or
//! aimed at the middle of their overlap at φb. Where both links' teeth are proved apart from
//! every contact along the chord by a margin m ([`ConfigBox::clear_along`]), and u lies inside
//! both links by m at φa, it lies inside both by m throughout: both links' teeth keep touching,
//! the upper end of c_i stays above θ and the lower end of c_{i+1} below it, each by m, so no
//! root of the core's search of that joint could be a change (each would have an end within
//! `held::AT_ROOT` of it), and the chord's far end is where the next one starts.
//!
//! A joint's proof runs on as far as it holds, a chord at a time, each chord twice as long as
//! the last that held (half as long after one that did not), and the joints of the chain are kept
//! in a queue ordered by the driver angle at which each one's proof ends: a step looks only at
//! the joints whose proof ends inside it. A proof is a joint's own (its two links' teeth and θ),
//! so it outlives the chain it was made for: after a chain breaks, the new chain's joints that
//! the old one had are proved already. The joints no chord proves are left to the core's search;
//! where it finds no change, the joint holds to the step's end.

use std::cmp::Reverse;
use std::collections::{BinaryHeap, HashMap, HashSet};

use super::Certifier;
use super::certify::ConfigBox;
use super::stats::count;
use crate::held::{AT_ROOT, Chain, joint_key};
use crate::mesh::{Mesh, Obstacle};

/// A joint's teeth (`held::joint_key`).
type Key = (i64, i64, i64, i64);

/// How many steps a chord may span at most, and how small a share of a step at least: a long
/// chord leaves its links' curving ends, a short one costs evaluations without getting far.
const LONGEST: f64 = 2.0;
const SHORTEST: f64 = 1.0 / 8.0;

/// A driver angle, ordered (for the queue).
#[derive(Debug, Clone, Copy, PartialEq)]
struct Angle(f64);

impl Eq for Angle {}

impl PartialOrd for Angle {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Angle {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}

/// What is proved of one joint: that it holds up to `until`.
#[derive(Debug, Clone, Copy)]
struct Proof {
    until: f64,
    /// Where the last chord ended: a driven angle inside both links by the margin at `until`,
    /// and the chord's slope.
    point: Option<(f64, f64)>,
    /// How far the next chord reaches (driver angle).
    span: f64,
    /// Where the core's search of the joint, asked for in the last step, would have it hold
    /// to, once the next step starts there (no change found: the chain went on unbroken).
    searched: Option<f64>,
}

/// The proofs about one held gear (at `theta`), and the queue of the current chain's joints.
#[derive(Debug, Default)]
pub(super) struct HeldJoints {
    theta: f64,
    proofs: HashMap<Key, Proof>,
    /// The chain the queue is of, and its joints (by the index of the lower link, the first of
    /// those a turn apart) ordered by where their proofs end.
    chain: Vec<(i64, i64)>,
    queue: BinaryHeap<Reverse<(Angle, usize)>>,
    /// The end of the last step asked about, and the joints left to the core there.
    last: (f64, Vec<Key>),
}

impl Certifier {
    /// See `Shortcut::held_joints`: the joints of `chain` whose proofs end before `phi1` and
    /// that no chord proves past it.
    pub(super) fn proved_held_joints(
        &mut self,
        chain: &mut Chain<'_>,
        theta: f64,
        phi1: f64,
    ) -> Vec<usize> {
        let phi0 = chain.phi();
        let mut state = std::mem::take(&mut self.held);
        state.start(chain, theta, phi0);
        let step = phi1 - phi0;
        let mut due = Vec::new();
        while let Some(&Reverse((Angle(until), i))) = state.queue.peek() {
            if until >= phi1 {
                break;
            }
            state.queue.pop();
            let key = state.key(chain, i);
            let mut proof = state.proofs.get(&key).copied();
            // The queue may hold an old entry of a joint proved further since.
            if let Some(p) = proof.filter(|p| p.until > until) {
                state.queue.push(Reverse((Angle(p.until), i)));
                continue;
            }
            let proved = self.prove_on(chain, i, theta, (phi0, phi1), step, &mut proof);
            let mut proof = proof.unwrap_or(Proof {
                until: phi0,
                point: None,
                span: step,
                searched: None,
            });
            if proved {
                count(|st| st.joints_proved += 1);
            } else {
                proof.searched = Some(phi1);
                due.push(i);
            }
            state.proofs.insert(key, proof);
            state.queue.push(Reverse((Angle(proof.until.max(phi1)), i)));
        }
        due.sort_unstable();
        state.last = (phi1, due.iter().map(|&i| state.key(chain, i)).collect());
        self.held = state;
        due
    }

    /// Runs joint `i`'s proof (`proof`, if any) on, chord after chord, past `phi1`, and
    /// returns whether it got there. A proof that ends before the range starts (`phi0`) starts
    /// again there, in the middle of the links' overlap. Each chord goes on along the last one's
    /// slope; where that fails, it is made half as long, and the shortest is aimed at the middle
    /// of the links' overlap at its far end instead (as is the first).
    fn prove_on(
        &self,
        chain: &mut Chain<'_>,
        i: usize,
        theta: f64,
        (phi0, phi1): (f64, f64),
        step: f64,
        proof: &mut Option<Proof>,
    ) -> bool {
        let (mut at, mut point, mut span) = match *proof {
            Some(p) if p.until >= phi0 && p.point.is_some() => (p.until, p.point, p.span),
            Some(p) => (phi0, None, p.span),
            None => (phi0, None, step),
        };
        let (link, next) = (chain.pairs()[i], chain.pairs()[i + 1]);
        let mesh = chain.mesh();
        let mut from = match point {
            Some((u, _)) => u,
            None => {
                let (Some(a), Some(b)) = (chain.link(i), chain.link(i + 1)) else {
                    return false;
                };
                let u = middle(a, b, theta);
                if !inside(a, b, u, theta) {
                    return false;
                }
                u
            }
        };
        let mut aimed = point.is_none();
        while at < phi1 {
            let to = at + span;
            let end = match point {
                Some((_, slope)) if !aimed => Some(from + slope * span),
                _ => {
                    aimed = true;
                    let at_to = |(j, k): (i64, i64)| mesh.obstacle(to, j, k);
                    at_to(link)
                        .zip(at_to(next))
                        .map(|(a, b)| middle(a, b, theta))
                }
            };
            match end.filter(|&u| self.chord_holds(mesh, (link, next), theta, (at, from), (to, u)))
            {
                Some(u) => {
                    point = Some((u, (u - from) / span));
                    (at, from, aimed) = (to, u, false);
                    span = (2.0 * span).min(LONGEST * step);
                    *proof = Some(Proof {
                        until: at,
                        point,
                        span,
                        searched: None,
                    });
                }
                // A chord too long for the links' curving ends: half as long, the same way.
                None if span > SHORTEST * step => span *= 0.5,
                // The shortest chord along the slope: aimed at the overlap's middle instead.
                None if !aimed => aimed = true,
                None => break,
            }
        }
        if let Some(p) = proof {
            p.span = span;
        }
        at >= phi1
    }

    /// Whether the joint of the tooth pairs `link` and `next` holds along the chord from
    /// (`phi_a`, `u_a`), a driven angle inside both links by the margin, to (`phi_b`, `u_b`):
    /// the chord stays above θ by the margin, and both links' teeth stay apart from any contact
    /// along it by the margin (see the module's docs).
    fn chord_holds(
        &self,
        mesh: &Mesh,
        (link, next): ((i64, i64), (i64, i64)),
        theta: f64,
        (phi_a, u_a): (f64, f64),
        (phi_b, u_b): (f64, f64),
    ) -> bool {
        let margin = margin(u_a.max(u_b));
        if u_b <= theta + margin {
            return false;
        }
        let chord = ConfigBox::new(phi_a, phi_b, u_a, u_b, mesh.centre_distance);
        let slope = (u_b - u_a) / (phi_b - phi_a);
        let apart = |(j, k): (i64, i64)| {
            chord.clear_along(
                &chord.place_driver(self.driver_tooth(j)),
                &chord.place_driven(self.driven_tooth(k)),
                (slope, slope),
                margin,
            )
        };
        apart(link) && apart(next)
    }
}

/// The margin a chord keeps near the driven angle `u`: far more than a root's distance from an
/// end that the core's search checks (`held::AT_ROOT`).
fn margin(u: f64) -> f64 {
    10.0 * AT_ROOT * (1.0 + u.abs())
}

/// The middle of the overlap above θ of a joint's links `link` and `next`.
fn middle(link: Obstacle, next: Obstacle, theta: f64) -> f64 {
    0.5 * (next.lo.max(theta) + link.hi)
}

/// Whether the driven angle `u` lies inside both of a joint's links by the margin, and above θ.
fn inside(link: Obstacle, next: Obstacle, u: f64, theta: f64) -> bool {
    let m = margin(u);
    let within = |o: Obstacle| o.lo + m < u && u < o.hi - m;
    within(link) && within(next) && u > theta + m
}

impl HeldJoints {
    /// Takes up `chain` at `phi0`, the gear held at `theta`: the proofs of another held angle are
    /// dropped; the joints left to the core last step held to its end if this step starts there
    /// on the same chain; and the queue is made again for a new chain.
    fn start(&mut self, chain: &Chain<'_>, theta: f64, phi0: f64) {
        if theta != self.theta {
            *self = Self {
                theta,
                ..Self::default()
            };
        }
        let same = self.chain == chain.pairs();
        let (last_end, searched) = std::mem::take(&mut self.last);
        for key in searched {
            if let Some(p) = self.proofs.get_mut(&key) {
                if same && phi0 == last_end && p.searched == Some(last_end) && p.until < last_end {
                    (p.until, p.point) = (last_end, None);
                }
                p.searched = None;
            }
        }
        if same {
            return;
        }
        self.chain = chain.pairs().to_vec();
        let mut seen = HashSet::new();
        let mut queue = Vec::with_capacity(self.chain.len());
        for i in 0..self.chain.len().saturating_sub(1) {
            let key = self.key(chain, i);
            if seen.insert(key) {
                let until = self.proofs.get(&key).map_or(f64::NEG_INFINITY, |p| p.until);
                queue.push(Reverse((Angle(until), i)));
            }
        }
        self.queue = BinaryHeap::from(queue);
    }

    /// The teeth of joint `i` of `chain`.
    fn key(&self, chain: &Chain<'_>, i: usize) -> Key {
        let pairs = chain.pairs();
        let n2 = chain.mesh().driven.tips.len() as i64;
        joint_key(n2, pairs[i], pairs[i + 1])
    }
}
