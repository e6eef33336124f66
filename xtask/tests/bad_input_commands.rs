//! Bad input across the runner's commands, tried on purpose: a pipe or a folder given as an input
//! file, empty gearings and blank names, a built-in gearing name that is also a file, names that
//! would break a line, a terminal or a CSV cell, and every input checked before any work. Each
//! is refused with exit status 2 and one line naming the file or flag and the rule, without a
//! panic and without writing anything. Malformed files of each format are in `bad_input.rs`.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

mod support;
use support::hostile::{assert_none, case, failures, freeth, gearing};
use support::stderr;

/// Runs `xtask args` in `dir` (a working folder of its own) and gives it `seconds` to end: an
/// input that waits for ever (a FIFO without a writer) is a failure, not a hung test.
fn within(seconds: u64, dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    use std::process::{Command, Stdio};
    let mut child = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_LOG")
        .env_remove("XTASK_PROGRESS")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed().as_secs() >= seconds {
            let _ = child.kill();
            let _ = child.wait();
            panic!("{args:?} still running after {seconds} s: it waits for ever");
        }
        std::thread::sleep(std::time::Duration::from_millis(50));
    }
    child.wait_with_output().unwrap()
}

/// Every input file is checked to be a regular file before it is opened: a named pipe with no
/// writer blocked `run pair --config F` (and `--gearing`, `--errors`) for ever in the open. Each
/// is refused at once, naming the flag and the file, and nothing is written.
#[test]
fn named_pipes_and_folders_given_as_input_files_are_refused_at_once() {
    let s = support::Scratch::new("fifo");
    let fifo = s.0.join("pipe.ron");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|st| st.success()) {
        eprintln!("skipped: no mkfifo");
        return;
    }
    std::fs::create_dir_all(s.0.join("folder.ron")).unwrap();
    let pipe = "must be a regular file, and this is a pipe (a named pipe or FIFO";
    for (args, words) in [
        (
            &["run", "pair", "--config", "pipe.ron"][..],
            &["--config: pipe.ron: ", pipe][..],
        ),
        (
            &["run", "table1", "--gearing", "pipe.ron"],
            &["--gearing: pipe.ron: read: ", pipe],
        ),
        (
            &["run", "table2", "--errors", "pipe.ron"],
            &["--errors: pipe.ron: ", pipe],
        ),
        (
            &["run", "failure", "--set", "measured=pipe.ron"],
            &["pipe.ron", pipe],
        ),
        (
            &["run", "table3", "--hypothesis", "measured:pipe.ron"],
            &["pipe.ron", pipe],
        ),
        (
            &["run", "fig6", "--set", "measured=pipe.ron"],
            &["pipe.ron", pipe],
        ),
        (
            &["merge", "pipe.ron"],
            &["pipe.ron", "must be a regular file"],
        ),
        (
            &["run", "pair", "--config", "folder.ron"],
            &[
                "--config: folder.ron: ",
                "must be a regular file, and this is a directory",
            ],
        ),
        (
            &["run", "table1", "--gearing", "folder.ron"],
            &["--gearing: folder.ron: read: ", "is a directory"],
        ),
    ] {
        let mut all = args.to_vec();
        all.extend(["--out", "out"]);
        let o = within(20, &s.0, &all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{all:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{all:?}: no {w:?} in {err}");
        }
        assert!(!s.0.join("out").exists(), "{all:?} wrote results");
    }
}

