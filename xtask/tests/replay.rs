//! `replay` as a reader of Table 3 uses it: the failed trials of a cell are the ones a sharded and
//! merged run counted, a replayed jam happens at the same driver angle when the written pair file
//! is rerun with `run pair`, and bad arguments are refused with one line.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{Scratch, stderr, succeeded, xtask};

/// The number in the `trials` column of a listing row (`| jam | 7 | 1, 2, ... |`).
fn listed(text: &str, failure: &str) -> (u64, Vec<u64>) {
    let row = text
        .lines()
        .find(|l| l.starts_with(&format!("| {failure} ")))
        .unwrap();
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    let indices = cells[3]
        .split(", ")
        .filter_map(|t| t.parse().ok())
        .collect();
    (cells[2].parse().unwrap(), indices)
}

#[test]
fn failed_trials_are_the_ones_a_sharded_run_counted_and_rerun_as_pairs() {
    let s = Scratch::new("replay");
    let out = s.path("out");
    // Table 3 at 12 trials per cell, in two shards merged.
    for k in ["0/2", "1/2"] {
        succeeded(&[
            "run",
            "table3",
            "-q",
            "--set",
            "trials=12",
            "--shard",
            k,
            "--out",
            &out,
        ]);
    }
    let merged = succeeded(&[
        "merge",
        &s.path("out/table3"),
        "-q",
        "--out",
        &s.path("merged"),
    ]);
    // Case B, m3-e3: `141/0 (168/0)` at 200 trials; here some count of 12.
    let row = merged.lines().find(|l| l.starts_with("| B ")).unwrap();
    let header = merged.lines().find(|l| l.starts_with("| case ")).unwrap();
    let column = header
        .split('|')
        .map(str::trim)
        .position(|c| c == "m3-e3")
        .unwrap();
    let cell = row.split('|').map(str::trim).nth(column).unwrap();
    let jams: u64 = cell
        .split('/')
        .next()
        .unwrap()
        .trim_end_matches('*')
        .parse()
        .unwrap();
    let listing = succeeded(&[
        "replay",
        "table3",
        "B/m3-e3",
        "-q",
        "--set",
        "trials=12",
        "--out",
        &out,
    ]);
    let (count, trials) = listed(&listing, "jam");
    assert_eq!(count, jams, "{listing}\n{merged}");
    assert!(!trials.is_empty(), "no jam to replay: {listing}");
    // The first jammed trial: its jam, then the same gears rerun from pair.ron by `run pair`.
    let t = trials[0].to_string();
    let one = succeeded(&[
        "replay", "table3", "B/m3-e3", &t, "-q",
        // `--trials N` as `run` takes it: the same as `--set trials=N`.
        "--trials", "12", "--out", &out,
    ]);
    assert!(one.contains(": jammed"), "{one}");
    let header = |text: &str| -> Vec<String> {
        let line = text.lines().find(|l| l.contains(" kind ")).unwrap();
        line.split('|').map(|c| c.trim().to_owned()).collect()
    };
    assert_eq!(
        header(&one)[1..3],
        ["phi - phi0 [deg]", "phi [deg]"],
        "both angles, named apart: {one}"
    );
    let jam_row = one.lines().find(|l| l.contains("| jam ")).unwrap();
    let cell =
        |row: &str, i: usize| -> f64 { row.split('|').nth(i).unwrap().trim().parse().unwrap() };
    let (rel, phi) = (cell(jam_row, 1), cell(jam_row, 2));
    let pair_file = s.0.join(format!("out/replay-table3-B-m3-e3-{t}/pair.ron"));
    let start_deg: f64 = std::fs::read_to_string(&pair_file)
        .unwrap()
        .lines()
        .find_map(|l| l.trim().strip_prefix("start_deg: "))
        .unwrap()
        .trim_end_matches(',')
        .parse()
        .unwrap();
    let rerun = succeeded(&[
        "run",
        "pair",
        "-q",
        "--config",
        pair_file.to_str().unwrap(),
        "--out",
        &out,
    ]);
    let first_jam = rerun
        .lines()
        .skip_while(|l| !l.starts_with("### Events"))
        .find(|l| l.contains("| jam "))
        .unwrap();
    // Both print phi - phi0 and phi, under the same headers, and agree on both.
    let events = &rerun[rerun.find("### Events").unwrap()..];
    assert_eq!(
        header(events)[1..3],
        ["phi - phi0 [deg]", "phi [deg]"],
        "{rerun}"
    );
    let (rerun_rel, rerun_phi) = (cell(first_jam, 1), cell(first_jam, 2));
    assert!(
        (rerun_rel + start_deg - phi).abs() < 1e-5 && (rerun_phi - phi).abs() < 1e-5,
        "replay {phi} deg, pair {rerun_phi} deg ({rerun_rel} + {start_deg} deg)"
    );
    assert!(
        (rerun_rel - rel).abs() < 1e-5,
        "replay {rel}, pair {rerun_rel}"
    );
}

