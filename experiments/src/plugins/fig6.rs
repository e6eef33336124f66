//! `fig6`: each gear's largest tolerable random error (Table 4 by the 1 % rule; a gear in two
//! meshes takes the smaller), beside the paper's (its Table 5 E. max row) and, when a table of
//! measured errors is given, the measured ones.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table};
use serde::{Deserialize, Serialize};

use presentation::common::{Band, Series, category_plot_band};
use presentation::emax::{paper_random, show};
use presentation::units::{GearRow, Value};
use setting_groups::typed::{Gearing, label, off_paper_inputs, unsplit_cells};
use study::cell::Purpose;
use study::drive::DriveParams;
use study::errors::ErrorParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::grids::TRIALS;
use study::results::{GearRandom, GearTolerances, MeasuredFile, RandomErrorTable};
use study::tolerance::{self, RULE, RandomGrid};

registry::params! {
    /// `measured`: RON table of measured per-gear errors (the `measured` hypothesis' format) to draw beside ours; empty (or none): no measured values.
    const MEASURED = Param::new("measured", "", "RON table of measured per-gear errors (the `measured` hypothesis' format) to draw beside ours; empty (or none): no measured values", registry::Kind::Text).recorded();
}

/// Figure 6's settings: trials per cell, the rule, the measured table, the gearing with h and
/// G, the hypothesis, Table 4's grid, the event rule and the pair-trial protocol.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell of Table 4's grid ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// The failure rule, % of trials ([`RULE`]).
    #[param(RULE)]
    pub rule: f64,
    /// The measured table to draw beside ours ([`MEASURED`]).
    #[param(MEASURED)]
    pub measured: String,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The hypothesis and its parameters.
    #[group]
    pub errors: ErrorParams,
    /// Table 4's random errors.
    #[group]
    pub random: RandomGrid,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// Figure 6.
pub struct Fig6;

impl registry::Experiment for Fig6 {
    const ID: &'static str = "fig6";
    const TITLE: &'static str = "Largest tolerable random error of each gear (from Table 4 by the 1 % rule), beside the paper's and any measured errors";
    const PAPER_ITEM: &'static str = "Figure 6 (section 5)";
    const PLACE: Place = Place::Paper(110);
    type Settings = Settings;
    type Results = GearTolerances;

    fn compute(s: &Settings, run: &Run) -> Result<GearTolerances, RunError> {
        let cs = unsplit_cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            Some(&s.events),
            Some(&s.drive),
            s.trials,
            s,
        )?;
        let (g, clearance) = (cs.gearing(), cs.clearance()?);
        let measured = measured(&s.measured)?;
        let values = s.random.values(s)?;
        let grid = study::grids::run_grid(run.engine(), &cs, values, s.trials, Purpose::Input)?;
        let random_grid = RandomErrorTable::from_grid(&grid, clearance);
        let tolerable = grid.tolerable(s.trials, s.rule);
        let gears = gears_in_mesh_order(g)
            .into_iter()
            .map(|(gear, ms)| gear_random(g, (gear, &ms), &tolerable, measured.as_ref()))
            .collect();
        Ok(GearTolerances {
            random_grid,
            gears,
            measured: measured.map(|(file, t)| MeasuredFile {
                file,
                gears: t.entries().count(),
            }),
        })
    }

    fn report(s: &Settings, r: &GearTolerances) -> Result<Report, RunError> {
        let (rule, trials) = (s.rule, s.trials);
        let smallest = r.random_grid.random.first();
        let mut table = fig6_table(rule, trials, r.random_grid.clearance);
        let mut csv = String::from("gear,meshes,ours,paper,measured\n");
        let values: Vec<[Option<f64>; 3]> = r
            .gears
            .iter()
            .map(|gr| [gr.tolerable, paper_of_gear(&gr.meshes), gr.measured])
            .collect();
        let (inside, outside) = equal_to_paper(&values);
        for (gr, &[ours, paper, meas]) in r.gears.iter().zip(&values) {
            table.row(gear_row(
                &shown_name(gr),
                &gr.meshes,
                [ours, paper, meas],
                smallest,
            ));
            let opt = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
            csv.push_str(&registry::csv_row!(
                gr.gear,
                gr.meshes.join(" "),
                opt(ours),
                opt(paper),
                opt(meas),
            ));
        }
        add_notes(&mut table, (rule, trials), smallest, (inside, outside));
        table.note(measured_note(r.measured.as_ref()));
        if let Some(note) = renamed_note(&r.gears) {
            table.note(note);
        }
        let names: Vec<String> = r.gears.iter().map(shown_name).collect();
        let measured_file = r.measured.as_ref().map(|m| m.file.as_str());
        let svg = plot(&names, rule, measured_file, series_points(&values))?;
        let report = Report {
            tables: vec![table, in_units(r)],
            files: vec![
                OutputFile::new("fig6-data.csv", csv),
                OutputFile::new("fig6.svg", svg),
            ],
            agreement: off_paper_inputs(s)
                .is_empty()
                .then_some(registry::Agreement {
                    consistent: inside,
                    differ: outside,
                    what: "gears whose largest tolerable random error, a value of Table 4's grid, equals the paper's E. max / does not (one grid step apart counts as differing; no test; each mesh's value counted once for each of its two gears)".into(),
                }),
            ..presentation::cells::counts_report(r.random_grid.table.counts())
        };
        label(&s.events, Some(&s.drive), report)
    }
}

