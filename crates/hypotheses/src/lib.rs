//! Manufacturing-error hypotheses as plugins: each turns a designed gear into a manufactured one.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use geometry::Gear;
use rand::RngCore;
use stdx::{Duplicate, one_line};

pub use geometry;
pub use inventory;
pub use rand;

mod edmunds;
/// Every file in `src/plugins/`, declared by `build.rs`: each hypothesis, built-in or new, is one
/// file there.
mod plugins {
    include!(concat!(env!("OUT_DIR"), "/plugins.rs"));
}
mod measured;
mod params;
mod stack;

pub use edmunds::{EdmundsErrors, MAX_RANDOM, eccentricity, manufacture};
/// Edmunds' three parameters, as Cases A-D and the tolerance grids set them (by declaration,
/// not by a name typed again).
pub use edmunds::{RANDOM, SPLIT, SYSTEMATIC};
pub use measured::{
    MEASURED_EXAMPLE, MeasuredEntry, MeasuredHypothesis, MeasuredTable, measured_file,
    measured_file_given, measured_from_ron,
};
pub use params::{Params, parse_overrides};
pub use stack::{SEPARATOR, stack_layers};

/// Why a hypothesis could not be looked up, configured or applied: what was wrong and the rule.
///
/// Displays on one line as `{what}: {rule}`, e.g.
/// `edmunds-split: --set split: must be between 0 and 1 (got 1.5)`.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{what}: {rule}")]
pub struct HypothesisError {
    /// The offending item: a hypothesis, a parameter, a gear, a table entry.
    pub what: String,
    /// The rule it broke, in words.
    pub rule: String,
}

impl HypothesisError {
    /// An error about `what` breaking `rule`; control characters in either (a newline in a
    /// gear's name, say) are escaped so that the message stays one line.
    pub fn new(what: impl Into<String>, rule: impl Into<String>) -> Self {
        Self {
            what: one_line(&what.into()),
            rule: one_line(&rule.into()),
        }
    }

    /// `gear_name`'s gear could not be built: `e` names the field (`gear `{gear_name}`:
    /// {field}`) and the rule.
    pub fn gear(gear_name: &str, e: geometry::GeometryError) -> Self {
        Self::new(format!("gear `{gear_name}`: {}", e.field), e.rule)
    }

    /// An error about parameter `spec` of hypothesis `hypothesis` breaking `rule`: its `what` is
    /// `{hypothesis}: parameter `{name}``.
    pub fn parameter(hypothesis: &str, spec: &Param, rule: impl Into<String>) -> Self {
        Self::new(format!("{hypothesis}: parameter `{}`", spec.name), rule)
    }
}

/// What [`Hypothesis::apply`] returns: the manufactured gear, or why it could not be made.
pub type Manufactured = Result<Gear, HypothesisError>;

/// One parameter of a hypothesis: declared like every parameter of the toolkit
/// ([`registry::Param`]: name, default, unit, help, a number [`registry::Kind`]) and read by that
/// declaration ([`Params::value`]).
pub use registry::{Kind, Param};

/// What a hypothesis says of itself ([`Plugin::ABOUT`]), and how every hypothesis answers
/// `name()`, `summary()` and `details()`: the same for every plugin kind.
pub use stdx::{About, Describe};

