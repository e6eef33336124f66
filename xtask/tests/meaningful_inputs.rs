//! Inputs that would run but give meaningless numbers, or a title or message about other inputs
//! than those used, are refused before anything runs: exit status 2 and one line naming the flag,
//! the field and the rule broken.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

mod support;
use support::{Scratch, stderr, stdout, xtask};

/// Runs `xtask args` (`{out}` stands for a scratch results dir) and asserts it is refused as bad
/// input in one line holding every one of `words`; returns that line.
fn refused(args: &str, words: &[&str]) -> String {
    let scratch = Scratch::new("meaningful-inputs");
    let out = scratch.path("out");
    let line = args.replace("{out}", &out);
    let argv: Vec<&str> = line.split(' ').collect();
    let o = xtask(&argv);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args}: {err}");
    assert_eq!(err.lines().count(), 1, "{args}: one line: {err}");
    for w in words {
        assert!(err.contains(w), "{args}: `{w}` missing from: {err}");
    }
    assert!(
        !std::path::Path::new(&out).exists(),
        "{args}: nothing may be written"
    );
    err
}

#[test]
fn counts_and_spans_below_what_their_statistic_needs_are_refused() {
    for (args, words) in [
        (
            "run fig3 --set samples=0 --out {out}",
            &["--set: samples: must be at least 100"][..],
        ),
        (
            "run fig3 --set samples=1 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run fig3 --set pitches=0 --out {out}",
            &["--set: pitches: must be at least 1"],
        ),
        (
            "run fig3 --set pitches=1000 --set samples=1000 --out {out}",
            &["--set: samples: must be at least 4000 for pitches = 1000"],
        ),
        (
            "run fig5 --set samples=0 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run fig5 --set teeth=1000 --out {out}",
            &["--set: samples: must be at least 4000 for teeth = 1000"],
        ),
        (
            "run fig5 --set teeth=2 --out {out}",
            &["--set: teeth: must be at least 3"],
        ),
        (
            "run fig2 --set teeth=0 --out {out}",
            &["--set: teeth: must be at least 3"],
        ),
        (
            "run fig4 --set samples=2 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run clearance --set samples=1 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run figIV --set samples=1 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run sigma-causes --set samples=1 --out {out}",
            &["--set: samples: must be at least 100"],
        ),
        (
            "run sigma-causes --set draws=0 --out {out}",
            &["--set: draws: must be at least 1"],
        ),
        (
            "run sigma-causes --set samples_per_engagement=0 --out {out}",
            &["--set: samples_per_engagement: must be at least 2"],
        ),
        (
            "run table1 --set lunar_turns=1e-300 --out {out}",
            &["--set: lunar_turns: must be between 0.05 and 100"],
        ),
        (
            "run table6 --set exeligmos_turns=0.001 --out {out}",
            &["--set: exeligmos_turns: must be between 0.05 and 100"],
        ),
        (
            "run table1 --set samples_per_engagement=0 --out {out}",
            &["--set: samples_per_engagement: must be at least 2"],
        ),
        (
            "run table2 --set samples_per_engagement=1 --out {out}",
            &["--set: samples_per_engagement: must be at least 2"],
        ),
        (
            "run lunar-anomaly --set samples_per_engagement=0 --out {out}",
            &["--set: samples_per_engagement: must be at least 2"],
        ),
        (
            "run lunar-anomaly --set lunar_turns=0.01 --out {out}",
            &["--set: lunar_turns: must be between 0.05 and 100"],
        ),
    ] {
        refused(args, words);
    }
}

#[test]
fn help_states_each_minimum() {
    let help = stdout(&xtask(&["help", "fig3"]));
    assert!(help.contains("integer 1 to"), "{help}");
    assert!(help.contains("integer 100 to"), "{help}");
    let help = stdout(&xtask(&["help", "table1"]));
    assert!(help.contains("0.05 to 100"), "{help}");
    assert!(help.contains("integer 2 to"), "{help}");
}