registry::register!(Fig6);

/// The measured table the `measured` parameter names, if any: (file name, table).
fn measured(given: &str) -> Result<Option<(String, hypotheses::MeasuredTable)>, RunError> {
    let Some(path) = hypotheses::measured_file_given(given) else {
        return Ok(None);
    };
    let text = input_file::read_to_string(std::path::Path::new(path), input_file::MAX_INPUT_BYTES)
        .map_err(|e| RunError::bad("--set", MEASURED.name, format!("cannot read {path}: {e}")))?;
    let table = hypotheses::measured_from_ron(path, &text).map_err(|e| {
        let what = e
            .what
            .strip_prefix(&format!("{path}: "))
            .unwrap_or(&e.what)
            .to_string();
        RunError::bad(path, what, e.rule)
    })?;
    Ok(Some((path.to_string(), table)))
}

/// The smaller of two tolerances, `None` (below the grid) being the smallest.
fn smaller(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(x), Some(y)) => Some(x.min(y)),
        _ => None,
    }
}

/// Points of a plotted series: (gear index, value).
type Points = Vec<(f64, f64)>;

/// Figure 6's plot: each gear's value, ours, the paper's and (from the file `measured`, when
/// one was given) the measured one, as (gear index, value) points.
fn plot(
    names: &[String],
    rule: f64,
    measured: Option<&str>,
    (ours_pts, paper_pts, measured_pts): (Points, Points, Points),
) -> Result<String, RunError> {
    let ours_label = format!("ours: largest tolerable (rule {rule} %)");
    let measured_label = measured
        .map(|f| format!("measured ({f})"))
        .unwrap_or_default();
    let mut series = vec![
        Series {
            label: &ours_label,
            points: ours_pts,
        },
        Series {
            label: "paper: Table 5 E. max",
            points: paper_pts,
        },
    ];
    if measured.is_some() {
        series.push(Series {
            label: &measured_label,
            points: measured_pts,
        });
    }
    let band_label = edmunds_range().map(|(lo, hi)| {
        format!(
            "Edmunds' published range of the random error ({} to {}, the paper's section 4)",
            study::cell::label(lo, 2),
            study::cell::label(hi, 2)
        )
    });
    let band = edmunds_range()
        .zip(band_label.as_deref())
        .map(|((lo, hi), label)| Band { label, lo, hi });
    category_plot_band(
        "Figure 6: largest tolerable random error of each gear",
        names,
        ("gear", "random error [fraction of the pitch]"),
        &series,
        band.as_ref(),
    )
}

/// The range of random errors Edmunds published (the paper's section 4), as paper.ron keeps it.
fn edmunds_range() -> Option<(f64, f64)> {
    let end = |q: &str| presentation::paper::get("fig6", q).map(|r| r.value);
    end("edmunds_random_from").zip(end("edmunds_random_to"))
}

/// Two columns of Edmunds' published range `(lo, hi)` (fractions of the pitch) on each gear of
/// `rows`, in degrees and millimetres at the tip, beside ours.
fn add_range_columns(t: &mut Table, rows: &[GearRow], (lo, hi): (f64, f64)) {
    let range = |a: f64, b: f64| format!("{}-{}", registry::fmt_f64(a, 3), registry::fmt_f64(b, 3));
    t.columns.push("Edmunds' range [deg]".into());
    t.columns.push("Edmunds' range at tip [mm]".into());
    for (cells, row) in t.rows.iter_mut().zip(rows) {
        let (a, b) = (row.gear.random(lo), row.gear.random(hi));
        cells.push(range(a.degrees, b.degrees));
        cells.push(range(a.tip_mm, b.tip_mm));
    }
    t.note(format!(
        "Edmunds' range: the random error he published, {} to {} of the pitch (the paper's section 4; the band of the figure), converted on each gear the same way.",
        study::cell::label(lo, 2),
        study::cell::label(hi, 2)
    ));
}

