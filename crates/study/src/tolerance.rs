//! The paper's tolerance rule (section 5): a mesh tolerates an error when at most `rule` % of its
//! trials jam (1 % of 200 = 2), and its largest tolerable error is the largest grid value up to
//! which every grid value passes. Also the grids of Tables 4 and 5 as parameters.

use registry::{Param, RunError};

/// A random error of a grid or search (fraction of the pitch): 0 to the hypotheses' limit
/// [`hypotheses::MAX_RANDOM`], checked with the parameter the user set rather than when a gear
/// is made.
pub const RANDOM_KIND: registry::Kind = registry::Kind::number(
    0.0,
    hypotheses::MAX_RANDOM,
    "of the pitch: with a larger spread neighbouring tips cross in some draws",
);

/// Start of the random-error grid (Table 4's first row).
pub const RANDOM_FROM: Param = Param {
    name: "random_from",
    default: "0.035",
    unit: "pitch",
    help: "smallest random error (sd of a tip's displacement / pitch 360/N); the paper's Table 4: 0.035",
    kind: RANDOM_KIND,
    reading: false,
};

/// End of the random-error grid.
pub const RANDOM_TO: Param = Param {
    name: "random_to",
    default: "0.065",
    unit: "pitch",
    help: "largest random error of the grid (the paper: 0.065)",
    kind: RANDOM_KIND,
    reading: false,
};

/// Step of the random-error grid.
pub const RANDOM_STEP: Param = Param {
    name: "random_step",
    default: "0.005",
    unit: "pitch",
    help: "step of the random-error grid (the paper: 0.005)",
    kind: registry::Kind::positive(f64::INFINITY, ""),
    reading: false,
};

/// Start of the systematic-error grid (Table 5's first row).
pub const SYSTEMATIC_FROM: Param = Param {
    name: "systematic_from",
    default: "0.1",
    unit: "deg",
    help: "smallest systematic amplitude A of the grid (the paper's Table 5: 0.1)",
    kind: registry::Kind::number(0.0, f64::INFINITY, ""),
    reading: false,
};

/// End of the systematic-error grid.
pub const SYSTEMATIC_TO: Param = Param {
    name: "systematic_to",
    default: "1.1",
    unit: "deg",
    help: "largest systematic amplitude of the grid (the paper: 1.1)",
    kind: registry::Kind::ANY_NUMBER,
    reading: false,
};

/// Step of the systematic-error grid.
pub const SYSTEMATIC_STEP: Param = Param {
    name: "systematic_step",
    default: "0.1",
    unit: "deg",
    help: "step of the systematic grid (the paper: 0.1)",
    kind: registry::Kind::positive(f64::INFINITY, ""),
    reading: false,
};

/// The failure threshold.
pub const RULE: Param = Param {
    name: "rule",
    default: "1",
    unit: "%",
    help: "a value is tolerable when at most this share of trials jam (the paper: 1 %, 2 of 200)",
    kind: registry::Kind::number(0.0, 100.0, "a percentage"),
    reading: false,
};

/// The random-error grid (Table 4's rows).
pub const RANDOM_GRID: &[Param] = &[RANDOM_FROM, RANDOM_TO, RANDOM_STEP];

/// The systematic-error grid (Table 5's rows).
pub const SYSTEMATIC_GRID: &[Param] = &[SYSTEMATIC_FROM, SYSTEMATIC_TO, SYSTEMATIC_STEP];

/// The random-error grid as typed ([`RANDOM_GRID`], Table 4's rows).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct RandomGrid {
    /// First random error, of the pitch ([`RANDOM_FROM`]).
    #[param(RANDOM_FROM)]
    pub random_from: f64,
    /// Last random error ([`RANDOM_TO`]).
    #[param(RANDOM_TO)]
    pub random_to: f64,
    /// Step between rows ([`RANDOM_STEP`]).
    #[param(RANDOM_STEP)]
    pub random_step: f64,
}

