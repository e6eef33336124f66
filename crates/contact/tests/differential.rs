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
        let fine = m.run_with_steps(phi0, end, Start::Touching(0.0), false, 32.0);
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
