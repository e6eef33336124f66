//! The gearing an experiment runs on: the embedded Freeth 2006 (or 2021, or either cosmos) data, or a user's RON file given
//! with `--set gearing=FILE`; and the gearing-wide parameters declared beside it.

use registry::{Param, RunError};
use train::Gearing;

/// The `gearing` parameter every train experiment declares.
pub const PARAM: Param = Param {
    name: "gearing",
    default: "freeth2006",
    unit: "",
    help: "gearing RON file, or an embedded one: freeth2006 (the default, crates/train/data/freeth2006.ron), freeth2021 (the same gearing with the outer radii of Freeth et al. 2021), freeth2021-cosmos or freeth2012-cosmos (freeth2006 with the cosmos display of Freeth et al. 2021 or of Freeth & Jones 2012 in front of b1)",
    kind: registry::Kind::Text,
    reading: false,
    clearance: false,
    recorded: true,
};

/// Clearance G of every mesh of the gearing (the paper's working value, Appendix II).
pub const CLEARANCE: Param = Param {
    name: "clearance",
    default: "40",
    unit: "% of h",
    help: "clearance G of every mesh",
    kind: registry::Kind::positive(100.0, "% of the tooth height h"),
    reading: false,
    clearance: true,
    recorded: true,
};

/// The tooth heights a `tooth_height` parameter takes: 0.01 mm (a hundredth of the paper's
/// 1.1 mm; below it R - h rounds to R on a large gear, and the tooth is no tooth) to 10 m.
pub const TOOTH_HEIGHT_KIND: registry::Kind = registry::Kind::number(
    0.01,
    10_000.0,
    "mm: from a hundredth of a millimetre to 10 m",
);

/// Tooth height h of every gear.
pub const TOOTH_HEIGHT: Param = Param {
    name: "tooth_height",
    default: "1.1",
    unit: "mm",
    help: "h = R - r of every gear (Efstathiou et al. 2012)",
    kind: TOOTH_HEIGHT_KIND,
    reading: false,
    clearance: false,
    recorded: true,
};

/// Whether the Lunar train includes the pin-and-slot (Freeth 2006's lunar anomaly mechanism).
pub const PIN_AND_SLOT: Param = Param {
    name: "pin_and_slot",
    default: "false",
    unit: "",
    help: "true: the Lunar train includes the pin-and-slot (k1's pin in k2's slot on the turning e3 turntable) and its TD is taken against the anomaly-bearing ideal; false: left out, as in the paper",
    kind: registry::Kind::Switch,
    reading: false,
    clearance: false,
    recorded: false,
};

/// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70). Declared
/// here, not in Table I's file, because `replay` checks a cell's clearance against it too.
pub const TABLE_I_CLEARANCES: Param = Param::new(
    "clearances",
    "10,40,70",
    "clearances G, comma-separated (the paper: 10, 40 and 70)",
    registry::Kind::Text,
)
.unit("% of h")
.a_clearance();

/// The gearing setting group: the gearing file, G and h of every mesh.
pub const GROUP: &[Param] = &[PARAM, CLEARANCE, TOOTH_HEIGHT];

/// The gearing file and h, for experiments that choose their own clearances.
pub const SHAPE: &[Param] = &[PARAM, TOOTH_HEIGHT];

/// The gearing group as typed ([`GROUP`]): the gearing as named, G and h of every mesh.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct GearingParams {
    /// The gearing: an embedded name or the user's RON file ([`PARAM`]).
    #[param(PARAM)]
    pub gearing: String,
    /// Clearance G of every mesh, % of h ([`CLEARANCE`]).
    #[param(CLEARANCE)]
    pub clearance: f64,
    /// Tooth height h of every gear, mm ([`TOOTH_HEIGHT`]).
    #[param(TOOTH_HEIGHT)]
    pub tooth_height: f64,
}

impl GearingParams {
    /// The gearing loaded and h checked against it ([`Shape::load`]), with G.
    pub fn load(&self) -> Result<Settings, RunError> {
        Ok(Settings::new(
            Shape::load(&self.gearing, self.tooth_height)?,
            self.clearance,
        ))
    }

    /// The gearing and h without G.
    pub fn shape(&self) -> ShapeParams {
        ShapeParams {
            gearing: self.gearing.clone(),
            tooth_height: self.tooth_height,
        }
    }
}

/// The gearing and h as typed ([`SHAPE`]), for experiments that choose their own clearances.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct ShapeParams {
    /// The gearing: an embedded name or the user's RON file ([`PARAM`]).
    #[param(PARAM)]
    pub gearing: String,
    /// Tooth height h of every gear, mm ([`TOOTH_HEIGHT`]).
    #[param(TOOTH_HEIGHT)]
    pub tooth_height: f64,
}

impl ShapeParams {
    /// The gearing loaded and h checked against it ([`Shape::load`]).
    pub fn load(&self) -> Result<Shape, RunError> {
        Shape::load(&self.gearing, self.tooth_height)
    }
}

