//! Every registered motion model: one per plugin file, named after it; each on Figure 2's pair
//! (it reproduces Thorndike's closed form, or the test states why not); the jams of each checked
//! against the independent polygon oracle (`polycheck`); and every run a function of its trial
//! alone (the same bits on any thread).
#![allow(clippy::unwrap_used, reason = "tests")]

use std::f64::consts::TAU;

use contact::{EventKind, Mesh};
use geometry::Gear;
use motion::{Model, Path, Trial, Want};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

#[path = "support/cases.rs"]
mod cases;
use cases::{Case, case};

/// One model per file of `src/plugins/` (file `a_b.rs` registers `a-b`), `push` the default.
#[test]
fn every_plugin_file_registers_its_model_and_push_is_the_default() {
    motion::link();
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/plugins");
    let mut files: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().replace('_', "-"))
        .collect();
    files.sort_unstable();
    let registered: Vec<&str> = motion::models().unwrap().keys().copied().collect();
    assert_eq!(registered, files);
    assert_eq!(Model::default().name(), motion::DEFAULT);
    assert_eq!(motion::DEFAULT, "push");
    let e = Model::parse("pushed").unwrap_err().to_string();
    assert!(
        e.contains("unknown; known models: carried, carried-drawn"),
        "{e}"
    );
    assert!(motion::listing().contains("first-flank"));
}

/// Figure 2's pair run by `name` over one driver turn from φ' = 0, touching: the largest
/// difference from the closed form (degrees), at every 0.05° and, for a stepped program, at
/// its steps; and the TD's spread over the last seven pitches (degrees).
fn figure2(name: &str) -> (f64, f64, f64) {
    motion::link();
    let gear = Gear::ideal(8, 200.0, 100.0).unwrap();
    let mesh = Mesh::new(gear.clone(), gear, 310.0).unwrap();
    let pair = thorndike::Pair::new(8, 8, 200.0, 100.0, 200.0, 100.0, 310.0).unwrap();
    let trial = Trial {
        mesh: &mesh,
        phi0: 0.0,
        turn: TAU,
        drawn: Some(1.0),
        tooth_height: 100.0,
    };
    // A drawn angle is ignored where the caller starts touching: Figure 2 gives its own start.
    let fixed = Trial {
        drawn: None,
        ..trial
    };
    let path = Model::parse(name)
        .unwrap()
        .run(&fixed, Want::Path)
        .path
        .unwrap();
    let th0 = path.theta_at(0.0);
    let (mut worst, mut lo, mut hi) = (0.0_f64, f64::INFINITY, f64::NEG_INFINITY);
    for i in 0..=7200 {
        let phi = TAU * f64::from(i) / 7200.0;
        let theta = path.theta_at(phi);
        worst = worst.max((theta - thorndike::theta_prime(&pair, phi)).abs());
        if phi >= TAU / 8.0 {
            let td = theta - th0 - phi;
            (lo, hi) = (lo.min(td), hi.max(td));
        }
    }
    let own = match &path {
        Path::Steps(steps) => steps
            .iter()
            .map(|&(phi, theta)| (theta - thorndike::theta_prime(&pair, phi)).abs())
            .fold(0.0, f64::max),
        _ => worst,
    };
    (worst.to_degrees(), own.to_degrees(), (hi - lo).to_degrees())
}

/// The push model is the solver, on the closed form to rounding; `first-flank` starts touching
/// a tooth behind where Figure 2 fixes the start, and is then the push model.
#[test]
fn push_and_first_flank_reproduce_figure_2() {
    for name in ["push", "first-flank"] {
        let (worst, _, _) = figure2(name);
        assert!(worst < 1e-9, "{name}: {worst} deg");
    }
}