#[test]
fn a_title_names_the_values_that_ran() {
    let scratch = Scratch::new("meaningful-title");
    let out = scratch.path("out");
    let o = xtask(&[
        "run",
        "fig5",
        "-q",
        "--set",
        "hypothesis_params=random=0.04",
        "--out",
        &out,
    ]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(text.contains("random 0.04 of the pitch"), "{text}");
    assert!(!text.contains("random 0.05"), "{text}");
    // A hypothesis that takes no random error is not said to run with one.
    let o = xtask(&["run", "fig5", "-q", "--hypothesis", "ideal", "--out", &out]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!text.contains("random 0.05"), "{text}");
    assert!(text.contains("r = 180, hypothesis ideal"), "{text}");
}

#[test]
fn a_comparison_that_cannot_hold_is_refused_or_not_made() {
    for h in [
        "asymmetric-teeth",
        "curved-flanks",
        "non-circular",
        "edmunds-split+curved-flanks",
    ] {
        refused(
            &format!("run fig5 --hypothesis {h} --out {{out}}"),
            &[
                &format!("--hypothesis: {h}: makes gears with"),
                "Edmunds' radial-line model cannot take",
            ],
        );
    }
    // Ideal gears keep Edmunds' pointer exact: no ratio of a sigma to 0.
    let scratch = Scratch::new("meaningful-ideal");
    let out = scratch.path("out");
    let o = xtask(&["run", "fig5", "-q", "--hypothesis", "ideal", "--out", &out]);
    let text = stdout(&o);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(text.contains("n/a"), "{text}");
    assert!(
        !text.contains("e1") && !text.contains("inf") && !text.contains("NaN"),
        "{text}"
    );
}

#[test]
fn a_key_given_twice_or_an_empty_entry_is_refused() {
    for (args, words) in [
        (
            "run fig5 --set hypothesis_params=random=0.03,random=0.04 --out {out}",
            &["--set: hypothesis_params: `random` is given twice"][..],
        ),
        (
            "run fig5 --set hypothesis_params=,,, --out {out}",
            &["--set: hypothesis_params: entry 1 is empty"],
        ),
        (
            "run fig5 --set hypothesis_params=random=0.04, --out {out}",
            &["--set: hypothesis_params: entry 2 is empty"],
        ),
        (
            "run fig5 --set events=friction:mu=0.2,mu=0.3 --out {out}",
            &["--set: events: event rule friction: parameter `mu`: is given twice"],
        ),
        (
            "run fig5 --set events=friction:mu=0.2,,mu=0.3 --out {out}",
            &["--set: events: event rule friction: entry 2 after `:` is empty"],
        ),
        // A value the table sets for each of its rows cannot be replaced for all of them: the
        // rows would name values that did not run.
        (
            "run table4 --set hypothesis_params=random=0.03 --out {out}",
            &["--set: hypothesis_params: `random` is set by the experiment itself"],
        ),
        (
            "run fig5 --set hypothesis_params=split=0.3 --out {out}",
            &["--set: hypothesis_params: `split` is set by the experiment itself"],
        ),
    ] {
        refused(args, words);
    }
}

#[test]
fn a_refusal_names_the_key_typed_and_prints_numbers_short() {
    for (args, words) in [
        (
            "run fig2 --set tip_radius=-200 --out {out}",
            &["--set: tip_radius: must be greater than 0"][..],
        ),
        (
            "run fig2 --set centre_distance=1e300 --out {out}",
            &["--set: centre_distance: must be greater than 0 and at most 1000000"],
        ),
        (
            "run fig5 --set root_radius=1e300 --out {out}",
            &["--set: root_radius:"],
        ),
        (
            "run figIV --set to=-5 --out {out}",
            &["--set: to: must be between 0 and 100"],
        ),
        (
            "run figIV --set to=5 --out {out}",
            &["--set: to: must be at least from = 10 (got 5)"],
        ),
        (
            "run figIV --set from=95 --out {out}",
            &["--set: from: must be at most to = 90 (got 95)"],
        ),
        (
            "run fig5 --set random=-0.05 --out {out}",
            &["--set: random: must be between 0 and 0.1"],
        ),
        (
            "run fig5 --set systematic=1e300 --out {out}",
            &["--set: systematic: must be between 0 and 45"],
        ),
    ] {
        let line = refused(args, words);
        assert!(line.len() < 300, "{args}: {line}");
    }
}

#[test]
fn replay_refuses_the_cells_run_refuses_naming_the_part_typed() {
    for (args, words) in [
        (
            "replay tableI B/1e300/m3-e3 --out {out}",
            &[
                "replay: cell `B/1e300/m3-e3` of tableI: G `1e300`: must be above 0 and at most 200 % of h",
            ][..],
        ),
        (
            "replay tableI B/0/m3-e3 --out {out}",
            &["replay: cell `B/0/m3-e3` of tableI: G `0`: must be above 0"],
        ),
        (
            "replay tableI B/0/m3-e3 3 --out {out}",
            &["replay: cell `B/0/m3-e3` of tableI: G `0`: must be above 0"],
        ),
        (
            "replay table4 0.5/m3-e3 --out {out}",
            &["replay: cell `0.5/m3-e3` of table4: random error `0.5`: must be between 0 and 0.1"],
        ),
        // A hypothesis that takes no random error does not make the value one run refuses.
        (
            "replay table4 0.5/m3-e3 --set hypothesis=ideal --out {out}",
            &["replay: cell `0.5/m3-e3` of table4: random error `0.5`: must be between 0 and 0.1"],
        ),
        (
            "replay table5 0.05/1e300/e4-f1 0 --out {out}",
            &[
                "replay: cell `0.05/1e300/e4-f1` of table5: systematic error `1e300`: ",
                "= 5e299°",
            ],
        ),
    ] {
        let line = refused(args, words);
        assert!(!line.contains("--hypothesis"), "{args}: {line}");
        assert!(line.len() < 300, "{args}: {line}");
    }
    // `run` refuses the same values with the same rules.
    refused(
        "run tableI --set clearances=0 --out {out}",
        &["--set: clearances: each must be above 0 and at most 200 % of h"],
    );
    refused(
        "run table4 --set random_to=0.5 --out {out}",
        &["--set: random_to: must be between 0 and 0.1"],
    );
}

#[test]
fn a_refusal_names_the_parameter_set_not_an_internal_field() {
    for (args, words, never) in [
        (
            "run fig5 --set clearance=1e-300 --out {out}",
            &["--set: clearance: 1e-300 % of h"][..],
            "centre_distance",
        ),
        (
            "run clearance --set tooth_height=1e-300 --out {out}",
            &["--set: tooth_height: must be between 0.01 and 10000"],
            "root_radius",
        ),
        (
            "run fig5 --hypothesis curved-flanks --set hypothesis_params=sagitta=5 --out {out}",
            &["curved-flanks: parameter `sagitta`: the sagitta s = 5 mm"],
            "flank_sagitta",
        ),
        (
            "run table3 --hypothesis non-circular --set hypothesis_params=radial_error=3 --out {out}",
            &["non-circular: parameter `radial_error`: too large for teeth 1.100 mm high"],
            "radii[",
        ),
        (
            "run table4 --set random_from=0.07 --out {out}",
            &["--set: random_from: must be at most random_to = 0.065 (got 0.07)"],
            "--set: random_to",
        ),
        (
            "run table4 --set random_step=1e-300 --out {out}",
            &[
                "--set: random_step: gives more than 1000 grid values",
                "by random_step = 1e-300",
            ],
            "000000000",
        ),
        (
            "run tolerance --set search_lo=0.09 --out {out}",
            &["--set: search_lo: must be less than search_hi = 0.08 (got 0.09)"],
            "search_hi:",
        ),
        (
            "run fig5 --set hypothesis_params=systematic=1e300 --out {out}",
            &[
                "--set: hypothesis_params: edmunds-split: systematic: its eccentric share",
                "must be less than 90°",
            ],
            "000000000",
        ),
    ] {
        let line = refused(args, words);
        assert!(!line.contains(never), "{args}: {line}");
        assert!(line.len() < 300, "{args}: {line}");
    }
}

#[test]
fn a_gearing_file_refuses_sizes_beyond_ten_metres_naming_the_field() {
    let gearing = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../crates/train/data/freeth2006.ron"),
    )
    .unwrap();
    for (from, to, words) in [
        (
            "pin_radius: 9.6",
            "pin_radius: 1e300",
            "pin_and_slot.pin_radius: must be above 0 and at most 10000 mm",
        ),
        (
            "axis_offset: 1.1",
            "axis_offset: 2e4",
            "pin_and_slot.axis_offset: must be above 0 and at most 10000 mm",
        ),
    ] {
        assert!(gearing.contains(from), "{from}");
        let (code, err, wrote) = support::run_with_file(
            "meaningful-gearing-size",
            "gearing.ron",
            &gearing.replacen(from, to, 1),
            &["run", "failure", "--gearing", "{file}", "--out", "{out}"],
        );
        assert_eq!(code, Some(2), "{to}: {err}");
        assert_eq!(err.lines().count(), 1, "{to}: {err}");
        assert!(err.contains(words), "{to}: {err}");
        assert!(err.len() < 300 && !wrote, "{to}: {err}");
    }
}

