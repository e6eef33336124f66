//! Every figure the experiments draw, in a real browser: cheap runs of every experiment that
//! writes an SVG, each SVG put on one page that headless Chromium lays out, and a script on that
//! page measuring what a reader sees. Every chart must give each series a style of its own (the
//! colour and dash of its line and the shape and colour of its marker, as rendered), name each
//! series in its legend in that same style, keep the legend box off the plot area and off
//! every series, and keep every text on the canvas; every other picture must draw something. The page is also screenshot, which
//! must not be blank. Skipped when Chromium is missing, unless `CI=true` (`.ci/run` installs it).
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use std::path::Path;

use support::{Scratch, browser, chromium_or_skip, stderr, xtask};

/// The experiments that write figures, with settings that make them quick (a few seconds in
/// all); `contact-tolerance` runs on its own, as its `samples` means something else in `figIV`.
const RUNS: [&[&str]; 2] = [
    &[
        "fig2",
        "fig3",
        "fig4",
        "fig5",
        "figIV",
        "clearance",
        "pair",
        "failure",
        "fig6",
        "table2",
        "lunar-anomaly",
        "clearance-design",
        "sensitivity",
        "fig-events",
        "--set",
        "trials=2",
        "--set",
        "cases=B,D",
        "--set",
        "case=D",
        "--set",
        "random_from=0.05",
        "--set",
        "random_to=0.06",
        "--set",
        "random_step=0.01",
        "--set",
        "lunar_turns=0.05",
        "--set",
        "curve_samples=100",
        "--set",
        "grid=30,40",
        "--set",
        "coarse_trials=1",
        "--set",
        "refine_trials=1",
        "--set",
        "runs=1",
    ],
    &["contact-tolerance", "--set", "samples=8"],
];

/// Figures that are pictures of gears, not charts of series: they carry no legend.
fn is_picture(name: &str) -> bool {
    name == "pair-check.svg" || name.starts_with("fig-V_") || name.starts_with("event-")
}

/// The script run on the page: one line per figure, tab-separated: file, `chart` or `picture`,
/// and for a chart the number of series, of distinct rendered styles, and `ok` or the problems.
const SCRIPT: &str = r#"
(function () {
  function box(el) { const r = el.getBoundingClientRect(); return {x: r.left, y: r.top, w: r.width, h: r.height}; }
  function meets(a, b) { return a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h; }
  function marker(el) {
    if (!el) return 'none';
    const cs = getComputedStyle(el);
    const t = el.tagName.toLowerCase();
    let shape = t;
    if (t === 'polygon') {
      const p = Array.from(el.points).map(q => [q.x, q.y]);
      const cx = p.reduce((s, q) => s + q[0], 0) / p.length, cy = p.reduce((s, q) => s + q[1], 0) / p.length;
      const r = Math.max(...p.map(q => Math.hypot(q[0] - cx, q[1] - cy)));
      shape += p.map(q => Math.round((q[0] - cx) / r * 4) + ',' + Math.round((q[1] - cy) / r * 4)).join(' ');
    }
    if (t === 'path') {
      const n = (el.getAttribute('d').match(/-?[0-9.]+/g) || []).map(Number);
      shape += n.length >= 4 && Math.abs(n[1] - n[3]) < 0.01 ? ':plus' : ':cross';
    }
    return shape + '|' + (t === 'path' ? cs.stroke : cs.fill);
  }
  function line(g) {
    const l = g.querySelector('polyline');
    if (!l) return 'no line';
    const cs = getComputedStyle(l);
    return cs.stroke + '|' + cs.strokeDasharray;
  }
  function look(g) { return line(g) + ' # ' + marker(g.querySelector('circle, polygon, path')); }
  const out = [];
  document.querySelectorAll('div.fig').forEach(function (div) {
    const svg = div.querySelector('svg');
    const file = div.dataset.file;
    const plot = svg.querySelector('rect.plot-area');
    if (!plot) {
      const b = box(svg);
      // An inset of exaggerated eccentricity: its factor, and the longest offset it draws (px).
      const inset = svg.querySelector('g.inset');
      let drawn = 0;
      if (inset) inset.querySelectorAll('line[stroke-width="2.5"]').forEach(function (l) {
        const r = box(l);
        drawn = Math.max(drawn, Math.hypot(r.w, r.h));
      });
      out.push(file + '\tpicture\t' + (svg.querySelectorAll('path, polyline, polygon, line').length > 0 && b.w > 0 && b.h > 0)
        + '\t' + (inset ? inset.dataset.exaggeration : 'none') + '\t' + Math.round(drawn));
      return;
    }
    const problems = [];
    const P = box(plot);
    const lb = svg.querySelector('rect.legend-box');
    if (!lb) problems.push('no legend box');
    const L = lb ? box(lb) : {x: 0, y: 0, w: 0, h: 0};
    const canvas = box(svg);
    if (meets(P, L)) problems.push('the legend box lies on the plot area');
    if (L.x < canvas.x - 0.5 || L.y + L.h > canvas.y + canvas.h + 0.5 || L.x + L.w > canvas.x + canvas.w + 0.5)
      problems.push('the legend box leaves the canvas');
    const keys = [];
    svg.querySelectorAll('g.series').forEach(function (g, k) {
      const key = look(g);
      keys.push(key);
      const S = box(g);
      if ((S.w > 0 || S.h > 0) && meets(S, L)) problems.push('series ' + k + ' runs under the legend');
      const entry = svg.querySelector('g.legend-entry[data-series="' + g.dataset.series + '"]');
      if (!entry) problems.push('series ' + k + ' is not in the legend');
      else {
        if (look(entry) !== key) problems.push('series ' + k + ' drawn as ' + key + ', its legend entry as ' + look(entry));
        const E = box(entry);
        if (E.x < L.x - 0.5 || E.y < L.y - 0.5 || E.x + E.w > L.x + L.w + 0.5 || E.y + E.h > L.y + L.h + 0.5)
          problems.push('legend entry ' + k + ' leaves its box');
      }
    });
    if (keys.length === 0) problems.push('no series');
    svg.querySelectorAll('text').forEach(function (t) {
      const T = box(t);
      if (T.w > 0 && (T.x < canvas.x - 1 || T.x + T.w > canvas.x + canvas.w + 1))
        problems.push('text runs off the canvas: ' + t.textContent.trim().slice(0, 40));
    });
    out.push(file + '\tchart\t' + keys.length + '\t' + new Set(keys).size + '\t' + (problems.join('; ') || 'ok'));
  });
  document.getElementById('result').textContent = out.join('\n');
  document.getElementById('status').textContent = 'done';
})();
"#;

