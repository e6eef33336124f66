//! Every tolerance the toolkit prints carries, per gear, the random error in degrees and in
//! millimetres at the tip beside its fraction of the pitch (and, where a systematic error is
//! part of the tolerance, the eccentricity in millimetres beside the amplitude in degrees), each
//! value the conversion `study::units` makes on that gear's size.

#![allow(clippy::unwrap_used, reason = "tests")]

use registry::{Table, fmt_f64};

/// An output: its id, the `--set` pairs that make it small, whether its tolerance has a
/// systematic part.
type Output = (&'static str, &'static [(&'static str, &'static str)], bool);

/// Each tolerance output at a reduced size.
const OUTPUTS: [Output; 5] = [
    (
        "table4",
        &[
            ("trials", "2"),
            ("random_from", "0.05"),
            ("random_to", "0.06"),
            ("random_step", "0.01"),
        ],
        false,
    ),
    (
        "table5",
        &[
            ("trials", "2"),
            ("random_from", "0.05"),
            ("random_to", "0.06"),
            ("random_step", "0.01"),
            ("systematic_from", "0.1"),
            ("systematic_to", "0.1"),
        ],
        true,
    ),
    (
        "fig6",
        &[
            ("trials", "2"),
            ("random_from", "0.05"),
            ("random_to", "0.06"),
            ("random_step", "0.01"),
        ],
        false,
    ),
    (
        "tolerance",
        &[
            ("search_lo", "0.04"),
            ("search_hi", "0.06"),
            ("resolution", "0.01"),
            ("batch", "2"),
            ("cap", "2"),
            ("random_from", "0.05"),
            ("random_to", "0.05"),
        ],
        false,
    ),
    (
        "clearance-design",
        &[
            ("grid", "40"),
            ("coarse_trials", "1"),
            ("refine_step", "0"),
            ("refine_trials", "1"),
            ("runs", "1"),
            ("cases", "B"),
        ],
        true,
    ),
];

/// The report's table with the units columns.
fn units_table(tables: &[Table]) -> Option<&Table> {
    tables
        .iter()
        .find(|t| t.columns.iter().any(|c| c == "random at tip [mm]"))
}

/// The column named `name` of `t`.
fn column(t: &Table, name: &str) -> usize {
    t.columns
        .iter()
        .position(|c| c == name)
        .unwrap_or_else(|| panic!("no column {name} in {:?}", t.columns))
}

/// Checks gear `gear`'s first row of `t` against `study::units` on its size in the gearing.
fn agrees_with_study_units(id: &str, t: &Table, gear: &str, systematic: bool) {
    let g = train::Gearing::freeth2006();
    let (teeth, radius) = (
        g.gear(gear).unwrap().teeth as usize,
        g.tip_radius(gear).unwrap(),
    );
    let row = t
        .rows
        .iter()
        .find(|r| r[column(t, "gear")] == gear)
        .unwrap_or_else(|| panic!("{id}: no row of gear {gear}"));
    assert_eq!(row[column(t, "N")], teeth.to_string(), "{id}");
    let fraction = row[column(t, "random [pitch]")]
        .trim_start_matches("< ")
        .trim_start_matches(">= ")
        .parse::<f64>()
        .unwrap();
    let r = study::units::random_error(fraction, teeth, radius);
    let deg = &row[column(t, "random [deg]")];
    let mm = &row[column(t, "random at tip [mm]")];
    assert!(
        deg.ends_with(&fmt_f64(r.degrees, 3)),
        "{id}: {deg} vs {r:?}"
    );
    assert!(mm.ends_with(&fmt_f64(r.tip_mm, 3)), "{id}: {mm} vs {r:?}");
    if systematic {
        let a = &row[column(t, "systematic A [deg]")];
        let Ok(a) = a.trim_start_matches("< ").parse::<f64>() else {
            return; // "-": the mesh's random error was below its grid, nothing run on top.
        };
        let s = study::units::systematic_error(a, 0.5, radius);
        let e = &row[column(t, "eccentricity [mm]")];
        assert!(
            e.ends_with(&fmt_f64(s.eccentricity_mm, 3)),
            "{id}: {e} vs {s:?}"
        );
    }
}

#[test]
fn every_tolerance_prints_millimetres_and_degrees_per_gear() {
    for (id, sets, systematic) in OUTPUTS {
        let report = experiments::run(id, 2025, 2, sets).unwrap();
        let t = units_table(&report.tables)
            .unwrap_or_else(|| panic!("{id}: no table of tolerances in mm and degrees"));
        for c in ["gear", "N", "R [mm]", "random [pitch]", "random [deg]"] {
            column(t, c);
        }
        if systematic {
            for c in ["systematic A [deg]", "eccentricity [mm]"] {
                column(t, c);
            }
        }
        // Both gears of every mesh (a gear once where the table lists gears once).
        assert!(t.rows.len() >= 29, "{id}: {} rows", t.rows.len());
        agrees_with_study_units(id, t, "b2", systematic);
        agrees_with_study_units(id, t, "e3", systematic);
    }
}

#[test]
fn figure_6_shades_edmunds_published_range() {
    let sets = [
        ("trials", "2"),
        ("random_from", "0.05"),
        ("random_to", "0.05"),
    ];
    let report = experiments::run("fig6", 7, 2, &sets).unwrap();
    let svg = report.files.iter().find(|f| f.name == "fig6.svg").unwrap();
    let svg = String::from_utf8(svg.contents.clone()).unwrap();
    assert!(svg.contains("class=\"band\""), "the range is drawn");
    assert!(svg.contains("Edmunds' published range"), "and named");
    let t = units_table(&report.tables).unwrap();
    let range = &t.rows[0][column(t, "Edmunds' range at tip [mm]")];
    let from = presentation::paper::get("fig6", "edmunds_random_from").unwrap();
    let b2 = train::Gearing::freeth2006();
    let expected = study::units::random_error(from.value, 64, b2.tip_radius("b2").unwrap());
    assert!(
        range.starts_with(&fmt_f64(expected.tip_mm, 3)),
        "{range} vs {expected:?}"
    );
}
