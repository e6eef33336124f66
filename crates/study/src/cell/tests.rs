//! Tests of the per-mesh cells: the `tests` module of `cell/mod.rs`.
#![allow(clippy::unwrap_used, reason = "tests")]
use super::*;

fn cell(mesh: &str, random: f64) -> CellSpec {
    let hyp = hypotheses::lookup("edmunds-split").unwrap();
    let params = Params::new(
        hyp,
        &[
            ("random".into(), random.to_string()),
            ("systematic".into(), "0.5".into()),
        ],
    )
    .unwrap();
    CellSpec {
        mesh: mesh.into(),
        hypothesis: hyp,
        params,
        tooth_height: 1.1,
        clearance: 40.0,
        events: rules::Rule::default(),
        drive: Drive::Listed,
        end: End::Turn,
    }
}

/// A trial's run ends once every rule has seen a jam and a disengagement: its events are the
/// whole turn's up to the cut, and its bits the whole turn's, under every registered rule, on
/// meshes that jam, slip, or do neither; and some runs are cut short (else this means nothing).
#[test]
fn a_trial_cut_at_its_answer_counts_as_the_whole_turn() {
    let g = Gearing::freeth2006();
    let all: Vec<rules::Rule> = rules::rules()
        .unwrap()
        .keys()
        .map(|name| rules::Rule::parse(name).unwrap())
        .collect();
    // Every rule under every end, so that some countings close at a first event.
    let listed: Vec<Counting> = all
        .iter()
        .flat_map(|rule| {
            End::ALL.into_iter().map(|end| Counting {
                rule: rule.clone(),
                drive: Drive::Listed,
                end,
            })
        })
        .collect();
    let refs: Vec<&Counting> = listed.iter().collect();
    assert!(all.len() >= 4, "{all:?}");
    let mut cut_short = 0;
    let at = |mut spec: CellSpec, clearance: f64| {
        spec.clearance = clearance;
        spec
    };
    for spec in [
        cell("m3-e3", 0.08),
        at(cell("b2-c1", 0.1), 70.0),
        at(cell("e4-f1", 0.02), 10.0),
        // Jammed and disengaged for a pitch or more in the same turn: every rule answered
        // before the end (idle-rotation's disengagements are the long losses alone).
        at(cell("m3-e3", 0.08), 70.0),
    ] {
        let p = prepare(&g, &spec).unwrap();
        for t in 0..30 {
            let rebuilt = rebuild_prepared(&p, 11, t).unwrap();
            let Some(mesh) = &rebuilt.mesh else { continue };
            let whole = rebuilt.events();
            let (_, cut) = tallies_to_answer(mesh, &rebuilt, &refs);
            assert_eq!(
                cut[..],
                whole[..cut.len()],
                "{} trial {t}",
                spec.canonical()
            );
            let from_whole = listed.iter().enumerate().fold(0, |acc, (r, c)| {
                let (jam, dis) = c.tally(&whole);
                acc | (u64::from(jam) | u64::from(dis) << 1) << (2 * r)
            });
            assert_eq!(
                trial(&p, 11, t, &listed).unwrap(),
                from_whole,
                "{} trial {t}",
                spec.canonical()
            );
            cut_short += usize::from(cut.len() < whole.len());
        }
    }
    assert!(cut_short > 0);
}

