//! A pushed gear's step taken on a certificate, where bounds on the contact conditions over the
//! step prove that no event lies in it, so that the step ends where the pushing curves end
//! without any search (`certify.rs` has the bounds). Its one entry is
//! [`Certifier::try_certified`] (the whole step, or else its two halves); it reads where the run
//! stands (`Stand`) and, when it succeeds, moves it on as the exact step would
//! (`Run::take_proved_step`).

use smallvec::SmallVec;

use super::Certifier;
use super::certify::{ConfigBox, PlacedTooth, Placement, Verdict};
use super::stats::count;
use crate::mesh::End;
use crate::solver::shortcut::PairAtEnd;
use crate::solver::{Pairs, Run, SIDE_TOL, Side, Stand};

/// How far a certified step's first box reaches above the pushers' end, as a share of their rise
/// over the step (a performance choice only: any box holding the path is sound; 0.1 judged the
/// fewest boxes again on `examples/turns`, 0.25 and 0.5 more pairs in taller boxes).
const BOX_HEADROOM: f64 = 0.1;

/// A pair behind the driven gear that does not carry it at a certified step's end.
fn not_carrying(pair: (i64, i64)) -> PairAtEnd {
    PairAtEnd {
        pair,
        hi: f64::NEG_INFINITY,
        rising: false,
    }
}

/// A tooth pair touching a certified step's box, and its role there.
type Boxed = ((i64, i64), Role);

/// The pairs touching a certified step's box (a dozen or so), kept inline.
type BoxedPairs = SmallVec<[Boxed; 16]>;

/// A tooth pair and the upper end of its obstacle at a step's end, if any.
type Evaluated = ((i64, i64), Option<f64>);

/// What a tooth pair touching a certified step's box may do there.
#[derive(Debug, Clone, Copy)]
enum Role {
    /// Behind the driven gear, its contact curves rising: it may push. `born`: not there at
    /// the step's start; `slopes`: the range of its contact curves' slopes dθ/dφ in the box.
    Rising { born: bool, slopes: (f64, f64) },
    /// Behind the driven gear, its contact curves falling: it never reaches it.
    Falling,
    /// Anything else: it must stay clear of the driven gear's path. `ahead`: an untracked pair
    /// whose contacts rise, found ahead of the driven gear (or gone) at the step's start.
    Suspect { ahead: bool },
}

/// The verdicts of a certified step: the pairs evaluated at its end, and which of them are born
/// or gone within it.
#[derive(Debug, Default)]
struct JudgedStep {
    pairs: SmallVec<[PairAtEnd; 8]>,
    /// Rising pairs not there at the step's start and there at its end.
    newborn: Pairs,
    /// Rising pairs there at the step's start and gone at its end.
    dead: Pairs,
    /// The driven angle at the step's end.
    theta1: f64,
    /// The range of slopes of the carriers' contact curves (the driven gear's path).
    slopes: (f64, f64),
    /// Untracked pairs found ahead at the step's start and proved clear of the path: ahead of
    /// the driven gear (or gone) at its end.
    clear_ahead: Pairs,
}

/// Where a certified step's pairs are judged: the stand at its start, its box, the driver angle
/// at its end, where the pushers end and the box's top.
struct BoxAt<'a, 's, 'm> {
    at: &'a Stand<'s, 'm>,
    cell: &'a ConfigBox,
    phi1: f64,
    pushed: f64,
    top: f64,
}

/// What one judgement of a certified step's pairs found ([`Certifier::judge_pairs`]).
#[allow(
    clippy::large_enum_variant,
    reason = "made once per judgement and moved straight out; a Box would allocate on the solver's hot path"
)]
enum Judgement {
    /// The step's verdicts.
    Step(JudgedStep),
    /// No certificate: a pair may meet the driven gear other than by pushing it.
    Refused,
    /// Judge again: the path has changed (a carrier widened it, or θ1 rose within the box).
    Again,
    /// θ1 rose above the box: judge in a taller one.
    Grow,
}