/// A manufacturing-error hypothesis as its plugin file writes it: a unit struct implementing
/// this, registered with [`register!`] (the crate's own plugins and any other crate's alike;
/// `tests/plugin.rs` is one written outside):
///
/// ```
/// use hypotheses::geometry::Gear;
/// use hypotheses::rand::RngCore;
/// use hypotheses::{About, Manufactured, Params};
///
/// /// The whole toothing turned on its blank by 0.01 rad (an example plugin).
/// struct ToyTurn;
///
/// impl hypotheses::Plugin for ToyTurn {
///     const ABOUT: About = About {
///         name: "toy-turn",
///         summary: "every tip turned by 0.01 rad",
///         details: "",
///     };
///
///     fn apply(gear: &Gear, name: &str, _: &Params, _: &mut dyn RngCore) -> Manufactured {
///         let tips = gear.tip_angles().iter().map(|t| t + 0.01).collect();
///         hypotheses::manufacture(gear, name, tips, gear.rotation_centre())
///     }
/// }
///
/// hypotheses::register!(ToyTurn);
///
/// let h = hypotheses::lookup("toy-turn").unwrap();
/// assert_eq!(h.summary(), "every tip turned by 0.01 rad");
/// ```
pub trait Plugin: 'static {
    /// Its name (`--hypothesis NAME`), one line telling what it models, and the model in a few
    /// sentences: what it changes, how it draws, what it leaves alone, and its sources (shown by
    /// `cargo xtask help NAME`; empty if the summary says it all).
    const ABOUT: About;
    /// Its parameters with their defaults; none unless given.
    const PARAMS: &'static [Param] = &[];
    /// Refuses values of `params` that no gear can take ([`Hypothesis::check`]); the default
    /// accepts every value.
    fn check(params: &Params) -> Result<(), HypothesisError> {
        let _ = params;
        Ok(())
    }
    /// The manufactured version of `gear` ([`Hypothesis::apply`]).
    fn apply(gear: &Gear, gear_name: &str, params: &Params, rng: &mut dyn RngCore) -> Manufactured;
}

/// A manufacturing-error hypothesis: how a designed gear becomes a manufactured one.
///
/// It takes a gear, its name, its [`Params`] and a random number generator and returns the gear
/// as it might have been made: tip angles displaced (valleys stay midway, as
/// [`geometry::Gear::new`] places them) and the rotation centre moved off the geometric centre
/// (build the result with [`manufacture`], which checks it); a plugin may change other things
/// too (radii in `ratio-mismatch`, valley angles via [`geometry::Gear::with_valleys`] in
/// `asymmetric-teeth`, per-tooth radii via [`geometry::Gear::with_radii`] in `non-circular`,
/// arc flanks via [`geometry::Gear::with_flank_sagitta`] in `curved-flanks`). One file each in
/// `src/plugins/` ([`Plugin`]): `ideal`, `edmunds-split` (the paper's model, section 4),
/// `eccentric-only`, `sinusoid-only` and `measured` (per-gear values from a RON table; the
/// registered one uses an embedded table of invented example values), beside the other
/// plugins. A stack of them (`a+b`) and a `measured:FILE` are hypotheses too, made when looked
/// up. Its name, summary and details come from [`Describe`].
pub trait Hypothesis: Describe + Sync {
    /// Its parameters with their defaults (may be empty).
    fn params(&self) -> &'static [Param];
    /// Refuses values of `params` that no gear can take, as [`Hypothesis::apply`] would, without
    /// a gear: the error's `what` ends with the parameter's name (`NAME: key`), so that a caller
    /// can name where the value came from (a `--set` the user typed, a value of its own) before
    /// anything is computed. The default accepts every value.
    fn check(&self, params: &Params) -> Result<(), HypothesisError> {
        let _ = params;
        Ok(())
    }
    /// The manufactured version of `gear` (named `gear_name`, for errors and per-gear tables).
    ///
    /// `params` holds a value for every entry of [`Hypothesis::params`]; randomness comes only
    /// from `rng`, so the same stream gives the same gear.
    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn RngCore,
    ) -> Result<Gear, HypothesisError>;
}

/// A registered hypothesis as `inventory` collects it: a plain descriptor of plugin `H`, made
/// by [`Entry::of`] (through [`register!`]). A binary must name the crate that registers it
/// (e.g. [`link`]) or the linker drops it.
#[derive(Debug)]
pub struct Entry {
    about: About,
    params: &'static [Param],
    check: fn(&Params) -> Result<(), HypothesisError>,
    apply: fn(&Gear, &str, &Params, &mut dyn RngCore) -> Manufactured,
}

