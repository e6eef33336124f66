//! `--set gearing=FILE` with a broken gearing: one line naming the file and the line or item,
//! exit status 2, nothing written.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;
use support::{Scratch, run_with_file, succeeded_output, xtask};

/// Runs `table1` with the gearing `text`; returns (exit code, stderr, whether the results dir
/// exists).
fn run_table1(tag: &str, text: &str) -> (Option<i32>, String, bool) {
    run_with_file(
        &format!("gearing-{tag}"),
        "gearing.ron",
        text,
        &["run", "table1", "--set", "gearing={file}", "--out", "{out}"],
    )
}

#[test]
fn malformed_gearing_names_the_line() {
    let (code, err, written) = run_table1("syntax", "(gears: [\n (name: \"b1\", teeth: 223,\n");
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("gearing.ron") && err.contains("line"), "{err}");
    assert!(!written);
}

#[test]
fn gearing_with_an_unknown_gear_names_the_mesh() {
    let text = train::FREETH2006_RON.replace(
        "(label: \"b2-c1\", driver: \"b2\", driven: \"c1\")",
        "(label: \"b2-c1\", driver: \"b2\", driven: \"zz\")",
    );
    assert_ne!(text, train::FREETH2006_RON, "the test must change the file");
    let (code, err, written) = run_table1("unknown", &text);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("b2-c1") && err.contains("zz"), "{err}");
    assert!(!written);
}

#[test]
fn one_wrong_tooth_count_changes_the_ratio_checks() {
    let s = Scratch::new("gearing-ratio");
    let file = s.path("wrong.ron");
    let original = "(name: \"b2\", teeth: 64,";
    assert!(train::FREETH2006_RON.contains(original));
    std::fs::write(
        &file,
        train::FREETH2006_RON.replace(original, "(name: \"b2\", teeth: 63,"),
    )
    .unwrap();
    let short = support::TABLE1_TINY;

    let out = s.path("out");
    let run = |gearing: Option<&str>| {
        let mut args = vec!["run", "table1", "--out", &out];
        args.extend(short);
        if let Some(g) = gearing {
            args.extend(["--gearing", g]);
        }
        succeeded_output(&xtask(&args)).0
    };
    let default = run(None);
    let wrong = run(Some(&file));
    assert!(
        default.contains("| Lunar     |      6 | 254/19"),
        "{default}"
    );
    let lunar_row = |t: &str| {
        t.lines()
            .find(|l| l.starts_with("| Lunar ") && l.contains('/'))
            .map(str::to_owned)
    };
    assert_ne!(lunar_row(&default), lunar_row(&wrong), "{wrong}");
    assert!(
        lunar_row(&wrong).is_some_and(|r| r.contains("8001/608")),
        "{wrong}"
    );
}
