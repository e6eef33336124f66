//! The report page's tests: results read, bad results refused, the page and its heatmaps.

use super::heatmap::{Count, CountCell, count_cell, heat_rows, listing_folder};
use super::*;
use registry::{Context, Entry, OutputFile, Report};

// `a` is titled with markup the page must escape.
registry::test_experiment!(ExpA, "a", "Figure 1", registry::NoSettings, title: "First <one>");
registry::test_experiment!(ExpB, "b", "Table 2", registry::NoSettings, title: "Second");
static A: Entry = Entry::of::<ExpA>();
static B: Entry = Entry::of::<ExpB>();

fn registry() -> Registry {
    let mut r: Registry = BTreeMap::new();
    r.insert(A.id, &A);
    r.insert(B.id, &B);
    r
}

struct Scratch(PathBuf);
impl Scratch {
    fn new(tag: &str) -> Self {
        let nanos = std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .unwrap()
            .as_nanos();
        let p =
            std::env::temp_dir().join(format!("xtask-report-{tag}-{}-{nanos}", std::process::id()));
        fs::create_dir_all(&p).unwrap();
        Scratch(p)
    }
}
impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = fs::remove_dir_all(&self.0);
    }
}

const SVG: &str = "<?xml version=\"1.0\"?>\n<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><polyline points=\"0,0 5,5\"/></svg>\n";

fn write_a(out: &Path) {
    let mut t = Table::new("Ours & the paper's", ["quantity", "ours", "paper"]);
    t.row(vec!["x".into(), "1.5 (1.4)".into(), "1.4".into()]);
    t.note("a <note>");
    let report = Report {
        tables: vec![t],
        files: vec![OutputFile::new("a.svg", SVG)],
        trials: 30,
        agreement: Some(registry::Agreement {
            consistent: 3,
            differ: 1,
            what: "values of a test".into(),
        }),
        ..Default::default()
    };
    let ctx = Context::new(&A, 11, 2, &[], None).unwrap();
    registry::write_results(
        &out.join("a"),
        &provenance::stamp(&report, &A, &ctx, &[], None),
    )
    .unwrap();
}

#[test]
fn page_has_tables_figures_provenance_and_not_run() {
    let s = Scratch::new("page");
    write_a(&s.0);
    fs::create_dir_all(s.0.join(".a.tmp-1")).unwrap(); // hidden: ignored
    let page = build(&registry(), &s.0, "", true).unwrap();
    assert!(page.contains("<section id=\"exp-a\" class=\"experiment run\">"));
    assert!(page.contains("<h2>a: First &lt;one&gt;</h2>"));
    assert!(page.contains("<p class=\"table-title\">Ours &amp; the paper's</p>"));
    assert!(page.contains("<td class=\"num\">1.5 (1.4)</td><td class=\"num paper\">1.4</td>"));
    assert!(page.contains("<li>a &lt;note&gt;</li>"));
    assert!(page.contains("<figure data-file=\"a/a.svg\">\n<svg xmlns"));
    assert!(!page.contains("<?xml"));
    assert!(page.contains("seed <b>11</b>, 2 threads"));
    assert!(page.contains("against the paper: 3 / 1: values of a test"));
    assert!(page.contains("<section id=\"exp-b\" class=\"experiment not-run\">"));
    assert!(page.contains("<p class=\"status\">not run</p>"));
    assert!(!page.contains("tmp-1"));
    assert!(
        !page.contains("<link") && !page.contains("<script"),
        "self-contained"
    );
    assert_eq!(page.matches("<svg").count(), 1);
}

