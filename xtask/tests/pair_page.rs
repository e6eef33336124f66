//! `pair.html` in a real browser: headless Chromium opens the page at a driver angle
//! (`#phi=X`), or lets the page drive itself as a reader would (`#selftest`: the slider moved,
//! the first event clicked), and the driven gear it draws is turned by θ at that angle as
//! `pair.csv` gives it; no script error occurred (the page writes any on itself); a screenshot is
//! not blank. Skipped when Chromium is missing, unless `CI=true` (`.ci/run` installs it).
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use std::path::Path;

use support::{Scratch, browser, chromium_or_skip, stderr, xtask};

/// The DOM after the page's script ran (`--dump-dom`).
fn dom(chrome: &Path, dir: &Path, url: &str) -> String {
    browser::dump_dom(chrome, &dir.join(".chromium-profile"), url)
}

/// A mesh far enough apart that its tips slip past each other: a run with events.
const SLIPPING: &str = "(
    driver: (teeth: 20, tip_radius: 20.0, root_radius: 18.9),
    driven: (teeth: 30, tip_radius: 30.0, root_radius: 28.9),
    clearance_percent: Some(97.0),
)";

/// Headless screenshot of `url` into `png`, which must then be a picture with more than one colour.
fn screenshot_not_blank(chrome: &Path, dir: &Path, url: &str, png: &Path) {
    browser::screenshot(chrome, &dir.join(".chromium-shot"), url, png, (960, 1000));
    let pixels = browser::Pixels::read(png);
    assert!(pixels.ink() > 1000, "the screenshot of {url} is blank");
    pixels.assert_not_blank(url, 8, 0);
}

/// The value of attribute `name` in the tag that starts at `tag`.
fn attribute(html: &str, tag: &str, name: &str) -> String {
    let start = html
        .find(tag)
        .unwrap_or_else(|| panic!("no {tag} in the page"));
    let rest = &html[start..start + html[start..].find('>').unwrap()];
    let at = rest.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
    rest[at..at + rest[at..].find('"').unwrap()].to_owned()
}

