//! The numbers a hypothesis is applied with: its defaults, then the user's overrides.

use crate::{Hypothesis, HypothesisError, Param};

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

/// Values of a hypothesis' parameters: every declared parameter has one, read by its
/// declaration (`params.value(&RANDOM)`).
#[derive(Debug, Clone, PartialEq)]
pub struct Params(registry::Values);

impl Params {
    /// `h`'s defaults, then `overrides` (name, value as typed), each checked against its
    /// declaration.
    ///
    /// An unknown name, a name given twice (which value was meant?), or a value its declaration
    /// refuses (not a finite number, outside its range) is an error naming the key, the
    /// hypothesis and its known keys.
    pub fn new(
        h: &dyn Hypothesis,
        overrides: &[(String, String)],
    ) -> Result<Self, HypothesisError> {
        let known = || {
            if h.params().is_empty() {
                format!("{} takes no parameters", h.name())
            } else {
                let names: Vec<&str> = h.params().iter().map(|p| p.name).collect();
                format!("known keys of {}: {}", h.name(), names.join(", "))
            }
        };
        registry::Values::new(h.params(), overrides)
            .map(Self)
            .map_err(|e| {
                let what = format!("{}: parameter `{}`", h.name(), e.key);
                if e.unknown {
                    HypothesisError::new(what, format!("unknown key ({})", known()))
                } else {
                    HypothesisError::new(what, format!("{}; {}", e.rule, known()))
                }
            })
    }

    /// The value of the declared parameter `p` (the declaration is the key: a name cannot be
    /// misspelled where it is read).
    pub fn value(&self, p: &Param) -> f64 {
        self.0.value(p)
    }

    /// The value of `spec`, a length of hypothesis `hypothesis` that must be finite and at least
    /// 0; any other value is an error naming the hypothesis and the parameter (`{hypothesis}:
    /// parameter `{name}`: must be a finite length of at least 0 {unit} (got {value})`).
    pub fn non_negative_length(
        &self,
        spec: &Param,
        hypothesis: &str,
    ) -> Result<f64, HypothesisError> {
        let x = self.value(spec);
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

    /// Whether the hypothesis declares `p`.
    pub fn declares(&self, p: &Param) -> bool {
        self.0.declarations().iter().any(|d| d == p)
    }

    /// Every (name, value), sorted by name.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.0.iter()
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
