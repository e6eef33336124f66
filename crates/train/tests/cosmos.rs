//! The cosmos gearings (Freeth et al. 2021, Freeth & Jones 2012): every period relation checked
//! exactly from the tooth counts, the back left as the paper's, the sources named, and the new
//! sections' rules.

use train::{
    DeviceKind, FREETH2006_RON, FREETH2012_COSMOS_RON, FREETH2021_COSMOS_RON, Gearing, Rate, Sizing,
};

fn load(name: &str, text: &str) -> Gearing {
    match Gearing::from_ron(name, text) {
        Ok(g) => g,
        Err(e) => panic!("embedded file must parse: {e}"),
    }
}

fn f21() -> Gearing {
    load("freeth2021-cosmos.ron", FREETH2021_COSMOS_RON)
}

fn fj12() -> Gearing {
    load("freeth2012-cosmos.ron", FREETH2012_COSMOS_RON)
}

fn rate(num: i128, den: i128) -> Rate {
    Rate::new(num, den).unwrap_or(Rate::ZERO)
}

/// The rate of `gear`'s arbor relative to b1, per year.
fn relative(g: &Gearing, gear: &str) -> Option<Rate> {
    g.relative_rate(g.arbor_of(gear)?)
}

#[test]
fn both_are_embedded_by_name() {
    assert_eq!(Gearing::builtin("freeth2021-cosmos"), Some(f21()));
    assert_eq!(Gearing::builtin("freeth2012-cosmos"), Some(fj12()));
}

#[test]
fn freeth2021_period_relations_are_exact() {
    let g = f21();
    // Synodic periods: each epicycle's (or pin gear's) turns relative to b1 per year.
    for (gear, num, den) in [
        ("me20", 1513, 480),
        ("ve63", 289, 462),
        ("ma71", 133, 284),
        ("ju43", 315, 344),
        ("sa68", 427, 442),
        ("su56", -1, 1),
    ] {
        assert_eq!(relative(&g, gear), Some(rate(num, den)), "{gear}");
    }
    // Outputs in the frame of the mechanism: sidereal turns a year.
    for (pointer, num, den) in [
        ("Mars", 151, 284),
        ("Jupiter", 29, 344),
        ("Saturn", 15, 442),
        ("Nodes", -5, 93),
        ("Sun", 0, 1),
    ] {
        assert_eq!(g.pointer_rate(pointer), Some(rate(num, den)), "{pointer}");
    }
    assert_eq!(g.differential_rate("Moon phase"), Some(rate(235, 19)));
    // The back is the paper's: the Lunar pointer 254/19, the Saros 940/4237 (backwards).
    assert_eq!(g.pointer_rate("Lunar"), Some(rate(254, 19)));
    assert_eq!(
        g.pointer_ratio("Saros"),
        Gearing::freeth2006().pointer_ratio("Saros")
    );
}

#[test]
fn freeth2012_period_relations_are_exact() {
    let g = fj12();
    for (pointer, num, den) in [
        ("Mercury", 104, 33),
        ("Venus", 5, 8),
        ("Sun", -1, 1),
        ("Mars", 37, 79),
        ("Jupiter", 76, 83),
        ("Saturn", 57, 59),
    ] {
        let pin = g
            .device(pointer)
            .map(|d| d.pin_gear.clone())
            .unwrap_or_default();
        assert_eq!(relative(&g, &pin), Some(rate(num, den)), "{pointer}");
    }
    // FJ12 3.7.1: Rot(G2) = 37/79 + 1 = 116/79, and Mars's output 1 - 37/79 = 42/79.
    assert_eq!(g.rate_from("b", "ma1"), Some(rate(116, 79)));
    for (pointer, num, den) in [("Mars", 42, 79), ("Jupiter", 7, 83), ("Saturn", 2, 59)] {
        assert_eq!(g.pointer_rate(pointer), Some(rate(num, den)), "{pointer}");
    }
}

