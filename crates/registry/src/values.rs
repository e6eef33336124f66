//! The values of a plugin's numeric parameters (an error hypothesis', an event rule's): each
//! declared once as a [`Param`] - name, default, unit, help and [`Kind`], the same declaration an
//! experiment's own parameters use - and read by that declaration, never by a name typed again.

use std::collections::BTreeMap;

use crate::{Kind, Param};

/// Why an override was refused: the key as typed, and the rule it broke.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ValueError {
    /// The key as typed (trimmed).
    pub key: String,
    /// The rule broken, in words.
    pub rule: String,
    /// Whether the key is no declared parameter at all (the caller lists the known ones).
    pub unknown: bool,
}

/// Every declared parameter's value: its default unless overridden.
///
/// A value is read by its declaration:
///
/// ```
/// use registry::{Kind, Param, Values};
/// const MU: Param = Param::new("mu", "0.2", "friction", Kind::number(0.0, 10.0, ""));
/// let v = Values::new(&[MU], &[]).unwrap();
/// assert_eq!(v.value(&MU), 0.2);
/// ```
///
/// and there is no reader that takes a name, so a misspelt one cannot compile:
///
/// ```compile_fail
/// use registry::{Kind, Param, Values};
/// const MU: Param = Param::new("mu", "0.2", "friction", Kind::number(0.0, 10.0, ""));
/// let v = Values::new(&[MU], &[]).unwrap();
/// let mu: f64 = v.get("mu");
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct Values {
    decls: &'static [Param],
    values: BTreeMap<&'static str, f64>,
}

impl Values {
    /// The defaults of `decls` (each a number: [`Kind::Number`], [`Kind::Positive`] or
    /// [`Kind::Count`]; a default that is not one is a bug in the declaration, read as NaN so
    /// that the plugin's own checks refuse it).
    pub fn defaults(decls: &'static [Param]) -> Values {
        let values = decls
            .iter()
            .map(|p| (p.name, p.default.trim().parse().unwrap_or(f64::NAN)))
            .collect();
        Values { decls, values }
    }

    /// The defaults of `decls`, then `overrides` (key, value as typed), each checked against
    /// its declaration's [`Kind`].
    ///
    /// # Errors
    /// The first override that names no declared parameter (`unknown`), names one a second time,
    /// or gives a value its kind refuses; the rule ends with the value as typed.
    pub fn new(
        decls: &'static [Param],
        overrides: &[(String, String)],
    ) -> Result<Values, ValueError> {
        let mut out = Values::defaults(decls);
        let mut given: Vec<&str> = Vec::new();
        for (key, text) in overrides {
            let key = key.trim();
            let refuse = |rule: String, unknown: bool| ValueError {
                key: key.to_owned(),
                rule,
                unknown,
            };
            let Some(p) = decls.iter().find(|p| p.name == key) else {
                return Err(refuse("unknown key".into(), true));
            };
            if given.contains(&key) {
                return Err(refuse("is given twice: give it once".into(), false));
            }
            given.push(key);
            let text = text.trim();
            let number = match p.kind {
                Kind::Number { .. } | Kind::Positive { .. } | Kind::Count { .. } => p.kind,
                _ => Kind::ANY_NUMBER,
            };
            number
                .check(text)
                .map_err(|rule| refuse(format!("{rule} (got {})", text.escape_debug()), false))?;
            let value: f64 = text.parse().map_err(|_| {
                refuse(
                    format!("must be a number (got {})", text.escape_debug()),
                    false,
                )
            })?;
            out.values.insert(p.name, value);
        }
        Ok(out)
    }

    /// The value of the declared parameter `p`: the declaration itself is the key, so a name
    /// cannot be misspelled where it is read. A declaration not among this plugin's (a bug)
    /// gives its own default.
    pub fn value(&self, p: &Param) -> f64 {
        self.values
            .get(p.name)
            .copied()
            .filter(|_| self.decls.iter().any(|d| d == p))
            .unwrap_or_else(|| p.default.trim().parse().unwrap_or(f64::NAN))
    }

    /// The declarations, in order.
    pub fn declarations(&self) -> &'static [Param] {
        self.decls
    }

    /// Every (name, value), sorted by name.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        self.values.iter().map(|(&k, &v)| (k, v))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    const MU: Param = Param::new(
        "mu",
        "0.2",
        "friction coefficient",
        Kind::number(0.0, 2.0, ""),
    );
    const N: Param = Param::new("n", "3", "a count", Kind::count(1, 10, ""));
    const DECLS: &[Param] = &[MU, N];

    #[test]
    fn values_are_read_by_their_declaration_and_checked_by_its_kind() {
        let v = Values::new(DECLS, &[("mu".into(), " 0.5 ".into())]).unwrap();
        assert_eq!(v.value(&MU), 0.5);
        assert_eq!(v.value(&N), 3.0);
        assert_eq!(v.iter().collect::<Vec<_>>(), [("mu", 0.5), ("n", 3.0)]);
        let e = Values::new(DECLS, &[("nu".into(), "1".into())]).unwrap_err();
        assert!(e.unknown && e.key == "nu", "{e:?}");
        let e = Values::new(DECLS, &[("mu".into(), "3".into())]).unwrap_err();
        assert_eq!(e.rule, "must be between 0 and 2 (got 3)");
        let e = Values::new(DECLS, &[("n".into(), "2.5".into())]).unwrap_err();
        assert!(e.rule.contains("integer"), "{e:?}");
        let e = Values::new(
            DECLS,
            &[("mu".into(), "1".into()), ("mu".into(), "1".into())],
        )
        .unwrap_err();
        assert!(e.rule.contains("twice"), "{e:?}");
        let e = Values::new(DECLS, &[("mu".into(), "inf".into())]).unwrap_err();
        assert!(e.rule.contains("finite"), "{e:?}");
        // A declaration that is not this plugin's reads as its own default.
        const OTHER: Param = Param::new("mu", "0.7", "another", Kind::ANY_NUMBER);
        assert_eq!(v.value(&OTHER), 0.7);
    }
}
