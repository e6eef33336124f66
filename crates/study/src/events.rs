//! The event rule of the experiments that count jams and disengagements: the `events` parameter
//! (`--set events=NAME`, `cargo xtask rules` lists them).

use registry::{Param, RunError};
use rules::Rule;

/// The `events` parameter.
pub const PARAM: Param = Param {
    name: "events",
    default: rules::DEFAULT,
    unit: "",
    help: "event rule: which events count as jams and disengagements, NAME or NAME:key=value (cargo xtask rules lists them)",
    kind: registry::Kind::Text,
    reading: true,
};

/// The event setting group: the event rule.
pub const GROUP: &[Param] = &[PARAM];

/// The event group as typed ([`GROUP`]): the event rule as named.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct EventParams {
    /// The rule, `NAME` or `NAME:key=value` ([`PARAM`]).
    #[param(PARAM)]
    pub events: String,
}

impl EventParams {
    /// The rule it names ([`parse`]).
    pub fn rule(&self) -> Result<Rule, RunError> {
        parse(&self.events)
    }
}

/// The rule `spec` names (the `events` parameter's value).
pub fn parse(spec: &str) -> Result<Rule, RunError> {
    Rule::parse(spec).map_err(|e| RunError::bad("--set", PARAM.name, e.to_string()))
}

/// The default rule, for experiments that count by other means and declare no `events`.
pub fn default_rule() -> Result<Rule, RunError> {
    Rule::parse(rules::DEFAULT).map_err(|e| RunError::Internal(e.to_string()))
}

/// (jams, disengagements) of a run, as `rule` counts them.
pub fn counts(rule: &Rule, traj: &contact::Trajectory) -> (usize, usize) {
    let events = traj.events();
    (
        events.iter().filter(|e| rule.is_jam(e)).count(),
        events.iter().filter(|e| rule.is_disengagement(e)).count(),
    )
}

/// `report` with every table's title naming the event rule it was counted with and, for an
/// experiment of per-mesh trials, which gear drove and (unless a trial counts its whole turn,
/// the paper's protocol) where a trial's counting ended: so the printed table, `table.md` and
/// `tables.json` all say it.
pub fn label(
    rule: &Rule,
    protocol: Option<(crate::drive::Drive, crate::trial_end::End)>,
    mut report: registry::Report,
) -> registry::Report {
    let tag = match protocol {
        Some((d, crate::trial_end::End::Turn)) => {
            format!("[events: {}; drive: {}]", rule.label(), d.name())
        }
        Some((d, end)) => format!(
            "[events: {}; drive: {}; end: {}]",
            rule.label(),
            d.name(),
            end.name()
        ),
        None => format!("[events: {}]", rule.label()),
    };
    for t in &mut report.tables {
        t.title = format!("{} {tag}", t.title);
    }
    report
}