/// The systematic-error grid as typed ([`SYSTEMATIC_GRID`], Table 5's rows).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct SystematicGrid {
    /// First systematic error, degrees ([`SYSTEMATIC_FROM`]).
    #[param(SYSTEMATIC_FROM)]
    pub systematic_from: f64,
    /// Last systematic error ([`SYSTEMATIC_TO`]).
    #[param(SYSTEMATIC_TO)]
    pub systematic_to: f64,
    /// Step between rows ([`SYSTEMATIC_STEP`]).
    #[param(SYSTEMATIC_STEP)]
    pub systematic_step: f64,
}

impl RandomGrid {
    /// The grid's values ([`grid`]), the parameter the user set named in a refusal.
    pub fn values<S: registry::Settings>(&self, whole: &S) -> Result<Vec<f64>, RunError> {
        grid(
            (&RANDOM_FROM, self.random_from),
            (&RANDOM_TO, self.random_to),
            (&RANDOM_STEP, self.random_step),
            &changed_names(whole),
        )
    }
}

impl SystematicGrid {
    /// The grid's values ([`grid`]), the parameter the user set named in a refusal.
    pub fn values<S: registry::Settings>(&self, whole: &S) -> Result<Vec<f64>, RunError> {
        grid(
            (&SYSTEMATIC_FROM, self.systematic_from),
            (&SYSTEMATIC_TO, self.systematic_to),
            (&SYSTEMATIC_STEP, self.systematic_step),
            &changed_names(whole),
        )
    }
}

/// The names of the parameters of `whole` that differ from their defaults.
fn changed_names<S: registry::Settings>(whole: &S) -> Vec<&'static str> {
    let mut changed = Vec::new();
    whole.changed(&mut changed);
    changed.into_iter().map(|(p, _)| p.name).collect()
}

/// Jams allowed among `trials` trials under a rule of `rule_percent` %: ⌊rule·trials/100⌋.
pub fn allowed_jams(trials: u64, rule_percent: f64) -> u64 {
    let x = rule_percent * trials as f64 / 100.0;
    // A hair above, so 1 % of 200 is 2 even if the product rounds just below.
    (x + 1e-9).floor().max(0.0) as u64
}

/// The paper's failure rule, in % of the trials (section 5: "a failure rate threshold of 1 %
/// ... in 200 trials, a maximum of 2 jams is acceptable").
pub const PAPER_RULE_PERCENT: f64 = 1.0;

/// Does a cell of `trials` trials with `jams` and `disengagements` keep the failure rule of
/// `rule_percent` % ([`allowed_jams`]: 2 of 200 at 1 %)? The paper's text states the rule for
/// jams and its derived E. max row tolerates 2 jams of 200 (m2-n1 at 0.035); its captions shade
/// "cells with one or fewer trials showing jamming or disengagement", so a disengagement counts
/// against a cell as a jam does: both counts must be within the rule.
pub fn keeps_rule(jams: u64, disengagements: u64, trials: u64, rule_percent: f64) -> bool {
    let allowed = allowed_jams(trials, rule_percent);
    jams <= allowed && disengagements <= allowed
}

/// The largest grid value `e` such that every grid value up to `e` has at most
/// [`allowed_jams`] jams; `None` when even the smallest fails. `grid` holds (value, jams) in any
/// order.
pub fn largest_tolerable(grid: &[(f64, u64)], trials: u64, rule_percent: f64) -> Option<f64> {
    let allowed = allowed_jams(trials, rule_percent);
    let mut sorted = grid.to_vec();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut best = None;
    for (e, jams) in sorted {
        if jams > allowed {
            break;
        }
        best = Some(e);
    }
    best
}

