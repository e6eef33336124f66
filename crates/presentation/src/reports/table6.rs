//! What `table6` shows: σ, Dm and P of the five pointers of a mechanism built with each mesh's
//! largest tolerable errors, beside the paper's with the 95 % intervals, and the tolerances it was
//! built with.

use registry::{OutputFile, Report, Table, fmt_f64};
use stats::Estimate;
use study::cell::label;
use study::results::{DerivedTolerances, GearTolerance, PointerEstimates, TolerableMechanism};

use crate::emax::{paper_random, paper_systematic, show};

/// How Table 6 was run, as its title and notes say it.
#[derive(Debug, Clone)]
pub struct Ran {
    /// The tolerance rule, % of trials jamming.
    pub rule: f64,
    /// Trials per cell of Tables 4 and 5, from which the tolerances are derived.
    pub cell_trials: u64,
    /// The clearance G, % of h.
    pub clearance: f64,
    /// Whether the random E. max row is the paper's own (`emax=paper`).
    pub from_paper: bool,
    /// The inputs that depart from the paper's (`name=value`); none: values are compared.
    pub off_paper: Vec<String>,
}

/// Table 6 from the mechanism built with the tolerable errors, `r`, run as `ran`: the pointers
/// beside the paper's, the detail, the tolerances it was built with, and the CSVs.
pub fn report(r: &TolerableMechanism, ran: &Ran) -> Report {
    let trials = r.trials as usize;
    let mut layout = layout_table(ran.from_paper, ran.clearance, trials);
    let (detail, csv, (inside, outside)) =
        pointer_rows(&mut layout, &r.pointers, trials, ran.off_paper.is_empty());
    layout.note(format!(
        "Values of the paper inside our 95 % Student-t intervals: {inside}; outside: {outside}."
    ));
    if let Some(note) = tolerances_note(&r.tolerances, ran.rule) {
        layout.note(note);
    }
    layout.note("Each trial: every gear manufactured afresh with its tolerances (systematic split as the split parameter says), random initial angles; a jam stops the pointer, so a trial that jammed is measured up to its first jam (as in table2).");
    let (inputs, inputs_csv) = inputs_table(&r.tolerances, ran.rule, ran.cell_trials, &r.gears);
    let cells = || r.tolerances.all();
    let trains = r.trials * r.pointers.len() as u64;
    let train_engagements: u64 = r.pointers.iter().map(|p| p.engagements).sum();
    Report {
        tables: vec![layout, detail, inputs],
        files: vec![
            OutputFile::new("table6-data.csv", csv),
            OutputFile::new("table6-inputs.csv", inputs_csv),
        ],
        trials: cells().map(|c| c.trials).sum::<u64>() + trains,
        engagements: cells().map(|c| c.engagements).sum::<u64>() + train_engagements,
        agreement: ran.off_paper.is_empty().then_some(registry::Agreement {
            consistent: inside,
            differ: outside,
            what: "the paper's values inside / outside our 95 % Student-t intervals".into(),
        }),
        ..Default::default()
    }
}

/// Table 6's inputs: each mesh's tolerances beside the paper's, and table6-inputs.csv.
fn inputs_table(
    tol: &DerivedTolerances,
    rule: f64,
    cell_trials: u64,
    gears: &[GearTolerance],
) -> (Table, String) {
    let mut inputs = Table::new(
        format!(
            "Table 6 inputs: each mesh's largest tolerable errors (rule {rule} % of {cell_trials} trials): ours (paper)"
        ),
        ["mesh", "random E. max [pitch]", "systematic E. max [deg]"],
    );
    let mut inputs_csv = String::from("mesh,random_emax,systematic_emax_deg\n");
    let sys_values = tol.systematic_values();
    for t in &tol.meshes {
        let mesh = &t.mesh;
        let paper_sys = paper_systematic(mesh, &sys_values, rule)
            .map_or_else(|| "-".into(), |p| show(p, sys_values.first(), 1));
        let ours_sys = if t.random.is_some() {
            show(t.systematic, sys_values.first(), 1)
        } else {
            "-".into()
        };
        inputs.row(vec![
            mesh.clone(),
            format!(
                "{} ({})",
                show(t.random, tol.random_grid.random.first(), 3),
                paper_random(mesh).map_or_else(|| "-".into(), |p| label(p, 3))
            ),
            format!("{ours_sys} ({paper_sys})"),
        ]);
        inputs_csv.push_str(&registry::csv_line([
            mesh.clone(),
            t.random.unwrap_or(0.0).to_string(),
            t.systematic.unwrap_or(0.0).to_string(),
        ]));
    }
    let shared: Vec<String> = gears
        .iter()
        .filter(|g| g.meshes.len() > 1)
        .map(|g| {
            format!(
                "{} ({}): random {}, systematic {} deg",
                g.gear,
                g.meshes.join(" and "),
                label(g.random, 3),
                label(g.systematic, 1)
            )
        })
        .collect();
    inputs.note(format!(
        "Each gear takes its mesh's values; a gear in two meshes takes the smaller of each: {}.",
        if shared.is_empty() {
            "none".to_string()
        } else {
            shared.join("; ")
        }
    ));
    inputs.note("A value below its grid (`< ...`) is built as 0. Systematic: the paper's value in brackets is what its own Table 5 counts give by the same rule.");
    (inputs, inputs_csv)
}

