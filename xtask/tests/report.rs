//! `cargo xtask report` end to end: run two cheap experiments with SVG figures (`fig2`, `fig3`),
//! write the page, and check it: (a) always, its structure - a section per experiment, run or
//! not, and every embedded figure backed by a non-empty SVG file that draws something; (b) when
//! Chromium is installed, a headless screenshot of the page that must not be blank and must show
//! coloured plot lines. With `CI=true` a missing Chromium is a failure, not a skip (`.ci/run`
//! installs it through `scripts/check-report.sh install`).
//!
//! `REPORT_CHECK_OUT=DIR` checks a directory `scripts/check-report.sh` has already filled
//! (`index.html`, and `report.png` if it took the screenshot) instead of making a new one.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

use std::path::{Path, PathBuf};

mod support;
use support::{Scratch, browser, chromium, chromium_or_skip, stderr, stdout, xtask};

/// The cheap experiments whose results the page is built from.
const RUN: [&str; 2] = ["fig2", "fig3"];

/// Does the SVG draw anything (the same rule as the report's)?
fn draws(svg: &str) -> bool {
    svg.contains("<svg")
        && ["<path", "<polyline", "<polygon", "<line"]
            .iter()
            .any(|t| svg.contains(t))
}

/// Every `<figure data-file="...">...</figure>` of the page: the file and the figure's HTML.
fn figures(page: &str) -> Vec<(String, String)> {
    let mut found = Vec::new();
    let mut rest = page;
    while let Some(i) = rest.find("<figure data-file=\"") {
        rest = &rest[i + "<figure data-file=\"".len()..];
        let q = rest.find('"').unwrap();
        let file = rest[..q].to_owned();
        let end = rest.find("</figure>").unwrap();
        found.push((file, rest[q..end].to_owned()));
        rest = &rest[end..];
    }
    found
}

/// The structural checks of the page in `out`.
fn check_page(out: &Path, run: &[&str]) {
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(page.starts_with("<!DOCTYPE html>"));
    assert!(
        !page.contains("<link") && !page.contains("<script") && !page.contains("src=\"http"),
        "the page must be self-contained"
    );

    // A section for every registered experiment: a run one for each we ran.
    let list = xtask(&["list"]);
    assert!(list.status.success(), "{}", stderr(&list));
    for id in stdout(&list).lines() {
        assert!(
            page.contains(&format!("<section id=\"exp-{id}\" class=\"experiment")),
            "no section for {id}"
        );
    }
    for id in run {
        assert!(
            page.contains(&format!(
                "<section id=\"exp-{id}\" class=\"experiment run\">"
            )),
            "{id} is not shown as run"
        );
        let start = page.find(&format!("<section id=\"exp-{id}\"")).unwrap();
        let section = &page[start..start + page[start..].find("</section>").unwrap()];
        assert!(
            section.contains("Produced with seed <b>2025</b>,"),
            "provenance of {id} missing"
        );
    }

    // Every figure on the page comes from a non-empty SVG file that draws something, and
    // every SVG file of a run experiment is on the page.
    let figs = figures(&page);
    let mut svg_files = Vec::new();
    for id in run {
        for e in std::fs::read_dir(out.join(id)).unwrap() {
            let name = e.unwrap().file_name().to_string_lossy().into_owned();
            if name.ends_with(".svg") {
                svg_files.push(format!("{id}/{name}"));
            }
        }
    }
    svg_files.sort();
    let mut on_page: Vec<String> = figs.iter().map(|(f, _)| f.clone()).collect();
    on_page.sort();
    assert_eq!(on_page, svg_files, "figures on the page vs SVG files");
    assert!(!figs.is_empty(), "fig2 and fig3 write SVG figures");
    for (file, html) in &figs {
        let svg = std::fs::read_to_string(out.join(file)).unwrap();
        assert!(draws(&svg), "{file} draws nothing");
        assert!(
            html.contains("<svg") && draws(html) || html.contains("<img src=\"data:image/svg+xml"),
            "{file}: the figure on the page is empty"
        );
    }
    assert_eq!(
        page.matches("<svg").count() + page.matches("<img").count(),
        figs.len(),
        "every <svg> or <img> of the page is one of the figures"
    );
}

/// Takes a 1280x4000 headless screenshot of `out/index.html` into `out/report.png`.
fn screenshot(chrome: &Path, out: &Path) -> PathBuf {
    let png = out.join("report.png");
    let url = format!("file://{}", out.join("index.html").display());
    browser::screenshot(
        chrome,
        &out.join(".chromium-profile"),
        &url,
        &png,
        (1280, 4000),
    );
    png
}