#[test]
fn replayed_trials_are_linked_from_their_experiment_not_shown_as_one() {
    let s = Scratch::new("replays");
    let mut t = Table::new("Table 3", ["case", "m3-e3"]);
    t.row(vec!["B".into(), "141/0".into()]);
    let report = Report {
        tables: vec![t],
        ..Default::default()
    };
    registry::write_results(&s.0.join("table3"), &report).unwrap();
    let replay = Report {
        tables: vec![Table::new("table3 B/m3-e3, trial 1", ["phi"])],
        files: vec![OutputFile::new("pair.html", "<!DOCTYPE html>")],
        ..Default::default()
    };
    registry::write_results(&s.0.join("replay-table3-B-m3-e3-1"), &replay).unwrap();
    // A listing of the cell's failed trials: shown on the page, not as its raw table.md.
    let mut failed = Table::new(
        "table3 B/m3-e3: the trials that failed, of 200 (seed 2025)",
        ["failure", "trials", "trial indices"],
    );
    failed.row(vec!["jam".into(), "141".into(), "1, 2, 3".into()]);
    let listing = Report {
        tables: vec![failed],
        files: vec![OutputFile::new(
            "failed-trials.csv",
            "trial,jammed,disengaged\n1,true,false\n",
        )],
        ..Default::default()
    };
    registry::write_results(&s.0.join("replay-table3-B-m3-e3-failed"), &listing).unwrap();
    let page = build(&registry(), &s.0, "", true).unwrap();
    assert!(
        page.contains("<a href=\"replay-table3-B-m3-e3-1/pair.html\">replay-table3-B-m3-e3-1</a>"),
        "{page}"
    );
    assert!(
        page.contains("<a href=\"#listing-replay-table3-B-m3-e3-failed\">")
            && page.contains(
                "<details class=\"listing\" id=\"listing-replay-table3-B-m3-e3-failed\">"
            )
            && page.contains("<td class=\"num\">141</td>"),
        "the listing is drawn on the page: {page}"
    );
    assert!(
        !page.contains("replay-table3-B-m3-e3-failed/table.md"),
        "no link opens the listing's raw table.md: {page}"
    );
    assert!(
        !page.contains("id=\"exp-replay-"),
        "a replay is no experiment of its own"
    );
}

#[test]
fn command_writes_the_page_atomically() {
    let s = Scratch::new("command");
    write_a(&s.0);
    command(&out_at(&s.0)).unwrap();
    let page = fs::read_to_string(s.0.join(INDEX_HTML)).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"));
    let names: Vec<String> = fs::read_dir(&s.0)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 2, "{names:?}");
}

#[test]
fn no_results_is_bad_input_and_writes_nothing() {
    let s = Scratch::new("empty");
    let e = build(&registry(), &s.0, "", true).unwrap_err();
    assert_eq!(e.code(), 2);
    assert!(format!("{e:?}").contains("no results"), "{e:?}");
    let e = command(&out_at(&s.0)).unwrap_err();
    assert_eq!(e.code(), 2);
    assert!(!s.0.join(INDEX_HTML).exists());
    let e = build(&registry(), &s.0.join("missing"), "", true).unwrap_err();
    assert_eq!(e.code(), 2);
    assert!(format!("{e:?}").contains("no such directory"), "{e:?}");
}

#[test]
fn broken_results_name_the_file_and_field() {
    let cases: [(&str, &str, &str); 6] = [
        ("tables.json", "{", "not valid JSON"),
        ("tables.json", "{\"tables\": 3}", "tables: must be an array"),
        (
            "tables.json",
            "{\"tables\": [{\"title\": \"t\", \"columns\": [1], \"rows\": []}]}",
            "tables[0].columns: must be an array of strings",
        ),
        (
            "tables.json",
            "{\"tables\": [], \"files\": [\"gone.svg\"]}",
            "files: lists gone.svg",
        ),
        (
            "run.json",
            "{\"seed\": -1}",
            "run.json: seed: must be a non-negative",
        ),
        ("a.svg", "<svg></svg>", "a.svg: must be an SVG drawing"),
    ];
    for (file, text, want) in cases {
        let s = Scratch::new("broken");
        write_a(&s.0);
        // Under a registered id: an unreadable folder of no experiment is skipped instead.
        fs::rename(s.0.join("a"), s.0.join("fig2")).unwrap();
        fs::write(s.0.join("fig2").join(file), text).unwrap();
        let e = command(&out_at(&s.0)).unwrap_err();
        assert_eq!(e.code(), 2, "{file}");
        let msg = format!("{e:?}");
        assert!(msg.contains(want), "{file}: {msg}");
        assert!(!s.0.join(INDEX_HTML).exists(), "{file}");
    }
}

/// `report --out DIR`.
fn out_at(dir: &Path) -> ReportArgs {
    ReportArgs {
        out: Some(dir.to_path_buf()),
        quiet: false,
        bundle: None,
    }
}

