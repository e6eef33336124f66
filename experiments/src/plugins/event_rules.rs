//! `event-rules`: Tables 3, 4 and I and the ideal meshes' clearance limits counted under every
//! registered event rule and every drive reading (which gear of each mesh drives) at once, with
//! each reading's share of the paper's counts that a two-sample test finds consistent with ours:
//! which reading of "jam" and "disengagement", and of the driver, reproduces the paper best.
//!
//! Every trial runs once with each gear driving and is counted under all the rules (the gears do
//! not depend on the rule or the drive; the contact motion depends on the drive only), and the
//! per-reading counts go into the shared cell cache, so Tables 3, 4 and I run afterwards in the
//! same process (`run all`) find their cells already run.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use rules::Rule;
use train::Gearing;

use crate::cells::{
    PaperTable, Tally, consistent_with_paper, paper_counts, paper_table_cells, share,
};
use study::cell::{CellSpec, Counting, Counts, Purpose, label, run_cells_counted};
use study::drive::Drive;
use study::grids::CellSettings;
use study::limits::IdealPair;
use study::trial_end::End;

registry::params! {
    /// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70).
    const CLEARANCES = Param::new("clearances", "10,40,70", "Table I's clearances G, comma-separated (the paper: 10, 40 and 70)", registry::Kind::Text).unit("% of h");
    /// `limit_tolerance`: how closely each ideal mesh's clearance limits are located (bisection).
    const LIMIT_TOLERANCE = Param::new("limit_tolerance", "0.1", "how closely each ideal mesh's clearance limits are located (bisection)", registry::Kind::number(0.001, 10.0, "% of h")).unit("% of h");
}

crate::experiment! {
    id: "event-rules", paper_item: "Tables 3, 4, I and section 3 / Appendix II (what counts as a jam or a disengagement)", run,
    title: "Every event rule and drive side by side: the paper's counts of Tables 3, 4 and I consistent with ours, and the ideal meshes' clearance limits",
    params: [study::grids::TRIALS, CLEARANCES, LIMIT_TOLERANCE, study::trial_end::PARAM], groups: [study::gearing::GROUP, study::errors::CASES_GROUP, study::tolerance::RANDOM_GRID],
}

/// Where a cell's paper counts are: experiment id and key in `paper.ron`, and the group of
/// cells it is reported in (table, Case, clearance).
struct PaperCell {
    table: &'static str,
    key: String,
    group: String,
    /// `Table 4`, or the clearance of a Case's cell (`G = 40 %`).
    region: String,
    /// A cell of Edmunds' Case D (at any clearance).
    case_d: bool,
}

/// The tables compared, in the order they are printed.
const TABLES: [&str; 3] = ["table3", "table4", "tableI"];

/// Every registered rule at its defaults, in name order.
fn every_rule() -> Result<Vec<Rule>, RunError> {
    let names = rules::rules().map_err(|e| RunError::Internal(e.to_string()))?;
    names
        .keys()
        .map(|n| Rule::parse(n).map_err(|e| RunError::Internal(e.to_string())))
        .collect()
}

/// Every registered rule under every drive, each trial's counting ending at `end`: rule by
/// rule in name order, each under `listed`, `other` and `either`; then the default rule under
/// every drive with each other end (counting costs nothing more: the same runs).
fn every_counting(end: End) -> Result<Vec<Counting>, RunError> {
    let mut out: Vec<Counting> = every_rule()?
        .into_iter()
        .flat_map(|rule| {
            Drive::ALL.into_iter().map(move |drive| Counting {
                rule: rule.clone(),
                drive,
                end,
            })
        })
        .collect();
    let default = Rule::parse(rules::DEFAULT).map_err(|e| RunError::Internal(e.to_string()))?;
    for other in End::ALL.into_iter().filter(|&e| e != end) {
        for drive in Drive::ALL {
            out.push(Counting {
                rule: default.clone(),
                drive,
                end: other,
            });
        }
    }
    Ok(out)
}

/// The index of `rule` (by name) under `drive` and `end` in `countings`.
fn counting_index(countings: &[Counting], rule: &str, drive: Drive, end: End) -> Option<usize> {
    countings
        .iter()
        .position(|c| c.rule.name() == rule && c.drive == drive && c.end == end)
}