/// The screenshot is a real page: many colours, a fair share of ink, and coloured plot lines.
fn check_png(png: &Path) {
    let pixels = browser::Pixels::read(png);
    assert!(
        pixels.width >= 1000 && pixels.height >= 1000,
        "{}x{}",
        pixels.width,
        pixels.height
    );
    let total = pixels.rgb.len();
    assert!(
        pixels.ink() * 100 >= total,
        "blank screenshot: {} of {total} pixels are not near white",
        pixels.ink()
    );
    pixels.assert_not_blank("report.png", 32, 500);
}

#[test]
fn report_page_shows_every_experiment_and_its_figures() {
    if let Some(dir) = std::env::var_os("REPORT_CHECK_OUT") {
        // Filled by scripts/check-report.sh: check what it made.
        let out = PathBuf::from(dir);
        check_page(&out, &RUN);
        let png = out.join("report.png");
        if png.exists() {
            check_png(&png);
        }
        return;
    }
    let mut scratch = Scratch::new("report-page");
    let out = scratch.0.clone();
    let o = out.to_str().unwrap();
    let mut args = vec!["run"];
    args.extend(RUN);
    args.extend(["--threads", "1", "--out", o]);
    let ran = xtask(&args);
    assert!(ran.status.success(), "{}", stderr(&ran));
    let rep = xtask(&["report", "--out", o]);
    assert!(rep.status.success(), "{}", stderr(&rep));
    assert!(stderr(&rep).contains("index.html"));
    check_page(&out, &RUN);

    match chromium() {
        Some(chrome) => {
            scratch.keep(true); // Kept while checking, for a failure to be looked at.
            let png = screenshot(&chrome, &out);
            check_png(&png);
            scratch.keep(false);
        }
        None if std::env::var("CI").is_ok_and(|v| v == "true") => panic!(
            "CI=true but Chromium is not installed (/usr/bin/chromium or $CHROMIUM): run `scripts/check-report.sh install`"
        ),
        None => eprintln!(
            "report: Chromium not found (/usr/bin/chromium or $CHROMIUM): screenshot check skipped; `scripts/check-report.sh install` installs it"
        ),
    }
}

#[test]
fn report_without_results_is_refused_and_writes_nothing() {
    let scratch = Scratch::new("report-empty");
    let o = scratch.0.to_str().unwrap();
    let rep = xtask(&["report", "--out", o]);
    assert_eq!(rep.status.code(), Some(2), "{}", stderr(&rep));
    let err = stderr(&rep);
    assert!(err.contains("no results") && err.contains(o), "{err}");
    assert!(!scratch.0.join("index.html").exists());
    let rep = xtask(&["report", "--out", &format!("{o}/missing")]);
    assert_eq!(rep.status.code(), Some(2));
    assert!(stderr(&rep).contains("no such directory"));
}

#[test]
fn usage_lists_report() {
    let o = xtask(&[]);
    assert!(o.status.success());
    assert!(stdout(&o).contains("cargo xtask report [--out DIR]"));
}

/// The fifteen meshes, as the per-mesh tables head their columns.
const MESHES: [&str; 15] = [
    "b2-c1", "c2-d1", "d2-e2", "e5-k1", "k2-e6", "e1-b3", "b2-l1", "l2-m1", "m3-e3", "e4-f1",
    "f2-g1", "m2-n1", "n2-o1", "g2-h1", "h2-i1",
];

/// Writes `<out>/<id>/tables.json` (one table) and a `run.json` with `overrides`.
fn write_table(
    out: &Path,
    id: &str,
    title: &str,
    columns: &[String],
    rows: &[Vec<String>],
    notes: &[&str],
    overrides: &[(&str, &str)],
) {
    let dir = out.join(id);
    std::fs::create_dir_all(&dir).unwrap();
    let tables = serde_json::json!({
        "tables": [{"title": title, "columns": columns, "rows": rows, "notes": notes}],
        "files": ["run.json"],
    });
    std::fs::write(dir.join("tables.json"), tables.to_string()).unwrap();
    let overrides: serde_json::Map<String, serde_json::Value> = overrides
        .iter()
        .map(|(k, v)| ((*k).to_owned(), serde_json::Value::from(*v)))
        .collect();
    let run = serde_json::json!({
        "id": id, "seed": 2025, "threads": 2, "overrides": overrides, "config": null,
        "version": {"crate": "0.1.0", "git": "test"}, "date": "2026-01-01T00:00:00Z",
    });
    std::fs::write(dir.join("run.json"), run.to_string()).unwrap();
}