/// The check can fail: one tooth more on one gear moves the rate it checks.
#[test]
fn one_wrong_tooth_count_changes_the_rate() {
    for (from, to, gear, num, den) in [
        (
            "name: \"ve34\", teeth: 34,",
            "name: \"ve34\", teeth: 35,",
            "ve63",
            289,
            462,
        ),
        (
            "name: \"sa61\", teeth: 61,",
            "name: \"sa61\", teeth: 62,",
            "sa68",
            427,
            442,
        ),
        (
            "name: \"fix51\", teeth: 51,",
            "name: \"fix51\", teeth: 52,",
            "me20",
            1513,
            480,
        ),
    ] {
        assert_eq!(FREETH2021_COSMOS_RON.matches(from).count(), 1, "{from}");
        let text = FREETH2021_COSMOS_RON.replace(from, to);
        let g = load("edited.ron", &text);
        let got = relative(&g, gear);
        assert!(
            got.is_some() && got != Some(rate(num, den)),
            "{gear}: {got:?}"
        );
    }
    // The signs are counted too: the true Sun's epicycle, two meshes from the fixed gear, keeps
    // its orientation (rate zero in the frame of the mechanism), where one mesh fewer would
    // turn it twice a year.
    let g = f21();
    assert_eq!(g.rate_from("b", "su1"), Some(Rate::ZERO));
    assert_eq!(g.rate_from("b", "sa1"), Some(rate(52 + 56, 52)));
}

/// The back of both cosmos files is freeth2006.ron, item for item and in its order.
#[test]
fn the_back_is_the_papers_gearing() {
    let paper = Gearing::freeth2006();
    for g in [f21(), fj12()] {
        for (i, gear) in paper.gears().iter().enumerate() {
            assert_eq!(&g.gears()[i], gear);
        }
        for (i, m) in paper.meshes().iter().enumerate() {
            assert_eq!(&g.meshes()[i], m);
            // Sized alike: the same mesh geometry as the paper's at h 1.1 mm, G 40 %.
            assert_eq!(
                g.mesh_geometry(&m.label, 1.1, 40.0),
                paper.mesh_geometry(&m.label, 1.1, 40.0)
            );
        }
        for (i, a) in paper.arbors().iter().enumerate() {
            assert_eq!(&g.arbors()[i], a);
        }
        for (i, p) in paper.pointers().iter().enumerate() {
            assert_eq!(&g.pointers()[i], p);
        }
        assert_eq!(g.pin_and_slot(), paper.pin_and_slot());
    }
    assert!(FREETH2021_COSMOS_RON.contains(
        &FREETH2006_RON[FREETH2006_RON.find("        (name: \"b1\"").unwrap_or(0)..][..200]
    ));
}

/// Every cosmos gear says where its tooth count comes from (primary or secondary) and whether
/// its radius was measured or sized by a rule; every device and section names its source.
#[test]
fn every_cosmos_gear_names_its_source() {
    for (g, name) in [(f21(), "F21"), (fj12(), "FJ12")] {
        let e = g.epicyclic().cloned();
        let Some(e) = e else {
            panic!("{name}: no epicyclic section")
        };
        assert!(!e.source.is_empty());
        let cosmos: Vec<&str> = g
            .arbors()
            .iter()
            .filter(|a| g.in_epicyclic(&a.name))
            .flat_map(|a| a.gears.iter().map(String::as_str))
            .collect();
        assert!(cosmos.len() >= 16, "{name}: {}", cosmos.len());
        for gear in cosmos {
            let d = g.gear(gear).cloned().unwrap_or_else(|| panic!("{gear}"));
            let s = d.source.to_lowercase();
            assert!(
                s.contains("primary") || s.contains("secondary"),
                "{gear}: {s}"
            );
            assert!(s.contains("measured") || s.contains("sized"), "{gear}: {s}");
            assert_eq!(d.sizing, Sizing::Pitch, "{gear}");
            // Measured or designed, never both; where neither, sized from its group.
            assert!(
                !(d.measured_radius.is_some() && d.design_radius.is_some()),
                "{gear}"
            );
            let r = g.tip_radius_at(gear, 1.1).unwrap_or(f64::NAN);
            assert!(r > 1.1 && g.tip_radius(gear).is_none(), "{gear}: {r}");
        }
        for d in g.devices() {
            assert!(
                d.source.contains("primary") || d.source.contains("secondary"),
                "{}",
                d.pointer
            );
        }
    }
    // The surviving Fragment D gear is measured, every other F21 cosmos gear sized by the rule.
    let g = f21();
    assert!(
        g.gear("ve63")
            .is_some_and(|d| d.measured_radius.is_some() && d.source.contains("survives"))
    );
    assert!(
        g.gear("ma71")
            .is_some_and(|d| d.source.contains("hypothetical"))
    );
}

