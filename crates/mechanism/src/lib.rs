//! Whole-train simulation: a pointer's meshes composed in order, each with its own random initial angle.
//!
//! The push model is quasi-static: a mesh's driven angle depends only on its driver angle, not on
//! how fast it turns. So a train is simulated mesh by mesh: the first mesh's driver turns with the
//! input (b) arbor; each mesh's driven gear turns its arbor, and that arbor's rotation is the next
//! mesh's driver rotation. Every mesh starts at a uniformly random driver angle within its driver's
//! pitch (the paper: the maker could not set it), with the driven gear touching.
//!
//! The pin-and-slot (Freeth 2006's lunar anomaly mechanism, [`pin_slot`]) is left out unless a
//! mechanism asks for it with [`Mechanism::with_pin_and_slot`]: the paper treats k1 -> k2 as a
//! rigid arbor and holds the e3 turntable still.

pub mod pin_slot;

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use contact::{Mesh, Solve, Start, Trajectory};
use edmunds::RadialPair;
use geometry::Gear;
use rand::Rng;
use rules::Rule;
use train::Gearing;

pub use pin_slot::PinSlotTrain;

/// Why a mechanism could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("mesh {mesh}: {rule}")]
pub struct MechanismError {
    /// The mesh label.
    pub mesh: String,
    /// What went wrong.
    pub rule: String,
}

/// The gears of every mesh, ready to run.
#[derive(Debug, Clone)]
pub struct Mechanism {
    gearing: Gearing,
    meshes: BTreeMap<String, Mesh>,
    pin_and_slot: bool,
    /// Which events stop the train (the jams of an event rule).
    rule: Rule,
}

impl Mechanism {
    /// Ideal gears (no manufacturing error) sized as `train` sizes them, tooth height `h` mm and
    /// clearance `g_percent` of h for every mesh.
    pub fn ideal(gearing: &Gearing, h: f64, g_percent: f64) -> Result<Self, MechanismError> {
        Self::build(gearing, h, g_percent, |_name, gear| Ok(gear))
    }

    /// Like [`Mechanism::ideal`], but `make` turns each ideal gear into a manufactured one (an
    /// error model). It is called once per gear, in the gearing's gear order, so a gear in two
    /// meshes (b2) carries the same errors in both.
    pub fn build(
        gearing: &Gearing,
        h: f64,
        g_percent: f64,
        make: impl FnMut(&str, Gear) -> Result<Gear, String>,
    ) -> Result<Self, MechanismError> {
        Self::build_with_clearances(gearing, h, |_mesh| g_percent, make)
    }

    /// Like [`Mechanism::build`], but each mesh has its own clearance: `clearance(label)` is the
    /// clearance (% of h) of the mesh with that label, asked once per mesh in the gearing's mesh
    /// order. The gears are made exactly as by [`Mechanism::build`] (same calls of `make`, in the
    /// same order), so with the same `make` only the centre distances differ.
    pub fn build_with_clearances(
        gearing: &Gearing,
        h: f64,
        mut clearance: impl FnMut(&str) -> f64,
        mut make: impl FnMut(&str, Gear) -> Result<Gear, String>,
    ) -> Result<Self, MechanismError> {
        let in_a_mesh = |name: &str| {
            gearing
                .meshes()
                .iter()
                .any(|m| m.driver == name || m.driven == name)
        };
        let mut made: BTreeMap<String, Gear> = BTreeMap::new();
        for g in gearing.gears().iter().filter(|g| in_a_mesh(&g.name)) {
            let bad = |rule: String| MechanismError {
                mesh: format!("(gear {})", g.name),
                rule,
            };
            let ideal = gearing
                .ideal_gear(&g.name, h)
                .ok_or_else(|| bad("cannot be sized".into()))?
                .map_err(|e| bad(e.to_string()))?;
            made.insert(g.name.clone(), make(&g.name, ideal).map_err(bad)?);
        }
        let mut meshes = BTreeMap::new();
        for m in gearing.meshes() {
            let bad = |rule: String| MechanismError {
                mesh: m.label.clone(),
                rule,
            };
            let geo = gearing
                .mesh_geometry(&m.label, h, clearance(&m.label))
                .ok_or_else(|| bad("cannot be sized".into()))?;
            let gear = |name: &str| {
                made.get(name)
                    .cloned()
                    .ok_or_else(|| bad(format!("gear {name} was not made")))
            };
            let mesh = Mesh::new(gear(&m.driver)?, gear(&m.driven)?, geo.centre_distance)
                .map_err(|e| bad(e.to_string()))?;
            meshes.insert(m.label.clone(), mesh);
        }
        Ok(Self {
            gearing: gearing.clone(),
            meshes,
            pin_and_slot: false,
            rule: Rule::default(),
        })
    }