impl Certifier {
    /// Takes the step to `phi1` on a certificate - the whole step, or else its two halves - and
    /// returns whether it did (having changed nothing if not), counting the attempt.
    pub(super) fn try_certified(
        &mut self,
        run: &mut Run<'_>,
        phi1: f64,
        pushers: &[(i64, i64)],
    ) -> bool {
        let e0 = crate::mesh::tooth_pair_evaluations();
        let certified =
            self.certified_whole(run, phi1, pushers) || self.certified_halves(run, phi1, pushers);
        let spent = crate::mesh::tooth_pair_evaluations() - e0;
        count(|st| {
            if certified {
                st.certified += 1;
                st.certified_evaluations += spent;
            } else {
                st.refused += 1;
                st.refused_evaluations += spent;
            }
        });
        certified
    }

    /// Takes the whole step to `phi1` on a certificate ([`Certifier::proved`]), if one is
    /// found, and returns whether it did (having changed nothing if not).
    // One copy of this large step, its verdicts judged where they are taken (not handed back to
    // a caller: a few hundred bytes copied at every step cost 0.7 % of table5's instructions).
    #[inline(never)]
    fn certified_whole(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        let at = run.stand();
        let Some(mut judged) = self.judge_step(&at, phi1, pushers) else {
            return false;
        };
        if !self.proved(&at, &mut judged, phi1, pushers) {
            return false;
        }
        run.take_proved_step(phi1, judged.theta1, &judged.pairs);
        true
    }

    /// Whether the verdicts `judged` of the step from where the run stands (`at`) to `phi1`
    /// ([`Certifier::judge_step`]) are a certificate for it; if so the pairs it proves ahead are
    /// remembered for the next step. The certificate (`certify.rs` has the bounds):
    ///
    /// - Over the **box** of the step's driver angles and the driven angles from θ0 (less the
    ///   side tolerance) to θ1, every tooth pair near the driven gear either touches nowhere, or
    ///   is behind it with contact curves that only rise (it may push) or only fall; any other
    ///   pair is a *suspect*.
    /// - The driven angle, the running maximum of the rising curves, one of which (a pusher)
    ///   starts at θ0, then rises throughout (no gap): its **path** from (φ0, θ0) to (φ1, θ1)
    ///   lies in a thin tube about the chord, as wide as the spread of the slopes of the curves
    ///   it follows. Every suspect must stay clear of that tube (nothing ahead meets the driven
    ///   gear: no lock, no strike), and a rising pair that stays clear of it never carries the
    ///   gear and needs no evaluating.
    /// - Only the **carriers** bound the tube: the pushers, every pair behind whose contacts rise
    ///   and which ends the step above them (it has taken the gear over: known from the start),
    ///   and every rising pair found to reach the tube (each widens it by its own slopes, and
    ///   then every pair is judged again). This is
    ///   sound: the running maximum P of the carriers' curves has their slopes, so lies in their
    ///   tube; a rising pair that stays clear of that tube never meets P, and, starting below
    ///   it, stays below; so P is the driven gear's path. Unrelated rising pairs (an incoming
    ///   tooth's tip, a pair long past) no longer widen the tube: on m3-e3 the pushers' slopes
    ///   span 0.08-0.15 where every rising pair in the box spans 0.03-0.41.
    /// - θ1 is the largest upper end at φ1 of the rising pairs that reach the tube. A rising pair
    ///   cannot pass above θ1 and come back within the step (it would fall through the box), nor
    ///   vanish above it; one found higher at φ1 moves θ1 (and, past the box, widens it).
    /// - Pairs born or gone within the step meet the conditions of `births_and_deaths_hold`.
    ///
    /// Then no event lies in the step, and it ends at θ1, exactly as the exact step would end it.
    fn proved(
        &mut self,
        at: &Stand<'_, '_>,
        judged: &mut JudgedStep,
        phi1: f64,
        pushers: &[(i64, i64)],
    ) -> bool {
        // Every pusher is among the rising pairs (`judge_step` refuses a box where one is not):
        // one that fell would leave the driven gear.
        debug_assert!(
            pushers
                .iter()
                .all(|p| judged.pairs.iter().any(|m| m.pair == *p && m.rising)),
            "a pusher not judged rising"
        );
        if !self.births_and_deaths_hold(at, judged, phi1) {
            return false;
        }
        self.clear_ahead = (phi1, judged.theta1, std::mem::take(&mut judged.clear_ahead));
        true
    }

