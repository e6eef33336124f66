//! In a real browser: the Theoretical Difference plot of a run with many events stays readable
//! (every event ticked, its numbers apart from one another and inside the picture), and an
//! idle start's picture shows the gap it is, with no contact ring.

#![allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.

mod support;

use std::path::Path;

use support::{Scratch, browser, chromium_or_skip, stderr, xtask};

/// Lays out the inline SVG and reports what a reader sees: the events ticked, the numbers
/// drawn, numbers that overlap one another, numbers outside the picture, and for an event
/// picture its rings, its dashed gap and the gap's ends against the two tip dots.
const SCRIPT: &str = r#"
const svg = document.querySelector("svg");
const box = svg.getBoundingClientRect();
const nums = [...svg.querySelectorAll("text.mark-number")].map(t => t.getBoundingClientRect());
let overlaps = 0, outside = 0;
nums.forEach((a, i) => {
  if (a.left < box.left || a.right > box.right || a.top < box.top || a.bottom > box.bottom) outside++;
  nums.slice(i + 1).forEach(b => {
    if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) overlaps++;
  });
});
const gap = svg.querySelector("line.nearest");
document.getElementById("result").textContent = [
  svg.querySelectorAll("line.mark-tick").length, nums.length, overlaps, outside,
  svg.querySelectorAll("circle.contact").length, gap ? 1 : 0,
].join("\t");
document.getElementById("status").textContent = "done";
"#;

/// `svg` inline in a page with [`SCRIPT`]; the page's DOM after it ran, as numbers.
/// `chromatic`: the strongly coloured pixels the screenshot must have at least.
fn seen(chrome: &Path, dir: &Path, name: &str, svg: &str, chromatic: usize) -> Vec<usize> {
    let page = dir.join(format!("{name}.html"));
    std::fs::write(
        &page,
        format!("<!doctype html><html><body style=\"margin:0\">{svg}<pre id=\"result\"></pre><p id=\"status\">not run</p><script>{SCRIPT}</script></body></html>"),
    )
    .unwrap();
    let url = format!("file://{}", page.display());
    let dom = browser::dump_dom(chrome, &dir.join(format!(".chromium-{name}")), &url);
    assert!(
        dom.contains("<p id=\"status\">done</p>"),
        "{name}: the script did not finish"
    );
    let png = dir.join(format!("{name}.png"));
    browser::screenshot(
        chrome,
        &dir.join(format!(".chromium-{name}-shot")),
        &url,
        &png,
        (900, 900),
    );
    browser::Pixels::read(&png).assert_not_blank(name, 8, chromatic);
    let start = dom.find("<pre id=\"result\">").unwrap() + "<pre id=\"result\">".len();
    dom[start..start + dom[start..].find("</pre>").unwrap()]
        .split('\t')
        .map(|v| v.parse().unwrap())
        .collect()
}

/// Runs `pair` on `config` into `dir/out`; the run's folder.
fn run_pair(dir: &Scratch, config: &str) -> std::path::PathBuf {
    let o = xtask(&[
        "run",
        "pair",
        "-q",
        "--config",
        config,
        "--out",
        &dir.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    dir.0.join("out/pair")
}

#[test]
fn an_event_plot_with_many_events_keeps_its_numbers_apart_and_inside() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("event-plot");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/many-events.ron");
    let dir = run_pair(&s, config.to_str().unwrap());
    let events = std::fs::read_to_string(dir.join("event-log.csv"))
        .unwrap()
        .lines()
        .count()
        - 1;
    assert!(
        events >= 30,
        "{events} events: the test needs a crowded plot"
    );
    let svg = std::fs::read_to_string(dir.join("pair.svg")).unwrap();
    assert!(
        svg.contains(&format!("its {events} events")),
        "the title counts the events"
    );
    let v = seen(&chrome, &s.0, "pair", &svg, 200);
    assert_eq!(v[0], events, "every event has its tick");
    assert!(v[1] >= 10, "{} numbers drawn", v[1]);
    assert_eq!(v[2], 0, "numbers over one another");
    assert_eq!(v[3], 0, "numbers outside the picture");
    // One picture per event.
    let pictures = std::fs::read_dir(&dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with("event-")
        })
        .count()
        - 1; // event-log.csv
    assert_eq!(pictures, events);
}

