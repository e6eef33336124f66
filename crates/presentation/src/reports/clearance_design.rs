//! What `clearance-design` shows: the search's table of each (case, mesh), the chosen clearances,
//! the failure study at the reference and at the chosen clearances with its paired test, the
//! Cases' errors in units of each gear, the CSVs and each case's plot of its worst meshes.

use registry::{OutputFile, Report, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use stats::{Proportion, clopper_pearson95, sign_test};

use crate::common::{Plot, Series};
use study::cell::{Counts, label};
use study::clearance_search::{Design, MeshSearch};
use study::grids::CASES;
use study::whole_mechanism::{self as whole, MechanismRun, Summary};

/// What the gears were made with, as the notes name it.
#[derive(Debug, Clone, Copy)]
pub struct Made {
    /// The tooth height h, mm.
    pub tooth_height: f64,
    /// The Cases' split of each error between the two gears of a mesh.
    pub split: f64,
}

/// The clearance design's report from its checked design `d` and results `r`: the search's
/// table, the chosen clearances, the failure study and the Cases' errors in units of each gear,
/// with the CSVs and plots.
pub fn report(d: &Design, made: Made, r: &Results) -> Result<Report, RunError> {
    let meshes: Vec<String> = r.meshes.iter().map(|m| m.mesh.clone()).collect();
    let (table, best_csv, probes_csv, used) = search_table(made, d, r);
    let design = design_table(d, &r.searches, &meshes);
    let per_input: Vec<&[MechanismRun]> = r.study.iter().map(|a| a.runs.as_slice()).collect();
    let summaries: Vec<Vec<Summary>> = per_input
        .iter()
        .map(|runs| whole::summarise(runs, d.days))
        .collect();
    let mut study = study_table(d, &per_input, &summaries);
    case_notes(&mut study, d, &r.searches, &meshes, &summaries, &per_input);
    let labels = r.study.iter().map(|a| a.label.as_str());
    let csvs = (
        best_csv,
        probes_csv,
        whole::labelled_runs_csv(labels, &per_input, d.days),
    );
    let files = files(d, &r.searches, meshes.len(), csvs)?;
    let pair_engagements: u64 = r
        .searches
        .iter()
        .flat_map(|sr| sr.probes.iter().map(|p| p.1.engagements))
        .sum();
    let runs = per_input.iter().flat_map(|runs| runs.iter());
    Ok(Report {
        tables: vec![table, design, study, cases_in_units(d, made.split, r)],
        files,
        trials: used + per_input.iter().map(|runs| runs.len() as u64).sum::<u64>(),
        engagements: pair_engagements + runs.map(|o| o.engagements).sum::<f64>().round() as u64,
        agreement: None,
        ..Default::default()
    })
}

/// One mesh's pair run in years of b.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshYears {
    /// The mesh, driver-driven.
    pub mesh: String,
    /// Years of the b arbor (one turn a year) in one pair run: one turn of the mesh's gear with
    /// more teeth, through the first pointer train holding it; `None` for a mesh on no train.
    pub years: Option<f64>,
}

/// One setting of the failure study: a case at the reference clearance for every mesh, or at
/// its chosen clearances.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyArm {
    /// `D at 40 %` or `D at best`.
    pub label: String,
    /// The whole-mechanism runs, in trial order (run t of a case draws the same gears and
    /// initial angles at both settings).
    pub runs: Vec<MechanismRun>,
}

/// The clearance design's results: every (case, mesh)'s search, and the failure study at the
/// reference and at the chosen clearances.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// The searches: case by case in the order run, each case's meshes in the gearing's order;
    /// clearances in % of h.
    pub searches: Vec<MeshSearch>,
    /// Each mesh's pair run in years of b, in the gearing's order.
    pub meshes: Vec<MeshYears>,
    /// The hypothesis the gears were made with.
    pub hypothesis: String,
    /// The failure study: each case at the reference, then at its chosen clearances.
    pub study: Vec<StudyArm>,
    /// Each mesh's gears (teeth, tip radius), in the gearing's order: the Cases' errors in
    /// millimetres and degrees. Empty in results stored before they were kept.
    #[serde(default)]
    pub gears: Vec<study::units::MeshGears>,
}

