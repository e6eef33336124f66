//! Bad input, tried on purpose: malformed and hostile values for every file format the runner
//! reads (gearing files, measured-error tables, pair configs, shard partial files, files that
//! never end). Each must be refused with exit status 2 and ONE line on stderr naming the file
//! (and the line or field where there is one) and the rule, without a panic, and without
//! writing anything: the `--out` directory stays absent. The flags' own are in `bad_flags.rs`.
//!
//! Each test collects every case that misbehaves and fails once, listing them all.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

mod support;
use support::hostile::{Row, assert_none, case, failures, freeth, gearing};
use support::{sealed, stderr};

#[test]
fn gearing_files() {
    let text = freeth();
    let run = "run table1 --gearing {file} --out {out}";
    let mut cases = vec![
        case(
            "truncated",
            Some(("gearing.ron", text.as_bytes()[..700].to_vec())),
            run,
            &["{file}: line "],
        ),
        case(
            "empty",
            Some(("gearing.ron", Vec::new())),
            run,
            &["{file}: line 1"],
        ),
        case(
            "not UTF-8",
            Some(("gearing.ron", b"(gears: [\xff\xfe\xfd".to_vec())),
            run,
            &["{file}: read: ", "UTF-8"],
        ),
        case(
            "unknown field",
            gearing("teeth: 223,", "teeth: 223, colour: 3,"),
            run,
            &["{file}: line 12", "colour"],
        ),
        case(
            "unknown field, named without a Rust type (was `colour`in `GearData`)",
            gearing("teeth: 223,", "teeth: 223, colour: 3,"),
            run,
            &["Unexpected field named `colour`, expected one of `name`, `teeth`"],
        ),
        case(
            "wrong type",
            gearing("teeth: 223,", "teeth: \"many\","),
            run,
            &["{file}: line 12"],
        ),
        case(
            "NaN radius",
            gearing("Some(64.4)", "Some(NaN)"),
            run,
            &["{file}: gear b1: measured_radius must be above 0 and at most 10000 mm"],
        ),
        case(
            "infinite radius",
            gearing("Some(64.4)", "Some(inf)"),
            run,
            &["{file}: gear b1: measured_radius must be above 0 and at most 10000 mm"],
        ),
        case(
            "negative radius",
            gearing("Some(64.4)", "Some(-64.4)"),
            run,
            &["{file}: gear b1: measured_radius must be above 0 and at most 10000 mm"],
        ),
        case(
            "zero radius",
            gearing("Some(64.4)", "Some(0.0)"),
            run,
            &["{file}: gear b1: measured_radius must be above 0 and at most 10000 mm"],
        ),
        case(
            "radius of a kilometre",
            gearing("Some(64.4)", "Some(1e6)"),
            run,
            &[
                "{file}: gear b1: measured_radius must be above 0 and at most 10000 mm",
                "got 1000000",
            ],
        ),
        case(
            "negative teeth",
            gearing("teeth: 64,", "teeth: -64,"),
            run,
            &["{file}: line 13"],
        ),
        case(
            "zero teeth",
            gearing("teeth: 64,", "teeth: 0,"),
            run,
            &["{file}: gear b2: teeth must be at least 3"],
        ),
        case(
            "a billion teeth",
            gearing("teeth: 223,", "teeth: 1000000000,"),
            run,
            &["{file}: gear b1: teeth must be at most 100000"],
        ),
        case(
            "teeth beyond u32",
            gearing("teeth: 223,", "teeth: 1000000000000,"),
            run,
            &["{file}: line 12"],
        ),
        case(
            "c1 with 100000 teeth (blamed tooth_height and gear b2)",
            gearing("teeth: 38,", "teeth: 100000,"),
            run,
            &["{file}: gear c1: 100000 teeth do not fit its measured radius 9.85 mm"],
        ),
        case(
            "unknown gear",
            gearing(
                r#"(label: "b2-c1", driver: "b2", driven: "c1")"#,
                r#"(label: "b2-c1", driver: "b2", driven: "zz")"#,
            ),
            run,
            &["{file}: mesh b2-c1: unknown gear zz"],
        ),
        case(
            "meshes in a loop",
            gearing(
                r#"(label: "h2-i1", driver: "h2", driven: "i1"),"#,
                r#"(label: "h2-i1", driver: "h2", driven: "i1"),
        (label: "i1-b1", driver: "i1", driven: "b1"),"#,
            ),
            run,
            &["{file}: mesh i1-b1: closes a loop of meshes"],
        ),
        case(
            "pointer chain breaks",
            gearing(
                r#"meshes: ["b2-c1", "c2-d1", "d2-e2""#,
                r#"meshes: ["b2-c1", "d2-e2", "c2-d1""#,
            ),
            run,
            &["{file}: pointer Lunar: chain does not connect at mesh d2-e2"],
        ),
        case(
            "missing file",
            None,
            "run table1 --gearing /no/such/gearing.ron --out {out}",
            &["/no/such/gearing.ron: read: "],
        ),
        case(
            "bad gearing under run all",
            gearing("teeth: 64,", "teeth: 0,"),
            "run all --gearing {file} --out {out}",
            &["{file}: gear b2: teeth must be at least 3"],
        ),
        case(
            "bad gearing given with --set",
            gearing("teeth: 64,", "teeth: 2,"),
            "run all --set gearing={file} --out {out}",
            &["{file}: gear b2: teeth must be at least 3"],
        ),
    ];
    for (value, words) in [
        ("150", "at most 100"),
        ("-10", "greater than 0"),
        ("0", "greater than 0"),
        ("NaN", "finite"),
        ("inf", "finite"),
    ] {
        cases.push(case(
            &format!("clearance {value}"),
            None,
            &format!("run table1 --set clearance={value} --out {{out}}"),
            &["--set: clearance: ", words],
        ));
        cases.push(case(
            &format!("clearance {value} of table3"),
            None,
            &format!("run table3 --set clearance={value} --out {{out}}"),
            &["--set: clearance: ", words],
        ));
    }
    for (value, words) in [
        ("0", "between 0.01 and 10000"),
        ("-1.1", "between 0.01 and 10000"),
        ("NaN", "finite"),
        ("100", "less than the smallest tip radius"),
    ] {
        cases.push(case(
            &format!("tooth height {value}"),
            None,
            &format!("run failure --set tooth_height={value} --out {{out}}"),
            &["--set: tooth_height: ", words],
        ));
    }
    assert_none(failures("gearing", cases));
}

