//! The paper's example pair of section 2 (two equal gears, N = 8, R = 200, r = 100, D = 310):
//! the parameters `fig2` and `fig3` share, and the mesh built from them.

use contact::Mesh;
use geometry::Gear;
use registry::{Param, RunError};

/// The largest radius or centre distance a parameter takes: 10^6 (the paper's example is 200;
/// a larger size is no gear, and prints as a number nobody typed).
pub const MAX_LENGTH: f64 = 1e6;

/// A length (a radius, a centre distance): parameter `name` with `default` and `help`, above 0
/// and at most [`MAX_LENGTH`].
pub const fn length(name: &'static str, default: &'static str, help: &'static str) -> Param {
    Param {
        name,
        default,
        unit: "length",
        help,
        kind: registry::Kind::positive(MAX_LENGTH, "a length; larger is no gear"),
        reading: false,
    }
}

/// Teeth N of both gears.
pub const TEETH: Param = Param {
    name: "teeth",
    default: "8",
    unit: "",
    help: "teeth N of both gears",
    kind: registry::Kind::count(3, geometry::MAX_TEETH as u64, "a gear needs three teeth"),
    reading: false,
};
/// Outer radius R of both gears.
pub const TIP_RADIUS: Param = length("tip_radius", "200", "outer radius R of both gears");
/// Inner radius r of both gears.
pub const ROOT_RADIUS: Param = length("root_radius", "100", "inner radius r of both gears");
/// Centre distance D.
pub const CENTRE_DISTANCE: Param = length("centre_distance", "310", "centre distance D");

/// The pair's setting group: N, R, r and D.
pub const GROUP: &[Param] = &[TEETH, TIP_RADIUS, ROOT_RADIUS, CENTRE_DISTANCE];

/// The pair's group as typed ([`GROUP`]).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct EqualPairParams {
    /// Teeth of each gear ([`TEETH`]).
    #[param(TEETH)]
    pub teeth: usize,
    /// Tip radius R ([`TIP_RADIUS`]).
    #[param(TIP_RADIUS)]
    pub tip_radius: f64,
    /// Root radius r ([`ROOT_RADIUS`]).
    #[param(ROOT_RADIUS)]
    pub root_radius: f64,
    /// Centre distance D ([`CENTRE_DISTANCE`]).
    #[param(CENTRE_DISTANCE)]
    pub centre_distance: f64,
}

impl EqualPairParams {
    /// The pair built ([`build`]).
    pub fn build(&self) -> Result<EqualPair, RunError> {
        build(
            self.teeth,
            self.tip_radius,
            self.root_radius,
            self.centre_distance,
        )
    }
}

/// The pair as set by the parameters above.
pub struct EqualPair {
    /// Teeth of each gear.
    pub teeth: usize,
    /// Tip radius R.
    pub tip_radius: f64,
    /// Root radius r.
    pub root_radius: f64,
    /// Centre distance D.
    pub centre_distance: f64,
    /// The mesh.
    pub mesh: Mesh,
}

/// Builds the mesh of two gears of `teeth` teeth, tip radius `tip_radius` and root radius
/// `root_radius` at `centre_distance`; a broken rule names the parameter.
pub fn build(
    teeth: usize,
    tip_radius: f64,
    root_radius: f64,
    centre_distance: f64,
) -> Result<EqualPair, RunError> {
    let bad = |field: String, rule: String| RunError::bad("--set", field, rule);
    let gear = Gear::ideal(teeth, tip_radius, root_radius).map_err(|e| bad(e.field, e.rule))?;
    // At or beyond touching tip circles no tooth can push another: nothing would be simulated.
    if centre_distance >= 2.0 * tip_radius {
        return Err(bad(
            CENTRE_DISTANCE.name.into(),
            format!(
                "must be below 2 x tip_radius = {}: at {} the tips cannot engage and the driven gear is never turned",
                registry::fmt_number(2.0 * tip_radius),
                registry::fmt_number(centre_distance),
            ),
        ));
    }
    let mesh = Mesh::new(gear.clone(), gear, centre_distance).map_err(|e| bad(e.field, e.rule))?;
    Ok(EqualPair {
        teeth,
        tip_radius,
        root_radius,
        centre_distance,
        mesh,
    })
}
