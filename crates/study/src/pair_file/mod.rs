//! The pair file (`cargo xtask run pair --config FILE`): one mesh described in RON - tooth
//! counts, radii, optional measured tip angles and eccentricity, centre distance or clearance,
//! and the start - parsed and checked into a [`Mesh`] and a [`Start`], naming the file, field
//! and rule of anything refused.

mod checks;

use std::f64::consts::{PI, TAU};

use contact::{Mesh, Start};
use geometry::{Gear, Vec2, polar};
use registry::{
    MAX_ANGLE_DEG, MAX_DATA_ROWS, MIN_SAMPLES, RunError, SAMPLES_PER_TOOTH, fmt_number,
};
use serde::{Deserialize, Serialize};

pub use checks::{MAX_HEIGHT_RATIO, MAX_PITCH_RATIO, MAX_TOOTH_HEIGHT_SHARE};
use checks::{angles, lengths, proportions, samples};

/// Which way a gear's `tips_deg` (and the y axis of its tips frame) run.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Sense {
    /// The direction the driver turns (counter-clockwise in the view of the help text): today's
    /// meaning, so files written before `sense` existed keep it.
    #[default]
    Driver,
    /// The direction this gear itself turns: how one reads a wheel off a scan.
    Own,
}

/// The frame in which `eccentricity` or `arbor` locate the arbor.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Frame {
    /// x along the gear's zero ray, y 90° from it in the sense of its `tips_deg`.
    #[default]
    Tips,
    /// The view's frame, with the gears at φ = 0 and θ = 0.
    World,
}

/// The arbor's position in polar form, seen from the tip-circle centre.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arbor {
    offset: f64,
    angle_deg: f64,
}

/// How the driven gear starts, as written in the file.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum StartSpec {
    /// From θ = 0, pushed clear or turned back until it touches the driver.
    #[default]
    Touching,
    /// Standing still at this absolute driven angle until the driver reaches it.
    AtRest {
        /// θ0, degrees.
        theta_deg: f64,
    },
    /// Driven tooth `driven` resting against driver tooth `driver` (the user's numbers).
    Teeth {
        /// Driver tooth j.
        driver: usize,
        /// Driven tooth k.
        driven: usize,
    },
}

/// One gear as written in the file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearSpec {
    /// Number of teeth.
    pub teeth: usize,
    /// Tip radius (mm).
    pub tip_radius: f64,
    /// Root (valley) radius (mm).
    pub root_radius: f64,
    #[serde(default)]
    /// Measured tip angles (degrees, in the sense `sense` names), one per tooth.
    pub tips_deg: Option<Vec<f64>>,
    #[serde(default)]
    /// Arbor minus tip-circle centre (mm), in the frame `eccentricity_frame` names.
    pub eccentricity: Option<(f64, f64)>,
    #[serde(default)]
    /// Which way `tips_deg` run.
    pub sense: Sense,
    #[serde(default)]
    /// The arbor in polar form (instead of `eccentricity`).
    pub arbor: Option<Arbor>,
    #[serde(default)]
    /// The frame of `eccentricity` and `arbor`.
    pub eccentricity_frame: Frame,
}

/// Which gear of the mesh a [`GearSpec`] describes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// The driving gear.
    Driver,
    /// The driven gear.
    Driven,
}

impl Role {
    /// `driver` or `driven`, as files and outputs name it.
    pub fn name(self) -> &'static str {
        match self {
            Role::Driver => "driver",
            Role::Driven => "driven",
        }
    }
}

/// How the user's tooth numbers map onto the solver's.
///
/// The solver wants tip angles increasing counter-clockwise in the view (the driver's sense). A
/// driven gear measured in its own sense is the mirror image: its angles are negated and the list
/// reversed, so the user's tooth k becomes the solver's tooth N − 1 − k. Negating is exact, so
/// the conversion adds no rounding.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Numbering {
    teeth: i64,
    /// Whether the user's numbering is the solver's mirrored (a driven gear in its own sense).
    pub mirrored: bool,
}