/// The stepped program that corrects either way from where the gear stood moves the ideal
/// pair as the push model does (an ideal pair has no tooth ahead closing on it): on the closed
/// form at its steps to within the overlap its tolerance lets the teeth make (0.0001 mm² is
/// nothing at these sizes) and its bisection, between its steps only as straight lines.
#[test]
fn stepped_nearest_reproduces_figure_2_at_its_steps() {
    let (worst, own, _) = figure2("stepped-nearest");
    assert!(own < 0.02, "{own} deg at its steps");
    assert!(worst < 1.0 && worst > own, "{worst} deg between its steps");
}

/// The carried models, and the stepped program that carries the gear by the ratio, do not
/// reproduce Figure 2, and cannot: carried at the ratio, the driven gear is pushed up the push
/// curve only while the curve rises faster than the ratio, so it leaves the curve at its peak
/// and rides there, every later tooth grazing it at the same peak - its Theoretical Difference
/// is flat after the first pitch (at most the stepped program's tolerance apart), where
/// Thorndike's swings by degrees each pitch.
#[test]
fn carried_models_cannot_reproduce_figure_2_their_td_is_flat() {
    for (name, flat) in [
        ("carried", 1e-9),
        ("carried-drawn", 1e-9),
        ("stepped-carried", 0.5),
    ] {
        let (worst, own, spread) = figure2(name);
        assert!(
            spread < flat,
            "{name}: TD spread {spread} deg after the first pitch"
        );
        assert!(
            own > 5.0 && worst > 5.0,
            "{name}: {worst} deg from the closed form"
        );
    }
}

fn config() -> Config {
    Config {
        cases: std::env::var("PROPS_CASES")
            .ok()
            .and_then(|s| s.parse().ok())
            .unwrap_or(16),
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(
            std::env::var("PROPS_SEED")
                .ok()
                .and_then(|s| s.parse().ok())
                .unwrap_or(0x0d_e15),
        ),
        ..Config::default()
    }
}

fn trial<'m>(case: &Case, mesh: &'m Mesh, share: f64) -> Trial<'m> {
    Trial {
        mesh,
        phi0: case.phi0,
        turn: case.phi_end() - case.phi0,
        drawn: Some(share * TAU / case.driven.tips.len() as f64),
        tooth_height: case.h,
    }
}

/// The deepest interpenetration (mm) a stepped program may leave outside a jam: the sliver of
/// a tip cut off by an overlap area of 0.0001 mm² on these teeth, with room for the search's
/// bisection.
const STEPPED_PEN: f64 = 0.02;