/// The errors of each Case the design ran, on each gear once, in units of the gear: what each
/// mesh's chosen clearance is designed to tolerate.
fn cases_in_units(d: &Design, split: f64, r: &Results) -> Table {
    let gears = crate::units::gears_once(&r.gears);
    let mut rows = Vec::new();
    for &c in &d.cases {
        let (case, systematic, random) = CASES[c];
        for (gear, meshes) in &gears {
            rows.push(crate::units::GearRow {
                label: format!("{case}: {}", meshes.join(", ")),
                gear: gear.clone(),
                random: crate::units::Value::At(random),
                systematic: crate::units::Value::At(systematic),
            });
        }
    }
    crate::units::table(
        "Edmunds' Cases the clearances are designed for, in units of each gear".to_string(),
        "case: meshes",
        Some(split),
        &rows,
    )
}

/// How many worst meshes each case's plot draws.
const PLOTTED: usize = 4;

/// A mesh whose failure rate at its chosen clearance is above this (by the lower end of its 95 %
/// interval) is named as still failing: no clearance of the search saves it.
const STILL_FAILING: f64 = 0.10;

/// Runs whose train `ti` (`TRAINS.len()`: the mechanism) jammed within a year at the first
/// setting and not at the second, and the reverse; `a` and `b` hold the same runs (same gears
/// and initial angles) at two settings.
fn discordant(a: &[MechanismRun], b: &[MechanismRun], ti: usize) -> (u64, u64) {
    let jammed =
        |o: &MechanismRun| whole::jam_of(o, ti).is_some_and(|j| j.day <= stats::DAYS_PER_YEAR);
    let mut only = (0, 0);
    for (x, y) in a.iter().zip(b) {
        match (jammed(x), jammed(y)) {
            (true, false) => only.0 += 1,
            (false, true) => only.1 += 1,
            _ => {}
        }
    }
    only
}

/// "k/n (jams/dis)" of a cell.
fn counts_cell(c: &Counts) -> String {
    format!(
        "{}/{} ({}/{})",
        c.failures, c.trials, c.jams, c.disengagements
    )
}

/// "lo .. hi" of a proportion in whole percent.
fn interval_cell(p: &Proportion) -> String {
    format!(
        "{} .. {}",
        fmt_f64(100.0 * p.lo, 0),
        fmt_f64(100.0 * p.hi, 0)
    )
}

/// "k/n, rate % [lo .. hi]" of a share of runs.
fn share_cell(p: &Proportion) -> String {
    format!("{}/{}, {}", p.k, p.n, crate::common::percent_cell(p))
}

/// The search's table, one row per (case, mesh): the coarse grid's counts, the best clearance
/// and the reference's, with the notes on how they were found; also clearance-design-best.csv,
/// clearance-design-probes.csv and the pair runs used.
fn search_table(made: Made, d: &Design, r: &Results) -> (Table, String, String, u64) {
    let mut table = search_header(d);
    let mut best_csv = String::from(
        "case,mesh,best_clearance,coarse_best,trials,failures,jams,disengagements,failure_lo,failure_hi,reference_clearance,reference_trials,reference_failures,reference_jams,reference_disengagements,reference_lo,reference_hi\n",
    );
    let mut probes_csv =
        String::from("case,mesh,clearance,trials,jams,disengagements,failures,finalist,chosen\n");
    for sr in &r.searches {
        let case = CASES[sr.case].0;
        let years = r.meshes.iter().find(|m| m.mesh == sr.mesh);
        let mut row = vec![
            case.to_string(),
            sr.mesh.clone(),
            years
                .and_then(|m| m.years)
                .map_or_else(|| "-".into(), |y| fmt_f64(y, 2)),
        ];
        for (&v, c) in d.grid.iter().zip(&sr.coarse) {
            let mark = if v == sr.coarse_best { "*" } else { "" };
            row.push(format!("{}{mark}", c.failures));
        }
        let (b, at_ref) = (sr.at(sr.best), sr.at(d.reference));
        let (bp, rp) = (
            clopper_pearson95(b.failures, b.trials),
            clopper_pearson95(at_ref.failures, at_ref.trials),
        );
        row.extend([
            label(sr.best, 0),
            counts_cell(&b),
            interval_cell(&bp),
            counts_cell(&at_ref),
            interval_cell(&rp),
        ]);
        table.row(row);
        search_csv(
            (&mut best_csv, &mut probes_csv),
            case,
            sr,
            d.reference,
            (&b, &bp),
            (&at_ref, &rp),
        );
    }
    let used: u64 = r.searches.iter().map(MeshSearch::trials).sum();
    search_notes(&mut table, (made, d, r), r.searches.len() as u64, used);
    (table, best_csv, probes_csv, used)
}