impl Numbering {
    fn new(role: Role, spec: &GearSpec) -> Self {
        Self {
            teeth: spec.teeth as i64,
            mirrored: role == Role::Driven && spec.sense == Sense::Own,
        }
    }

    /// The user's number (0..N) of the solver's tooth `k` (unwrapped: any integer).
    pub fn user(self, k: i64) -> i64 {
        if self.mirrored {
            (self.teeth - 1 - k).rem_euclid(self.teeth)
        } else {
            k.rem_euclid(self.teeth)
        }
    }

    /// The solver's tooth (0..N) of the user's tooth `k` (the map is its own inverse).
    pub fn solver(self, k: i64) -> i64 {
        self.user(k)
    }

    /// The numbering of the same gear seen from its other face ([`geometry::Gear::mirrored`]:
    /// the solver's tooth k becomes tooth N − 1 − k).
    fn flipped(self) -> Self {
        Self {
            teeth: self.teeth,
            mirrored: !self.mirrored,
        }
    }
}

/// The whole file.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairFile {
    /// The driving gear.
    pub driver: GearSpec,
    /// The driven gear.
    pub driven: GearSpec,
    #[serde(default)]
    /// Centre distance between the arbors (mm).
    pub centre_distance: Option<f64>,
    #[serde(default)]
    /// Clearance G (% of h), instead of `centre_distance`.
    pub clearance_percent: Option<f64>,
    #[serde(default)]
    /// Driver angle at the start (degrees).
    pub start_deg: f64,
    #[serde(default)]
    /// Driver angle run (degrees); default one turn of the gear with more teeth.
    pub run_deg: Option<f64>,
    #[serde(default = "default_sample")]
    /// Sampling step of pair.csv (degrees of driver angle).
    pub sample_deg: f64,
    #[serde(default)]
    /// How the driven gear starts.
    pub start: StartSpec,
}

fn default_sample() -> f64 {
    0.1
}

/// The most work a pair run is given: driver pitches run times the larger tooth count, 4·10^6
/// (a turn of two 2000-tooth gears, a few minutes).
const MAX_WORK: f64 = 4.0e6;

/// The driver angle run when `run_deg` is not given: one turn of the gear with more teeth.
pub fn default_run_deg(driver_teeth: usize, driven_teeth: usize) -> f64 {
    360.0 * driver_teeth.max(driven_teeth) as f64 / driver_teeth as f64
}

fn gear(file: &str, role: Role, spec: &GearSpec) -> Result<Gear, RunError> {
    let which = role.name();
    let field = |f: &str| format!("{which}.{f}");
    if spec.teeth < 3 {
        return Err(RunError::bad(
            file,
            field("teeth"),
            format!("must be at least 3 (got {})", spec.teeth),
        ));
    }
    if spec.teeth > geometry::MAX_TEETH {
        return Err(RunError::bad(
            file,
            field("teeth"),
            format!(
                "must be at most {} (the limit on teeth; got {})",
                geometry::MAX_TEETH,
                spec.teeth
            ),
        ));
    }
    let tips = match &spec.tips_deg {
        None => (0..spec.teeth)
            .map(|k| TAU * k as f64 / spec.teeth as f64)
            .collect(),
        Some(t) if t.len() != spec.teeth => {
            return Err(RunError::bad(
                file,
                field("tips_deg"),
                format!(
                    "must list exactly `teeth` = {} angles (got {})",
                    spec.teeth,
                    t.len()
                ),
            ));
        }
        Some(t) => t.iter().map(|a| a.to_radians()).collect(),
    };
    let numbering = Numbering::new(role, spec);
    let offset = arbor_offset(file, role, spec, numbering)?;
    let offset_field = if spec.arbor.is_some() {
        "arbor"
    } else {
        "eccentricity"
    };
    let build = |tips: Vec<f64>| {
        Gear::new(spec.tip_radius, spec.root_radius, tips, offset).map_err(|e| {
            // Name the field as written in the file.
            let f = match e.field.as_str() {
                "rotation_centre" | "rotation_centre.x" | "rotation_centre.y" => {
                    offset_field.to_string()
                }
                other if other.starts_with("tips[") => format!("tips_deg{}", &other[4..]),
                other => other.to_string(),
            };
            RunError::bad(file, field(&f), e.rule)
        })
    };
    // The user's own list is checked first, so that a rule broken by tooth k names the k the
    // user wrote; the mirror of a valid list is valid, so the second build cannot fail on it.
    let as_written = build(tips)?;
    if !numbering.mirrored {
        return Ok(as_written);
    }
    let mirrored = as_written.tip_angles().iter().rev().map(|t| -t).collect();
    build(mirrored)
}

