//! The paper's claims judged against our results: each judge takes typed results (ours, and the
//! paper's own numbers laid out the same way where the claim rests on a table) and says whether
//! the claim holds, with our figure, its uncertainty and the reason in one line.
//!
//! A judge computes; it never reads a verdict, a number or a list that decides it from anywhere
//! but its arguments, so that a change of input (a hypothesis, a smaller E. max, a reading of the
//! paper) moves the verdict it should.

use serde::{Deserialize, Serialize};

pub mod cells;
pub mod mechanism;
pub mod pointers;
pub mod tolerances;

/// What our results say of a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Verdict {
    /// Our results support the claim as stated.
    Holds,
    /// Some of its parts hold and some do not, or it holds only in direction, not in size.
    HoldsInPart,
    /// Our results contradict it.
    Differs,
    /// Our inputs cannot test it (the data it rests on is not available).
    NotTestable,
}

impl Verdict {
    /// The verdict in words, as the ledger prints it.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::HoldsInPart => "holds in part",
            Verdict::Differs => "differs",
            Verdict::NotTestable => "not testable",
        }
    }

    /// `holds` if every part holds, `differs` if none does, `holds in part` otherwise; parts that
    /// cannot be tested are left out (all of them: not testable).
    pub fn of_parts(parts: &[Verdict]) -> Verdict {
        let tested: Vec<Verdict> = parts
            .iter()
            .copied()
            .filter(|v| *v != Verdict::NotTestable)
            .collect();
        if tested.is_empty() {
            Verdict::NotTestable
        } else if tested.iter().all(|v| *v == Verdict::Holds) {
            Verdict::Holds
        } else if tested.iter().all(|v| *v == Verdict::Differs) {
            Verdict::Differs
        } else {
            Verdict::HoldsInPart
        }
    }

    /// `holds` when `yes`, else `differs`.
    pub fn from_bool(yes: bool) -> Verdict {
        if yes {
            Verdict::Holds
        } else {
            Verdict::Differs
        }
    }
}

/// A claim judged: the verdict, our figure (with its uncertainty) and the paper's figure computed
/// the same way, and the reason in one line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Judged {
    /// What our results say of the claim.
    pub verdict: Verdict,
    /// Our figure, as the ledger prints it.
    pub ours: String,
    /// The paper's figure, as the ledger prints it.
    pub paper: String,
    /// Why, in one line.
    pub reason: String,
}

/// One claim judged under every reading.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClaimRow {
    /// `C1` ... `C12`.
    pub id: String,
    /// The claim in our words.
    pub words: String,
    /// Where the paper makes it.
    pub place: String,
    /// As run (the paper's defaults).
    pub judged: Judged,
    /// Its verdict under each reading, in [`Ledger::readings`]' order.
    pub under: Vec<Verdict>,
}

/// One mesh's margin under Case B, for the drawing of the train.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshStanding {
    /// The mesh.
    pub mesh: String,
    /// Trials with a jam or a disengagement, of `trials`, under Case B at G = 40 %.
    pub failures: u64,
    /// Trials run.
    pub trials: u64,
    /// Whether the mesh keeps the paper's 1 % rule.
    pub keeps_rule: bool,
}

/// The ledger (`claims`' results): every claim judged, the readings' names, and Case B's meshes
/// for the drawing of the train.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ledger {
    /// The claims in order.
    pub claims: Vec<ClaimRow>,
    /// The readings, the columns of [`ClaimRow::under`].
    pub readings: Vec<String>,
    /// Case B's meshes as run.
    pub case_b: Vec<MeshStanding>,
    /// Table 5's tolerances as run (where the ledger judged them) and the systematic split they
    /// ran at: drawn per gear in mm and degrees beside the verdicts.
    #[serde(default)]
    pub tolerances: Option<(crate::results::DerivedTolerances, f64)>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_make_a_verdict() {
        use Verdict::*;
        assert_eq!(Verdict::of_parts(&[Holds, Holds]), Holds);
        assert_eq!(Verdict::of_parts(&[Holds, Differs]), HoldsInPart);
        assert_eq!(Verdict::of_parts(&[Differs, NotTestable]), Differs);
        assert_eq!(Verdict::of_parts(&[NotTestable]), NotTestable);
        assert_eq!(Verdict::of_parts(&[HoldsInPart, Holds]), HoldsInPart);
    }
}
