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
    kind: registry::Kind::Text,
};

/// The `hypothesis_params` parameter: the chosen hypothesis's own parameters, `name=value`
/// pairs separated by commas (e.g. `--set hypothesis_params=scale=0.5`).
pub const PARAMS_PARAM: Param = Param {
    name: "hypothesis_params",
    default: "",
    unit: "",
    help: "parameters of the hypothesis, name=value[,name=value] (cargo xtask hypotheses lists them)",
    kind: registry::Kind::Text,
};

/// Share of the systematic error put on the sinusoid of tip positions (the rest on the axis).
pub const SPLIT: Param = Param {
    name: "split",
    default: "0.5",
    unit: "",
    help: "share of the systematic error on the sinusoid (rest: eccentricity); 0.5 as in the paper",
    kind: registry::Kind::number(0.0, 1.0, ""),
};

/// The error setting group: the hypothesis and its parameters.
pub const GROUP: &[Param] = &[PARAM, PARAMS_PARAM];

/// The error setting group of experiments that run Edmunds' Cases: the split of the systematic
/// error, the hypothesis and its parameters.
pub const CASES_GROUP: &[Param] = &[SPLIT, PARAM, PARAMS_PARAM];

/// The hypothesis named by the `hypothesis` parameter.
pub fn chosen(ctx: &Context) -> Result<&'static dyn Hypothesis, RunError> {
    let name = ctx.param("hypothesis")?;
    hypotheses::lookup(name).map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}

/// Parameters for `h`: its defaults, then those of `values` it declares (others are ignored, so
/// a Case's random and systematic errors can be offered to any hypothesis), then the user's
/// `hypothesis_params`, which must all be declared by `h`.
///
/// A user's key that is also one of `values` replaces it only when the experiment declares a
/// parameter of that name (fig5's `random`: the value the user asked for is the one run, and the
/// title reads it from the result); one the experiment sets itself for each row, Case or gear (a
/// grid's random error, Figure 5's split) is refused, since the rows would name values that did
/// not run. `hypothesis_params` with an empty entry or a key given twice is refused.
pub fn params(
    ctx: &Context,
    h: &dyn Hypothesis,
    values: &[(&str, f64)],
) -> Result<Params, RunError> {
    let bad = |rule: String| RunError::bad("--set", PARAMS_PARAM.name, rule);
    let user = hypotheses::parse_overrides(ctx.param(PARAMS_PARAM.name)?).map_err(bad)?;
    for (k, _) in &user {
        // The same value set twice, as the experiment's parameter and the hypothesis's: which
        // one was meant? Refused like `--trials` with `--set trials`.
        if let Some((_, plain)) = ctx.changed().into_iter().find(|(name, _)| name == k) {
            return Err(bad(format!(
                "`{k}` is also set with --set {k}={plain}: give one of them"
            )));
        }
        if let Some((_, v)) = values.iter().find(|(name, _)| name == k)
            && !ctx.declares(k)
        {
            return Err(bad(format!(
                "`{k}` is set by the experiment itself for each row, Case or gear (here {}): it cannot be replaced here",
                registry::fmt_number(*v)
            )));
        }
    }
    let mut overrides: Vec<(String, String)> = values
        .iter()
        .filter(|(k, _)| h.params().iter().any(|p| p.name == *k))
        .filter(|(k, _)| !user.iter().any(|(u, _)| u == k))
        .map(|(k, v)| ((*k).to_string(), v.to_string()))
        .collect();
    let typed: Vec<String> = user.iter().map(|(k, _)| k.trim().to_string()).collect();
    overrides.extend(user);
    let p = Params::new(h, &overrides).map_err(|e| {
        RunError::bad(
            "--set",
            format!("{}: {}", PARAMS_PARAM.name, e.what),
            e.rule,
        )
    })?;
    // Values no gear can take are refused here, before anything is drawn, naming what the user
    // typed: a key of `hypothesis_params`, or the experiment's own parameter of that name.
    h.check(&p).map_err(|e| {
        let key = e.what.rsplit(": ").next().unwrap_or_default();
        if typed.iter().any(|k| k == key) {
            RunError::bad(
                "--set",
                format!("{}: {}", PARAMS_PARAM.name, e.what),
                e.rule,
            )
        } else if ctx.declares(key) {
            RunError::bad("--set", key, e.rule)
        } else {
            RunError::bad("--hypothesis", e.what, e.rule)
        }
    })?;
    Ok(p)
}

/// `gear` as manufactured under `h`. A failure is bad input (a parameter too large for the gear,
/// a gear missing from a measured table), so it is reported as such, naming the gear.
pub fn make(
    h: &dyn Hypothesis,
    gear: &Gear,
    name: &str,
    p: &Params,
    rng: &mut dyn rand::RngCore,
) -> Result<Gear, RunError> {
    h.apply(gear, name, p, rng)
        .map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}
