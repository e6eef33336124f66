//! Applying an error hypothesis to gears: the `hypothesis` parameter of the experiments that
//! manufacture gears, and the overrides they pass to it.

use geometry::Gear;
use hypotheses::{Hypothesis, Params};
use registry::{Context, Param, RunError};

/// The `hypothesis` parameter (the runner's `--hypothesis NAME`).
pub const PARAM: Param = Param {
    name: "hypothesis",
    default: "edmunds-split",
    unit: "",
    help: "error hypothesis (cargo xtask hypotheses lists them)",
};

/// The hypothesis named by the `hypothesis` parameter.
pub fn chosen(ctx: &Context) -> Result<&'static dyn Hypothesis, RunError> {
    let name = ctx.param("hypothesis")?;
    hypotheses::lookup(name).map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}

/// Parameters for `h`: its defaults, then those of `values` it declares (others are ignored, so
/// a Case's random and systematic errors can be offered to any hypothesis).
pub fn params(h: &dyn Hypothesis, values: &[(&str, f64)]) -> Result<Params, RunError> {
    let overrides: Vec<(String, String)> = values
        .iter()
        .filter(|(k, _)| h.params().iter().any(|p| p.name == *k))
        .map(|(k, v)| ((*k).to_string(), v.to_string()))
        .collect();
    Params::new(h, &overrides).map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}

/// `gear` as manufactured under `h`.
pub fn make(
    h: &dyn Hypothesis,
    gear: &Gear,
    name: &str,
    p: &Params,
    rng: &mut dyn rand::RngCore,
) -> Result<Gear, RunError> {
    h.apply(gear, name, p, rng)
        .map_err(|e| RunError::Internal(format!("{}: {}", e.what, e.rule)))
}
