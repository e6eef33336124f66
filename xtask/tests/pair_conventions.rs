//! `pair` as a user with measurements meets it: `help pair` states every convention of the file,
//! a run writes the check picture and the absolute angles, and the user's tooth numbers come
//! back as written.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{Scratch, browser, chromium_or_skip, stderr, stdout, xtask};

#[test]
fn help_states_every_convention_of_the_pair_file() {
    let o = xtask(&["help", "pair"]);
    assert!(o.status.success());
    let text = stdout(&o);
    for words in [
        "driver turns counter-clockwise",
        "Zero ray: each gear's tips_deg = 0",
        "phi (driver angle) is how far the driver has turned counter-clockwise",
        "theta (driven angle) is how far the driven gear has turned clockwise",
        "about the tip-circle centre",
        "not the arbor",
        "sense: driver (the default)",
        "own that they increase in the direction this gear turns",
        "eccentricity: Some((x, y)) is the arbor minus the tip-circle centre",
        "arbor: Some((offset: L, angle_deg: A))",
        "eccentricity_frame: tips (the default)",
        "world is the view's frame",
        "start_deg is phi at the start",
        "start: touching (the default)",
        "at_rest(theta_deg: T)",
        "teeth(driver: j, driven: k)",
        "phi_abs_deg, theta_abs_deg are phi and theta themselves",
        "tooth numbers as in your file",
        "pair-check.svg draws both gears at phi = 0 and theta = 0",
        // The proportions the loader refuses (`study::pair_file`), beside the older refusals.
        "teeth taller than half their tip radius",
        "more than 10 times apart",
        "more than 4 times apart",
        "below the other gear's valleys at every angle",
    ] {
        assert!(
            text.contains(words),
            "`{words}` missing from help pair:\n{text}"
        );
    }
}

/// A 20-tooth driver and a 5-tooth driven wheel, measured in its own sense, eccentric, started on
/// a named tooth pair.
const OWN_SENSE: &str = "(
    driver: (teeth: 20, tip_radius: 20.0, root_radius: 18.0),
    driven: (
        teeth: 5,
        tip_radius: 5.0,
        root_radius: 3.0,
        sense: own,
        tips_deg: Some([0.0, 71.0, 145.0, 215.0, 290.0]),
        arbor: Some((offset: 0.3, angle_deg: 30.0)),
        eccentricity_frame: tips,
    ),
    clearance_percent: Some(30.0),
    start_deg: 0.0,
    start: teeth(driver: 0, driven: 0),
    run_deg: Some(40.0),
)";

