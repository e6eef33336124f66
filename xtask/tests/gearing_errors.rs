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
