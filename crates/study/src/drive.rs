//! Which gear of a mesh drives a pair trial: the `drive` setting of the per-mesh jam tables.
//!
//! The paper names each mesh driver first (b2-c1: b2 drives c1), as the train runs from the
//! main wheel. Its jam counts lie between what our exact solver counts with the listed driver
//! driving and with the other gear driving, mesh by mesh (`event-rules` shows both), so the
//! setting lets every per-mesh table run either way, or draw the driver per trial.

use registry::{Param, RunError};

/// Which gear drives the trials of a cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub enum Drive {
    /// The mesh's listed driver (b2 in b2-c1), as the train runs: the default.
    #[default]
    Listed,
    /// The listed driven gear drives, both gears still turning their own way
    /// ([`contact::Mesh::other_driving`]); it starts at the same share of its own pitch as the
    /// listed driver would of its, and turns until the larger gear has turned once.
    Other,
    /// Each trial draws which gear drives, a fair coin from the trial's own stream after its
    /// gears and initial angle (so every other draw is the same as under `listed`).
    Either,
}

impl Drive {
    /// Every setting, in the order tables list them.
    pub const ALL: [Drive; 3] = [Drive::Listed, Drive::Other, Drive::Either];

    /// The setting's name, as `--set drive=NAME` takes it.
    pub fn name(self) -> &'static str {
        match self {
            Drive::Listed => "listed",
            Drive::Other => "other",
            Drive::Either => "either",
        }
    }

    /// The setting named `text`.
    ///
    /// Errors: a name that is not one of [`Drive::ALL`], naming the parameter.
    pub fn parse(text: &str) -> Result<Drive, RunError> {
        Drive::ALL
            .into_iter()
            .find(|d| d.name() == text.trim())
            .ok_or_else(|| {
                RunError::bad(
                    "--set",
                    PARAM.name,
                    format!("must be listed, other or either (got `{text}`)"),
                )
            })
    }

    /// The gear that drives a trial whose coin fell on `coin` (the coin is read under
    /// [`Drive::Either`] only).
    pub fn driver(self, coin: Driver) -> Driver {
        match self {
            Drive::Listed => Driver::Listed,
            Drive::Other => Driver::Other,
            Drive::Either => coin,
        }
    }
}

/// The gear that drove one trial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Driver {
    /// The mesh's listed driver.
    Listed,
    /// The mesh's listed driven gear.
    Other,
}

impl Driver {
    /// Both, listed first.
    pub const BOTH: [Driver; 2] = [Driver::Listed, Driver::Other];
}

/// The `drive` parameter.
pub const PARAM: Param = Param {
    name: "drive",
    default: "listed",
    unit: "",
    help: "which gear of each mesh drives its trials: `listed` (the first gear of the mesh's name, as the train runs), `other` (the second, both gears still turning their own way), or `either` (drawn per trial, a fair coin from the trial's own stream after its gears and initial angle)",
    kind: registry::Kind::Choice(&["listed", "other", "either"]),
    reading: true,
};

/// The pair-trial protocol group of the per-mesh tables: which gear drives, and where a
/// trial's counting ends ([`crate::trial_end`]).
pub const GROUP: &[Param] = &[PARAM, crate::trial_end::PARAM];

/// The pair-trial protocol group as typed ([`GROUP`]): which gear drives, where counting ends.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
pub struct DriveParams {
    /// `listed`, `other` or `either` ([`PARAM`]).
    #[param(PARAM)]
    pub drive: String,
    /// `turn`, `first-event` or `first-disengagement` ([`crate::trial_end::PARAM`]).
    #[param(crate::trial_end::PARAM)]
    pub end: String,
}

impl DriveParams {
    /// Which gear drives.
    pub fn drive(&self) -> Result<Drive, RunError> {
        Drive::parse(&self.drive)
    }

    /// Where a trial's counting ends.
    pub fn end(&self) -> Result<crate::trial_end::End, RunError> {
        crate::trial_end::End::parse(&self.end)
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn names_parse_back_and_others_are_refused() {
        for d in Drive::ALL {
            assert_eq!(Drive::parse(d.name()).unwrap(), d);
        }
        let e = Drive::parse("driven").unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("drive"), "{e}");
        assert_eq!(PARAM.default, Drive::default().name());
    }

    #[test]
    fn only_either_reads_the_coin() {
        for coin in Driver::BOTH {
            assert_eq!(Drive::Listed.driver(coin), Driver::Listed);
            assert_eq!(Drive::Other.driver(coin), Driver::Other);
            assert_eq!(Drive::Either.driver(coin), coin);
        }
    }
}