    /// The verdicts of the step from `at` to `phi1`, if they are a certificate for it
    /// ([`Certifier::proved`]).
    fn proved_step(
        &mut self,
        at: &Stand<'_, '_>,
        phi1: f64,
        pushers: &[(i64, i64)],
    ) -> Option<JudgedStep> {
        let mut judged = self.judge_step(at, phi1, pushers)?;
        self.proved(at, &mut judged, phi1, pushers)
            .then_some(judged)
    }

    /// Takes the step to `phi1` as two certified half steps when the whole step has no
    /// certificate (a thinner box and a thinner tube about the driven gear's path prove more), and
    /// returns whether it did. Only both halves together count: the second is proved from where
    /// the first would leave the run (`Stand::after_proved`), and the run moves over both only
    /// if it is; if not, the whole step is bracketed as before, over the same driver angles, so
    /// that no event is located differently. (Not tried while an event waits for the drive to
    /// resume and size it: the exact step sizes it where the drive resumes.)
    fn certified_halves(&mut self, run: &mut Run<'_>, phi1: f64, pushers: &[(i64, i64)]) -> bool {
        if run.sizing_waits() {
            return false;
        }
        let at = run.stand();
        let mid = 0.5 * (at.at().0 + phi1);
        let clear_ahead = self.clear_ahead.clone();
        if let Some(first) = self.proved_step(&at, mid, pushers) {
            let moved = at.after_proved(mid, first.theta1, &first.pairs);
            let pushers = moved.stand().pushers();
            if !pushers.is_empty()
                && let Some(second) = self.proved_step(&moved.stand(), phi1, &pushers)
            {
                run.take_proved_step(mid, first.theta1, &first.pairs);
                run.take_proved_step(phi1, second.theta1, &second.pairs);
                return true;
            }
        }
        self.clear_ahead = clear_ahead;
        false
    }

