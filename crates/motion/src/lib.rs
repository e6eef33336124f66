//! Motion models as plugins: how the driven gear of one mesh moves between and at its contacts (pushed, carried at the nominal ratio, stepped the paper's way).
//!
//! The contact solver (`contact`) gives the exact geometry of a mesh: at a driver angle φ, the
//! interval of driven angles `[lo, hi]` at which driver tooth j overlaps driven tooth k
//! ([`Mesh::obstacle`]). *How the driven gear moves* between and at its contacts is a separate
//! assumption, and the paper's words admit more than one reading: pushed by the driver's front
//! flanks and at rest between pushes (the exact solver's push model, [`Mesh::solve`]), carried at
//! the nominal ratio N1/N2 and stopped by whichever flank it meets, or turned after each driver
//! step by a program that detects overlapping areas. Each reading is a plugin: one file in
//! `src/plugins/`, registered with `inventory` by `model!`, listed by [`listing`], looked up
//! by name with [`Model::parse`]. A model turns one [`Trial`] (a mesh, the driver's start and
//! turn, optionally the driven gear's own drawn angle) into an [`Outcome`]: the run's events in
//! the solver's terms ([`contact::Event`], so that every event rule counts them) and, when
//! asked, its path θ(φ) ([`Path`]).

use std::collections::BTreeMap;
use std::fmt::Write as _;

pub use contact::{Answered, Event, EventKind, Mesh, Start, Trajectory};
pub use inventory;

pub mod carry;
mod log;
mod path;
/// Every file in `src/plugins/`, declared by `build.rs`: a new model is one file there.
mod plugins {
    include!(concat!(env!("OUT_DIR"), "/plugins.rs"));
}
mod register;
pub mod stepped;

pub use path::{Path, Piece, Rule};

pub(crate) use register::model;

/// The model of every table unless asked otherwise: the exact solver's push model.
pub const DEFAULT: &str = "push";

/// One trial of one mesh: what every model runs.
#[derive(Debug, Clone, Copy)]
pub struct Trial<'m> {
    /// The two gears at their centre distance (the driver as listed).
    pub mesh: &'m Mesh,
    /// The driver's initial angle φ0 (radians).
    pub phi0: f64,
    /// How far the driver turns (radians).
    pub turn: f64,
    /// The driven gear's own drawn initial angle (radians), for a model that places the driven
    /// gear there instead of touching the driver; `None` where the caller fixes the start
    /// touching (Figure 2's θ'o = θ'(0), and every model that ignores it).
    pub drawn: Option<f64>,
    /// Tooth height h (mm): how deep under its valleys the stepped program tiles a gear's body.
    pub tooth_height: f64,
}

impl Trial<'_> {
    /// The ratio N1/N2 (driver teeth over driven teeth).
    pub fn ratio(&self) -> f64 {
        self.mesh.driver().teeth() as f64 / self.mesh.driven().teeth() as f64
    }

    /// The driver's pitch (radians).
    pub fn driver_pitch(&self) -> f64 {
        std::f64::consts::TAU / self.mesh.driver().teeth() as f64
    }

    /// The last driver angle of the trial.
    pub fn phi_end(&self) -> f64 {
        self.phi0 + self.turn
    }
}

/// What a caller wants of a run.
#[derive(Clone, Copy)]
pub enum Want<'a> {
    /// The events and the path θ(φ) of the whole run.
    Path,
    /// The events only; the run may end once `answered` holds for the events so far (asked
    /// where every event is sized), as more events cannot change the caller's answer.
    Events(&'a Answered<'a>),
}

/// What a model gives for one trial.
#[derive(Debug, Clone)]
pub struct Outcome {
    /// The run's jams and losses of drive, in the solver's terms.
    pub events: Vec<Event>,
    /// The driven angle along the run, where [`Want::Path`] asked for it.
    pub path: Option<Path>,
}

/// A motion model: how the driven gear of one mesh moves between and at its contacts.
pub trait MotionModel: Sync {
    /// Unique name, e.g. `carried`.
    fn name(&self) -> &'static str;
    /// One line telling what the driven gear does.
    fn summary(&self) -> &'static str;
    /// The model in a few sentences: its definition from the contact, and why it is a reading
    /// of the paper.
    fn details(&self) -> &'static str;
    /// Runs one trial.
    fn run(&self, trial: &Trial<'_>, want: Want<'_>) -> Outcome;
}

/// The `inventory` item a model registers itself with; a plugin file writes it by `model!`.
pub struct Registration(pub &'static dyn MotionModel);

inventory::collect!(Registration);

/// Why a model could not be looked up.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{what}: {rule}")]
pub struct ModelError {
    /// The offending item.
    pub what: String,
    /// The rule it broke.
    pub rule: String,
}

/// Every registered model, sorted by name; a name registered twice is an error naming it.
pub fn models() -> Result<BTreeMap<&'static str, &'static dyn MotionModel>, ModelError> {
    let mut map = BTreeMap::new();
    for r in inventory::iter::<Registration> {
        if map.insert(r.0.name(), r.0).is_some() {
            return Err(ModelError {
                what: format!("motion model `{}`", r.0.name()),
                rule: "is registered twice".into(),
            });
        }
    }
    Ok(map)
}

/// A registered model, looked up by name.
#[derive(Clone, Copy)]
pub struct Model(&'static dyn MotionModel);

impl std::fmt::Debug for Model {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.0.name())
    }
}

impl PartialEq for Model {
    fn eq(&self, other: &Self) -> bool {
        self.0.name() == other.0.name()
    }
}

impl Model {
    /// The model named `name`; an unknown name lists the known ones.
    pub fn parse(name: &str) -> Result<Model, ModelError> {
        let all = models()?;
        all.get(name.trim()).map(|m| Model(*m)).ok_or_else(|| {
            let known: Vec<&str> = all.keys().copied().collect();
            ModelError {
                what: format!("motion model `{}`", name.escape_debug()),
                rule: format!("unknown; known models: {}", known.join(", ")),
            }
        })
    }

    /// Every registered model, in name order.
    pub fn all() -> Result<Vec<Model>, ModelError> {
        Ok(models()?.into_values().map(Model).collect())
    }

    /// The model's name.
    pub fn name(&self) -> &'static str {
        self.0.name()
    }

    /// The model's definition.
    pub fn definition(&self) -> &'static dyn MotionModel {
        self.0
    }

    /// Runs one trial under the model.
    pub fn run(&self, trial: &Trial<'_>, want: Want<'_>) -> Outcome {
        self.0.run(trial, want)
    }
}

impl Default for Model {
    /// The [`DEFAULT`] model.
    fn default() -> Self {
        #[allow(
            clippy::expect_used,
            reason = "the default model is a built-in plugin, tested"
        )]
        Model::parse(DEFAULT).expect("the default motion model is registered")
    }
}

/// A readable list of every registered model: name and summary, the default marked.
pub fn listing() -> String {
    let all = match models() {
        Ok(all) => all,
        Err(e) => return format!("error: {e}\n"),
    };
    let mut s = format!("Motion models (default {DEFAULT})\n\n");
    let w = all.keys().map(|k| k.len()).max().unwrap_or(0);
    for m in all.values() {
        let _ = writeln!(s, "{:w$}  {}", m.name(), m.summary());
    }
    s
}

/// Does nothing; calling it makes a binary link this crate, and with it every model it
/// registers.
pub fn link() {}
