//! Event rules as plugins: which mechanical events (lock, strike, gap, slip, blocked start) a table counts as a jam or a disengagement.
//!
//! The contact solver reports what the gears do ([`contact::EventKind`] with its sizes); the
//! paper prints two columns, jams and disengagements. A rule is the map between them, and
//! since the paper's words admit more than one reading, each reading is a plugin: one file in
//! `src/plugins/` implementing [`Plugin`] on a unit struct and registered with [`register!`]
//! (a plain [`Entry`] collected by `inventory`), listed by `cargo xtask rules`, chosen with
//! `--set events=NAME` (parameters as `NAME:key=value,key=value`). A rule looks at one event at
//! a time and at nothing but the contact motion: never at the clearance formula, never at a
//! table.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use stdx::{Duplicate, fmt_number};

pub use contact::{Event, EventKind};
pub use inventory;

/// Every file in `src/plugins/`, declared by `build.rs`: a new rule is one file there.
mod plugins {
    include!(concat!(env!("OUT_DIR"), "/plugins.rs"));
}

/// The rule of the paper's tables unless `--set events=NAME` says otherwise (see the README's
/// results section for the evidence that chose it).
pub const DEFAULT: &str = "idle-rotation";

/// Why a rule could not be looked up or configured: what was wrong and the rule broken.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{what}: {rule}")]
pub struct RuleError {
    /// The offending item: a rule name or one of its parameters.
    pub what: String,
    /// The rule it broke, in words.
    pub rule: String,
}

impl RuleError {
    fn new(what: impl Into<String>, rule: impl Into<String>) -> Self {
        Self {
            what: what.into(),
            rule: rule.into(),
        }
    }
}

/// One parameter of a rule: declared like every parameter of the toolkit
/// ([`registry::Param`], a number [`registry::Kind`] with its range) and read by that
/// declaration ([`Params::value`]).
pub use registry::{Kind, Param};

/// What a rule says of itself ([`Plugin::ABOUT`]), and how a registered one answers `name()`,
/// `summary()` and `details()`: the same for every plugin kind.
pub use stdx::{About, Describe};

/// An event rule as its plugin file writes it: a unit struct implementing this, registered with
/// [`register!`]:
///
/// ```
/// use rules::{About, Event, EventKind, Params};
///
/// /// Jams as interference; disengagement as a slip.
/// struct Mine;
///
/// impl rules::Plugin for Mine {
///     const ABOUT: About = About {
///         name: "mine",
///         summary: "jam: lock, strike or blocked start; disengagement: a slip",
///         details: "The reading in a few sentences, with the sentences it rests on.",
///     };
///     const JAMS: &str = "lock, strike, blocked start";
///     const DISENGAGEMENTS: &str = "slip";
///
///     fn is_jam(e: &Event, _: &Params) -> bool {
///         e.kind.is_contact_stop()
///     }
///
///     fn is_disengagement(e: &Event, _: &Params) -> bool {
///         e.kind == EventKind::Slip
///     }
/// }
///
/// rules::register!(Mine);
///
/// let mine = rules::Rule::parse("mine").unwrap();
/// assert_eq!(mine.definition().jams(), "lock, strike, blocked start");
/// ```
pub trait Plugin: 'static {
    /// Its name (`--set events=NAME`), one line telling what it counts, and the reading in a
    /// few sentences with the quoted sentences it rests on (`cargo xtask help NAME`).
    const ABOUT: About;
    /// Its parameters (`--set events=NAME:key=value`); none unless given.
    const PARAMS: &'static [Param] = &[];
    /// What it counts as a jam, in a few words: its cell of the README's table of rules
    /// ([`readme_row`]).
    const JAMS: &'static str;
    /// What it counts as a disengagement, in a few words: its cell of the README's table of
    /// rules.
    const DISENGAGEMENTS: &'static str;
    /// Whether `e` counts as a jam, with `params` holding a value for every declared parameter.
    fn is_jam(e: &Event, params: &Params) -> bool;
    /// Whether `e` counts as a disengagement.
    fn is_disengagement(e: &Event, params: &Params) -> bool;
}

