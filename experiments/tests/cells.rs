//! How a per-mesh table's cells compare with the paper's column when a run departs from the
//! paper's inputs: the presentation's marks (`presentation::cells`) as the experiments use them.
#![allow(clippy::unwrap_used, reason = "tests")]

/// A run off the paper's inputs (here G = 50 %, where the paper's Table 3 is at 40 %) is not
/// compared with the paper's column: no `*`, every cell `†`, a note naming the input, and
/// no tally; a run that changes only readings of the paper (the event rule, the drive) is.
#[test]
fn a_run_off_the_papers_inputs_is_not_compared_with_its_column() {
    let off = experiments::run("table3", 2025, 2, &[("trials", "3"), ("clearance", "50")]).unwrap();
    let t = &off.tables[0];
    let cells: Vec<&String> = t.rows.iter().flat_map(|r| &r[1..]).collect();
    assert!(
        cells.iter().all(|c| c.ends_with('†') && !c.contains('*')),
        "{cells:?}"
    );
    assert!(
        t.notes
            .iter()
            .any(|n| n.starts_with("`†`: not compared") && n.contains("clearance=50")),
        "{:?}",
        t.notes
    );
    let agreement = off.agreement.unwrap();
    assert_eq!((agreement.consistent, agreement.differ), (0, 0));

    // A reading of the paper (the event rule, the drive) is no departure; the trial count is.
    #[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize, registry::Settings)]
    struct Cells {
        #[param(study::grids::TRIALS)]
        trials: u64,
        #[group]
        events: study::events::EventParams,
        #[group]
        drive: study::drive::DriveParams,
    }
    let off_paper = |k: &str, v: &str| {
        let (_, ctx) = experiments::context("table3", 2025, 1, &[(k, v)]).unwrap();
        let s = <Cells as registry::Settings>::read(&ctx).unwrap();
        setting_groups::typed::off_paper_inputs(&s)
    };
    assert!(off_paper("events", "strict").is_empty());
    assert!(off_paper("drive", "other").is_empty());
    assert_eq!(off_paper("trials", "40"), ["trials=40"]);
}
