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