impl Entry {
    /// The entry of hypothesis `H`.
    pub const fn of<H: Plugin>() -> Entry {
        Entry {
            about: H::ABOUT,
            params: H::PARAMS,
            check: H::check,
            apply: H::apply,
        }
    }
}

impl Describe for Entry {
    fn about(&self) -> &About {
        &self.about
    }
}

impl Hypothesis for Entry {
    fn params(&self) -> &'static [Param] {
        self.params
    }

    fn check(&self, params: &Params) -> Result<(), HypothesisError> {
        (self.check)(params)
    }

    fn apply(
        &self,
        gear: &Gear,
        gear_name: &str,
        params: &Params,
        rng: &mut dyn RngCore,
    ) -> Result<Gear, HypothesisError> {
        (self.apply)(gear, gear_name, params, rng)
    }
}

inventory::collect!(Entry);

/// Registers hypothesis `$ty` (a type implementing [`Plugin`]) with `inventory`:
/// `hypotheses::register!(ToyShift);` (`crate::register!(Ideal);` in this crate's plugin files).
#[macro_export]
macro_rules! register {
    ($ty:ty) => {
        $crate::inventory::submit! { $crate::Entry::of::<$ty>() }
    };
}

/// Every registered hypothesis, sorted by name; a name registered twice is an error naming it.
pub fn hypotheses() -> Result<BTreeMap<&'static str, &'static dyn Hypothesis>, Duplicate> {
    collect(
        inventory::iter::<Entry>
            .into_iter()
            .map(|e| e as &'static dyn Hypothesis),
    )
}

/// Sorts `items` by name, refusing a duplicate.
fn collect(
    items: impl Iterator<Item = &'static dyn Hypothesis>,
) -> Result<BTreeMap<&'static str, &'static dyn Hypothesis>, Duplicate> {
    stdx::by_name("error hypothesis name", items, |h| h.name())
}

/// The registered hypothesis called `name`, or for `measured:FILE` the `measured` hypothesis
/// over the table in FILE ([`measured_file`]); an unknown name is an error listing every known
/// one.
///
/// Names joined by `+` are a stack, applied in that order to each gear:
/// `edmunds-split+curved-flanks` is Edmunds' errors on gears whose flanks are then curved. The
/// stack declares its layers' parameters together (two layers may not declare the same one).
pub fn lookup(name: &str) -> Result<&'static dyn Hypothesis, HypothesisError> {
    if name.contains(SEPARATOR) {
        return stack::lookup_stack(name, lookup_one);
    }
    lookup_one(name)
}

/// [`lookup`] of one hypothesis, not a stack.
fn lookup_one(name: &str) -> Result<&'static dyn Hypothesis, HypothesisError> {
    if let Some(path) = name.strip_prefix("measured:") {
        return measured_file(path).map(|h| h as &'static dyn Hypothesis);
    }
    let all = hypotheses().map_err(|e| HypothesisError::new("error hypotheses", e.to_string()))?;
    all.get(name).copied().ok_or_else(|| {
        let known: Vec<&str> = all.keys().copied().collect();
        HypothesisError::new(
            format!("error hypothesis `{name}`"),
            format!(
                "unknown; known hypotheses: {}, or measured:FILE (a table of per-gear errors)",
                known.join(", ")
            ),
        )
    })
}