    /// This mechanism with the pin-and-slot in (`true`) or left out (`false`, the paper and the
    /// default). With it, a pointer whose train runs through the gearing's pin gear (Freeth
    /// 2006: the Lunar pointer) is run with the pin mesh (e5-k1) and the slot gear's mesh
    /// (k2-e6) seen from the turntable, which turns at its mean rate from the gear ratios, and
    /// the pin-and-slot coupling the two ([`PinSlotTrain`]); its Theoretical Difference is taken
    /// against the anomaly-bearing ideal motion. Other pointers are run as without it.
    ///
    /// The cosmos's slot-gear devices (`train::PinDevice`) come in with it too: their pointers
    /// run with the slot gear's mesh driven through the pin, in b1's frame.
    ///
    /// # Errors
    /// `true` for a gearing with neither a `pin_and_slot` section nor devices.
    pub fn with_pin_and_slot(mut self, on: bool) -> Result<Self, MechanismError> {
        if on && self.gearing.pin_and_slot().is_none() && self.gearing.devices().is_empty() {
            return Err(MechanismError {
                mesh: "(pin-and-slot)".into(),
                rule: "the gearing has no pin_and_slot section".into(),
            });
        }
        self.pin_and_slot = on;
        Ok(self)
    }

    /// This mechanism with `rule` deciding which events are jams that stop the train (default:
    /// [`rules::DEFAULT`]).
    pub fn with_rule(mut self, rule: Rule) -> Self {
        self.rule = rule;
        self
    }

    /// The event rule that decides which events stop the train.
    pub fn rule(&self) -> &Rule {
        &self.rule
    }

    /// Whether the pin-and-slot is in (see [`Mechanism::with_pin_and_slot`]).
    pub fn has_pin_and_slot(&self) -> bool {
        self.pin_and_slot
    }

    /// The pin-and-slot in `pointer`'s train as this mechanism runs it: `None` when it is left
    /// out or the pointer's train does not run through it. The pin starts on the line of centres
    /// (phase 0).
    pub fn pin_slot_for(&self, pointer: &str) -> Option<PinSlotTrain> {
        if !self.pin_and_slot {
            return None;
        }
        PinSlotTrain::new(&self.gearing, pointer, 0.0)
    }

    /// The gearing this mechanism was built from.
    pub fn gearing(&self) -> &Gearing {
        &self.gearing
    }

    /// The contact mesh with this label.
    pub fn mesh(&self, label: &str) -> Option<&Mesh> {
        self.meshes.get(label)
    }

    /// Runs a pointer's train for `input_turns` turns of its input arbor with triangular teeth,
    /// drawing each mesh's initial driver angle from `rng`, in chain order.
    pub fn run_pointer(
        &self,
        pointer: &str,
        input_turns: f64,
        rng: &mut impl Rng,
    ) -> Option<PointerRun> {
        self.run_pointer_with(pointer, input_turns, rng, Model::Triangular)
    }

    /// Like [`Mechanism::run_pointer`], but each mesh stops at its first jam, and the meshes
    /// after it only turn as far as it got: enough for statistics up to the first stop, and much
    /// faster when gears jam often.
    pub fn run_pointer_to_first_jam(
        &self,
        pointer: &str,
        input_turns: f64,
        rng: &mut impl Rng,
    ) -> Option<PointerRun> {
        self.run_chain(pointer, input_turns, rng, Model::Triangular, true)
    }

    /// Runs a pointer's train with triangular teeth, each mesh stopping at its first jam, with
    /// the initial driver angle of each mesh given by `phi0(label)` instead of drawn: for a
    /// whole mechanism whose meshes got their angles once for all its pointers.
    pub fn run_pointer_from(
        &self,
        pointer: &str,
        input_turns: f64,
        mut phi0: impl FnMut(&str) -> Option<f64>,
    ) -> Option<PointerRun> {
        self.chain_from(
            pointer,
            input_turns,
            |label, _| phi0(label),
            Model::Triangular,
            true,
        )
    }
    /// Runs a pointer's train under either contact model. Both draw the same initial angles from
    /// the same stream, so a trial can be compared model against model on the same gears.
    pub fn run_pointer_with(
        &self,
        pointer: &str,
        input_turns: f64,
        rng: &mut impl Rng,
        model: Model,
    ) -> Option<PointerRun> {
        self.run_chain(pointer, input_turns, rng, model, false)
    }