/// The search table's title and columns: the coarse grid's, then the best's and the reference's.
fn search_header(d: &Design) -> Table {
    let rl = label(d.reference, 0);
    let n_final = d.final_trials();
    let mut header = vec![
        "case".to_string(),
        "mesh".to_string(),
        "years of b per pair run".to_string(),
    ];
    header.extend(d.grid.iter().map(|v| format!("{} %", label(*v, 0))));
    header.extend([
        "best G [%]".to_string(),
        format!("best: failed of {n_final} (jams/dis)"),
        "best: 95 % interval [%]".to_string(),
        format!("{rl} %: failed of {n_final} (jams/dis)"),
        format!("{rl} %: 95 % interval [%]"),
    ]);
    Table::new(
        format!(
            "Each mesh on its own, Edmunds' Cases: pair runs (of {}) with a jam or a disengagement at each clearance of the coarse grid, and the clearance that minimises them (best), against the paper's {rl} % for every mesh",
            d.coarse
        ),
        header,
    )
}

/// The search table's notes: what a pair run is, how the search went and what it saved, and
/// how to read the intervals. `n_searches` meshes were searched in `used` pair runs.
fn search_notes(
    table: &mut Table,
    (made, d, r): (Made, &Design, &Results),
    n_searches: u64,
    used: u64,
) {
    let h = made.tooth_height;
    let rl = label(d.reference, 0);
    let years: Vec<f64> = r.meshes.iter().filter_map(|m| m.years).collect();
    let (shortest, longest) = (
        years.iter().copied().fold(f64::INFINITY, f64::min),
        years.iter().copied().fold(0.0, f64::max),
    );
    table.note(format!(
        "Each pair run: both gears manufactured afresh under the Case ({} hypothesis, split {}), a random initial angle, one full turn of the gear with more teeth (the run of Tables 3, 4 and I); failed: at least one jam or at least one disengagement. One such turn is {} to {} years of the mechanism, depending on the mesh (the years column: turns of b, through the first pointer train holding the mesh), so these rates are per pair run, not per year. A step of 5 % of h is {} mm of centre distance.",
        r.hypothesis,
        made.split,
        fmt_f64(shortest, 2),
        fmt_f64(longest, 0),
        fmt_f64(0.05 * h, 3),
    ));
    if d.step > 0.0 {
        let lo = d.grid.first().copied().unwrap_or(d.reference);
        let hi = d.grid.last().copied().unwrap_or(d.reference);
        let fine_values = ((hi - lo) / d.step).floor() as u64 + 1;
        let fine = fine_values * d.refine * n_searches;
        table.note(format!(
            "Search: the coarse grid at {} trials each (grid columns; `*`: the coarse best, the fewest failures with ties going to the nearest to {rl} %, then the lower); then the coarse best, the best plus and minus {} % and the reference ({rl} %), each brought to {} trials by adding trials to the same cells, and the one with the fewest failures chosen by the same rule. {used} pair runs in all, where a single grid from {} to {} % by {} % at {} trials each would take {fine} ({} % saved).",
            d.coarse,
            label(d.step, 0),
            d.refine,
            label(lo, 0),
            label(hi, 0),
            label(d.step, 0),
            d.refine,
            fmt_f64(100.0 * (1.0 - used as f64 / fine as f64), 0),
        ));
    } else {
        table.note(format!(
            "Search: the coarse grid at {} trials each (`*`: the best), and the clearance with the fewest failures chosen (ties: nearest {rl} %, then the lower); {used} pair runs in all.",
            d.coarse
        ));
    }
    table.note(format!(
        "Intervals: exact (Clopper-Pearson) 95 % of the failure rate. The best's count is the smallest of the finalists' on the trials that chose it, so it is biased low (the more finalists, the more); the failure study below, on other trials, is the independent check. A cell at {} trials of the same clearance and case is the same cell as in table3/tableI (same content, same trial streams): `--set coarse_trials=200` reuses their cells when they ran first in the same process.",
        d.coarse
    ));
}