    /// The verdicts of a certified step to `phi1` (see [`Certifier::proved`]), or None when a
    /// pair may meet the driven gear other than by pushing it.
    fn judge_step(
        &self,
        at: &Stand<'_, '_>,
        phi1: f64,
        pushers: &[(i64, i64)],
    ) -> Option<JudgedStep> {
        let mesh = at.mesh();
        let (phi0, theta0) = at.at();
        // Each pair is evaluated at φ1 once, however often the box grows or θ1 moves; only the
        // upper ends are asked for (where the pairs behind end).
        let mut at1: SmallVec<[Evaluated; 8]> = SmallVec::new();
        let mut end_of = |pair: (i64, i64)| -> Option<f64> {
            if let Some(&(_, o)) = at1.iter().find(|e| e.0 == pair) {
                return o;
            }
            let o = mesh.obstacle_end(phi1, pair.0, pair.1, End::Upper);
            at1.push((pair, o));
            o
        };
        let pushed = pushers
            .iter()
            .filter_map(|&p| end_of(p))
            .fold(theta0, f64::max);
        let (overtakers, mut theta1) = overtakers(at, pushers, pushed, &mut end_of);
        'grow: for grown in 0..4 {
            // The first box reaches a little above where the pushers end: the next pusher, taking
            // over within the step, often ends higher, and a box found too low is judged again.
            let top = if grown == 0 {
                theta1 + BOX_HEADROOM * (theta1 - theta0)
            } else {
                theta1
            };
            let cell = ConfigBox::new(phi0, phi1, theta0 - SIDE_TOL, top, mesh.centre_distance);
            let boxed = self.box_verdicts(at, &cell, phi1, top)?;
            // A pusher whose contacts are not all rising cannot be followed: no certificate.
            if !pushers.iter().all(|&p| rises(&boxed, p)) {
                return None;
            }
            // An overtaker is a carrier where its contacts in the box rise (else it is judged
            // like any pair: a certificate needs them rising).
            let mut carriers: Pairs = SmallVec::from_slice(pushers);
            carriers.extend(overtakers.iter().copied().filter(|&o| rises(&boxed, o)));
            // θ1 only rises, each time to a pair's upper end, and the carriers only grow: this
            // ends.
            loop {
                let box_at = BoxAt {
                    at,
                    cell: &cell,
                    phi1,
                    pushed,
                    top,
                };
                match self.judge_pairs(&box_at, &boxed, (&mut carriers, &mut theta1), &mut end_of) {
                    Judgement::Step(judged) => return Some(judged),
                    Judgement::Refused => return None,
                    Judgement::Again => {}
                    Judgement::Grow => continue 'grow,
                }
            }
        }
        None
    }

    /// One judgement of every pair in the box `b` holds (`boxed`) against the driven gear's path
    /// from θ0 to `theta1` carried by `carriers`: the step's verdicts, or a refusal, or the
    /// path to judge again (a carrier added that widens it, or θ1 raised to a pair's upper
    /// end), or a taller box (θ1 above its top). Only `carriers` and `theta1` change between
    /// judgements.
    fn judge_pairs(
        &self,
        b: &BoxAt<'_, '_, '_>,
        boxed: &BoxedPairs,
        (carriers, theta1): (&mut Pairs, &mut f64),
        end_of: &mut impl FnMut((i64, i64)) -> Option<f64>,
    ) -> Judgement {
        let theta0 = b.at.at().1;
        let (cell, pushed) = (b.cell, b.pushed);
        let theta1_now = *theta1;
        let slopes = carrier_slopes(boxed, carriers);
        let path = cell.with_driven(theta0, theta1_now);
        let clear = |(j, k): (i64, i64)| {
            path.clear_along(
                &path.place_driver(self.driver_tooth(j)),
                &path.place_driven(self.driven_tooth(k)),
                slopes,
                SIDE_TOL,
            )
        };
        let mut judged = JudgedStep {
            theta1: theta1_now,
            slopes,
            ..JudgedStep::default()
        };
        for &(pair, role) in boxed {
            match role {
                Role::Suspect { ahead } if clear(pair) => {
                    if ahead {
                        judged.clear_ahead.push(pair);
                    }
                }
                Role::Suspect { .. } => return Judgement::Refused,
                Role::Falling if pushed - theta0 > 2.0 * SIDE_TOL => {
                    // Falling from behind θ0: it never reaches θ, whatever becomes of
                    // it, and ends too far below θ1 to push at the next step.
                    judged.pairs.push(not_carrying(pair));
                }
                Role::Falling => judged.pairs.push(PairAtEnd {
                    pair,
                    hi: end_of(pair).unwrap_or(f64::NEG_INFINITY),
                    rising: false,
                }),
                // Never on the path: it carries nothing, wherever it ends. One that was
                // behind at φ0 still is (tracked, as no pusher); one born in the step
                // may be on either side of the driven gear (left untracked).
                Role::Rising { born, .. } if !carriers.contains(&pair) && clear(pair) => {
                    if !born {
                        judged.pairs.push(not_carrying(pair));
                    }
                }
                Role::Rising { born, slopes: r } => {
                    // It reaches the tube: a carrier, whose slopes may widen the tube
                    // (and then every pair is judged again).
                    if !carriers.contains(&pair) {
                        carriers.push(pair);
                        if r.0 < slopes.0 || r.1 > slopes.1 {
                            return Judgement::Again;
                        }
                    }
                    let end = end_of(pair);
                    if let Some(early) =
                        self.carrier_at_end(b, (pair, born), end, theta1, &mut judged)
                    {
                        return early;
                    }
                }
            }
        }
        Judgement::Step(judged)
    }

    /// A carrier `pair` (`born` within the step) at the step's end, its obstacle's upper end
    /// `end` there: θ1 raised to it (the path judged again, or in a taller box), a refusal, or
    /// its verdict added to `judged` (`None`: judging goes on).
    fn carrier_at_end(
        &self,
        b: &BoxAt<'_, '_, '_>,
        (pair, born): ((i64, i64), bool),
        end: Option<f64>,
        theta1: &mut f64,
        judged: &mut JudgedStep,
    ) -> Option<Judgement> {
        match end {
            Some(hi) if hi > *theta1 => {
                *theta1 = hi;
                if hi > b.top {
                    return Some(Judgement::Grow);
                }
                return Some(Judgement::Again);
            }
            Some(hi) => {
                judged.pairs.push(PairAtEnd {
                    pair,
                    hi,
                    rising: true,
                });
                if born {
                    judged.newborn.push(pair);
                }
            }
            None if born => {
                // Neither at φ0 nor at φ1: a pair whose contacts only rise is
                // born and dies where two of its vertices meet; with no meeting
                // in the step it never touches.
                if self
                    .vertex_meeting(b.at.mesh(), pair, (b.at.at().0, b.phi1), false)
                    .is_some()
                {
                    return Some(Judgement::Refused);
                }
            }
            None => {
                judged.dead.push(pair);
                judged.pairs.push(PairAtEnd {
                    pair,
                    hi: f64::NEG_INFINITY,
                    rising: true,
                });
            }
        }
        None
    }

    /// Every tooth pair that touches `cell`, the box of the step to `phi1` and driven angles
    /// from θ0 (less the side tolerance) to `top`, with its role (for a rising pair, with the range of
    /// slopes of its contact curves in the box); None when an untracked pair straddles the
    /// driven angle at the step's start.
    fn box_verdicts(
        &self,
        at: &Stand<'_, '_>,
        cell: &ConfigBox,
        phi1: f64,
        top: f64,
    ) -> Option<BoxedPairs> {
        let mesh = at.mesh();
        let (phi0, theta0) = at.at();
        let (driver, driven) = (&mesh.driver, &mesh.driven);
        let bottom = theta0 - SIDE_TOL;
        let drivers = driver.teeth_between(-phi1 - driver.window, -phi0 + driver.window);
        let drivens = driven.teeth_between(bottom - driven.window, top + driven.window);
        // Each tooth is placed in the box once, and only if its disc comes near another's.
        let discs: SmallVec<[_; 16]> = drivens
            .clone()
            .map(|k| cell.driven_disc(self.driven_tooth(k)))
            .collect();
        let mut placed: SmallVec<[Option<Placement>; 16]> = SmallVec::from_elem(None, discs.len());
        let mut boxed = SmallVec::new();
        for j in drivers {
            let disc = cell.driver_disc(self.driver_tooth(j));
            let mut a = None;
            for (i, k) in drivens.clone().enumerate() {
                if cell.apart(disc, discs[i]) {
                    continue;
                }
                let a = a.get_or_insert_with(|| cell.place_driver(self.driver_tooth(j)));
                let tooth = self.driven_tooth(k);
                let b = placed[i].get_or_insert_with(|| cell.place_driven(tooth).at);
                let pair = (j, k);
                let (verdict, range) = cell.pair(a, &PlacedTooth { tooth, at: *b });
                let role = match (verdict, at.side_of(pair)) {
                    (Verdict::Clear, _) => continue,
                    (Verdict::Rising, Some(Side::Behind)) => Role::Rising {
                        born: false,
                        slopes: range,
                    },
                    (Verdict::Falling, Some(Side::Behind)) => Role::Falling,
                    // A pair not yet tracked whose contacts in the box only rise: behind if it is
                    // behind θ at φ0; if it is not there yet, it is born in the step, and where is
                    // judged by `births_and_deaths_hold`. It is classified (and then tracked)
                    // even when it stays clear of the path: left untracked, a later bracketed step
                    // would judge it as a pair new to the scan, which it is not. One already
                    // ahead at φ0 is an obstacle ahead like any other: it must stay clear of the
                    // path (untracked, as a bracketed step finds it ahead where it starts).
                    // One the last step proved ahead (or gone) here is taken as ahead: a
                    // suspect whatever it does, it must stay clear of the path.
                    (Verdict::Rising, None) if self.known_clear_ahead(at, pair) => {
                        Role::Suspect { ahead: true }
                    }
                    (Verdict::Rising, None) => match mesh.obstacle(phi0, j, k) {
                        None => Role::Rising {
                            born: true,
                            slopes: range,
                        },
                        Some(o) if o.hi <= theta0 + SIDE_TOL => Role::Rising {
                            born: false,
                            slopes: range,
                        },
                        Some(o) if o.lo >= theta0 - SIDE_TOL => Role::Suspect { ahead: true },
                        Some(_) => return None,
                    },
                    // Ahead of the driven gear, or not proved to rise or fall: it must stay
                    // clear of the driven gear's path.
                    _ => Role::Suspect { ahead: false },
                };
                boxed.push((pair, role));
            }
        }
        Some(boxed)
    }

    /// Whether the pairs born or gone in a judged step leave the drive continuous and nothing
    /// ahead: a pair whose contacts only rise is born, and dies, where two of its vertices meet
    /// (`certify::vertex_meeting`). A pair born above the driven gear would be an obstacle ahead;
    /// one that died while carrying it must hand it to another there.
    fn births_and_deaths_hold(&self, at: &Stand<'_, '_>, judged: &JudgedStep, phi1: f64) -> bool {
        let mesh = at.mesh();
        let (phi0, theta0) = at.at();
        // The driven angle at φ without pair `except`: the largest upper end of the other rising
        // pairs, at least θ0.
        let others = |phi: f64, except: (i64, i64)| {
            judged
                .pairs
                .iter()
                .filter(|m| m.rising && m.pair != except)
                .map(|m| mesh.hi(phi, m.pair))
                .fold(theta0, f64::max)
        };
        let meeting =
            |pair: (i64, i64), last: bool| self.vertex_meeting(mesh, pair, (phi0, phi1), last);

        // Where the driven gear is at least, by the path's tube (`ConfigBox::clear_along`): when
        // a pair is born below that, nothing need be evaluated.
        let (s_lo, s_hi) = judged.slopes;
        let chord = (judged.theta1 - theta0) / (phi1 - phi0);
        let width = (s_hi - s_lo).max(0.0) * (phi1 - phi0) / 4.0;
        let at_least = |phi: f64| (theta0 + chord * (phi - phi0) - width).max(theta0);
        // A pair that dies below where the driven gear is at least was not carrying it.
        let deaths_hand_over = judged.dead.iter().all(|&pair| {
            meeting(pair, true).is_some_and(|(phi_d, at)| {
                crate::tooth::wrap_pi(at - at_least(phi_d)) < -SIDE_TOL
                    || crate::tooth::wrap_pi(at - others(phi_d, pair)) <= SIDE_TOL
            })
        });
        let births_behind = judged.newborn.iter().all(|&pair| {
            meeting(pair, false).is_some_and(|(phi_b, at)| {
                crate::tooth::wrap_pi(at - at_least(phi_b)) <= SIDE_TOL
                    || crate::tooth::wrap_pi(at - others(phi_b, pair)) <= SIDE_TOL
            })
        });
        deaths_hand_over && births_behind
    }
}