/// The cells of Tables 3 (Cases A-D at the clearance), 4 (the random grid, no systematic error)
/// and I (Cases A-D at each of its clearances), each with where its paper counts are.
fn all_cells(ctx: &Context, s: &CellSettings) -> Result<Vec<(CellSpec, PaperCell)>, RunError> {
    let clearances = crate::settings::clearance_list(ctx, &CLEARANCES, 200.0)?;
    let randoms = crate::settings::random_grid(ctx)?;
    let cells = paper_table_cells(s, &randoms, &clearances)?;
    let table3_clearance = s.clearance()?;
    let at = |g: f64| format!("G = {} %", label(g, 0));
    Ok(cells
        .into_iter()
        .map(|c| {
            let (group, region, case) = match c.table {
                PaperTable::Table3 { case } => (
                    format!("Table 3, Case {case}"),
                    at(table3_clearance),
                    Some(case),
                ),
                PaperTable::Table4 { .. } => (
                    "Table 4, random error only".to_string(),
                    "Table 4".to_string(),
                    None,
                ),
                PaperTable::TableI { case, clearance } => (
                    format!("Table I, Case {case}, G = {} %", label(clearance, 0)),
                    at(clearance),
                    Some(case),
                ),
            };
            let paper = PaperCell {
                table: c.id,
                key: c.key,
                group,
                region,
                case_d: case.is_some_and(|c| c == "D"),
            };
            (c.cell, paper)
        })
        .collect())
}

/// Per counting, per table: the tally of the paper's counts against ours; then, last, the tally
/// of every table without the paper's counts that look copied from another cell (`suspect` in
/// the reference file).
fn tallies(
    cells: &[(CellSpec, PaperCell)],
    counts: &[Vec<Counts>],
    rules: usize,
) -> Vec<[Tally; 4]> {
    let mut out = vec![[Tally::default(); 4]; rules];
    for ((_, p), per_rule) in cells.iter().zip(counts) {
        let paper = paper_counts(p.table, &p.key);
        let slip = |q: &str| crate::paper::suspect(p.table, &format!("{}.{q}", p.key));
        let trusted = (
            paper.0.filter(|_| !slip("jam")),
            paper.1.filter(|_| !slip("dis")),
        );
        let t = TABLES.iter().position(|&id| id == p.table).unwrap_or(0);
        for (r, c) in per_rule.iter().enumerate() {
            out[r][t].add(c, paper);
            out[r][3].add(c, trusted);
        }
    }
    out
}

/// The counts of the paper that look copied from another cell, as `table KEY` (for a note).
fn copy_slips() -> Vec<String> {
    crate::paper::all()
        .iter()
        .filter(|r| r.suspect.is_some())
        .map(|r| format!("{} {}", r.experiment, r.quantity))
        .collect()
}

/// The shares table: one row per counting (rule and drive).
fn shares_table(countings: &[Counting], tallies: &[[Tally; 4]], trials: u64) -> Table {
    let mut t = Table::new(
        format!(
            "The paper's counts consistent with ours under each event rule and drive (Fisher's exact two-sample test at 5 %; ours {trials} trials per cell, the paper's 200)"
        ),
        [
            "rule",
            "drive",
            "Table 3 jams",
            "Table 3 dis.",
            "Table 4 jams",
            "Table 4 dis.",
            "Table I jams",
            "Table I dis.",
            "all jams",
            "all dis.",
            "all jams, copy slips out",
            "all dis., copy slips out",
        ],
    );
    let end = countings.first().map_or(End::Turn, |c| c.end);
    for (counting, per_table) in countings.iter().zip(tallies) {
        if counting.end != end {
            continue;
        }
        let mut row = vec![counting.rule.label(), counting.drive.name().to_owned()];
        let mut all = Tally::default();
        let [tables @ .., trusted] = per_table;
        for tally in tables {
            row.push(share(tally.jams_consistent, tally.jams_compared));
            row.push(share(tally.dis_consistent, tally.dis_compared));
            all.jams_consistent += tally.jams_consistent;
            all.jams_compared += tally.jams_compared;
            all.dis_consistent += tally.dis_consistent;
            all.dis_compared += tally.dis_compared;
        }
        row.push(share(all.jams_consistent, all.jams_compared));
        row.push(share(all.dis_consistent, all.dis_compared));
        row.push(share(trusted.jams_consistent, trusted.jams_compared));
        row.push(share(trusted.dis_consistent, trusted.dis_compared));
        t.row(row);
    }
    t.note("Cells: Table 3 (Cases A-D at G = 40 %), Table 4 (random error only, the grid of its rows) and Table I (Cases A-D at G = 10, 40, 70 %), each mesh on its own. Every trial runs once with each gear driving and is counted under each rule: the gears and initial share of a pitch are the same for every row, the contact motion for every rule of one drive; only what counts as a jam or a disengagement, and which gear drives, differ.");
    t.note("Drive: `listed`, the first gear of the mesh's name drives, as the train runs (the default of every table); `other`, the second drives, both gears still turning their own way (it starts at the same share of its own pitch and turns until the larger gear has turned once); `either`, each trial's driver drawn by a fair coin from the trial's own stream after its gears and initial angle. `either` is a reading of the paper's counts, not a mechanism: nothing in the paper says its program chose the driver at random.");
    t.note("Table I's 40 % rows are Table 3's cells; the paper printed them twice, with some differences, and each printing is compared.");
    t.note(format!(
        "Copy slips out: the same comparison without the paper's counts that look copied from another cell ({}: Case C at G = 70 % for m3-e3 and e4-f1, 200/1 and 200/0, repeat its Case C at 40 % exactly, while every other mesh's counts move between the two clearances); they are flagged in the reference file, where a test checks that each equals the cell it repeats.",
        copy_slips().join(", ")
    ));
    t
}

