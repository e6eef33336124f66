#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;

use registry::Settings as _;
use study::cell::{Purpose, run_cells};

#[test]
fn the_verdict_needs_every_threshold() {
    let t = |t4: u64, jams: u64, dis: u64| {
        let mut x = [Tally::default(); 4];
        x[1] = Tally {
            jams_consistent: t4,
            jams_compared: 105,
            ..Tally::default()
        };
        x[3] = Tally {
            jams_consistent: jams,
            jams_compared: 345,
            dis_consistent: dis,
            dis_compared: 345,
        };
        x
    };
    assert!(reproduces(&t(95, 280, 320)));
    assert!(!reproduces(&t(94, 345, 345)));
    assert!(!reproduces(&t(105, 279, 345)));
    assert!(!reproduces(&t(105, 345, 319)));
}

#[test]
fn medians_of_odd_and_even_lists() {
    assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
    assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), Some(2.5));
    assert_eq!(median(&mut []), None);
}

/// The cells' trials are the tables' own: under the push model every count is what the shared
/// cell runner gives the listed driver under the default rule, cell by cell.
#[test]
fn the_push_models_counts_are_the_tables() {
    let (_, ctx) = crate::context("motion-models", 2025, 1, &[]).unwrap();
    let s = cell_settings(&Settings::read(&ctx).unwrap()).unwrap();
    let cells: Vec<CellSpec> = [
        ("m2-n1", 0.065, 0.0, 40.0),
        ("h2-i1", 0.06, 0.0, 40.0),
        ("b2-c1", 0.08, 2.0, 70.0),
        ("m3-e3", 0.08, 2.0, 40.0),
    ]
    .iter()
    .map(|&(mesh, random, sys, g)| {
        presentation::cells::cell(&s, mesh, &[("random", random), ("systematic", sys)], g).unwrap()
    })
    .collect();
    let push = Model::parse("push").unwrap();
    let ours = study::motion_models::cell_counts(
        ctx.engine(),
        s.gearing(),
        &cells,
        &[push],
        &rules::Rule::default(),
        12,
    )
    .unwrap();
    let tables = run_cells(ctx.engine(), s.gearing(), &cells, 12, Purpose::Own).unwrap();
    for ((c, ours), theirs) in cells.iter().zip(&ours).zip(&tables) {
        assert_eq!(
            (ours[0].jams, ours[0].disengagements),
            (theirs.jams, theirs.disengagements),
            "{}",
            c.canonical()
        );
    }
    assert!(tables.iter().any(|c| c.jams > 0) && tables.iter().any(|c| c.disengagements > 0));
}

/// Table 1's pointers composed mesh by mesh under the push model are Table 1's own runs: the
/// same initial angles from the same streams, the same σ of every pointer in every trial.
#[test]
fn the_push_models_pointers_are_table_1s() {
    let sets = [
        ("lunar_turns", "0.2"),
        ("metonic_turns", "0.2"),
        ("saros_turns", "0.2"),
        ("games_turns", "0.2"),
        ("exeligmos_turns", "0.2"),
    ];
    let (_, ctx) = crate::context("motion-models", 7, 1, &sets).unwrap();
    let settings = Settings::read(&ctx).unwrap();
    let gearing = settings.gearing.load().unwrap();
    let rule = settings.events.rule().unwrap();
    let mech = study::pointers::ideal_mechanism(&gearing, &rule).unwrap();
    let per = settings.run_lengths.samples_per_engagement;
    let turns = settings.run_lengths.turns();
    let runs = study::pointers::pointer_runs(&gearing.gearing, &turns, per).unwrap();
    let push = Model::parse("push").unwrap();
    let ours = study::motion_models::pointer_sigmas(
        ctx.engine(),
        &mech,
        &runs,
        &[push],
        3,
        gearing.tooth_height,
    )
    .unwrap();
    let table1 = study::pointers::ideal_trials(ctx.engine(), "table 1", &mech, &runs, 3).unwrap();
    for (t, (a, b)) in ours[0].iter().zip(&table1).enumerate() {
        for (i, (x, y)) in a.iter().zip(b).enumerate() {
            assert!(
                (x.sigma - y.sigma).abs() <= 1e-12 * y.sigma.abs().max(1e-9),
                "trial {t}, pointer {i}: {} vs {}",
                x.sigma,
                y.sigma
            );
        }
    }
}

/// A reduced run gives the same bits with one thread and with two.
#[test]
fn a_reduced_run_is_identical_with_one_and_two_threads() {
    let sets = [
        ("trials", "1"),
        ("clearances", "40"),
        ("random_to", "0.035"),
        ("fig_iv_clearances", "40"),
        ("fig_iv_samples", "50"),
        ("lunar_turns", "0.05"),
        ("metonic_turns", "0.05"),
        ("saros_turns", "0.05"),
        ("games_turns", "0.05"),
        ("exeligmos_turns", "0.05"),
    ];
    let text = |threads| {
        crate::run("motion-models", 99, threads, &sets)
            .unwrap()
            .text()
    };
    assert_eq!(text(1), text(2));
}
