//! Looking hypotheses up, building their parameters, and the listing.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use hypotheses::{Params, hypotheses, listing, lookup};

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

/// Files in `crates/hypotheses/src/plugins/`, found by `build.rs` with no `mod` line anywhere.
const PLUGINS: [&str; 4] = [
    "asymmetric-teeth",
    "curved-flanks",
    "non-circular",
    "ratio-mismatch",
];

#[test]
fn built_ins_are_registered_and_sorted() {
    let all = hypotheses().unwrap();
    for name in BUILT_INS.into_iter().chain(PLUGINS) {
        assert_eq!(all[name].name(), name);
    }
    let names: Vec<&str> = all.keys().copied().collect();
    let mut sorted = names.clone();
    sorted.sort_unstable();
    assert_eq!(names, sorted);
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
    assert_eq!(p.get("random"), 0.04);
    assert_eq!(p.get("systematic"), 0.5);
    assert_eq!(p.get("split"), 0.5);
    let p = Params::new(
        h,
        &sets(&[("systematic", " 2 "), ("split", "0"), ("split", "0.25")]),
    )
    .unwrap();
    assert_eq!(p.get("systematic"), 2.0);
    assert_eq!(p.get("split"), 0.25);
    assert_eq!(p.try_get("phase"), None);
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
