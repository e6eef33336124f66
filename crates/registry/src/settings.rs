//! Typed settings: a struct whose fields name their parameter declarations
//! (`#[derive(Settings)]`), read once from the run's checked values.

use serde::Serialize;
use serde::de::DeserializeOwned;

use crate::{Context, FromParam, Param, RunError};

/// A struct of typed settings: its parameter table, read once from the run's checked values.
///
/// Derived (`#[derive(registry::Settings)]`, see the `settings_derive` crate): each field is
/// `#[param(DECLARATION)]` - one parameter, read by its [`Param`] declaration - or `#[group]` -
/// a nested struct of settings shared by several experiments (a gearing with h and G, an error
/// hypothesis, an event rule). The table is what `--set`, `help`, provenance and the labels of a
/// run off the paper's inputs are derived from; nothing reads a parameter by a name typed again.
pub trait Settings:
    Sized + Clone + std::fmt::Debug + PartialEq + Serialize + DeserializeOwned + Send + Sync + 'static
{
    /// Every parameter, in field order (a group's where the group stands).
    fn params(out: &mut Vec<&'static Param>);

    /// Reads every field by its declaration from `values` (the run's parameters, each already
    /// checked against its kind), then any check across fields the struct names.
    ///
    /// # Errors
    /// A value that does not parse as its field's type ([`RunError::BadInput`], naming the
    /// parameter), or a check across fields that fails.
    fn read(values: &Context) -> Result<Self, RunError>;

    /// Every parameter whose value differs from its declared default, with the value as it
    /// would be typed, in field order.
    fn changed(&self, out: &mut Vec<(&'static Param, String)>);

    /// The parameter table as a list.
    fn table() -> Vec<&'static Param> {
        let mut out = Vec::new();
        Self::params(&mut out);
        out
    }

    /// The parameters set to other than their defaults, except the readings of the paper
    /// ([`Param::reading`]): the inputs in which this run departs from the paper's, so that the
    /// paper's numbers beside ours come from other inputs and are not compared with them.
    fn departures(&self) -> Vec<(&'static Param, String)> {
        let mut out = Vec::new();
        self.changed(&mut out);
        out.retain(|(p, _)| !p.reading);
        out
    }
}

/// No settings at all: an experiment that takes no parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, serde::Deserialize)]
pub struct NoSettings {}

impl Settings for NoSettings {
    fn params(_: &mut Vec<&'static Param>) {}
    fn read(_: &Context) -> Result<Self, RunError> {
        Ok(NoSettings {})
    }
    fn changed(&self, _: &mut Vec<(&'static Param, String)>) {}
}

/// A type a parameter's value is read as and written back in: a number, a count, a switch, a
/// text. [`Settings::changed`] compares a field with its default read the same way, so that
/// `--set clearance=40.0` is no departure from a default of `40`.
pub trait ParamValue: FromParam + PartialEq {
    /// The value `text` stands for (a declaration's default), or `None` if it does not parse.
    fn from_text(text: &str) -> Option<Self>;
    /// The value as it would be typed after `--set NAME=`.
    fn to_text(&self) -> String;
}

impl ParamValue for f64 {
    fn from_text(text: &str) -> Option<f64> {
        text.trim().parse().ok().filter(|x: &f64| x.is_finite())
    }
    fn to_text(&self) -> String {
        self.to_string()
    }
}

impl ParamValue for u64 {
    fn from_text(text: &str) -> Option<u64> {
        text.trim().parse().ok()
    }
    fn to_text(&self) -> String {
        self.to_string()
    }
}

impl ParamValue for usize {
    fn from_text(text: &str) -> Option<usize> {
        text.trim().parse().ok()
    }
    fn to_text(&self) -> String {
        self.to_string()
    }
}

impl ParamValue for bool {
    fn from_text(text: &str) -> Option<bool> {
        text.trim().parse().ok()
    }
    fn to_text(&self) -> String {
        self.to_string()
    }
}

impl ParamValue for String {
    fn from_text(text: &str) -> Option<String> {
        Some(text.trim().to_owned())
    }
    fn to_text(&self) -> String {
        self.clone()
    }
}

/// Pushes `(decl, value)` onto `out` when `value` differs from `decl`'s default: what
/// `#[derive(Settings)]` writes for each field of [`Settings::changed`].
pub fn changed_from_default<T: ParamValue>(
    decl: &'static Param,
    value: &T,
    out: &mut Vec<(&'static Param, String)>,
) {
    let text = value.to_text();
    let same = match T::from_text(decl.default) {
        Some(default) => default == *value,
        None => decl.default.trim() == text.trim(),
    };
    if !same {
        out.push((decl, text));
    }
}
