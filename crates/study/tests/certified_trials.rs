//! The contact solver's certified steps (`crates/contact/src/certify.rs`) on the trials the
//! tables run: Edmunds' Case D gears (the largest errors, where jams, releases and slips follow
//! one another) on every mesh of the Freeth 2006 gearing, at 40 % clearance. Each trial's
//! events must be those of the plain solver, which brackets every step: the same kinds at the
//! same angles to 1e-9 rad.
#![allow(clippy::unwrap_used, reason = "tests")]

use contact::{Solve, Start};
use study::cell::{CellSpec, rebuild};

#[test]
fn case_d_trials_find_the_events_of_the_plain_solver() {
    let g = train::Gearing::freeth2006();
    let hyp = hypotheses::lookup("edmunds-split").unwrap();
    let params = hypotheses::Params::new(
        hyp,
        &[
            ("systematic".into(), "2.0".into()),
            ("random".into(), "0.08".into()),
            ("split".into(), "0.5".into()),
        ],
    )
    .unwrap();
    let (mut trials, mut events) = (0, 0);
    for m in g.meshes() {
        for clearance in [40.0] {
            let cell = CellSpec {
                mesh: m.label.clone(),
                hypothesis: hyp,
                params: params.clone(),
                tooth_height: 1.1,
                clearance,
                events: rules::Rule::parse("paper").unwrap(),
                drive: study::drive::Drive::Listed,
                end: study::trial_end::End::Turn,
            };
            for t in 0..100 {
                let trial = rebuild(&g, &cell, 2025, t).unwrap();
                let Some(mesh) = &trial.mesh else { continue };
                let end = trial.phi0 + trial.turn;
                let certified = mesh.solve(trial.phi0..=end, Start::Touching(0.0), Solve::events());
                let plain = mesh.solve(
                    trial.phi0..=end,
                    Start::Touching(0.0),
                    Solve::path().steps_per_pitch(4.0).exact_core(),
                );
                let what = format!("{} G {clearance} % trial {t}", m.label);
                assert_eq!(certified.len(), plain.events().len(), "{what}");
                for (a, b) in certified.iter().zip(plain.events()) {
                    assert_eq!(a.kind, b.kind, "{what}: {a:?} vs {b:?}");
                    assert!((a.phi - b.phi).abs() < 1e-9, "{what}: {a:?} vs {b:?}");
                    assert_eq!(a.phase_shift, b.phase_shift, "{what}: {a:?} vs {b:?}");
                }
                trials += 1;
                events += certified.len();
            }
        }
    }
    assert!(
        trials > 300 && events > 1000,
        "{trials} trials, {events} events"
    );
}
