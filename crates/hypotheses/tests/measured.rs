//! The `measured` hypothesis: reading tables, the embedded example, per-gear values applied.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::f64::consts::TAU;

use geometry::Gear;
use hypotheses::{Describe, Hypothesis, MEASURED_EXAMPLE, Params, lookup, measured_from_ron};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

/// Every gear of the Freeth 2006 gearing with its tooth count.
const FREETH: [(&str, usize); 30] = [
    ("b1", 223),
    ("b2", 64),
    ("b3", 32),
    ("c1", 38),
    ("c2", 48),
    ("d1", 24),
    ("d2", 127),
    ("e1", 32),
    ("e2", 32),
    ("e3", 223),
    ("e4", 188),
    ("e5", 50),
    ("e6", 50),
    ("f1", 53),
    ("f2", 30),
    ("g1", 54),
    ("g2", 20),
    ("h1", 60),
    ("h2", 15),
    ("i1", 60),
    ("k1", 50),
    ("k2", 50),
    ("l1", 38),
    ("l2", 53),
    ("m1", 96),
    ("m2", 15),
    ("m3", 27),
    ("n1", 53),
    ("n3", 57),
    ("o1", 60),
];

fn sized_gear(n: usize) -> Gear {
    let r_tip = 0.25 * n as f64 + 0.5;
    Gear::ideal(n, r_tip, r_tip - 1.1).unwrap()
}

#[test]
fn example_table_covers_the_freeth_gearing_and_says_it_is_invented() {
    assert!(MEASURED_EXAMPLE.contains("INVENTED"));
    let table = measured_from_ron("measured-example.ron", MEASURED_EXAMPLE).unwrap();
    assert_eq!(table.split(), 0.5);
    let names: Vec<&str> = table.entries().map(|(n, _)| n).collect();
    let mut expected: Vec<&str> = FREETH.iter().map(|(n, _)| *n).collect();
    expected.sort_unstable();
    assert_eq!(names, expected);
}

#[test]
fn registered_measured_applies_to_every_freeth_gear() {
    let h = lookup("measured").unwrap();
    let p = Params::new(h, &[]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    for (name, teeth) in FREETH {
        let g = sized_gear(teeth);
        let made = h.apply(&g, name, &p, &mut rng).unwrap();
        assert_eq!(made.teeth(), teeth);
    }
    // scale 0 removes every error.
    let p = Params::new(h, &[("scale".into(), "0".into())]).unwrap();
    let g = sized_gear(53);
    let made = h.apply(&g, "f1", &p, &mut rng).unwrap();
    assert_eq!(made, g);
    let p = Params::new(h, &[("scale".into(), "-1".into())]).unwrap();
    let e = h.apply(&g, "f1", &p, &mut rng).unwrap_err();
    assert_eq!(e.what, "measured: scale");
}

#[test]
fn a_gear_missing_from_the_table_is_an_error_naming_it() {
    let h = lookup("measured").unwrap();
    let p = Params::new(h, &[]).unwrap();
    let e = h
        .apply(&sized_gear(40), "z9", &p, &mut ChaCha8Rng::seed_from_u64(2))
        .unwrap_err();
    assert_eq!(e.what, "measured-example.ron: gear z9");
    assert!(e.rule.contains("missing"), "{e}");
}

#[test]
fn a_users_table_gives_its_phase_amplitude_and_eccentricity() {
    let table = measured_from_ron(
        "mine.ron",
        r#"(
            gears: [
                (gear: "x1", random: 0.0, systematic: 2.0, phase: 30.0),
                (gear: "x2", random: 0.0, systematic: 2.0, phase: Some(30.0), split: 1.0),
            ],
        )"#,
    )
    .unwrap();
    assert_eq!(table.file_name(), "mine.ron");
    let h = table.hypothesis();
    assert_eq!(h.name(), "measured");
    let p = Params::new(&h, &[]).unwrap();
    let g = sized_gear(60);
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    for (name, split) in [("x1", 0.5), ("x2", 1.0)] {
        let made = h.apply(&g, name, &p, &mut rng).unwrap();
        // Fit d = a sin t + b cos t = s·sin(t + phase).
        let n = 60.0;
        let (mut a, mut b) = (0.0, 0.0);
        for (k, (m, d)) in made.tip_angles().iter().zip(g.tip_angles()).enumerate() {
            let t = TAU * k as f64 / n;
            a += (m - d) * t.sin() * 2.0 / n;
            b += (m - d) * t.cos() * 2.0 / n;
        }
        assert!(
            (a.hypot(b).to_degrees() - 2.0 * split).abs() < 1e-9,
            "{name}"
        );
        assert!((b.atan2(a).to_degrees() - 30.0).abs() < 1e-6, "{name}");
        let shift = g.tip_radius() * ((1.0 - split) * 2.0_f64).to_radians().tan();
        assert!(
            (made.rotation_centre().norm() - shift).abs() < 1e-12,
            "{name}"
        );
    }
}