#[test]
fn a_run_writes_the_check_picture_absolute_angles_and_the_users_tooth_numbers() {
    let s = Scratch::new("pair-conventions");
    std::fs::write(s.path("mesh.ron"), OWN_SENSE).unwrap();
    let o = xtask(&[
        "run",
        "pair",
        "-q",
        "--config",
        &s.path("mesh.ron"),
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let read = |f: &str| std::fs::read_to_string(s.0.join("out/pair").join(f)).unwrap();
    // One file of events: the event table in table.md is an excerpt of event-log.csv, not a
    // second CSV with fewer columns.
    let mut csvs: Vec<String> = std::fs::read_dir(s.0.join("out/pair"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".csv"))
        .collect();
    csvs.sort();
    let others: Vec<&String> = csvs
        .iter()
        .filter(|n| !matches!(n.as_str(), "event-log.csv" | "pair.csv"))
        .collect();
    assert!(
        csvs.len() == 3 && others.len() == 1 && others[0].starts_with("mesh-from-"),
        "the summary, pair.csv and event-log.csv only: {csvs:?}"
    );
    let check = read("pair-check.svg");
    assert!(check.contains("<polygon id=\"driven-outline\""), "{check}");
    assert!(check.contains("tips_deg run clockwise here (sense: own)"));
    assert!(check.contains("(start: teeth(driver: 0, driven: 0))"));
    // Absolute angles beside the relative ones: their difference is the start, on every row.
    let csv = read("pair.csv");
    let mut lines = csv.lines();
    assert_eq!(
        lines.next(),
        Some("phi_minus_phi0_deg,theta_minus_theta0_deg,td_deg,phi_abs_deg,theta_abs_deg")
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let theta0 = rows[0][4];
    assert_eq!(rows[0][1], 0.0);
    for r in &rows {
        assert!((r[3] - r[0]).abs() < 1e-9, "{r:?}");
        assert!((r[4] - r[1] - theta0).abs() < 1e-8, "{r:?}");
    }
    // A 5-tooth wheel on a 20-tooth driver loses contact tooth by tooth: every event names a
    // driven tooth as written in the file, and the first is the tooth the run started on.
    let log = read("event-log.csv");
    let mut events = log.lines();
    assert_eq!(
        events.next(),
        Some(
            "phi_minus_phi0_deg,kind,counted_as,driver_tooth,driven_tooth,theta_minus_theta0_deg,theta_after_minus_theta0_deg,lost_motion_pitches,resumed,phase_shift,lag_deg,wedge_angle_deg,phi_abs_deg,theta_abs_deg,theta_after_abs_deg,ahead_of_ideal_driven_pitches,after_first_lock,release_phi_minus_phi0_deg,release_theta_abs_deg"
        )
    );
    let first: Vec<&str> = events.next().unwrap().split(',').collect();
    // A loss of drive (a gap, or a slip when it lasts a pitch or moves the tooth phase).
    assert!(matches!(first[1], "gap" | "slip"), "{log}");
    assert_eq!((first[3], first[4]), ("0", "0"), "{log}");
}

#[test]
fn a_start_that_cannot_be_taken_is_refused_naming_the_field() {
    let cases = [
        (
            "start: teeth(driver: 1, driven: 0)",
            "mesh.ron: start: driver tooth 1 cannot touch driven tooth 0 at start_deg = 0 (driver teeth that can touch there: 0)",
        ),
        (
            "start: at_rest(theta_deg: 10.0)",
            "mesh.ron: start.theta_deg: the driven gear at rest at theta = 10 deg overlaps a driver tooth at start_deg = 0: the nearest free driven angle ahead is 16.96",
        ),
    ];
    for (start, expected) in cases {
        let s = Scratch::new("pair-start");
        let text = OWN_SENSE.replace("start: teeth(driver: 0, driven: 0)", start);
        std::fs::write(s.path("mesh.ron"), text).unwrap();
        let o = xtask(&[
            "run",
            "pair",
            "--config",
            &s.path("mesh.ron"),
            "--out",
            &s.path("out"),
        ]);
        assert_eq!(o.status.code(), Some(2), "{start}");
        let err = stderr(&o);
        let line = err.lines().find(|l| l.contains("mesh.ron")).unwrap();
        assert!(line.contains(expected), "{start}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!s.0.join("out").exists(), "{start}: results were written");
    }
}

/// The script run on a page holding one `pair-check.svg`: one line per problem a reader would
/// see in the drawing (above the insets), then `done`: a label leaving the canvas, crossing a
/// tooth, lying on a gear's body (a tooth label), struck through by an axis or by a turning
/// arrow, or overlapping another label.
const CHECK_SCRIPT: &str = r#"
const svg = document.querySelector("svg");
const W = svg.viewBox.baseVal.width;
const problems = [];
const poly = id => Array.from(svg.getElementById(id).points).map(p => [p.x, p.y]);
const edges = pts => pts.map((p, i) => [p, pts[(i + 1) % pts.length]]);
const gears = [poly("driver-outline"), poly("driven-outline")];
const teeth = edges(gears[0]).concat(edges(gears[1]));
const segs = sel => Array.from(svg.querySelectorAll(sel)).flatMap(e => e.tagName === "line"
  ? [[[e.x1.baseVal.value, e.y1.baseVal.value], [e.x2.baseVal.value, e.y2.baseVal.value]]]
  : edges(Array.from(e.points).map(p => [p.x, p.y])).slice(0, -1));
const axes = segs("line.axis"), arrows = segs("polyline.turn");
// Does the segment a-b meet the box r (Liang-Barsky)?
function meets(r, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  let t0 = 0, t1 = 1;
  for (const [p, q] of [[-dx, a[0] - r.x], [dx, r.x + r.width - a[0]], [-dy, a[1] - r.y], [dy, r.y + r.height - a[1]]]) {
    if (p === 0) { if (q < 0) return false; } else { const t = q / p; if (p < 0) t0 = Math.max(t0, t); else t1 = Math.min(t1, t); }
  }
  return t0 <= t1;
}
function inside(pts, x, y) {
  let w = false;
  for (let i = 0, j = pts.length - 1; i < pts.length; j = i++) {
    const [a, b] = [pts[i], pts[j]];
    if ((a[1] > y) !== (b[1] > y) && x < a[0] + (y - a[1]) / (b[1] - a[1]) * (b[0] - a[0])) w = !w;
  }
  return w;
}
const labels = Array.from(svg.querySelectorAll("text.label")).map(t => [t.dataset.label, t.getBBox()]);
labels.forEach(([name, r], i) => {
  if (r.x < 0 || r.x + r.width > W || r.y < 0) problems.push(name + " leaves the canvas");
  if (teeth.some(([a, b]) => meets(r, a, b))) problems.push(name + " crosses a tooth");
  if (name.includes("tooth") && gears.some(g => inside(g, r.x + r.width / 2, r.y + r.height / 2))) problems.push(name + " lies on a gear");
  if (axes.some(([a, b]) => meets(r, a, b))) problems.push(name + " is struck through by an axis");
  if (arrows.some(([a, b]) => meets(r, a, b))) problems.push(name + " is crossed by a turning arrow");
  labels.slice(i + 1).forEach(([other, o]) => {
    if (r.x < o.x + o.width && o.x < r.x + r.width && r.y < o.y + o.height && o.y < r.y + r.height) problems.push(name + " overlaps " + other);
  });
});
problems.push("labels " + labels.length);
document.getElementById("result").textContent = problems.join("\n");
document.getElementById("status").textContent = "done";
"#;

/// A pair of `n1` and `n2` teeth on the mechanism's module (tip radius about a quarter of a
/// millimetre a tooth, h = 1.1 mm), both arbors a little off their tip-circle centres.
fn pair_of(n1: u32, n2: u32) -> String {
    let tip = |n: u32| 0.24 * f64::from(n) + 0.55;
    format!(
        "(driver: (teeth: {n1}, tip_radius: {}, root_radius: {}, eccentricity: Some((0.05, 0.02))), driven: (teeth: {n2}, tip_radius: {}, root_radius: {}, eccentricity: Some((0.1, 0.05))), clearance_percent: Some(40.0), start_deg: 0.0, run_deg: Some(30.0))",
        tip(n1),
        tip(n1) - 1.1,
        tip(n2),
        tip(n2) - 1.1
    )
}

/// `pair-check.svg` of a small driver on a large wheel (27:223, as Table 3's m3-e3), a large
/// driver on a small wheel (127:32, d2-e2), a pinion driving (15:53, m2-n1) and a pinion driven
/// (48:15), laid out in a browser: every label on the canvas, off the teeth (a tooth's label off
/// both gears' bodies), clear of the axes, the turning arrows and the other labels.
#[test]
fn check_picture_labels_stay_on_the_canvas_and_off_the_teeth() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("pair-check-labels");
    for (n1, n2) in [(27, 223), (127, 32), (15, 53), (48, 15)] {
        let name = format!("{n1}-{n2}");
        std::fs::write(s.path(&format!("{name}.ron")), pair_of(n1, n2)).unwrap();
        let out = s.path(&format!("out-{name}"));
        let o = xtask(&[
            "run",
            "pair",
            "-q",
            "--config",
            &s.path(&format!("{name}.ron")),
            "--out",
            &out,
        ]);
        assert!(o.status.success(), "{name}: {}", stderr(&o));
        let svg =
            std::fs::read_to_string(s.0.join(format!("out-{name}/pair/pair-check.svg"))).unwrap();
        let page = s.0.join(format!("{name}.html"));
        std::fs::write(
            &page,
            format!("<!doctype html><html><body style=\"margin:0\">{svg}<pre id=\"result\"></pre><p id=\"status\">not run</p><script>{CHECK_SCRIPT}</script></body></html>"),
        )
        .unwrap();
        let url = format!("file://{}", page.display());
        let dom = browser::dump_dom(&chrome, &s.0.join(format!(".chromium-{name}")), &url);
        assert!(
            dom.contains("<p id=\"status\">done</p>"),
            "{name}: the script did not finish"
        );
        let start = dom.find("<pre id=\"result\">").unwrap() + "<pre id=\"result\">".len();
        let result = &dom[start..start + dom[start..].find("</pre>").unwrap()];
        let lines: Vec<&str> = result.lines().collect();
        assert_eq!(lines.len(), 1, "{name}: {result}");
        let labels: usize = lines[0].trim_start_matches("labels ").parse().unwrap();
        assert!(labels >= 12, "{name}: {labels} labels");
        let png = s.0.join(format!("{name}.png"));
        browser::screenshot(
            &chrome,
            &s.0.join(format!(".chromium-{name}-shot")),
            &url,
            &png,
            (1000, 1200),
        );
        browser::Pixels::read(&png).assert_not_blank(&name, 8, 100);
    }
}
