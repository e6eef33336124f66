//! Every rule of `Gearing::from_ron`, each with a message naming the offending item.

use train::Gearing;

/// A small valid gearing: a -(a1,a2)-, b -(b1,b2)-, c (c1); meshes a1-b1, b2-c1; pointer P.
const BASE: &str = r#"(
    gears: [
        (name: "a1", teeth: 40, measured_radius: Some(10.0), source: "test"),
        (name: "a2", teeth: 20, measured_radius: Some(5.0), source: "test"),
        (name: "b1", teeth: 20, measured_radius: Some(5.0), source: "test"),
        (name: "b2", teeth: 30, measured_radius: None, source: "test"),
        (name: "c1", teeth: 60, measured_radius: Some(15.0), source: "test"),
    ],
    arbors: [
        (name: "a", gears: ["a1", "a2"]),
        (name: "b", gears: ["b1", "b2"]),
        (name: "c", gears: ["c1"]),
    ],
    meshes: [
        (label: "a1-b1", driver: "a1", driven: "b1"),
        (label: "b2-c1", driver: "b2", driven: "c1"),
    ],
    pointers: [
        (name: "P", input: "a", meshes: ["a1-b1", "b2-c1"], days: true),
    ],
)"#;

/// `BASE` with `from` replaced by `to` (which must occur).
fn edit(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from}");
    BASE.replacen(from, to, 1)
}