#[test]
fn measured_error_tables() {
    let f = |text: &str| Some(("errors.ron", text.as_bytes().to_vec()));
    let good = r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5)])"#;
    let mut cases = Vec::new();
    for (run, flag) in [
        ("run table2 --errors {file} --out {out}", "--errors: "),
        ("run failure --errors {file} --out {out}", "--errors: "),
        ("run all --errors {file} --out {out}", "--errors: "),
        (
            "run table2 --hypothesis measured:{file} --out {out}",
            "--hypothesis: ",
        ),
        (
            "run failure --set measured={file} --out {out}",
            "--set measured: ",
        ),
    ] {
        let rows: [Row<'_>; 10] = [
            ("truncated", f(&good[..30]), &["{file}: line 1"]),
            (
                "not UTF-8",
                Some(("errors.ron", b"(gears: [\xff".to_vec())),
                &["{file}: cannot read: ", "UTF-8"],
            ),
            (
                "unknown field",
                f(r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5, colour: 1)])"#),
                &["{file}: line 1", "colour"],
            ),
            (
                "wrong type",
                f(r#"(gears: [(gear: "b1", random: "lots", systematic: 0.5)])"#),
                &["{file}: line 1"],
            ),
            (
                "NaN",
                f(r#"(gears: [(gear: "b1", random: NaN, systematic: 0.5)])"#),
                &["{file}: gear b1: random", "finite"],
            ),
            (
                "infinite",
                f(r#"(gears: [(gear: "b1", random: 0.05, systematic: inf)])"#),
                &["{file}: gear b1: systematic", "finite"],
            ),
            (
                "negative",
                f(r#"(gears: [(gear: "b1", random: -0.05, systematic: 0.5)])"#),
                &["{file}: gear b1: random"],
            ),
            (
                "split outside 0-1",
                f(r#"(split: 1.5, gears: [(gear: "b1", random: 0.05, systematic: 0.5)])"#),
                &["{file}: split: must be between 0 and 1"],
            ),
            (
                "gear twice",
                f(
                    r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5), (gear: "b1", random: 0.05, systematic: 0.5)])"#,
                ),
                &["{file}: gear b1: listed twice"],
            ),
            ("empty", f(""), &["{file}: line 1"]),
        ];
        for (what, file, words) in rows {
            let mut words = words.to_vec();
            words.push(flag);
            cases.push(case(&format!("{what} ({run})"), file, run, &words));
        }
    }
    cases.push(case(
        "a gear missing from --errors (blamed --hypothesis)",
        f(r#"(gears: [(gear: "driver", random: 0.05, systematic: 0.5)])"#),
        "run fig5 --errors {file} --out {out}",
        &["--errors: ", "{file}: gear driven: missing from the table"],
    ));
    cases.push(case(
        "missing table",
        None,
        "run table2 --errors /no/such/errors.ron --out {out}",
        &["--errors: /no/such/errors.ron: cannot read: "],
    ));
    // Silent wrong answers: a row for a gear the gearing does not have (was unused), and a
    // random error large enough that only some draws failed (passed with 2 trials, not 50).
    let stray = f(
        r#"(gears: [(gear: "b1", random: 0.05, systematic: 0.5), (gear: "zz9", random: 0.05, systematic: 0.5)])"#,
    );
    for (run, flag) in [
        (
            "run table3 --errors {file} --trials 2 --out {out}",
            "--errors: ",
        ),
        (
            "run failure --errors {file} --trials 2 --out {out}",
            "--errors: ",
        ),
        (
            "run failure --set measured={file} --trials 2 --out {out}",
            "--set measured: ",
        ),
        (
            "run table3 --hypothesis measured:{file} --trials 2 --out {out}",
            "--hypothesis: ",
        ),
    ] {
        cases.push(case(
            &format!("a gear not in the gearing ({run})"),
            stray.clone(),
            run,
            &[
                flag,
                "{file}: gear zz9: is not a gear of the gearing `freeth2006`",
            ],
        ));
    }
    for run in [
        "run table3 --errors {file} --trials 2 --out {out}",
        "run table2 --errors {file} --trials 2 --out {out}",
        "run failure --errors {file} --trials 2 --out {out}",
    ] {
        cases.push(case(
            &format!("random 0.2 of the pitch with 2 trials ({run})"),
            f(r#"(gears: [(gear: "b1", random: 0.2, systematic: 0.5)])"#),
            run,
            &[
                "--errors: ",
                "{file}: gear b1: random: must be at most 0.1 of the pitch",
            ],
        ));
    }
    assert_none(failures("errors", cases));
}

#[test]
fn pair_configs() {
    let f = |text: &str| Some(("mesh.ron", text.as_bytes().to_vec()));
    let mesh = |driver: &str, extra: &str| {
        f(&format!(
            "(driver: {driver}, driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), {extra})"
        ))
    };
    let good = "(teeth: 20, tip_radius: 10.0, root_radius: 9.0)";
    let g40 = "clearance_percent: Some(40.0)";
    let run = "run pair --config {file} --out {out}";
    let rows: Vec<Row<'_>> = vec![
        (
            "truncated",
            f("(driver: (teeth: 20, tip_radius: 1"),
            &["{file}: line 1, column"],
        ),
        ("empty", f(""), &["{file}: line 1"]),
        (
            "not UTF-8",
            Some(("mesh.ron", b"(driver: (teeth: \xff".to_vec())),
            &["--config: ", "{file}: cannot read: ", "UTF-8"],
        ),
        (
            "unknown field",
            mesh(good, "clearance_percent: Some(40.0), colour: 3"),
            &["{file}: line 1", "colour"],
        ),
        (
            "unknown field, named without a Rust type (was `colour`in `PairFile`)",
            mesh(good, "clearance_percent: Some(40.0), colour: 3"),
            &["Unexpected field named `colour`, expected one of `driver`, `driven`"],
        ),
        (
            "wrong type",
            mesh(
                "(teeth: \"twenty\", tip_radius: 10.0, root_radius: 9.0)",
                g40,
            ),
            &["{file}: line 1"],
        ),
        (
            "NaN radius",
            mesh("(teeth: 20, tip_radius: NaN, root_radius: 9.0)", g40),
            &["{file}: driver.tip_radius: must be a finite number"],
        ),
        (
            "infinite radius",
            mesh("(teeth: 20, tip_radius: inf, root_radius: 9.0)", g40),
            &["{file}: driver.tip_radius: must be a finite number"],
        ),
        (
            "negative teeth",
            mesh("(teeth: -20, tip_radius: 10.0, root_radius: 9.0)", g40),
            &["{file}: line 1"],
        ),
        (
            "zero teeth",
            mesh("(teeth: 0, tip_radius: 10.0, root_radius: 9.0)", g40),
            &["{file}: driver.teeth: must be at least 3"],
        ),
        (
            "a billion teeth",
            mesh(
                "(teeth: 1000000000, tip_radius: 10.0, root_radius: 9.0)",
                g40,
            ),
            &["{file}: driver.teeth: must be at most 100000"],
        ),
        (
            "negative radius",
            mesh("(teeth: 20, tip_radius: 10.0, root_radius: -9.0)", g40),
            &["{file}: driver.root_radius: must be greater than 0"],
        ),
        (
            "zero radius",
            mesh("(teeth: 20, tip_radius: 10.0, root_radius: 0.0)", g40),
            &["{file}: driver.root_radius: must be greater than 0"],
        ),
        (
            "root >= tip",
            mesh("(teeth: 20, tip_radius: 10.0, root_radius: 10.0)", g40),
            &["{file}: driver.root_radius: must be less than tip_radius"],
        ),
        (
            "clearance 150 %",
            mesh(good, "clearance_percent: Some(150.0)"),
            &["{file}: clearance_percent: must be more than 0 and less than 100"],
        ),
        (
            "clearance -1 %",
            mesh(good, "clearance_percent: Some(-1.0)"),
            &["{file}: clearance_percent: must be more than 0 and less than 100"],
        ),
        (
            "clearance NaN",
            mesh(good, "clearance_percent: Some(NaN)"),
            &["{file}: clearance_percent: must be more than 0 and less than 100"],
        ),
        (
            "no distance",
            mesh(good, ""),
            &["{file}: centre_distance: give exactly one of"],
        ),
        (
            "NaN distance",
            mesh(good, "centre_distance: Some(NaN)"),
            &["{file}: centre_distance"],
        ),
        (
            "overlapping gears",
            mesh(good, "centre_distance: Some(15.0)"),
            &["{file}: centre_distance: must exceed"],
        ),
        (
            "tips miscounted",
            mesh(
                "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([0.0, 10.0]))",
                g40,
            ),
            &["{file}: driver.tips_deg: must list exactly"],
        ),
        (
            "tips out of order",
            mesh(
                "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([0.0, 200.0, 100.0]))",
                g40,
            ),
            &["{file}: driver.tips_deg[2]"],
        ),
        (
            "axis outside the root",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, eccentricity: Some((9.5, 0.0)))",
                g40,
            ),
            &["{file}: driver.eccentricity"],
        ),
        (
            "sample step zero",
            mesh(good, "clearance_percent: Some(40.0), sample_deg: 0.0"),
            &["{file}: sample_deg"],
        ),
        (
            "run too long",
            mesh(good, "clearance_percent: Some(40.0), run_deg: Some(1e12)"),
            &["{file}: run_deg"],
        ),
        (
            "sample step 1e-12 without run_deg (aborted on allocation)",
            mesh(good, "clearance_percent: Some(40.0), sample_deg: 1e-12"),
            &[
                "{file}: sample_deg: must be at least 0.00036 degrees",
                "more than 1000000 rows",
            ],
        ),
        (
            "sample step 1e-4 (a 143 MB CSV)",
            mesh(good, "clearance_percent: Some(40.0), sample_deg: 1e-4"),
            &["{file}: sample_deg: must be at least 0.00036 degrees"],
        ),
        (
            "a turn of a 65535-tooth driver (18 hours, silently)",
            mesh(
                "(teeth: 65535, tip_radius: 10.0, root_radius: 9.0)",
                "clearance_percent: Some(40.0), sample_deg: 0.01",
            ),
            &[
                "{file}: run_deg: 360 degrees of a 65535-tooth driver against 65535 teeth",
                "more than the limit of 4000000",
            ],
        ),
        (
            "tip radius 1e308 with a clearance (blamed centre_distance)",
            mesh("(teeth: 20, tip_radius: 1e308, root_radius: 9.0)", g40),
            // Since lengths are checked for scale: refused for its size, in short form.
            &[
                "{file}: driver.tip_radius: must be from 1e-9 to 1000000000",
                "(got 1e308)",
            ],
        ),
        (
            "tip radius 1e308 with a distance (printed 309 digits)",
            mesh(
                "(teeth: 20, tip_radius: 1e308, root_radius: 9.0)",
                "centre_distance: Some(25.0)",
            ),
            &[
                "{file}: driver.tip_radius: must be from 1e-9",
                "(got 1e308)",
            ],
        ),
        (
            "gears that never touch",
            mesh(good, "centre_distance: Some(25.0)"),
            &["{file}: centre_distance: the gears never touch", "= 20,"],
        ),
        (
            "gears just out of reach",
            mesh(good, "centre_distance: Some(20.0)"),
            &["{file}: centre_distance: the gears never touch"],
        ),
        (
            "eccentric gears out of reach",
            mesh(
                "(teeth: 20, tip_radius: 10.0, root_radius: 9.0, eccentricity: Some((0.5, 0.0)))",
                "centre_distance: Some(20.6)",
            ),
            &["{file}: centre_distance: the gears never touch", "= 20.5,"],
        ),
        (
            "clearance 100 % (tips only graze)",
            mesh(good, "clearance_percent: Some(100.0)"),
            &["{file}: clearance_percent: must be more than 0 and less than 100 (got 100)"],
        ),
        (
            "clearance 0 % (refused by a rule naming 0 as allowed)",
            mesh(good, "clearance_percent: Some(0.0)"),
            &["{file}: clearance_percent: must be more than 0 and less than 100 (got 0)"],
        ),
    ];
    let cases = rows
        .into_iter()
        .map(|(what, file, words)| case(what, file, run, words))
        .collect();
    assert_none(failures("pair", cases));
}