/// A registered event rule, as an experiment holds it (through [`Rule`]): which events are jams
/// and which are disengagements, and what it says of itself ([`Describe`]).
pub trait EventRule: Describe + Sync {
    /// Its parameters (may be empty).
    fn params(&self) -> &'static [Param];
    /// What it counts as a jam, in a few words ([`Plugin::JAMS`]).
    fn jams(&self) -> &'static str;
    /// What it counts as a disengagement, in a few words ([`Plugin::DISENGAGEMENTS`]).
    fn disengagements(&self) -> &'static str;
    /// Whether `e` counts as a jam, with `params` holding a value for every declared parameter.
    fn is_jam(&self, e: &Event, params: &Params) -> bool;
    /// Whether `e` counts as a disengagement.
    fn is_disengagement(&self, e: &Event, params: &Params) -> bool;
}

/// A registered rule as `inventory` collects it: a plain descriptor of rule `R`, made by
/// [`Entry::of`] (through [`register!`]).
#[derive(Debug)]
pub struct Entry {
    about: About,
    params: &'static [Param],
    jams: &'static str,
    disengagements: &'static str,
    is_jam: fn(&Event, &Params) -> bool,
    is_disengagement: fn(&Event, &Params) -> bool,
}

impl Entry {
    /// The entry of rule `R`.
    pub const fn of<R: Plugin>() -> Entry {
        Entry {
            about: R::ABOUT,
            params: R::PARAMS,
            jams: R::JAMS,
            disengagements: R::DISENGAGEMENTS,
            is_jam: R::is_jam,
            is_disengagement: R::is_disengagement,
        }
    }
}

impl Describe for Entry {
    fn about(&self) -> &About {
        &self.about
    }
}

impl EventRule for Entry {
    fn params(&self) -> &'static [Param] {
        self.params
    }

    fn jams(&self) -> &'static str {
        self.jams
    }

    fn disengagements(&self) -> &'static str {
        self.disengagements
    }

    fn is_jam(&self, e: &Event, params: &Params) -> bool {
        (self.is_jam)(e, params)
    }

    fn is_disengagement(&self, e: &Event, params: &Params) -> bool {
        (self.is_disengagement)(e, params)
    }
}

inventory::collect!(Entry);

/// Registers rule `$ty` (a type implementing [`Plugin`]) with `inventory`:
/// `rules::register!(Paper);` (`crate::register!(Paper);` in this crate's plugin files).
#[macro_export]
macro_rules! register {
    ($ty:ty) => {
        $crate::inventory::submit! { $crate::Entry::of::<$ty>() }
    };
}

/// Every registered rule, sorted by name; a name registered twice is an error naming it.
pub fn rules() -> Result<BTreeMap<&'static str, &'static dyn EventRule>, Duplicate> {
    collect(
        inventory::iter::<Entry>
            .into_iter()
            .map(|e| e as &'static dyn EventRule),
    )
}

fn collect(
    items: impl Iterator<Item = &'static dyn EventRule>,
) -> Result<BTreeMap<&'static str, &'static dyn EventRule>, Duplicate> {
    stdx::by_name("event rule name", items, |r| r.name())
}

/// A rule's parameter values: every declared parameter has one, read by its declaration
/// (`params.value(&MU)`).
pub type Params = registry::Values;

/// A rule with its parameter values: what an experiment counts with.
#[derive(Clone)]
pub struct Rule {
    def: &'static dyn EventRule,
    params: Params,
}

impl std::fmt::Debug for Rule {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.label())
    }
}

impl PartialEq for Rule {
    fn eq(&self, other: &Self) -> bool {
        self.label() == other.label()
    }
}