/// A per-mesh count table in the printed form: `lead` label columns, cells
/// `ours[*]/ours[*] (paper/paper)`; cell (row, mesh) differs in its jams where `differs` says.
fn count_rows(labels: &[Vec<&str>], differs: &[(usize, usize)]) -> Vec<Vec<String>> {
    labels
        .iter()
        .enumerate()
        .map(|(r, lead)| {
            let mut row: Vec<String> = lead.iter().map(|s| (*s).to_owned()).collect();
            for m in 0..MESHES.len() {
                row.push(if differs.contains(&(r, m)) {
                    "141*/0 (168/0)".to_owned()
                } else if (r, m) == (0, 1) {
                    // Ours keeps the 1 % rule, the paper's does not: the verdicts differ.
                    "2/0✓ (3/0)".to_owned()
                } else if (r, m) == (0, 2) {
                    // Both keep it.
                    "0/0✓ (1/0✓)".to_owned()
                } else {
                    format!("{}/0 ({}/0)", 100 + m, 99 + m)
                });
            }
            row
        })
        .collect()
}

/// The script appended to a copy of the page: one line per heatmap (table, kind, cells,
/// differing cells, differing cells with a link, whether the two verdicts' colours differ),
/// the links of differing cells, and whether anything is wider than the window.
const HEATMAP_SCRIPT: &str = r#"
(function () {
  const out = [];
  document.querySelectorAll('table.heatmap').forEach(function (t) {
    const cells = t.querySelectorAll('td.hm');
    const differs = t.querySelectorAll('td.hm.differs');
    const linked = t.querySelectorAll('td.hm.differs a[href]');
    const one = t.querySelector('td.hm.consistent'), two = t.querySelector('td.hm.differs');
    const apart = one && two && getComputedStyle(one).backgroundColor !== getComputedStyle(two).backgroundColor;
    const marked = Array.from(cells).filter(c => c.textContent.includes('\u2713')).length;
    const outlined = Array.from(t.querySelectorAll('td.hm.rule-differs')).filter(c => getComputedStyle(c).outlineStyle === 'dashed').length;
    out.push(['heatmap', t.dataset.table, t.dataset.kind, cells.length, differs.length, linked.length, !!apart, marked, outlined].join('\t'));
    linked.forEach(function (a) {
      const h = a.getAttribute('href');
      const inPage = h.startsWith('#') ? !!document.getElementById(decodeURIComponent(h.slice(1))) : 'file';
      out.push(['link', t.dataset.table, h, inPage].join('\t'));
    });
  });
  const key = document.querySelector('p.heat-key');
  const swatch = key.querySelector('span.hm.consistent'), green = document.querySelector('table.heatmap td.hm.consistent');
  out.push(['key', getComputedStyle(swatch).backgroundColor === getComputedStyle(green).backgroundColor, key.textContent.includes('however many trials failed')].join('\t'));
  out.push(['order'].concat(Array.from(document.querySelectorAll('section.experiment')).map(e => e.id + (e.classList.contains('run') ? ':run' : ''))).join('\t'));
  const widest = Math.max(...Array.from(document.querySelectorAll('main, nav, section, .table-wrap')).map(e => e.getBoundingClientRect().right));
  out.push(['width', document.documentElement.scrollWidth, window.innerWidth, Math.round(widest)].join('\t'));
  document.getElementById('heat-result').textContent = out.join('\n');
  document.getElementById('heat-status').textContent = 'done';
})();
"#;