/// A gearing's identity in cache keys and batch names: FNV-1a of its data written as RON (its
/// serde serialization, a stable rendering of every field it holds; never its `Debug` text,
/// which is no contract), so two gearings with the same data have the same identity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct GearingId(u64);

impl GearingId {
    /// The identity of `g`.
    ///
    /// Errors: the gearing cannot be written as RON (an internal error: its data is plain).
    pub fn of(g: &Gearing) -> Result<GearingId, RunError> {
        let text = ron::to_string(g)
            .map_err(|e| RunError::Internal(format!("the gearing cannot be written: {e}")))?;
        Ok(GearingId(registry::fnv1a64(text.as_bytes())))
    }
}

impl std::fmt::LowerHex for GearingId {
    /// The identity as cache keys and batch names print it (`{:016x}`).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        std::fmt::LowerHex::fmt(&self.0, f)
    }
}

/// A mechanism the gearing could not build, as the user's error: the gearing, the mesh and the
/// rule it broke (one mapping for every experiment that builds a mechanism).
pub fn mechanism_error(e: mechanism::MechanismError) -> RunError {
    RunError::bad("gearing", format!("mesh {}", e.mesh), e.rule)
}

/// `mech` with the pin-and-slot in or out as `on` says; a gearing without a `pin_and_slot`
/// section cannot have it in (bad input, naming the gearing `file`).
pub fn with_pin_and_slot(
    file: &str,
    mech: mechanism::Mechanism,
    on: bool,
) -> Result<mechanism::Mechanism, RunError> {
    mech.with_pin_and_slot(on).map_err(|e| {
        RunError::bad(
            file,
            "pin_and_slot",
            format!("{} (needed by --set pin_and_slot=true)", e.rule),
        )
    })
}

/// The gearing and its tooth height, read and checked once: what experiments that choose their
/// own clearances read ([`SHAPE`]), and the first part of [`Settings`].
#[derive(Debug, Clone)]
pub struct Shape {
    /// The gearing.
    pub gearing: Gearing,
    /// The `gearing` parameter as typed: an embedded name or the user's file.
    pub file: String,
    /// Tooth height h of every gear (mm).
    pub tooth_height: f64,
}

impl Shape {
    /// The gearing `file` (as typed: an embedded name or a RON file) with tooth height
    /// `tooth_height`: loads the gearing and checks h against it ([`check`]).
    pub fn load(file: &str, tooth_height: f64) -> Result<Shape, RunError> {
        let file = file.to_owned();
        let gearing = load_file(&file)?;
        check(&file, &gearing, tooth_height)?;
        Ok(Shape {
            gearing,
            file,
            tooth_height,
        })
    }
}

/// The gearing setting group ([`GROUP`]) read once: the gearing, h and the clearance G of every
/// mesh.
#[derive(Debug, Clone)]
pub struct Settings {
    /// The gearing.
    pub gearing: Gearing,
    /// The `gearing` parameter as typed: an embedded name or the user's file.
    pub file: String,
    /// Tooth height h of every gear (mm).
    pub tooth_height: f64,
    /// Clearance G of every mesh (% of h): [`CLEARANCE`], the gearing's one.
    pub clearance: f64,
}

impl Settings {
    /// The gearing `shape` with clearance G of every mesh `clearance` (% of h).
    pub fn new(shape: Shape, clearance: f64) -> Settings {
        let Shape {
            gearing,
            file,
            tooth_height,
        } = shape;
        Settings {
            gearing,
            file,
            tooth_height,
            clearance,
        }
    }
}

/// The gearing `name`: an embedded one, or a RON file.
pub fn load_file(name: &str) -> Result<Gearing, RunError> {
    if let Some(g) = Gearing::builtin(name) {
        Ok(g)
    } else {
        Gearing::load(std::path::Path::new(name))
            .map_err(|e| RunError::bad(e.file, e.location, e.rule))
    }
}

