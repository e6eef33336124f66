//! Looking hypotheses up, building their parameters, and the listing.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use hypotheses::{Params, hypotheses, listing, lookup};

/// The hypotheses the other tests below use by name.
const BUILT_INS: [&str; 5] = [
    "ideal",
    "edmunds-split",
    "eccentric-only",
    "sinusoid-only",
    "measured",
];

fn sets(pairs: &[(&str, &str)]) -> Vec<(String, String)> {
    pairs
        .iter()
        .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
        .collect()
}

/// The files in `crates/hypotheses/src/plugins/` (file `a_b.rs` registers `a-b`), found by
/// `build.rs` with no `mod` line or list anywhere.
fn plugin_files() -> Vec<String> {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/plugins");
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "rs"))
        .map(|p| p.file_stem().unwrap().to_string_lossy().replace('_', "-"))
        .collect();
    names.sort_unstable();
    names
}

#[test]
fn every_plugin_file_registers_its_hypothesis_and_nothing_else_is_registered() {
    let all = hypotheses().unwrap();
    for name in BUILT_INS {
        assert_eq!(all[name].name(), name);
    }
    // One hypothesis per file, named after it: the registry is the list (the pinned
    // `snapshots/hypotheses.snap` shows a new one in review).
    let registered: Vec<&str> = all.keys().copied().collect();
    assert_eq!(registered, plugin_files());
}

#[test]
fn unknown_name_lists_every_registered_one() {
    let e = lookup("edmunds").err().unwrap();
    assert!(e.what.contains("`edmunds`"), "{e}");
    for name in hypotheses().unwrap().keys() {
        assert!(e.rule.contains(name), "{name} not in: {e}");
    }
    assert!(!e.to_string().contains('\n'));
}

#[test]
fn params_are_defaults_then_overrides() {
    let h = lookup("edmunds-split").unwrap();
    let p = Params::new(h, &[]).unwrap();
    assert_eq!(value(&p, "random").unwrap(), 0.04);
    assert_eq!(value(&p, "systematic").unwrap(), 0.5);
    assert_eq!(value(&p, "split").unwrap(), 0.5);
    let p = Params::new(h, &sets(&[("systematic", " 2 "), ("split", "0.25")])).unwrap();
    assert_eq!(value(&p, "systematic").unwrap(), 2.0);
    assert_eq!(value(&p, "split").unwrap(), 0.25);
    assert_eq!(value(&p, "phase"), None);
    assert_eq!(
        p.iter().collect::<Vec<_>>(),
        [("random", 0.04), ("split", 0.25), ("systematic", 2.0)]
    );
}

#[test]
fn bad_params_name_the_key_the_hypothesis_and_the_known_keys() {
    let h = lookup("edmunds-split").unwrap();
    let e = Params::new(h, &sets(&[("randum", "0.1")])).unwrap_err();
    assert!(
        e.what.contains("randum") && e.what.contains("edmunds-split"),
        "{e}"
    );
    assert!(
        e.rule.contains("random") && e.rule.contains("systematic") && e.rule.contains("split"),
        "{e}"
    );
    for bad in ["abc", "", "inf", "NaN", "-inf", "1e999"] {
        let e = Params::new(h, &sets(&[("random", bad)])).unwrap_err();
        assert!(e.what.contains("`random`"), "{bad}: {e}");
        assert!(e.rule.contains("number"), "{bad}: {e}");
        assert!(e.rule.contains("known keys"), "{bad}: {e}");
        assert!(!e.to_string().contains('\n'));
    }
    // eccentric-only has no split.
    let h = lookup("eccentric-only").unwrap();
    let e = Params::new(h, &sets(&[("split", "0.5")])).unwrap_err();
    assert!(
        e.what.contains("`split`") && e.what.contains("eccentric-only"),
        "{e}"
    );
    let h = lookup("ideal").unwrap();
    let e = Params::new(h, &sets(&[("random", "0.1")])).unwrap_err();
    assert!(e.rule.contains("takes no parameters"), "{e}");
}

#[test]
fn listing_shows_every_hypothesis_with_its_params() {
    let s = listing();
    for name in BUILT_INS {
        assert!(s.contains(&format!("{name}: ")), "{name} missing:\n{s}");
    }
    for p in [
        "random",
        "systematic",
        "split",
        "scale",
        "0.04",
        "deg",
        "pitch",
    ] {
        assert!(s.contains(p), "{p} missing:\n{s}");
    }
    assert!(s.contains("INVENTED"), "{s}");
}

/// `a+b` applies `a`, then `b` to what `a` made, from the same random stream, and declares both
/// parameter lists; the stack is built once per name.
#[test]
fn a_stack_applies_its_layers_in_order() {
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;

    let stack = lookup("edmunds-split+asymmetric-teeth").unwrap();
    assert_eq!(stack.name(), "edmunds-split+asymmetric-teeth");
    assert!(std::ptr::addr_eq(
        stack,
        lookup("edmunds-split+asymmetric-teeth").unwrap()
    ));
    let names: Vec<&str> = stack.params().iter().map(|p| p.name).collect();
    assert_eq!(names, ["random", "systematic", "split", "valley_shift"]);
    let p = Params::new(stack, &sets(&[("valley_shift", "0.1"), ("random", "0.08")])).unwrap();
    let (edm, asym) = (
        lookup("edmunds-split").unwrap(),
        lookup("asymmetric-teeth").unwrap(),
    );
    let designed = geometry::Gear::ideal(48, 11.0, 9.9).unwrap();
    let made = stack
        .apply(&designed, "c2", &p, &mut ChaCha8Rng::seed_from_u64(4))
        .unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let by_hand = edm.apply(&designed, "c2", &p, &mut rng).unwrap();
    let by_hand = asym.apply(&by_hand, "c2", &p, &mut rng).unwrap();
    assert_eq!(made, by_hand);
    // Both layers acted: the tips moved (Edmunds) and the valleys left the midpoints.
    assert_ne!(made.tip_angles(), designed.tip_angles());
    let t = made.tip_angles();
    assert!((0..47).any(|k| (made.valley_angles()[k] - 0.5 * (t[k] + t[k + 1])).abs() > 1e-6));
}

#[test]
fn a_stack_with_an_empty_repeated_or_unknown_layer_or_a_shared_parameter_is_refused() {
    let e = lookup("edmunds-split+").err().unwrap();
    assert!(e.rule.contains("none of them empty"), "{e}");
    let e = lookup("ideal+ideal").err().unwrap();
    assert!(e.rule.contains("twice"), "{e}");
    let e = lookup("edmunds-split+curly-teeth").err().unwrap();
    assert!(e.what.contains("`curly-teeth`"), "{e}");
    let e = lookup("edmunds-split+eccentric-only").err().unwrap();
    assert!(
        e.rule
            .contains("declared by both `edmunds-split` and `eccentric-only`"),
        "{e}"
    );
}

/// A parameter's value by its name, as a test reads it (plugins read by declaration).
fn value(p: &Params, name: &str) -> Option<f64> {
    p.iter().find(|(k, _)| *k == name).map(|(_, v)| v)
}