/// Every RON input a user gives: how it is run, a valid file, and what it is called in
/// messages.
const RON_LOADERS: [(&str, &str, &str); 4] = [
    (
        "run pair -q --config {file} --out {out}",
        "(driver: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), clearance_percent: Some(40.0))",
        "a pair file",
    ),
    (
        // The gearing is read, then h checked against it: a refusal that shows it was read.
        "run failure -q --gearing {file} --set tooth_height=100 --out {out}",
        "",
        "a gearing file",
    ),
    (
        // A table without gear b2 is read, then refused for it: the same message with and
        // without a byte-order mark shows the mark was read past.
        "run table2 -q --errors {file} --out {out}",
        r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5)])"#,
        "a measured-error table",
    ),
    (
        // `--hypothesis measured:FILE` reads the table through the hypotheses' own loader
        // (`--set measured=FILE` of failure and fig6 reads it with the same parser, after
        // minutes of work).
        "run table3 -q --hypothesis measured:{file} --out {out}",
        r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5)])"#,
        "a measured-error table",
    ),
];

/// Our type names a parser could leak into a message.
const TYPE_NAMES: [&str; 16] = [
    "Raw",
    "struct `",
    "PairFile",
    "GearSpec",
    "StartSpec",
    "Frame",
    "Sense",
    "Arbor`",
    "GearData",
    "MeshData",
    "Pointer`",
    "PinAndSlot",
    "RawEntry",
    "RawTable",
    "RawGearing",
    "serde_stacker",
];

