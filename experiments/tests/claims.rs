//! The claims ledger's verdicts move with its inputs: a verdict computed from the results is
//! never a constant. Each case runs the ledger on a few claims at reduced counts.
#![allow(clippy::unwrap_used, reason = "tests")]

use study::claims::{Ledger, Verdict};

/// The verdicts (as run, then under each reading) of claim `id`, the ledger run on it alone
/// with `sets` beside reduced counts (`trials` per cell).
fn verdicts(id: &str, trials: &str, sets: &[(&str, &str)]) -> Vec<Verdict> {
    experiments::link();
    let mut all = vec![("only", id), ("trials", trials), ("runs", "2")];
    all.extend_from_slice(sets);
    let outcome = experiments::outcome("claims", 2025, 2, &all).unwrap();
    let ledger: Ledger = serde_json::from_value(outcome.data["results"].clone()).unwrap();
    assert_eq!(ledger.claims.len(), 1, "only {id} was asked for");
    let row = &ledger.claims[0];
    assert_eq!(row.id, id);
    assert_eq!(
        row.under[0], row.judged.verdict,
        "the first reading is as run"
    );
    row.under.clone()
}

/// Gears made without error tolerate the whole of Table 4's grid: m2-n1 then tolerates more
/// than the paper's 0.04, so the claim on the random error no longer holds as a whole.
#[test]
fn the_random_error_claim_moves_with_the_hypothesis() {
    let edmunds = verdicts("C7", "20", &[]);
    let ideal = verdicts("C7", "20", &[("hypothesis", "ideal")]);
    assert_eq!(edmunds[0], Verdict::Holds, "{edmunds:?}");
    assert_eq!(ideal[0], Verdict::HoldsInPart, "{ideal:?}");
}

/// With no Case's errors there is no Table 3 of Cases to judge.
#[test]
fn the_cases_claim_moves_with_the_hypothesis() {
    assert_eq!(verdicts("C5", "10", &[])[0], Verdict::Holds);
    assert_eq!(
        verdicts("C5", "10", &[("hypothesis", "ideal")])[0],
        Verdict::NotTestable
    );
}

/// An unknown claim is refused, naming it.
#[test]
fn an_unknown_claim_is_refused() {
    experiments::link();
    let e = experiments::outcome("claims", 2025, 1, &[("only", "C99")]).unwrap_err();
    assert!(e.to_string().contains("C99"), "{e}");
}