/// How one group of cells compares under one rule: consistent counts, and among the counts the
/// test separates, how many of ours are higher than the paper's.
#[derive(Default)]
struct Split {
    jams: (u64, u64, u64),
    dis: (u64, u64, u64),
}

/// (consistent, compared, ours higher among the separated) for one count.
fn compare(into: &mut (u64, u64, u64), ours: u64, trials: u64, paper: Option<u64>) {
    let Some(p) = paper else { return };
    into.1 += 1;
    if consistent_with_paper(ours, trials, paper) {
        into.0 += 1;
    } else if ours as f64 / trials as f64 > p as f64 / 200.0 {
        into.2 += 1;
    }
}

/// Where the differences lie under `counting` (index `r`): one row per group of cells.
fn breakdown_table(
    cells: &[(CellSpec, PaperCell)],
    counts: &[Vec<Counts>],
    counting: &Counting,
    r: usize,
) -> Table {
    let mut groups: Vec<(String, Split)> = Vec::new();
    for ((_, p), per_rule) in cells.iter().zip(counts) {
        let paper = paper_counts(p.table, &p.key);
        let c = &per_rule[r];
        let i = match groups.iter().position(|(g, _)| *g == p.group) {
            Some(i) => i,
            None => {
                groups.push((p.group.clone(), Split::default()));
                groups.len() - 1
            }
        };
        compare(&mut groups[i].1.jams, c.jams, c.trials, paper.0);
        compare(&mut groups[i].1.dis, c.disengagements, c.trials, paper.1);
    }
    let mut t = Table::new(
        format!(
            "Where the differences lie under rule {}, drive {}: the paper's counts consistent with ours, by table, Case and clearance",
            counting.rule.label(),
            counting.drive.name()
        ),
        [
            "cells",
            "jams consistent",
            "jams differing: ours higher / lower",
            "dis. consistent",
            "dis. differing: ours higher / lower",
        ],
    );
    for (g, s) in &groups {
        let differing = |x: (u64, u64, u64)| {
            let d = x.1 - x.0;
            if d == 0 {
                "-".to_string()
            } else {
                format!("{} / {}", x.2, d - x.2)
            }
        };
        t.row(vec![
            g.clone(),
            share(s.jams.0, s.jams.1),
            differing(s.jams),
            share(s.dis.0, s.dis.1),
            differing(s.dis),
        ]);
    }
    t.note("Higher / lower compares the rates (ours of this run's trials, the paper's of 200) of the counts the two-sample test separates.");
    t
}

/// In how many cells every rule gives the same jam count, and the same disengagement count,
/// with the listed driver driving.
fn agreement_between_rules(counts: &[Vec<Counts>], countings: &[Counting]) -> (usize, usize) {
    let end = countings.first().map_or(End::Turn, |c| c.end);
    let listed: Vec<usize> = (0..countings.len())
        .filter(|&r| countings[r].drive == Drive::Listed && countings[r].end == end)
        .collect();
    let same = |f: fn(&Counts) -> u64| {
        counts
            .iter()
            .filter(|per| listed.iter().all(|&r| f(&per[r]) == f(&per[listed[0]])))
            .count()
    };
    (same(|c| c.jams), same(|c| c.disengagements))
}