#[test]
fn ron_inputs_that_are_not_ron_are_named_in_the_users_words() {
    let freeth = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../crates/train/data/freeth2006.ron"),
    )
    .unwrap();
    let deep_lists = "[".repeat(10_000);
    let deep_groups = format!("(driver: {}", "(".repeat(10_000));
    let deep_fields = format!("(gears: {}", "[".repeat(10_000));
    let deep_options = format!("(driver: {}", "Some(".repeat(10_000));
    for (args, valid, what) in RON_LOADERS {
        let valid = if valid.is_empty() {
            freeth.as_str()
        } else {
            valid
        };
        let argv: Vec<&str> = args.split(' ').collect();
        let run = |text: &str| support::run_with_file("meaningful-ron", "my.ron", text, &argv);
        // A UTF-8 byte-order mark is read past: the same outcome as without it.
        // Each run has its own scratch dir: compare what follows the file's name.
        let after_name = |e: &str| e.rsplit("my.ron").next().unwrap_or("").to_owned();
        let (code, err, _) = run(valid);
        let (bom_code, bom_err, _) = run(&format!("\u{feff}{valid}"));
        assert_eq!(
            (bom_code, after_name(&bom_err)),
            (code, after_name(&err)),
            "{args}: BOM: {bom_err}"
        );
        for (name, text, words) in [
            ("empty", "", "the file is empty"),
            ("blank", " \n\n ", "the file is empty"),
            (
                "CSV",
                "gear,random,systematic\nb1,0.05,0.5\n",
                "this looks like CSV",
            ),
            (
                "JSON",
                r#"{"driver": {"teeth": 20}, "gears": []}"#,
                "this looks like JSON",
            ),
            ("JSON list", r#"[{"gear": "b1"}]"#, "this looks like JSON"),
            ("deep lists", deep_lists.as_str(), ""),
            ("deep groups", deep_groups.as_str(), ""),
            ("deep fields", deep_fields.as_str(), ""),
            ("deep options", deep_options.as_str(), ""),
        ] {
            let (code, err, wrote) = run(text);
            assert_eq!(code, Some(2), "{args}: {name}: {err}");
            assert_eq!(err.lines().count(), 1, "{args}: {name}: one line: {err}");
            assert!(err.contains("my.ron: line "), "{args}: {name}: {err}");
            assert!(!wrote, "{args}: {name}: nothing may be written");
            if !words.is_empty() {
                assert!(
                    err.contains(&format!("expected {what} in RON, `(")) && err.contains(words),
                    "{args}: {name}: {err}"
                );
            }
            for t in TYPE_NAMES {
                assert!(!err.contains(t), "{args}: {name}: `{t}` in: {err}");
            }
            assert!(err.len() < 400, "{args}: {name}: {err}");
        }
    }
}
