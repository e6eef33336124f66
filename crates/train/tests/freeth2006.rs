//! The embedded Freeth 2006 gearing: parsing, exact ratios, days per degree and radii.

use train::{FREETH2006_RON, Gearing, Ratio};

fn default_gearing() -> Gearing {
    match Gearing::from_ron("freeth2006.ron", FREETH2006_RON) {
        Ok(g) => g,
        Err(e) => panic!("embedded file must parse: {e}"),
    }
}

#[test]
fn default_file_parses_and_matches_freeth2006() {
    let g = default_gearing();
    assert_eq!(Gearing::freeth2006(), g);
    assert_eq!(g.gears().len(), 30);
    assert_eq!(g.meshes().len(), 15);
    assert_eq!(g.pointers().len(), 5);
    let labels: Vec<&str> = g.meshes().iter().map(|m| m.label.as_str()).collect();
    assert_eq!(
        labels,
        [
            "b2-c1", "c2-d1", "d2-e2", "e5-k1", "k2-e6", "e1-b3", "b2-l1", "l2-m1", "m3-e3",
            "e4-f1", "f2-g1", "m2-n1", "n2-o1", "g2-h1", "h2-i1"
        ]
    );
    for lost in ["m3", "n1", "n3"] {
        assert_eq!(
            g.gear(lost).map(|x| x.measured_radius),
            Some(None),
            "{lost}"
        );
    }
    assert!(g.gears().iter().all(|x| !x.source.is_empty()));
    assert_eq!(g.arbor_of("b3"), Some("moon"));
    assert_eq!(g.arbor_of("k1"), g.arbor_of("k2"));
    assert_eq!(g.arbor_of("m3"), Some("m"));
    assert_eq!(g.mesh("n2-o1").map(|m| m.driver.as_str()), Some("n3"));
    assert!(g.mesh("b2-x9").is_none());
    assert!(g.pointer("Solar").is_none());
}

#[test]
fn exact_pointer_ratios() {
    let g = default_gearing();
    for (name, num, den) in [
        ("Lunar", 254, 19),
        ("Metonic", 5, 19),
        ("Games", 1, 4),
        ("Saros", 940, 4237),
        ("Exeligmos", 235, 12711),
    ] {
        assert_eq!(g.pointer_ratio(name), Some(Ratio { num, den }), "{name}");
    }
    assert_eq!(g.pointer_ratio("Nope"), None);
    assert_eq!(g.mesh_ratio("b2-c1"), Some(Ratio { num: 32, den: 19 }));
    assert_eq!(g.mesh_ratio("nope"), None);
}

#[test]
fn days_per_degree_is_computed() {
    let g = default_gearing();
    let metonic = g.days_per_degree("Metonic").unwrap_or(f64::NAN);
    let saros = g.days_per_degree("Saros").unwrap_or(f64::NAN);
    assert!((metonic - 365.25 * 19.0 / (360.0 * 5.0)).abs() < 1e-12);
    assert!((metonic - 3.855).abs() < 1e-3, "{metonic}");
    assert!((saros - 365.25 * 4237.0 / (360.0 * 940.0)).abs() < 1e-12);
    assert!((saros - 4.573).abs() < 1e-3, "{saros}");
    assert_eq!(g.days_per_degree("Lunar"), None);
    assert_eq!(g.days_per_degree("Nope"), None);
}

#[test]
fn every_mesh_keeps_the_tooth_ratio() {
    let g = default_gearing();
    let radii = g.tip_radii();
    assert_eq!(radii.len(), g.gears().len());
    for m in g.meshes() {
        let (Some(d), Some(n)) = (g.gear(&m.driver), g.gear(&m.driven)) else {
            panic!("mesh {} names unknown gears", m.label);
        };
        let ratio = radii[&m.driver] / radii[&m.driven];
        let want = f64::from(d.teeth) / f64::from(n.teeth);
        assert!(
            ((ratio - want) / want).abs() < 1e-12,
            "{}: {ratio} vs {want}",
            m.label
        );
    }
    // Lost gears get a radius from their partners.
    for lost in ["m3", "n1", "n3"] {
        assert!(radii[lost] > 1.0, "{lost}: {}", radii[lost]);
    }
    // A gear in no mesh keeps its measured radius.
    assert!((radii["b1"] - 64.4).abs() < 1e-12);
}

#[test]
fn b2_has_one_radius_for_both_meshes() {
    let g = default_gearing();
    let (Some(a), Some(b)) = (
        g.mesh_geometry("b2-c1", 1.1, 40.0),
        g.mesh_geometry("b2-l1", 1.1, 40.0),
    ) else {
        panic!("both b2 meshes must exist");
    };
    assert_eq!(a.driver_tip_radius.to_bits(), b.driver_tip_radius.to_bits());
    assert_eq!(Some(a.driver_tip_radius), g.tip_radius("b2"));
    // c1 and l1 both have 38 teeth: same radius too.
    assert_eq!(a.driven_tip_radius.to_bits(), b.driven_tip_radius.to_bits());
    // Least squares over b2, c1, l1.
    let mu = (64.0 * 15.30 + 38.0 * 9.85 + 38.0 * 8.65) / (64.0 * 64.0 + 2.0 * 38.0 * 38.0);
    assert!((a.driver_tip_radius - 64.0 * mu).abs() < 1e-12);
}

