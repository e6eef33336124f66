//! `--set gearing=FILE` with a broken gearing: one line naming the file and the line or item,
//! exit status 2, nothing written.
#![allow(clippy::unwrap_used, reason = "tests")]

use std::process::Command;

fn run_table1(tag: &str, text: &str) -> (Option<i32>, String, bool) {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    let dir = std::env::temp_dir().join(format!(
        "xtask-gearing-{tag}-{}-{nanos}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("gearing.ron");
    std::fs::write(&file, text).unwrap();
    let out = dir.join("results");
    let o = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args([
            "run",
            "table1",
            "--set",
            &format!("gearing={}", file.display()),
            "--out",
            out.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    let written = out.exists();
    let _ = std::fs::remove_dir_all(&dir);
    (
        o.status.code(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
        written,
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
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .unwrap()
        .as_nanos();
    let dir = std::env::temp_dir().join(format!(
        "xtask-gearing-ratio-{}-{nanos}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("wrong.ron");
    let original = "(name: \"b2\", teeth: 64,";
    assert!(train::FREETH2006_RON.contains(original));
    std::fs::write(
        &file,
        train::FREETH2006_RON.replace(original, "(name: \"b2\", teeth: 63,"),
    )
    .unwrap();
    let short = [
        "--set",
        "trials=2",
        "--set",
        "lunar_turns=0.05",
        "--set",
        "metonic_turns=0.05",
        "--set",
        "saros_turns=0.05",
        "--set",
        "games_turns=0.05",
        "--set",
        "exeligmos_turns=0.05",
        "--set",
        "samples_per_engagement=2",
    ];
    let run = |gearing: Option<&std::path::Path>| {
        let mut args = vec![
            "run".to_string(),
            "table1".into(),
            "--out".into(),
            dir.join("out").display().to_string(),
        ];
        args.extend(short.iter().map(|s| s.to_string()));
        if let Some(g) = gearing {
            args.extend(["--gearing".to_string(), g.display().to_string()]);
        }
        let o = Command::new(env!("CARGO_BIN_EXE_xtask"))
            .args(&args)
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8_lossy(&o.stdout).into_owned()
    };
    let default = run(None);
    let wrong = run(Some(&file));
    let _ = std::fs::remove_dir_all(&dir);
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
