//! Whole-train simulation: a pointer's meshes composed in order, each with its own random initial angle.
//!
//! The push model is quasi-static: a mesh's driven angle depends only on its driver angle, not on
//! how fast it turns. So a train is simulated mesh by mesh: the first mesh's driver turns with the
//! input (b) arbor; each mesh's driven gear turns its arbor, and that arbor's rotation is the next
//! mesh's driver rotation. Every mesh starts at a uniformly random driver angle within its driver's
//! pitch (the paper: the maker could not set it), with the driven gear touching.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use contact::{EventKind, Mesh, Start, Trajectory};
use edmunds::RadialPair;
use geometry::Gear;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use train::Gearing;

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
}

/// The RNG stream of one trial: depends only on (seed, trial index), never on threads.
pub fn trial_rng(seed: u64, trial: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(trial);
    rng
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
            let radius = gearing
                .tip_radius(&g.name)
                .ok_or_else(|| bad("cannot be sized".into()))?;
            let ideal = Gear::ideal(g.teeth as usize, radius, radius - h)
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
        })
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
        let p = self.gearing.pointer(pointer)?;
        let ratio = self.gearing.pointer_ratio(pointer)?.to_f64();
        let mut stages = Vec::with_capacity(p.meshes.len());
        let mut range = input_turns * TAU;
        for label in &p.meshes {
            let mesh = self.meshes.get(label)?;
            let pitch = TAU / mesh.driver().teeth() as f64;
            let phi0 = rng.random::<f64>() * pitch;
            let run = match model {
                Model::Triangular => StageRun::Triangular(Box::new(mesh.run_until(
                    phi0,
                    phi0 + range,
                    Start::Touching(0.0),
                    stop_at_jam,
                ))),
                Model::Edmunds => {
                    StageRun::Radial(RadialPair::new(mesh.driver(), mesh.driven(), phi0))
                }
            };
            let theta0 = run.theta_at(phi0);
            range = run.theta_at(phi0 + range) - theta0;
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
            input_range: input_turns * TAU,
            stages,
        })
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
}

impl PointerRun {
    /// Rotation of the output arbor after the input arbor has turned `psi` (radians), through the
    /// first `upto` meshes.
    pub fn arbor_angle(&self, psi: f64, upto: usize) -> f64 {
        let mut x = psi;
        for s in &self.stages[..upto] {
            x = s.run.theta_at(s.phi0 + x) - s.theta0;
        }
        x
    }

    /// Pointer rotation (radians) after the input has turned `psi`.
    pub fn pointer_angle(&self, psi: f64) -> f64 {
        self.arbor_angle(psi, self.stages.len())
    }

    /// Theoretical Difference (radians): pointer rotation minus ratio × input rotation.
    pub fn theoretical_difference(&self, psi: f64) -> f64 {
        self.pointer_angle(psi) - self.ratio * psi
    }

    /// The first jam anywhere on the train, mapped back to the input arbor, if any.
    pub fn first_stop(&self) -> Option<Stop> {
        let mut best: Option<Stop> = None;
        for (i, s) in self.stages.iter().enumerate() {
            let jam = s
                .run
                .trajectory()
                .and_then(|t| t.events().iter().find(|e| e.kind == EventKind::Jam));
            let Some(e) = jam else {
                continue;
            };
            // Input angle at which this mesh's driver arbor reached the jam: the upstream
            // composition is non-decreasing, so bisect.
            let target = e.phi - s.phi0;
            let (mut lo, mut hi) = (0.0, self.input_range);
            for _ in 0..100 {
                let mid = 0.5 * (lo + hi);
                if self.arbor_angle(mid, i) < target {
                    lo = mid
                } else {
                    hi = mid
                }
            }
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
            .find(|e| e.kind == EventKind::Jam)
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