/// A readable table of every registered hypothesis: name, summary, and each parameter with its
/// default, unit and help (what `cargo xtask hypotheses` prints).
pub fn listing() -> String {
    let all = match hypotheses() {
        Ok(all) => all,
        Err(e) => return format!("error: {e}\n"),
    };
    let mut s = String::from("Manufacturing-error hypotheses\n\n");
    if all.is_empty() {
        s.push_str("none registered\n");
        return s;
    }
    // Parameter columns aligned across every hypothesis.
    let specs = all.values().flat_map(|h| h.params());
    let defaults: Vec<String> = specs.clone().map(|p| p.default.to_string()).collect();
    let w_name = specs
        .clone()
        .map(|p| p.name.len())
        .max()
        .unwrap_or(0)
        .max("parameter".len());
    let w_def = defaults.iter().map(String::len).max().unwrap_or(0).max(7);
    let w_unit = specs.map(|p| p.unit.len()).max().unwrap_or(0).max(4);
    for (i, h) in all.values().enumerate() {
        if i > 0 {
            s.push('\n');
        }
        let _ = writeln!(s, "{}: {}", h.name(), h.summary());
        if h.params().is_empty() {
            s.push_str("  parameters: none\n");
            continue;
        }
        let _ = writeln!(
            s,
            "  {:w_name$}  {:>w_def$}  {:w_unit$}  help",
            "parameter", "default", "unit"
        );
        for p in h.params() {
            let _ = writeln!(
                s,
                "  {:w_name$}  {:>w_def$}  {:w_unit$}  {}",
                p.name,
                p.default.to_string(),
                p.unit,
                p.help
            );
        }
    }
    s
}

/// What the plugins' tests share.
#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
pub(crate) mod test_support {
    use crate::{Hypothesis, Params};

    /// The registered hypothesis `name` with its default parameters.
    pub(crate) fn with_defaults(name: &str) -> (&'static dyn Hypothesis, Params) {
        let h = crate::lookup(name).unwrap();
        (h, Params::new(h, &[]).unwrap())
    }

    /// Asserts that `deviations` (draws less their design value, of the quantity `what`)
    /// average 0 and that their root mean square is `sd`, each within `tolerance`.
    pub(crate) fn assert_spread(deviations: &[f64], sd: f64, tolerance: f64, what: &str) {
        let n = deviations.len() as f64;
        let mean = deviations.iter().sum::<f64>() / n;
        let rms = (deviations.iter().map(|d| d * d).sum::<f64>() / n).sqrt();
        assert!(mean.abs() < tolerance, "mean {what} {mean}");
        assert!((rms - sd).abs() < tolerance, "sd of the {what} {rms}");
    }
}

/// Does nothing; calling it makes a binary link this crate, and with it every built-in
/// hypothesis it registers.
pub fn link() {}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    struct Named(About);

    impl Describe for Named {
        fn about(&self) -> &About {
            &self.0
        }
    }

    impl Hypothesis for Named {
        fn params(&self) -> &'static [Param] {
            &[]
        }
        fn apply(
            &self,
            gear: &Gear,
            _: &str,
            _: &Params,
            _: &mut dyn rand::RngCore,
        ) -> Result<Gear, HypothesisError> {
            Ok(gear.clone())
        }
    }

    const fn named(name: &'static str) -> Named {
        Named(About {
            name,
            summary: "test",
            details: "",
        })
    }

    static A: Named = named("a");
    static B: Named = named("b");
    static A2: Named = named("a");

    #[test]
    fn collect_sorts_by_name() {
        let map = collect([&B as &dyn Hypothesis, &A].into_iter()).unwrap();
        assert_eq!(map.keys().copied().collect::<Vec<_>>(), ["a", "b"]);
    }

    #[test]
    fn collect_refuses_duplicate_name() {
        let err = collect([&A as &dyn Hypothesis, &B, &A2].into_iter())
            .err()
            .unwrap();
        assert_eq!(err.name, "a");
        assert_eq!(
            err.to_string(),
            "error hypothesis name `a` is registered twice"
        );
    }

    #[test]
    fn built_ins_are_registered_once() {
        let all = hypotheses().unwrap();
        for name in [
            "ideal",
            "edmunds-split",
            "eccentric-only",
            "sinusoid-only",
            "measured",
        ] {
            assert!(all.contains_key(name), "{name} missing");
        }
    }
}
