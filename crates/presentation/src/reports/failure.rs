//! What `failure` shows: the study beside the paper's Table 6 of section 6 (each train's share
//! of runs jammed within a year and the mean day of its first jam), the detail per train, the
//! survival table read at fixed angles of b, the runs' CSV and each train's survival plot.

use registry::{Agreement, OutputFile, Report, RunError, Table, fmt_f64};
use stats::DAYS_PER_YEAR;
use study::results::{FailureStudy, TrainSummary};
use study::whole_mechanism::TRAINS;

use crate::common::{Plot, Series, mean_day_cell, percent_cell};

/// The failure study's report from its results `r` at clearance `clearance` (% of h, for the
/// paper's column), noting a Lunar train run with its pin-and-slot: the table beside the paper's,
/// the detail per train, the survival table, the runs' CSV and each train's survival plot.
pub fn report(r: &FailureStudy, clearance: f64, pin_and_slot: bool) -> Result<Report, RunError> {
    let runs = r.inputs.iter().flat_map(|i| &i.runs);
    let mut report = Report {
        trials: runs.clone().count() as u64,
        engagements: runs.map(|o| o.engagements).sum::<f64>().round() as u64,
        ..Default::default()
    };
    let (mut paper_table, agreement) = paper_table(r, clearance);
    if pin_and_slot {
        paper_table.note("The Lunar train includes the pin-and-slot (--set pin_and_slot=true), beyond the paper: e5-k1 and k2-e6 turn in the frame of the e3 turntable, which turns at its mean rate.");
    }
    report.tables.push(paper_table);
    report.tables.push(detail_table(r));
    report.tables.push(survival_table(r));
    report.agreement = agreement;
    report
        .files
        .push(OutputFile::new("failure-runs.csv", runs_csv(r)));
    report.files.extend(survival_files(r)?);
    Ok(report)
}

/// Points of b at which the survival table is read: degrees of the solar (b) pointer.
const READ_AT_DEG: [f64; 5] = [30.0, 60.0, 120.0, 180.0, 360.0];

/// Per train, the share of runs not yet jammed against the day (Kaplan-Meier), every input a
/// curve.
fn survival_files(r: &FailureStudy) -> Result<Vec<OutputFile>, RunError> {
    let mut files = Vec::new();
    let Some(first) = r.inputs.first() else {
        return Ok(files);
    };
    for (ti, train) in first.trains.iter().enumerate() {
        let curves: Vec<(String, Vec<(f64, f64)>)> = r
            .inputs
            .iter()
            .map(|inp| {
                let steps: Vec<stats::Step> =
                    inp.trains[ti].survival.iter().map(|s| s.step()).collect();
                (inp.legend.clone(), stats::step_points(&steps, r.horizon))
            })
            .collect();
        let svg = survival_plot(
            &format!(
                "Section 5's failure study, {} runs per input: {}, runs not yet jammed (Kaplan-Meier)",
                r.runs_per_input, train.train
            ),
            r.horizon,
            &curves,
        )?;
        files.push(OutputFile::new(
            format!("failure-{}.svg", file_stem(&train.train)),
            svg,
        ));
    }
    Ok(files)
}

/// One input's cell of the paper table, and whether the paper's value `p` is inside its 95 %
/// interval (none where there is no paper value, or too few jams for a mean's interval).
fn judged_cell(s: &TrainSummary, share: bool, p: Option<f64>) -> (String, Option<bool>) {
    if share {
        let inside = p.map(|v| {
            let r = v / 100.0;
            s.within_year.lo <= r && r <= s.within_year.hi
        });
        (percent_cell(&s.within_year.proportion()), inside)
    } else {
        let inside = s
            .mean_day
            .filter(|_| s.days.len() >= 2)
            .and_then(|e| p.map(|v| e.lo <= v && v <= e.hi));
        (mean_day_cell(s.mean_day.as_ref()), inside)
    }
}

fn file_stem(train: &str) -> String {
    let first = train.split(' ').next().unwrap_or(train);
    first.to_lowercase().replace('/', "-")
}

