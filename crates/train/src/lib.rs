//! The Antikythera Mechanism's gearing (Freeth 2006) as data: gears, arbors, meshes, pointers, exact ratios and radii.
//!
//! The default gearing is embedded from `data/freeth2006.ron` ([`FREETH2006_RON`]); a user file
//! in the same format replaces it through [`Gearing::from_ron`] or [`Gearing::load`]. Every
//! gearing is validated when it is read, so the queries on a [`Gearing`] never fail on
//! inconsistent data.
//!
//! Beyond the paper, a gearing may carry a cosmos display (`data/freeth2021-cosmos.ron`,
//! `data/freeth2012-cosmos.ron`): gears fixed to the frame and arbors carried round by b1
//! ([`Epicyclic`]), where every mesh runs as an ordinary pair in b1's frame and rates compose
//! exactly with signs ([`Rate`], [`Gearing::pointer_rate`]); the pin-and-slot devices of the
//! planets ([`PinDevice`]); the Moon phase's differential ([`Differential`]); and gears sized by
//! Freeth & Jones' rule from a pitch radius ([`Sizing::Pitch`]).
//!
//! Conventions (the paper's section 3): every angle is positive in its own gear's direction of
//! rotation, so all ratios are positive; one turn of the input arbor `b` is one year of 365.25
//! days; in every mesh the tip radii keep `R1/R2 = N1/N2` exactly (see [`Gearing::tip_radii`]
//! for the least-squares rule that sizes them).

mod ratio;
mod validate;

use std::collections::{BTreeMap, BTreeSet};
use std::fmt;
use std::path::Path;

use serde::{Deserialize, Serialize};
use stdx::{fmt_number, one_line};

pub use ratio::{Rate, Ratio};

/// The text of the embedded default gearing, `data/freeth2006.ron`.
pub const FREETH2006_RON: &str = include_str!("../data/freeth2006.ron");

/// The same gearing with the outer radii of Freeth et al. 2021 (Table S8), `data/freeth2021.ron`:
/// for asking how much the results depend on the radii the paper took.
pub const FREETH2021_RON: &str = include_str!("../data/freeth2021.ron");

/// The Freeth 2006 gearing with the cosmos display of Freeth et al. 2021 (Sci. Rep. 11:5821) in
/// front of b1, `data/freeth2021-cosmos.ron`: its planetary trains from secondary transcriptions,
/// the hypothetical gears sized by Freeth & Jones' rule.
pub const FREETH2021_COSMOS_RON: &str = include_str!("../data/freeth2021-cosmos.ron");

/// The Freeth 2006 gearing with the cosmos display of Freeth & Jones 2012 (ISAW Papers 4) in
/// front of b1, `data/freeth2012-cosmos.ron`: tooth counts, radii and pins from its Figs. 42-43.
pub const FREETH2012_COSMOS_RON: &str = include_str!("../data/freeth2012-cosmos.ron");

/// The embedded gearings by name, for `--set gearing=NAME`: (name, file name, text).
pub const BUILTIN: [(&str, &str, &str); 4] = [
    ("freeth2006", "freeth2006.ron", FREETH2006_RON),
    ("freeth2021", "freeth2021.ron", FREETH2021_RON),
    (
        "freeth2021-cosmos",
        "freeth2021-cosmos.ron",
        FREETH2021_COSMOS_RON,
    ),
    (
        "freeth2012-cosmos",
        "freeth2012-cosmos.ron",
        FREETH2012_COSMOS_RON,
    ),
];

/// The most teeth a gear of a gearing file may have: 10^5, the limit of `geometry::MAX_TEETH`
/// (the mechanism's largest gear has 223).
pub const MAX_TEETH: u32 = 100_000;

/// The largest size in a gearing file: 10 m (10 000 mm) for a measured radius, a pin radius or
/// an axis offset. The mechanism's largest gear is about 65 mm; a larger size is no part of one.
pub const MAX_SIZE_MM: f64 = 10_000.0;

/// Days in one turn of the input arbor `b` (one year).
pub const DAYS_PER_TURN: f64 = 365.25;

/// One gear: tooth count, measured radius and where both come from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearData {
    /// The gear's name (Freeth 2006), e.g. `b2`.
    pub name: String,
    /// Number of teeth.
    pub teeth: u32,
    /// Measured radius in mm (Freeth 2006: mean of the best-fit inner and outer radius of the
    /// fragment); `None` for a lost gear, which is sized from its mesh partners.
    pub measured_radius: Option<f64>,
    /// Provenance of the tooth count and radius.
    pub source: String,
    /// What the radius given stands for, and so how the gear is sized ([`Sizing`]; the default,
    /// [`Sizing::Fitted`], is the paper's).
    #[serde(default, skip_serializing_if = "Sizing::is_fitted")]
    pub sizing: Sizing,
    /// A pitch radius in mm that a reconstruction designed rather than measured (a hypothetical
    /// gear sized by a rule: `source` says which); only with [`Sizing::Pitch`], never beside
    /// `measured_radius`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub design_radius: Option<f64>,
}

