//! One step of the push model with no certificate: the tooth pairs near the driven gear are
//! sorted into those behind it and those ahead, the path is planned from the pairs behind (push,
//! gap, rest, push again), and the first pair ahead to close on that path is found at a root of
//! their contact conditions (`closing.rs`); the run then follows the plan up to the step's end
//! or the jam.

use std::cell::{OnceCell, RefCell};

use super::*;
use crate::mesh::ConditionSet;

/// How far (radians of driven angle, relative to 1 + |θ|) the box a closing is searched in
/// reaches past the driven angles of the step's path: far past the rounding of the roots and the
/// obstacles' ends (about 1e-14 rad), so that no condition with a root the search reads is left
/// out of it.
const BOX_MARGIN: f64 = 1e-9;

/// A planned stretch of a step: its last driver angle, its last driven angle, the motion over
/// it, and the event at its end, if any.
type Planned = (f64, f64, Motion, Option<Event>);

/// Tooth pairs (driver tooth, driven tooth), unwrapped.
type PairList = Vec<(i64, i64)>;

/// What a step knows of the tooth pairs near the driven gear: the obstacles at its end, and each
/// end of a pair's obstacle evaluated once at each driver angle it is asked for.
struct Step<'m> {
    mesh: &'m Mesh,
    phi0: f64,
    theta0: f64,
    phi1: f64,
    pushers: Pairs,
    /// The obstacles at `phi1` near the driven gear.
    obs1: Vec<Obstacle>,
    /// Ends evaluated at driver angles other than `phi1` (a few dozen at most a step).
    memo: RefCell<Vec<Memo>>,
    /// Where the pushers' upper envelope peaks in the step, and its value there, once asked.
    peak: OnceCell<(f64, f64)>,
}

impl Step<'_> {
    fn at1(&self, pair: (i64, i64)) -> Option<&Obstacle> {
        self.obs1
            .iter()
            .find(|o| (o.driver_tooth, o.driven_tooth) == pair)
    }

    /// One end of a pair's obstacle at φ = `p`, evaluated once.
    fn end_at(&self, p: f64, pair: (i64, i64), end: End) -> Option<f64> {
        if p == self.phi1 {
            return self.at1(pair).map(|o| match end {
                End::Lower => o.lo,
                End::Upper => o.hi,
            });
        }
        if let Some(&(.., o)) = self
            .memo
            .borrow()
            .iter()
            .find(|m| m.0 == p && m.1 == pair && m.2 == end)
        {
            return o;
        }
        let o = self.mesh.obstacle_end(p, pair.0, pair.1, end);
        let mut m = self.memo.borrow_mut();
        if m.len() >= 64 {
            m.clear();
        }
        m.push((p, pair, end, o));
        o
    }

    fn hi(&self, p: f64, pair: (i64, i64)) -> f64 {
        self.end_at(p, pair, End::Upper)
            .unwrap_or(f64::NEG_INFINITY)
    }

    fn lo(&self, p: f64, pair: (i64, i64)) -> f64 {
        self.end_at(p, pair, End::Lower).unwrap_or(f64::INFINITY)
    }

    /// The highest upper end of `pairs` at φ = `p`.
    fn envelope(&self, pairs: &[(i64, i64)], p: f64) -> f64 {
        pairs
            .iter()
            .map(|&b| self.hi(p, b))
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Where the pushers' upper envelope peaks in the step (a golden-section search, refined
    /// where a pushing curve peaks smoothly: `Mesh::smooth_peak`), made once: the side of a
    /// pair born in the step and the plan both ask for it.
    fn push_peak(&self) -> (f64, f64) {
        *self.peak.get_or_init(|| {
            let env = |p: f64| self.envelope(&self.pushers, p);
            let (phi0, phi1) = (self.phi0, self.phi1);
            let phi_pk = golden_max(phi0, phi1, env);
            let phi_pk = self
                .mesh
                .smooth_peak(phi_pk, (phi0, phi1), &self.pushers, env);
            (phi_pk, env(phi_pk))
        })
    }

    /// θ on the plan at φ = `p`.
    fn theta_on(&self, plan: &[Planned], p: f64) -> f64 {
        let mut from = self.theta0;
        for (end, th, motion, _) in plan {
            if p <= *end {
                return match motion {
                    Motion::Push(pairs) => self.envelope(pairs, p).max(from).min(*th),
                    _ => from,
                };
            }
            from = *th;
        }
        from
    }
}

