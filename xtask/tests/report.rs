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
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

mod support;
use support::{Scratch, chromium, stderr, stdout, xtask};

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
    let log = std::fs::File::create(out.join("chromium.log")).unwrap();
    let mut child = Command::new(chrome)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--hide-scrollbars",
            "--window-size=1280,4000",
        ])
        .arg(format!(
            "--user-data-dir={}",
            out.join(".chromium-profile").display()
        ))
        .arg(format!("--screenshot={}", png.display()))
        .arg(format!("file://{}", out.join("index.html").display()))
        .stdout(Stdio::null())
        .stderr(log)
        .spawn()
        .unwrap();
    let start = Instant::now();
    loop {
        if let Some(status) = child.try_wait().unwrap() {
            assert!(
                status.success(),
                "chromium failed ({status}); see {}",
                out.join("chromium.log").display()
            );
            break;
        }
        if start.elapsed() > Duration::from_secs(90) {
            let _ = child.kill();
            let _ = child.wait();
            panic!("chromium took more than 90 s");
        }
        std::thread::sleep(Duration::from_millis(100));
    }
    png
}

/// The screenshot is a real page: many colours, a fair share of ink, and coloured plot lines.
fn check_png(png: &Path) {
    let bytes = std::fs::read(png).unwrap();
    assert!(!bytes.is_empty(), "{} is empty", png.display());
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::normalize_to_color8());
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    let channels = match info.color_type {
        png::ColorType::Rgb => 3,
        png::ColorType::Rgba => 4,
        other => panic!("unexpected colour type {other:?}"),
    };
    assert!(info.width >= 1000 && info.height >= 1000, "{info:?}");
    let mut colours = std::collections::HashSet::new();
    let (mut ink, mut chromatic, mut total) = (0u64, 0u64, 0u64);
    for row in buf.chunks(info.line_size).take(info.height as usize) {
        for px in row[..info.width as usize * channels].chunks(channels) {
            let (r, g, b) = (px[0], px[1], px[2]);
            colours.insert((r, g, b));
            total += 1;
            if u16::from(r) + u16::from(g) + u16::from(b) < 600 {
                ink += 1;
            }
            if r.max(g).max(b) - r.min(g).min(b) > 120 {
                chromatic += 1;
            }
        }
    }
    assert!(
        colours.len() >= 32,
        "blank screenshot: {} colours",
        colours.len()
    );
    assert!(
        ink * 100 >= total,
        "blank screenshot: {ink} of {total} pixels are not near white"
    );
    assert!(
        chromatic >= 500,
        "no plot lines in the screenshot: {chromatic} strongly coloured pixels"
    );
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