/// How a gear's radius becomes its tip and root radii. Every gear of a group of meshed gears
/// (a [`Component`]) is sized the same way.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub enum Sizing {
    /// The paper's rule: the radius given (Freeth 2006's mean of the fragment's inner and outer
    /// radius) is fitted as the tip radius `R`, the root radius is `R - h`.
    #[default]
    Fitted,
    /// Freeth & Jones' rule (ISAW Papers 4, Figs. 42-43): the radius given is the pitch radius
    /// `p` (the mean of tip and root), so `R = p + h/2` and the root radius is `p - h/2`; a
    /// mesh's centre distance `p1 + p2 + margin` is then `R1 + R2 - h + margin`, the paper's
    /// `D` with `G = margin`.
    Pitch,
}

impl Sizing {
    /// Whether this is the paper's rule (left out when a gearing is written).
    #[must_use]
    pub fn is_fitted(&self) -> bool {
        *self == Sizing::Fitted
    }
}

/// Gears fixed together on one arbor: they turn as one body.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arbor {
    /// The arbor's name, e.g. `b`.
    pub name: String,
    /// Names of the gears fixed on it.
    pub gears: Vec<String>,
}

/// One external mesh between two gears.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MeshData {
    /// The label as the paper writes it, e.g. `b2-c1` (the paper's `n2-o1` has driver `n3`).
    pub label: String,
    /// Name of the driving gear.
    pub driver: String,
    /// Name of the driven gear.
    pub driven: String,
    /// The centre-distance margin (mm) a reconstruction states over the sum of the two pitch
    /// radii (Freeth & Jones: 0.2-0.4 mm, "since triangular-toothed gears cannot mesh too
    /// closely"); with [`Sizing::Pitch`] it is the clearance `G` in mm. Only recorded: the
    /// simulations take their clearance from their settings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub margin: Option<f64>,
}

/// A pointer: the train of meshes from the input arbor to the pointer's arbor.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Pointer {
    /// The pointer's name, e.g. `Lunar`.
    pub name: String,
    /// Name of the input arbor (`b`, the mean Sun).
    pub input: String,
    /// Mesh labels in order from the input arbor to the pointer.
    pub meshes: Vec<String>,
    /// Whether the paper converts this pointer's degrees to days.
    pub days: bool,
}

/// The pin-and-slot lunar anomaly mechanism (Freeth 2006), an optional section of a gearing file.
///
/// Two gears ride on a turntable on axes `axis_offset` mm apart: a pin on the pin gear,
/// `pin_radius` mm from its axis, engages a radial slot of the slot gear, so that the slot gear
/// turns at a varying rate while the pin gear turns evenly. In the file the two gears share one
/// arbor (the rigid coupling that stands in for the pin-and-slot when it is left out, as the
/// paper does); the simulation may replace that coupling by the pin-and-slot and turn the
/// turntable at its own rate (see `mechanism::Mechanism::with_pin_and_slot`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PinAndSlot {
    /// The gear carrying the pin (Freeth 2006: `k1`).
    pub pin_gear: String,
    /// The gear with the radial slot (Freeth 2006: `k2`).
    pub slot_gear: String,
    /// A gear of the turntable arbor both gears ride on (Freeth 2006: `e3`).
    pub turntable: String,
    /// Distance between the pin gear's and the slot gear's axes, mm.
    pub axis_offset: f64,
    /// Distance of the pin from the pin gear's axis, mm (greater than `axis_offset`).
    pub pin_radius: f64,
    /// Provenance of the geometry.
    pub source: String,
}

/// Arbors carried round by a turning wheel (the carrier, b1 in the cosmos) about gears fixed to
/// the frame: an epicyclic system, an optional section of a gearing file.
///
/// Seen from the carrier every arbor of the system turns on a fixed axis and the fixed arbor
/// turns once backwards per turn of the carrier, so each mesh of the system is an ordinary pair
/// in the carrier's frame, and a pointer whose input is the fixed arbor is run in that frame.
/// An arbor's rate in the frame of the mechanism is the carrier's plus its rate relative to the
/// carrier ([`Gearing::rate_from`]).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Epicyclic {
    /// The arbor that carries the system (the cosmos: `b`, whose b1 turns once a year).
    pub carrier: String,
    /// The arbor of the gears fixed to the frame (rate zero in the frame of the mechanism).
    pub fixed: String,
    /// The arbors whose meshes run in the carrier's frame: those it carries, and the output
    /// tubes on its axis that their gears drive. Each is turned from `fixed` by a chain of
    /// meshes.
    pub arbors: Vec<String>,
    /// Provenance of the arrangement.
    pub source: String,
}