/// The chosen clearances by case, as a table.
fn design_table(d: &Design, searches: &[MeshSearch], meshes: &[String]) -> Table {
    let rl = label(d.reference, 0);
    let mut header = vec!["case".to_string()];
    header.extend(meshes.iter().cloned());
    let mut design = Table::new(
        format!("Chosen clearance of each mesh [% of h] by case (the paper: {rl} for every mesh)"),
        header,
    );
    for (k, &ci) in d.cases.iter().enumerate() {
        let rows = &searches[k * meshes.len()..(k + 1) * meshes.len()];
        let mut row = vec![CASES[ci].0.to_string()];
        row.extend(rows.iter().map(|sr| label(sr.best, 0)));
        design.row(row);
    }
    design
}

/// Each case's note under the failure study: how many meshes moved, the share jammed within a
/// year at both settings, the paired split with its sign test, and the meshes still failing.
fn case_notes(
    study: &mut Table,
    d: &Design,
    searches: &[MeshSearch],
    meshes: &[String],
    summaries: &[Vec<Summary>],
    per_input: &[&[MechanismRun]],
) {
    let rl = label(d.reference, 0);
    for (k, &ci) in d.cases.iter().enumerate() {
        let mech = whole::TRAINS.len();
        let (r, b) = (
            &summaries[2 * k][mech].year,
            &summaries[2 * k + 1][mech].year,
        );
        let (only_ref, only_best) = discordant(per_input[2 * k], per_input[2 * k + 1], mech);
        let rows = &searches[k * meshes.len()..(k + 1) * meshes.len()];
        let changed = rows.iter().filter(|sr| sr.best != d.reference).count();
        let still: Vec<String> = rows
            .iter()
            .filter_map(|sr| {
                let c = sr.at(sr.best);
                (clopper_pearson95(c.failures, c.trials).lo > STILL_FAILING).then(|| {
                    format!(
                        "{} at {} % ({}/{})",
                        sr.mesh,
                        label(sr.best, 0),
                        c.failures,
                        c.trials
                    )
                })
            })
            .collect();
        let horizon = if d.days > stats::DAYS_PER_YEAR {
            let within = |runs: &[MechanismRun]| {
                runs.iter()
                    .filter(|o| whole::jam_of(o, mech).is_some_and(|j| j.day <= d.days))
                    .count()
            };
            format!(
                " Within the whole horizon ({} days of b): {}/{} at {rl} %, {}/{} at the chosen clearances.",
                fmt_f64(d.days, 2),
                within(per_input[2 * k]),
                d.runs,
                within(per_input[2 * k + 1]),
                d.runs,
            )
        } else {
            String::new()
        };
        let case = CASES[ci].0;
        let question = if case == "B" {
            "Could a careful maker have made Case B work? "
        } else {
            ""
        };
        study.note(format!(
            "{question}Case {case}: with {changed} of {} meshes moved off {rl} %, {}/{} mechanisms jammed within a year ({} %, 95 % interval {}-{} %), against {}/{} at {rl} % everywhere ({} %, {}-{} %); paired, {only_ref} runs jammed only at {rl} % and {only_best} only at the chosen clearances (exact p = {}). Meshes still failing in more than {} % of pair runs at their chosen clearance (lower 95 % bound): {}.{horizon}",
            meshes.len(),
            b.k,
            b.n,
            fmt_f64(100.0 * b.rate(), 0),
            fmt_f64(100.0 * b.lo, 0),
            fmt_f64(100.0 * b.hi, 0),
            r.k,
            r.n,
            fmt_f64(100.0 * r.rate(), 0),
            fmt_f64(100.0 * r.lo, 0),
            fmt_f64(100.0 * r.hi, 0),
            fmt_f64(sign_test(only_ref, only_best), 2),
            fmt_f64(100.0 * STILL_FAILING, 0),
            if still.is_empty() {
                "none".to_string()
            } else {
                still.join(", ")
            },
        ));
    }
}