#[test]
fn pitch_sizing_is_freeth_and_jones_rule() {
    let g = f21();
    // Module 0.5 mm: pitch radius 0.25 mm per tooth, tip half a tooth height out.
    let h = 1.1;
    let pitch = g.fitted_radius("ma71").unwrap_or(f64::NAN);
    assert!((pitch - 71.0 * 0.25).abs() < 1e-12, "{pitch}");
    assert_eq!(g.tip_radius_at("ma71", h), Some(pitch + h / 2.0));
    // A mesh's centre distance at G (% of h) is the pitch radii plus G: FJ12's margin.
    let m = g
        .mesh_geometry("ma40-ma71", h, 40.0)
        .unwrap_or_else(|| panic!("mesh"));
    let pitches = 0.25 * (40.0 + 71.0);
    assert!(
        (m.centre_distance - (pitches + 0.44)).abs() < 1e-12,
        "{m:?}"
    );
    // The Venus group takes the surviving 63's module.
    let v = g.fitted_radius("ve26").unwrap_or(f64::NAN) / 26.0;
    assert!((v - 16.41 / 63.0).abs() < 1e-12);
    // The back is sized as the paper's: its tip radius whatever h.
    assert_eq!(g.tip_radius_at("b2", 0.3), g.tip_radius("b2"));
    // FJ12's Mercury pair (modules 0.38 / 0.40) gets one least-squares module.
    let j = fj12();
    let mu = (104.0 * 19.9 + 33.0 * 6.6) / (104.0f64.powi(2) + 33.0f64.powi(2));
    assert!((j.fitted_radius("me33").unwrap_or(f64::NAN) - 33.0 * mu).abs() < 1e-12);
}

#[test]
fn devices_and_margins_are_read() {
    let g = f21();
    let mars = g.device("Mars").cloned().unwrap_or_else(|| panic!("Mars"));
    assert_eq!(
        (mars.kind, mars.axis_offset, mars.pin_radius),
        (DeviceKind::SlotGear, 6.58, 10.0)
    );
    assert_eq!(mars.slot_gear.as_deref(), Some("ma80"));
    let venus = g
        .device("Venus")
        .cloned()
        .unwrap_or_else(|| panic!("Venus"));
    assert_eq!(venus.kind, DeviceKind::Follower);
    // Venus's greatest elongation, 46 degrees, from the pin and offset.
    let elong = (venus.pin_radius / venus.axis_offset).asin().to_degrees();
    assert!((elong - 46.0).abs() < 0.1, "{elong}");
    // The superior planets' pin / offset are their mean distances in AU.
    for (p, au) in [("Mars", 1.52), ("Jupiter", 5.20), ("Saturn", 9.58)] {
        let d = g.device(p).cloned().unwrap_or_else(|| panic!("{p}"));
        assert!((d.pin_radius / d.axis_offset - au).abs() < 0.01, "{p}");
    }
    assert_eq!(g.mesh("ma40-ma71").and_then(|m| m.margin), Some(0.4));
    assert_eq!(fj12().mesh("ve40-ve64").and_then(|m| m.margin), Some(0.2));
    assert_eq!(g.meshes().len(), 15 + 20);
    assert_eq!(fj12().meshes().len(), 15 + 10);
    assert!(g.is_epicyclic_pointer("Venus") && !g.is_epicyclic_pointer("Lunar"));
}

/// `text` with `from` replaced by `to` (which must be there once).
fn edit(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from}");
    text.replace(from, to)
}

/// The error a bad cosmos file gives: one line naming the file, the item or field, the rule.
fn refused(text: &str, location: &str, words: &str) {
    match Gearing::from_ron("bad-cosmos.ron", text) {
        Ok(_) => panic!("accepted, wanted {location}: {words}"),
        Err(e) => {
            let msg = e.to_string();
            assert!(msg.starts_with("bad-cosmos.ron: "), "{msg}");
            assert_eq!(e.location, location, "{msg}");
            assert!(e.rule.contains(words), "{msg}");
            assert!(!msg.contains('\n'), "{msg}");
        }
    }
}