/// What a pin-and-slot device of the cosmos drives.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum DeviceKind {
    /// The pin drives a slotted gear on an axis `axis_offset` from the pin gear's, both carried
    /// (the superior planets, as the lunar pin-and-slot): in the file the two gears share one
    /// arbor (the rigid coupling the device replaces) and the pointer's next mesh is driven by
    /// the slot gear. The offset is less than the pin radius, so the slot gear turns round.
    SlotGear,
    /// The pin drives a slotted follower on the carrier's axis, `axis_offset` from the pin
    /// gear's axis: the follower is the pointer (the inferior planets and the true Sun). The pin
    /// radius is less than the offset, so the follower swings either side of the carrier's
    /// direction (a planet's elongation from the mean Sun) by at most `asin(pin / offset)`.
    Follower,
}

/// A pin-and-slot device at the end (or in the train) of a cosmos pointer: its pin and offset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PinDevice {
    /// The pointer it belongs to.
    pub pointer: String,
    /// What it drives.
    pub kind: DeviceKind,
    /// The gear carrying the pin.
    pub pin_gear: String,
    /// The gear with the slot ([`DeviceKind::SlotGear`] only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slot_gear: Option<String>,
    /// Distance between the pin gear's axis and the slot's axis (the slot gear's, or the
    /// carrier's for a follower), mm.
    pub axis_offset: f64,
    /// Distance of the pin from the pin gear's axis, mm.
    pub pin_radius: f64,
    /// Provenance of the geometry.
    pub source: String,
}

/// A differential: two arbors' rates subtracted through a pair of gears (the cosmos's Moon phase:
/// the mean-Sun tube's gear driving a crown gear on the Moon pointer, so that the phase ball
/// turns at the Moon's rate less the Sun's). Not a mesh of the contact simulation: a crown gear
/// is no pair of plane gears.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Differential {
    /// The output's name (`Moon phase`).
    pub name: String,
    /// The arbor all rates are counted per turn of (`b`).
    pub input: String,
    /// The arbor whose rate is added (the Moon pointer's).
    pub plus: String,
    /// The arbor whose rate is subtracted (the mean Sun's).
    pub minus: String,
    /// Teeth of the gear on `minus` that drives.
    pub driver_teeth: u32,
    /// Teeth of the gear it drives (the crown gear).
    pub driven_teeth: u32,
    /// Provenance.
    pub source: String,
}

/// A gearing file rejected by [`Gearing::from_ron`], displayed as `{file}: {location}: {rule}`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{file}: {location}: {rule}")]
pub struct GearingError {
    /// The file name given to the reader.
    pub file: String,
    /// `line L, column C` for a RON syntax error, otherwise the item: `gear m3`, `mesh b2-c1`,
    /// `pointer Lunar`, `arbor m`.
    pub location: String,
    /// What is wrong.
    pub rule: String,
}

/// Dimensions of one mesh for the contact simulation (all lengths in mm).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshGeometry {
    /// The mesh label.
    pub label: String,
    /// Teeth of the driver.
    pub driver_teeth: u32,
    /// Teeth of the driven gear.
    pub driven_teeth: u32,
    /// Tip (outer) radius `R1` of the driver.
    pub driver_tip_radius: f64,
    /// Tip (outer) radius `R2` of the driven gear.
    pub driven_tip_radius: f64,
    /// Root (inner) radius `r1 = R1 - h` of the driver.
    pub driver_root_radius: f64,
    /// Root (inner) radius `r2 = R2 - h` of the driven gear.
    pub driven_root_radius: f64,
    /// Tooth height `h`, the same for both gears.
    pub tooth_height: f64,
    /// Centre distance `D = R1 + R2 - h + G` with `G = h * clearance_percent / 100`.
    pub centre_distance: f64,
}

/// Gears connected by meshes: they share one scale `mu`, with tip radius `R = mu * N`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Component {
    /// Gear names, in file order.
    pub gears: Vec<String>,
    /// Labels of the meshes joining them, in file order (empty for a gear in no mesh).
    pub meshes: Vec<String>,
    /// Tip radius per tooth in mm: `mu = sum(N_i a_i) / sum(N_i^2)` over measured gears.
    pub mu: f64,
}

