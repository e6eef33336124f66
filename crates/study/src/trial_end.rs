//! Where a pair trial's counting ends: the `end` setting of the per-mesh jam tables.
//!
//! The paper's protocol (section 5): "Our program was designed to complete one full rotation of
//! the gear with the most teeth, allowing the driven gear to rotate freely if a jam or
//! disengagement was detected until movement was possible again. Once movement resumed, the
//! pair continued operating, searching for further instances of jamming or disengagement." So a
//! trial runs its whole turn and counts every kind of failure it meets (`turn`, the default). In
//! some of its cells, though (Case D: e4-f1 at every clearance, d2-e2 at 40 %, m3-e3 at every
//! clearance), its jams and disengagements add up to exactly 200, as if a trial had stopped at
//! its first failure. The other settings count that way, as readings to compare.

use registry::{Param, RunError};

/// Where a trial stops counting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum End {
    /// The whole turn: every failure of the trial counts (the paper's stated protocol).
    #[default]
    Turn,
    /// The first event counted as a jam or a disengagement: only that one counts.
    FirstEvent,
    /// The first disengagement: jams count until then, and that disengagement.
    FirstDisengagement,
}

impl End {
    /// Every setting, in the order tables list them.
    pub const ALL: [End; 3] = [End::Turn, End::FirstEvent, End::FirstDisengagement];

    /// The setting's name, as `--set end=NAME` takes it.
    pub fn name(self) -> &'static str {
        match self {
            End::Turn => "turn",
            End::FirstEvent => "first-event",
            End::FirstDisengagement => "first-disengagement",
        }
    }

    /// The setting named `text`.
    ///
    /// Errors: a name that is not one of [`End::ALL`], naming the parameter.
    pub fn parse(text: &str) -> Result<End, RunError> {
        End::ALL
            .into_iter()
            .find(|e| e.name() == text.trim())
            .ok_or_else(|| {
                RunError::bad(
                    "--set",
                    PARAM.name,
                    format!("must be turn, first-event or first-disengagement (got `{text}`)"),
                )
            })
    }
}

/// A trial's tally as its events come, in order: whether it has jammed and disengaged, and
/// whether its counting has ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Tally {
    /// A jam counted.
    pub jam: bool,
    /// A disengagement counted.
    pub disengaged: bool,
    /// Nothing later can change the tally.
    pub closed: bool,
}

impl Tally {
    /// The tally after one more event, `jam` and `disengagement` being what the rule counts it
    /// as, under `end`.
    pub fn after(mut self, end: End, jam: bool, disengagement: bool) -> Tally {
        if self.closed || !(jam || disengagement) {
            return self;
        }
        self.jam |= jam;
        self.disengaged |= disengagement;
        self.closed = match end {
            End::Turn => self.jam && self.disengaged,
            End::FirstEvent => true,
            End::FirstDisengagement => self.disengaged,
        };
        self
    }
}

/// The `end` parameter.
pub const PARAM: Param = Param {
    name: "end",
    default: "turn",
    unit: "",
    help: "where a pair trial's counting ends: `turn` (its whole turn, every failure counted: the paper's protocol), `first-event` (only its first jam or disengagement counts), `first-disengagement` (jams until its first disengagement, and that); a reading to compare, as some of the paper's Case D cells add up to exactly 200",
    kind: registry::Kind::Choice(&["turn", "first-event", "first-disengagement"]),
    reading: true,
};

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn each_end_counts_what_it_says() {
        // Events in order: a jam, a disengagement, a jam.
        let run = |end| {
            [(true, false), (false, true), (true, false)]
                .into_iter()
                .fold(Tally::default(), |t, (j, d)| t.after(end, j, d))
        };
        let turn = run(End::Turn);
        assert!(turn.jam && turn.disengaged && turn.closed);
        let first = run(End::FirstEvent);
        assert!(first.jam && !first.disengaged && first.closed);
        let until_dis = run(End::FirstDisengagement);
        assert!(until_dis.jam && until_dis.disengaged && until_dis.closed);
        // A disengagement first: under first-disengagement the later jam does not count.
        let dis_first = [(false, true), (true, false)]
            .into_iter()
            .fold(Tally::default(), |t, (j, d)| {
                t.after(End::FirstDisengagement, j, d)
            });
        assert!(!dis_first.jam && dis_first.disengaged);
        // Events counted as neither change nothing.
        assert_eq!(
            Tally::default().after(End::FirstEvent, false, false),
            Tally::default()
        );
        for e in End::ALL {
            assert_eq!(End::parse(e.name()).unwrap(), e);
        }
        assert_eq!(End::parse("first").unwrap_err().exit_code(), 2);
    }
}