/// The error message for `text`, which must be rejected.
fn error(text: &str) -> String {
    match Gearing::from_ron("test.ron", text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn assert_error(text: &str, location: &str, words: &str) {
    let msg = error(text);
    assert!(
        msg.starts_with(&format!("test.ron: {location}: ")),
        "{msg:?} should name {location:?}"
    );
    assert!(msg.contains(words), "{msg:?} should contain {words:?}");
    assert!(!msg.contains('\n'), "{msg:?} is one line");
}

#[test]
fn base_is_valid() {
    let g = match Gearing::from_ron("test.ron", BASE) {
        Ok(g) => g,
        Err(e) => panic!("{e}"),
    };
    // 40/20 * 30/60 = 1.
    assert_eq!(
        g.pointer_ratio("P").map(|r| r.to_string()),
        Some("1/1".into())
    );
    // {a1, b1}, {a2} (in no mesh), {b2, c1}.
    assert_eq!(g.components().len(), 3);
    // b2 is lost and sized from c1: 30 * 15/60.
    assert_eq!(g.tip_radius("b2"), Some(7.5));
}

#[test]
fn syntax_error_names_line_and_column() {
    let text = edit(
        "teeth: 20, measured_radius: Some(5.0)",
        "teeth: 20 measured_radius: Some(5.0)",
    );
    let msg = error(&text);
    assert!(msg.starts_with("test.ron: line 4, column "), "{msg}");
    let msg = error(&edit("teeth: 40", "teeth: \"forty\""));
    assert!(msg.contains("line 3"), "{msg}");
}

#[test]
fn duplicates() {
    assert_error(
        &edit("\"a2\", teeth", "\"a1\", teeth"),
        "gear a1",
        "duplicate gear",
    );
    assert_error(
        &edit("(name: \"c\", gears", "(name: \"b\", gears"),
        "arbor b",
        "duplicate arbor",
    );
    assert_error(
        &edit("(label: \"b2-c1\"", "(label: \"a1-b1\""),
        "mesh a1-b1",
        "duplicate mesh",
    );
    let text = edit(
        "days: true),",
        "days: true), (name: \"P\", input: \"a\", meshes: [\"a1-b1\"], days: false),",
    );
    assert_error(&text, "pointer P", "duplicate pointer");
}

#[test]
fn gear_rules() {
    assert_error(
        &edit("teeth: 40", "teeth: 2"),
        "gear a1",
        "teeth must be at least 3",
    );
    assert_error(
        &edit("Some(10.0)", "Some(0.0)"),
        "gear a1",
        "must be above 0 and at most 10000 mm",
    );
    assert_error(
        &edit("Some(10.0)", "Some(-1.5)"),
        "gear a1",
        "must be above 0 and at most 10000 mm",
    );
    assert_error(
        &edit("Some(10.0)", "Some(inf)"),
        "gear a1",
        "must be above 0 and at most 10000 mm",
    );
    assert_error(
        &edit("Some(10.0)", "Some(NaN)"),
        "gear a1",
        "must be above 0 and at most 10000 mm",
    );
}

#[test]
fn arbor_rules() {
    assert_error(
        &edit("[\"c1\"]", "[\"c1\", \"z9\"]"),
        "arbor c",
        "unknown gear z9",
    );
    assert_error(
        &edit("[\"c1\"]", "[\"c1\", \"a2\"]"),
        "gear a2",
        "two arbors: a and c",
    );
    assert_error(
        &edit("[\"a1\", \"a2\"]", "[\"a1\"]"),
        "gear a2",
        "on no arbor",
    );
    assert_error(&edit("[\"c1\"]", "[]"), "arbor c", "no gears");
}

#[test]
fn mesh_rules() {
    assert_error(
        &edit("driven: \"c1\"", "driven: \"z9\""),
        "mesh b2-c1",
        "unknown gear z9",
    );
    assert_error(
        &edit("driver: \"a1\"", "driver: \"z9\""),
        "mesh a1-b1",
        "unknown gear z9",
    );
    assert_error(
        &edit(
            "driver: \"b2\", driven: \"c1\"",
            "driver: \"b2\", driven: \"b1\"",
        ),
        "mesh b2-c1",
        "both on arbor b",
    );
}

#[test]
fn unsizable_component() {
    let text = edit(
        "(name: \"c1\", teeth: 60, measured_radius: Some(15.0)",
        "(name: \"c1\", teeth: 60, measured_radius: None",
    );
    assert_error(&text, "mesh b2-c1", "cannot be sized");
    // A lost gear in no mesh cannot be sized either.
    let text = edit("(label: \"b2-c1\", driver: \"b2\", driven: \"c1\"),", "");
    let text = text.replace(", \"b2-c1\"]", "]");
    assert_error(&text, "gear b2", "cannot be sized");
}

#[test]
fn pointer_rules() {
    assert_error(
        &edit("input: \"a\"", "input: \"q\""),
        "pointer P",
        "unknown input arbor q",
    );
    assert_error(
        &edit("\"a1-b1\", \"b2-c1\"]", "\"a1-b1\", \"x-y\"]"),
        "pointer P",
        "unknown mesh x-y",
    );
    assert_error(
        &edit("[\"a1-b1\", \"b2-c1\"]", "[]"),
        "pointer P",
        "no meshes",
    );
    // First driver not on the input arbor.
    assert_error(
        &edit("input: \"a\"", "input: \"c\""),
        "pointer P",
        "not on the input arbor c",
    );
    // Second mesh does not start where the first ended.
    assert_error(
        &edit("[\"a1-b1\", \"b2-c1\"]", "[\"b2-c1\", \"a1-b1\"]"),
        "pointer P",
        "chain does not connect at mesh b2-c1",
    );
    assert_error(
        &edit("[\"a1-b1\", \"b2-c1\"]", "[\"a1-b1\", \"a1-b1\"]"),
        "pointer P",
        "driver a1 is on arbor a, not on arbor b",
    );
}

#[test]
fn error_display_is_file_location_rule() {
    let e = train::GearingError {
        file: "f.ron".into(),
        location: "gear m3".into(),
        rule: "bad".into(),
    };
    assert_eq!(e.to_string(), "f.ron: gear m3: bad");
}

#[test]
fn enormous_tooth_count_is_refused_with_the_limit() {
    assert_error(
        &edit("teeth: 40", "teeth: 1000000000"),
        "gear a1",
        "at most 100000",
    );
    assert_eq!(train::MAX_TEETH, 100_000);
}

#[test]
fn meshes_closing_a_loop_are_refused() {
    // A second mesh between arbors a and b.
    assert_error(
        &edit(
            r#"(label: "b2-c1", driver: "b2", driven: "c1"),"#,
            r#"(label: "b2-c1", driver: "b2", driven: "c1"),
        (label: "b1-a2", driver: "b1", driven: "a2"),"#,
        ),
        "mesh b1-a2",
        "closes a loop of meshes: arbors b and a",
    );
    // A ring a -> b -> c -> a.
    let ring = edit(
        r#"(label: "b2-c1", driver: "b2", driven: "c1"),"#,
        r#"(label: "b2-c1", driver: "b2", driven: "c1"),
        (label: "c1-a2", driver: "c1", driven: "a2"),"#,
    );
    assert_error(&ring, "mesh c1-a2", "arbors c and a are already joined");
}

#[test]
fn unknown_fields_of_every_item_are_refused() {
    for (from, to) in [
        ("teeth: 40,", "teeth: 40, colour: 3,"),
        (r#"(name: "a", gears"#, r#"(name: "a", colour: 3, gears"#),
        (r#"(label: "a1-b1","#, r#"(label: "a1-b1", colour: 3,"#),
        (r#"(name: "P","#, r#"(name: "P", colour: 3,"#),
    ] {
        let msg = error(&edit(from, to));
        assert!(msg.starts_with("test.ron: line "), "{msg}");
        assert!(msg.contains("colour"), "{msg}");
    }
}

// Found by `cargo xtask fuzz` (docs/fuzzing.md).

#[test]
fn a_misspelt_field_is_refused_not_ignored() {
    // `measured_radius` misspelt used to leave b1 unmeasured and sized from its partner.
    let msg = error(&edit(
        "(name: \"b1\", teeth: 20, measured_radius: Some(5.0)",
        "(name: \"b1\", teeth: 20, measured_radus: Some(5.0)",
    ));
    assert!(msg.starts_with("test.ron: line 5, column "), "{msg}");
    assert!(msg.contains("measured_radus"), "{msg}");
    for (from, to) in [
        ("(name: \"a\", gears:", "(name: \"a\", gear:"),
        ("(label: \"a1-b1\", driver:", "(label: \"a1-b1\", drive:"),
        ("days: true", "days: true, day: true"),
    ] {
        let msg = error(&edit(from, to));
        assert!(msg.starts_with("test.ron: line "), "{from}: {msg}");
    }
}

#[test]
fn radii_that_overflow_or_vanish_are_refused() {
    // a1: 1e308 mm is refused as no gear of a mechanism before the fit could overflow; a2 (in no
    // mesh): 5e-324 mm, the smallest float, passes that range and rounds to a zero tip radius.
    let msg = error(&edit(
        "(name: \"a1\", teeth: 40, measured_radius: Some(10.0)",
        "(name: \"a1\", teeth: 40, measured_radius: Some(1e308)",
    ));
    assert!(
        msg.starts_with("test.ron: gear a1: measured_radius must be above 0 and at most 10000 mm"),
        "{msg}"
    );
    let msg = error(&edit(
        "(name: \"a2\", teeth: 20, measured_radius: Some(5.0)",
        "(name: \"a2\", teeth: 20, measured_radius: Some(5e-324)",
    ));
    assert!(
        msg.starts_with("test.ron: gear a2: its tip radius") && msg.contains("positive finite"),
        "{msg}"
    );
}

#[test]
fn a_name_with_a_newline_gives_a_one_line_message() {
    assert_error(
        &edit("gears: [\"c1\"]", "gears: [\"c\\n1\"]"),
        "arbor c",
        "unknown gear c\\n1",
    );
}

/// `BASE` with a pin-and-slot on arbor b (pin gear b1 driven by a1, slot gear b2 driving c1) and a
/// turntable arbor t (t1, turned from the input arbor a by mesh a2-t1), and `section` as its
/// `pin_and_slot` field.
fn with_pin_and_slot(section: &str) -> String {
    let text = edit(
        r#"(name: "c1", teeth: 60, measured_radius: Some(15.0), source: "test"),"#,
        r#"(name: "c1", teeth: 60, measured_radius: Some(15.0), source: "test"),
        (name: "t1", teeth: 80, measured_radius: Some(20.0), source: "test"),"#,
    )
    .replacen(
        r#"(name: "c", gears: ["c1"]),"#,
        r#"(name: "c", gears: ["c1"]),
        (name: "t", gears: ["t1"]),"#,
        1,
    )
    .replacen(
        r#"(label: "b2-c1", driver: "b2", driven: "c1"),"#,
        r#"(label: "b2-c1", driver: "b2", driven: "c1"),
        (label: "a2-t1", driver: "a2", driven: "t1"),"#,
        1,
    );
    let end = text.rfind(')').unwrap_or(text.len());
    format!("{}    pin_and_slot: {section},\n)", &text[..end])
}

const PIN_AND_SLOT: &str = r#"Some((pin_gear: "b1", slot_gear: "b2", turntable: "t1", axis_offset: 1.0, pin_radius: 8.0, source: "test"))"#;

#[test]
fn pin_and_slot_section_is_optional_and_validated() {
    // Absent (as in BASE) or None: no pin-and-slot.
    let none = Gearing::from_ron("test.ron", &with_pin_and_slot("None"));
    assert!(none.is_ok_and(|g| g.pin_and_slot().is_none()));
    let g = match Gearing::from_ron("test.ron", &with_pin_and_slot(PIN_AND_SLOT)) {
        Ok(g) => g,
        Err(e) => panic!("{e}"),
    };
    assert_eq!(g.pin_and_slot().map(|p| p.pin_radius), Some(8.0));
    assert_eq!(g.mesh_path("a", "t"), Some(vec!["a2-t1".to_string()]));
    for (from, to, location, words) in [
        (
            r#"pin_gear: "b1""#,
            r#"pin_gear: "x9""#,
            "pin_and_slot.pin_gear",
            "unknown gear x9",
        ),
        (
            r#"slot_gear: "b2""#,
            r#"slot_gear: "b1""#,
            "pin_and_slot.slot_gear",
            "must differ",
        ),
        (
            r#"slot_gear: "b2""#,
            r#"slot_gear: "c1""#,
            "pin_and_slot.slot_gear",
            "not on the pin gear's arbor b",
        ),
        (
            r#"turntable: "t1""#,
            r#"turntable: "b2""#,
            "pin_and_slot.turntable",
            "must be another arbor",
        ),
        (
            "axis_offset: 1.0",
            "axis_offset: 0.0",
            "pin_and_slot.axis_offset",
            "must be above 0 and at most 10000 mm",
        ),
        (
            "axis_offset: 1.0",
            "axis_offset: -1.0",
            "pin_and_slot.axis_offset",
            "must be above 0 and at most 10000 mm",
        ),
        (
            "pin_radius: 8.0",
            "pin_radius: inf",
            "pin_and_slot.pin_radius",
            "must be above 0 and at most 10000 mm",
        ),
        (
            "axis_offset: 1.0",
            "axis_offset: 8.0",
            "pin_and_slot.axis_offset",
            "less than the pin radius 8 mm",
        ),
        // The slot gear must drive the train on: swap the roles.
        (
            r#"pin_gear: "b1", slot_gear: "b2""#,
            r#"pin_gear: "b2", slot_gear: "b1""#,
            "pin_and_slot.pin_gear",
            "does not drive the pin gear b2",
        ),
    ] {
        let section = PIN_AND_SLOT.replacen(from, to, 1);
        assert_ne!(section, PIN_AND_SLOT, "{from}");
        assert_error(&with_pin_and_slot(&section), location, words);
    }
    // The turntable cannot be turned from the input arbor: t1 driven by nothing the input reaches.
    let unreachable = with_pin_and_slot(PIN_AND_SLOT).replacen(
        r#"(label: "a2-t1", driver: "a2", driven: "t1"),"#,
        r#"(label: "t1-a2", driver: "t1", driven: "a2"),"#,
        1,
    );
    assert_error(
        &unreachable,
        "pin_and_slot.turntable",
        "no chain of meshes turns the turntable arbor t",
    );
    // A pin-and-slot no pointer runs through.
    let idle = with_pin_and_slot(PIN_AND_SLOT).replacen(
        r#"meshes: ["a1-b1", "b2-c1"]"#,
        r#"meshes: ["a2-t1"]"#,
        1,
    );
    assert_error(
        &idle,
        "pin_and_slot.pin_gear",
        "no pointer's train runs through",
    );
    // Unknown fields of the section are refused, like every other item's.
    let colour =
        with_pin_and_slot(&PIN_AND_SLOT.replacen("pin_radius:", "colour: 3, pin_radius:", 1));
    let msg = error(&colour);
    assert!(
        msg.starts_with("test.ron: line ") && msg.contains("colour"),
        "{msg}"
    );
}
