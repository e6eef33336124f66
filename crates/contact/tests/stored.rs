//! A run stored as JSON and read back (what an experiment's `results.json` holds) is the same
//! run: the mesh placed again from its gears and centre distance, every segment and event, and
//! θ(φ) bit for bit, so that a report drawn again from stored results draws the same pictures.
#![allow(clippy::unwrap_used, reason = "tests")]

use contact::{Solve, Start, Trajectory};

#[path = "support/hard_meshes.rs"]
mod hard_meshes;
use hard_meshes::{HardMesh, hard_mesh};

#[test]
fn a_stored_run_reads_back_as_the_same_run() {
    let mut checked = 0;
    for case in 0..24u64 {
        let Some(HardMesh {
            mesh,
            phi0,
            end,
            what,
        }) = hard_mesh(case, None)
        else {
            continue;
        };
        let run = mesh.solve(phi0..=end, Start::Touching(0.0), Solve::path());
        let text = serde_json::to_string(&run).unwrap();
        let back: Trajectory = serde_json::from_str(&text).unwrap();
        assert_eq!(back.mesh().driver(), run.mesh().driver(), "{what}");
        assert_eq!(back.mesh().driven(), run.mesh().driven(), "{what}");
        assert_eq!(
            back.mesh().centre_distance().to_bits(),
            run.mesh().centre_distance().to_bits(),
            "{what}"
        );
        assert_eq!(back.segments(), run.segments(), "{what}");
        assert_eq!(back.events(), run.events(), "{what}");
        for i in 0..=200 {
            let phi = phi0 + (end - phi0) * f64::from(i) / 200.0;
            assert_eq!(
                back.theta_at(phi).to_bits(),
                run.theta_at(phi).to_bits(),
                "{what}: theta at {phi}"
            );
        }
        // The mesh alone too, and the start.
        let m: contact::Mesh =
            serde_json::from_str(&serde_json::to_string(&mesh).unwrap()).unwrap();
        assert_eq!(m.driver(), mesh.driver(), "{what}");
        let start = Start::At(0.25);
        let s: Start = serde_json::from_str(&serde_json::to_string(&start).unwrap()).unwrap();
        assert_eq!(s, start);
        checked += 1;
    }
    assert!(checked >= 12, "only {checked} meshes could be placed");
}

/// A stored mesh whose gears cannot be placed is refused when read back, naming the rule.
#[test]
fn a_stored_mesh_that_cannot_be_placed_is_refused() {
    let HardMesh { mesh, .. } = (0..24).find_map(|c| hard_mesh(c, None)).unwrap();
    let mut value: serde_json::Value = serde_json::to_value(&mesh).unwrap();
    value["centre_distance"] = serde_json::json!(0.5);
    let e = serde_json::from_value::<contact::Mesh>(value).unwrap_err();
    assert!(e.to_string().contains("centre_distance"), "{e}");
}