/// A validated gearing: gears, the arbors that fix them together, meshes and pointer trains.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Gearing {
    gears: Vec<GearData>,
    arbors: Vec<Arbor>,
    meshes: Vec<MeshData>,
    pointers: Vec<Pointer>,
    pin_and_slot: Option<PinAndSlot>,
    #[serde(skip_serializing_if = "Option::is_none")]
    epicyclic: Option<Epicyclic>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    devices: Vec<PinDevice>,
    #[serde(skip_serializing_if = "Vec::is_empty")]
    differentials: Vec<Differential>,
    #[serde(skip)]
    components: Vec<Component>,
}

/// A gearing file in the user's words, for a file that is not one at all.
pub const RON_FILE: input_file::RonFile = input_file::RonFile {
    what: "a gearing file",
    shape: "( gears: [ ... ], arbors: [ ... ], meshes: [ ... ], pointers: [ ... ] )",
};

/// The file format, before validation.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGearing {
    gears: Vec<GearData>,
    arbors: Vec<Arbor>,
    meshes: Vec<MeshData>,
    pointers: Vec<Pointer>,
    /// Optional: files without it (the format before the pin-and-slot) still load.
    #[serde(default)]
    pin_and_slot: Option<PinAndSlot>,
    /// Optional: the cosmos's carried arbors.
    #[serde(default)]
    epicyclic: Option<Epicyclic>,
    /// Optional: the cosmos's pin-and-slot devices.
    #[serde(default)]
    devices: Vec<PinDevice>,
    /// Optional: the Moon phase's differential.
    #[serde(default)]
    differentials: Vec<Differential>,
}

/// Builds [`GearingError`]s for one file.
struct Errors<'a> {
    file: &'a str,
}

impl Errors<'_> {
    fn at(&self, location: impl fmt::Display, rule: impl fmt::Display) -> GearingError {
        GearingError {
            file: one_line(self.file),
            location: one_line(&location.to_string()),
            rule: one_line(&rule.to_string()),
        }
    }
}

/// Finds `x`'s root in a union-find forest, halving paths.
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

impl Gearing {
    /// The Freeth 2006 gearing embedded from `data/freeth2006.ron`.
    ///
    /// The embedded file is checked by the crate's tests, so it always parses; should it ever
    /// not, this returns an empty gearing rather than panicking (use
    /// `Gearing::from_ron("freeth2006.ron", FREETH2006_RON)` to see the error).
    #[must_use]
    pub fn freeth2006() -> Gearing {
        Gearing::from_ron("freeth2006.ron", FREETH2006_RON).unwrap_or_default()
    }

    /// The embedded gearing called `name` (see [`BUILTIN`]: `freeth2006`, `freeth2021`), or
    /// None for any other name. Like [`Gearing::freeth2006`], an embedded file that failed to
    /// parse would give an empty gearing; the crate's tests parse each one.
    #[must_use]
    pub fn builtin(name: &str) -> Option<Gearing> {
        BUILTIN
            .iter()
            .find(|(n, _, _)| *n == name)
            .map(|(_, file, text)| Gearing::from_ron(file, text).unwrap_or_default())
    }

    /// Reads a gearing file from disk (see [`Gearing::from_ron`]).
    ///
    /// # Errors
    /// The file cannot be read (location `read`), or [`Gearing::from_ron`] rejects it.
    pub fn load(path: &Path) -> Result<Gearing, GearingError> {
        let file = path.display().to_string();
        match input_file::read_to_string(path, input_file::MAX_INPUT_BYTES) {
            Ok(text) => Gearing::from_ron(&file, &text),
            Err(e) => Err(Errors { file: &file }.at("read", e)),
        }
    }

