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
use support::sealed;

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