#[test]
fn counting_under_several_rules_gives_each_rules_own_counts() {
    let g = Gearing::freeth2006();
    let strict = rules::Rule::parse("strict").unwrap();
    let paper = rules::Rule::parse("paper").unwrap();
    // Case D-like errors at a wide clearance: gaps and slips happen, so the rules differ.
    let mut cells = vec![cell("m3-e3", 0.08), cell("b2-c1", 0.08)];
    for c in &mut cells {
        c.clearance = 70.0;
    }
    let listed = |rule: &rules::Rule| Counting {
        rule: rule.clone(),
        drive: Drive::Listed,
        end: End::Turn,
    };
    let both = run_cells_under(
        &g,
        &cells,
        Some(&[listed(&strict), listed(&paper)]),
        6,
        11,
        false,
        local,
    )
    .unwrap();
    for (r, rule) in [strict.clone(), paper.clone()].iter().enumerate() {
        let own: Vec<CellSpec> = cells
            .iter()
            .map(|c| CellSpec {
                events: rule.clone(),
                ..c.clone()
            })
            .collect();
        let alone = run_cells_with(&g, &own, 6, 11, false, local).unwrap();
        for (i, a) in alone.iter().enumerate() {
            assert_eq!(both[i][r], *a, "cell {i} under {}", rule.label());
        }
    }
    // The rules must differ somewhere here, or the test shows nothing.
    assert!(
        both.iter().any(|c| c[0] != c[1]),
        "strict and paper count alike: {both:?}"
    );
    // Counted under both, then read from the cache under one: the same counts.
    forget_cache();
    let filled = run_cells_under(
        &g,
        &cells[..1],
        Some(&[listed(&strict), listed(&paper)]),
        6,
        11,
        true,
        local,
    )
    .unwrap();
    let mut paper_cell = cells[0].clone();
    paper_cell.events = rules::Rule::parse("paper").unwrap();
    let never = |_: &str,
                 _: u64,
                 _: &(dyn Fn(u64) -> Result<RuleBits, RunError> + Sync + Send)|
     -> Result<Vec<RuleBits>, RunError> {
        panic!("the cell should come from the cache")
    };
    let cached = run_cells_with(&g, &[paper_cell], 6, 11, true, never).unwrap();
    assert_eq!(cached[0], filled[0][1]);
    forget_cache();
}

/// Whichever gear drives, a trial draws the same gears and the same share of a pitch; the
/// other gear's run is its own mesh's, reflected; and `either` takes each trial's coin.
#[test]
fn the_drive_changes_the_driver_and_nothing_drawn() {
    let g = Gearing::freeth2006();
    let spec = cell("m2-n1", 0.06);
    let p = prepare(&g, &spec).unwrap();
    let (n1, n2) = (15.0, 53.0);
    let mut coins = [0, 0];
    for t in 0..40 {
        let drawn = draw(&p, 11, t).unwrap();
        let (a, b) = (
            drawn.driven_by(Driver::Listed),
            drawn.driven_by(Driver::Other),
        );
        let (ma, mb) = (a.mesh.as_ref().unwrap(), b.mesh.as_ref().unwrap());
        assert_eq!(mb.driver(), &ma.driven().mirrored());
        assert_eq!(mb.driven(), &ma.driver().mirrored());
        assert_eq!((a.driver, b.driver), (Driver::Listed, Driver::Other));
        assert!((a.phi0 * n1 / TAU - b.phi0 * n2 / TAU).abs() < 1e-12);
        assert!((a.turn - TAU * n2 / n1).abs() < 1e-12);
        assert!((b.turn - TAU).abs() < 1e-12);
        // The listed trial is the one a cell without a drive setting ran.
        assert_eq!(rebuild_prepared(&p, 11, t).unwrap().phi0, a.phi0);
        coins[usize::from(drawn.coin() == Driver::Other)] += 1;
    }
    assert!(coins[0] >= 8 && coins[1] >= 8, "{coins:?}");
    // Counted under every drive at once: each as run alone, and either trial by trial.
    let spec = cell("m2-n1", 0.065);
    let p = prepare(&g, &spec).unwrap();
    let rule = rules::Rule::default();
    let under = |drive| Counting {
        rule: rule.clone(),
        drive,
        end: End::Turn,
    };
    let all = [
        under(Drive::Listed),
        under(Drive::Other),
        under(Drive::Either),
    ];
    for t in 0..40 {
        let bits = trial(&p, 11, t, &all).unwrap();
        for (r, c) in all.iter().enumerate() {
            let alone = trial(&p, 11, t, std::slice::from_ref(c)).unwrap();
            assert_eq!(bits >> (2 * r) & 0b11, alone, "trial {t}, {:?}", c.drive);
        }
        let coin = draw(&p, 11, t).unwrap().coin();
        let from = usize::from(coin == Driver::Other);
        assert_eq!(bits >> 4 & 0b11, bits >> (2 * from) & 0b11, "trial {t}");
    }
}

#[test]
fn canonical_text_names_the_content() {
    let c = cell("b2-c1", 0.04);
    assert_eq!(
        c.canonical(),
        "mesh=b2-c1;hypothesis=edmunds-split;random=0.04;split=0.5;systematic=0.5;h=1.1;G=40.0"
    );
    let first = |c: &CellSpec, t| -> f64 {
        Streams::new(11)
            .stream(Draws::Cell(&c.canonical()).identity(), t)
            .random()
    };
    assert_ne!(first(&c, 0), first(&c, 1));
    assert_ne!(first(&c, 0), first(&cell("b2-c1", 0.045), 0));
}