/// The arbor minus the tip-circle centre in the solver's frame of the gear (x along the zero ray,
/// y 90° counter-clockwise in the view), from `eccentricity` or `arbor` in the frame the file names.
fn arbor_offset(
    file: &str,
    role: Role,
    spec: &GearSpec,
    numbering: Numbering,
) -> Result<Vec2, RunError> {
    let field = |f: &str| format!("{}.{f}", role.name());
    let given = match (spec.eccentricity, spec.arbor) {
        (Some(_), Some(_)) => {
            return Err(RunError::bad(
                file,
                field("arbor"),
                "give at most one of eccentricity and arbor (they are the same offset)",
            ));
        }
        (Some((x, y)), None) => Vec2::new(x, y),
        (None, Some(a)) => {
            if !(a.offset.is_finite() && a.offset >= 0.0) {
                return Err(RunError::bad(
                    file,
                    field("arbor.offset"),
                    format!(
                        "must be a finite length >= 0 (got {})",
                        fmt_number(a.offset)
                    ),
                ));
            }
            if !a.angle_deg.is_finite() {
                return Err(RunError::bad(
                    file,
                    field("arbor.angle_deg"),
                    "must be a finite number of degrees",
                ));
            }
            polar(a.offset, a.angle_deg.to_radians())
        }
        (None, None) => Vec2::zeros(),
    };
    Ok(match spec.eccentricity_frame {
        // In the tips frame y follows the sense of the tip angles: a mirrored gear's y is the
        // solver's −y.
        Frame::Tips if numbering.mirrored => Vec2::new(given.x, -given.y),
        Frame::Tips => given,
        // At φ = 0 the driver's frame is the world's; at θ = 0 the driven gear's is the world
        // turned by π (its zero ray points back at the driver).
        Frame::World => match role {
            Role::Driver => given,
            Role::Driven => -given,
        },
    })
}

/// A pair file in the user's words, for a file that is not one at all.
pub const RON_FILE: input_file::RonFile = input_file::RonFile {
    what: "a pair file",
    shape: "( driver: ( teeth: ..., ... ), driven: ( ... ), clearance_percent: ..., ... )",
};

/// Parses and checks a pair file, naming the file, the field (or line and column) and the rule.
pub fn load(file: &str, text: &str) -> Result<(Mesh, PairFile), RunError> {
    let spec: PairFile = input_file::parse_ron(&ron::Options::default(), text, &RON_FILE)
        .map_err(|e| RunError::bad(file, e.location, e.rule))?;
    angles(file, &spec)?;
    lengths(file, &spec)?;
    let driver = gear(file, Role::Driver, &spec.driver)?;
    let driven = gear(file, Role::Driven, &spec.driven)?;
    let d = centre_distance(file, &spec, &driver, &driven)?;
    let run_deg = run_length(file, &spec)?;
    // Gears that never touch: every tip of a gear lies within its largest tip radius of its
    // geometric centre, which is |e| from its rotation centre.
    let reach = driver.max_tip_radius()
        + driven.max_tip_radius()
        + driver.rotation_centre().norm()
        + driven.rotation_centre().norm();
    if d >= reach {
        let field = if spec.centre_distance.is_some() {
            "centre_distance"
        } else {
            "clearance_percent"
        };
        return Err(RunError::bad(
            file,
            field,
            format!(
                "the gears never touch: the centre distance {} is at least R1 + R2 + |e1| + |e2| = {}, so no tip reaches the other gear",
                fmt_number(d),
                fmt_number(reach)
            ),
        ));
    }
    let distance_field = if spec.centre_distance.is_some() {
        "centre_distance"
    } else {
        "clearance_percent"
    };
    let blamed = mesh_field(&spec, (&driver, &driven), d, distance_field);
    let mesh = Mesh::new(driver, driven, d).map_err(|e| {
        let field = if e.field == "centre_distance" {
            blamed.clone()
        } else {
            e.field
        };
        RunError::bad(file, field, e.rule)
    })?;
    proportions(file, &mesh, distance_field)?;
    // Last: what the file asks of the run's statistics, once the gears themselves are sound.
    samples(file, &spec, run_deg, spec.driver.teeth)?;
    Ok((mesh, spec))
}