#[test]
fn bad_tables_name_the_file_the_gear_and_the_rule() {
    let cases = [
        (
            r#"(gears: [(gear: "a", random: -0.1, systematic: 0.0)])"#,
            "bad.ron: gear a: random",
        ),
        (
            r#"(gears: [(gear: "a", random: 0.1, systematic: 1.0, split: 2.0)])"#,
            "bad.ron: gear a: split",
        ),
        (
            r#"(gears: [(gear: "a", random: 0.1, systematic: 0.0), (gear: "a", random: 0.1, systematic: 0.0)])"#,
            "bad.ron: gear a",
        ),
        (r#"(split: 1.5, gears: [])"#, "bad.ron: split"),
    ];
    for (text, what) in cases {
        let e = measured_from_ron("bad.ron", text).unwrap_err();
        assert_eq!(e.what, what, "{text}: {e}");
        assert!(!e.to_string().contains('\n'));
    }
    // A typo in a field name, and broken RON, give the position.
    let e = measured_from_ron(
        "bad.ron",
        r#"(gears: [(gear: "a", randm: 0.1, systematic: 0.0)])"#,
    )
    .unwrap_err();
    assert!(e.what.starts_with("bad.ron: line 1"), "{e}");
    assert!(e.rule.contains("randm"), "{e}");
    let e = measured_from_ron("bad.ron", "(gears: [").unwrap_err();
    assert!(e.what.starts_with("bad.ron: line"), "{e}");
}

#[test]
fn measured_colon_file_reads_the_users_table() {
    let dir = std::env::temp_dir().join(format!(
        "hypotheses-measured-file-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("mine.ron");
    std::fs::write(
        &file,
        r#"(gears: [(gear: "x1", random: 0.0, systematic: 2.0, phase: 30.0)])"#,
    )
    .unwrap();
    let name = format!("measured:{}", file.display());
    let h = lookup(&name).unwrap();
    assert_eq!(h.name(), name, "the name carries the file");
    assert!(
        std::ptr::eq(
            h as *const dyn Hypothesis as *const u8,
            lookup(&name).unwrap() as *const dyn Hypothesis as *const u8
        ),
        "read once per process"
    );
    let p = Params::new(h, &[]).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(3);
    let made = h.apply(&sized_gear(60), "x1", &p, &mut rng).unwrap();
    assert_ne!(made.tip_angles(), sized_gear(60).tip_angles());
    let e = h.apply(&sized_gear(60), "b1", &p, &mut rng).unwrap_err();
    assert!(e.to_string().contains("gear b1: missing"), "{e}");

    // Bad files name the file and the rule.
    let bad = dir.join("bad.ron");
    std::fs::write(
        &bad,
        r#"(gears: [(gear: "x1", random: NaN, systematic: 0.0)])"#,
    )
    .unwrap();
    let e = lookup(&format!("measured:{}", bad.display()))
        .err()
        .unwrap();
    assert!(
        e.to_string()
            .starts_with(&format!("{}: gear x1", bad.display())),
        "{e}"
    );
    std::fs::write(&bad, b"(gears: [\xff\xfe").unwrap();
    let e = lookup(&format!("measured:{}", bad.display()))
        .err()
        .unwrap();
    assert!(e.to_string().contains("cannot read"), "{e}");
    let e = lookup(&format!("measured:{}", dir.join("missing.ron").display()))
        .err()
        .unwrap();
    assert!(e.to_string().contains("missing.ron: cannot read"), "{e}");
    assert!(lookup("measured:").is_err());
    let e = lookup("nonsense").err().unwrap();
    assert!(e.rule.contains("measured:FILE"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Found by `cargo xtask fuzz` (docs/fuzzing.md): a name holding a newline made a two-line message.
#[test]
fn a_name_with_a_newline_gives_a_one_line_message() {
    let text = r#"(gears: [(gear: "a\nb", random: 0.1, systematic: 0.0), (gear: "a\nb", random: 0.1, systematic: 0.0)])"#;
    let e = measured_from_ron("bad.ron", text).unwrap_err();
    assert_eq!(e.to_string(), "bad.ron: gear a\\nb: listed twice");
    let e = measured_from_ron("bad\nname.ron", "(gears: [").unwrap_err();
    assert!(!e.to_string().contains('\n'), "{e}");
}