/// The check page: every SVG of `files` (relative to `out`) inline, then the script.
fn check_page(out: &Path, files: &[String]) -> String {
    let mut page = String::from(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><style>body{margin:0;width:1100px} div.fig{margin:8px 0}</style></head><body>\n",
    );
    for f in files {
        let svg = std::fs::read_to_string(out.join(f)).unwrap();
        let start = svg.find("<svg").unwrap();
        page.push_str(&format!(
            "<div class=\"fig\" data-file=\"{f}\">{}</div>\n",
            &svg[start..]
        ));
    }
    page.push_str("<pre id=\"result\"></pre><p id=\"status\">not run</p>\n<script>");
    page.push_str(SCRIPT);
    page.push_str("</script>\n</body></html>\n");
    page
}

#[test]
fn every_chart_gives_each_series_its_own_style_and_keeps_its_legend_off_the_data() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let mut s = Scratch::new("figures");
    let out = s.0.join("out");
    for run in RUNS {
        let mut args = vec![
            "run",
            "-q",
            "--threads",
            "2",
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(run.iter().copied());
        let o = xtask(&args);
        assert!(o.status.success(), "{run:?}: {}", stderr(&o));
    }
    let mut files = Vec::new();
    for dir in std::fs::read_dir(&out).unwrap() {
        let dir = dir.unwrap().path();
        if !dir.is_dir() {
            continue;
        }
        for f in std::fs::read_dir(&dir).unwrap() {
            let name = f.unwrap().file_name().to_string_lossy().into_owned();
            if name.ends_with(".svg") {
                let id = dir.file_name().unwrap().to_string_lossy().into_owned();
                files.push(format!("{id}/{name}"));
            }
        }
    }
    files.sort();
    // Every experiment run wrote at least one figure.
    for run in RUNS {
        for id in run.iter().take_while(|a| !a.starts_with("--")) {
            assert!(
                files.iter().any(|f| f.starts_with(&format!("{id}/"))),
                "{id} wrote no figure: {files:?}"
            );
        }
    }
    std::fs::write(s.0.join("figures.html"), check_page(&out, &files)).unwrap();
    s.keep(true); // Kept while checking, for a failure to be looked at.
    let url = format!("file://{}", s.0.join("figures.html").display());
    let dom = browser::dump_dom(&chrome, &s.0.join(".chromium-dom"), &url);
    assert!(
        dom.contains("<p id=\"status\">done</p>"),
        "the check script did not finish (see {})",
        s.0.display()
    );
    let start = dom.find("<pre id=\"result\">").unwrap() + "<pre id=\"result\">".len();
    let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
    let lines: Vec<Vec<&str>> = result.lines().map(|l| l.split('\t').collect()).collect();
    assert_eq!(lines.len(), files.len(), "{result}");
    let mut charts = 0;
    for l in &lines {
        let (file, kind) = (l[0], l[1]);
        let name = file.rsplit('/').next().unwrap();
        if is_picture(name) {
            assert_eq!(
                kind, "picture",
                "{file}: a picture of gears, drawn as a chart?"
            );
            assert_eq!(l[2], "true", "{file} draws nothing");
            if name == "pair-check.svg" {
                // The example pair's driven arbor sits 1.6 mm off its tip-circle centre on a
                // 200 mm gear: invisible to scale, plain in the inset.
                let factor: f64 = l[3].parse().unwrap_or(0.0);
                let drawn: f64 = l[4].parse().unwrap();
                assert!(factor > 1.0, "{file}: exaggeration {}", l[3]);
                assert!(drawn >= 10.0, "{file}: the offset is drawn {drawn} px long");
            }
            continue;
        }
        assert_eq!(kind, "chart", "{file} was not drawn by the chart builder");
        charts += 1;
        let (n, distinct) = (l[2], l[3]);
        assert_eq!(n, distinct, "{file}: {n} series in {distinct} styles");
        assert_eq!(l[4], "ok", "{file}: {}", l[4]);
    }
    assert!(charts >= 20, "{charts} charts checked");
    let png = s.0.join("figures.png");
    browser::screenshot(
        &chrome,
        &s.0.join(".chromium-shot"),
        &url,
        &png,
        (1100, 6000),
    );
    browser::Pixels::read(&png).assert_not_blank("figures.png", 32, 500);
    s.keep(false);
}