/// The cache's gearing identity is its data: the same gearing read twice has one identity, a
/// gearing with other data another.
#[test]
fn the_gearing_identity_is_its_data() {
    let a = GearingId::of(&Gearing::freeth2006()).unwrap();
    assert_eq!(a, GearingId::of(&Gearing::freeth2006()).unwrap());
    let other = Gearing::builtin("freeth2021").unwrap();
    assert_ne!(a, GearingId::of(&other).unwrap());
}

/// The batch runner of a plain run: every trial, in order, over rayon.
fn local(
    _key: &str,
    n: u64,
    f: &(dyn Fn(u64) -> Result<RuleBits, RunError> + Sync + Send),
) -> Result<Vec<RuleBits>, RunError> {
    use rayon::prelude::*;
    (0..n).into_par_iter().map(f).collect()
}

#[test]
fn counts_depend_on_content_not_position_cache_or_threads() {
    let g = Gearing::freeth2006();
    let a = [cell("e1-b3", 0.06), cell("m2-n1", 0.06)];
    let b = [
        cell("m2-n1", 0.06),
        cell("c2-d1", 0.05),
        cell("e1-b3", 0.06),
    ];
    let pool = |n: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .unwrap()
    };
    let ra = pool(1).install(|| run_cells_with(&g, &a, 3, 11, false, local).unwrap());
    let rb = pool(2).install(|| run_cells_with(&g, &b, 3, 11, false, local).unwrap());
    assert_eq!(ra[0], rb[2]);
    assert_eq!(ra[1], rb[0]);
    // Through the cache (first run fills it, second reads it): the same counts.
    let first = run_cells_with(&g, &b, 3, 11, true, local).unwrap();
    let second = run_cells_with(&g, &b, 3, 11, true, local).unwrap();
    assert_eq!(first, rb);
    assert_eq!(second, rb);
    assert_eq!(rb[0].trials, 3);
    assert_eq!(rb[0].engagements, 3 * 53); // m2-n1: 15 and 53 teeth
}

#[test]
fn ranges_add_up_to_the_whole_cell() {
    let g = Gearing::freeth2006();
    let whole = run_cells_with(
        &g,
        &[cell("m2-n1", 0.06), cell("e1-b3", 0.07)],
        5,
        11,
        false,
        local,
    )
    .unwrap();
    let range = |c: CellSpec, r: std::ops::Range<u64>| CellRange { cell: c, range: r };
    let parts = run_cell_ranges_with(
        &g,
        &[
            range(cell("m2-n1", 0.06), 0..2),
            range(cell("e1-b3", 0.07), 0..5),
            range(cell("m2-n1", 0.06), 2..5),
        ],
        11,
        local,
    )
    .unwrap();
    let sum = |a: Counts, b: Counts| Counts {
        jams: a.jams + b.jams,
        disengagements: a.disengagements + b.disengagements,
        failures: a.failures + b.failures,
        trials: a.trials + b.trials,
        engagements: a.engagements + b.engagements,
    };
    assert_eq!(sum(parts[0], parts[2]), whole[0]);
    let mut added = parts[0];
    added += parts[2];
    assert_eq!(added, whole[0]);
    assert_eq!(parts[1], whole[1]);
    for c in &whole {
        // A trial fails when it jams, disengages or both.
        assert!(c.failures >= c.jams.max(c.disengagements), "{c:?}");
        assert!(c.failures <= c.jams + c.disengagements, "{c:?}");
    }
    let e = run_cell_ranges_with(&g, &[range(cell("m2-n1", 0.06), 3..3)], 1, local).unwrap_err();
    assert_eq!(e.exit_code(), 2);
}

#[test]
fn labels_keep_the_value() {
    assert_eq!(label(0.04, 3), "0.040");
    assert_eq!(label(0.0375, 3), "0.0375");
    assert_eq!(label(1.0, 1), "1.0");
    assert_eq!(label(40.0, 0), "40");
}

#[test]
fn bad_cells_are_bad_input() {
    let g = Gearing::freeth2006();
    let e = run_cells_with(&g, &[cell("x-y", 0.04)], 2, 1, true, local).unwrap_err();
    assert_eq!(e.exit_code(), 2);
    let e = run_cells_with(&g, &[cell("b2-c1", 0.04)], 0, 1, true, local).unwrap_err();
    assert_eq!(e.exit_code(), 2);
}
