//! What every plugin kind shares: its account of itself ([`About`], [`Describe`]) and the
//! sorted map of its registrations ([`by_name`]).

use std::collections::BTreeMap;
use std::fmt;

/// What a plugin says of itself: the name it is chosen by, one line telling what it does, and
/// the model in a few sentences with its sources (empty where the line says it all). A plugin
/// file writes it once, as a constant:
///
/// ```
/// const ABOUT: stdx::About = stdx::About {
///     name: "ideal",
///     summary: "no manufacturing error: the gear exactly as designed",
///     details: "",
/// };
/// assert_eq!(ABOUT.name, "ideal");
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct About {
    /// Unique name within its kind, as typed on the command line, e.g. `edmunds-split`.
    pub name: &'static str,
    /// One line telling what it does (listings print it).
    pub summary: &'static str,
    /// The model in a few sentences: what it does, what it leaves alone and what it rests on
    /// (`cargo xtask help NAME` prints it); empty if the summary says it all.
    pub details: &'static str,
}

/// A plugin as its users hold it (`dyn hypotheses::Hypothesis`, `dyn rules::EventRule`, `dyn
/// motion::MotionModel` have it as a supertrait): its name, summary and details, read from its
/// [`About`]. A trait object's supertrait methods need no import, so `h.name()` reads the same
/// on every kind.
pub trait Describe {
    /// What it says of itself.
    fn about(&self) -> &About;

    /// Its unique name.
    fn name(&self) -> &'static str {
        self.about().name
    }

    /// One line telling what it does.
    fn summary(&self) -> &'static str {
        self.about().summary
    }

    /// The model in a few sentences (empty if the summary says it all).
    fn details(&self) -> &'static str {
        self.about().details
    }
}

/// Two registrations of one kind answer to the same name: a build error of the plugins, found
/// when the kind's registry is first read.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Duplicate {
    /// What the name names, as the message says it, e.g. `event rule name`.
    pub what: &'static str,
    /// The name registered twice.
    pub name: &'static str,
}

impl fmt::Display for Duplicate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{} `{}` is registered twice", self.what, self.name)
    }
}

impl std::error::Error for Duplicate {}

/// A plugin kind's registrations sorted by name (`name` reads it from each item), so that
/// every listing comes out in the same order whatever order the linker left them in; a name
/// registered twice is refused as a [`Duplicate`] of `what` (e.g. `error hypothesis name`), as
/// a lookup by name could not say which was meant.
///
/// # Errors
/// The first name met twice.
pub fn by_name<T>(
    what: &'static str,
    items: impl IntoIterator<Item = T>,
    name: impl Fn(&T) -> &'static str,
) -> Result<BTreeMap<&'static str, T>, Duplicate> {
    let mut map = BTreeMap::new();
    for item in items {
        let key = name(&item);
        if map.insert(key, item).is_some() {
            return Err(Duplicate { what, name: key });
        }
    }
    Ok(map)
}

#[cfg(test)]
#[allow(clippy::unwrap_used, reason = "tests fail loudly on purpose")]
mod tests {
    use super::*;

    const A: About = About {
        name: "a",
        summary: "first",
        details: "",
    };
    const B: About = About {
        name: "b",
        summary: "second",
        details: "the second in words",
    };

    impl Describe for About {
        fn about(&self) -> &About {
            self
        }
    }

    #[test]
    fn by_name_sorts_whatever_the_order_given() {
        let map = by_name("test name", [&B, &A], |x| x.name).unwrap();
        assert_eq!(map.keys().copied().collect::<Vec<_>>(), ["a", "b"]);
        assert_eq!(map["b"].summary, "second");
    }

    #[test]
    fn by_name_refuses_a_name_registered_twice() {
        let again = About {
            summary: "again",
            ..A
        };
        let err = by_name("event rule name", [A, B, again], |x| x.name).unwrap_err();
        assert_eq!(
            err,
            Duplicate {
                what: "event rule name",
                name: "a"
            }
        );
        assert_eq!(err.to_string(), "event rule name `a` is registered twice");
    }

    #[test]
    fn describe_reads_the_about() {
        let d: &dyn Describe = &B;
        assert_eq!(
            (d.name(), d.summary(), d.details()),
            ("b", "second", "the second in words")
        );
    }
}