    /// Parses and validates a gearing in RON (the format of `data/freeth2006.ron`).
    ///
    /// `file_name` is only used in error messages.
    ///
    /// # Errors
    /// A RON syntax or shape error (location `line L, column C`; a field name that is not part
    /// of the format, such as a misspelt `measured_radius`, is one), or a rule broken by an item
    /// (location `gear X`, `arbor X`, `mesh X` or `pointer X`): duplicate names; teeth < 3 or
    /// more than [`MAX_TEETH`]; a measured radius that is not positive and finite; an arbor or
    /// mesh naming an unknown gear; a gear on two arbors or on none; a mesh between two gears
    /// of one arbor; a mesh closing a loop of meshes between arbors (two meshes joining the same
    /// two arbors, or a ring of them: each arbor must be turned along one chain); a group of
    /// meshed gears with no measured radius at all (it cannot be sized), or measured radii so
    /// large or small that a fitted tip radius is not a positive finite number; a pointer with
    /// an unknown input arbor or mesh, no meshes, or a chain that does not connect (the first
    /// driver must be on the input arbor, each next driver on the arbor of the previous driven
    /// gear); a `pin_and_slot` section (location `pin_and_slot.FIELD`) naming an unknown gear,
    /// with pin and slot gear not on one arbor or the turntable on theirs, an axis offset or pin
    /// radius that is not positive and finite or an offset not less than the pin radius, no
    /// pointer whose train runs through it, or such a pointer whose train enters the arbor by
    /// another gear than the pin gear, leaves it by another than the slot gear, or has no chain
    /// of meshes from its input arbor to the turntable. The cosmos's sections (location
    /// `epicyclic.FIELD`, `devices[i].FIELD`, `differentials[i].FIELD`, or the gear or mesh):
    /// an unknown arbor, pointer or gear; a fixed arbor that is the carrier; a listed arbor
    /// twice, or not turned from the fixed arbor by a chain of meshes; a mesh joining an arbor
    /// of the epicyclic system to one outside it; a pointer entering the system elsewhere than
    /// at the fixed arbor; a device on a pointer not run in the carrier's frame, or a second
    /// device on one pointer, or a pin gear (slot gear) where its kind does not drive (go on
    /// from) it, or a pin radius not below the offset of a follower (an offset not below the
    /// pin radius of a slot gear); a negative margin; a design radius beside a measured one or
    /// without `sizing: Pitch`; gears of one group of meshed gears sized by two rules; a
    /// differential whose rates no chain gives. The message is one line: control characters in
    /// names are escaped.
    pub fn from_ron(file_name: &str, text: &str) -> Result<Gearing, GearingError> {
        let errors = Errors { file: file_name };
        let raw: RawGearing = input_file::parse_ron(&ron::Options::default(), text, &RON_FILE)
            .map_err(|e| errors.at(e.location, e.rule))?;
        let mut gearing = Gearing {
            gears: raw.gears,
            arbors: raw.arbors,
            meshes: raw.meshes,
            pointers: raw.pointers,
            pin_and_slot: raw.pin_and_slot,
            epicyclic: raw.epicyclic,
            devices: raw.devices,
            differentials: raw.differentials,
            components: Vec::new(),
        };
        gearing.validate(&errors)?;
        gearing.validate_pin_and_slot(&errors)?;
        gearing.validate_cosmos(&errors)?;
        gearing.components = gearing.find_components(&errors)?;
        Ok(gearing)
    }

    /// All gears, in file order.
    #[must_use]
    pub fn gears(&self) -> &[GearData] {
        &self.gears
    }

    /// All arbors, in file order.
    #[must_use]
    pub fn arbors(&self) -> &[Arbor] {
        &self.arbors
    }

    /// All meshes, in file order (the paper's column order for the default gearing).
    #[must_use]
    pub fn meshes(&self) -> &[MeshData] {
        &self.meshes
    }

    /// All pointers, in file order.
    #[must_use]
    pub fn pointers(&self) -> &[Pointer] {
        &self.pointers
    }

    /// The mesh-connected components with their fitted scales (see [`Gearing::tip_radii`]),
    /// in file order of their first gear.
    #[must_use]
    pub fn components(&self) -> &[Component] {
        &self.components
    }

    /// The pin-and-slot section, if the file has one (the default gearing does; the paper's
    /// simulation leaves the pin-and-slot out).
    #[must_use]
    pub fn pin_and_slot(&self) -> Option<&PinAndSlot> {
        self.pin_and_slot.as_ref()
    }

    /// The epicyclic section, if the file has one (the cosmos files do).
    #[must_use]
    pub fn epicyclic(&self) -> Option<&Epicyclic> {
        self.epicyclic.as_ref()
    }

    /// The cosmos's pin-and-slot devices, in file order.
    #[must_use]
    pub fn devices(&self) -> &[PinDevice] {
        &self.devices
    }

    /// The pin-and-slot device of `pointer`, if it has one.
    #[must_use]
    pub fn device(&self, pointer: &str) -> Option<&PinDevice> {
        self.devices.iter().find(|d| d.pointer == pointer)
    }

    /// The differentials, in file order.
    #[must_use]
    pub fn differentials(&self) -> &[Differential] {
        &self.differentials
    }

    /// Whether `arbor` belongs to the epicyclic system (its fixed arbor or one it lists).
    #[must_use]
    pub fn in_epicyclic(&self, arbor: &str) -> bool {
        self.epicyclic
            .as_ref()
            .is_some_and(|e| e.fixed == arbor || e.arbors.iter().any(|a| a == arbor))
    }

    /// Whether `pointer`'s train runs in the carrier's frame (its input is the fixed arbor).
    #[must_use]
    pub fn is_epicyclic_pointer(&self, pointer: &str) -> bool {
        match (self.pointer(pointer), &self.epicyclic) {
            (Some(p), Some(e)) => p.input == e.fixed,
            _ => false,
        }
    }