/// The files: the search's CSVs (`best`, `probes`), the runs of the failure study (`runs`),
/// and each case's plot of its worst meshes.
fn files(
    d: &Design,
    searches: &[MeshSearch],
    meshes: usize,
    (best_csv, probes_csv, runs_csv): (String, String, String),
) -> Result<Vec<OutputFile>, RunError> {
    let mut files = vec![
        OutputFile::new("clearance-design-best.csv", best_csv),
        OutputFile::new("clearance-design-probes.csv", probes_csv),
        OutputFile::new("clearance-design-runs.csv", runs_csv),
    ];
    // The clearances every case tried, from the least to the greatest: the plots' shared x axis.
    let tried = searches
        .iter()
        .flat_map(|sr| sr.probes.iter().map(|(g, _)| *g));
    let range = tried.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), g| {
        (lo.min(g), hi.max(g))
    });
    let range = crate::common::drawable(range.0, range.1);
    for (k, &ci) in d.cases.iter().enumerate() {
        let rows = &searches[k * meshes..(k + 1) * meshes];
        files.push(OutputFile::new(
            format!("clearance-design-case-{}.svg", CASES[ci].0),
            worst_plot(CASES[ci].0, rows, d.reference, range)?,
        ));
    }
    Ok(files)
}

/// One (case, mesh)'s lines of clearance-design-best.csv (its best `b` and the reference `r`,
/// each with its interval) and clearance-design-probes.csv (every clearance tried).
fn search_csv(
    (best_csv, probes_csv): (&mut String, &mut String),
    case: &str,
    sr: &MeshSearch,
    reference: f64,
    (b, bp): (&Counts, &Proportion),
    (r, rp): (&Counts, &Proportion),
) {
    best_csv.push_str(&registry::csv_row!(
        case,
        sr.mesh,
        sr.best,
        sr.coarse_best,
        b.trials,
        b.failures,
        b.jams,
        b.disengagements,
        bp.lo,
        bp.hi,
        reference,
        r.trials,
        r.failures,
        r.jams,
        r.disengagements,
        rp.lo,
        rp.hi
    ));
    for (v, c) in &sr.probes {
        probes_csv.push_str(&registry::csv_row!(
            case,
            sr.mesh,
            v,
            c.trials,
            c.jams,
            c.disengagements,
            c.failures,
            sr.finalists.contains(v),
            *v == sr.best
        ));
    }
}