#[test]
fn per_mesh_tables_show_as_heatmaps_linking_differing_cells_to_their_replays() {
    let mut scratch = Scratch::new("report-heatmaps");
    let out = scratch.0.clone();
    let mut columns = vec!["case".to_owned()];
    columns.extend(MESHES.iter().map(|m| (*m).to_owned()));
    let title3 = "Table 3: trials (of 200) with at least one jam / disengagement, G = 40 %: ours (paper); * where a two-sample test separates our count from the paper's [events: idle-rotation(pitches=1)]";
    let cases: Vec<Vec<&str>> = ["A", "B", "C", "D"].iter().map(|c| vec![*c]).collect();
    write_table(
        &out,
        "table3",
        title3,
        &columns,
        &count_rows(&cases, &[(1, 8), (3, 0)]),
        &[
            "The paper's counts consistent with ours by Fisher's exact two-sample test: jams 58 of 60. `*` after one of our counts: the test separates it from the paper's.",
        ],
        &[],
    );
    // B/m3-e3 has been replayed, trial 7 of it under the table's settings, so its cell links
    // to that trial's page; D/b2-c1 has not, so its cell links to the command that lists it.
    let trial = out.join("replay-table3-B-m3-e3-7");
    std::fs::create_dir_all(&trial).unwrap();
    std::fs::write(trial.join("pair.html"), "<html></html>\n").unwrap();
    std::fs::write(
        trial.join("tables.json"),
        serde_json::json!({"tables": [{"title": "table3 B/m3-e3, trial 7 (seed 2025): jammed [events: idle-rotation(pitches=1); drive: listed, m3 drove]", "columns": [], "rows": []}]}).to_string(),
    )
    .unwrap();
    std::fs::write(
        trial.join("run.json"),
        serde_json::json!({"id": "table3", "seed": 2025, "overrides": {}}).to_string(),
    )
    .unwrap();
    let listing = out.join("replay-table3-B-m3-e3-failed");
    std::fs::create_dir_all(&listing).unwrap();
    std::fs::write(listing.join("table.md"), "listing\n").unwrap();
    std::fs::write(
        listing.join("tables.json"),
        serde_json::json!({"tables": []}).to_string(),
    )
    .unwrap();
    // Table I on other inputs than the paper's: no marks, no heatmap, agreement for reference.
    let mut columns_i = vec!["case".to_owned(), "G [%]".to_owned()];
    columns_i.extend(MESHES.iter().map(|m| (*m).to_owned()));
    let lead_i: Vec<Vec<&str>> = vec![vec!["A", "10"], vec!["", "40"], vec!["B", "10"]];
    write_table(
        &out,
        "tableI",
        "Table I: trials (of 200) with at least one jam / disengagement, Cases A-D at several clearances: ours (paper); * where a two-sample test separates our count from the paper's [events: idle-rotation(pitches=1)] [inputs differ from the defaults: trials=20]",
        &columns_i,
        &count_rows(&lead_i, &[(0, 3), (2, 4)]),
        &[
            "The paper's counts consistent with ours by Fisher's exact two-sample test: jams 28 of 30.",
            "This run's inputs differ from the paper's (trials=20): the paper's numbers shown beside ours come from its own inputs, for reference, not as a check of these.",
        ],
        &[("trials", "20")],
    );
    let rep = xtask(&["report", "-q", "--out", out.to_str().unwrap()]);
    assert!(rep.status.success(), "{}", stderr(&rep));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();

    let section = |id: &str| {
        let start = page.find(&format!("<section id=\"exp-{id}\"")).unwrap();
        page[start..start + page[start..].find("</section>").unwrap()].to_owned()
    };
    let t3 = section("table3");
    assert_eq!(
        t3.matches("<table class=\"heatmap\"").count(),
        2,
        "jams and disengagements"
    );
    assert!(
        t3.contains("<a href=\"replay-table3-B-m3-e3-7/pair.html\">141 | 168</a>"),
        "{t3}"
    );
    assert!(t3.contains(&format!("<li id=\"replay-table3-D-b2-c1-failed\"><b>D/b2-c1</b>: <code>cargo xtask replay table3 D/b2-c1 --seed 2025 --out {}</code>", out.display())), "{t3}");
    let t_i = section("tableI");
    assert!(
        !t_i.contains("class=\"heatmap\""),
        "no heatmap on other inputs"
    );
    assert!(t_i.contains("No heatmap of Table I"));
    assert!(
        !t_i.contains("141*") && !t_i.contains("; * where"),
        "no marks on other inputs"
    );
    assert!(t_i.contains("For reference only, not a check"));
    // The paper items (the contents' column, each section's) come from the registry, as in
    // `cargo xtask`'s overview: none names a tracker's issue.
    let overview = xtask(&[]);
    for (what, text) in [
        ("the report", page.as_str()),
        ("cargo xtask", &stdout(&overview)),
    ] {
        let lower = text.to_ascii_lowercase();
        for (i, _) in lower.match_indices("issue ") {
            let next = lower[i + "issue ".len()..].chars().next();
            assert!(
                !next.is_some_and(|c| c.is_ascii_digit()),
                "{what} names an issue: {}",
                &text[i..(i + 20).min(text.len())]
            );
        }
    }

    let Some(chrome) = chromium() else {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI=true but Chromium is not installed: run `scripts/check-report.sh install`"
        );
        eprintln!("report: Chromium not found: the heatmaps' browser check is skipped");
        return;
    };
    scratch.keep(true);
    let checked = page.replace(
        "</body>",
        &format!(
            "<pre id=\"heat-result\"></pre><p id=\"heat-status\">not run</p><script>{HEATMAP_SCRIPT}</script></body>"
        ),
    );
    std::fs::write(out.join("check.html"), checked).unwrap();
    let dom = browser::headless(
        &chrome,
        &out.join(".chromium-heat"),
        &[
            "--window-size=1280,4000".to_owned(),
            "--dump-dom".to_owned(),
        ],
        &format!("file://{}", out.join("check.html").display()),
    );
    assert!(
        dom.contains("<p id=\"heat-status\">done</p>"),
        "script did not finish"
    );
    let start = dom.find("<pre id=\"heat-result\">").unwrap() + "<pre id=\"heat-result\">".len();
    let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let lines: Vec<Vec<&str>> = result.lines().map(|l| l.split('\t').collect()).collect();
    let maps: Vec<&Vec<&str>> = lines.iter().filter(|l| l[0] == "heatmap").collect();
    assert_eq!(maps.len(), 2, "{result}");
    for m in &maps {
        assert_eq!(m[1], "table3", "{result}");
        assert_eq!(m[3], "60", "4 cases x 15 meshes: {result}");
        let want = if m[2] == "jams" { "2" } else { "0" };
        assert_eq!(m[4], want, "differing cells: {result}");
        assert_eq!(m[5], want, "each differing cell links its replay: {result}");
        if m[2] == "jams" {
            assert_eq!(
                m[6], "true",
                "differing and consistent cells look alike: {result}"
            );
            // The 1 % rule: the two cells that keep it on some side show its mark, and the one
            // whose two sides' verdicts differ is outlined, dashed, where a reader sees it.
            assert_eq!(m[7], "2", "cells marked as keeping the 1 % rule: {result}");
            assert_eq!(
                m[8], "1",
                "cells outlined as the rule's verdicts differing: {result}"
            );
        }
    }
    for l in lines.iter().filter(|l| l[0] == "link") {
        match l[3] {
            "file" => assert!(out.join(l[2]).is_file(), "{} links nothing", l[2]),
            inpage => assert_eq!(inpage, "true", "{} has no target on the page", l[2]),
        }
    }
    // The key names the consistent cells' colour and says what it means: agreement, not a
    // mesh that works.
    let key = lines.iter().find(|l| l[0] == "key").unwrap();
    assert_eq!(key[1..], ["true", "true"], "{result}");
    // The report's order as a reader meets it: the paper's items in the paper's order (Table 3
    // before Table I, its appendix), the results before the experiments not run.
    let order = lines.iter().find(|l| l[0] == "order").unwrap();
    let at = |id: &str| {
        order
            .iter()
            .position(|s| s.starts_with(&format!("exp-{id}")))
    };
    assert!(at("table3").unwrap() < at("tableI").unwrap(), "{result}");
    assert!(
        order.len() > 20,
        "every experiment has its section: {result}"
    );
    let first_not_run = order[1..].iter().position(|s| !s.ends_with(":run"));
    let last_run = order[1..].iter().rposition(|s| s.ends_with(":run"));
    if let (Some(n), Some(r)) = (first_not_run, last_run) {
        assert!(r < n, "an experiment not run before a result: {result}");
    }
    let width = lines.iter().find(|l| l[0] == "width").unwrap();
    let (scroll, window, widest): (f64, f64, f64) = (
        width[1].parse().unwrap(),
        width[2].parse().unwrap(),
        width[3].parse().unwrap(),
    );
    assert!(
        scroll <= window && widest <= window,
        "the page is wider than its window: {result}"
    );
    scratch.keep(false);
}

