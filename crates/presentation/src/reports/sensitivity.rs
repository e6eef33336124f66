//! What `sensitivity` shows: one row per assumption changed, with the share of whole mechanisms
//! jammed within a year, the mean day of the first jam and the Lunar pointer's σ, and the share
//! plotted row by row.

use registry::{OutputFile, Report, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::mean_ci95;
use study::results::{FailureRun, TrainSummary};
use study::whole_mechanism::TRAINS;

use crate::common::{Series, category_plot, mean_day_cell, percent_cell};

/// The sensitivity study's report from its results `r`, run with `(trials, days, clearance)`
/// (runs per row, horizon in days of b, G in % of h): the table of rows and the plot of the
/// share of mechanisms jammed within a year.
pub fn report(r: &Results, ran: (u64, f64, f64)) -> Result<Report, RunError> {
    let runs = r.rows.iter().flat_map(|row| &row.runs);
    let mut report = Report {
        trials: r.rows.iter().map(|row| row.runs.len() as u64).sum(),
        engagements: runs.map(|o| o.engagements).sum::<f64>().round() as u64,
        ..Default::default()
    };
    report.tables.push(headline_table(ran, r));
    report.files.push(OutputFile::new(
        "sensitivity-share.svg",
        share_plot(r, &r.case)?,
    ));
    Ok(report)
}

/// What the rows measured: the Case they start from, the seed their draws come from, and each
/// row's runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// The Case every row starts from, as Edmunds names it (`A`-`D`).
    pub case: String,
    /// The seed of the run (every row draws trial t's errors and angles from it alike).
    pub seed: u64,
    /// One per row of the table, in its order.
    pub rows: Vec<RowResults>,
}

/// One row: the paper's model with one thing changed, its runs and what they show.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RowResults {
    /// Which assumption it changes: the paper's numbering in section 6, or the model input.
    pub assumption: String,
    /// What it is changed to, with its values.
    pub variant: String,
    /// The hypotheses applied to each gear, in order.
    pub hypotheses: String,
    /// Tooth height h of its gears, mm.
    pub tooth_height: f64,
    /// Whether the row changes the gears' shape or h (the table then names h beside the
    /// hypotheses).
    pub shape_changed: bool,
    /// Every run, in trial order.
    pub runs: Vec<FailureRun>,
    /// Per train, then the mechanism (a jam in any train): what the runs show.
    pub trains: Vec<TrainSummary>,
}

/// The one table: per row, the share of mechanisms jammed within a year, the day of the first
/// jam and the Lunar σ.
fn headline_table((trials, days, clearance): (u64, f64, f64), r: &Results) -> Table {
    let mechanism = TRAINS.len();
    let case = &r.case;
    let mut t = Table::new(
        format!(
            "Case {case}, G = {} %, {trials} whole-mechanism runs per row, horizon {days} d of b, seed {}: one assumption changed per row",
            clearance, r.seed
        ),
        [
            "assumption",
            "changed to",
            "mechanisms jammed within a year",
            "share [%] and 95 % interval",
            "day of the first jam: mean [95 % interval]",
            "median day",
            "Lunar sigma [deg]: mean [95 % interval]",
            "meshes that jammed first (runs)",
        ],
    );
    for row in &r.rows {
        let m = &row.trains[mechanism];
        let sigmas: Vec<f64> = row.runs.iter().filter_map(|o| o.lunar_sigma).collect();
        let sigma = match sigmas.len() {
            0 => "-".to_string(),
            1 => format!("{} (n = 1)", fmt_f64(sigmas[0], 3)),
            _ => crate::common::estimate(&mean_ci95(&sigmas), 3),
        };
        let first: Vec<String> = m
            .first_meshes
            .iter()
            .map(|(mesh, n)| format!("{mesh} ({n})"))
            .collect();
        let label = if row.shape_changed {
            format!(
                "{} [h = {} mm; {}]",
                row.variant, row.tooth_height, row.hypotheses
            )
        } else {
            format!("{} [{}]", row.variant, row.hypotheses)
        };
        t.row(vec![
            row.assumption.clone(),
            label,
            format!("{}/{}", m.within_year.k, m.within_year.n),
            percent_cell(&m.within_year.proportion()),
            mean_day_cell(m.mean_day.as_ref()),
            m.median_day.map_or("-".into(), |d| fmt_f64(d, 0)),
            sigma,
            if first.is_empty() {
                "-".into()
            } else {
                first.join(", ")
            },
        ]);
    }
    t.note(format!(
        "Every row is the failure study of Case {case} with one thing changed; a shape hypothesis is applied to each gear after Edmunds' errors (in brackets: what is applied, in order), drawing from a stream of its own. Edmunds' errors and the initial angles of trial t are the same draws in every row (those of Case {case}'s trial t in `failure`, so the first row is `failure`'s Case {case} row when the run counts agree): the rows run the same mechanisms and differ only by the change."
    ));
    t.note("Share: mechanisms (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed, 95 % Student-t interval clipped to the horizon. Lunar sigma: standard deviation of the Lunar pointer's Theoretical Difference over each run up to its first jam (8 samples per engagement of the busiest mesh), mean over runs with a 95 % Student-t interval.");
    t.note("ratio-mismatch keeps every arbor where the design puts it, so a gear cut with a larger module also reaches deeper into its partner: at Freeth et al.'s 3.7 % the clearance changes by more than the tooth height on the large gears, and most such mechanisms cannot turn at all (day 0) or slip (the Lunar sigma of hundreds of degrees). A maker who set each arbor to suit the gears he had cut would keep the clearance; that reading is not modelled here.");
    t.note("Assumption (4), flat gears turning in one plane, is outside a planar model and is not varied.");
    t
}

/// Share jammed within a year per row, with its interval, as an SVG chart.
fn share_plot(r: &Results, case: &str) -> Result<String, RunError> {
    let mechanism = TRAINS.len();
    let categories: Vec<String> = (1..=r.rows.len()).map(|i| format!("row {i}")).collect();
    let (mut share, mut lo, mut hi) = (Vec::new(), Vec::new(), Vec::new());
    for (i, row) in r.rows.iter().enumerate() {
        let p = row.trains[mechanism].within_year.proportion();
        share.push((i as f64, 100.0 * p.rate()));
        lo.push((i as f64, 100.0 * p.lo));
        hi.push((i as f64, 100.0 * p.hi));
    }
    category_plot(
        &format!(
            "Case {case}: mechanisms jammed within a year, one assumption changed per row (rows as in the table)"
        ),
        &categories,
        "row of the sensitivity table",
        "jammed within a year [%]",
        &[
            Series {
                label: "share",
                points: share,
            },
            Series {
                label: "95 % interval, lower end",
                points: lo,
            },
            Series {
                label: "95 % interval, upper end",
                points: hi,
            },
        ],
    )
}