/// θ (absolute, degrees) at φ − φ0 = `phi` from pair.csv, linearly between its rows.
/// The angle of an SVG `rotate(A X Y)` transform.
fn rotation(transform: &str) -> f64 {
    transform
        .strip_prefix("rotate(")
        .unwrap()
        .split(' ')
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

fn csv_theta(csv: &str, phi: f64) -> f64 {
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let i = rows.iter().position(|r| r[0] >= phi).unwrap().max(1);
    let (a, b) = (&rows[i - 1], &rows[i]);
    let w = (phi - a[0]) / (b[0] - a[0]);
    a[4] + w * (b[4] - a[4])
}

#[test]
fn the_page_draws_the_driven_gear_at_theta_of_phi() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("pair-page");
    let o = xtask(&["run", "pair", "-q", "--out", &s.path("out")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dir = s.0.join("out/pair");
    let csv = std::fs::read_to_string(dir.join("pair.csv")).unwrap();
    for phi in [10.0, 95.5] {
        let page = dom(
            &chrome,
            &s.0,
            &format!("file://{}#phi={phi}", dir.join("pair.html").display()),
        );
        assert!(
            page.contains("<p id=\"status\">ok</p>"),
            "the script did not finish:\n{page}"
        );
        let shown_phi: f64 = attribute(&page, "<g id=\"driven\"", "data-phi-deg")
            .parse()
            .unwrap();
        let theta: f64 = attribute(&page, "<g id=\"driven\"", "data-theta-deg")
            .parse()
            .unwrap();
        let transform = attribute(&page, "<g id=\"driven\"", "transform");
        // The slider lands on the page's sample nearest the address's angle.
        assert!((shown_phi - phi).abs() < 0.1, "{phi} -> {shown_phi}");
        // The drawn rotation is −θ about the driven arbor...
        let angle = rotation(&transform);
        assert!(
            (angle + theta).abs() < 1e-9,
            "{transform} against theta {theta}"
        );
        // ... and θ is pair.csv's at that angle: within 0.01 deg, far less than a pixel at the
        // page's scale for this mesh (about 0.1 deg per pixel at the driven gear's tips).
        let expected = csv_theta(&csv, shown_phi);
        assert!(
            (theta - expected).abs() < 0.01,
            "phi {shown_phi}: page {theta}, pair.csv {expected}"
        );
    }
}

#[test]
fn a_reader_moving_the_slider_and_clicking_an_event_sees_theta_of_phi() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("pair-page-selftest");
    std::fs::write(s.path("slip.ron"), SLIPPING).unwrap();
    let o = xtask(&[
        "run",
        "pair",
        "-q",
        "--config",
        &s.path("slip.ron"),
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let dir = s.0.join("out/pair");
    let csv = std::fs::read_to_string(dir.join("pair.csv")).unwrap();
    let log = std::fs::read_to_string(dir.join("event-log.csv")).unwrap();
    let first: Vec<f64> = log
        .lines()
        .nth(1)
        .expect("the mesh must have an event")
        .split(',')
        .map(|c| c.parse().unwrap_or(f64::NAN))
        .collect();
    // phi - phi0 and the absolute theta of the first event.
    let first_event = (first[0], first[13]);
    let url = format!("file://{}#selftest", dir.join("pair.html").display());
    let page = dom(&chrome, &s.0, &url);
    assert!(
        page.contains("<p id=\"status\">ok</p>"),
        "a script error or an unfinished script:\n{page}"
    );
    for (what, near) in [
        ("selftest-slider", None),
        ("selftest-event", Some(first_event)),
    ] {
        let tag = format!("<p id=\"{what}\"");
        let phi: f64 = attribute(&page, &tag, "data-phi").parse().unwrap();
        let theta: f64 = attribute(&page, &tag, "data-theta").parse().unwrap();
        let transform = attribute(&page, &tag, "data-transform");
        let angle = rotation(&transform);
        assert!(
            (angle + theta).abs() < 1e-9,
            "{what}: {transform} against theta {theta}"
        );
        if let Some((event_phi, event_theta)) = near {
            // The click draws the event's own angles, not the nearest of the page's samples
            // (where pair.csv, read between its rows, cuts the corner of the loss of drive).
            assert!(
                (phi - event_phi).abs() < 1e-6 && (theta - event_theta).abs() < 1e-6,
                "clicked the event at {event_phi}, {event_theta}; shown {phi}, {theta}"
            );
        } else {
            assert!(
                (theta - csv_theta(&csv, phi)).abs() < 0.01,
                "{what}: phi {phi}, theta {theta}"
            );
        }
    }
    screenshot_not_blank(&chrome, &s.0, &url, &s.0.join("page.png"));
}

/// The `<li>` records `#selftest` wrote, one per event link clicked: (link, drawn phi - phi0,
/// drawn theta, the link's theta, the rotation drawn, contacts drawn, contacts the link has).
fn clicked(page: &str) -> Vec<(String, f64, f64, f64, f64, usize, usize)> {
    let list = &page[page.find("<ol id=\"selftest-events\"").unwrap()..];
    let list = &list[..list.find("</ol>").unwrap()];
    list.split("<li ")
        .skip(1)
        .map(|li| {
            let tag = format!("<li {li}");
            let get = |name: &str| attribute(&tag, "<li", name);
            (
                get("data-link"),
                get("data-phi").parse().unwrap(),
                get("data-theta").parse().unwrap(),
                get("data-expected").parse().unwrap(),
                rotation(&get("data-transform")),
                get("data-contacts").parse().unwrap(),
                get("data-wanted").parse().unwrap(),
            )
        })
        .collect()
}

/// Every event link of a replayed trial with locks and a gap (Table 3, Case C, d2-e2, trial 1),
/// clicked in a browser, draws the driven gear at the event's own θ - within 1e-6 deg of the
/// event log's, not at the nearest of the page's samples - with every contact of the event (two
/// at a lock), and a lock's release link draws θ after the release.
#[test]
fn each_event_link_draws_the_event_itself() {
    let Some(chrome) = chromium_or_skip() else {
        return;
    };
    let s = Scratch::new("pair-page-events");
    let o = xtask(&[
        "replay",
        "table3",
        "C/d2-e2",
        "1",
        "-q",
        "--out",
        &s.path("out"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let replayed = s.0.join("out/replay-table3-C-d2-e2-1");
    // The same trial through `run pair`, for its event log's nine decimals.
    let o = xtask(&[
        "run",
        "pair",
        "-q",
        "--config",
        replayed.join("pair.ron").to_str().unwrap(),
        "--out",
        &s.path("rerun"),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    let rerun = s.0.join("rerun/pair");
    let log = std::fs::read_to_string(rerun.join("event-log.csv")).unwrap();
    // (kind, phi - phi0, theta absolute, where a release let the gear go: phi - phi0 and theta
    // absolute, the event's own where it has none)
    let events: Vec<(String, f64, f64, (f64, f64))> = log
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<&str> = l.split(',').collect();
            let num = |i: usize| c[i].parse::<f64>().unwrap();
            let release = if c[17].is_empty() {
                (num(0), num(14))
            } else {
                (num(17), num(18))
            };
            (c[1].to_owned(), num(0), num(13), release)
        })
        .collect();
    let kinds: Vec<&str> = events.iter().map(|e| e.0.as_str()).collect();
    assert!(
        kinds.contains(&"lock") && kinds.contains(&"gap"),
        "a lock and a gap: {kinds:?}"
    );
    for dir in [&replayed, &rerun] {
        let url = format!("file://{}#selftest", dir.join("pair.html").display());
        let page = dom(&chrome, &s.0, &url);
        assert!(
            page.contains("<p id=\"status\">ok</p>"),
            "a script error or an unfinished script:\n{page}"
        );
        let records = clicked(&page);
        let releases = records.iter().filter(|r| r.0.ends_with("-release")).count();
        assert_eq!(records.len() - releases, events.len(), "{records:?}");
        for (link, phi, theta, expected, angle, drawn, wanted) in &records {
            let n: usize = link
                .trim_start_matches("#event=")
                .trim_end_matches("-release")
                .parse()
                .unwrap();
            let (kind, event_phi, event_theta, (release_phi, after)) = &events[n - 1];
            let release = link.ends_with("-release");
            let (want_phi, want) = if release {
                (release_phi, after)
            } else {
                (event_phi, event_theta)
            };
            assert!(
                (theta - want).abs() < 1e-6 && (expected - want).abs() < 1e-6,
                "{link} ({kind}): drawn theta {theta}, the event's {want}"
            );
            assert!((angle + theta).abs() < 1e-9, "{link}: rotation {angle}");
            assert!(
                (phi - want_phi).abs() < 1e-6,
                "{link}: phi {phi}, {want_phi}"
            );
            assert_eq!(drawn, wanted, "{link}: every contact drawn");
            if kind == "lock" && !release {
                assert_eq!(*wanted, 2, "{link}: a lock has two contacts");
            }
            if kind == "gap" {
                assert_eq!(*wanted, 1, "{link}: the contact lost");
            }
        }
        assert!(releases > 0, "a lock's release has its own link");
    }
}

/// The page's controls say what they will do: `play` becomes `pause` while playing, the zoom
/// button names the other view; no stray status word shows under the events; the TD strip
/// has named axes with units.
#[test]
fn the_page_labels_its_controls_and_axes() {
    let s = Scratch::new("pair-page-labels");
    let o = xtask(&["run", "pair", "-q", "--out", &s.path("out")]);
    assert!(o.status.success(), "{}", stderr(&o));
    let html = std::fs::read_to_string(s.0.join("out/pair/pair.html")).unwrap();
    for words in [
        "playButton.textContent = \"pause\"",
        "\"show the whole mesh\"",
        "driver angle from the start, phi - phi0 [deg]",
        ">TD [deg]</text>",
        "#status { display: none; }",
    ] {
        assert!(html.contains(words), "`{words}` missing from pair.html");
    }
}
