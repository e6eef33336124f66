//! The numbers a hypothesis is applied with: its defaults, then the user's overrides.

use std::collections::BTreeMap;

use crate::{Hypothesis, HypothesisError, ParamSpec};

/// The `name=value` pairs of a hypothesis' parameters as typed (`random=0.04,systematic=0.6`),
/// trimmed, in order; blank text is no pairs.
///
/// # Errors
/// The rule broken, in words: an empty entry (`,,`, a comma at either end), an entry that is not
/// `name=value` or has no name or no value, a name given twice (which value was meant?).
pub fn parse_overrides(text: &str) -> Result<Vec<(String, String)>, String> {
    if text.trim().is_empty() {
        return Ok(Vec::new());
    }
    let mut pairs: Vec<(String, String)> = Vec::new();
    for (i, entry) in text.split(',').enumerate() {
        let entry = entry.trim();
        if entry.is_empty() {
            return Err(format!(
                "entry {} is empty: give name=value pairs separated by single commas",
                i + 1
            ));
        }
        let Some((k, v)) = entry.split_once('=') else {
            return Err(format!("`{}` is not name=value", entry.escape_debug()));
        };
        let (k, v) = (k.trim(), v.trim());
        if k.is_empty() {
            return Err(format!("`{}` has no name", entry.escape_debug()));
        }
        if v.is_empty() {
            return Err(format!("`{}` has no value", k.escape_debug()));
        }
        if pairs.iter().any(|(other, _)| other == k) {
            return Err(format!(
                "`{}` is given twice: give it once",
                k.escape_debug()
            ));
        }
        pairs.push((k.to_owned(), v.to_owned()));
    }
    Ok(pairs)
}

/// Values of a hypothesis' parameters, by name: every declared parameter has one.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    values: BTreeMap<&'static str, f64>,
}

impl Params {
    /// `h`'s defaults, then `overrides` (name, value as typed).
    ///
    /// An unknown name, a name given twice (which value was meant?), or a value that is not a
    /// finite number, is an error naming the key, the hypothesis and its known keys.
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
            if overrides
                .iter()
                .filter(|(other, _)| other.trim() == key.trim())
                .count()
                > 1
            {
                return Err(HypothesisError::new(
                    what,
                    "is given twice: give it once".to_string(),
                ));
            }
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

    /// The value of `spec`, a length of hypothesis `hypothesis` that must be finite and at least
    /// 0; any other value is an error naming the hypothesis and the parameter (`{hypothesis}:
    /// parameter `{name}`: must be a finite length of at least 0 {unit} (got {value})`).
    ///
    /// # Panics
    ///
    /// As [`Params::get`], if `spec` is not one of the hypothesis' declared parameters.
    pub fn non_negative_length(
        &self,
        spec: &ParamSpec,
        hypothesis: &str,
    ) -> Result<f64, HypothesisError> {
        let x = self.get(spec.name);
        if x.is_finite() && x >= 0.0 {
            return Ok(x);
        }
        Err(HypothesisError::parameter(
            hypothesis,
            spec,
            format!(
                "must be a finite length of at least 0 {} (got {})",
                spec.unit,
                registry::fmt_number(x)
            ),
        ))
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

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn overrides_are_pairs_each_named_once() {
        assert_eq!(parse_overrides(" ").unwrap(), []);
        assert_eq!(
            parse_overrides(" random = 0.04 ,systematic=1").unwrap(),
            [
                ("random".to_owned(), "0.04".to_owned()),
                ("systematic".to_owned(), "1".to_owned())
            ]
        );
        for (text, rule) in [
            (",,,", "entry 1 is empty"),
            ("random=0.04,", "entry 2 is empty"),
            ("random=0.04,,split=1", "entry 2 is empty"),
            ("random=0.03,random=0.04", "`random` is given twice"),
            ("random", "`random` is not name=value"),
            ("=1", "`=1` has no name"),
            ("random=", "`random` has no value"),
        ] {
            let e = parse_overrides(text).unwrap_err();
            assert!(e.contains(rule), "{text}: {e}");
        }
    }

    #[test]
    fn a_key_given_twice_is_refused() {
        let h = crate::lookup("edmunds-split").unwrap();
        let twice = [
            ("random".to_owned(), "0.03".to_owned()),
            ("random".to_owned(), "0.04".to_owned()),
        ];
        let e = Params::new(h, &twice).unwrap_err();
        assert_eq!(e.what, "edmunds-split: parameter `random`");
        assert!(e.rule.contains("given twice"), "{e}");
    }
}
