//! Applying an error hypothesis to gears: the `hypothesis` parameter of the experiments that
//! manufacture gears, and the overrides they pass to it.

use geometry::Gear;
use hypotheses::{Hypothesis, Params};
use registry::{Param, RunError};

/// The `hypothesis` parameter (the runner's `--hypothesis NAME`).
pub const PARAM: Param = Param {
    name: "hypothesis",
    default: "edmunds-split",
    unit: "",
    help: "error hypothesis (cargo xtask hypotheses lists them)",
    kind: registry::Kind::Text,
    reading: false,
    clearance: false,
    recorded: true,
};

/// The `hypothesis_params` parameter: the chosen hypothesis's own parameters, `name=value`
/// pairs separated by commas (e.g. `--set hypothesis_params=scale=0.5`).
pub const PARAMS_PARAM: Param = Param {
    name: "hypothesis_params",
    default: "",
    unit: "",
    help: "parameters of the hypothesis, name=value[,name=value] (cargo xtask hypotheses lists them)",
    kind: registry::Kind::Text,
    reading: false,
    clearance: false,
    recorded: true,
};

/// Share of the systematic error put on the sinusoid of tip positions (the rest on the axis).
pub const SPLIT: Param = Param {
    name: "split",
    default: "0.5",
    unit: "",
    help: "share of the systematic error on the sinusoid (rest: eccentricity); 0.5 as in the paper",
    kind: registry::Kind::number(0.0, 1.0, ""),
    reading: false,
    clearance: false,
    recorded: true,
};

/// The error setting group: the hypothesis and its parameters.
pub const GROUP: &[Param] = &[PARAM, PARAMS_PARAM];

/// The error setting group of experiments that run Edmunds' Cases: the split of the systematic
/// error, the hypothesis and its parameters.
pub const CASES_GROUP: &[Param] = &[SPLIT, PARAM, PARAMS_PARAM];

/// The error group as typed ([`GROUP`]): the hypothesis as named and its parameters as typed.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct ErrorParams {
    /// The hypothesis' name ([`PARAM`]).
    #[param(PARAM)]
    pub hypothesis: String,
    /// Its own parameters, `name=value[,name=value]` ([`PARAMS_PARAM`]).
    #[param(PARAMS_PARAM)]
    pub hypothesis_params: String,
}

/// The error group of experiments that run Edmunds' Cases, as typed ([`CASES_GROUP`]): the
/// split of the systematic error, then the hypothesis and its parameters.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct CaseParams {
    /// Share of the systematic error on the sinusoid ([`SPLIT`]).
    #[param(SPLIT)]
    pub split: f64,
    /// The hypothesis and its parameters.
    #[group]
    pub errors: ErrorParams,
}

impl ErrorParams {
    /// The settings: the hypothesis looked up, `hypothesis_params` parsed, `split` where the
    /// experiment declares one, and what [`Settings::params`] must know of the whole run to say
    /// whose a value is - the experiment's settings `whole` (which parameters differ from their
    /// defaults, which it declares).
    pub fn load<S: registry::Settings>(
        &self,
        split: Option<f64>,
        whole: &S,
    ) -> Result<Settings, RunError> {
        let mut changed = Vec::new();
        whole.changed(&mut changed);
        Settings::new(
            lookup(&self.hypothesis)?,
            &self.hypothesis_params,
            split,
            changed.into_iter().map(|(p, v)| (p.name, v)).collect(),
            S::table().into_iter().map(|p| p.name).collect(),
        )
    }
}

impl CaseParams {
    /// [`ErrorParams::load`] with this group's split.
    pub fn load<S: registry::Settings>(&self, whole: &S) -> Result<Settings, RunError> {
        self.errors.load(Some(self.split), whole)
    }
}

/// The hypothesis `name` (the `hypothesis` parameter's value).
pub fn lookup(name: &str) -> Result<&'static dyn Hypothesis, RunError> {
    hypotheses::lookup(name).map_err(|e| RunError::bad("--hypothesis", e.what, e.rule))
}