/// The regions of the paper's cells, in print order: Table 4, each clearance, then Case D
/// (across clearances, its cells also counted in their clearance's column).
fn regions(cells: &[(CellSpec, PaperCell)]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for (_, p) in cells {
        if !out.contains(&p.region) {
            out.push(p.region.clone());
        }
    }
    out.sort_by_key(|r| {
        let g = r
            .trim_start_matches("G = ")
            .trim_end_matches(" %")
            .parse::<f64>()
            .unwrap_or(-1.0);
        (r != "Table 4", (g * 1000.0) as i64)
    });
    out.push("Case D".into());
    out
}

/// Per reading of the default rule (each drive): the paper's jams and disengagements consistent
/// with ours in each region.
fn regions_table(
    cells: &[(CellSpec, PaperCell)],
    counts: &[Vec<Counts>],
    countings: &[Counting],
) -> Table {
    let regions = regions(cells);
    let mut head = vec!["rule".to_string(), "drive".to_string(), "end".to_string()];
    for r in &regions {
        head.push(format!("{r} jams"));
        head.push(format!("{r} dis."));
    }
    head.push("all jams".into());
    head.push("all dis.".into());
    let mut t = Table::new(
        "The paper's counts consistent with ours by region, under the default rule, each drive and each end of a trial's counting (Fisher's exact two-sample test at 5 %)",
        head,
    );
    let readings = End::ALL
        .into_iter()
        .flat_map(|end| Drive::ALL.into_iter().map(move |drive| (drive, end)));
    for (drive, end) in readings {
        let Some(r) = counting_index(countings, rules::DEFAULT, drive, end) else {
            continue;
        };
        let mut split: Vec<Split> = regions.iter().map(|_| Split::default()).collect();
        let mut all = Split::default();
        for ((_, p), per) in cells.iter().zip(counts) {
            let paper = paper_counts(p.table, &p.key);
            let c = &per[r];
            let mut into = |i: usize| {
                compare(&mut split[i].jams, c.jams, c.trials, paper.0);
                compare(&mut split[i].dis, c.disengagements, c.trials, paper.1);
            };
            if let Some(i) = regions.iter().position(|x| *x == p.region) {
                into(i);
            }
            if p.case_d {
                into(regions.len() - 1);
            }
            compare(&mut all.jams, c.jams, c.trials, paper.0);
            compare(&mut all.dis, c.disengagements, c.trials, paper.1);
        }
        let mut row = vec![
            countings[r].rule.label(),
            drive.name().to_owned(),
            end.name().to_owned(),
        ];
        for x in split.iter().chain([&all]) {
            row.push(share(x.jams.0, x.jams.1));
            row.push(share(x.dis.0, x.dis.1));
        }
        t.row(row);
    }
    t.note("Regions: Table 4 (random error only, G = 40 %); each clearance G, Tables 3 and I (Cases A-D; Table 3's cells are Table I's at 40 %, each printing compared); Case D, its cells at every clearance (also counted in their clearance's columns). All: every one of the paper's 345 counts of each kind.");
    t.note("End: `turn`, a trial counts every failure of its whole turn (the paper's stated protocol, and every table's default); `first-event`, only its first jam or disengagement counts (the trial stops there); `first-disengagement`, jams until its first disengagement and that. The same runs are counted each way.");
    t
}

/// Table 4's jams summed over its grid, mesh by mesh, under the default rule and each drive
/// (and the setting's end), beside the paper's sums: where the drive moves the jams.
fn table4_sums_table(
    g: &Gearing,
    cells: &[(CellSpec, PaperCell)],
    counts: &[Vec<Counts>],
    countings: &[Counting],
    end: End,
) -> Table {
    let meshes: Vec<String> = g.meshes().iter().map(|m| m.label.clone()).collect();
    let mut head = vec!["drive".to_string()];
    head.extend(meshes.iter().cloned());
    head.push("all".into());
    let mut t = Table::new(
        format!(
            "Table 4's jams summed over its rows, per mesh, under rule {} and each drive: ours (the paper's)",
            rules::DEFAULT
        ),
        head,
    );
    let table4: Vec<usize> = (0..cells.len())
        .filter(|&i| cells[i].1.table == "table4")
        .collect();
    let paper_sum = |mesh: &str| -> u64 {
        table4
            .iter()
            .filter(|&&i| cells[i].0.mesh == mesh)
            .filter_map(|&i| paper_counts("table4", &cells[i].1.key).0)
            .sum()
    };
    for drive in Drive::ALL {
        let Some(r) = counting_index(countings, rules::DEFAULT, drive, end) else {
            continue;
        };
        let ours = |mesh: Option<&str>| -> u64 {
            table4
                .iter()
                .filter(|&&i| mesh.is_none_or(|m| cells[i].0.mesh == m))
                .map(|&i| counts[i][r].jams)
                .sum()
        };
        let mut row = vec![drive.name().to_owned()];
        for m in &meshes {
            row.push(format!("{} ({})", ours(Some(m)), paper_sum(m)));
        }
        let all_paper: u64 = meshes.iter().map(|m| paper_sum(m)).sum();
        row.push(format!("{} ({all_paper})", ours(None)));
        t.row(row);
    }
    t.note("Each sum adds a mesh's jam counts over Table 4's rows (random error 0.035-0.065 of the pitch, no systematic error, G = 40 %), each of 200 trials. The paper's sums are of its own counts, printed in brackets.");
    t
}