/// The values from..=to by step, each given with the parameter it was read from, checked:
/// from >= 0, step > 0, from <= to, at most 1000 values; a refusal names the parameter the user
/// set, as `changed` (the names of the run's parameters set to other than their default) says.
/// Each value is rounded to nine decimals, so 0.1 + 9 × 0.1 is 1.0 and the same grid gives the
/// same cells in every experiment.
pub fn grid(
    (from, a): (&Param, f64),
    (to, b): (&Param, f64),
    (step, s): (&Param, f64),
    changed: &[&str],
) -> Result<Vec<f64>, RunError> {
    let short = registry::fmt_number;
    if a > b {
        // Name the one the user set: `to` below the default `from`, or `from` above `to`.
        let to_set = changed.contains(&to.name);
        let (field, rule) = if to_set {
            (
                to.name,
                format!(
                    "must be at least {} = {} (got {})",
                    from.name,
                    short(a),
                    short(b)
                ),
            )
        } else {
            (
                from.name,
                format!(
                    "must be at most {} = {} (got {})",
                    to.name,
                    short(b),
                    short(a)
                ),
            )
        };
        return Err(RunError::bad("--set", field, rule));
    }
    let n = ((b - a) / s + 1e-9).floor();
    if n >= 1000.0 {
        // Name the one the user set: the step, or else the end (or start) they moved.
        let set = |p: &Param| changed.contains(&p.name);
        let field = if set(step) || !(set(to) || set(from)) {
            step.name
        } else if set(to) {
            to.name
        } else {
            from.name
        };
        return Err(RunError::bad(
            "--set",
            field,
            format!(
                "gives more than 1000 grid values from {} = {} to {} = {} by {} = {}",
                from.name,
                short(a),
                to.name,
                short(b),
                step.name,
                short(s)
            ),
        ));
    }
    Ok((0..=n as u64)
        .map(|i| ((a + i as f64 * s) * 1e9).round() / 1e9)
        .collect())
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn one_percent_of_200_is_two() {
        assert_eq!(allowed_jams(200, 1.0), 2);
        assert_eq!(allowed_jams(200, 5.0), 10);
        assert_eq!(allowed_jams(20, 1.0), 0);
        assert_eq!(allowed_jams(20, 5.0), 1);
        assert_eq!(allowed_jams(10, 0.0), 0);
        assert_eq!(allowed_jams(7, 100.0), 7);
    }

    #[test]
    fn largest_value_up_to_which_every_value_passes() {
        // The paper's Table 4, column b2-c1: 0/0/0/1/1/17/20 jams -> 0.055.
        let col = [
            (0.035, 0),
            (0.040, 0),
            (0.045, 0),
            (0.050, 1),
            (0.055, 1),
            (0.060, 17),
            (0.065, 20),
        ];
        assert_eq!(largest_tolerable(&col, 200, 1.0), Some(0.055));
        // n2-o1: 0, 0, 0, 1, 0, 4, 17 -> 0.055; m2-n1: 2, 0, 11 -> 0.040.
        let n2 = [
            (0.035, 0),
            (0.04, 0),
            (0.045, 0),
            (0.05, 1),
            (0.055, 0),
            (0.06, 4),
        ];
        assert_eq!(largest_tolerable(&n2, 200, 1.0), Some(0.055));
        let m2 = [(0.035, 2), (0.04, 0), (0.045, 11), (0.05, 20)];
        assert_eq!(largest_tolerable(&m2, 200, 1.0), Some(0.04));
        // A failure hides passes above it; order of the input does not matter.
        let gap = [(0.05, 0), (0.04, 3), (0.035, 0)];
        assert_eq!(largest_tolerable(&gap, 200, 1.0), Some(0.035));
        // Even the first fails.
        assert_eq!(largest_tolerable(&[(0.035, 3)], 200, 1.0), None);
        assert_eq!(largest_tolerable(&[], 200, 1.0), None);
        // A looser rule moves it up.
        assert_eq!(largest_tolerable(&col, 200, 10.0), Some(0.065));
    }
}