#[test]
fn bad_cosmos_files_are_refused_naming_file_field_and_rule() {
    let t = FREETH2021_COSMOS_RON;
    refused(
        &edit(t, "fixed: \"frame\"", "fixed: \"fram\""),
        "epicyclic.fixed",
        "unknown arbor fram",
    );
    refused(
        &edit(t, "fixed: \"frame\"", "fixed: \"b\""),
        "epicyclic.fixed",
        "must differ from the carrier",
    );
    refused(
        &edit(t, "\"nd1\", \"nd2\"]", "\"nd1\"]"),
        "mesh nd64-nd48",
        "joins an arbor of the epicyclic system",
    );
    refused(
        &edit(
            t,
            "pin_gear: \"ve63\", axis_offset: 27.8, pin_radius: 20.01",
            "pin_gear: \"ve63\", axis_offset: 27.8, pin_radius: 28.0",
        ),
        "devices[1].pin_radius",
        "must be less than the axis offset",
    );
    refused(
        &edit(
            t,
            "axis_offset: 6.58, pin_radius: 10.0",
            "axis_offset: 10.5, pin_radius: 10.0",
        ),
        "devices[3].axis_offset",
        "must be less than the pin radius",
    );
    refused(
        &edit(t, "slot_gear: Some(\"ma80\")", "slot_gear: Some(\"ma80o\")"),
        "devices[3].slot_gear",
        "on the pin gear's arbor",
    );
    refused(
        &edit(t, "pin_gear: \"me20\"", "pin_gear: \"me40\""),
        "devices[0].pin_gear",
        "last mesh drives",
    );
    refused(
        &edit(t, "(pointer: \"Venus\"", "(pointer: \"Lunar\""),
        "devices[1].pointer",
        "not run in a carrier's frame",
    );
    refused(
        &edit(t, "(pointer: \"Sun\"", "(pointer: \"Venus\""),
        "devices[1].pointer",
        "has two devices",
    );
    refused(
        &edit(
            t,
            "label: \"ma40-ma71\", driver: \"ma40\", driven: \"ma71\", margin: Some(0.4)",
            "label: \"ma40-ma71\", driver: \"ma40\", driven: \"ma71\", margin: Some(-0.4)",
        ),
        "mesh ma40-ma71",
        "margin must be at least 0",
    );
    refused(
        &edit(
            t,
            "name: \"ma71\", teeth: 71, measured_radius: None, design_radius: Some(17.75), sizing: Pitch",
            "name: \"ma71\", teeth: 71, measured_radius: None, design_radius: Some(17.75)",
        ),
        "gear ma71",
        "needs `sizing: Pitch`",
    );
    refused(
        &edit(
            t,
            "name: \"ma71\", teeth: 71, measured_radius: None,",
            "name: \"ma71\", teeth: 71, measured_radius: Some(17.0),",
        ),
        "gear ma71",
        "has both measured_radius and design_radius",
    );
    refused(
        &edit(
            t,
            "name: \"ma40\", teeth: 40, measured_radius: None, design_radius: Some(10.00), sizing: Pitch",
            "name: \"ma40\", teeth: 40, measured_radius: Some(10.0)",
        ),
        "gear ma40",
        "differs from gear",
    );
    refused(
        &edit(t, "plus: \"moon\"", "plus: \"sun\""),
        "differentials[0].plus",
        "unknown arbor sun",
    );
    refused(
        &edit(t, "driven_teeth: 20", "driven_teeth: 2"),
        "differentials[0].driven_teeth",
        "at least 3",
    );
    refused(
        &edit(
            t,
            "(name: \"Nodes\", input: \"frame\"",
            "(name: \"Nodes\", input: \"nd1\"",
        ),
        "pointer Nodes",
        "chain does not connect",
    );
    // A gear meshing itself, or a mesh within one carried arbor, is refused as in the paper's file.
    refused(
        &edit(
            t,
            "driver: \"ma40\", driven: \"ma71\"",
            "driver: \"ma80\", driven: \"ma71\"",
        ),
        "mesh ma40-ma71",
        "both on arbor ma3",
    );
    // A misspelt field of the new sections is refused, not ignored.
    refused(
        &edit(
            t,
            "kind: SlotGear, pin_gear: \"ju43\"",
            "kind: SlotGear, pin_gaer: \"ju43\"",
        ),
        "line 265, column 54",
        "pin_gaer",
    );
}