/// The script appended to a copy of the page: one line per linked heatmap cell (table, kind,
/// row, mesh, link), and where each in-page link's target is.
const LINKS_SCRIPT: &str = r#"
(function () {
  const out = [];
  document.querySelectorAll('table.heatmap').forEach(function (t) {
    const meshes = Array.from(t.querySelectorAll('thead th')).map(th => th.textContent);
    t.querySelectorAll('tbody tr').forEach(function (tr) {
      const row = tr.querySelector('th').textContent;
      tr.querySelectorAll('td').forEach(function (td, i) {
        const a = td.querySelector('a[href]');
        if (!a) return;
        const h = a.getAttribute('href');
        const target = h.startsWith('#') ? !!document.getElementById(decodeURIComponent(h.slice(1))) : 'file';
        out.push(['cell', t.dataset.table, t.dataset.kind, row, meshes[i + 1], h, target].join('\t'));
      });
    });
  });
  document.querySelectorAll('ul.replay-commands code').forEach(c => out.push(['command', c.textContent].join('\t')));
  // A table cut off at the right: wider than its box, the rest hidden.
  document.querySelectorAll('.table-wrap').forEach(w => {
    if (w.scrollWidth > w.clientWidth + 1) out.push(['cut', w.previousElementSibling.textContent.slice(0, 80) + ': ' + w.scrollWidth + ' > ' + w.clientWidth].join('\t'));
  });
  document.getElementById('link-result').textContent = out.join('\n');
  document.getElementById('link-status').textContent = 'done';
})();
"#;