impl Run<'_> {
    /// Advances from `self.phi` to `phi1` (or, at rest, to just past the first touch of any
    /// driver tooth), locating every event in between; `speed` may leave out of a closing's
    /// search the conditions it proves to hold nowhere near the step's path.
    pub(super) fn exact_step(&mut self, phi1: f64, pushers: Pairs, speed: &mut dyn Shortcut) {
        count(|st| st.bracketed += 1);
        let mesh = self.mesh;
        let (phi0, theta0) = (self.phi, self.theta);
        // Standing still, the first touch of any driver tooth is found exactly; end the step just
        // after it, so that even a brief graze (a tip clipping a tip) is seen at the step's end.
        let touch = if pushers.is_empty() {
            mesh.first_touch(theta0, phi0, phi1)
        } else {
            None
        };
        let phi1 = touch.map_or(phi1, |t| phi1.min(t + TOUCH_STEP));
        let gap = mesh.driven.max_gap;
        mesh.obstacles(
            phi1,
            theta0 - 0.4 * gap,
            theta0 + 0.6 * gap,
            &mut self.scratch,
        );
        let step = Step {
            mesh,
            phi0,
            theta0,
            phi1,
            pushers,
            obs1: std::mem::take(&mut self.scratch),
            memo: RefCell::new(Vec::new()),
            peak: OnceCell::new(),
        };
        let (mut behind, mut ahead) = self.sides_in_step(&step);
        let all_behind = behind.clone();
        // Only obstacles that can reach θ within this step matter to the motion.
        behind.retain(|&p| step.pushers.contains(&p) || step.hi(phi1, p) >= theta0 - 0.25 * gap);
        let plan = self.plan_step(&step, &behind);
        let theta1 = step.theta_on(&plan, phi1);
        ahead.retain(|&a| step.lo(phi1, a) <= theta1 + 0.5 * gap);
        // A pair ahead where the step starts may close on the driven gear and be gone by its
        // end (a tip passing a tip): it is not among the obstacles at φ1, so it is added.
        for t in &self.sides {
            if t.side == Side::Ahead
                && step.at1(t.pair).is_none()
                && step.lo(phi0, t.pair) <= theta0 + 0.5 * gap
            {
                ahead.push(t.pair);
            }
        }
        // Just after a closing that held nothing (its pair now counts as behind), a closing at
        // the step's very start is that one again: only later roots are asked for, so that the
        // run moves on, and a pair ahead closing later in the step is still found.
        let after_start = self.unheld_at == Some(phi0);
        let jam = first_jam(&step, &plan, &ahead, after_start, speed);
        match jam {
            None => self.follow_plan(&step, plan, &all_behind, theta1),
            Some(phi_j) => self.jam(&step, plan, phi_j, &ahead),
        }
        self.scratch = step.obs1;
    }

    /// The pairs near the driven gear at the step's end sorted into those behind it (the pushers
    /// first) and those ahead: by the side they were on, or, for a pair new to the step, by
    /// where it lies, or where it first appeared.
    fn sides_in_step(&self, step: &Step<'_>) -> (PairList, PairList) {
        let mut behind: Vec<(i64, i64)> = step.pushers.to_vec();
        let mut ahead: Vec<(i64, i64)> = Vec::new();
        let mut unsure: Vec<Obstacle> = Vec::new();
        for o in &step.obs1 {
            let pair = (o.driver_tooth, o.driven_tooth);
            match self.side_of(pair) {
                Some(Side::Behind) => {
                    if !behind.contains(&pair) {
                        behind.push(pair);
                    }
                }
                Some(Side::Ahead) => ahead.push(pair),
                None if o.hi <= step.theta0 + SIDE_TOL => behind.push(pair),
                None => unsure.push(*o),
            }
        }
        for o in unsure {
            let pair = (o.driver_tooth, o.driven_tooth);
            match side_of_new_pair(step, &o, &behind) {
                Side::Behind => behind.push(pair),
                Side::Ahead => ahead.push(pair),
            }
        }
        (behind, ahead)
    }

    /// The step's path planned from the pairs `behind` alone (the pushers first): pushed
    /// throughout, or to where the pushers stop rising (a gap), then at rest until a pair behind
    /// reaches the gear again.
    fn plan_step(&self, step: &Step<'_>, behind: &[(i64, i64)]) -> Vec<Planned> {
        let (phi0, theta0, phi1) = (step.phi0, step.theta0, step.phi1);
        let pushers = &step.pushers;
        let mut plan = Vec::new();
        if pushers.is_empty() {
            rest_then_maybe_push(step, &mut plan, behind, (phi0, theta0));
            return plan;
        }
        // Is the push continuous through the step? The pushers' envelope must not peak: a curve
        // higher mid-step, or just before the end, than at the end has peaked inside the step.
        // (Rounding may put the pushers' curve a hair below θ at a step end: that is not a
        // lost contact.)
        let e1 = step.envelope(behind, phi1);
        let p1 = step.envelope(pushers, phi1);
        let dphi = 1e-6 * (phi1 - phi0);
        let mid = 0.5 * (phi0 + phi1);
        let pushers_hold = p1 >= theta0 - SIDE_TOL
            && step.envelope(pushers, mid) <= p1 + SIDE_TOL
            && step.envelope(pushers, phi1 - dphi) <= p1;
        let all_rising =
            step.envelope(behind, mid) <= e1 + SIDE_TOL && step.envelope(behind, phi1 - dphi) <= e1;
        if pushers_hold && all_rising {
            // Every obstacle behind takes part: another tooth pair may carry the driven gear
            // for part of the step (two pairs in contact at once).
            plan.push((phi1, e1.max(theta0), Motion::Push(behind.to_vec()), None));
            return plan;
        }
        // Where do the pushers stop rising (peak or vanish)? Did another pair behind take over
        // before that?
        let (phi_pk, theta_pk) = step.push_peak();
        let theta_pk = theta_pk.max(theta0);
        let others: Vec<(i64, i64)> = behind
            .iter()
            .copied()
            .filter(|p| !pushers.contains(p))
            .collect();
        if step.envelope(&others, phi_pk) >= theta_pk - SIDE_TOL {
            // Continuous hand-over: one push over the whole step with every pair behind.
            plan.push((phi1, e1.max(theta0), Motion::Push(behind.to_vec()), None));
        } else if !self.sizing.pending.is_empty() && theta_pk <= theta0 + SIDE_TOL {
            // The gear rests (drive lost) and the pair touching it from behind where the step
            // starts falls away without lifting it: a graze, not drive resumed (a tip of the
            // radius of the one that left the gear there passes it exactly).
            rest_then_maybe_push(step, &mut plan, &others, (phi0, theta0));
        } else {
            let lost = step.mesh.top_pair(phi_pk, pushers).unwrap_or(pushers[0]);
            plan.push((
                phi_pk,
                theta_pk,
                Motion::Push(pushers.to_vec()),
                Some(Event::new(EventKind::Gap, phi_pk, theta_pk, lost)),
            ));
            rest_then_maybe_push(step, &mut plan, &others, (phi_pk, theta_pk));
        }
        plan
    }

    /// No pair ahead closes in the step: the plan is followed to its end, and the sides of the
    /// pairs there are kept for the next step.
    fn follow_plan(
        &mut self,
        step: &Step<'_>,
        plan: Vec<Planned>,
        all_behind: &[(i64, i64)],
        theta1: f64,
    ) {
        for (end, th, motion, event) in plan {
            self.push_segment(end, th, motion);
            if let Some(e) = event {
                self.record(e, Some(e.driver_tooth + e.driven_tooth));
            }
        }
        self.sides.clear();
        for o in &step.obs1 {
            let pair = (o.driver_tooth, o.driven_tooth);
            let side = if all_behind.contains(&pair) || o.hi <= theta1 + SIDE_TOL {
                Side::Behind
            } else {
                Side::Ahead
            };
            self.sides.push(Tracked {
                pair,
                side,
                hi: o.hi,
            });
        }
    }

    /// A pair of `ahead` closes on the driven gear at φ_j: the plan is followed up to there, and
    /// the closing is judged - a lock (a pair touches behind) or a strike (none does), the gear
    /// let go to the next free position or held where there is none; or no jam at all, where
    /// nothing ahead actually holds the gear (the closing tooth only touches it, or vanished).
    fn jam(&mut self, step: &Step<'_>, plan: Vec<Planned>, phi_j: f64, ahead: &[(i64, i64)]) {
        let mesh = self.mesh;
        let th_j = step.theta_on(&plan, phi_j);
        for (end, th, motion, event) in plan {
            if end < phi_j {
                self.push_segment(end, th, motion);
                if let Some(e) = event {
                    self.record(e, Some(e.driver_tooth + e.driven_tooth));
                }
            } else {
                self.push_segment(phi_j, th_j, motion);
                break;
            }
        }
        let theta_j = self.theta;
        // Every scan at φ_j below evaluates a pair once (`PairMemo`).
        let mut memo = PairMemo::new(mesh, phi_j);
        let mut lo_j = |pair: (i64, i64)| {
            mesh.obstacle_in(phi_j, pair.0, pair.1, &mut memo)
                .map_or(f64::INFINITY, |o| o.lo)
        };
        let closing = ahead
            .iter()
            .map(|&pair| (pair, lo_j(pair)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map_or((0, 0), |(pair, _)| pair);
        let release = mesh
            .free_or_cover_in(phi_j, theta_j, true, None, &mut memo)
            .ok();
        if release.is_some_and(|t| t <= theta_j + SIDE_TOL) {
            // No jam. Count the pair as behind and go on.
            self.classify_all(phi_j, &mut memo);
            for t in &mut self.sides {
                if t.pair == closing {
                    t.side = Side::Behind;
                }
            }
            // Guarantee progress: at most one such non-event per driver angle.
            self.unheld_at = Some(phi_j);
            return;
        }
        if release.is_none() {
            self.drive = Drive::Held { links: Vec::new() };
        }
        let after = release.unwrap_or(theta_j);
        // Held from both sides (a pair touching behind as the one ahead closes), or struck
        // from the front with nothing pushing.
        let behind_pair = self.touching_behind(phi_j, theta_j, Some(closing), &mut memo);
        let (kind, before) = match behind_pair {
            Some(p) => (EventKind::Lock, Some(p.0 + p.1)),
            None => (EventKind::Strike, self.sizing.phase),
        };
        let mut e = Event::new(kind, phi_j, theta_j, closing);
        e.theta_after = after;
        e.wedge_angle = mesh
            .contact_normal(phi_j, theta_j, closing.0, closing.1)
            .map(|(p, n)| mesh.angle_to_driven_centre(p, n));
        self.record(e, before);
        self.theta = after;
        self.classify_all(phi_j, &mut memo);
    }
}

/// The side of a pair new to the step, not clearly behind the driven gear (`o`: its obstacle at
/// the step's end): ahead if it lies above where the gear can get to in the step; behind if it
/// was already there behind θ at the start (obstacles do not pass through θ without a jam);
/// otherwise decided where it first appeared.
fn side_of_new_pair(step: &Step<'_>, o: &Obstacle, behind: &[(i64, i64)]) -> Side {
    let (mesh, phi0, theta0) = (step.mesh, step.phi0, step.theta0);
    let pair = (o.driver_tooth, o.driven_tooth);
    let reach = behind
        .iter()
        .map(|&p| step.hi(step.phi1, p))
        .fold(theta0, f64::max);
    let at_start = mesh.obstacle(phi0, pair.0, pair.1);
    if o.lo >= reach + mesh.driven.max_gap {
        return Side::Ahead;
    }
    if let Some(a0) = at_start {
        if a0.hi <= theta0 + SIDE_TOL {
            return Side::Behind;
        }
        if a0.lo >= theta0 - SIDE_TOL {
            return Side::Ahead;
        }
    }
    // Where it appeared, closely enough to tell its side (not to LOCATE_TOL: the side is all
    // that is asked). An obstacle that appeared below θ and rose past it within the step is
    // behind (it pushed), even though it lies above θ0 now.
    let phi_a = bracket(phi0, step.phi1, SIDE_LOCATE_TOL, |p| {
        mesh.obstacle(p, pair.0, pair.1).is_none()
    })
    .1;
    let at = mesh
        .obstacle(phi_a, pair.0, pair.1)
        .map_or(o.lo, |a| 0.5 * (a.lo + a.hi));
    let theta_a = behind
        .iter()
        .map(|&b| mesh.hi(phi_a, b))
        .fold(theta0, f64::max);
    // The driven gear never turns back: where the pushers peaked before φ_a (they lost
    // contact there), it rests at least at their peak, which may lie above where they are at
    // φ_a.
    let rests_above = || {
        let (phi_pk, theta_pk) = step.push_peak();
        phi_pk <= phi_a && at <= theta_pk + SIDE_TOL
    };
    if at <= theta_a + SIDE_TOL || (!step.pushers.is_empty() && rests_above()) {
        Side::Behind
    } else {
        Side::Ahead
    }
}

/// Plans a rest at θ from `phi_a`, re-engaging where a pair of `behind` reaches θ, if one does
/// by the step's end: a root of one of its conditions at θ (`closing::first_reach`).
fn rest_then_maybe_push(
    step: &Step<'_>,
    plan: &mut Vec<Planned>,
    behind: &[(i64, i64)],
    (phi_a, theta): (f64, f64),
) {
    let phi1 = step.phi1;
    let e1 = step.envelope(behind, phi1);
    if e1 > theta + SIDE_TOL {
        let reach = |p: f64| theta - step.envelope(behind, p);
        let phi_r = closing::first_reach(step.mesh, behind, theta, (phi_a, phi1), reach);
        debug_assert!(phi_r.is_some(), "a pair behind rose past θ at no root");
        plan.push((phi_r.unwrap_or(phi1), theta, Motion::Rest, None));
        plan.push((phi1, e1, Motion::Push(behind.to_vec()), None));
    } else {
        plan.push((phi1, theta, Motion::Rest, None));
    }
}

/// Where the first pair of `ahead` closes on the planned path in the step: at its start if one
/// overlaps the gear there already, else at the first root where the backlash stops being
/// positive (`closing::first_closing`); with `after_start`, at a root after the start only. The
/// speed layer may leave out of the search the conditions that hold nowhere in the box of the
/// step's driver angles and the path's driven angles (`Shortcut::conditions_in_box`).
fn first_jam(
    step: &Step<'_>,
    plan: &[Planned],
    ahead: &[(i64, i64)],
    after_start: bool,
    speed: &mut dyn Shortcut,
) -> Option<f64> {
    if ahead.is_empty() {
        return None;
    }
    let backlash = |p: f64| {
        let front = ahead
            .iter()
            .map(|&a| step.lo(p, a))
            .fold(f64::INFINITY, f64::min);
        front - step.theta_on(plan, p)
    };
    if !after_start && backlash(step.phi0) < -SIDE_TOL {
        return Some(step.phi0);
    }
    let stretches = stretches_of(plan, step.phi0, step.theta0);
    let theta1 = step.theta_on(plan, step.phi1);
    let widen = BOX_MARGIN * (1.0 + theta1.abs());
    let (phis, thetas) = (
        (step.phi0, step.phi1),
        (step.theta0 - widen, theta1 + widen),
    );
    // After a closing that held nothing the search starts at its first root, whichever
    // conditions it comes from: then every condition is taken.
    let mut sets = |pair: (i64, i64)| {
        if after_start {
            ConditionSet::ALL
        } else {
            speed.conditions_in_box(step.mesh, pair, phis, thetas)
        }
    };
    let search = (
        after_start,
        &mut sets as &mut dyn FnMut((i64, i64)) -> ConditionSet,
    );
    closing::first_closing(step.mesh, &stretches, ahead, search, backlash)
}

/// The stretches of a step's plan from (φ0, θ0), as the closing search reads them.
fn stretches_of(plan: &[Planned], phi0: f64, theta0: f64) -> Vec<closing::Stretch<'_>> {
    let (mut phi, mut theta) = (phi0, theta0);
    let mut out = Vec::with_capacity(plan.len());
    for (end, th, motion, _) in plan {
        let path = match motion {
            Motion::Push(pairs) => closing::Path::Push {
                pairs,
                levels: [theta, *th],
            },
            _ => closing::Path::Rest(theta),
        };
        out.push(closing::Stretch {
            phi: (phi, *end),
            path,
        });
        (phi, theta) = (*end, *th);
    }
    out
}