/// Files that never end or are far too large: read up to a stated limit, then refused.
#[test]
fn endless_and_huge_files() {
    let huge = || Some(("huge.ron", vec![b' '; 17 * 1024 * 1024]));
    let cases = vec![
        case(
            "--config /dev/zero (grew past 2 GB)",
            None,
            "run pair --config /dev/zero --out {out}",
            &[
                "--config: /dev/zero: cannot read: is larger than 16777216 bytes, the limit on input files",
            ],
        ),
        case(
            "--config /dev/urandom (hung)",
            None,
            "run pair --config /dev/urandom --out {out}",
            &["--config: /dev/urandom: cannot read: is larger than 16777216 bytes"],
        ),
        case(
            "--config of 17 MiB",
            huge(),
            "run pair --config {file} --out {out}",
            &[
                "--config: ",
                "{file}: cannot read: is larger than 16777216 bytes",
            ],
        ),
        case(
            "--gearing /dev/zero",
            None,
            "run table1 --gearing /dev/zero --out {out}",
            &["/dev/zero: read: ", "is larger than 16777216 bytes"],
        ),
        case(
            "--gearing of 17 MiB",
            huge(),
            "run table1 --gearing {file} --out {out}",
            &["{file}: read: ", "is larger than 16777216 bytes"],
        ),
        case(
            "--errors /dev/urandom",
            None,
            "run table2 --errors /dev/urandom --out {out}",
            &["--errors: /dev/urandom: cannot read: is larger than 16777216 bytes"],
        ),
        case(
            "--set measured=/dev/zero",
            None,
            "run failure --set measured=/dev/zero --out {out}",
            &["--set measured: /dev/zero: cannot read: is larger than 16777216 bytes"],
        ),
        case(
            "fig6 --set measured=/dev/zero",
            None,
            "run fig6 --set measured=/dev/zero --out {out}",
            &["/dev/zero", "is larger than 16777216 bytes"],
        ),
        case(
            "merge /dev/zero",
            None,
            "merge /dev/zero --out {out}",
            &["/dev/zero: file: must be a regular file"],
        ),
    ];
    assert_none(failures("endless", cases));
}

