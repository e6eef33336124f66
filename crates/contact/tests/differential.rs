//! The bracketing step must not change what the solver finds: the same random meshes run with
//! the default step and with an eight times finer one give the same first event (kind and
//! driven angle) and the same answer to "jammed at all?" and "disengaged at all?", which is all
//! the jam statistics use. (Later events after a jam's release may differ in rare near-tangent
//! cases; `cargo run --release -p contact --example differential` reports them.)
#![allow(clippy::unwrap_used, reason = "tests")]

use contact::Start;

#[path = "support/hard_meshes.rs"]
mod hard_meshes;
use hard_meshes::{HardMesh, hard_mesh};

#[test]
fn first_events_do_not_depend_on_the_step() {
    let (mut checked, mut with_events) = (0, 0);
    for case in 0..120u64 {
        let Some(HardMesh {
            mesh: m,
            phi0,
            end,
            what,
        }) = hard_mesh(case, None)
        else {
            continue;
        };
        let coarse = m.run(phi0, end, Start::Touching(0.0));
        let fine = m.run_with_steps(phi0, end, Start::Touching(0.0), false, 32.0, false);
        // The events-only run (no segments kept) finds exactly the same events.
        assert_eq!(
            m.run_events(phi0, end, Start::Touching(0.0)),
            coarse.events(),
            "{what}: run_events"
        );
        assert_eq!(coarse.jams() > 0, fine.jams() > 0, "{what}: jammed at all");
        assert_eq!(
            coarse.disengagements() > 0,
            fine.disengagements() > 0,
            "{what}: disengaged at all"
        );
        match (coarse.events().first(), fine.events().first()) {
            (None, None) => {}
            (Some(a), Some(b)) => {
                with_events += 1;
                assert_eq!(a.kind, b.kind, "{what}: first event kind");
                assert!((a.theta - b.theta).abs() < 1e-9, "{what}: {a:?} vs {b:?}");
                // The angle of a disengagement is a flat maximum of θ: ill-conditioned in φ.
                assert!((a.phi - b.phi).abs() < 1e-6, "{what}: {a:?} vs {b:?}");
            }
            (a, b) => panic!("{what}: first events {a:?} vs {b:?}"),
        }
        checked += 1;
    }
    assert!(
        checked > 100 && with_events > 40,
        "{checked} cases, {with_events} with events"
    );
}

/// Steps taken on certificates (`certify.rs`) find exactly the events that bracketing every step
/// finds: the same kinds, at the same angles to 1e-9 rad, on every hard mesh, after releases too.
#[test]
fn certified_steps_find_the_events_bracketing_finds() {
    let (mut checked, mut events) = (0, 0);
    for case in 0..120u64 {
        let Some(HardMesh {
            mesh: m,
            phi0,
            end,
            what,
        }) = hard_mesh(case, None)
        else {
            continue;
        };
        let certified = m.run_with_steps(phi0, end, Start::Touching(0.0), false, 4.0, true);
        let bracketed = m.run_with_steps(phi0, end, Start::Touching(0.0), false, 4.0, false);
        let (a, b) = (certified.events(), bracketed.events());
        assert_eq!(a.len(), b.len(), "{what}: {a:?} vs {b:?}");
        for (x, y) in a.iter().zip(b) {
            assert_eq!(x.kind, y.kind, "{what}: {x:?} vs {y:?}");
            assert!((x.phi - y.phi).abs() < 1e-9, "{what}: {x:?} vs {y:?}");
            assert!((x.theta - y.theta).abs() < 1e-9, "{what}: {x:?} vs {y:?}");
        }
        // θ agrees between the events too.
        for i in 0..=50 {
            let phi = phi0 + (end - phi0) * f64::from(i) / 50.0;
            let (p, q) = (certified.theta_at(phi), bracketed.theta_at(phi));
            assert!((p - q).abs() < 1e-9, "{what}: θ at φ {phi}: {p} vs {q}");
        }
        checked += 1;
        events += a.len();
    }
    assert!(
        checked > 100 && events > 500,
        "{checked} cases, {events} events"
    );
}