/// The pairs behind the driven gear that end the step above where the pushers do (`pushed`),
/// and the highest end of all: such a pair has taken the gear over within the step, so it is
/// a carrier from the start, that the first box be tall enough and the path's tube wide
/// enough (else the box grows, and every pair is judged again, once it is found). Only pairs
/// near enough to overtake are evaluated: within twice the pushers' rise below θ0.
fn overtakers(
    at: &Stand<'_, '_>,
    pushers: &[(i64, i64)],
    pushed: f64,
    end_of: &mut impl FnMut((i64, i64)) -> Option<f64>,
) -> (Pairs, f64) {
    let theta0 = at.at().1;
    let (mut overtakers, mut theta1) = (Pairs::new(), pushed);
    for t in at.tracked() {
        if t.side == Side::Behind
            && !pushers.contains(&t.pair)
            && t.hi > theta0 - 2.0 * (pushed - theta0)
            && let Some(hi) = end_of(t.pair)
            && hi > pushed
        {
            theta1 = theta1.max(hi);
            overtakers.push(t.pair);
        }
    }
    (overtakers, theta1)
}

/// Whether `pair`'s contacts in the box all rise.
fn rises(boxed: &BoxedPairs, pair: (i64, i64)) -> bool {
    boxed
        .iter()
        .any(|(p, role)| *p == pair && matches!(role, Role::Rising { .. }))
}

/// The range of slopes dθ/dφ of the carriers' contacts in the box, which bounds the path: the
/// pushers, and each rising pair found to reach the path's tube.
fn carrier_slopes(boxed: &BoxedPairs, carriers: &Pairs) -> (f64, f64) {
    boxed
        .iter()
        .filter(|(pair, _)| carriers.contains(pair))
        .fold(
            (f64::INFINITY, f64::NEG_INFINITY),
            |s, (_, role)| match role {
                Role::Rising { slopes: r, .. } => (s.0.min(r.0), s.1.max(r.1)),
                _ => s,
            },
        )
}
