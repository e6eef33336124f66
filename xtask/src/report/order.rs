//! The order of the report's sections: the paper's items in the order the paper gives them,
//! then the studies beyond it, then anything else by id.

/// The experiments that reproduce an item of the paper, in the order the paper presents them
/// (after the ledger of its claims, which opens the page):
/// section 2 (Figures 2 and 3, and any pair of gears), section 3 (Figure 4, Table 1), section 4
/// (Table 2, Figure 5), section 5 (Tables 3-5, Figure 6, Table 6, the 30-run study), then
/// Appendix II (Figure IV, the clearance limits, Figures V_A and V_B, Table I).
pub(super) const PAPER_ORDER: [&str; 18] = [
    "claims",
    "fig2",
    "fig3",
    "pair",
    "fig4",
    "table1",
    "table2",
    "fig5",
    "table3",
    "table4",
    "table5",
    "fig6",
    "table6",
    "failure",
    "figIV",
    "clearance",
    "fig-events",
    "tableI",
];

/// The studies beyond the paper, in the order the README discusses them.
pub(super) const BEYOND_ORDER: [&str; 9] = [
    "tolerance",
    "clearance-design",
    "lunar-anomaly",
    "sensitivity",
    "event-rules",
    "jam-readings",
    "motion-models",
    "sigma-causes",
    "contact-tolerance",
];

/// `ids` in the report's order: [`PAPER_ORDER`], then [`BEYOND_ORDER`], then any other (an
/// experiment added since, a folder of results no experiment of this build owns) by id.
pub(super) fn in_paper_order(mut ids: Vec<String>) -> Vec<String> {
    let rank = |id: &str| {
        PAPER_ORDER
            .iter()
            .chain(BEYOND_ORDER.iter())
            .position(|p| *p == id)
            .unwrap_or(usize::MAX)
    };
    ids.sort_by(|a, b| rank(a).cmp(&rank(b)).then_with(|| a.cmp(b)));
    ids
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    /// Every listed id is a registered experiment, listed once; every experiment that
    /// reproduces or reads a table or figure of the paper has its place; any other (a
    /// study added as a plugin file, with no edit here) lands after the listed ones, by id, as
    /// does a folder no experiment of this build owns.
    #[test]
    fn every_paper_item_has_its_place() {
        experiments::link();
        let exps = registry::experiments().unwrap();
        let listed: Vec<&str> = PAPER_ORDER.iter().chain(&BEYOND_ORDER).copied().collect();
        let mut unique = listed.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), listed.len(), "an id listed twice");
        for id in &listed {
            assert!(exps.contains_key(id), "{id} is listed but not registered");
        }
        for (id, e) in &exps {
            let of_the_paper = (e.paper_item.starts_with("Table")
                || e.paper_item.starts_with("Figure"))
                && !e.paper_item.contains("beyond");
            if of_the_paper {
                assert!(listed.contains(id), "{id} ({}) has no place", e.paper_item);
            }
        }
        let ids: Vec<String> = ["zzz-new", "table3", "event-rules", "fig2", "tableI"]
            .iter()
            .map(|s| (*s).to_owned())
            .collect();
        assert_eq!(
            in_paper_order(ids),
            ["fig2", "table3", "tableI", "event-rules", "zzz-new"]
        );
    }
}