/// Each rule's clearance limits of every ideal mesh, with their envelope.
struct RuleLimits {
    /// `per_mesh[mesh][rule]`: (smallest G without a jam, largest G without a disengagement).
    per_mesh: Vec<Vec<(Option<f64>, Option<f64>)>>,
}

/// The ideal meshes' limits under every rule, located to `tol` % of h.
fn ideal_limits(g: &Gearing, h: f64, rules: &[Rule], tol: f64) -> Result<RuleLimits, RunError> {
    let pairs: Vec<IdealPair> = g
        .meshes()
        .iter()
        .map(|m| {
            IdealPair::of_mesh(g, &m.label, h)
                .ok_or_else(|| RunError::Internal(format!("mesh {} has no geometry", m.label)))
        })
        .collect::<Result<_, RunError>>()?;
    let per_mesh = study::limits::limits_under_rules(&pairs, tol, rules)?;
    Ok(RuleLimits { per_mesh })
}

/// `lo .. hi` of the values given (`-` when none), and how many meshes have none.
fn envelope(values: impl Iterator<Item = Option<f64>>) -> (Option<(f64, f64)>, usize) {
    let mut range: Option<(f64, f64)> = None;
    let mut missing = 0;
    for v in values {
        match v {
            Some(v) => {
                range = Some(range.map_or((v, v), |(lo, hi)| (lo.min(v), hi.max(v))));
            }
            None => missing += 1,
        }
    }
    (range, missing)
}

fn show_envelope((range, missing): (Option<(f64, f64)>, usize)) -> String {
    let mut s = range.map_or_else(
        || "-".to_string(),
        |(lo, hi)| format!("{} .. {}", fmt_f64(lo, 1), fmt_f64(hi, 1)),
    );
    if missing > 0 {
        s.push_str(&format!(" ({missing} meshes without a limit in 0-100 %)"));
    }
    s
}

/// The limits table: per rule, the envelope over the meshes, and whether the paper's figure
/// lies inside it.
fn limits_table(g: &Gearing, rules: &[Rule], limits: &RuleLimits, tol: f64) -> Table {
    let jam_paper = crate::paper::get("clearance", "jam_below").map(|r| r.value);
    let dis_paper = crate::paper::get("clearance", "disengage_above").map(|r| r.value);
    let mut t = Table::new(
        format!(
            "Ideal meshes' clearance limits under each rule, over all {} meshes (one turn of the larger gear, located to {} % of h): ours (the paper's section 3 / Appendix II)",
            g.meshes().len(),
            fmt_f64(tol, 2)
        ),
        [
            "rule",
            "jams below G [% of h]",
            "paper's inside?",
            "disengages above G [% of h]",
            "paper's inside?",
        ],
    );
    let inside = |env: &(Option<(f64, f64)>, usize), paper: Option<f64>| match (env.0, paper) {
        (Some((lo, hi)), Some(p)) => {
            if p >= lo && p <= hi {
                format!("yes ({})", fmt_f64(p, 0))
            } else {
                format!("no ({})", fmt_f64(p, 0))
            }
        }
        _ => "-".into(),
    };
    for (r, rule) in rules.iter().enumerate() {
        let jam = envelope(limits.per_mesh.iter().map(|m| m[r].0));
        let dis = envelope(limits.per_mesh.iter().map(|m| m[r].1));
        t.row(vec![
            rule.label(),
            show_envelope(jam),
            inside(&jam, jam_paper),
            show_envelope(dis),
            inside(&dis, dis_paper),
        ]);
    }
    t.note("The paper's reading: no value below about 10 % (the teeth interfere at all times) and none above 87 % (section 3 says about 90 %) in its Figure IV, for b2-c1; read here as an envelope over every mesh: is the paper's figure between our smallest and largest limit?");
    t
}