/// The heatmap cells with links, as [`LINKS_SCRIPT`] reads them in the browser: (table, kind,
/// row, mesh, href), and the commands listed.
fn linked_cells(chrome: &Path, out: &Path, page: &str) -> (Vec<[String; 5]>, Vec<String>) {
    let checked = page.replace(
        "</body>",
        &format!(
            "<pre id=\"link-result\"></pre><p id=\"link-status\">not run</p><script>{LINKS_SCRIPT}</script></body>"
        ),
    );
    std::fs::write(out.join("links.html"), checked).unwrap();
    let url = format!("file://{}", out.join("links.html").display());
    let dom = browser::headless(
        chrome,
        &out.join(".chromium-links"),
        &[
            "--window-size=1280,4000".to_owned(),
            "--dump-dom".to_owned(),
        ],
        &url,
    );
    assert!(
        dom.contains("<p id=\"link-status\">done</p>"),
        "script did not finish"
    );
    let start = dom.find("<pre id=\"link-result\">").unwrap() + "<pre id=\"link-result\">".len();
    let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let result = result
        .replace("&amp;", "&")
        .replace("&lt;", "<")
        .replace("&gt;", ">");
    let mut cells = Vec::new();
    let mut commands = Vec::new();
    for l in result.lines() {
        let f: Vec<&str> = l.split('\t').collect();
        match f[0] {
            "cut" => panic!("a table cut off at the right of a 1280 px window: {}", f[1]),
            "cell" => {
                assert_ne!(f[6], "false", "{l}: the link has no target on the page");
                cells.push([f[1], f[2], f[3], f[4], f[5]].map(str::to_owned));
            }
            _ => commands.push(f[1].to_owned()),
        }
    }
    let png = out.join("links.png");
    browser::screenshot(
        chrome,
        &out.join(".chromium-links-shot"),
        &url,
        &png,
        (1280, 4000),
    );
    browser::Pixels::read(&png).assert_not_blank("links.png", 32, 500);
    (cells, commands)
}

/// What a replayed trial did, from its table's title: (jammed, disengaged).
fn trial_did(out: &Path, href: &str) -> (bool, bool) {
    let folder = href.trim_end_matches("/pair.html");
    let tables: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(out.join(folder).join("tables.json")).unwrap(),
    )
    .unwrap();
    let title = tables["tables"][0]["title"].as_str().unwrap();
    let said = title
        .split("): ")
        .nth(1)
        .unwrap()
        .split(" [")
        .next()
        .unwrap();
    (
        said.starts_with("jammed"),
        said.ends_with("disengaged") && !said.starts_with("neither"),
    )
}