#[test]
fn svg_embedding() {
    assert_eq!(
        embed_svg(SVG),
        Embed::Inline(
            "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><polyline points=\"0,0 5,5\"/></svg>"
                .into()
        )
    );
    for risky in [
        "<svg><script>alert(1)</script><path d=\"M0 0\"/></svg>",
        "<svg onload=\"x()\"><path/></svg>",
        "<svg><line/></svg><svg onclick = \"x\"/>",
        "<div><svg><path/></svg></div>",
    ] {
        assert!(matches!(embed_svg(risky), Embed::DataUri(_)), "{risky}");
    }
    assert!(matches!(
        embed_svg("<svg><text>one driver turn</text><line/></svg>"),
        Embed::Inline(_)
    ));
    assert!(has_drawing(SVG));
    assert!(!has_drawing("<svg><rect/></svg>"));
}

#[test]
fn helpers() {
    assert_eq!(base64(b""), "");
    assert_eq!(base64(b"f"), "Zg==");
    assert_eq!(base64(b"fo"), "Zm8=");
    assert_eq!(base64(b"foo"), "Zm9v");
    assert_eq!(base64(b"foobar"), "Zm9vYmFy");
    assert_eq!(
        esc("<a href='x'>&\"</a>"),
        "&lt;a href='x'&gt;&amp;&quot;&lt;/a&gt;"
    );
    assert_eq!(url_part("fig 2/ä.svg"), "fig%202%2F%C3%A4.svg");
    assert!(numeric("17.96") && numeric("< 1e-12") && numeric("-0.5") && numeric("0 / 0"));
    assert!(!numeric("theta") && !numeric("-") && !numeric(""));
    // The page's commands carry its --out as one word of the shell.
    assert_eq!(out_flag(None), "");
    assert_eq!(out_flag(Some(Path::new("runs/a"))), " --out runs/a");
    assert_eq!(
        out_flag(Some(Path::new("my 'runs'"))),
        r" --out 'my '\''runs'\'''"
    );
}

#[test]
fn count_cells_are_read_as_printed() {
    let c = |ours, paper, differs| Count {
        ours,
        paper,
        differs,
    };
    let cell = |jams, dis, ours_keep_rule, paper_keeps_rule, compared| CountCell {
        jams,
        dis,
        ours_keep_rule,
        paper_keeps_rule,
        compared,
    };
    assert_eq!(
        count_cell("141*/0 (168/0)"),
        Some(cell(
            c(141, Some(168), true),
            c(0, Some(0), false),
            false,
            Some(false),
            true
        ))
    );
    assert_eq!(
        count_cell("200/3* (200/189)"),
        Some(cell(
            c(200, Some(200), false),
            c(3, Some(189), true),
            false,
            Some(false),
            true
        ))
    );
    // Both sides keep the 1 % rule: each marked.
    assert_eq!(
        count_cell("2/0✓ (1/0✓)"),
        Some(cell(
            c(2, Some(1), false),
            c(0, Some(0), false),
            true,
            Some(true),
            true
        ))
    );
    // Ours keeps it, the paper's does not; the cell ran on other inputs than the paper's.
    assert_eq!(
        count_cell("0/0✓ (3/0)†"),
        Some(cell(
            c(0, Some(3), false),
            c(0, Some(0), false),
            true,
            Some(false),
            false
        ))
    );
    assert_eq!(
        count_cell("5/0 (-/-)"),
        Some(cell(
            c(5, None, false),
            c(0, None, false),
            false,
            None,
            true
        ))
    );
    for other in ["-", "0.055 (0.045)*", "< 0.1 (0.2)", "1/2", ""] {
        assert_eq!(count_cell(other), None, "{other}");
    }
}

#[test]
fn heatmap_cells_are_named_as_replay_names_them() {
    let mut t5 = Table::new("Table 5: x", ["E. sys [deg]", "b2-c1", "e4-f1"]);
    t5.row(vec![
        "E. max (random)".into(),
        "0.055 (0.055)".into(),
        "< 0.035 (0.045)*".into(),
    ]);
    t5.row(vec!["0.7".into(), "11*/0 (1/0)".into(), "-".into()]);
    t5.row(vec![
        "E. max (systematic)".into(),
        "0.2 (0.7)".into(),
        "< 0.1 (0.2)".into(),
    ]);
    let rows = heat_rows("table5", &t5, 1);
    assert_eq!(rows.len(), 1, "the E. max rows are no counts");
    assert_eq!(rows[0].1[0].as_ref().unwrap().0, "0.055/0.7/b2-c1");
    assert!(rows[0].1[1].is_none(), "a column below the grid is not run");

    let mut t_i = Table::new("Table I: x", ["case", "G [%]", "m3-e3"]);
    t_i.row(vec!["B".into(), "10".into(), "1/0 (1/0)".into()]);
    t_i.row(vec!["".into(), "70".into(), "200/29* (197/186)".into()]);
    let rows = heat_rows("tableI", &t_i, 2);
    assert_eq!(rows[1].0, "Case B, G = 70 %");
    assert_eq!(rows[1].1[0].as_ref().unwrap().0, "B/70/m3-e3");
    assert_eq!(
        listing_folder("tableI", "B/70/m3-e3"),
        "replay-tableI-B-70-m3-e3-failed"
    );
    assert_eq!(
        listing_folder("table4", "0.065/m3-e3"),
        "replay-table4-0.065-m3-e3-failed"
    );
}

