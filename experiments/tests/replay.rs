//! `replay`, run against the experiments that register cell grammars: a replayed trial is the one
//! its table counted, its pair file reruns it, its teeth pass the polygon oracle, and bad cells and
//! trials are named. (The replay crate cannot test this itself: the grammars are registered by
//! the experiments, which depend on it.)
#![allow(clippy::unwrap_used, reason = "tests")]

use contact::Solve;
use registry::{Context, Report};
use replay::{REPLAYABLE, ReplayedTrial, cell_spec, grammars, replay, trial_key};
use study::cell::{Purpose, rebuild, run_cells};
use study::drive::Driver;

fn ctx(id: &str, sets: &[(&str, &str)]) -> Context {
    experiments::context(id, 2025, 2, sets).unwrap().1
}

/// The first cell of the listing's row `row`: the count of failed trials.
fn listed(report: &Report, row: usize) -> u64 {
    report.tables[0].rows[row][1].parse().unwrap()
}

/// Trials in which the solver once let a tooth pair born under the resting driven gear pass
/// through it (Table 5's 0.7 deg row of e4-f1, trial 15: 0.21 mm of interpenetration; Table
/// I's C/70 k2-e6, trial 196): the polygon oracle finds their teeth apart to rounding.
#[test]
fn the_polygon_oracle_finds_replayed_teeth_apart() {
    for (id, cell, t) in [
        ("table5", "0.050/0.7/e4-f1", 15),
        ("tableI", "C/70/k2-e6", 196),
    ] {
        let report = replay(&ctx(id, &[]), id, cell, Some(t)).unwrap();
        let note = report.tables[0]
            .notes
            .iter()
            .find(|n| n.starts_with("Polygon oracle"))
            .unwrap();
        let depth: f64 = note
            .split("at most ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .unwrap()
            .parse()
            .unwrap();
        assert!(depth < 1e-9, "{id} {cell} trial {t}: {note}");
    }
}

#[test]
fn replayed_trials_are_the_ones_the_table_counted() {
    for (id, cell) in [
        ("table3", "B/m3-e3"),
        ("tableI", "D/70/l2-m1"),
        ("table4", "0.065/m2-n1"),
        ("table5", "0.050/0.7/e4-f1"),
    ] {
        // Fewer trials than a listing shows, so every failed one is named.
        let ctx = ctx(id, &[("trials", "16")]);
        let s = setting_groups::read::cells(&ctx, &study::grids::TRIALS).unwrap();
        let spec = cell_spec(&s, ctx.seed(), id, cell).unwrap();
        let counts = run_cells(
            ctx.engine(),
            s.gearing(),
            std::slice::from_ref(&spec),
            16,
            Purpose::Own,
        )
        .unwrap()[0];
        let listing = replay(&ctx, id, cell, None).unwrap();
        assert_eq!(listed(&listing, 0), counts.jams, "{id} {cell}: jams");
        assert_eq!(
            listed(&listing, 1),
            counts.disengagements,
            "{id} {cell}: disengagements"
        );
        assert!(
            counts.jams > 0,
            "{id} {cell}: the cell must jam for the test to show anything"
        );
        // Each trial the listing names as jammed replays as a jam, and one it does not name
        // does not.
        let jammed: Vec<u64> = listing.tables[0].rows[0][2]
            .split(", ")
            .filter_map(|t| t.parse().ok())
            .collect();
        for t in 0..16 {
            let one = replay(&ctx, id, cell, Some(t)).unwrap();
            let title = &one.tables[0].title;
            assert_eq!(
                title.contains(": jammed"),
                jammed.contains(&t),
                "{id} {cell} trial {t}: {title}"
            );
            // The title names the trial and what it did, for the report's links to read.
            let named = ReplayedTrial::from_title(title).unwrap();
            assert_eq!(
                (named.experiment.as_str(), named.cell.as_str(), named.trial),
                (id, cell, t)
            );
            assert_eq!(named.jammed, jammed.contains(&t), "{title}");
        }
    }
}

/// Under `drive=either` a replay names the gear its trial's coin picked, counts as the table
/// counted, and its pair file, run by `run pair`, gives the trial's events again; a listed
/// trial's pair file run with `--set drive=other` is the other gear's trial.
#[test]
fn a_replayed_trial_names_the_gear_that_drove_and_its_pair_file_reruns_it() {
    let (id, cell) = ("table4", "0.065/m2-n1");
    let ctx = ctx(id, &[("trials", "12"), ("drive", "either")]);
    let s = setting_groups::read::cells(&ctx, &study::grids::TRIALS).unwrap();
    let spec = cell_spec(&s, ctx.seed(), id, cell).unwrap();
    let mut seen = [false, false];
    for t in 0..12 {
        let drawn = study::cell::draw_trial(s.gearing(), &spec, ctx.seed(), t).unwrap();
        let gear = match drawn.coin() {
            Driver::Listed => "m2",
            Driver::Other => "n1",
        };
        seen[usize::from(drawn.coin() == Driver::Other)] = true;
        let one = replay(&ctx, id, cell, Some(t)).unwrap();
        let title = &one.tables[0].title;
        assert!(
            title.contains(&format!("drive: either, {gear} drove")),
            "{title}"
        );
        let ron = one.files.iter().find(|f| f.name == "pair.ron").unwrap();
        let text = String::from_utf8(ron.contents.clone()).unwrap();
        assert!(text.contains(&format!("Driver: {gear}")), "{text}");
        // The pair file reruns the trial: the same events, to the rounding of degrees.
        let rebuilt = rebuild(s.gearing(), &spec, ctx.seed(), t).unwrap();
        let p = study::pair_file::prepare("pair.ron", &text).unwrap();
        let phi0 = p.spec.start_deg.to_radians();
        let again = p
            .mesh
            .solve(phi0..=phi0 + rebuilt.turn, p.start, Solve::events());
        let events = rebuilt.events();
        assert_eq!(again.len(), events.len(), "trial {t}");
        for (a, b) in again.iter().zip(&events) {
            assert_eq!(a.kind, b.kind, "trial {t}");
            assert!(
                (a.phi - b.phi).abs() < 1e-9,
                "trial {t}: {} {}",
                a.phi,
                b.phi
            );
        }
    }
    assert_eq!(
        seen,
        [true, true],
        "the coin picked both gears in 12 trials"
    );
}

/// Table 3's `B/m3-e3` and Table I's `B/40/m3-e3` are one cell, counted alike: one trial
/// key; another G, another rule or another seed is another.
#[test]
fn one_cell_of_two_tables_has_one_trial_key() {
    let key = |id: &str, cell: &str, sets: &[(&str, &str)], seed: u64| {
        let ctx = experiments::context(id, seed, 1, sets).unwrap().1;
        trial_key(&ctx, id, cell).unwrap()
    };
    let b = key("table3", "B/m3-e3", &[], 2025);
    assert_eq!(b, key("tableI", "B/40/m3-e3", &[], 2025));
    assert_ne!(b, key("tableI", "B/70/m3-e3", &[], 2025));
    assert_ne!(b, key("table3", "B/m3-e3", &[("events", "strict")], 2025));
    assert_ne!(b, key("table3", "B/m3-e3", &[], 7));
    assert_eq!(b, key("table3", "B/m3-e3", &[("trials", "12")], 2025));
}

/// Each grammar is its experiment's: registered in its file, for a registered experiment;
/// `REPLAYABLE` lists them all.
#[test]
fn every_cell_grammar_belongs_to_a_registered_experiment() {
    experiments::link();
    let experiments = registry::experiments().unwrap();
    let all = grammars().unwrap();
    assert!(all.len() >= 4, "{:?}", all.keys());
    for id in all.keys() {
        assert!(experiments.contains_key(id), "{id}");
    }
    let listed: Vec<&str> = REPLAYABLE.iter().map(|(id, _)| *id).collect();
    assert_eq!(listed, all.keys().copied().collect::<Vec<_>>());
}

#[test]
fn bad_cells_and_trials_are_named() {
    let ctx3 = ctx("table3", &[("trials", "10")]);
    for (cell, words) in [
        ("B", "must be CASE/MESH"),
        ("E/m3-e3", "`E` is not a Case"),
        ("B/x-y", "no mesh `x-y`"),
    ] {
        let e = replay(&ctx3, "table3", cell, Some(0)).err().unwrap();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains(words), "{cell}: {e}");
    }
    let e = replay(&ctx3, "table3", "B/m3-e3", Some(10)).err().unwrap();
    assert!(
        e.to_string().contains("must be below table3's 10 trials"),
        "{e}"
    );
    let e = replay(&ctx("fig2", &[]), "fig2", "x", Some(0))
        .err()
        .unwrap();
    assert!(e.to_string().contains("has no replayable trials"), "{e}");
}