/// Each gear's largest tolerable random error in units of the gear, beside Edmunds' published
/// range in the same units.
fn in_units(r: &GearTolerances) -> Table {
    let smallest = r.random_grid.random.first().copied();
    let rows: Vec<GearRow> = r
        .gears
        .iter()
        .filter_map(|gr| {
            let size = presentation::units::gear_named(&r.random_grid.gears, &gr.paper_name)?;
            Some(GearRow {
                label: gr.meshes.join(", "),
                gear: size.clone(),
                random: Value::of(gr.tolerable, smallest),
                systematic: Value::Missing,
            })
        })
        .collect();
    let mut t = presentation::units::table(
        "Figure 6 in units of each gear: its largest tolerable random error".to_string(),
        "meshes",
        None,
        &rows,
    );
    if let Some((lo, hi)) = edmunds_range() {
        add_range_columns(&mut t, &rows, (lo, hi));
    }
    t
}

/// The note on the measured column: the file and how many gears it lists, or how to give one.
fn measured_note(measured: Option<&MeasuredFile>) -> String {
    match measured {
        Some(MeasuredFile { file, gears }) => format!(
            "Measured: the random error of each gear in {file} ({gears} gears listed){}.",
            if file.ends_with("measured-example.ron") {
                "; that shipped example's values are INVENTED, not Edmunds' measurements"
            } else {
                ""
            }
        ),
        None => "Measured: none given (--set measured=FILE, a table in the format of crates/hypotheses/data/measured-example.ron, whose values are invented).".into(),
    }
}

/// The gears in mesh order, first appearance, each with the meshes it is in.
fn gears_in_mesh_order(g: &train::Gearing) -> Vec<(String, Vec<usize>)> {
    let mut gears: Vec<(String, Vec<usize>)> = Vec::new();
    for (m, mesh) in g.meshes().iter().enumerate() {
        for gear in [&mesh.driver, &mesh.driven] {
            match gears.iter_mut().find(|(n, _)| n == gear) {
                Some((_, ms)) => ms.push(m),
                None => gears.push((gear.clone(), vec![m])),
            }
        }
    }
    gears
}

/// A gear as the tables show it: the paper's name (the one its mesh's label writes), with the
/// gearing file's name beside it where the two differ (`n2 (n3)`).
fn shown_name(gear: &GearRandom) -> String {
    if gear.paper_name == gear.gear {
        gear.gear.clone()
    } else {
        format!("{} ({})", gear.paper_name, gear.gear)
    }
}

/// The note that explains each gear shown under two names, or none.
fn renamed_note(gears: &[GearRandom]) -> Option<String> {
    let renamed: Vec<String> = gears
        .iter()
        .filter(|g| g.paper_name != g.gear)
        .map(|g| {
            let (paper, n) = (&g.paper_name, &g.gear);
            format!("{paper} ({n}) is named {paper} by its mesh's label, as in the paper, and {n} by the gearing file (its source: {})", g.source)
        })
        .collect();
    (!renamed.is_empty()).then(|| format!("Names: {}.", renamed.join("; ")))
}

/// The paper's value of a gear in `meshes`: the smaller of its meshes' E. max (none if one is
/// missing).
fn paper_of_gear(meshes: &[String]) -> Option<f64> {
    meshes
        .iter()
        .map(|m| paper_random(m))
        .collect::<Option<Vec<f64>>>()
        .and_then(|v| v.into_iter().reduce(f64::min))
}

/// A gear's row: its meshes, ours, the paper's and the measured value (marked above ours).
fn gear_row(
    gear: &str,
    labels: &[String],
    [ours, paper, meas]: [Option<f64>; 3],
    smallest: Option<&f64>,
) -> Vec<String> {
    let opt = |v: Option<f64>| v.map_or_else(|| "-".into(), |v| study::cell::label(v, 3));
    let meas_text = match (meas, ours) {
        (Some(v), Some(o)) if v > o => format!("{} (above ours)", study::cell::label(v, 3)),
        (v, _) => opt(v),
    };
    vec![
        gear.to_owned(),
        labels.join(", "),
        show(ours, smallest, 3),
        opt(paper),
        meas_text,
    ]
}

/// The table's title and columns.
fn fig6_table(rule: f64, trials: u64, clearance: f64) -> Table {
    Table::new(
        format!(
            "Figure 6: largest tolerable random error of each gear (rule {rule} % of {trials} trials, no systematic error, G = {clearance} %) [fraction of the pitch]"
        ),
        [
            "gear",
            "meshes",
            "ours",
            "paper (Table 5 E. max)",
            "measured",
        ],
    )
}