#[test]
fn runs_on_other_inputs_show_no_marks_and_no_agreement_as_a_check() {
    let title = "Table 3: counts: ours (paper); * where a two-sample test separates them [events: x] [inputs differ from the defaults: trials=2]";
    assert_eq!(
        without_marks(title),
        "Table 3: counts: ours (paper) [events: x] [inputs differ from the defaults: trials=2]"
    );
    let mut t = Table::new(title, ["case", "m3-e3"]);
    t.row(vec!["B".into(), "141*/0 (168/0)".into()]);
    t.note("The paper's counts consistent with ours: jams 1 of 2.");
    t.note("Each trial: one turn.");
    let mut h = String::new();
    table(&mut h, &t, true);
    assert!(!h.contains('*'), "{h}");
    assert!(h.contains("<li><b>For reference only, not a check"), "{h}");
    assert!(h.contains("<li>Each trial: one turn.</li>"), "{h}");
    let mut h = String::new();
    table(&mut h, &t, false);
    assert!(h.contains("141*/0 (168/0)"));
    assert!(!h.contains("For reference only"));
}

/// The names and contents of the files in the gzipped tar archive `file`.
fn archive_entries(file: &Path) -> Vec<(String, Vec<u8>)> {
    archive_dated(file)
        .into_iter()
        .map(|(n, b, _)| (n, b))
        .filter(|(n, _)| !n.ends_with('/'))
        .collect()
}

/// Every entry of the archive `file`, folders too: name, contents and date (seconds since 1970).
fn archive_dated(file: &Path) -> Vec<(String, Vec<u8>, u64)> {
    use std::io::Read as _;
    let gz = flate2::read::GzDecoder::new(fs::File::open(file).unwrap());
    let mut tar = tar::Archive::new(gz);
    tar.entries()
        .unwrap()
        .map(|e| {
            let mut e = e.unwrap();
            let name = e.path().unwrap().to_string_lossy().into_owned();
            let mtime = e.header().mtime().unwrap();
            let mut bytes = Vec::new();
            e.read_to_end(&mut bytes).unwrap();
            (name, bytes, mtime)
        })
        .collect()
}

/// `report --bundle FILE` archives the page, every experiment's folder and every input file
/// a `run.json` names (checked against its SHA-256); an input changed since the run is refused
/// naming both files, and nothing is written.
#[test]
fn bundle_holds_results_and_inputs_and_refuses_a_changed_input() {
    let dir = Scratch::new("bundle");
    let out = dir.0.join("results");
    write_a(&out);
    let gearing = dir.0.join("gearing.ron");
    fs::write(&gearing, "(gears: [])\n").unwrap();
    let run_json = out.join("a").join("run.json");
    let mut v: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(&run_json).unwrap()).unwrap();
    v["inputs"] = serde_json::json!([{
        "role": "gearing",
        "path": gearing.display().to_string(),
        "sha256": crate::provenance::sha256(b"(gears: [])\n"),
    }]);
    fs::write(&run_json, v.to_string()).unwrap();
    let file = dir.0.join("supplement.tar.gz");
    let args = ReportArgs {
        bundle: Some(file.clone()),
        ..out_at(&out)
    };
    let before = super::bundle::now_seconds();
    command(&args).unwrap();
    let after = super::bundle::now_seconds();
    // Every entry, folders too, dated when the bundle was written.
    for (name, _, mtime) in archive_dated(&file) {
        assert!(
            (before..=after).contains(&mtime),
            "{name} dated {mtime}, not {before}..{after}"
        );
    }
    let entries = archive_entries(&file);
    let names: Vec<&str> = entries.iter().map(|(n, _)| n.as_str()).collect();
    assert!(names.contains(&"results/index.html"), "{names:?}");
    assert!(names.contains(&"results/a/run.json"), "{names:?}");
    assert!(names.contains(&"results/a/tables.json"), "{names:?}");
    let input = format!("inputs/{}", super::bundle_path_of(&gearing));
    let (_, bytes) = entries.iter().find(|(n, _)| *n == input).unwrap();
    assert_eq!(bytes, b"(gears: [])\n");

    // The input changed since the run: refused, the earlier archive left as it was.
    fs::write(&gearing, "(gears: [1])\n").unwrap();
    let before = fs::read(&file).unwrap();
    let Err(Failure::Bad(m)) = command(&args) else {
        panic!("a changed input must be refused")
    };
    assert!(
        m.contains("run.json") && m.contains("gearing.ron") && m.contains("changed"),
        "{m}"
    );
    assert_eq!(fs::read(&file).unwrap(), before);
}