/// What the gearing asks of the gearing-wide parameters beyond their kinds (`clearance` G above
/// 0 and at most 100 % of h, `tooth_height` h above 0, checked before anything runs): h must be
/// smaller than the tip radius of every gear in a mesh (the root radius R - h must stay
/// positive). `file` is the gearing as typed, named when a gear of it is to blame.
pub fn check(file: &str, g: &Gearing, h: f64) -> Result<(), RunError> {
    let meshed = g
        .meshes()
        .iter()
        .flat_map(|m| [m.driver.as_str(), m.driven.as_str()]);
    let smallest = meshed
        .filter_map(|name| Some((name, g.tip_radius_at(name, h)?)))
        .min_by(|a, b| a.1.total_cmp(&b.1));
    if let Some((gear, r)) = smallest
        && h >= r
    {
        // A gear whose tooth count does not fit its measured radius (its own module,
        // radius per tooth, far from the others') shrinks the radii fitted to its whole
        // meshed group: blame it, in the file that holds it.
        let modules: Vec<(&train::GearData, f64)> = g
            .gears()
            .iter()
            .filter_map(|d| Some((d, d.measured_radius? / f64::from(d.teeth))))
            .filter(|(_, m)| m.is_finite() && *m > 0.0)
            .collect();
        let mut logs: Vec<f64> = modules.iter().map(|(_, m)| m.ln()).collect();
        logs.sort_by(f64::total_cmp);
        let median = logs.get(logs.len() / 2).copied().unwrap_or(0.0);
        let outlier = modules.iter().max_by(|a, b| {
            (a.1.ln() - median)
                .abs()
                .total_cmp(&(b.1.ln() - median).abs())
        });
        if let Some(&(d, module)) = outlier
            && (module.ln() - median).abs() > 2f64.ln()
        {
            return Err(RunError::bad(
                file,
                format!("gear {}", d.name),
                format!(
                    "{} teeth do not fit its measured radius {} mm ({} mm per tooth, where the gears' median is {} mm): the radii fitted with it make gear {gear}'s tip radius {} mm, less than the tooth height {h} mm",
                    d.teeth,
                    registry::fmt_number(d.measured_radius.unwrap_or(f64::NAN)),
                    registry::fmt_number(module),
                    registry::fmt_number(median.exp()),
                    registry::fmt_number(r)
                ),
            ));
        }
        return Err(RunError::bad(
            "--set",
            TOOTH_HEIGHT.name,
            format!(
                "must be less than the smallest tip radius of the gearing, {r:.3} mm (gear {gear}; got {h})"
            ),
        ));
    }
    Ok(())
}

/// A clearance `g` (% of h, the parameter `name`) with tooth height `h` must leave the tips of
/// every mesh of `gearing` at least [`geometry::MIN_DECIDING_SHARE`] of its largest tip radius
/// from the opposite valleys: closer, rounding decides whether teeth touch (`--set
/// clearance=1e-12` ran, its tips 10^-14 mm from the valleys, and counted noise).
pub fn check_clearance(gearing: &Gearing, h: f64, g: f64, name: &str) -> Result<(), RunError> {
    let largest = gearing
        .meshes()
        .iter()
        .flat_map(|m| [m.driver.as_str(), m.driven.as_str()])
        .filter_map(|gear| gearing.tip_radius(gear))
        .fold(0.0, f64::max);
    let smallest = geometry::MIN_DECIDING_SHARE * largest;
    let gap = g / 100.0 * h;
    // Three significant digits, the least clearance rounded up so that it passes.
    let short = |x: f64| registry::fmt_number(format!("{x:.2e}").parse().unwrap_or(x));
    if gap < smallest {
        return Err(RunError::bad(
            "--set",
            name,
            format!(
                "{} % of h = {h} mm leaves the tips {} mm from the opposite valleys, less than {} of the gearing's largest tip radius ({} mm): a clearance that small is below what the solver can tell from touching, and its jams would be noise; give at least {} %",
                registry::fmt_number(g),
                short(gap),
                registry::fmt_number(geometry::MIN_DECIDING_SHARE),
                short(smallest),
                short(smallest / h * 100.0 * 1.01)
            ),
        ));
    }
    Ok(())
}

/// `text`, the value of the parameter `name`: a comma-separated list of clearances (% of h),
/// each above 0 and at most `max`, each once (a clearance named twice would be one row of the
/// table twice over, and its cells counted twice).
pub fn clearance_list(text: &str, name: &str, max: f64) -> Result<Vec<f64>, RunError> {
    let mut out = Vec::new();
    for part in text.split(',').map(str::trim) {
        let g = clearance_value(part, max).map_err(|rule| {
            let rule = if rule.starts_with('`') {
                format!("{rule} (give e.g. 10,40,70)")
            } else {
                format!("each {rule}")
            };
            RunError::bad("--set", name, rule)
        })?;
        if out.contains(&g) {
            return Err(RunError::bad(
                "--set",
                name,
                format!("names the clearance {part} twice: give each once (got `{text}`)"),
            ));
        }
        out.push(g);
    }
    Ok(out)
}

/// The largest clearance of Table I's list (`clearances`), and of a Table I cell `replay` names.
pub const MAX_LISTED_CLEARANCE: f64 = 200.0;

/// One clearance G as typed (% of h), above 0 and at most `max`; the error is the rule broken:
/// "`x` is not a number" or "must be above 0 and at most 200 % of h (got 0)".
pub fn clearance_value(text: &str, max: f64) -> Result<f64, String> {
    let text = text.trim();
    let g: f64 = text
        .parse()
        .map_err(|_| format!("`{text}` is not a number"))?;
    if !(g.is_finite() && g > 0.0 && g <= max) {
        return Err(format!(
            "must be above 0 and at most {} % of h (got {text})",
            registry::fmt_number(max)
        ));
    }
    Ok(g)
}