/// A gearing with no meshes ran table3 and figIV to exit 0 with empty tables, and a gear named
/// `""` made messages like "gear : teeth must be at least 3". Every experiment that reads a
/// gearing refuses them, naming the file and the rule, before anything runs.
#[test]
fn empty_gearings_and_blank_names_are_refused_by_every_experiment() {
    let ids = support::succeeded(&["list"]);
    let empty = Some((
        "gearing.ron",
        b"(gears: [], arbors: [], meshes: [], pointers: [])".to_vec(),
    ));
    let gears_only = Some((
        "gearing.ron",
        br#"(gears: [(name: "a", teeth: 20, measured_radius: Some(10.0), source: "")], arbors: [(name: "x", gears: ["a"])], meshes: [], pointers: [])"#.to_vec(),
    ));
    let mut cases = Vec::new();
    for id in ids.lines() {
        let args = format!("run {id} --gearing {{file}} --out {{out}}");
        let help = support::succeeded(&["help", id]);
        if !help.contains("--gearing FILE sets") {
            continue;
        }
        cases.push(case(
            &format!("{id}: no gears, no meshes"),
            empty.clone(),
            &args,
            &["{file}: meshes: must list at least one mesh"],
        ));
        cases.push(case(
            &format!("{id}: gears but no meshes"),
            gears_only.clone(),
            &args,
            &["{file}: meshes: must list at least one mesh", "has 1 gears"],
        ));
    }
    assert!(
        cases.len() >= 20,
        "{} experiments read a gearing",
        cases.len() / 2
    );
    let run = "run table3 --gearing {file} --out {out}";
    for (what, from, to, words) in [
        (
            "a gear named \"\"",
            "name: \"b1\",",
            "name: \"\",",
            "gears[0]: name must not be empty",
        ),
        (
            "a gear named \" \"",
            "name: \"b1\",",
            "name: \"  \",",
            "gears[0]: name must not be empty",
        ),
        (
            "an arbor named \"\"",
            "name: \"b\",",
            "name: \"\",",
            "arbors[0]: name must not be empty",
        ),
        (
            "a mesh labelled \"\"",
            "label: \"b2-c1\",",
            "label: \"\",",
            "label must not be empty",
        ),
    ] {
        cases.push(case(what, gearing(from, to), run, &["{file}: ", words]));
    }
    cases.push(case(
        "a measured row for gear \"\"",
        Some((
            "errors.ron",
            br#"(gears: [(gear: "", random: 0.05, systematic: 0.5)])"#.to_vec(),
        )),
        "run table2 --errors {file} --out {out}",
        &["{file}: gears[0]: gear must name a gear"],
    ));
    assert_none(failures("empty-gearing", cases));
}