/// The overview says what each count counts: a count of gears equal on a grid is not read as
/// mostly wrong, and an experiment that judges no agreement but prints ours over the paper's
/// shows that ratio rather than `-`.
#[test]
fn the_overview_says_what_its_counts_count() {
    let s = Scratch::new("overview");
    let mut t = Table::new("Figure 6", ["gear", "ours", "paper"]);
    t.row(vec!["b2".into(), "0.050".into(), "0.055".into()]);
    let fig = Report {
        tables: vec![t],
        agreement: Some(registry::Agreement {
            consistent: 9,
            differ: 20,
            what: "gears whose value equals the paper's / does not (no test)".into(),
        }),
        ..Default::default()
    };
    registry::write_results(&s.0.join("a"), &fig).unwrap();
    let mut t = Table::new("Table 1", ["pointer", "ours", "paper", "ours/paper"]);
    t.row(vec![
        "Lunar".into(),
        "0.75".into(),
        "0.60".into(),
        "1.26".into(),
    ]);
    t.row(vec![
        "Games".into(),
        "0.07".into(),
        "0.04".into(),
        "1.76".into(),
    ]);
    t.row(vec![
        "Lunar P".into(),
        "0.50".into(),
        "0.66".into(),
        "0.76".into(),
    ]);
    let table1 = Report {
        tables: vec![t],
        ..Default::default()
    };
    registry::write_results(&s.0.join("b"), &table1).unwrap();
    let page = build(&registry(), &s.0, "", true).unwrap();
    let row = |id: &str| {
        let at = page.find(&format!("<a href=\"#exp-{id}\">")).unwrap();
        page[at..at + page[at..].find("</tr>").unwrap()].to_owned()
    };
    assert!(
        row("a").contains("9 / 20: gears whose value equals the paper's / does not (no test)"),
        "{}",
        row("a")
    );
    assert!(row("b").contains("ours/paper 0.76 to 1.76"), "{}", row("b"));
    assert!(page.contains("against the paper: 9 / 20: gears whose"));
}

/// The heatmaps' key says what green means: agreement with the paper's count, however many
/// trials failed, not a mesh that works.
#[test]
fn the_heatmap_key_says_what_green_means() {
    let s = Scratch::new("heat-key");
    let mut columns = vec!["case".to_owned()];
    columns.extend(["b2-c1", "c2-d1"].map(str::to_owned));
    let mut t = Table::new(
        "Table 3: trials (of 200) with at least one jam / disengagement, G = 40 %: ours (paper); * where a two-sample test separates our count from the paper's",
        columns,
    );
    t.row(vec![
        "D".into(),
        "199/0 (200/0)".into(),
        "150*/0 (195/0)".into(),
    ]);
    let report = Report {
        tables: vec![t],
        ..Default::default()
    };
    registry::write_results(&s.0.join("table3"), &report).unwrap();
    let mut exps = registry();
    exps.insert("table3", &A);
    let page = build(&exps, &s.0, "", true).unwrap();
    let key = &page[page.find("<p class=\"heat-key\">").unwrap()..];
    let key = &key[..key.find("</p>").unwrap()];
    for words in [
        "green: consistent",
        "however many trials failed",
        "green does not say the mesh works",
        "red: differs",
    ] {
        assert!(key.contains(words), "`{words}` missing from the key: {key}");
    }
    assert!(
        page.contains("<td class=\"hm consistent\""),
        "the 199 | 200 cell is green"
    );
}