/// Per mesh and rule: the limits, for the CSV.
fn limits_csv(g: &Gearing, rules: &[Rule], limits: &RuleLimits) -> String {
    let mut s = String::from("mesh,rule,jam_below_percent,disengage_above_percent\n");
    let show = |v: Option<f64>| v.map_or_else(String::new, |v| fmt_f64(v, 3));
    for (m, per_rule) in g.meshes().iter().zip(&limits.per_mesh) {
        for (rule, (jam, dis)) in rules.iter().zip(per_rule) {
            s.push_str(&registry::csv_row!(
                m.label,
                rule.label(),
                show(*jam),
                show(*dis)
            ));
        }
    }
    s
}

/// Every cell's counts under every rule, with the paper's and the test's verdict.
fn cells_csv(
    cells: &[(CellSpec, PaperCell)],
    countings: &[Counting],
    counts: &[Vec<Counts>],
) -> String {
    let mut s = String::from(
        "table,key,rule,drive,end,trials,jams,paper_jams,jams_consistent,disengagements,paper_disengagements,disengagements_consistent\n",
    );
    let show = |v: Option<u64>| v.map_or_else(String::new, |v| v.to_string());
    for ((_, p), per_rule) in cells.iter().zip(counts) {
        let paper = paper_counts(p.table, &p.key);
        for (counting, c) in countings.iter().zip(per_rule) {
            let verdict = |k: u64, q: Option<u64>| {
                q.map_or_else(String::new, |_| {
                    consistent_with_paper(k, c.trials, q).to_string()
                })
            };
            s.push_str(&registry::csv_row!(
                p.table,
                p.key,
                counting.rule.label(),
                counting.drive.name(),
                counting.end.name(),
                c.trials,
                c.jams,
                show(paper.0),
                verdict(c.jams, paper.0),
                c.disengagements,
                show(paper.1),
                verdict(c.disengagements, paper.1),
            ));
        }
    }
    s
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    let s = crate::settings::cells(ctx, &study::grids::TRIALS)?;
    let (g, trials) = (s.gearing(), s.trials);
    let tol = ctx.get(&LIMIT_TOLERANCE)?;
    let (rules, countings) = (every_rule()?, every_counting(s.end)?);
    let cells = all_cells(ctx, &s)?;
    let specs: Vec<CellSpec> = cells.iter().map(|(c, _)| c.clone()).collect();
    let counts = run_cells_counted(
        ctx.engine(),
        g,
        &specs,
        Some(&countings),
        trials,
        Purpose::Own,
    )?;
    let tallies = tallies(&cells, &counts, countings.len());
    let limits = ideal_limits(g, s.gearing.tooth_height, &rules, tol)?;
    let mut shares = shares_table(&countings, &tallies, trials);
    let (same_jams, same_dis) = agreement_between_rules(&counts, &countings);
    shares.note(format!(
        "Between the rules: with the listed driver driving, the same jam count under every rule in {same_jams} of {} cells, the same disengagement count in {same_dis}.",
        counts.len()
    ));
    let breakdowns = [Drive::Listed, Drive::Either]
        .into_iter()
        .filter_map(|d| counting_index(&countings, rules::DEFAULT, d, s.end))
        .map(|r| breakdown_table(&cells, &counts, &countings[r], r));
    let mut tables = vec![
        shares,
        regions_table(&cells, &counts, &countings),
        table4_sums_table(g, &cells, &counts, &countings, s.end),
    ];
    tables.extend(breakdowns);
    if s.end != End::Turn {
        for t in &mut tables {
            t.title = format!("{} [end: {}]", t.title, s.end.name());
        }
    }
    tables.push(limits_table(g, &rules, &limits, tol));
    Ok(Report {
        tables,
        files: vec![
            OutputFile::new(
                "event-rules-cells.csv",
                cells_csv(&cells, &countings, &counts),
            ),
            OutputFile::new("event-rules-limits.csv", limits_csv(g, &rules, &limits)),
        ],
        trials: counts.iter().map(|c| c[0].trials).sum(),
        engagements: counts.iter().map(|c| c[0].engagements).sum(),
        ..Default::default()
    })
}
