//! The numbers a hypothesis is applied with: its defaults, then the user's overrides.

use std::collections::BTreeMap;

use crate::{Hypothesis, HypothesisError};

/// Values of a hypothesis' parameters, by name: every declared parameter has one.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    values: BTreeMap<&'static str, f64>,
}

impl Params {
    /// `h`'s defaults, then `overrides` (name, value as typed) in order, a later one winning.
    ///
    /// An unknown name, or a value that is not a finite number, is an error naming the key, the
    /// hypothesis and its known keys.
    pub fn new(
        h: &dyn Hypothesis,
        overrides: &[(String, String)],
    ) -> Result<Self, HypothesisError> {
        let mut values: BTreeMap<&'static str, f64> =
            h.params().iter().map(|p| (p.name, p.default)).collect();
        let known = || {
            if h.params().is_empty() {
                format!("{} takes no parameters", h.name())
            } else {
                let names: Vec<&str> = h.params().iter().map(|p| p.name).collect();
                format!("known keys of {}: {}", h.name(), names.join(", "))
            }
        };
        for (key, text) in overrides {
            let what = format!("{}: parameter `{key}`", h.name());
            let Some(spec) = h.params().iter().find(|p| p.name == key.trim()) else {
                return Err(HypothesisError::new(
                    what,
                    format!("unknown key ({})", known()),
                ));
            };
            let value: f64 = text.trim().parse().map_err(|_| {
                HypothesisError::new(
                    what.clone(),
                    format!("must be a number (got `{text}`; {})", known()),
                )
            })?;
            if !value.is_finite() {
                return Err(HypothesisError::new(
                    what,
                    format!("must be a finite number (got `{text}`; {})", known()),
                ));
            }
            values.insert(spec.name, value);
        }
        Ok(Self { values })
    }

    /// The value of parameter `name`.
    ///
    /// # Panics
    ///
    /// If `name` is not one of the hypothesis' declared parameters: a bug in the hypothesis, not
    /// bad input (use [`Params::try_get`] to ask).
    pub fn get(&self, name: &str) -> f64 {
        match self.try_get(name) {
            Some(v) => v,
            None => panic!(
                "parameter `{name}` is not declared (declared: {})",
                self.values.keys().copied().collect::<Vec<_>>().join(", ")
            ),
        }
    }

    /// The value of parameter `name`, or `None` if it is not declared.
    pub fn try_get(&self, name: &str) -> Option<f64> {
        self.values.get(name).copied()
    }

    /// Every (name, value), sorted by name.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.values.iter().map(|(&k, &v)| (k, v))
    }
}