impl Rule {
    /// The rule named by `spec`: `NAME` or `NAME:key=value[,key=value]`. An unknown name lists
    /// the known ones; an unknown key lists the rule's keys; a value outside its range names it.
    pub fn parse(spec: &str) -> Result<Self, RuleError> {
        let (name, args) = match spec.split_once(':') {
            Some((n, a)) => (n.trim(), Some(a)),
            None => (spec.trim(), None),
        };
        let all = rules().map_err(|e| RuleError::new("event rules", e.to_string()))?;
        let Some(&def) = all.get(name) else {
            let known: Vec<&str> = all.keys().copied().collect();
            return Err(RuleError::new(
                format!("event rule `{}`", name.escape_debug()),
                format!("unknown; known rules: {}", known.join(", ")),
            ));
        };
        let keys = || {
            let names: Vec<&str> = def.params().iter().map(|p| p.name).collect();
            if names.is_empty() {
                format!("{name} takes no parameters")
            } else {
                format!("known keys of {name}: {}", names.join(", "))
            }
        };
        let mut pairs: Vec<(String, String)> = Vec::new();
        for (i, pair) in args.into_iter().flat_map(|a| a.split(',')).enumerate() {
            let what = |k: &str| format!("event rule {name}: parameter `{}`", k.escape_debug());
            if pair.trim().is_empty() {
                return Err(RuleError::new(
                    format!("event rule {name}"),
                    format!(
                        "entry {} after `:` is empty: give key=value pairs separated by single commas ({})",
                        i + 1,
                        keys()
                    ),
                ));
            }
            let Some((key, text)) = pair.split_once('=') else {
                return Err(RuleError::new(
                    what(pair),
                    format!("must be key=value ({})", keys()),
                ));
            };
            pairs.push((key.trim().to_owned(), text.to_owned()));
        }
        let params = Params::new(def.params(), &pairs).map_err(|e| {
            let what = format!("event rule {name}: parameter `{}`", e.key.escape_debug());
            if e.unknown {
                RuleError::new(what, format!("unknown key ({})", keys()))
            } else {
                RuleError::new(what, e.rule)
            }
        })?;
        Ok(Self { def, params })
    }

    /// The rule's name.
    pub fn name(&self) -> &'static str {
        self.def.name()
    }

    /// The rule's definition.
    pub fn definition(&self) -> &'static dyn EventRule {
        self.def
    }

    /// Its parameter values.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The rule as a table names it: `paper`, or `friction(mu=0.2)` with every parameter.
    pub fn label(&self) -> String {
        let mut s = self.def.name().to_string();
        if !self.def.params().is_empty() {
            let args: Vec<String> = self
                .params
                .iter()
                .map(|(k, v)| format!("{k}={}", fmt_number(v)))
                .collect();
            let _ = write!(s, "({})", args.join(","));
        }
        s
    }

    /// Whether `e` counts as a jam.
    pub fn is_jam(&self, e: &Event) -> bool {
        self.def.is_jam(e, &self.params)
    }

    /// Whether `e` counts as a disengagement.
    pub fn is_disengagement(&self, e: &Event) -> bool {
        self.def.is_disengagement(e, &self.params)
    }

    /// (at least one jam, at least one disengagement) among `events`: one trial of a table.
    pub fn tally(&self, events: &[Event]) -> (bool, bool) {
        (
            events.iter().any(|e| self.is_jam(e)),
            events.iter().any(|e| self.is_disengagement(e)),
        )
    }

    /// The first event that counts as a jam, if any.
    pub fn first_jam<'e>(&self, events: &'e [Event]) -> Option<&'e Event> {
        events.iter().find(|e| self.is_jam(e))
    }
}

impl Default for Rule {
    /// The [`DEFAULT`] rule.
    fn default() -> Self {
        #[allow(
            clippy::expect_used,
            reason = "the default rule is a built-in plugin, tested"
        )]
        Self::parse(DEFAULT).expect("the default event rule is registered")
    }
}

/// A readable list of every registered rule: name, summary and parameters (what `cargo xtask
/// rules` prints, pinned in `snapshots/rules.snap`).
pub fn listing() -> String {
    let all = match rules() {
        Ok(all) => all,
        Err(e) => return format!("error: {e}\n"),
    };
    let mut s = String::from("Event rules (--set events=NAME; default ");
    let _ = writeln!(s, "{DEFAULT})\n");
    let w = all.keys().map(|k| k.len()).max().unwrap_or(0);
    for r in all.values() {
        let _ = writeln!(s, "{:w$}  {}", r.name(), r.summary());
        for p in r.params() {
            let _ = writeln!(
                s,
                "{:w$}    {}: default {}{}{}, {}: {}",
                "",
                p.name,
                p.default,
                if p.unit.is_empty() { "" } else { " " },
                p.unit,
                p.kind.describe(),
                p.help
            );
        }
    }
    s.push_str("\nEvent kinds (from the contact motion): ");
    let kinds: Vec<&str> = EventKind::ALL.iter().map(|k| k.name()).collect();
    s.push_str(&kinds.join(", "));
    s.push('\n');
    s
}

