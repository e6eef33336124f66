//! A hypothesis defined outside the crate with one file and one registration: it is listed,
//! looked up and applied like a built-in.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use geometry::Gear;
use hypotheses::rand::RngCore;
use hypotheses::{About, Kind, Manufactured, Param, Params, manufacture};

const SHIFT: Param =
    Param::new("shift", "1", "angle added to every tip", Kind::ANY_NUMBER).unit("deg");

/// Every tip moved by the same angle: the whole toothing turned on its blank.
struct ToyShift;

impl hypotheses::Plugin for ToyShift {
    const ABOUT: About = About {
        name: "toy-shift",
        summary: "every tip shifted by the same angle (an example plugin)",
        details: "",
    };
    const PARAMS: &[Param] = &[SHIFT];

    fn apply(gear: &Gear, gear_name: &str, params: &Params, _: &mut dyn RngCore) -> Manufactured {
        let shift = params.value(&SHIFT).to_radians();
        let tips = gear.tip_angles().iter().map(|t| t + shift).collect();
        manufacture(gear, gear_name, tips, gear.rotation_centre())
    }
}

hypotheses::register!(ToyShift);

#[test]
fn a_plugin_is_listed_looked_up_and_applied() {
    let all = hypotheses::hypotheses().unwrap();
    assert!(all.contains_key("toy-shift"));
    assert!(all.contains_key("edmunds-split"), "built-ins still there");
    let listing = hypotheses::listing();
    assert!(
        listing.contains("toy-shift: every tip shifted"),
        "{listing}"
    );
    assert!(listing.contains("shift"), "{listing}");

    let h = hypotheses::lookup("toy-shift").unwrap();
    let p = Params::new(h, &[("shift".into(), "2".into())]).unwrap();
    let g = Gear::ideal(20, 5.5, 4.4).unwrap();
    let mut rng = <rand_chacha::ChaCha8Rng as rand::SeedableRng>::seed_from_u64(1);
    let made = h.apply(&g, "g2", &p, &mut rng).unwrap();
    for (m, d) in made.tip_angles().iter().zip(g.tip_angles()) {
        assert!((m - d - 2.0_f64.to_radians()).abs() < 1e-15);
    }
}