    /// The signed rate of arbor `to` along the chain of meshes from `from`, both in one frame:
    /// `(-1)^k` times the chain's ratio, `k` its meshes (each external mesh reverses the sense).
    fn chain_rate(&self, from: &str, to: &str) -> Option<Rate> {
        let path = self.mesh_path(from, to)?;
        let ratio = self.path_ratio(from, to)?;
        Rate::from_ratio(ratio, path.len() % 2 == 1)
    }

    /// The rate of `arbor` relative to the carrier, per turn of the carrier, counted in the
    /// carrier's sense: the fixed arbor's is -1, and each mesh in the carrier's frame multiplies
    /// by minus its ratio. `None` for an arbor outside the epicyclic system.
    #[must_use]
    pub fn relative_rate(&self, arbor: &str) -> Option<Rate> {
        let e = self.epicyclic.as_ref()?;
        if !self.in_epicyclic(arbor) {
            return None;
        }
        (-Rate::ONE).checked_mul(self.chain_rate(&e.fixed, arbor)?)
    }

    /// Signed turns of arbor `to` per turn of arbor `from`, both in the frame of the mechanism
    /// and counted in `from`'s sense. Outside an epicyclic system: the chain of meshes from
    /// `from` ([`Gearing::mesh_path`]), each mesh reversing the sense. In one: the carrier's
    /// rate plus the arbor's rate relative to it ([`Gearing::relative_rate`]) times the
    /// carrier's. `None` where no chain joins them, or `from` is in the epicyclic system and
    /// `to` is not `from`.
    #[must_use]
    pub fn rate_from(&self, from: &str, to: &str) -> Option<Rate> {
        if from == to {
            self.arbor(from)?;
            return Some(Rate::ONE);
        }
        if self.in_epicyclic(from) {
            return None;
        }
        if self.in_epicyclic(to) {
            let carrier = self.rate_from(from, &self.epicyclic.as_ref()?.carrier)?;
            let relative = self.relative_rate(to)?.checked_mul(carrier)?;
            return carrier.checked_add(relative);
        }
        self.chain_rate(from, to)
    }

    /// The arbor `pointer` shows: the one its last mesh drives.
    #[must_use]
    pub fn pointer_arbor(&self, pointer: &str) -> Option<&str> {
        let last = self.pointer(pointer)?.meshes.last()?;
        self.arbor_of(&self.mesh(last)?.driven)
    }

    /// The signed rate of `pointer`'s arbor in the frame of the mechanism, per turn of its input
    /// arbor (of the carrier, for a pointer run in the carrier's frame), in that arbor's sense:
    /// exact, so each period relation can be checked as its source states it (the Lunar
    /// pointer 254/19; Freeth 2021's Mars 151/284, the nodes -5/93). `None` for an unknown
    /// pointer or a rate that does not fit in `i128`.
    #[must_use]
    pub fn pointer_rate(&self, pointer: &str) -> Option<Rate> {
        let p = self.pointer(pointer)?;
        let from = match &self.epicyclic {
            Some(e) if p.input == e.fixed => e.carrier.as_str(),
            _ => p.input.as_str(),
        };
        self.rate_from(from, self.pointer_arbor(pointer)?)
    }

    /// The signed rate of differential `name`'s output per turn of its input arbor: `plus`'s
    /// rate less `minus`'s, times `driver_teeth / driven_teeth` (the Moon phase: 254/19 - 1 =
    /// 235/19 turns a year).
    #[must_use]
    pub fn differential_rate(&self, name: &str) -> Option<Rate> {
        let d = self.differentials.iter().find(|d| d.name == name)?;
        let plus = self.rate_from(&d.input, &d.plus)?;
        let minus = self.rate_from(&d.input, &d.minus)?;
        let gears = Rate::new(d.driver_teeth.into(), d.driven_teeth.into())?;
        plus.checked_sub(minus)?.checked_mul(gears)
    }

    /// The chain of meshes (labels, driver to driven) that turns arbor `to` from arbor `from`:
    /// empty if they are the same arbor, `None` if no chain joins them that way (or either is
    /// unknown). Meshes between arbors form a forest, so the chain is unique.
    #[must_use]
    pub fn mesh_path(&self, from: &str, to: &str) -> Option<Vec<String>> {
        self.arbor(from)?;
        self.arbor(to)?;
        // Breadth-first from `from`, remembering the mesh that reached each arbor.
        let mut reached: BTreeMap<&str, Option<&MeshData>> = BTreeMap::new();
        reached.insert(from, None);
        let mut queue = std::collections::VecDeque::from([from]);
        while let Some(arbor) = queue.pop_front() {
            if arbor == to {
                break;
            }
            for m in &self.meshes {
                if self.arbor_of(&m.driver) != Some(arbor) {
                    continue;
                }
                if let Some(next) = self.arbor_of(&m.driven)
                    && !reached.contains_key(next)
                {
                    reached.insert(next, Some(m));
                    queue.push_back(next);
                }
            }
        }
        let mut path = Vec::new();
        let mut at = to;
        while let Some(Some(m)) = reached.get(at).copied() {
            path.push(m.label.clone());
            at = self.arbor_of(&m.driver)?;
        }
        if at != from || !reached.contains_key(to) {
            return None;
        }
        path.reverse();
        Some(path)
    }

