//! Tables 3, 4 and 5 run on the cosmos gearings by the same plugins (`--gearing
//! freeth2021-cosmos`): every mesh of the display has its counts, the paper's counts are not
//! compared with inputs other than the paper's, and Table 5's agreement note counts only the
//! meshes the paper has a row for. Few trials: what is checked is what the tables print, not
//! the counts themselves.
#![allow(clippy::unwrap_used, reason = "tests")]

use registry::Report;
use train::Gearing;

/// Experiment `id` run on gearing `gearing` with `sets` besides, two threads.
fn run(id: &str, gearing: &str, sets: &[(&str, &str)]) -> Report {
    let mut all = vec![("gearing", gearing)];
    all.extend_from_slice(sets);
    let (exp, ctx) = experiments::context(id, 5, 2, &all).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| (exp.run)(&ctx, ctx.engine()))
        .unwrap_or_else(|e| panic!("{id} on {gearing}: {e}"))
        .report
}

/// The table's column headed `mesh` has a cell in every row, each `jams / disengagements`.
fn every_row_counts(report: &Report, table: usize, mesh: &str) {
    let t = &report.tables[table];
    let col = t
        .columns
        .iter()
        .position(|h| h == mesh)
        .unwrap_or_else(|| panic!("{}: no column {mesh}", t.title));
    assert!(!t.rows.is_empty(), "{}", t.title);
    for row in &t.rows {
        let cell = &row[col];
        assert!(
            cell.contains('/') && cell.chars().next().is_some_and(|c| c.is_ascii_digit()),
            "{}: {mesh}: `{cell}`",
            t.title
        );
    }
}

/// The display's meshes of the embedded gearing `name`.
fn cosmos_meshes(name: &str) -> Vec<String> {
    let meshes = study::cosmos::cosmos_meshes(&Gearing::builtin(name).unwrap());
    assert!(meshes.len() >= 10, "{name}: {meshes:?}");
    meshes
}

/// Whether the report's first table says it ran off the paper's inputs, naming the gearing.
fn labelled_off_paper(report: &Report, gearing: &str) -> bool {
    report.tables[0]
        .notes
        .iter()
        .any(|n| n.contains("not compared with the paper's counts") && n.contains(gearing))
}

#[test]
fn table3_prints_every_cosmos_mesh_of_both_gearings() {
    for gearing in ["freeth2021-cosmos", "freeth2012-cosmos"] {
        let report = run("table3", gearing, &[("trials", "2")]);
        for mesh in cosmos_meshes(gearing) {
            every_row_counts(&report, 0, &mesh);
        }
        // The back's meshes run too, beside the display's.
        every_row_counts(&report, 0, "b2-c1");
        assert!(labelled_off_paper(&report, gearing), "{gearing}");
        // Nothing is compared with the paper: no cell is tallied against it.
        let agreement = report.agreement.unwrap();
        assert_eq!(agreement.consistent + agreement.differ, 0, "{agreement:?}");
    }
}

#[test]
fn table4_prints_every_cosmos_mesh() {
    let gearing = "freeth2021-cosmos";
    let grid = [
        ("trials", "2"),
        ("random_from", "0.04"),
        ("random_to", "0.05"),
    ];
    let report = run("table4", gearing, &grid);
    for mesh in cosmos_meshes(gearing) {
        every_row_counts(&report, 0, &mesh);
    }
    assert!(labelled_off_paper(&report, gearing));
}

#[test]
fn table5_counts_agreement_over_the_papers_meshes_only() {
    let gearing = "freeth2012-cosmos";
    let sets = [
        ("trials", "2"),
        ("random_from", "0.05"),
        ("random_to", "0.06"),
        ("systematic_from", "0.5"),
        ("systematic_to", "0.6"),
    ];
    let report = run("table5", gearing, &sets);
    let t = &report.tables[0];
    for mesh in cosmos_meshes(gearing) {
        assert!(t.columns.contains(&mesh), "{}: no column {mesh}", t.title);
    }
    // The paper has a row for the back's meshes, the 2006 gearing's, and for none of the
    // display's.
    let back = Gearing::freeth2006();
    let papers: Vec<&str> = back
        .meshes()
        .iter()
        .map(|m| m.label.as_str())
        .filter(|m| presentation::emax::paper_random(m).is_some())
        .collect();
    assert!(!papers.is_empty());
    for mesh in cosmos_meshes(gearing) {
        assert!(presentation::emax::paper_random(&mesh).is_none(), "{mesh}");
    }
    let of = format!("of {} meshes", papers.len());
    assert!(
        t.notes
            .iter()
            .any(|n| n.contains("ours agree with the paper's row for") && n.contains(&of)),
        "{:?}",
        t.notes
    );
}

/// A cosmos gearing that cannot be read, or one with no cosmos, is refused before anything runs,
/// named by the setting that gave it (`--set gearings`) and the file.
#[test]
fn the_cosmos_study_names_a_bad_gearing_by_its_setting() {
    for (gearings, words) in [
        ("freeth2021-cosmos,no-such-file.ron", "no-such-file.ron"),
        ("freeth2006", "has no cosmos"),
    ] {
        let (exp, ctx) = experiments::context("cosmos", 5, 1, &[("gearings", gearings)]).unwrap();
        let e = (exp.run)(&ctx, ctx.engine()).err().unwrap().to_string();
        assert!(e.starts_with("--set gearings"), "{gearings}: {e}");
        assert!(e.contains(words), "{gearings}: {e}");
    }
}