/// The header of the README's table of rules, whose rows are [`readme_row`].
pub const README_HEADER: &str = "| rule | jam | disengagement |\n|---|---|---|\n";

/// Rule `r`'s row of the README's table of rules (the test that pins `rules.snap` checks each row
/// the README lists against it): its name (with `default` and its parameters' defaults),
/// what it counts as a jam and as a disengagement; one line, ending in a newline.
pub fn readme_row(r: &dyn EventRule) -> String {
    let mut notes = Vec::new();
    if r.name() == DEFAULT {
        notes.push("default".to_owned());
    }
    if !r.params().is_empty() {
        let args: Vec<String> = r
            .params()
            .iter()
            .map(|p| format!("{}={}", p.name, p.default))
            .collect();
        notes.push(format!("`events={}:{}`", r.name(), args.join(",")));
    }
    let notes = if notes.is_empty() {
        String::new()
    } else {
        format!(" ({})", notes.join("; "))
    };
    format!(
        "| `{}`{notes} | {} | {} |\n",
        r.name(),
        r.jams(),
        r.disengagements()
    )
}

/// Does nothing; calling it makes a binary link this crate, and with it every rule it registers.
pub fn link() {}

#[cfg(test)]
#[allow(clippy::unwrap_used, reason = "tests")]
mod tests {
    use super::*;

    fn event(kind: EventKind) -> Event {
        Event {
            phi: 0.0,
            theta: 0.0,
            kind,
            driver_tooth: 0,
            driven_tooth: 0,
            theta_after: 0.0,
            lost_motion: 0.2,
            resumed: true,
            resumed_by: None,
            phase_shift: 0,
            lag: 0.0,
            wedge_angle: None,
            idle_start: false,
        }
    }

    #[test]
    fn the_readings_the_tests_name_are_registered_and_default_exists() {
        let all = rules().unwrap();
        for name in ["friction", "idle-rotation", "paper", "strict", "sync"] {
            assert!(all.contains_key(name), "{name} missing");
        }
        assert_eq!(Rule::default().name(), DEFAULT);
    }