    /// Turns of arbor `to` per turn of arbor `from` along [`Gearing::mesh_path`]: the exact
    /// product of `N_driver / N_driven` (every angle positive in its own gear's direction).
    #[must_use]
    pub fn path_ratio(&self, from: &str, to: &str) -> Option<Ratio> {
        self.mesh_path(from, to)?
            .iter()
            .try_fold(Ratio::ONE, |acc, label| {
                acc.checked_mul(self.mesh_ratio(label)?)
            })
    }

    /// The gear called `name`.
    #[must_use]
    pub fn gear(&self, name: &str) -> Option<&GearData> {
        self.gears.iter().find(|g| g.name == name)
    }

    /// The arbor called `name`.
    #[must_use]
    pub fn arbor(&self, name: &str) -> Option<&Arbor> {
        self.arbors.iter().find(|a| a.name == name)
    }

    /// The name of the arbor carrying `gear`.
    #[must_use]
    pub fn arbor_of(&self, gear: &str) -> Option<&str> {
        self.arbors
            .iter()
            .find(|a| a.gears.iter().any(|g| g == gear))
            .map(|a| a.name.as_str())
    }

    /// The name the mesh labels write for `gear`: its own name, or, where the label of a mesh it
    /// is in names it otherwise, that name. The paper writes the Games mesh `n2-o1`; the gearing
    /// file names its 57-tooth driver `n3`, after Freeth 2008, so tables print the paper's `n2`.
    #[must_use]
    pub fn label_name<'a>(&'a self, gear: &'a str) -> &'a str {
        for m in &self.meshes {
            let Some((driver, driven)) = m.label.split_once('-') else {
                continue;
            };
            if m.driver == gear && driver != gear {
                return driver;
            }
            if m.driven == gear && driven != gear {
                return driven;
            }
        }
        gear
    }

    /// The mesh labelled `label`.
    #[must_use]
    pub fn mesh(&self, label: &str) -> Option<&MeshData> {
        self.meshes.iter().find(|m| m.label == label)
    }

    /// The pointer called `name`.
    #[must_use]
    pub fn pointer(&self, name: &str) -> Option<&Pointer> {
        self.pointers.iter().find(|p| p.name == name)
    }

    /// Turns of the driven gear per turn of the driver: `N_driver / N_driven`, exact.
    #[must_use]
    pub fn mesh_ratio(&self, label: &str) -> Option<Ratio> {
        let mesh = self.mesh(label)?;
        let driver = self.gear(&mesh.driver)?;
        let driven = self.gear(&mesh.driven)?;
        Some(Ratio::new(driver.teeth.into(), driven.teeth.into()))
    }

    /// Turns of the pointer's arbor per turn of its input arbor: the exact product of
    /// `N_driver / N_driven` over its meshes (every angle positive in its own gear's direction,
    /// as in the paper). `None` for an unknown pointer or if the product overflows `u128`.
    #[must_use]
    pub fn pointer_ratio(&self, name: &str) -> Option<Ratio> {
        self.pointer(name)?
            .meshes
            .iter()
            .try_fold(Ratio::ONE, |acc, label| {
                acc.checked_mul(self.mesh_ratio(label)?)
            })
    }

    /// Days shown by one degree of the pointer, `365.25 / (360 * ratio)` with one turn of the
    /// input arbor being one year of [`DAYS_PER_TURN`] days. `None` for an unknown pointer or
    /// one whose degrees the paper does not convert to days (`days: false`).
    ///
    /// Default gearing: Metonic about 3.855 d per degree, Saros about 4.573 d per degree.
    #[must_use]
    pub fn days_per_degree(&self, name: &str) -> Option<f64> {
        if !self.pointer(name)?.days {
            return None;
        }
        let ratio = self.pointer_ratio(name)?;
        Some(DAYS_PER_TURN / (360.0 * ratio.to_f64()))
    }