/// The centre distance a pair file gives: its `centre_distance`, or the one its
/// `clearance_percent` gives between `driver` and `driven` (exactly one of the two).
fn centre_distance(
    file: &str,
    spec: &PairFile,
    driver: &Gear,
    driven: &Gear,
) -> Result<f64, RunError> {
    let d = match (spec.centre_distance, spec.clearance_percent) {
        (Some(d), None) => d,
        (None, Some(g)) => {
            if !(g > 0.0 && g < 100.0) {
                return Err(RunError::bad(
                    file,
                    "clearance_percent",
                    format!(
                        "must be more than 0 and less than 100 (got {}): at 0 the tips reach the other gear's valleys, at 100 they only graze its tips",
                        fmt_number(g)
                    ),
                ));
            }
            let h = 0.5 * (driver.tooth_height() + driven.tooth_height());
            let d = geometry::centre_distance(driver.tip_radius(), driven.tip_radius(), h, g);
            if !d.is_finite() {
                let which = if driver.tip_radius() >= driven.tip_radius() {
                    "driver"
                } else {
                    "driven"
                };
                return Err(RunError::bad(
                    file,
                    format!("{which}.tip_radius"),
                    "is too large: the centre distance it gives with clearance_percent is not a finite number",
                ));
            }
            d
        }
        _ => {
            return Err(RunError::bad(
                file,
                "centre_distance",
                "give exactly one of centre_distance and clearance_percent",
            ));
        }
    };
    Ok(d)
}

/// The driver angle a pair file runs, in degrees (`run_deg`, or a turn of the gear with more
/// teeth), checked with its `sample_deg` against the rows of `pair.csv` and the solver's work.
fn run_length(file: &str, spec: &PairFile) -> Result<f64, RunError> {
    if !(spec.sample_deg > 0.0 && spec.sample_deg.is_finite()) {
        return Err(RunError::bad(
            file,
            "sample_deg",
            "must be a positive number of degrees",
        ));
    }
    if let Some(r) = spec.run_deg
        && !(r > 0.0 && r.is_finite() && r <= 360.0 * 1000.0)
    {
        return Err(RunError::bad(
            file,
            "run_deg",
            "must be a positive number of degrees, at most 360000",
        ));
    }
    let run_deg = spec
        .run_deg
        .unwrap_or_else(|| default_run_deg(spec.driver.teeth, spec.driven.teeth));
    if run_deg / spec.sample_deg > MAX_DATA_ROWS as f64 {
        return Err(RunError::bad(
            file,
            "sample_deg",
            format!(
                "must be at least {} degrees: {} degrees of driver angle in steps of {} would be more than {MAX_DATA_ROWS} rows of pair.csv, the limit",
                fmt_number(run_deg / MAX_DATA_ROWS as f64),
                fmt_number(run_deg),
                fmt_number(spec.sample_deg)
            ),
        ));
    }
    // The solver's work grows with the driver pitches run times the teeth in play: a turn of
    // two 500-tooth gears takes some 20 s, of two 2000-tooth gears minutes.
    let (n1, n2) = (spec.driver.teeth as f64, spec.driven.teeth as f64);
    let work = run_deg / 360.0 * n1 * n1.max(n2);
    if work > MAX_WORK {
        return Err(RunError::bad(
            file,
            "run_deg",
            format!(
                "{} degrees of a {n1}-tooth driver against {} teeth is {} driver pitches times teeth, more than the limit of {MAX_WORK} (minutes of computing; it grows as the square of the teeth per turn): give a shorter run_deg",
                fmt_number(run_deg),
                n1.max(n2),
                fmt_number(work.round())
            ),
        ));
    }
    Ok(run_deg)
}