/// The paper's numbers beside ours, per input; the agreement counts the measured input only.
fn paper_table(r: &FailureStudy, clearance: f64) -> (Table, Option<Agreement>) {
    let mut header = vec!["quantity".to_string(), "paper".to_string()];
    header.extend(r.inputs.iter().map(|i| {
        if i.measured {
            "measured table".to_string()
        } else {
            format!("Case {}", i.label)
        }
    }));
    let mut table = Table::new(
        format!(
            "Section 5, the 30-run study: the paper beside ours (G = {clearance} %, {} runs per input, {} days of b): ours [95 % interval]; * where the paper's value is outside it",
            r.runs_per_input,
            fmt_f64(r.horizon, 2)
        ),
        header,
    );
    let paper = |q: &str| crate::paper::get("failure", q).map(|r| r.value);
    let mut agreement = Agreement {
        what: "the paper's values inside / outside our 95 % intervals, the measured input's column"
            .into(),
        ..Agreement::default()
    };
    let mut judged = false;
    // (label, paper quantity, train index, is the share row)
    let mut rows: Vec<(String, String, usize, bool)> = vec![(
        "mechanisms jammed within a year [%]".into(),
        "mechanisms_jammed".into(),
        TRAINS.len(),
        true,
    )];
    for (ti, (name, _)) in TRAINS.iter().enumerate() {
        rows.push((
            format!("{name}: mean day of the first jam"),
            format!("{name}.mean_days"),
            ti,
            false,
        ));
    }
    for (label, quantity, ti, share) in rows {
        let p = paper(&quantity);
        let mut row = vec![label, p.map_or_else(|| "-".into(), |v| fmt_f64(v, 0))];
        for inp in &r.inputs {
            let (cell, inside) = judged_cell(&inp.trains[ti], share, p);
            let mark = if inside == Some(false) { " *" } else { "" };
            row.push(format!("{cell}{mark}"));
            if inp.measured
                && let Some(inside) = inside
            {
                judged = true;
                if inside {
                    agreement.consistent += 1;
                } else {
                    agreement.differ += 1;
                }
            }
        }
        table.row(row);
    }
    table.row(stop_row(r, paper("stop_angle")));
    table.note("The paper ran Edmunds' measured per-gear errors (its Figure 6), which are not available here: our inputs are Edmunds' Cases A-D until a measured table is given with --set measured=FILE. Only that column is counted as agreement with the paper; the cases are for orientation.");
    table.note("Shares: runs whose mechanism (any train) jammed within one year of b, 95 % Clopper-Pearson interval. Days: b arbor, 365.25 d per turn; mean over the runs that jammed within the horizon, 95 % Student-t interval clipped to 0 .. horizon (none for fewer than two).");
    table.note("The paper's horizon is not stated (Table 1 ran 1, 3.8 and 4.5 turns of b); ours is the days parameter. The last row compares with the conclusions: a mechanism with Edmunds' errors 'would generally stop after the solar pointer completed one-third (120 deg)'.");
    (table, judged.then_some(agreement))
}

/// The conclusion's "one-third (120 deg)" (`stop_angle`, degrees of b) beside the median day
/// each input's mechanism stopped.
fn stop_row(r: &FailureStudy, stop_angle: Option<f64>) -> Vec<String> {
    let third = stop_angle.map(|deg| deg / 360.0 * DAYS_PER_YEAR);
    let mut row = vec![
        "median day the mechanism stopped (of the runs that did)".to_string(),
        third.map_or_else(|| "-".into(), |d| format!("about {}", fmt_f64(d, 0))),
    ];
    for inp in &r.inputs {
        row.push(
            inp.trains[TRAINS.len()]
                .median_day
                .map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
        );
    }
    row
}

fn detail_table(r: &FailureStudy) -> Table {
    let mut table = Table::new(
        format!(
            "Days to the first jam per input and train ({} runs each, horizon {} days of b)",
            r.runs_per_input,
            fmt_f64(r.horizon, 2)
        ),
        [
            "input",
            "train",
            "jammed within a year",
            "95 % interval [%]",
            "jammed within the horizon",
            "mean day [95 % interval]",
            "median day",
            "meshes that jammed first (runs)",
        ],
    );
    for inp in &r.inputs {
        for s in &inp.trains {
            let year = &s.within_year;
            table.row(vec![
                inp.label.clone(),
                s.train.clone(),
                format!("{}/{}", year.k, year.n),
                format!(
                    "{} .. {}",
                    fmt_f64(100.0 * year.lo, 0),
                    fmt_f64(100.0 * year.hi, 0)
                ),
                format!("{}/{}", s.days.len(), year.n),
                mean_day_cell(s.mean_day.as_ref()),
                s.median_day.map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                crate::common::jammed_first(&s.first_meshes),
            ]);
        }
    }
    for inp in &r.inputs {
        let p: Vec<String> = inp
            .params
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        table.note(format!(
            "{}: hypothesis {} with {}.",
            inp.label,
            inp.hypothesis,
            if p.is_empty() {
                "no parameters".into()
            } else {
                p.join(", ")
            }
        ));
    }
    table.note("One run is one mechanism: every gear manufactured once, each mesh given one random initial angle, each mesh run once up to its first jam; trains sharing meshes (b2-l1, l2-m1) share their motion. A train's first jam is the earliest jam on any of its pointers' meshes, dated on the b arbor. Trains are counted separately, as the paper did; in the real mechanism any jam stops every train (the mechanism row).");
    table
}