    /// The tip (outer) radius `R` of `gear` in mm (see [`Gearing::tip_radii`]), for a gear sized
    /// by the paper's rule ([`Sizing::Fitted`]); `None` for a gear sized from its pitch radius,
    /// whose tip radius depends on the tooth height ([`Gearing::tip_radius_at`]).
    #[must_use]
    pub fn tip_radius(&self, gear: &str) -> Option<f64> {
        match self.gear(gear)?.sizing {
            Sizing::Fitted => self.fitted_radius(gear),
            Sizing::Pitch => None,
        }
    }

    /// The radius the sizing rule fits to `gear`, `mu * N` with its group's `mu` (see
    /// [`Gearing::tip_radii`]): the tip radius under [`Sizing::Fitted`], the pitch radius under
    /// [`Sizing::Pitch`].
    #[must_use]
    pub fn fitted_radius(&self, gear: &str) -> Option<f64> {
        let teeth = self.gear(gear)?.teeth;
        let c = self
            .components
            .iter()
            .find(|c| c.gears.iter().any(|g| g == gear))?;
        Some(c.mu * f64::from(teeth))
    }

    /// The tip radius `R` of `gear` in mm with teeth `h` mm high: the fitted radius itself under
    /// the paper's rule, the pitch radius plus `h/2` under Freeth & Jones' ([`Sizing`]).
    #[must_use]
    pub fn tip_radius_at(&self, gear: &str, h: f64) -> Option<f64> {
        let fitted = self.fitted_radius(gear)?;
        Some(match self.gear(gear)?.sizing {
            Sizing::Fitted => fitted,
            Sizing::Pitch => fitted + 0.5 * h,
        })
    }

    /// `gear` with ideal triangular teeth of height `h` mm, sized as every experiment sizes it
    /// (tip radius [`Gearing::tip_radius_at`], root radius `R - h`): the one place a gearing's
    /// gear becomes a [`geometry::Gear`]. None for a gear the gearing does not have.
    pub fn ideal_gear(
        &self,
        gear: &str,
        h: f64,
    ) -> Option<Result<geometry::Gear, geometry::GeometryError>> {
        let teeth = self.gear(gear)?.teeth as usize;
        let radius = self.tip_radius_at(gear, h)?;
        Some(geometry::Gear::ideal(teeth, radius, radius - h))
    }

    /// Tip (outer) radius `R` of every gear sized by the paper's rule in mm, by name (a gear sized
    /// from its pitch radius has its tip radius at a tooth height: [`Gearing::tip_radius_at`]).
    ///
    /// The paper keeps `R1/R2 = N1/N2` exactly in every mesh, with `R` as close as possible to
    /// Freeth's measured radii, one radius per gear (b2 has one radius for both of its meshes)
    /// and lost gears sized from their partners. The project's rule: the gears connected by
    /// meshes form one component, and every gear of a component gets `R = mu * N` with one
    /// `mu` per component, chosen by least squares against the measured radii `a_i` of the
    /// component's gears: `mu = sum(N_i a_i) / sum(N_i^2)` over the gears with a measured
    /// radius. A gear in no mesh keeps its measured radius. The measured radius (the mean of the
    /// fragment's inner and outer radius) is fitted as it is, without a correction of about
    /// `h/2` towards the tip.
    #[must_use]
    pub fn tip_radii(&self) -> BTreeMap<String, f64> {
        self.gears
            .iter()
            .filter_map(|g| Some((g.name.clone(), self.tip_radius(&g.name)?)))
            .collect()
    }

    /// Dimensions of mesh `label` with tooth height `tooth_height_mm` (the paper uses 1.1 mm)
    /// and clearance `G` given as a percentage of the tooth height (the paper's working value
    /// is 40): tip radii from [`Gearing::tip_radius_at`], root radii `r = R - h`, centre distance
    /// `D = R1 + R2 - h + h * G / 100`. `None` for an unknown mesh. The parameters are not
    /// checked: `h` should be positive and smaller than both tip radii.
    #[must_use]
    pub fn mesh_geometry(
        &self,
        label: &str,
        tooth_height_mm: f64,
        clearance_percent: f64,
    ) -> Option<MeshGeometry> {
        let mesh = self.mesh(label)?;
        let h = tooth_height_mm;
        let r1 = self.tip_radius_at(&mesh.driver, h)?;
        let r2 = self.tip_radius_at(&mesh.driven, h)?;
        Some(MeshGeometry {
            label: mesh.label.clone(),
            driver_teeth: self.gear(&mesh.driver)?.teeth,
            driven_teeth: self.gear(&mesh.driven)?.teeth,
            driver_tip_radius: r1,
            driven_tip_radius: r2,
            driver_root_radius: r1 - h,
            driven_root_radius: r2 - h,
            tooth_height: h,
            // The paper's D = R1 + R2 - h + G, written once, in geometry.
            centre_distance: geometry::centre_distance(r1, r2, h, clearance_percent),
        })
    }
}