/// How a gear's value is read from Table 4's grid, and how many equal the paper's.
fn add_notes(
    table: &mut Table,
    (rule, trials): (f64, u64),
    smallest: Option<&f64>,
    (inside, outside): (u64, u64),
) {
    table.note(format!(
    "Each mesh's value: the largest random error of Table 4's grid up to which every value has at most {} of {trials} trials jammed; each gear takes its mesh's, a gear in two meshes the smaller. `< {}`: below the grid.",
    tolerance::allowed_jams(trials, rule),
    smallest.map_or_else(|| "-".into(), |v| study::cell::label(*v, 3)),
));
    table.note(format!(
    "Gears whose value equals the paper's: {inside}; differ: {outside}. The paper's figure gives no numbers; its per-mesh values are the E. max row of its Table 5, assigned to gears the same way."
));
}

/// A gear's values: ours (the smaller of its meshes' `tolerable`) and the measured one.
fn gear_random(
    g: &train::Gearing,
    (gear, ms): (String, &[usize]),
    tolerable: &[Option<f64>],
    measured: Option<&(String, hypotheses::MeasuredTable)>,
) -> GearRandom {
    let tolerable = ms.iter().map(|&m| tolerable[m]).reduce(smaller).flatten();
    let measured = measured.and_then(|(_, t)| t.errors(&gear).ok().map(|e| e.random));
    GearRandom {
        paper_name: g.label_name(&gear).to_owned(),
        source: g.gear(&gear).map_or("-", |d| d.source.as_str()).to_owned(),
        meshes: ms.iter().map(|&m| g.meshes()[m].label.clone()).collect(),
        gear,
        tolerable,
        measured,
    }
}

/// How many gears' values equal the paper's, and how many differ (of those it gives).
fn equal_to_paper(values: &[[Option<f64>; 3]]) -> (u64, u64) {
    let (mut inside, mut outside) = (0, 0);
    for [ours, paper, _] in values {
        if let Some(p) = paper {
            if ours.is_some_and(|o| (o - p).abs() < 1e-9) {
                inside += 1;
            } else {
                outside += 1;
            }
        }
    }
    (inside, outside)
}

/// The plotted series, ours, the paper's and the measured, as (gear index, value) points.
fn series_points(values: &[[Option<f64>; 3]]) -> (Points, Points, Points) {
    let column = |k: usize| -> Points {
        values
            .iter()
            .enumerate()
            .filter_map(|(i, v)| v[k].map(|y| (i as f64, y)))
            .collect()
    };
    (column(0), column(1), column(2))
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    fn run(measured: &str) -> Result<registry::Report, registry::RunError> {
        let sets = [
            ("trials", "2"),
            ("random_from", "0.05"),
            ("random_to", "0.06"),
            ("random_step", "0.01"),
            ("measured", measured),
        ];
        crate::run("fig6", 7, 2, &sets)
    }

    #[test]
    fn measured_values_are_drawn_beside_ours() {
        // The shipped example table: its values are INVENTED, used here only to exercise the
        // `measured` parameter.
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../crates/hypotheses/data/measured-example.ron"
        );
        let report = run(path).unwrap();
        let table = &report.tables[0];
        assert_eq!(
            table.rows.len(),
            29,
            "29 gears in the 15 meshes (b2 in two)"
        );
        let b2 = &table.rows[0];
        assert_eq!(b2[0], "b2");
        assert_eq!(b2[1], "b2-c1, b2-l1");
        assert!(b2[4].starts_with("0.070"), "{b2:?}");
        assert!(table.notes.iter().any(|n| n.contains("INVENTED")));
        let svg = report.files.iter().find(|f| f.name == "fig6.svg").unwrap();
        let svg = String::from_utf8(svg.contents.clone()).unwrap();
        assert!(
            svg.contains("measured ("),
            "legend names the measured table"
        );
        assert_eq!(report.trials, 2 * 2 * 15);

        let none = run("none").unwrap();
        assert!(none.tables[0].rows.iter().all(|r| r[4] == "-"));
    }

    #[test]
    fn a_missing_or_broken_measured_table_is_bad_input() {
        assert_eq!(run("/nonexistent/measured.ron").unwrap_err().exit_code(), 2);
        let broken = std::env::temp_dir().join(format!("fig6-broken-{}.ron", std::process::id()));
        std::fs::write(
            &broken,
            "(gears: [(gear: \"b2\", random: -1.0, systematic: 0.0)])",
        )
        .unwrap();
        let e = run(broken.to_str().unwrap()).unwrap_err();
        let _ = std::fs::remove_file(&broken);
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().contains("gear b2"), "{e}");
    }
}
