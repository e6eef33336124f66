//! The order of the report's sections: each experiment's declared place
//! ([`registry::Place`]): the paper's items in the order the paper gives them, then the studies
//! beyond it, then anything else (a folder of results no experiment of this build owns) by id.

use registry::Entry;

/// `ids` in the report's order: by the place each registered experiment declares, then any
/// other id by name.
pub(super) fn in_paper_order(
    mut ids: Vec<String>,
    exps: &std::collections::BTreeMap<&'static str, &'static Entry>,
) -> Vec<String> {
    let rank = |id: &str| exps.get(id).map(|e| e.place);
    // `None` (no experiment of this build) after every place.
    let key = |id: &str| (rank(id).is_none(), rank(id));
    ids.sort_by(|a, b| key(a).cmp(&key(b)).then_with(|| a.cmp(b)));
    ids
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use registry::Place;

    /// Every experiment's place is its own (no two share one); the ledger of claims opens the
    /// page, the paper's items come before the studies beyond it, and a folder no experiment owns
    /// lands after all, by id.
    #[test]
    fn every_experiment_has_its_own_place() {
        experiments::link();
        let exps = registry::experiments().unwrap();
        let mut places: Vec<Place> = exps.values().map(|e| e.place).collect();
        places.sort_unstable();
        places.dedup();
        assert_eq!(places.len(), exps.len(), "two experiments share a place");
        let ids: Vec<String> = [
            "zzz-new",
            "table3",
            "event-rules",
            "fig2",
            "tableI",
            "claims",
        ]
        .iter()
        .map(|s| (*s).to_owned())
        .collect();
        assert_eq!(
            in_paper_order(ids, &exps),
            [
                "claims",
                "fig2",
                "table3",
                "tableI",
                "event-rules",
                "zzz-new"
            ]
        );
    }
}