/// The error setting group read once: the hypothesis, the user's `hypothesis_params` parsed,
/// [`SPLIT`] where the experiment declares it, and what [`Settings::params`] must know of the
/// run to say whose a value is (the parameters changed from their defaults, the names declared).
/// Cells take their parameters from here, so nothing is parsed again per cell.
#[derive(Clone)]
pub struct Settings {
    /// The hypothesis the experiment's gears are made with.
    pub hypothesis: &'static dyn Hypothesis,
    /// Share of the systematic error on the sinusoid, when the experiment declares [`SPLIT`].
    pub split: Option<f64>,
    /// The user's `hypothesis_params`, as (key, value) in the order typed.
    user: Vec<(String, String)>,
    /// The parameters set to something other than their default, as (name, value).
    changed: Vec<(&'static str, String)>,
    /// Every parameter the experiment declares.
    declared: Vec<&'static str>,
}

impl Settings {
    /// The settings of `hypothesis` with the user's `hypothesis_params` text `user` parsed (an
    /// empty entry or a key given twice is refused), the `split` where the experiment declares
    /// [`SPLIT`], the run's parameters `changed` from their defaults (name, value) and every
    /// parameter name it `declared`.
    pub fn new(
        hypothesis: &'static dyn Hypothesis,
        user: &str,
        split: Option<f64>,
        changed: Vec<(&'static str, String)>,
        declared: Vec<&'static str>,
    ) -> Result<Settings, RunError> {
        let bad = |rule: String| RunError::bad("--set", PARAMS_PARAM.name, rule);
        let user = hypotheses::parse_overrides(user).map_err(bad)?;
        Ok(Settings {
            hypothesis,
            split,
            user,
            changed,
            declared,
        })
    }

    /// These settings with `hypothesis` in place of the chosen one (the user's parameters kept).
    #[must_use]
    pub fn with_hypothesis(&self, hypothesis: &'static dyn Hypothesis) -> Settings {
        Settings {
            hypothesis,
            ..self.clone()
        }
    }

    /// The split of the systematic error; an experiment that does not declare [`SPLIT`] asking
    /// for it is a bug.
    pub fn split(&self) -> Result<f64, RunError> {
        self.split.ok_or_else(|| {
            RunError::Internal(format!(
                "the split of the systematic error was asked for without the `{}` parameter",
                SPLIT.name
            ))
        })
    }

    fn declares(&self, name: &str) -> bool {
        self.declared.contains(&name)
    }

    /// Parameters for the hypothesis: its defaults, then those of `values` it declares (others
    /// are ignored, so a Case's random and systematic errors can be offered to any hypothesis),
    /// then the user's `hypothesis_params`, which must all be declared by it.
    ///
    /// A user's key that is also one of `values` replaces it only when the experiment declares a
    /// parameter of that name (fig5's `random`: the value the user asked for is the one run, and
    /// the title reads it from the result); one the experiment sets itself for each row, Case or
    /// gear (a grid's random error, Figure 5's split) is refused, since the rows would name
    /// values that did not run.
    pub fn params(&self, values: &[(&str, f64)]) -> Result<Params, RunError> {
        let h = self.hypothesis;
        let bad = |rule: String| RunError::bad("--set", PARAMS_PARAM.name, rule);
        for (k, _) in &self.user {
            // The same value set twice, as the experiment's parameter and the hypothesis's: which
            // one was meant? Refused like `--trials` with `--set trials`.
            if let Some((_, plain)) = self.changed.iter().find(|(name, _)| name == k) {
                return Err(bad(format!(
                    "`{k}` is also set with --set {k}={plain}: give one of them"
                )));
            }
            if let Some((_, v)) = values.iter().find(|(name, _)| name == k)
                && !self.declares(k)
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
            .filter(|(k, _)| !self.user.iter().any(|(u, _)| u == k))
            .map(|(k, v)| ((*k).to_string(), v.to_string()))
            .collect();
        let typed: Vec<String> = self
            .user
            .iter()
            .map(|(k, _)| k.trim().to_string())
            .collect();
        overrides.extend(self.user.iter().cloned());
        let p = Params::new(h, &overrides).map_err(|e| {
            RunError::bad(
                "--set",
                format!("{}: {}", PARAMS_PARAM.name, e.what),
                e.rule,
            )
        })?;
        // Values no gear can take are refused here, before anything is drawn, naming what the
        // user typed: a key of `hypothesis_params`, or the experiment's own parameter of that
        // name.
        h.check(&p).map_err(|e| {
            let key = e.what.rsplit(": ").next().unwrap_or_default();
            if typed.iter().any(|k| k == key) {
                RunError::bad(
                    "--set",
                    format!("{}: {}", PARAMS_PARAM.name, e.what),
                    e.rule,
                )
            } else if self.declares(key) {
                RunError::bad("--set", key, e.rule)
            } else {
                RunError::bad("--hypothesis", e.what, e.rule)
            }
        })?;
        Ok(p)
    }

    /// The parameters for an error of `systematic` degrees and `random` of the pitch (as
    /// Edmunds' Cases give them), with the split: [`Settings::params`] of the three.
    pub fn case_params(&self, (systematic, random): (f64, f64)) -> Result<Params, RunError> {
        let values = [
            (hypotheses::RANDOM.name, random),
            (hypotheses::SYSTEMATIC.name, systematic),
            (hypotheses::SPLIT.name, self.split()?),
        ];
        self.params(&values)
    }
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

/// A mechanism of `gearing` (tooth height `h`, clearance `clearance` % of h) whose every gear is
/// made under `hypothesis` from `rng`, in the gearing's gear order, with `params_of(gear)` its
/// parameters (an `Err` text refuses the gear). The hypothesis's own refusal is returned as it
/// is; gears made so that they cannot be placed at the clearance are refused naming the mesh:
/// these inputs cannot be run. Every study that makes a whole mechanism from errors goes
/// through here, so that each draws the gears' errors in the same order.
pub fn made_mechanism<'p>(
    (gearing, h, clearance): (&train::Gearing, f64, f64),
    hypothesis: &dyn Hypothesis,
    params_of: impl Fn(&str) -> Result<&'p Params, String>,
    rng: &mut dyn rand::RngCore,
) -> Result<mechanism::Mechanism, RunError> {
    let mut failure = None;
    let mech = mechanism::Mechanism::build(gearing, h, clearance, |name, gear| {
        let p = params_of(name)?;
        make(hypothesis, &gear, name, p, rng).map_err(|e| {
            let text = e.to_string();
            failure = Some(e);
            text
        })
    });
    match (mech, failure) {
        (_, Some(e)) => Err(e),
        (Err(e), None) => Err(unplaceable(&e)),
        (Ok(m), None) => Ok(m),
    }
}

/// The refusal of gears that cannot be placed at the run's clearance, naming the mesh.
pub fn unplaceable(e: &mechanism::MechanismError) -> RunError {
    RunError::bad(
        "--hypothesis",
        format!("mesh {}", e.mesh),
        format!(
            "{}: the manufactured gears cannot be placed at this clearance",
            e.rule
        ),
    )
}

/// Figure 5's trial: a driver and a driven gear made from `ideal` under `h` with `p`, and an
/// initial driver angle within the driver's pitch, in that order from the one stream of trial
/// `trial` of [`crate::draws::Draws::Figure5Pair`], so that pairs made with other parameters
/// from the same trial differ by the parameters alone.
pub fn made_pair(
    h: &dyn Hypothesis,
    ideal: &Gear,
    p: &Params,
    seed: u64,
    trial: u64,
) -> Result<(Gear, Gear, f64), RunError> {
    use rand::Rng;
    let streams = registry::Streams::new(seed);
    let mut rng = crate::draws::Draws::Figure5Pair.stream(streams, trial);
    let driver = make(h, ideal, "driver", p, &mut rng)?;
    let driven = make(h, ideal, "driven", p, &mut rng)?;
    let phi0 = rng.random::<f64>() * std::f64::consts::TAU / ideal.teeth() as f64;
    Ok((driver, driven, phi0))
}