proptest! {
    #![proptest_config(config())]

    /// Every jam of every exact model is what the oracle sees: the teeth touch at the lock and
    /// are pinched just after, and the gear is let go into a free position. (`first-flank`'s
    /// jams after the first flank are the push model's on the mesh as driven, which the
    /// contact solver's own property tests hold to the oracle; its listed-driver jams are
    /// checked here.)
    #[test]
    fn the_oracle_confirms_every_exact_models_jams(
        case in case(10.0..60.0),
        share in 0.0..1.0f64,
    ) {
        let Some(mesh) = case.mesh() else {
            return Err(TestCaseError::reject("mesh refused"));
        };
        let oracle = case.oracle();
        for name in ["push", "carried", "carried-drawn", "first-flank"] {
            let out = Model::parse(name).unwrap().run(&trial(&case, &mesh, share), Want::Path);
            // first-flank's events after a flank met ahead are the other gear's run.
            let listed = !matches!(out.path, Some(Path::Joined { ref then, .. }) if matches!(**then, Path::Inverse(_)));
            if !listed {
                continue;
            }
            for e in out.events.iter().filter(|e| matches!(e.kind, EventKind::Lock | EventKind::Strike)) {
                let tol = 1e-9_f64.max(1e-10 * case.centre_distance());
                let (pen, dist) = (oracle.penetration_at(e.phi, e.theta), oracle.distance_at(e.phi, e.theta));
                prop_assert!(pen <= tol && (pen > 0.0 || dist < 1e-7), "{name}: jam {e:?} not touching: {pen}, {dist}");
                prop_assert!(oracle.penetration_at(e.phi + 1e-7, e.theta) > 0.0, "{name}: jam {e:?} not blocked");
                if e.theta_after != e.theta {
                    let pen = oracle.penetration_at(e.phi, e.theta_after);
                    prop_assert!(pen <= 1e-9, "{name}: jam {e:?} let go into overlap {pen}");
                }
            }
        }
    }

    /// The stepped programs: between jams the teeth interpenetrate at most by what the area
    /// tolerance allows, at every step; at a jam they overlap where the gear stood and within
    /// the search step either side, and the gear is let go no deeper than that allowance (or,
    /// with nothing free a few pitches ahead, stays where it jammed). A blocked start has no
    /// free position to start at.
    #[test]
    fn the_oracle_confirms_every_stepped_programs_steps_and_jams(
        case in case(10.0..60.0),
    ) {
        let Some(mesh) = case.mesh() else {
            return Err(TestCaseError::reject("mesh refused"));
        };
        let oracle = case.oracle();
        let pitch2 = TAU / case.driven.tips.len() as f64;
        for name in ["stepped-nearest", "stepped-carried"] {
            let out = Model::parse(name).unwrap().run(&trial(&case, &mesh, 0.0), Want::Path);
            // (driver angle, let go) of each jam: with nothing free a few pitches ahead, the gear
            // stays where it jammed.
            let jams: Vec<(f64, bool)> = out.events.iter().filter(|e| e.kind == EventKind::Lock).map(|e| (e.phi, e.theta_after != e.theta)).collect();
            let Some(Path::Steps(steps)) = out.path else {
                panic!("{name}: a stepped program's path is its steps");
            };
            let blocked = out.events.iter().any(|e| e.kind == EventKind::BlockedAtStart);
            for &(phi, theta) in steps.iter().skip(usize::from(blocked)) {
                let pen = oracle.penetration_at(phi, theta);
                if let Some(&(_, let_go)) = jams.iter().find(|j| j.0 == phi) {
                    prop_assert!(!let_go || pen <= STEPPED_PEN, "{name}: let go into {pen} mm at {phi}");
                    continue;
                }
                prop_assert!(pen <= STEPPED_PEN, "{name}: {pen} mm at step {phi}");
            }
            for e in out.events.iter().filter(|e| e.kind == EventKind::Lock) {
                for d in [-1.0, 0.0, 1.0] {
                    let theta = e.theta + d * pitch2 / 64.0;
                    prop_assert!(oracle.penetration_at(e.phi, theta) > 0.0, "{name}: jam {e:?} free at {theta}");
                }
            }
        }
    }

    /// A model's run depends on its trial alone: run again, on other threads, in another order,
    /// it gives the same bits.
    #[test]
    fn every_model_gives_the_same_bits_on_any_thread(case in case(10.0..60.0), share in 0.0..1.0f64) {
        let Some(mesh) = case.mesh() else {
            return Err(TestCaseError::reject("mesh refused"));
        };
        let bits = |name: &str| {
            let out = Model::parse(name).unwrap().run(&trial(&case, &mesh, share), Want::Path);
            let path = out.path.unwrap();
            let span = case.phi_end() - case.phi0;
            let thetas: Vec<u64> = (0..=50).map(|i| path.theta_at(case.phi0 + span * f64::from(i) / 50.0).to_bits()).collect();
            (format!("{:?}", out.events), thetas)
        };
        let names: Vec<&str> = motion::models().unwrap().keys().copied().collect();
        let here: Vec<_> = names.iter().map(|n| bits(n)).collect();
        let there: Vec<_> = std::thread::scope(|s| {
            let handles: Vec<_> = names.iter().rev().map(|n| s.spawn(move || bits(n))).collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let there: Vec<_> = there.into_iter().rev().collect();
        prop_assert_eq!(here, there);
    }
}