#[test]
fn bad_arguments_are_refused_in_one_line() {
    for (args, words) in [
        (
            &["replay", "fig2", "x", "0"][..],
            "has no replayable trials",
        ),
        (&["replay", "table3", "B"], "must be CASE/MESH"),
        (
            &["replay", "table3", "B/m3-e3", "200"],
            "must be below table3's 200 trials",
        ),
        (
            &["replay", "table3", "B/m3-e3", "x"],
            "is not a trial index",
        ),
        (&["replay", "table3"], "usage: cargo xtask replay"),
        (&["replay", "nope", "B/m3-e3", "0"], "nope"),
    ] {
        let o = xtask(args);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        let err = stderr(&o);
        assert!(err.contains(words), "{args:?}: {err}");
        assert!(o.stdout.is_empty(), "{args:?}: nothing on stdout");
    }
}

/// A driven gear that no driver tooth ever pushes is a failure a reader must see: Case D's
/// eccentric m3-e3 at G = 40 % starts out of reach in trial 0 and never moves. `replay` reports
/// the idle start, every registered rule counts it as a disengagement, and `run pair` on the
/// written pair file reports it too (never "driven throughout").
#[test]
fn an_idle_start_is_reported_and_every_rule_counts_it() {
    let s = Scratch::new("replay-idle");
    let out = s.path("out");
    for rule in rules::rules().unwrap().keys() {
        let text = succeeded(&[
            "replay",
            "table3",
            "D/m3-e3",
            "0",
            "-q",
            "--set",
            &format!("events={rule}"),
            "--out",
            &out,
        ]);
        let title = text.lines().find(|l| l.starts_with("### ")).unwrap();
        assert!(title.contains("disengaged"), "{rule}: {text}");
        let row = text.lines().find(|l| l.contains("| idle start ")).unwrap();
        assert!(row.contains("| disengagement "), "{rule}: {text}");
        // No tooth touches the driven gear: the row names none.
        let cells: Vec<&str> = row.split('|').map(str::trim).collect();
        assert_eq!(&cells[5..7], ["-", "-"], "{rule}: {row}");
    }
    let pair = succeeded(&[
        "run",
        "pair",
        "-q",
        "--config",
        &s.path("out/replay-table3-D-m3-e3-0/pair.ron"),
        "--out",
        &s.path("pair"),
    ]);
    assert!(pair.contains("| idle start "), "{pair}");
    let row = pair.lines().find(|l| l.contains("| idle start ")).unwrap();
    let cells: Vec<&str> = row.split('|').map(str::trim).collect();
    assert_eq!(&cells[5..7], ["-", "-"], "{row}");
    assert!(pair.contains("never pushed"), "{pair}");
    assert!(!pair.contains("driven throughout"), "{pair}");
}