/// The field of the file a refusal of the mesh's centre distance names: the one the file has
/// (`centre_distance`, or `clearance_percent` from which the distance was made), but the
/// eccentricity of a gear where it alone makes the bodies overlap (the distance clears the two
/// root circles, and the arbors' offsets take it below them).
fn mesh_field(spec: &PairFile, (driver, driven): (&Gear, &Gear), d: f64, distance: &str) -> String {
    let (e1, e2) = (
        driver.rotation_centre().norm(),
        driven.rotation_centre().norm(),
    );
    let roots = driver.min_root_radius() + driven.min_root_radius();
    if d > roots && d <= roots + e1 + e2 {
        let (which, g) = if e1 >= e2 {
            ("driver", &spec.driver)
        } else {
            ("driven", &spec.driven)
        };
        let offset = if g.arbor.is_some() {
            "arbor"
        } else {
            "eccentricity"
        };
        return format!("{which}.{offset}");
    }
    distance.to_owned()
}

/// A loaded pair file, ready to run: the mesh, the file, how its tooth numbers map onto the
/// solver's, and the start it asks for. Stored with a run's results (serde), so that what is
/// drawn of it is drawn again without the file.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Prepared {
    /// The mesh in the solver's conventions.
    pub mesh: Mesh,
    /// The file as written.
    pub spec: PairFile,
    /// The driver's numbering (never mirrored: its own sense is the driver's).
    pub driver: Numbering,
    /// The driven gear's numbering.
    pub driven: Numbering,
    /// How the run starts.
    pub start: Start,
}

impl Prepared {
    /// The file's pair with its driven gear driving (`--set drive=other`), both gears still
    /// turning their own way ([`Mesh::other_driving`]): the run's φ is the file's driven gear's
    /// angle θ, its θ the file's driver's angle φ, and `start_deg` the angle the file's driven
    /// gear starts at; every output numbers each gear's teeth as the file does.
    ///
    /// Errors: a `start` other than `touching` (it names the file's driven gear resting against
    /// its driver, which no longer holds when the driven gear drives), naming the file and field.
    pub fn other_driving(self, file: &str) -> Result<Prepared, RunError> {
        if self.spec.start != StartSpec::Touching {
            return Err(RunError::bad(
                file,
                "start",
                "must be `touching` with --set drive=other: at_rest and teeth(...) place the file's driven gear against its driver, and here the driven gear drives",
            ));
        }
        let mesh = self
            .mesh
            .other_driving()
            .map_err(|e| RunError::bad(file, e.field, e.rule))?;
        // The samples are of the driving gear's angle now: checked against its teeth.
        let (n1, n2) = (self.spec.driven.teeth, self.spec.driver.teeth);
        let run_deg = self.spec.run_deg.unwrap_or_else(|| default_run_deg(n1, n2));
        samples(file, &self.spec, run_deg, n1)?;
        Ok(Prepared {
            mesh,
            driver: self.driven.flipped(),
            driven: self.driver.flipped(),
            spec: self.spec,
            start: Start::Touching(0.0),
        })
    }
}

/// [`load`], then the numbering and the start, all checked before anything runs.
pub fn prepare(file: &str, text: &str) -> Result<Prepared, RunError> {
    let (mesh, spec) = load(file, text)?;
    let driver = Numbering::new(Role::Driver, &spec.driver);
    let driven = Numbering::new(Role::Driven, &spec.driven);
    let start = start_of(file, &mesh, &spec, driven)?;
    Ok(Prepared {
        mesh,
        spec,
        driver,
        driven,
        start,
    })
}

/// Largest overlap (radians of driven angle) tolerated in a start the user chose: two tooth pairs
/// touching at once may overlap by rounding; the solver then pushes the driven gear clear.
const START_SLACK: f64 = 1e-9;