/// The pointers' rows: σ, Dm and P of each over the trials beside the paper's (into `layout`),
/// the detail table, table6-data.csv, and how many of the paper's values lie inside and outside
/// our intervals (none compared, and no `*`, unless `compared`: the run's inputs are the
/// paper's).
fn pointer_rows(
    layout: &mut Table,
    pointers: &[PointerEstimates],
    trials: usize,
    compared: bool,
) -> (Table, String, (u64, u64)) {
    let mut detail = Table::new(
        "Table 6 in detail: mean over trials with its 95 % interval, the paper's value, trials that jammed",
        [
            "pointer",
            "statistic",
            "ours [deg]",
            "95 % interval [deg]",
            "paper [deg]",
            "trials that jammed",
        ],
    );
    let mut csv = String::from("pointer,statistic,mean_deg,lo_deg,hi_deg,paper_deg,jammed\n");
    let mut rows: Vec<Vec<String>> = ["sigma", "Dm", "P"]
        .iter()
        .map(|s| vec![(*s).to_string()])
        .collect();
    let (mut inside, mut outside) = (0, 0);
    for p in pointers {
        let (name, turns, jammed) = (p.pointer.as_str(), p.turns, p.jammed);
        // P: the average absolute value of the oscillation mean, as in Table 1.
        let columns = [
            ("sigma", "sigma", p.sigma),
            ("Dm", "dm", p.dm),
            ("P", "mean", p.p),
        ];
        for (row, (label_text, key, estimate)) in columns.into_iter().enumerate() {
            let e: Estimate = estimate.into();
            let paper = crate::paper::get("table6", &format!("{name}.{key}")).map(|r| r.value);
            let ok = !compared || paper.is_none_or(|p| e.contains(p));
            if compared && paper.is_some() {
                if ok { inside += 1 } else { outside += 1 }
            }
            let cell =
                |x: Option<f64>, dec: usize| x.map_or_else(|| "-".to_string(), |v| fmt_f64(v, dec));
            rows[row].push(format!(
                "{} ({}){}",
                fmt_f64(e.mean, 3),
                cell(paper, 2),
                if ok { "" } else { "*" }
            ));
            let mut cells = crate::common::estimate_cells(name, turns, label_text, &e);
            cells.extend([cell(paper, 2), format!("{jammed}/{trials}")]);
            detail.row(cells);
            let paper_csv = paper.map_or(String::new(), |v| v.to_string());
            let mut fields = crate::common::estimate_csv(name, label_text, &e);
            fields.extend([paper_csv, jammed.to_string()]);
            csv.push_str(&registry::csv_line(fields));
        }
    }
    for r in rows {
        layout.row(r);
    }
    (detail, csv, (inside, outside))
}

/// The meshes that ran at tolerances other than the paper's, as a note: a random E. max other
/// than the paper's row, or a systematic one other than what the paper's own Table 5 counts give
/// by the same rule. The paper's values come from its own tolerances, so where these differ the
/// comparison is not like for like; none where every mesh ran at the paper's.
fn tolerances_note(tol: &DerivedTolerances, rule: f64) -> Option<String> {
    let differs = |ours: Option<f64>, paper: Option<f64>| match (ours, paper) {
        (Some(o), Some(p)) => (o - p).abs() > 1e-9,
        (None, None) => false,
        _ => true,
    };
    let mut random = Vec::new();
    let mut systematic = Vec::new();
    let sys_values = tol.systematic_values();
    for t in &tol.meshes {
        let mesh = t.mesh.as_str();
        if differs(t.random, paper_random(mesh)) {
            random.push(mesh);
        }
        let paper_sys = paper_systematic(mesh, &sys_values, rule);
        if paper_sys.is_some_and(|p| differs(t.systematic, p)) {
            systematic.push(mesh);
        }
    }
    if random.is_empty() && systematic.is_empty() {
        return None;
    }
    let list = |v: &[&str]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    Some(format!(
        "Not like for like in every mesh: the paper's values come from its own tolerances, and this run's differ (the inputs table) in random E. max for {} of {} meshes ({}) and in systematic E. max for {} ({}); `--set emax=paper` takes the paper's random E. max row.",
        random.len(),
        tol.meshes.len(),
        list(&random),
        systematic.len(),
        list(&systematic)
    ))
}

/// The table in the paper's layout, its title saying where the random tolerances come from.
fn layout_table(emax_from_paper: bool, clearance: f64, trials: usize) -> Table {
    Table::new(
        format!(
            "Table 6: tolerable errors{}, G = {clearance} %, {trials} trials: ours (paper) [deg]; * where the paper's value is outside our 95 % interval",
            if emax_from_paper {
                " (random: the paper's E. max row, emax=paper)"
            } else {
                ""
            }
        ),
        study::pointers::COLUMNS,
    )
}