/// The failure study's table: per case and train, both settings side by side and the runs that
/// jammed at one only.
fn study_table(d: &Design, per_input: &[&[MechanismRun]], summaries: &[Vec<Summary>]) -> Table {
    let rl = label(d.reference, 0);
    let mut study = Table::new(
        format!(
            "The failure study rerun ({} whole mechanisms per case and setting, {} days of b): {rl} % for every mesh against each mesh at its case's chosen clearance, on the same gears and initial angles",
            d.runs,
            fmt_f64(d.days, 2)
        ),
        [
            "case".to_string(),
            "train".to_string(),
            format!("{rl} %: jammed within a year [%, 95 % interval]"),
            format!("{rl} %: mean day [95 %]"),
            format!("{rl} %: median day"),
            "best: jammed within a year [%, 95 % interval]".to_string(),
            "best: mean day [95 %]".to_string(),
            "best: median day".to_string(),
            "best: meshes that jammed first (runs)".to_string(),
            format!("jammed within a year at {rl} % only / at best only (exact p)"),
        ],
    );
    for (k, &ci) in d.cases.iter().enumerate() {
        let (at_ref, at_best) = (&summaries[2 * k], &summaries[2 * k + 1]);
        let (runs_ref, runs_best) = (per_input[2 * k], per_input[2 * k + 1]);
        for (ti, ((name, r), b)) in whole::train_names().zip(at_ref).zip(at_best).enumerate() {
            let (only_ref, only_best) = discordant(runs_ref, runs_best, ti);
            study.row(vec![
                CASES[ci].0.to_string(),
                name.to_string(),
                share_cell(&r.year),
                crate::common::mean_cell(&r.days, d.days),
                stats::median(&r.days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                share_cell(&b.year),
                crate::common::mean_cell(&b.days, d.days),
                stats::median(&b.days).map_or_else(|| "-".into(), |d| fmt_f64(d, 0)),
                crate::common::jammed_first(&b.meshes),
                format!(
                    "{only_ref} / {only_best} ({})",
                    fmt_f64(sign_test(only_ref, only_best), 2)
                ),
            ]);
        }
    }
    study.note(format!(
        "Run t of a case draws the same gears and initial angles at both settings (failure's streams), so the {rl} % columns are failure's own runs and the difference is the clearances' alone; the last column pairs them: runs that jammed within a year at one setting and not at the other, with the exact two-sided sign (McNemar) test of that split. Shares: runs with a jam within one year of b, exact 95 % interval; days: b arbor, mean over the runs that jammed within the horizon with its 95 % Student-t interval clipped to the horizon. Only jams stop a run (a disengagement does not), as in failure."
    ));
    study
}

/// Failure rate [%] against clearance of the case's `PLOTTED` meshes that fail most at the
/// reference (every clearance tried, each at the trials it had).
fn worst_plot(
    case: &str,
    rows: &[MeshSearch],
    reference: f64,
    clearance_range: (f64, f64),
) -> Result<String, RunError> {
    let rate = |c: &Counts| {
        if c.trials == 0 {
            0.0
        } else {
            c.failures as f64 / c.trials as f64
        }
    };
    let mut order: Vec<&MeshSearch> = rows.iter().collect();
    order.sort_by(|a, b| rate(&b.at(reference)).total_cmp(&rate(&a.at(reference))));
    let legends: Vec<String> = order
        .iter()
        .take(PLOTTED)
        .map(|sr| worst_legend(sr))
        .collect();
    let series: Vec<Series<'_>> = order
        .iter()
        .zip(&legends)
        .map(|(sr, l)| Series {
            label: l,
            points: sr
                .probes
                .iter()
                .map(|(g, c)| (*g, 100.0 * rate(c)))
                .collect(),
        })
        .collect();
    let title = format!(
        "Case {case}: pair runs with a jam or a disengagement against the clearance, the {PLOTTED} meshes failing most at {} % (beyond the paper)",
        label(reference, 0)
    );
    // Every case on the same axes (the whole clearance range searched, 0-100 % failed), so
    // that the cases' plots compare side by side.
    Plot::new(
        &title,
        "clearance G [% of the tooth height h]",
        "pair runs failed [%]",
        &series,
    )
    .ranges(clearance_range, (0.0, 102.0))
    .svg()
}

/// A plotted mesh's legend: its chosen clearance, or, where even that one still fails in more
/// than [`STILL_FAILING`] of its pair runs, that no clearance tried saves it (the chosen one is
/// then only the least bad).
fn worst_legend(sr: &MeshSearch) -> String {
    let c = sr.at(sr.best);
    if clopper_pearson95(c.failures, c.trials).lo > STILL_FAILING {
        format!(
            "{} (fails at every G tried; fewest at {} %: {}/{})",
            sr.mesh,
            label(sr.best, 0),
            c.failures,
            c.trials
        )
    } else {
        format!("{} (best {} %)", sr.mesh, label(sr.best, 0))
    }
}