/// `--gearing freeth2021` with a file `./freeth2021` in the folder used the embedded gearing and
/// ignored the file without a word: a name that is both is refused, saying how to ask for each.
#[test]
fn a_builtin_gearing_name_that_is_also_a_file_is_refused() {
    let s = support::Scratch::new("builtin-and-file");
    std::fs::write(s.0.join("freeth2021"), freeth()).unwrap();
    std::fs::write(s.0.join("freeth2006"), freeth()).unwrap();
    for args in [
        &["run", "figIV", "--gearing", "freeth2021"][..],
        &["run", "table3", "--set", "gearing=freeth2006"],
        &["run", "all", "--gearing", "freeth2021"],
    ] {
        let mut all = args.to_vec();
        all.extend(["--out", "out"]);
        let o = within(60, &s.0, &all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{all:?}: {err}");
        assert!(
            err.contains("is both an embedded gearing and a file in this folder")
                && err.contains("write ./freeth20"),
            "{all:?}: {err}"
        );
        let flag = if args.contains(&"--gearing") {
            "--gearing: "
        } else {
            "--set: gearing: "
        };
        assert!(err.starts_with(flag), "{all:?}: {err}");
        assert!(!s.0.join("out").exists(), "{all:?} wrote results");
    }
    // Written as a path it is the file, read as such (here a file that is no gearing).
    std::fs::write(s.0.join("freeth2021"), "not a gearing").unwrap();
    let o = within(
        60,
        &s.0,
        &["run", "figIV", "--gearing", "./freeth2021", "--out", "out"],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with("--gearing: ./freeth2021: line 1"), "{err}");
}

/// A mesh label `b2-c1\nX`, a gear name holding a NUL byte or an escape sequence
/// (`b2\u{1b}[31mRED`) was written raw to the terminal, `table.md` and the CSV files; a label
/// `m3/e3` or `40/m3` ran, but its cells could not be replayed. Names with a control character,
/// and mesh labels with a `/`, are refused when the gearing is read, naming the item. New
/// instances: an arbor name with a tab, a pointer name with an escape.
#[test]
fn names_that_would_break_a_line_a_terminal_or_a_cell_are_refused() {
    let run = "run table3 --trials 2 --gearing {file} --out {out}";
    let control = "must not contain a control character";
    let cases = vec![
        case(
            "a line break in a mesh label",
            gearing("(label: \"b2-c1\"", "(label: \"b2-c1\\nX\""),
            run,
            &["{file}: meshes[", control],
        ),
        case(
            "a NUL in a gear name",
            gearing("(name: \"b2\"", "(name: \"b2\\u{0}\""),
            run,
            &["{file}: gears[", control],
        ),
        case(
            "an escape in a gear name",
            gearing("(name: \"b2\"", "(name: \"b2\\u{1b}[31mRED\""),
            run,
            &["{file}: gears[", control, "\\u{1b}[31mRED"],
        ),
        case(
            "a slash in a mesh label",
            gearing("(label: \"m3-e3\"", "(label: \"m3/e3\""),
            run,
            &[
                "label `m3/e3` must not contain `/`",
                "could not be replayed",
            ],
        ),
        case(
            "a clearance-like slash in a mesh label",
            gearing("(label: \"m3-e3\"", "(label: \"40/m3\""),
            run,
            &["label `40/m3` must not contain `/`"],
        ),
        case(
            "a tab in an arbor name",
            gearing("(name: \"b\"", "(name: \"b\\t\""),
            run,
            &["{file}: arbors[", control],
        ),
        case(
            "an escape in a pointer name",
            gearing("(name: \"Lunar\"", "(name: \"Lunar\\u{1b}]0;x\\u{7}\""),
            run,
            &["{file}: pointers[", control],
        ),
    ];
    let bad = failures("names", cases);
    for b in &bad {
        assert!(!b.contains('\u{1b}'), "raw escape on stderr: {b:?}");
    }
    assert_none(bad);
}

/// The fields of a CSV file as a CSV reader reads them, row by row.
fn csv_rows(path: &std::path::Path) -> Vec<Vec<String>> {
    let text = std::fs::read_to_string(path).unwrap();
    let mut rows = Vec::new();
    let (mut row, mut field, mut quoted, mut chars) =
        (Vec::new(), String::new(), false, text.chars().peekable());
    while let Some(c) = chars.next() {
        match (c, quoted) {
            ('"', true) if chars.peek() == Some(&'"') => {
                chars.next();
                field.push('"');
            }
            ('"', _) => quoted = !quoted,
            (',', false) => row.push(std::mem::take(&mut field)),
            ('\n', false) => {
                row.push(std::mem::take(&mut field));
                rows.push(std::mem::take(&mut row));
            }
            (c, _) => field.push(c),
        }
    }
    rows
}

/// A mesh label `b2,c1`: `table3-data.csv` had 17 fields under its 16-column header, and
/// `table4-data.csv` 7 bad rows. Every data file is written by one CSV writer: each row has its
/// header's fields and the label reads back whole. New instance: `failure-runs.csv`, whose
/// `mesh` column names where a run jammed; and a path with an escape sequence, shown escaped on
/// the terminal.
#[test]
fn every_data_file_quotes_its_fields() {
    let s = support::Scratch::new("csv-quoting");
    let g = s.0.join("gearing.ron");
    let text = freeth()
        .replace("\"b2-c1\"", "\"b2,c1\"")
        .replace("\"d2-e2\"", "\"d2,e2\"");
    std::fs::write(&g, text).unwrap();
    let out = s.0.join("out");
    let (g, o_) = (g.to_str().unwrap(), out.to_str().unwrap());
    for (run, file, label) in [
        (
            &["table3", "--trials", "2"][..],
            "table3/table3-data.csv",
            "b2,c1",
        ),
        (
            &["table4", "--trials", "2"],
            "table4/table4-data.csv",
            "b2,c1",
        ),
        (
            &[
                "failure",
                "--set",
                "cases=D",
                "--trials",
                "2",
                "--set",
                "days=2000",
            ],
            "failure/failure-runs.csv",
            "d2,e2",
        ),
    ] {
        let o = support::run_args(run, &["-q", "--gearing", g, "--out", o_]);
        assert!(o.status.success(), "{run:?}: {}", stderr(&o));
        let rows = csv_rows(&out.join(file));
        let width = rows[0].len();
        for (i, r) in rows.iter().enumerate() {
            assert_eq!(
                r.len(),
                width,
                "{file}: row {i} has {} fields: {r:?}",
                r.len()
            );
        }
        assert!(
            rows.iter().any(|r| r.iter().any(|f| f == label)),
            "{file}: no field {label:?}"
        );
    }
    // A path holding an escape sequence: shown escaped on stderr.
    let o = support::xtask(&[
        "run",
        "table1",
        "--gearing",
        "no\u{1b}[31mRED.ron",
        "--out",
        o_,
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        !err.contains('\u{1b}') && err.contains("no\\u{1b}[31mRED.ron"),
        "{err:?}"
    );
}

/// `run failure --errors m.ron` with a table lacking b2 was refused only after Cases A-D were
/// computed (8 s at 300 trials), naming `--set measured:` though `--errors` was typed; `run
/// tableI --set clearances=10,10,10` gave three identical rows and counted 15 cells three
/// times; `report` over a results folder it could not read said "not run" and exited 0;
/// `TMPDIR=/nonexistent fuzz` skipped its file check and found nothing. Each is refused before
/// any work, naming what was typed. New instances: the same table through `--hypothesis
/// measured:FILE`, a Case named twice, a tolerance named twice (also under `run all`, where
/// the experiments before jam-readings would otherwise have run), a results folder whose
/// `tables.json` is a link that leads nowhere.
#[test]
fn every_input_is_checked_before_any_work() {
    let s = support::Scratch::new("before-work");
    let example = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../crates/hypotheses/data/measured-example.ron"
    ))
    .unwrap();
    let lacking: String = example
        .lines()
        .filter(|l| !l.contains("\"b2\""))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(s.0.join("m.ron"), lacking).unwrap();
    let m = s.path("m.ron");
    let out = s.path("out");
    for (args, words) in [
        (
            vec!["run", "failure", "--errors", &m, "--trials", "300"],
            &["--errors: ", "gear b2: missing from the table"][..],
        ),
        (
            vec!["run", "table3", "--hypothesis", &format!("measured:{m}")],
            &["--hypothesis: ", "gear b2: missing from the table"],
        ),
        (
            vec!["run", "tableI", "--set", "clearances=10,10,10"],
            &["--set: clearances: names the clearance 10 twice"],
        ),
        (
            vec!["run", "failure", "--set", "cases=A,a"],
            &["--set: cases: names the case `a` twice"],
        ),
        (
            vec!["run", "jam-readings", "--set", "tolerances=0.001,0.0010"],
            &["--set: tolerances: names the tolerance 0.0010 twice"],
        ),
        // Every experiment's settings are checked before the first computes: `all` stops on
        // jam-readings' check without running the experiments before it.
        (
            vec!["run", "all", "--set", "tolerances=0.001,0.0010"],
            &[
                "--set: tolerances: names the tolerance 0.0010 twice",
                "for experiment jam-readings",
            ],
        ),
    ] {
        let mut all = args.clone();
        all.extend(["--out", &out]);
        let start = std::time::Instant::now();
        let o = support::xtask(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{all:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{all:?}: missing {w:?}: {err}");
        }
        assert!(
            start.elapsed().as_secs() < 5,
            "{all:?}: refused after {:?}",
            start.elapsed()
        );
        assert!(!s.0.join("out").exists(), "{all:?} wrote results");
    }
    // Results the report cannot read: refused naming them, no page.
    let results = s.0.join("results");
    let o = support::xtask(&["run", "fig3", "-q", "--out", results.to_str().unwrap()]);
    assert!(o.status.success(), "{}", stderr(&o));
    let unreadable: Vec<(std::path::PathBuf, Box<dyn Fn()>)> = vec![
        (results.join("fig2"), {
            let p = results.join("fig2");
            Box::new(move || std::os::unix::fs::symlink("fig2", &p).unwrap())
        }),
        (results.join("fig4"), {
            let p = results.join("fig4");
            Box::new(move || std::os::unix::fs::symlink("/nonexistent/fig4", &p).unwrap())
        }),
        (results.join("fig5/tables.json"), {
            let p = results.join("fig5");
            Box::new(move || {
                std::fs::create_dir_all(&p).unwrap();
                std::os::unix::fs::symlink("gone.json", p.join("tables.json")).unwrap();
            })
        }),
        // The claims ledger the page opens on: a results.json that leads nowhere is not "not
        // judged".
        (results.join("claims/results.json"), {
            let p = results.join("claims");
            Box::new(move || {
                std::fs::create_dir_all(&p).unwrap();
                std::os::unix::fs::symlink("gone.json", p.join("results.json")).unwrap();
            })
        }),
    ];
    for (path, make) in unreadable {
        make();
        let o = support::xtask(&["report", "--out", results.to_str().unwrap()]);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{}: {err}", path.display());
        assert!(
            err.contains(path.to_str().unwrap()) && err.contains("cannot be read"),
            "{err}"
        );
        assert!(!results.join("index.html").exists());
        let _ = std::fs::remove_file(&path);
        let _ = std::fs::remove_dir_all(results.join("fig5"));
    }
    // A folder that cannot be read, where this process is not root (root reads everything).
    let root = std::process::Command::new("id")
        .arg("-u")
        .output()
        .is_ok_and(|o| String::from_utf8_lossy(&o.stdout).trim() == "0");
    if !root {
        use std::os::unix::fs::PermissionsExt;
        let locked = results.join("fig2");
        std::fs::create_dir_all(&locked).unwrap();
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o000)).unwrap();
        let o = support::xtask(&["report", "--out", results.to_str().unwrap()]);
        std::fs::set_permissions(&locked, std::fs::Permissions::from_mode(0o755)).unwrap();
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    }
    // The fuzzer's scratch folder.
    let o = support::xtask_env(&["fuzz", "--execs", "300"], &[("TMPDIR", "/nonexistent")]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with("TMPDIR: /nonexistent: "), "{err}");
}