/// `--out` naming a file is refused before the trial is rebuilt, in one line, with exit 2 (it
/// used to fail after computing, as an internal error).
#[test]
fn an_out_that_is_a_file_is_refused_before_computing() {
    let s = Scratch::new("replay-out-file");
    let file = s.path("a-file");
    std::fs::write(&file, "kept").unwrap();
    let o = support::xtask(&["replay", "table3", "B/m3-e3", "1", "--out", &file]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("--out"), "{err}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "kept");
}

/// One validation path for a cell, whichever command names it: a replayed trial's pair file is
/// checked by the loader `run pair` uses before anything is computed or written. Teeth 2 mm tall
/// on h2 (tip radius 3.2 mm) are more than half its radius: `replay` wrote that pair file and
/// `run pair` then refused it. Now `replay` refuses in one line naming the setting typed and the
/// rule, and a height within the rule gives a pair file `run pair` runs.
#[test]
fn a_trial_whose_pair_file_run_pair_refuses_is_refused_before_anything_is_written() {
    let s = Scratch::new("replay-refused-pair");
    let out = s.path("out");
    let o = xtask(&[
        "replay",
        "table3",
        "B/h2-i1",
        "0",
        "-q",
        "--set",
        "tooth_height=2",
        "--out",
        &out,
    ]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(o.stdout.is_empty(), "nothing on stdout: {err}");
    for words in ["--set: tooth_height=2", "run pair", "driver.root_radius"] {
        assert!(err.contains(words), "`{words}` missing: {err}");
    }
    assert!(
        !s.0.join("out/replay-table3-B-h2-i1-0").exists(),
        "nothing written: {err}"
    );
    // Within the rule (h = 1.5 mm, under half of 3.2 mm), the written pair file runs.
    succeeded(&[
        "replay",
        "table3",
        "B/h2-i1",
        "0",
        "-q",
        "--set",
        "tooth_height=1.5",
        "--out",
        &out,
    ]);
    succeeded(&[
        "run",
        "pair",
        "-q",
        "--config",
        &s.path("out/replay-table3-B-h2-i1-0/pair.ron"),
        "--out",
        &s.path("pair"),
    ]);
}

/// `replay` accepted cells its table does not hold and titled them as the table's: a G not in
/// Table I's clearances, a random error between Table 4's rows, a Table 5 row at another random
/// error than the mesh's E. max, `-0` for a row. Each is refused in one line naming the part of
/// the cell typed (not a flag never typed) and the table's values, before anything is written.
#[test]
fn cells_that_are_not_cells_of_the_table_are_refused_naming_what_was_typed() {
    let s = Scratch::new("replay-not-cells");
    let out = s.path("out");
    for (args, words) in [
        (
            &["tableI", "B/55/m3-e3"][..],
            &[
                "cell `B/55/m3-e3` of tableI",
                "G `55`: is not one of the table's clearances (10, 40, 70",
            ][..],
        ),
        (
            &["tableI", "B/100.5/m3-e3", "0"],
            &["G `100.5`: is not one of the table's clearances"],
        ),
        (
            &["tableI", "B/40/m3-e3", "0", "--set", "clearances=10,70"],
            &["G `40`: is not one of the table's clearances (10, 70"],
        ),
        (
            &["table4", "0.066/m3-e3", "1"],
            &[
                "cell `0.066/m3-e3` of table4",
                "random error `0.066`: is not a row of the table (0.035, 0.04",
            ],
        ),
        (
            &["table4", "0.030/m3-e3", "1"],
            &["random error `0.030`: is not a row"],
        ),
        (
            &["table5", "0.050/-0/e4-f1", "1"],
            &["systematic error `-0`: is not a row of the table (0.1, 0.2"],
        ),
        (
            &["table5", "0.050/0.75/e4-f1", "1"],
            &["systematic error `0.75`: is not a row"],
        ),
        (
            &["table5", "0.050/99/e4-f1", "1"],
            &["cell `0.050/99/e4-f1` of table5", "systematic error `99`"],
        ),
        (
            &["table5", "0.035/0.7/e4-f1", "1", "--set", "emax=paper"],
            &[
                "random error `0.035`: is not the random error the table runs mesh e4-f1 at, its E. max 0.045 (the paper's",
            ],
        ),
        (
            &["table5", "0.035/0.7/e4-f1", "1"],
            &[
                "random error `0.035`: is not the random error the table runs mesh e4-f1 at, its E. max 0.05 (the largest of Table 4's grid",
            ],
        ),
    ] {
        let mut all = vec!["replay"];
        all.extend(args);
        all.extend(["--out", &out]);
        let o = xtask(&all);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{all:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{all:?}: {err}");
        for w in words {
            assert!(err.contains(w), "{all:?}: no {w:?} in {err}");
        }
        assert!(
            !err.contains("--hypothesis"),
            "{all:?} blamed a flag never typed: {err}"
        );
        assert!(o.stdout.is_empty(), "{all:?}");
        assert!(!s.0.join("out").exists(), "{all:?} wrote results");
    }
    // The cells of the tables are replayed.
    for args in [
        &["tableI", "B/70/m3-e3", "0", "--trials", "4"][..],
        &["table4", "0.065/m3-e3", "0", "--trials", "4"],
        &[
            "table5",
            "0.045/0.7/e4-f1",
            "0",
            "--set",
            "emax=paper",
            "--trials",
            "4",
        ],
    ] {
        let mut all = vec!["replay"];
        all.extend(args);
        all.extend(["-q", "--out", &out]);
        succeeded(&all);
    }
}

/// `replay ... --set clearance=50` wrote into the default replay's folder under the same title:
/// a replay under other settings goes to a folder of its own, and its title names them.
#[test]
fn a_replay_under_other_settings_keeps_the_default_replays_results() {
    let s = Scratch::new("replay-settings");
    let out = s.path("out");
    let base = [
        "replay", "table3", "B/m3-e3", "0", "--trials", "4", "-q", "--out", &out,
    ];
    let default = succeeded(&base);
    let mut other = base.to_vec();
    other.extend(["--set", "clearance=50"]);
    let changed = succeeded(&other);
    let mut seeded = base.to_vec();
    seeded.extend(["--seed", "7"]);
    succeeded(&seeded);
    let title = |text: &str| text.lines().next().unwrap_or_default().to_owned();
    assert!(!title(&default).contains("clearance=50"), "{default}");
    assert!(title(&changed).contains("clearance=50"), "{changed}");
    let read =
        |dir: &str| std::fs::read_to_string(s.0.join("out").join(dir).join("table.md")).unwrap();
    assert_eq!(title(&read("replay-table3-B-m3-e3-0")), title(&default));
    assert_eq!(
        title(&read("replay-table3-B-m3-e3-0-clearance-50")),
        title(&changed)
    );
    assert!(read("replay-table3-B-m3-e3-0-seed-7").contains("(seed 7)"));
    // The other way round: the replay under other settings is there first, in the plain folder;
    // the replay at the defaults takes that folder and moves it to its own name.
    let out2 = s.path("out2");
    let mut first = other.clone();
    let at = first.iter().position(|a| *a == out.as_str()).unwrap();
    first[at] = &out2;
    succeeded(&first);
    let read2 =
        |dir: &str| std::fs::read_to_string(s.0.join("out2").join(dir).join("table.md")).unwrap();
    assert_eq!(title(&read2("replay-table3-B-m3-e3-0")), title(&changed));
    let mut then = base.to_vec();
    then[at] = &out2;
    succeeded(&then);
    assert_eq!(title(&read2("replay-table3-B-m3-e3-0")), title(&default));
    assert_eq!(
        title(&read2("replay-table3-B-m3-e3-0-clearance-50")),
        title(&changed)
    );
}

/// A cell's listing names every failed trial in its data files, not the first few the printed
/// table shows: Table 3's Case B m3-e3 fails in over a hundred of its 200 trials.
#[test]
fn a_listing_writes_every_failed_trial() {
    let s = Scratch::new("replay-listing");
    let out = s.path("out");
    let text = succeeded(&["replay", "table3", "B/m3-e3", "-q", "--out", &out]);
    let row = text.lines().find(|l| l.starts_with("| jam ")).unwrap();
    let jams: usize = row.split('|').nth(2).unwrap().trim().parse().unwrap();
    assert!(jams > 20, "{text}");
    assert!(text.contains("every one in failed-trials.csv"), "{text}");
    let dir = s.0.join("out/replay-table3-B-m3-e3-failed");
    let csv = std::fs::read_to_string(dir.join("failed-trials.csv")).unwrap();
    let jammed: Vec<&str> = csv
        .lines()
        .skip(1)
        .filter(|l| l.split(',').nth(1) == Some("true"))
        .collect();
    assert_eq!(jammed.len(), jams, "{csv}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("failed-trials.json")).unwrap())
            .unwrap();
    assert_eq!(json["jammed"].as_array().unwrap().len(), jams);
    let tables = std::fs::read_to_string(dir.join("tables.json")).unwrap();
    assert!(
        !tables.contains("more)\""),
        "tables.json cuts the list short"
    );
}

/// The cells of the markdown table row `row`, trimmed.
fn cells(row: &str) -> Vec<&str> {
    row.trim_matches('|').split('|').map(str::trim).collect()
}

/// The script appended to a copy of a replayed trial's page: the colour of an event before
/// and after the first lock, the greyed stretch of the TD strip against where the first lock
/// is drawn, and the release links.
const PROTOCOL_SCRIPT: &str = r#"
(function () {
  const out = [];
  const items = document.querySelectorAll('#events > li');
  const colour = li => getComputedStyle(li.querySelector('a.event')).color;
  out.push(['before', colour(items[0])].join('\t'));
  out.push(['after', colour(document.querySelector('#events > li.protocol'))].join('\t'));
  out.push(['protocol-items', document.querySelectorAll('#events > li.protocol').length, items.length].join('\t'));
  out.push(['releases', document.querySelectorAll('#events a.release').length].join('\t'));
  const shade = document.querySelector('#plot rect.protocol');
  const b = shade.getBBox();
  out.push(['shade', b.x, b.width, getComputedStyle(shade).fill, PX0 + PW * PROTOCOL_FROM / PHI_MAX].join('\t'));
  document.getElementById('protocol-result').textContent = out.join('\n');
})();
"#;

/// Table 3's D/d2-e2, trial 4 locks 58 times, each released by letting the driven gear go to
/// the next free position (the paper's protocol), which takes its Theoretical Difference to
/// thousands of degrees. The replay and `run pair` mark the motion after the first lock as that
/// protocol (a motion column, a note, the Theoretical Difference greyed from there in pair.svg
/// and pair.html, the events after it greyed), and size every release and tooth-phase shift in
/// driven pitches - the held lock of event 59 too, 29 teeth on; the table's counts stay.
#[test]
fn motion_after_the_first_lock_is_marked_as_the_papers_protocol() {
    let s = Scratch::new("replay-protocol");
    let out = s.path("out");
    let text = succeeded(&["replay", "table3", "D/d2-e2", "4", "-q", "--out", &out]);
    assert!(text.contains("): jammed ["), "{text}");
    let header = text
        .lines()
        .find(|l| l.starts_with("| phi - phi0"))
        .unwrap();
    let columns = cells(header);
    let (size, motion) = (
        columns
            .iter()
            .position(|c| *c == "size")
            .expect("a size column"),
        columns
            .iter()
            .position(|c| *c == "motion")
            .expect("a motion column"),
    );
    let rows: Vec<Vec<&str>> = text
        .lines()
        .filter(|l| {
            l.starts_with("| ") && l.contains(" | lock ")
                || l.contains(" | gap ")
                || l.contains(" | slip ")
        })
        .map(cells)
        .collect();
    assert_eq!(rows.len(), 74, "{text}");
    assert!(rows[0][motion].contains("first lock"), "{:?}", rows[0]);
    for r in &rows[1..] {
        assert_eq!(r[motion], "protocol (after the first lock)", "{r:?}");
    }
    let locks: Vec<&Vec<&str>> = rows.iter().filter(|r| r[2] == "lock").collect();
    assert_eq!(locks.len(), 58);
    for r in &locks {
        assert!(
            r[size].contains("driven pitches") && r[size].contains("tooth phase"),
            "{r:?}"
        );
    }
    // Event 59: held, then let go 29 teeth on.
    assert!(
        rows[58][size].starts_with("held ")
            && rows[58][size].contains("28.95 driven pitches ahead")
            && rows[58][size].contains("tooth phase +29"),
        "{:?}",
        rows[58]
    );
    for words in [
        "After the first lock the motion is the paper's protocol",
        "Releases and tooth-phase shifts",
    ] {
        assert!(text.contains(words), "`{words}` missing:\n{text}");
    }
    let dir = s.0.join("out/replay-table3-D-d2-e2-4");
    let caption = std::fs::read_to_string(dir.join("event-59-lock.svg")).unwrap();
    for words in ["28.95 driven pitches", "After the trial's first lock"] {
        assert!(
            caption.contains(words),
            "event 59's caption lacks `{words}`"
        );
    }
    // The same trial through `run pair`: its statistics up to the first lock, the greyed TD,
    // and the event log's sizes.
    let rerun = succeeded(&[
        "run",
        "pair",
        "-q",
        "--config",
        dir.join("pair.ron").to_str().unwrap(),
        "--out",
        &s.path("rerun"),
    ]);
    assert!(
        rerun.contains("The run's first lock is at phi - phi0 = 3.102385 deg")
            && rerun.contains("up to it, sigma = "),
        "{rerun}"
    );
    let pair = s.0.join("rerun/pair");
    let svg = std::fs::read_to_string(pair.join("pair.svg")).unwrap();
    assert!(
        svg.contains("class=\"shade\"") && svg.contains("after the first lock (event 1)"),
        "pair.svg"
    );
    let log = std::fs::read_to_string(pair.join("event-log.csv")).unwrap();
    let head: Vec<&str> = log.lines().next().unwrap().split(',').collect();
    let col = |n: &str| head.iter().position(|c| *c == n).unwrap();
    let line59: Vec<&str> = log.lines().nth(59).unwrap().split(',').collect();
    let ahead: f64 = line59[col("ahead_of_ideal_driven_pitches")]
        .parse()
        .unwrap();
    assert!((ahead - 28.95).abs() < 0.01, "{line59:?}");
    assert_eq!(line59[col("after_first_lock")], "true");
    assert!(
        !line59[col("release_phi_minus_phi0_deg")].is_empty(),
        "{line59:?}"
    );

    let Some(chrome) = support::chromium_or_skip() else {
        return;
    };
    let page = std::fs::read_to_string(dir.join("pair.html")).unwrap();
    let checked = page.replace(
        "</body>",
        &format!("<pre id=\"protocol-result\"></pre><script>{PROTOCOL_SCRIPT}</script></body>"),
    );
    std::fs::write(dir.join("check.html"), checked).unwrap();
    let url = format!("file://{}", dir.join("check.html").display());
    let dom = support::browser::dump_dom(&chrome, &s.0.join(".chromium"), &url);
    let start =
        dom.find("<pre id=\"protocol-result\">").unwrap() + "<pre id=\"protocol-result\">".len();
    let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let lines: Vec<Vec<&str>> = result.lines().map(|l| l.split('\t').collect()).collect();
    let get = |k: &str| {
        lines
            .iter()
            .find(|l| l[0] == k)
            .unwrap_or_else(|| panic!("{k}: {result}"))
    };
    assert_ne!(
        get("before")[1],
        get("after")[1],
        "the protocol's events are not greyed: {result}"
    );
    assert_eq!(get("after")[1], "rgb(136, 136, 136)", "{result}");
    assert_eq!(get("protocol-items")[1..], ["73", "74"], "{result}");
    assert_eq!(
        get("releases")[1],
        "58",
        "every lock's release has its line: {result}"
    );
    let shade = get("shade");
    let (x, w, at): (f64, f64, f64) = (
        shade[1].parse().unwrap(),
        shade[2].parse().unwrap(),
        shade[4].parse().unwrap(),
    );
    assert!(
        (x - at).abs() < 0.5 && w > 100.0,
        "the grey starts at the first lock: {result}"
    );
    let png = s.0.join("protocol.png");
    support::browser::screenshot(
        &chrome,
        &s.0.join(".chromium-shot"),
        &url,
        &png,
        (1000, 1400),
    );
    support::browser::Pixels::read(&png).assert_not_blank("protocol.png", 16, 100);
}

/// Runs the built runner in the folder `dir` with `args`.
fn in_folder(dir: &std::path::Path, args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_LOG")
        .output()
        .unwrap()
}

/// `replay table3 B/m3-e3 --set gearing=freeth2006` with an edited file `./freeth2006` in the
/// folder used the built-in gearing (exit 0), where `run` refuses the ambiguity. Every command
/// that names an input resolves it by the one rule `run` uses: `replay`, and `merge` (new
/// instance: shards that ran on the built-in gearing, merged where a file of that name
/// appeared), and a replay's gearing file that breaks its rules (new instance) is refused
/// before the trial is rebuilt.
#[test]
fn every_command_resolves_a_named_input_by_one_rule() {
    let s = Scratch::new("one-rule");
    let here = s.0.join("here");
    std::fs::create_dir_all(&here).unwrap();
    std::fs::write(here.join("freeth2006"), "(gears: [])\n").unwrap();
    let ambiguous = "`freeth2006` is both an embedded gearing and a file in this folder";
    let o = in_folder(
        &here,
        &[
            "replay",
            "table3",
            "B/m3-e3",
            "0",
            "--trials",
            "2",
            "--set",
            "gearing=freeth2006",
            "--out",
            "out",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("--set: gearing: ") && err.contains(ambiguous),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(!here.join("out").exists(), "the replay wrote results");
    // A gearing file that is no gearing: refused before anything runs.
    let o = in_folder(
        &here,
        &[
            "replay",
            "table3",
            "B/m3-e3",
            "0",
            "--trials",
            "2",
            "--set",
            "gearing=./freeth2006",
            "--out",
            "out",
        ],
    );
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.starts_with("--set: gearing: ./freeth2006: "), "{err}");
    assert!(!here.join("out").exists(), "the replay wrote results");
    // Shards on the built-in gearing, merged where a file of its name is.
    let shards = s.path("shards");
    for k in ["0/2", "1/2"] {
        succeeded(&[
            "run",
            "table3",
            "-q",
            "--trials",
            "2",
            "--set",
            "gearing=freeth2006",
            "--shard",
            k,
            "--out",
            &shards,
        ]);
    }
    let o = in_folder(&here, &["merge", &shards, "--out", "merged"]);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains(ambiguous), "{err}");
    assert!(!here.join("merged").exists());
}

/// `run table3 --hypothesis measured` ran on the invented example table and neither its output
/// nor stderr said so (`pair` says so of its example). Both do now; so does `replay` (new
/// instance).
#[test]
fn a_run_on_the_invented_example_table_says_so() {
    let s = Scratch::new("example-table");
    let out = s.path("out");
    let o = xtask(&[
        "run",
        "table3",
        "--hypothesis",
        "measured",
        "--trials",
        "2",
        "--out",
        &out,
    ]);
    let err = stderr(&o);
    assert!(o.status.success(), "{err}");
    let said = "example table shipped with the toolkit";
    assert!(err.contains(said) && err.contains("INVENTED"), "{err}");
    let md = std::fs::read_to_string(s.0.join("out/table3/table.md")).unwrap();
    assert!(md.contains(said) && md.contains("INVENTED"), "{md}");
    assert!(support::stdout(&o).contains(said));
    let o = xtask(&[
        "replay",
        "table3",
        "B/m3-e3",
        "0",
        "--trials",
        "2",
        "--set",
        "hypothesis=measured",
        "--out",
        &out,
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(support::stdout(&o).contains(said) && stderr(&o).contains(said));
}