    fn run_chain(
        &self,
        pointer: &str,
        input_turns: f64,
        rng: &mut impl Rng,
        model: Model,
        stop_at_jam: bool,
    ) -> Option<PointerRun> {
        self.chain_from(
            pointer,
            input_turns,
            |_, mesh| {
                let pitch = TAU / mesh.driver().teeth() as f64;
                Some(rng.random::<f64>() * pitch)
            },
            model,
            stop_at_jam,
        )
    }

    /// The chain of `pointer`, mesh `label` starting at driver angle `phi0(label, mesh)`; each
    /// mesh is run over the range its driver turns, in the frame it turns in (the turntable's,
    /// for the pin-and-slot's two meshes).
    fn chain_from(
        &self,
        pointer: &str,
        input_turns: f64,
        mut phi0: impl FnMut(&str, &Mesh) -> Option<f64>,
        model: Model,
        stop_at_jam: bool,
    ) -> Option<PointerRun> {
        let rule = &self.rule;
        let is_jam = |e: &contact::Event| rule.is_jam(e);
        let how = if stop_at_jam {
            Solve::path().stop_at(&is_jam)
        } else {
            Solve::path()
        };
        let p = self.gearing.pointer(pointer)?;
        let ratio = self.gearing.pointer_ratio(pointer)?.to_f64();
        let pin_slot = self.pin_slot_for(pointer);
        let input_range = input_turns * TAU;
        let mut stages = Vec::with_capacity(p.meshes.len());
        // The driven arbor's rotation over the run, in the fixed frame, of the previous mesh.
        let mut range = input_range;
        for (i, label) in p.meshes.iter().enumerate() {
            let mesh = self.meshes.get(label)?;
            let phi0 = phi0(label, mesh)?;
            let run_frame = Frame::of(pin_slot.as_ref(), i);
            // The most the driver turns in its own frame over the run.
            let range_in = run_frame.into_range(range, input_range);
            let run = match model {
                Model::Triangular => StageRun::Triangular(Box::new(mesh.solve(
                    phi0..=phi0 + range_in,
                    Start::Touching(0.0),
                    how,
                ))),
                Model::Edmunds => {
                    StageRun::Radial(RadialPair::new(mesh.driver(), mesh.driven(), phi0))
                }
            };
            let theta0 = run.theta_at(phi0);
            range = run_frame.out_range(run.theta_at(phi0 + range_in) - theta0, input_range);
            stages.push(Stage {
                label: label.clone(),
                phi0,
                theta0,
                run,
            });
        }
        Some(PointerRun {
            pointer: pointer.to_string(),
            ratio,
            input_range,
            stages,
            pin_slot,
            rule: self.rule.clone(),
        })
    }
}