#[test]
fn mesh_geometry_follows_the_paper() {
    let g = default_gearing();
    let Some(m) = g.mesh_geometry("m2-n1", 1.1, 40.0) else {
        panic!("m2-n1 exists");
    };
    assert_eq!((m.driver_teeth, m.driven_teeth), (15, 53));
    // n1 is lost: the component is sized by m2 alone.
    assert!((m.driver_tip_radius - 3.85).abs() < 1e-12);
    assert!((m.driven_tip_radius - 3.85 * 53.0 / 15.0).abs() < 1e-12);
    assert!((m.driver_root_radius - (3.85 - 1.1)).abs() < 1e-12);
    let d = m.driver_tip_radius + m.driven_tip_radius - 1.1 + 0.44;
    assert!((m.centre_distance - d).abs() < 1e-12);
    assert_eq!(m.tooth_height, 1.1);
    assert!(g.mesh_geometry("nope", 1.1, 40.0).is_none());
}

#[test]
fn one_wrong_tooth_count_changes_the_lunar_ratio() {
    let text = FREETH2006_RON.replace("(name: \"b2\", teeth: 64,", "(name: \"b2\", teeth: 63,");
    assert_ne!(text, FREETH2006_RON);
    let g = match Gearing::from_ron("b2-63.ron", &text) {
        Ok(g) => g,
        Err(e) => panic!("{e}"),
    };
    let lunar = g.pointer_ratio("Lunar");
    assert_ne!(lunar, Some(Ratio { num: 254, den: 19 }));
    assert_eq!(lunar, Some(Ratio::new(63 * 48 * 127, 38 * 24 * 32)));
}

/// The 2021 variant differs from the 2006 gearing in the measured radii only, each by the
/// difference between the S8 outer radius and the F06 mean radius, and so every sized tip
/// radius but f1's grows.
#[test]
fn freeth2021_differs_from_2006_in_radii_only() {
    let (a, b) = match (
        Gearing::builtin("freeth2006"),
        Gearing::from_ron("freeth2021.ron", train::FREETH2021_RON),
    ) {
        (Some(a), Ok(b)) => (a, b),
        (_, Err(e)) => panic!("embedded 2021 file must parse: {e}"),
        (None, _) => panic!("freeth2006 is a builtin name"),
    };
    assert_eq!(Gearing::builtin("freeth2021"), Some(b.clone()));
    assert_eq!(Gearing::builtin("freeth1901"), None);
    assert_eq!(a.meshes(), b.meshes());
    assert_eq!(a.pointers(), b.pointers());
    assert_eq!(a.arbors(), b.arbors());
    let mut larger = 0;
    for (x, y) in a.gears().iter().zip(b.gears()) {
        assert_eq!((&x.name, x.teeth), (&y.name, y.teeth));
        assert_eq!(
            x.measured_radius.is_none(),
            y.measured_radius.is_none(),
            "{}",
            x.name
        );
        if let (Some(r6), Some(r21)) = (x.measured_radius, y.measured_radius) {
            let moved = r21 - r6;
            assert!(moved.abs() <= 0.6 + 1e-9, "{}: {moved}", x.name);
            if x.name != "f1" {
                assert!(moved >= 0.15 - 1e-9, "{}: {moved}", x.name);
            }
        }
        let (ta, tb) = (a.tip_radius(&x.name), b.tip_radius(&x.name));
        if x.name != "f1" && x.name != "e4" && ta.zip(tb).is_some_and(|(p, q)| q > p) {
            larger += 1;
        }
    }
    assert!(larger >= 20, "only {larger} gears grew");
    assert_eq!(a.pin_and_slot(), b.pin_and_slot());
}

#[test]
fn pin_and_slot_section_is_read_and_the_turntable_is_reached() {
    let g = default_gearing();
    let Some(ps) = g.pin_and_slot() else {
        panic!("the default gearing has a pin-and-slot section")
    };
    assert_eq!(
        (
            ps.pin_gear.as_str(),
            ps.slot_gear.as_str(),
            ps.turntable.as_str()
        ),
        ("k1", "k2", "e3")
    );
    assert_eq!((ps.axis_offset, ps.pin_radius), (1.1, 9.6));
    assert!(!ps.source.is_empty());
    // The turntable is turned by the Saros train's first three meshes: 64/38 * 53/96 * 27/223.
    assert_eq!(
        g.mesh_path("b", "e turntable"),
        Some(vec!["b2-l1".into(), "l2-m1".into(), "m3-e3".into()])
    );
    assert_eq!(
        g.path_ratio("b", "e turntable"),
        Some(Ratio::new(64 * 53 * 27, 38 * 96 * 223))
    );
    assert_eq!(g.mesh_path("b", "b"), Some(vec![]));
    // No chain runs against the meshes' direction.
    assert_eq!(g.mesh_path("e turntable", "b"), None);
    assert_eq!(g.mesh_path("b", "nowhere"), None);
}

/// Tables print a gear by the name its mesh's label writes: the paper's Games mesh `n2-o1` is
/// driven by the file's `n3` (Freeth 2008's name), which tables call `n2`; every other gear
/// keeps its own name.
#[test]
fn gears_are_named_as_the_mesh_labels_write_them() {
    let g = Gearing::freeth2006();
    assert_eq!(g.label_name("n3"), "n2");
    assert_eq!(g.label_name("o1"), "o1");
    assert_eq!(g.label_name("b2"), "b2");
    let renamed: Vec<&str> = g
        .gears()
        .iter()
        .map(|gear| gear.name.as_str())
        .filter(|n| g.label_name(n) != *n)
        .collect();
    assert_eq!(renamed, ["n3"]);
}