/// Table 3 at its defaults, three of its trials replayed (D/m3-e3 trial 0 an idle start that
/// only disengages, D/d2-e2 trial 4 that only jams, B/m3-e3 trial 1 that jams) and a Table I
/// whose B/40/m3-e3 is Table 3's B/m3-e3: every heatmap cell with a link to a trial links one
/// that had the heatmap's failure; a cell whose trial with that failure is there links to it,
/// a consistent cell too and across tables; the commands the page prints carry its `--out`;
/// no table, Wilson intervals and Table I's heatmaps among them, is cut off at the right of a
/// 1280 px window.
#[test]
fn heatmap_cells_link_replayed_trials_that_had_their_failure() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let mut scratch = Scratch::new("report-links");
    let out = scratch.0.clone();
    let o = out.to_str().unwrap();
    let ran = xtask(&["run", "table3", "-q", "--threads", "2", "--out", o]);
    assert!(ran.status.success(), "{}", stderr(&ran));
    for args in [
        &["D/m3-e3", "0"][..],
        &["D/d2-e2", "4"],
        &["B/m3-e3", "1"],
        &["D/d2-e2"],
    ] {
        let mut a = vec!["replay", "table3", "-q", "--out", o];
        a.extend(args);
        let r = xtask(&a);
        assert!(r.status.success(), "{a:?}: {}", stderr(&r));
    }
    // Table I's B/40 row, as a run at the defaults prints it, on the trials of Table 3's B row.
    let mut columns = vec!["case".to_owned(), "G [%]".to_owned()];
    columns.extend(MESHES.iter().map(|m| (*m).to_owned()));
    let mut row = vec!["B".to_owned(), "40".to_owned()];
    // Cells as wide as Table I's widest, so that the page must fit them.
    row.extend(MESHES.iter().map(|m| {
        if *m == "m3-e3" {
            "141*/0 (168/0)"
        } else {
            "200*/161* (151/49)"
        }
        .to_owned()
    }));
    write_table(
        &out,
        "tableI",
        "Table I: trials (of 200) with at least one jam / disengagement, Cases A-D at several clearances: ours (paper); * where a two-sample test separates our count from the paper's [events: idle-rotation(pitches=1)]",
        &columns,
        &[row],
        &[],
        &[],
    );
    let rep = xtask(&["report", "-q", "--out", o]);
    assert!(rep.status.success(), "{}", stderr(&rep));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    scratch.keep(true);
    let (cells, commands) = linked_cells(&chrome, &out, &page);
    let link = |table: &str, kind: &str, row: &str, mesh: &str| {
        cells
            .iter()
            .find(|c| c[0] == table && c[1] == kind && c[2] == row && c[3] == mesh)
            .map(|c| c[4].clone())
    };
    for [table, kind, row, mesh, href] in &cells {
        if href.ends_with("/pair.html") {
            let (jammed, disengaged) = trial_did(&out, href);
            let had = if kind == "jams" { jammed } else { disengaged };
            assert!(
                had,
                "{table} {kind} {row} {mesh} links {href}, a trial without that failure"
            );
        }
    }
    assert_eq!(
        link("table3", "disengagements", "Case D", "m3-e3").as_deref(),
        Some("replay-table3-D-m3-e3-0/pair.html"),
        "a consistent cell whose failed trial is replayed links it: {cells:?}"
    );
    assert_eq!(
        link("table3", "jams", "Case D", "d2-e2").as_deref(),
        Some("replay-table3-D-d2-e2-4/pair.html")
    );
    for (kind, row, mesh) in [
        ("jams", "Case D", "m3-e3"),
        ("disengagements", "Case D", "d2-e2"),
    ] {
        let href = link("table3", kind, row, mesh).unwrap();
        assert!(
            href.starts_with('#'),
            "{kind} {row} {mesh}: {href}, no replayed trial of its failure"
        );
    }
    assert_eq!(
        link("tableI", "jams", "Case B, G = 40 %", "m3-e3").as_deref(),
        Some("replay-table3-B-m3-e3-1/pair.html"),
        "Table I's B/40/m3-e3 is Table 3's B/m3-e3: {cells:?}"
    );
    // The commands carry the page's --out, and a disengagement's trial from the listing.
    assert!(!commands.is_empty());
    for c in &commands {
        assert!(c.ends_with(&format!("--out {o}")), "{c}");
    }
    assert!(
        commands.contains(&format!(
            "cargo xtask replay table3 D/d2-e2 0 --seed 2025 --out {o}"
        )),
        "{commands:?}"
    );
    scratch.keep(false);
}

/// The first screen's window, as a reader on a laptop or desktop sees it.
const FIRST_SCREEN: (u32, u32) = (1400, 1000);

/// The script appended to a copy of the page: the box (left, top, right, bottom, in CSS pixels
/// of the page) of the ledger's verdict column - its heading and every verdict - and of the
/// train's picture.
const FIRST_SCREEN_SCRIPT: &str = r#"
(function () {
  const box = e => { const r = e.getBoundingClientRect(); return [r.left, r.top, r.right, r.bottom].map(Math.round).join('\t'); };
  const out = [];
  const heads = Array.from(document.querySelectorAll('.verdict-table thead th')).filter(e => e.textContent === 'verdict');
  heads.forEach(e => out.push('verdict-head\t' + box(e)));
  document.querySelectorAll('.verdict-table td.verdict-cell').forEach(e => out.push('verdict\t' + box(e)));
  document.querySelectorAll('figure.train svg').forEach(e => out.push('train\t' + box(e)));
  document.getElementById('first-result').textContent = out.join('\n');
  document.getElementById('first-status').textContent = 'done';
})();
"#;