/// `--gearing <(...)`: the message lacked the `--gearing:` prefix the other file flags have, and
/// called a live pipe one "which waits for a writer that may never come". Every file flag names
/// itself, and a pipe is said to be read only once. New instances: `--errors <(...)` and
/// `--config <(...)`.
#[test]
fn a_pipe_given_as_an_input_file_is_named_by_its_flag() {
    if std::process::Command::new("bash")
        .arg("-c")
        .arg("true")
        .status()
        .is_err()
    {
        eprintln!("skipped: no bash");
        return;
    }
    let s = support::Scratch::new("process-substitution");
    let gearing = s.0.join("g.ron");
    std::fs::write(&gearing, freeth()).unwrap();
    let xtask = env!("CARGO_BIN_EXE_xtask");
    for (flag, run) in [
        ("--gearing", "run table1"),
        ("--errors", "run table2"),
        ("--config", "run pair"),
    ] {
        let line = format!(
            "{xtask} {run} {flag} <(cat {}) --out {}",
            gearing.display(),
            s.0.join("out").display()
        );
        let o = std::process::Command::new("bash")
            .args(["-c", &line])
            .env_remove("RUST_LOG")
            .output()
            .unwrap();
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{line}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{line}: {err}");
        assert!(
            err.starts_with(&format!("{flag}: /dev/fd/")),
            "{line}: {err}"
        );
        assert!(
            err.contains("can be read only once") && !err.contains("waits for a writer"),
            "{line}: {err}"
        );
        assert!(!s.0.join("out").exists());
    }
}