#[test]
fn partial_files() {
    let f = |bytes: &[u8]| Some(("partial-0-of-1.json", bytes.to_vec()));
    // A partial file's JSON with the checksum the runner would give it.
    let seal = |json: &str| sealed(serde_json::from_str(json).unwrap()).into_bytes();
    let with_values = r#"{"format":"cargo-xtask-partial/1","experiment":"table1","seed":1,"sets":[],"config":null,"shard":0,"shards":1,"version":"0.1.0","batches":{"b":{"trials":2,"whole":false,"values":{"0":0.25,"1":0.5}}}}"#;
    let good = seal(with_values);
    let flipped = String::from_utf8(good.clone())
        .unwrap()
        .replace("0.25", "0.75")
        .into_bytes();
    assert_ne!(flipped, good);
    let merge = "merge {file} --out {out}";
    let cases = vec![
        case("truncated", f(br#"{"format":"cargo-xtask-partial/1","experiment":"#), merge, &["{file}: contents: is not a partial file", "EOF"]),
        case("not UTF-8", f(b"{\"format\":\xff}"), merge, &["{file}: file: cannot read: ", "UTF-8"]),
        case("empty", f(b""), merge, &["{file}: contents: is not a partial file"]),
        case(
            "unknown field",
            f(br#"{"format":"cargo-xtask-partial/1","experiment":"table1","seed":1,"sets":[],"config":null,"shard":0,"shards":1,"version":"0.1.0","batches":{},"colour":3}"#),
            merge,
            &["{file}: contents: ", "colour"],
        ),
        case(
            "wrong type",
            f(br#"{"format":"cargo-xtask-partial/1","experiment":"table1","seed":"one","sets":[],"config":null,"shard":0,"shards":1,"version":"0.1.0","batches":{}}"#),
            merge,
            &["{file}: contents: "],
        ),
        case(
            "shard out of range",
            Some(("p.json", br#"{"format":"cargo-xtask-partial/1","experiment":"table1","seed":1,"sets":[],"config":null,"shard":5,"shards":2,"version":"0.1.0","batches":{}}"#.to_vec())),
            merge,
            &["p.json: shard: 5/2 is not a shard K/N with K < N"],
        ),
        case(
            "unknown experiment",
            f(&seal(r#"{"format":"cargo-xtask-partial/1","experiment":"no-such","seed":1,"sets":[],"config":null,"shard":0,"shards":1,"version":"0.1.0","batches":{}}"#)),
            merge,
            &["unknown experiment `no-such`"],
        ),
        case(
            "trials beyond the limit",
            f(&seal(r#"{"format":"cargo-xtask-partial/1","experiment":"table1","seed":1,"sets":[["trials","18446744073709551615"]],"config":null,"shard":0,"shards":1,"version":"0.1.0","batches":{}}"#)),
            merge,
            &["--set: trials: must be at most 1000000, the limit on trials"],
        ),
        case("no partial file", None, "merge /no/such/dir --out {out}", &["merge: /no/such/dir: cannot read"]),
        case(
            "a value flipped after the shard wrote it (was merged)",
            f(&flipped),
            merge,
            &["{file}: checksum: does not match the contents"],
        ),
        case(
            "no checksum",
            f(with_values.as_bytes()),
            merge,
            &["{file}: checksum: is missing"],
        ),
    ];
    assert_none(failures("partial", cases));
}

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