/// The boxes the script measured, by kind: (left, top, right, bottom).
fn first_screen_boxes(result: &str, kind: &str) -> Vec<[f64; 4]> {
    result
        .lines()
        .map(|l| l.split('\t').collect::<Vec<_>>())
        .filter(|l| l[0] == kind)
        .map(|l| [1, 2, 3, 4].map(|i| l[i].parse::<f64>().unwrap()))
        .collect()
}

#[test]
fn first_screen_holds_the_verdict_column_and_the_train() {
    let mut scratch = Scratch::new("report-first-screen");
    let out = scratch.0.clone();
    let o = out.to_str().unwrap();
    // The ledger at a few trials a cell: its layout is what is checked, not its numbers.
    let ran = xtask(&[
        "run",
        "claims",
        "--set",
        "trials=2",
        "--threads",
        "2",
        "-q",
        "--out",
        o,
    ]);
    assert!(ran.status.success(), "{}", stderr(&ran));
    let rep = xtask(&["report", "-q", "--out", o]);
    assert!(rep.status.success(), "{}", stderr(&rep));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    let verdict = page
        .find("<section id=\"verdict\"")
        .expect("no verdict block");
    assert!(
        verdict < page.find("<nav>").unwrap(),
        "the verdict comes before the contents"
    );
    let Some(chrome) = chromium() else {
        assert!(
            std::env::var("CI").map_or(true, |v| v != "true"),
            "CI=true but Chromium is not installed: run `scripts/check-report.sh install`"
        );
        eprintln!("report: Chromium not found: the first screen's browser check is skipped");
        return;
    };
    scratch.keep(true);
    let (width, height) = FIRST_SCREEN;
    let checked = page.replace(
        "</body>",
        &format!(
            "<pre id=\"first-result\"></pre><p id=\"first-status\">not run</p><script>{FIRST_SCREEN_SCRIPT}</script></body>"
        ),
    );
    std::fs::write(out.join("check.html"), checked).unwrap();
    let dom = browser::headless(
        &chrome,
        &out.join(".chromium-first"),
        &[
            format!("--window-size={width},{height}"),
            "--dump-dom".to_owned(),
        ],
        &format!("file://{}", out.join("check.html").display()),
    );
    assert!(
        dom.contains("<p id=\"first-status\">done</p>"),
        "script did not finish"
    );
    let start = dom.find("<pre id=\"first-result\">").unwrap() + "<pre id=\"first-result\">".len();
    let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let heads = first_screen_boxes(result, "verdict-head");
    let verdicts = first_screen_boxes(result, "verdict");
    let train = first_screen_boxes(result, "train");
    assert_eq!(heads.len(), 1, "the ledger's verdict column: {result}");
    assert!(!verdicts.is_empty(), "no verdicts: {result}");
    assert_eq!(train.len(), 1, "the train's picture: {result}");
    let (w, h) = (f64::from(width), f64::from(height));
    for (what, b) in heads
        .iter()
        .chain(&verdicts)
        .map(|b| ("verdict column", b))
        .chain(train.iter().map(|b| ("train", b)))
    {
        assert!(
            b[0] >= 0.0 && b[1] >= 0.0 && b[2] <= w && b[3] <= h,
            "the {what} ({b:?}) is not on the first {width}x{height} screen: {result}"
        );
        assert!(b[2] > b[0] && b[3] > b[1], "the {what} is empty: {result}");
    }
    // The picture of that screen, kept for a reader to look at.
    let png = Path::new(env!("CARGO_TARGET_TMPDIR")).join("report-first-screen.png");
    let url = format!("file://{}", out.join("index.html").display());
    browser::screenshot(
        &chrome,
        &out.join(".chromium-shot"),
        &url,
        &png,
        FIRST_SCREEN,
    );
    let pixels = browser::Pixels::read(&png);
    assert_eq!((pixels.width, pixels.height), FIRST_SCREEN);
    pixels.assert_not_blank("report-first-screen.png", 32, 500);
    scratch.keep(false);
}