#[test]
fn an_idle_start_is_pictured_as_a_gap_not_a_contact() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("idle-start");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/idle-start.ron");
    let dir = run_pair(&s, config.to_str().unwrap());
    let svg = std::fs::read_to_string(dir.join("event-1-slip.svg")).unwrap();
    assert!(svg.contains("No contact"), "{svg}");
    let v = seen(&chrome, &s.0, "idle", &svg, 0);
    assert_eq!(v[4], 0, "a contact ring where nothing touches");
    assert_eq!(v[5], 1, "the gap is drawn");
}

/// A lock's release can throw the driven gear pitches on: the event table gives each jump in
/// driven pitches, and the table and the page say why the gear moves so far.
#[test]
fn a_locks_release_is_measured_in_pitches_and_explained() {
    let s = Scratch::new("release");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/many-events.ron");
    let o = xtask(&[
        "run",
        "pair",
        "--config",
        config.to_str().unwrap(),
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let text = support::stdout(&o);
    let row = text
        .lines()
        .find(|l| l.contains("| lock ") && l.contains("driven pitches ahead of the ideal ("))
        .unwrap_or_else(|| panic!("no lock with its release in pitches:\n{text}"));
    assert!(
        row.contains("released at once") || row.contains("then let go"),
        "{row}"
    );
    let why = "let go to the next position ahead at which no driver tooth overlaps it";
    assert!(text.contains(why), "{text}");
    let page = std::fs::read_to_string(s.0.join("out/pair/pair.html")).unwrap();
    assert!(page.contains("class=\"release-note\"") && page.contains(why));
}

/// Lays out a TD plot inline and reports, tab-separated: its events ticked, the numbers drawn,
/// the numbers 1 to N each drawn once (`true`/`false`), numbers over one another, numbers and
/// markers outside the plot's frame (its plot area), and the gap between the first number and
/// the frame's left edge (px).
const FRAME_SCRIPT: &str = r#"
const svg = document.querySelector("svg");
const frame = svg.querySelector("rect.plot-area").getBoundingClientRect();
const texts = [...svg.querySelectorAll("text.mark-number")];
const nums = texts.map(t => t.getBoundingClientRect());
const ticks = svg.querySelectorAll("line.mark-tick").length;
const seen = texts.map(t => Number(t.textContent)).sort((a, b) => a - b);
const once = seen.length === ticks && seen.every((n, i) => n === i + 1);
const inside = r => r.left >= frame.left - 0.5 && r.right <= frame.right + 0.5 && r.top >= frame.top - 0.5 && r.bottom <= frame.bottom + 0.5;
let overlaps = 0;
nums.forEach((a, i) => nums.slice(i + 1).forEach(b => {
  if (a.left < b.right && b.left < a.right && a.top < b.bottom && b.top < a.bottom) overlaps++;
}));
const markers = [...svg.querySelectorAll("g.marks > polygon, g.marks > path, g.marks > circle")].map(m => m.getBoundingClientRect());
const first = texts.find(t => t.textContent === "1");
document.getElementById("result").textContent = [
  ticks, nums.length, once, overlaps, nums.filter(r => !inside(r)).length,
  markers.filter(r => !inside(r)).length, first ? Math.round(first.getBoundingClientRect().left - frame.left) : -1,
].join("\t");
document.getElementById("status").textContent = "done";
"#;

/// What [`FRAME_SCRIPT`] reports of `svg`, with a screenshot that must not be blank.
fn framed(chrome: &Path, dir: &Path, name: &str, svg: &str) -> Vec<String> {
    let page = dir.join(format!("{name}.html"));
    std::fs::write(
        &page,
        format!("<!doctype html><html><body style=\"margin:0\">{svg}<pre id=\"result\"></pre><p id=\"status\">not run</p><script>{FRAME_SCRIPT}</script></body></html>"),
    )
    .unwrap();
    let url = format!("file://{}", page.display());
    let dom = browser::dump_dom(chrome, &dir.join(format!(".chromium-{name}")), &url);
    assert!(
        dom.contains("<p id=\"status\">done</p>"),
        "{name}: the script did not finish"
    );
    let png = dir.join(format!("{name}.png"));
    browser::screenshot(
        chrome,
        &dir.join(format!(".chromium-{name}-shot")),
        &url,
        &png,
        (900, 900),
    );
    browser::Pixels::read(&png).assert_not_blank(name, 8, 100);
    let start = dom.find("<pre id=\"result\">").unwrap() + "<pre id=\"result\">".len();
    dom[start..start + dom[start..].find("</pre>").unwrap()]
        .split('\t')
        .map(str::to_owned)
        .collect()
}

/// Table 3's D/d2-e2, trial 4 has 74 events, 50 of them within 90 deg of the driver: its TD
/// plot numbers every one, once, inside the plot's frame and apart from the others; an idle
/// start's number and marker keep off the y axis, inside the frame too.
#[test]
fn every_event_of_a_crowded_trial_is_numbered_inside_the_frame() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("numbered");
    let o = xtask(&[
        "replay",
        "table3",
        "D/d2-e2",
        "4",
        "-q",
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let ron = s.0.join("out/replay-table3-D-d2-e2-4/pair.ron");
    let dir = run_pair(&s, ron.to_str().unwrap());
    let svg = std::fs::read_to_string(dir.join("pair.svg")).unwrap();
    assert!(
        svg.contains("its 74 events, numbered as in the event table")
            && !svg.contains("where there is room"),
        "the title says every event is numbered"
    );
    let v = framed(&chrome, &s.0, "crowded", &svg);
    assert_eq!(v[0], "74", "every event ticked: {v:?}");
    assert_eq!(v[1], "74", "every event numbered: {v:?}");
    assert_eq!(v[2], "true", "numbers 1 to 74, each once: {v:?}");
    assert_eq!(v[3], "0", "numbers over one another: {v:?}");
    assert_eq!(v[4], "0", "numbers outside the frame: {v:?}");
    assert_eq!(v[5], "0", "markers outside the frame: {v:?}");
    // An idle start: its event at the very start of the run.
    let s2 = Scratch::new("numbered-idle");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/idle-start.ron");
    let idle = run_pair(&s2, config.to_str().unwrap());
    let svg = std::fs::read_to_string(idle.join("pair.svg")).unwrap();
    let v = framed(&chrome, &s2.0, "idle", &svg);
    assert_eq!(v[2], "true", "{v:?}");
    assert_eq!(
        (v[4].as_str(), v[5].as_str()),
        ("0", "0"),
        "inside the frame: {v:?}"
    );
    let gap: f64 = v[6].parse().unwrap();
    assert!(gap >= 2.0, "the first number sits on the y axis: {v:?}");
}

/// Lays out an event picture and reports, tab-separated: the scale bar's length in mm as it
/// says, the length it is drawn at against the picture's width in mm (both in mm), whether its
/// label says its length, whether it sits in the picture above the caption, and the two tip
/// dots' colours.
const SCALE_SCRIPT: &str = r#"
const svg = document.querySelector("svg");
const bar = svg.querySelector("g.scale-bar");
const view = svg.viewBox.baseVal;
const box = svg.getBoundingClientRect();
const drawn = bar.querySelector("line.bar").getBoundingClientRect();
const mm = Number(bar.dataset.mm);
const label = bar.querySelector("text").textContent;
const band = Array.from(svg.querySelectorAll("text")).find(t => t.getAttribute("font-weight") === "bold").getBoundingClientRect();
const fill = c => getComputedStyle(svg.querySelector(c)).fill;
document.getElementById("result").textContent = [
  mm, drawn.width / box.width * view.width, label.trim() === mm + " mm", drawn.bottom < band.top && drawn.left > box.left,
  fill("circle.driver-tip"), fill("circle.driven-tip"),
].join("\t");
document.getElementById("status").textContent = "done";
"#;

/// The script appended to a copy of a page of a run that starts idle: the arbors' labels, the
/// Theoretical Difference's event markers and ticks, and, once the idle start's link is
/// clicked, the dashed line where the gears come nearest.
const PAGE_SCRIPT: &str = r##"
document.querySelector("#events a.event").click();
document.getElementById("page-result").textContent = [
  Array.from(document.querySelectorAll("#mesh .arbor-label")).map(t => t.textContent).join(","),
  document.querySelectorAll("#plot circle.event-mark").length,
  document.querySelectorAll("#plot text.tick").length,
  document.querySelectorAll("#contacts line.nearest").length,
].join("\t");
"##;

/// An event picture carries a scale bar in millimetres, drawn at its stated length, and the
/// driver's and driven gear's dots in colours a reader tells apart; `pair.html` labels the
/// arbors, marks the events on its Theoretical Difference with enough ticks to read it, and
/// draws an idle start's nearest approach as the picture does.
#[test]
fn event_pictures_carry_a_scale_bar_and_the_page_draws_as_they_do() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("scale-bar");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/many-events.ron");
    let dir = run_pair(&s, config.to_str().unwrap());
    let svg = std::fs::read_to_string(dir.join("event-1-lock.svg"))
        .or_else(|_| std::fs::read_to_string(dir.join("event-1-gap.svg")))
        .or_else(|_| std::fs::read_to_string(dir.join("event-1-slip.svg")))
        .unwrap();
    let page = s.0.join("scale.html");
    std::fs::write(
        &page,
        format!("<!doctype html><html><body style=\"margin:0\">{svg}<pre id=\"result\"></pre><p id=\"status\">not run</p><script>{SCALE_SCRIPT}</script></body></html>"),
    )
    .unwrap();
    let url = format!("file://{}", page.display());
    let dom = browser::dump_dom(&chrome, &s.0.join(".chromium-scale"), &url);
    assert!(
        dom.contains("<p id=\"status\">done</p>"),
        "the script did not finish"
    );
    let start = dom.find("<pre id=\"result\">").unwrap() + "<pre id=\"result\">".len();
    let v: Vec<&str> = dom[start..start + dom[start..].find("</pre>").unwrap()]
        .split('\t')
        .collect();
    let (mm, drawn): (f64, f64) = (v[0].parse().unwrap(), v[1].parse().unwrap());
    assert!(
        mm > 0.0 && (drawn - mm).abs() < 0.02 * mm,
        "a {mm} mm bar drawn {drawn} mm long: {v:?}"
    );
    assert_eq!(v[2], "true", "the bar's label: {v:?}");
    assert_eq!(
        v[3], "true",
        "the bar in the picture, above the caption: {v:?}"
    );
    let rgb = |c: &str| -> Vec<f64> {
        c.trim_start_matches("rgb(")
            .trim_end_matches(')')
            .split(", ")
            .map(|x| x.parse().unwrap())
            .collect()
    };
    // Apart in colour and in hue (navy and dark purple, 68 apart and 60 deg of hue, were not).
    let hue = |c: &[f64]| {
        let (max, min) = (c[0].max(c[1]).max(c[2]), c[0].min(c[1]).min(c[2]));
        let d = (max - min).max(1e-9);
        let h = if max == c[0] {
            (c[1] - c[2]) / d
        } else if max == c[1] {
            2.0 + (c[2] - c[0]) / d
        } else {
            4.0 + (c[0] - c[1]) / d
        };
        (h * 60.0).rem_euclid(360.0)
    };
    let (a, b) = (rgb(v[4]), rgb(v[5]));
    let apart = a
        .iter()
        .zip(&b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt();
    let turn = (hue(&a) - hue(&b)).abs();
    let turn = turn.min(360.0 - turn);
    assert!(
        apart > 100.0 && turn > 70.0,
        "the tips' dots {} and {} look alike ({apart:.0} apart, {turn:.0} deg of hue)",
        v[4],
        v[5]
    );
    let png = s.0.join("scale.png");
    browser::screenshot(
        &chrome,
        &s.0.join(".chromium-scale-shot"),
        &url,
        &png,
        (600, 900),
    );
    browser::Pixels::read(&png).assert_not_blank("scale.png", 8, 100);

    // The page of a run that starts idle.
    let idle = Scratch::new("scale-bar-idle");
    let config = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/idle-start.ron");
    let dir = run_pair(&idle, config.to_str().unwrap());
    let html = std::fs::read_to_string(dir.join("pair.html"))
        .unwrap()
        .replace(
            "</body>",
            &format!("<pre id=\"page-result\"></pre><script>{PAGE_SCRIPT}</script></body>"),
        );
    std::fs::write(dir.join("check.html"), html).unwrap();
    let url = format!("file://{}", dir.join("check.html").display());
    let dom = browser::dump_dom(&chrome, &idle.0.join(".chromium-page"), &url);
    let start = dom.find("<pre id=\"page-result\">").unwrap() + "<pre id=\"page-result\">".len();
    let v: Vec<&str> = dom[start..start + dom[start..].find("</pre>").unwrap()]
        .split('\t')
        .collect();
    assert_eq!(v[0], "driver arbor,driven arbor", "{v:?}");
    assert_eq!(v[1], "1", "the idle start's marker on the TD: {v:?}");
    let ticks: usize = v[2].parse().unwrap();
    assert!(
        ticks >= 10,
        "{ticks} tick labels on the TD's two axes: {v:?}"
    );
    assert_eq!(
        v[3], "1",
        "the idle start's nearest approach, dashed: {v:?}"
    );
}