    /// One rule per file of `src/plugins/` (file `a_b.rs` registers `a-b`), found by `build.rs`:
    /// the registry is the list, written nowhere by hand.
    #[test]
    fn every_plugin_file_registers_its_rule_and_nothing_else_is_registered() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/plugins");
        let mut files: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "rs"))
            .map(|p| p.file_stem().unwrap().to_string_lossy().replace('_', "-"))
            .collect();
        files.sort_unstable();
        let registered: Vec<&str> = rules().unwrap().keys().copied().collect();
        assert_eq!(registered, files);
    }

    #[test]
    fn collect_refuses_a_duplicate_name() {
        let a = rules().unwrap()["paper"];
        let err = collect([a, a].into_iter()).err().unwrap();
        assert_eq!(
            err.to_string(),
            "event rule name `paper` is registered twice"
        );
    }

    #[test]
    fn strict_counts_every_stop_and_every_loss() {
        let r = Rule::parse("strict").unwrap();
        for k in EventKind::ALL {
            assert_eq!(r.is_jam(&event(k)), k.is_contact_stop(), "{k:?}");
            assert_eq!(r.is_disengagement(&event(k)), k.is_loss(), "{k:?}");
        }
    }

    #[test]
    fn paper_and_sync_ignore_a_hand_over_gap() {
        for name in ["paper", "sync", "friction"] {
            let r = Rule::parse(name).unwrap();
            let gap = event(EventKind::Gap);
            assert!(!r.is_jam(&gap) && !r.is_disengagement(&gap), "{name}");
            let slip = event(EventKind::Slip);
            assert!(r.is_disengagement(&slip), "{name}");
            assert!(r.is_jam(&event(EventKind::Lock)), "{name}");
            assert!(r.is_jam(&event(EventKind::BlockedAtStart)), "{name}");
        }
    }

    #[test]
    fn sync_counts_a_strike_only_when_it_moves_the_tooth_phase() {
        let r = Rule::parse("sync").unwrap();
        let mut s = event(EventKind::Strike);
        assert!(!r.is_jam(&s) && !r.is_disengagement(&s));
        s.phase_shift = 1;
        assert!(!r.is_jam(&s) && r.is_disengagement(&s));
    }

    #[test]
    fn idle_rotation_counts_lost_drive_by_its_length_alone() {
        let r = Rule::parse("idle-rotation").unwrap();
        assert_eq!(r.label(), "idle-rotation(pitches=1)");
        let mut loss = event(EventKind::Gap);
        loss.lost_motion = 0.99;
        assert!(!r.is_disengagement(&loss));
        // A short loss that resumes a tooth out of step is a slip, yet no idle rotation.
        loss.kind = EventKind::Slip;
        loss.phase_shift = 1;
        assert!(!r.is_disengagement(&loss));
        loss.lost_motion = 1.0;
        assert!(r.is_disengagement(&loss));
        loss.kind = EventKind::Gap;
        assert!(r.is_disengagement(&loss), "a gap is sized, not named");
        assert!(r.is_jam(&event(EventKind::Lock)) && r.is_jam(&event(EventKind::Strike)));
        let half = Rule::parse("idle-rotation:pitches=0.5").unwrap();
        let mut short = event(EventKind::Gap);
        short.lost_motion = 0.6;
        assert!(half.is_disengagement(&short) && !r.is_disengagement(&short));
    }

    #[test]
    fn every_rule_that_counts_slips_counts_an_idle_start() {
        let mut idle = event(EventKind::Slip);
        idle.idle_start = true;
        idle.resumed = false;
        idle.lost_motion = 0.3; // a run shorter than a pitch, never driven
        // Every registered rule counts losses of drive in some form, so every one counts it.
        for name in rules().unwrap().keys() {
            let r = Rule::parse(name).unwrap();
            assert!(r.is_disengagement(&idle), "{name}");
        }
    }

    #[test]
    fn friction_wedges_inside_the_cone_only() {
        let r = Rule::parse("friction:mu=0.2").unwrap();
        let mut s = event(EventKind::Strike);
        s.wedge_angle = Some(0.1); // inside atan(0.2) = 0.197
        assert!(r.is_jam(&s));
        s.wedge_angle = Some(0.3);
        assert!(!r.is_jam(&s));
        let frictionless = Rule::parse("friction:mu=0").unwrap();
        s.wedge_angle = Some(1e-6);
        assert!(!frictionless.is_jam(&s));
        assert_eq!(r.label(), "friction(mu=0.2)");
    }

    #[test]
    fn bad_specs_are_refused_with_the_rule_broken() {
        let e = Rule::parse("papr").unwrap_err().to_string();
        let known: Vec<&str> = rules().unwrap().keys().copied().collect();
        assert!(
            e.contains(&format!("unknown; known rules: {}", known.join(", "))),
            "{e}"
        );
        let e = Rule::parse("friction:nu=1").unwrap_err().to_string();
        assert!(
            e.contains("unknown key (known keys of friction: mu)"),
            "{e}"
        );
        let e = Rule::parse("friction:mu=-1").unwrap_err().to_string();
        assert!(e.contains("must be between 0 and"), "{e}");
        let e = Rule::parse("friction:mu").unwrap_err().to_string();
        assert!(e.contains("must be key=value"), "{e}");
        let e = Rule::parse("paper:mu=1").unwrap_err().to_string();
        assert!(e.contains("paper takes no parameters"), "{e}");
        let e = Rule::parse("friction:mu=0.2,mu=0.3")
            .unwrap_err()
            .to_string();
        assert!(e.contains("parameter `mu`: is given twice"), "{e}");
        for spec in ["friction:", "friction:mu=0.2,", "friction:,,,"] {
            let e = Rule::parse(spec).unwrap_err().to_string();
            assert!(e.contains("is empty"), "{spec}: {e}");
        }
        let e = Rule::parse("friction:mu=1e300").unwrap_err().to_string();
        assert!(e.contains("(got 1e300)"), "{e}");
        assert!(e.len() < 200, "{e}");
        let tiny = Rule::parse("friction:mu=1e-300").unwrap();
        assert_eq!(tiny.label(), "friction(mu=1e-300)");
    }
}