/// How a mesh of a train with the pin-and-slot sees its driver and hands on its driven angle.
#[derive(Debug, Clone, Copy)]
enum Frame<'a> {
    /// Fixed frame in and out (every mesh without the pin-and-slot).
    Fixed,
    /// The pin mesh: its driver seen from the turntable; the pin gear rides on it.
    Pin(&'a PinSlotTrain),
    /// The slot gear's mesh: driven by the pin-and-slot, its driven gear carried back to the
    /// fixed frame by the turntable.
    Slot(&'a PinSlotTrain),
}

impl<'a> Frame<'a> {
    fn of(pin_slot: Option<&'a PinSlotTrain>, stage: usize) -> Frame<'a> {
        match pin_slot {
            Some(p) if stage == p.pin_stage => Frame::Pin(p),
            Some(p) if stage == p.pin_stage + 1 => Frame::Slot(p),
            _ => Frame::Fixed,
        }
    }

    /// The stage's driver angle, from the previous stage's handed-on angle `x`, at input `psi`.
    fn into(self, x: f64, psi: f64) -> f64 {
        match self {
            Frame::Fixed => x,
            Frame::Pin(p) => p.into_turntable(x, psi),
            Frame::Slot(p) => p.slot_change(x),
        }
    }

    /// The angle handed on to the next stage, from this stage's driven angle `x`.
    fn out(self, x: f64, psi: f64) -> f64 {
        match self {
            Frame::Slot(p) => p.out_of_turntable(x, psi),
            Frame::Fixed | Frame::Pin(_) => x,
        }
    }

    /// The most the stage's driver turns over an input run of `end`, from the most the previous
    /// stage hands on, `x`. In the fixed frame that is `x` itself (each stage's angle never
    /// decreases); seen from the turntable the driver's angle is not monotone (a driver held
    /// still by tooth play turns back against the turntable, and a train stopped by a jam
    /// upstream stops while the turntable goes on), so the bound takes the turntable at the
    /// moment that gives the most. A stage run this far may reach a jam its driver never
    /// reaches; [`PointerRun::first_stop`] leaves such jams out.
    fn into_range(self, x: f64, end: f64) -> f64 {
        match self {
            Frame::Fixed => x,
            Frame::Pin(p) => x + (-p.turntable_angle(end)).max(0.0),
            Frame::Slot(p) => p.slot_change(x),
        }
    }

    /// The most the stage hands on over an input run of `end`, from the most its driven gear
    /// turns, `x` (see [`Frame::into_range`]).
    fn out_range(self, x: f64, end: f64) -> f64 {
        match self {
            Frame::Slot(p) => x + p.turntable_angle(end).max(0.0),
            Frame::Fixed | Frame::Pin(_) => x,
        }
    }
}

/// Which contact model a run uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Model {
    /// Exact push-model contact of triangular teeth (`contact`).
    Triangular,
    /// Edmunds' radial-line model (`edmunds`): no tooth shape, no jams.
    Edmunds,
}

/// Steps per input turn in which [`PointerRun::first_stop`] looks for the first moment a driver
/// on the pin-and-slot's turntable reaches a jam (4096: about a sixth of a tooth of e5, which
/// turns 668 teeth per turn of b, per step).
pub const REACH_GRID: usize = 4096;

/// One mesh as run under one model.
#[derive(Debug, Clone)]
pub enum StageRun {
    /// Triangular teeth: the exact trajectory, with its events.
    Triangular(Box<Trajectory>),
    /// Edmunds' radial lines.
    Radial(RadialPair),
}

impl StageRun {
    /// Driven angle at driver angle φ.
    pub fn theta_at(&self, phi: f64) -> f64 {
        match self {
            StageRun::Triangular(t) => t.theta_at(phi),
            StageRun::Radial(r) => r.theta(phi),
        }
    }

    /// The trajectory, for triangular teeth.
    pub fn trajectory(&self) -> Option<&Trajectory> {
        match self {
            StageRun::Triangular(t) => Some(t),
            StageRun::Radial(_) => None,
        }
    }
}

/// One mesh of a pointer's train, as run.
#[derive(Debug, Clone)]
pub struct Stage {
    /// Mesh label.
    pub label: String,
    /// Initial driver angle (radians, within the driver's pitch).
    pub phi0: f64,
    /// Driven angle at the start.
    pub theta0: f64,
    /// The run of this mesh.
    pub run: StageRun,
}

/// The first jam on a pointer's train.
#[derive(Debug, Clone, PartialEq)]
pub struct Stop {
    /// Label of the mesh that jammed.
    pub mesh: String,
    /// Input-arbor angle at the jam (radians from the start).
    pub input_angle: f64,
    /// The same in days of the b arbor (one turn = 365.25 d).
    pub day: f64,
}

/// A pointer's train after one trial.
#[derive(Debug, Clone)]
pub struct PointerRun {
    /// Pointer name.
    pub pointer: String,
    /// Exact pointer ratio as a float (turns of the pointer per input turn).
    pub ratio: f64,
    /// Input rotation simulated (radians).
    pub input_range: f64,
    /// The meshes in chain order.
    pub stages: Vec<Stage>,
    /// The pin-and-slot in this train, if the run includes it (see
    /// [`Mechanism::with_pin_and_slot`]); `None`: every mesh turns in the fixed frame.
    pub pin_slot: Option<PinSlotTrain>,
    /// The event rule deciding which events are jams ([`PointerRun::first_stop`]).
    pub rule: Rule,
}

impl PointerRun {
    /// Rotation of the output arbor after the input arbor has turned `psi` (radians), through the
    /// first `upto` meshes. With the pin-and-slot, the pin gear's arbor (after the pin mesh) is
    /// measured relative to the turntable it rides on.
    pub fn arbor_angle(&self, psi: f64, upto: usize) -> f64 {
        let mut x = psi;
        for (i, s) in self.stages[..upto].iter().enumerate() {
            let frame = Frame::of(self.pin_slot.as_ref(), i);
            x = frame.into(x, psi);
            x = s.run.theta_at(s.phi0 + x) - s.theta0;
            x = frame.out(x, psi);
        }
        x
    }

    /// Rotation of mesh `stage`'s driver from its start, in the frame the mesh turns in (the
    /// turntable's for the pin-and-slot's two meshes, where the slot gear turns as the pin
    /// drives it), after the input has turned `psi`: the angle its trajectory is run at.
    pub fn driver_angle(&self, psi: f64, stage: usize) -> f64 {
        Frame::of(self.pin_slot.as_ref(), stage).into(self.arbor_angle(psi, stage), psi)
    }

    /// The pointer's ideal rotation (radians) after the input has turned `psi`: `ratio * psi`,
    /// or with the pin-and-slot the anomaly-bearing motion of perfect gears
    /// ([`PinSlotTrain::ideal_pointer_angle`]).
    pub fn ideal_angle(&self, psi: f64) -> f64 {
        match &self.pin_slot {
            Some(p) => p.ideal_pointer_angle(psi),
            None => self.ratio * psi,
        }
    }

    /// Pointer rotation (radians) after the input has turned `psi`.
    pub fn pointer_angle(&self, psi: f64) -> f64 {
        self.arbor_angle(psi, self.stages.len())
    }

    /// Theoretical Difference (radians): pointer rotation minus its ideal rotation
    /// ([`PointerRun::ideal_angle`]: ratio × input rotation, or with the pin-and-slot the
    /// anomaly-bearing ideal motion).
    pub fn theoretical_difference(&self, psi: f64) -> f64 {
        self.pointer_angle(psi) - self.ideal_angle(psi)
    }

    /// The first jam anywhere on the train, mapped back to the input arbor, if any.
    pub fn first_stop(&self) -> Option<Stop> {
        let mut best: Option<Stop> = None;
        for (i, s) in self.stages.iter().enumerate() {
            let jam = s
                .run
                .trajectory()
                .and_then(|t| self.rule.first_jam(t.events()));
            let Some(e) = jam else {
                continue;
            };
            // Input angle at which this mesh's driver arbor reached the jam: the upstream
            // composition is non-decreasing, so bisect.
            let target = e.phi - s.phi0;
            let Some(hi) = self.first_reach(i, target) else {
                continue;
            };
            if best.as_ref().is_none_or(|b| hi < b.input_angle) {
                best = Some(Stop {
                    mesh: s.label.clone(),
                    input_angle: hi,
                    day: hi / TAU * stats::DAYS_PER_YEAR,
                });
            }
        }
        best
    }

    /// The first input angle at which mesh `stage`'s driver reaches `target` in its own frame,
    /// or `None` if it never does.
    ///
    /// Without the pin-and-slot every driver angle is non-decreasing and the stage was run just
    /// as far as its driver turns, so bisecting the whole run finds it. With it, a driver seen
    /// from the turntable can turn back (held by tooth play, or stopped by a jam upstream while
    /// the turntable goes on) and its mesh was run over a bound on its travel: the first grid
    /// point ([`REACH_GRID`] steps per input turn) at or past `target` is found, then bisected
    /// from the point before; a jam no grid point reaches never happens.
    fn first_reach(&self, stage: usize, target: f64) -> Option<f64> {
        let (mut lo, mut hi) = (0.0, self.input_range);
        if self.pin_slot.is_some() {
            let steps = ((self.input_range / TAU * REACH_GRID as f64).ceil() as usize).max(1);
            let step = self.input_range / steps as f64;
            let k = (0..=steps).find(|&k| self.driver_angle(step * k as f64, stage) >= target)?;
            (lo, hi) = (step * k.saturating_sub(1) as f64, step * k as f64);
        }
        for _ in 0..100 {
            let mid = 0.5 * (lo + hi);
            if self.driver_angle(mid, stage) < target {
                lo = mid
            } else {
                hi = mid
            }
        }
        Some(hi)
    }

    /// Number of disengagements on every mesh of the train.
    pub fn disengagements(&self) -> usize {
        self.stages
            .iter()
            .filter_map(|s| s.run.trajectory())
            .map(Trajectory::disengagements)
            .sum()
    }

    /// σ, Dm and mean P of the Theoretical Difference (degrees) over `samples` input angles spread
    /// evenly over the run, up to the first jam.
    pub fn stats(&self, samples: usize) -> stats::PointerStats {
        let end = self
            .first_stop()
            .map_or(self.input_range, |s| s.input_angle);
        self.stats_until(samples, end)
    }

    /// The same over the whole run, through any jam: as the paper's program did, a jammed driven
    /// gear is released to its next free position and the run goes on.
    pub fn stats_through_jams(&self, samples: usize) -> stats::PointerStats {
        self.stats_until(samples, self.input_range)
    }

    fn stats_until(&self, samples: usize, end: f64) -> stats::PointerStats {
        let n = samples.max(2);
        let acc: stats::Accumulator = (0..n)
            .map(|i| {
                self.theoretical_difference(end * i as f64 / (n - 1) as f64)
                    .to_degrees()
            })
            .collect();
        acc.stats()
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    /// A generator for these tests. The studies draw from `registry::Streams`, the one scheme
    /// of every trial; a mechanism only takes the generator it is handed.
    fn trial_rng(seed: u64, trial: u64) -> ChaCha8Rng {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(trial);
        rng
    }

    #[test]
    fn ideal_pointer_follows_its_exact_ratio_after_whole_turns() {
        let g = Gearing::freeth2006();
        let m = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        let mut rng = trial_rng(7, 0);
        let run = m.run_pointer("Metonic", 3.8, &mut rng).unwrap();
        assert!(run.first_stop().is_none());
        // After 19 turns of b, every gear of the Metonic train is back at a whole number of teeth
        // (5 turns of n): the pointer equals the ratio exactly.
        let run19 = m
            .run_pointer("Metonic", 19.0, &mut trial_rng(7, 1))
            .unwrap();
        let td = run19.theoretical_difference(19.0 * TAU) - run19.theoretical_difference(0.0);
        assert!(td.to_degrees().abs() < 1e-9, "{}", td.to_degrees());
        let s = run.stats(2000);
        assert!(s.sigma > 0.0 && s.sigma < 1.0, "{s:?}");
    }

    #[test]
    fn a_jam_stops_the_train_and_is_dated_in_days() {
        let g = Gearing::freeth2006();
        // At 6 % clearance c2-d1 (24-tooth d1) pinches: the Lunar train jams within the year.
        let m = Mechanism::ideal(&g, 1.1, 6.0).unwrap();
        let run = m.run_pointer("Lunar", 1.0, &mut trial_rng(3, 0)).unwrap();
        let stop = run.first_stop().unwrap();
        assert!(
            g.pointer("Lunar").unwrap().meshes.contains(&stop.mesh),
            "{stop:?}"
        );
        assert!(stop.day >= 0.0 && stop.day <= 365.25, "{stop:?}");
        // The jammed mesh's driver arbor had reached the jam angle at that day, not before.
        let i = run
            .stages
            .iter()
            .position(|s| s.label == stop.mesh)
            .unwrap();
        let jam = run.stages[i]
            .run
            .trajectory()
            .unwrap()
            .events()
            .iter()
            .find(|e| e.kind.is_contact_stop())
            .unwrap();
        let reached = run.arbor_angle(stop.input_angle, i);
        assert!(
            (reached - (jam.phi - run.stages[i].phi0)).abs() < 1e-9,
            "{reached} vs {}",
            jam.phi
        );
    }

    #[test]
    fn both_models_agree_for_ideal_gears_after_whole_teeth() {
        let g = Gearing::freeth2006();
        let m = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        let tri = m
            .run_pointer_with("Metonic", 19.0, &mut trial_rng(5, 0), Model::Triangular)
            .unwrap();
        let rad = m
            .run_pointer_with("Metonic", 19.0, &mut trial_rng(5, 0), Model::Edmunds)
            .unwrap();
        // Same initial angles from the same stream.
        let phis = |r: &PointerRun| {
            r.stages
                .iter()
                .map(|s| s.phi0.to_bits())
                .collect::<Vec<_>>()
        };
        assert_eq!(phis(&tri), phis(&rad));
        // Ideal radial lines follow the ratio exactly everywhere.
        for i in 0..50 {
            let psi = 19.0 * TAU * f64::from(i) / 49.0;
            assert!(rad.theoretical_difference(psi).to_degrees().abs() < 1e-9);
        }
        let td = tri.theoretical_difference(19.0 * TAU) - tri.theoretical_difference(0.0);
        assert!(td.to_degrees().abs() < 1e-9);
    }

    /// Largest |TD| (degrees) of `run` over `n` samples.
    fn max_td(run: &PointerRun, n: usize) -> f64 {
        (0..=n)
            .map(|i| {
                let psi = run.input_range * i as f64 / n as f64;
                run.theoretical_difference(psi).to_degrees().abs()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn pin_and_slot_left_out_is_the_rigid_train_bit_for_bit() {
        let g = Gearing::freeth2006();
        let m = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        let off = m.clone().with_pin_and_slot(false).unwrap();
        assert!(!off.has_pin_and_slot() && off.pin_slot_for("Lunar").is_none());
        let a = m.run_pointer("Lunar", 0.5, &mut trial_rng(9, 0)).unwrap();
        let b = off.run_pointer("Lunar", 0.5, &mut trial_rng(9, 0)).unwrap();
        assert!(a.pin_slot.is_none() && b.pin_slot.is_none());
        for i in 0..200 {
            let psi = a.input_range * f64::from(i) / 199.0;
            assert_eq!(
                a.theoretical_difference(psi).to_bits(),
                b.theoretical_difference(psi).to_bits()
            );
        }
        // A pointer that does not run through it is unchanged even with it in.
        let on = m.clone().with_pin_and_slot(true).unwrap();
        let c = m.run_pointer("Saros", 0.5, &mut trial_rng(9, 1)).unwrap();
        let d = on.run_pointer("Saros", 0.5, &mut trial_rng(9, 1)).unwrap();
        assert!(d.pin_slot.is_none());
        assert_eq!(
            c.theoretical_difference(2.0).to_bits(),
            d.theoretical_difference(2.0).to_bits()
        );
    }

    #[test]
    fn a_gearing_without_the_section_refuses_the_pin_and_slot() {
        let text = train::FREETH2006_RON;
        let cut = text.find("    pin_and_slot:").unwrap();
        let g = Gearing::from_ron("cut.ron", &format!("{})", &text[..cut])).unwrap();
        assert!(g.pin_and_slot().is_none());
        let m = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        let e = m.clone().with_pin_and_slot(true).unwrap_err();
        assert!(e.rule.contains("no pin_and_slot section"), "{e}");
        assert!(m.with_pin_and_slot(false).is_ok());
    }

    #[test]
    fn ideal_gears_with_the_pin_and_slot_follow_the_anomaly_bearing_ideal() {
        let g = Gearing::freeth2006();
        let rigid = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        let on = rigid.clone().with_pin_and_slot(true).unwrap();
        for trial in 0..4 {
            let r = rigid
                .run_pointer("Lunar", 1.0, &mut trial_rng(11, trial))
                .unwrap();
            let p = on
                .run_pointer("Lunar", 1.0, &mut trial_rng(11, trial))
                .unwrap();
            let ps = p.pin_slot.as_ref().unwrap();
            assert!(r.first_stop().is_none() && p.first_stop().is_none());
            // The pointer shows the anomaly (about 6.6 degrees) ...
            let shown = (0..=2000)
                .map(|i| {
                    let psi = p.input_range * f64::from(i) / 2000.0;
                    (p.pointer_angle(psi) - p.ratio * psi).to_degrees().abs()
                })
                .fold(0.0, f64::max);
            assert!(shown > 6.0, "{shown}");
            // ... and against the anomaly-bearing ideal only the tooth play is left: within the
            // rigid train's TD (a wrong turntable sign would drift by 2 x 0.11 turns a year, a
            // wrong anomaly phase by up to 13 degrees).
            let (td_rigid, td_pin) = (max_td(&r, 4000), max_td(&p, 4000));
            assert!(td_rigid > 0.1 && td_rigid < 6.0, "{td_rigid}");
            assert!(td_pin < 1.5 * td_rigid + 0.2, "{td_pin} vs {td_rigid}");
            // The meshes on the turntable ran in its frame: e5 relative to e3 and the slot's k2.
            let i = ps.pin_stage;
            let end = p.input_range;
            assert!(
                (p.driver_angle(end, i) - (p.arbor_angle(end, i) - ps.turntable_angle(end))).abs()
                    < 1e-12
            );
            assert!(
                (p.driver_angle(end, i + 1) - ps.slot_change(p.arbor_angle(end, i + 1))).abs()
                    < 1e-12
            );
        }
    }

    #[test]
    fn a_jam_with_the_pin_and_slot_is_dated_where_its_driver_reached_it() {
        let g = Gearing::freeth2006();
        // Edmunds' Case D (systematic 2 deg, random 0.08 of the pitch): jams everywhere.
        let hyp = hypotheses::lookup("edmunds-split").unwrap();
        let params = hypotheses::Params::new(
            hyp,
            &[
                ("systematic".into(), "2".into()),
                ("random".into(), "0.08".into()),
                ("split".into(), "0.5".into()),
            ],
        )
        .unwrap();
        let mut on_turntable = 0;
        for trial in 0..6 {
            let mut rng = trial_rng(3, trial);
            let m = Mechanism::build(&g, 1.1, 40.0, |name, ideal| {
                hyp.apply(&ideal, name, &params, &mut rng)
                    .map_err(|e| e.to_string())
            })
            .unwrap()
            .with_pin_and_slot(true)
            .unwrap();
            let run = m.run_pointer("Lunar", 1.0, &mut rng).unwrap();
            let Some(stop) = run.first_stop() else {
                continue;
            };
            let i = run
                .stages
                .iter()
                .position(|s| s.label == stop.mesh)
                .unwrap();
            let jam = run.stages[i]
                .run
                .trajectory()
                .unwrap()
                .events()
                .iter()
                .find(|e| e.kind.is_contact_stop())
                .unwrap();
            // The bisection brackets the moment the driver (in its own frame) reached the jam.
            let target = jam.phi - run.stages[i].phi0;
            let before = run.driver_angle(stop.input_angle - 1e-9, i);
            let after = run.driver_angle(stop.input_angle, i);
            assert!(
                before < target + 1e-9 && after > target - 1e-9,
                "{}: {before} .. {after} vs {target}",
                stop.mesh
            );
            // The turntable's two meshes were run over a bound on their drivers' travel: count
            // their jams, reached or not.
            for (k, s) in run.stages.iter().enumerate() {
                let jammed = s
                    .run
                    .trajectory()
                    .is_some_and(|t| t.events().iter().any(|e| e.kind.is_contact_stop()));
                on_turntable += usize::from(jammed && (k == 3 || k == 4));
            }
        }
        assert!(on_turntable > 0, "no jam on the turntable's meshes");
    }

    #[test]
    fn run_pointer_from_uses_the_given_angles() {
        let g = Gearing::freeth2006();
        let m = Mechanism::ideal(&g, 1.1, 40.0)
            .unwrap()
            .with_pin_and_slot(true)
            .unwrap();
        let drawn = m
            .run_pointer_to_first_jam("Lunar", 0.3, &mut trial_rng(4, 0))
            .unwrap();
        let phis: BTreeMap<String, f64> = drawn
            .stages
            .iter()
            .map(|s| (s.label.clone(), s.phi0))
            .collect();
        let given = m
            .run_pointer_from("Lunar", 0.3, |l| phis.get(l).copied())
            .unwrap();
        assert_eq!(
            drawn.theoretical_difference(1.0).to_bits(),
            given.theoretical_difference(1.0).to_bits()
        );
        assert!(m.run_pointer_from("Lunar", 0.3, |_| None).is_none());
    }

    #[test]
    fn per_mesh_clearances_move_only_their_own_centre_distances() {
        let g = Gearing::freeth2006();
        let uniform = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        // The same clearance everywhere through the per-mesh builder: the same mechanism.
        let same = Mechanism::build_with_clearances(&g, 1.1, |_| 40.0, |_, gear| Ok(gear)).unwrap();
        // One mesh at 30 %, the others at 40 %.
        let one = Mechanism::build_with_clearances(
            &g,
            1.1,
            |label| if label == "b2-c1" { 30.0 } else { 40.0 },
            |_, gear| Ok(gear),
        )
        .unwrap();
        let at30 = Mechanism::ideal(&g, 1.1, 30.0).unwrap();
        let d = |m: &Mechanism, label: &str| m.mesh(label).unwrap().centre_distance();
        for m in g.meshes() {
            let l = m.label.as_str();
            assert_eq!(d(&same, l).to_bits(), d(&uniform, l).to_bits(), "{l}");
            let want = if l == "b2-c1" { &at30 } else { &uniform };
            assert_eq!(d(&one, l).to_bits(), d(want, l).to_bits(), "{l}");
        }
        assert!(d(&one, "b2-c1") < d(&uniform, "b2-c1"));
    }

    #[test]
    fn trial_streams_depend_only_on_seed_and_index() {
        let a: f64 = trial_rng(1, 5).random();
        let b: f64 = trial_rng(1, 5).random();
        let c: f64 = trial_rng(1, 6).random();
        assert_eq!(a.to_bits(), b.to_bits());
        assert_ne!(a.to_bits(), c.to_bits());
    }
}