/// Share of runs not yet jammed at fixed angles of b.
fn survival_table(r: &FailureStudy) -> Table {
    let mut header = vec!["input".to_string(), "train".to_string()];
    for deg in READ_AT_DEG {
        header.push(format!(
            "{deg} deg of b ({} d)",
            fmt_f64(deg / 360.0 * DAYS_PER_YEAR, 1)
        ));
    }
    let mut table = Table::new(
        "Runs not yet jammed [%] at angles of the solar pointer (b arbor)",
        header,
    );
    let mut unplaceable = 0;
    for inp in &r.inputs {
        unplaceable += inp.runs.iter().filter(|o| o.unplaceable.is_some()).count();
        for s in &inp.trains {
            let steps: Vec<stats::Step> = s.survival.iter().map(|p| p.step()).collect();
            let mut row = vec![inp.label.clone(), s.train.clone()];
            for deg in READ_AT_DEG {
                row.push(survival_cell(&steps, deg / 360.0 * DAYS_PER_YEAR));
            }
            table.row(row);
        }
    }
    table.note("Kaplan-Meier estimate [95 % band]; every run is observed to the same horizon, so it is the share of runs whose first jam came later, and the band is that share's exact (Clopper-Pearson) interval.");
    if unplaceable > 0 {
        table.note(format!(
            "{unplaceable} runs had gears whose bodies overlapped at every angle (errors too large for the clearance): counted as jammed at day 0."
        ));
    }
    table
}

/// Per run and train: the day of the first jam, or the horizon and "censored".
fn runs_csv(r: &FailureStudy) -> String {
    let mut csv = String::from("input,trial,train,first_jam_day,status,mesh\n");
    for inp in &r.inputs {
        for (t, o) in inp.runs.iter().enumerate() {
            for (jam, s) in o.first_jams.iter().zip(&inp.trains) {
                let (label, name) = (&inp.label, &s.train);
                csv.push_str(&match jam {
                    Some(j) => registry::csv_row!(label, t, name, j.day, "jammed", j.mesh),
                    None => registry::csv_row!(label, t, name, r.horizon, "censored", ""),
                });
            }
        }
    }
    csv
}

/// A survival share [%] at `day` with its 95 % band: `50 [33 .. 70]`.
fn survival_cell(steps: &[stats::Step], day: f64) -> String {
    let at = steps
        .iter()
        .take_while(|p| p.day <= day)
        .last()
        .copied()
        .unwrap_or(stats::Step {
            day: 0.0,
            survival: 100.0,
            lo: 100.0,
            hi: 100.0,
        });
    crate::common::interval(at.survival, at.lo, at.hi, 0)
}

fn survival_plot(
    title: &str,
    horizon: f64,
    curves: &[(String, Vec<(f64, f64)>)],
) -> Result<String, RunError> {
    let series: Vec<Series<'_>> = curves
        .iter()
        .map(|(label, points)| Series {
            label,
            points: points.clone(),
        })
        .collect();
    Plot::new(
        title,
        "days of the b arbor (solar pointer; 365.25 d per turn)",
        "runs not yet jammed [%]",
        &series,
    )
    .ranges((0.0, horizon), (0.0, 102.0))
    .whole_ticks()
    .svg()
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn survival_cells_carry_their_band() {
        let steps = stats::kaplan_meier(&[Some(30.0), None, Some(10.0), Some(10.0)], 100.0);
        // 4 of 4 not yet jammed: the exact interval still reaches down to 40 %.
        assert_eq!(survival_cell(&steps, 5.0), "100 [40 .. 100]");
        let at_10 = survival_cell(&steps, 10.0);
        assert!(at_10.starts_with("50 ["), "{at_10}");
        assert_eq!(
            stats::survival_at(&steps, 99.0),
            25.0,
            "the cell reads the same curve"
        );
    }
}
