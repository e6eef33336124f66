//! A driven gear measured in its own sense is numbered the other way round inside the solver:
//! every output of `run pair` - the event table of `table.md`, `event-log.csv`, the event links
//! of `pair.html` and the captions of the event pictures - gives the tooth numbers of the file.
#![allow(clippy::unwrap_used, reason = "tests")]

mod support;

use support::{Scratch, stderr, xtask};

/// A 20-tooth driver and an eccentric 30-tooth wheel written in its own sense, at clearance
/// `G` % of h: 15 % locks, 80 % loses drive.
fn own_sense(clearance: f64) -> String {
    format!(
        "(
    driver: (teeth: 20, tip_radius: 20.0, root_radius: 18.0),
    driven: (
        teeth: 30,
        tip_radius: 30.0,
        root_radius: 28.0,
        sense: own,
        arbor: Some((offset: 0.4, angle_deg: 30.0)),
    ),
    clearance_percent: Some({clearance:?}),
    start_deg: 0.0,
    run_deg: Some(360.0),
)"
    )
}

/// `(driver tooth, driven tooth)` after `from` in `text`: the first `driver tooth J` and the
/// `driven tooth K` that follows it.
fn teeth_after(text: &str) -> (i64, i64) {
    let number = |key: &str| -> i64 {
        let at = text
            .find(key)
            .unwrap_or_else(|| panic!("no `{key}` in {text}"))
            + key.len();
        text[at..]
            .chars()
            .take_while(char::is_ascii_digit)
            .collect::<String>()
            .parse()
            .unwrap()
    };
    (number("driver tooth "), number("driven tooth "))
}

#[test]
fn own_sense_numbering_agrees_across_every_output() {
    let s = Scratch::new("pair-numbering");
    for (clearance, kind) in [(15.0, "lock"), (80.0, "slip")] {
        let ron = s.path(&format!("own-{clearance}.ron"));
        std::fs::write(&ron, own_sense(clearance)).unwrap();
        let out = s.path(&format!("out-{clearance}"));
        let o = xtask(&["run", "pair", "-q", "--config", &ron, "--out", &out]);
        assert!(o.status.success(), "{}", stderr(&o));
        let dir = std::path::Path::new(&out).join("pair");
        let read = |f: &str| std::fs::read_to_string(dir.join(f)).unwrap();
        // event-log.csv: columns 3 and 4 are the driver and driven tooth.
        let log: Vec<(String, i64, i64)> = read("event-log.csv")
            .lines()
            .skip(1)
            .map(|l| {
                let c: Vec<&str> = l.split(',').collect();
                (
                    c[1].to_owned(),
                    c[3].parse().unwrap(),
                    c[4].parse().unwrap(),
                )
            })
            .collect();
        assert!(
            log.iter().any(|(k, _, _)| k == kind),
            "G = {clearance} %: expected a {kind}: {log:?}"
        );
        // table.md's event table: columns driver tooth, driven tooth after the two angles, kind
        // and counted as.
        let table = read("table.md");
        let rows: Vec<(i64, i64)> = table
            .lines()
            .skip_while(|l| !l.starts_with("### Events"))
            .filter(|l| l.starts_with('|') && !l.contains("---") && !l.contains("kind"))
            .map(|l| {
                let c: Vec<&str> = l.split('|').map(str::trim).collect();
                (c[5].parse().unwrap(), c[6].parse().unwrap())
            })
            .collect();
        let html = read("pair.html");
        let links: Vec<(i64, i64)> = html
            .split("<li class=\"")
            .skip(1)
            .map(|li| teeth_after(&li[..li.find("</li>").unwrap()]))
            .collect();
        assert_eq!(rows.len(), log.len().min(20));
        assert_eq!(links.len(), log.len());
        for (i, (kind, j, k)) in log.iter().enumerate() {
            // The solver's own number of the driven tooth is 29 - k: a different tooth.
            assert_ne!(*k, 29 - k);
            if i < rows.len() {
                assert_eq!(rows[i], (*j, *k), "table.md, event {}", i + 1);
            }
            assert_eq!(links[i], (*j, *k), "pair.html, event {}", i + 1);
            if i < 20 {
                let svg = read(&format!("event-{}-{kind}.svg", i + 1));
                // Captions start a sentence with "Driver tooth".
                let caption = svg[svg.find("<text").unwrap()..].to_lowercase();
                assert_eq!(
                    teeth_after(&caption),
                    (*j, *k),
                    "event-{}-{kind}.svg",
                    i + 1
                );
            }
        }
    }
}