/// The solver's start for the file's `start`, refusing one that cannot be taken.
fn start_of(
    file: &str,
    mesh: &Mesh,
    spec: &PairFile,
    driven: Numbering,
) -> Result<Start, RunError> {
    let phi0 = spec.start_deg.to_radians();
    // Whether the driven gear at θ overlaps no driver tooth at φ0 (beyond rounding).
    let overlap = |field: &str, theta: f64, what: String| -> Result<(), RunError> {
        match mesh.next_free(phi0, theta, false) {
            Some(t) if t <= theta + START_SLACK => Ok(()),
            Some(t) => Err(RunError::bad(
                file,
                field,
                format!(
                    "{what} overlaps a driver tooth at start_deg = {}: the nearest free driven angle ahead is {:.6} deg",
                    spec.start_deg,
                    t.to_degrees()
                ),
            )),
            None => Err(RunError::bad(
                file,
                field,
                format!(
                    "{what}: the driver leaves the driven gear no free position at start_deg = {}",
                    spec.start_deg
                ),
            )),
        }
    };
    match spec.start {
        StartSpec::Touching => Ok(Start::Touching(0.0)),
        StartSpec::AtRest { theta_deg } => {
            if !theta_deg.is_finite() {
                return Err(RunError::bad(
                    file,
                    "start.theta_deg",
                    "must be a finite number of degrees",
                ));
            }
            let theta = theta_deg.to_radians();
            overlap(
                "start.theta_deg",
                theta,
                format!("the driven gear at rest at theta = {theta_deg} deg"),
            )?;
            Ok(Start::At(theta))
        }
        StartSpec::Teeth {
            driver: j,
            driven: k,
        } => {
            let (n1, n2) = (spec.driver.teeth, spec.driven.teeth);
            if j >= n1 {
                return Err(RunError::bad(
                    file,
                    "start.driver",
                    format!("must be a driver tooth, 0 to {} (got {j})", n1 - 1),
                ));
            }
            if k >= n2 {
                return Err(RunError::bad(
                    file,
                    "start.driven",
                    format!("must be a driven tooth, 0 to {} (got {k})", n2 - 1),
                ));
            }
            let k_solver = driven.solver(k as i64);
            // θ is defined only up to whole turns of the driven gear: take the one within half a
            // turn of θ = 0, as the touching start does, by the unwrapped tooth index the solver
            // itself would use there.
            let turns = mesh
                .obstacle(phi0, j as i64, k_solver)
                .map_or(0, |o| -(o.hi / TAU).round() as i64);
            let pair = mesh.obstacle(phi0, j as i64, k_solver + turns * n2 as i64);
            let Some(o) = pair else {
                return Err(RunError::bad(
                    file,
                    "start",
                    format!(
                        "driver tooth {j} cannot touch driven tooth {k} at start_deg = {} ({})",
                        spec.start_deg,
                        in_reach(mesh, phi0)
                    ),
                ));
            };
            // The upper end of the pair's obstacle: the driven tooth just clear ahead of the
            // driver tooth, which pushes it as the driver turns on.
            overlap(
                "start",
                o.hi,
                format!("driven tooth {k} resting against driver tooth {j}"),
            )?;
            Ok(Start::At(o.hi))
        }
    }
}

/// The driver teeth that can touch the driven gear at φ (each can touch any driven tooth, the
/// driven gear turned to suit), in words, for a refused `start: teeth(...)`.
fn in_reach(mesh: &Mesh, phi: f64) -> String {
    let n1 = mesh.driver().teeth() as i64;
    let mut obs = Vec::new();
    // Every driven angle of one turn, and a little more for the pairs that straddle ±π.
    mesh.obstacles(phi, -PI - 0.5, PI + 0.5, &mut obs);
    let mut js: Vec<i64> = obs.iter().map(|o| o.driver_tooth.rem_euclid(n1)).collect();
    js.sort_unstable();
    js.dedup();
    let list = |v: Vec<i64>| {
        let shown: Vec<String> = v.iter().take(12).map(i64::to_string).collect();
        let more = if v.len() > 12 { ", ..." } else { "" };
        format!("{}{more}", shown.join(", "))
    };
    if js.is_empty() {
        "no driver tooth can touch the driven gear there".to_string()
    } else {
        format!("driver teeth that can touch there: {}", list(js))
    }
}
