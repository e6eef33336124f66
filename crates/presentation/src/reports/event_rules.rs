//! What `event-rules` shows: the paper's counts consistent with ours under each event rule and
//! drive, by table, by region and in Table 4's sums, the breakdowns of the default rule, each
//! rule's clearance limits of the ideal meshes, and the CSVs.

use registry::{OutputFile, Report, RunError, Table, fmt_f64};

use crate::cells::{consistent_with_paper, paper_counts, share};
use study::cell::Counts;
use study::drive::Drive;
use study::results::event_rules::{Consistency, Counted, EventRules, Reading, RuleCell};
use study::trial_end::End;

/// The report of `event-rules` from its results `r`, counted to `end`, the ideal limits located
/// to `limit_tolerance` % of h: the shares consistent with the paper under each reading, the
/// regions, Table 4's sums and the breakdowns, each rule's limits, and the CSVs.
pub fn report(r: &EventRules, end: End, limit_tolerance: f64) -> Result<Report, RunError> {
    let mut shares = shares_table(&r.countings, &r.consistency, r.trials);
    let (same_jams, same_dis) = agreement_between_rules(&r.cells, &r.countings);
    shares.note(format!(
        "Between the rules: with the listed driver driving, the same jam count under every rule in {same_jams} of {} cells, the same disengagement count in {same_dis}.",
        r.cells.len()
    ));
    let breakdowns = [Drive::Listed, Drive::Either]
        .into_iter()
        .filter_map(|d| counting_index(&r.countings, rules::DEFAULT, d, end))
        .map(|i| breakdown_table(&r.cells, &r.countings[i], i));
    let mut tables = vec![
        shares,
        regions_table(&r.cells, &r.countings),
        table4_sums_table(&r.meshes, &r.cells, &r.countings, end),
    ];
    tables.extend(breakdowns);
    if end != End::Turn {
        for t in &mut tables {
            t.title = format!("{} [end: {}]", t.title, end.name());
        }
    }
    tables.push(limits_table(r, limit_tolerance));
    let first = |c: &RuleCell| c.counts.first().copied().unwrap_or_default();
    Ok(Report {
        tables,
        files: vec![
            OutputFile::new("event-rules-cells.csv", cells_csv(&r.cells, &r.countings)),
            OutputFile::new("event-rules-limits.csv", limits_csv(r)),
        ],
        trials: r.cells.iter().map(|c| first(c).trials).sum(),
        engagements: r.cells.iter().map(|c| first(c).engagements).sum(),
        ..Default::default()
    })
}

/// The index of the reading of `rule` (by name) under `drive` and `end` in `countings`.
fn counting_index(countings: &[Reading], rule: &str, drive: Drive, end: End) -> Option<usize> {
    countings
        .iter()
        .position(|c| c.rule == rule && c.drive == drive.name() && c.end == end.name())
}

/// The counts of the paper that look copied from another cell, as `table KEY` (for a note).
fn copy_slips() -> Vec<String> {
    crate::paper::all()
        .iter()
        .filter(|r| r.suspect.is_some())
        .map(|r| format!("{} {}", r.experiment, r.quantity))
        .collect()
}

/// The shares table: one row per reading (rule and drive) at the run's end.
fn shares_table(countings: &[Reading], consistency: &[Consistency], trials: u64) -> Table {
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
    let end = countings
        .first()
        .map_or(End::Turn.name(), |c| c.end.as_str());
    for (counting, per_table) in countings.iter().zip(consistency) {
        if counting.end != end {
            continue;
        }
        let mut row = vec![counting.rule_label.clone(), counting.drive.clone()];
        let mut all = Counted::default();
        for tally in per_table.tables() {
            row.push(share(tally.jams_consistent, tally.jams_compared));
            row.push(share(tally.dis_consistent, tally.dis_compared));
            all.jams_consistent += tally.jams_consistent;
            all.jams_compared += tally.jams_compared;
            all.dis_consistent += tally.dis_consistent;
            all.dis_compared += tally.dis_compared;
        }
        let trusted = &per_table.without_copy_slips;
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
fn breakdown_table(cells: &[RuleCell], counting: &Reading, r: usize) -> Table {
    let mut groups: Vec<(String, Split)> = Vec::new();
    for p in cells {
        let paper = paper_counts(&p.table, &p.key);
        let c = &p.counts[r];
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
            counting.rule_label, counting.drive
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
fn agreement_between_rules(cells: &[RuleCell], countings: &[Reading]) -> (usize, usize) {
    let end = countings
        .first()
        .map_or(End::Turn.name(), |c| c.end.as_str());
    let listed: Vec<usize> = (0..countings.len())
        .filter(|&r| countings[r].drive == Drive::Listed.name() && countings[r].end == end)
        .collect();
    let same = |f: fn(&Counts) -> u64| {
        cells
            .iter()
            .filter(|c| {
                let per = &c.counts;
                listed.iter().all(|&r| f(&per[r]) == f(&per[listed[0]]))
            })
            .count()
    };
    (same(|c| c.jams), same(|c| c.disengagements))
}

/// The regions of the paper's cells, in print order: Table 4, each clearance, then Case D
/// (across clearances, its cells also counted in their clearance's column).
fn regions(cells: &[RuleCell]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for p in cells {
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
fn regions_table(cells: &[RuleCell], countings: &[Reading]) -> Table {
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
        for p in cells {
            let paper = paper_counts(&p.table, &p.key);
            let c = &p.counts[r];
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
            countings[r].rule_label.clone(),
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
    meshes: &[String],
    cells: &[RuleCell],
    countings: &[Reading],
    end: End,
) -> Table {
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
        .filter(|&i| cells[i].table == "table4")
        .collect();
    let paper_sum = |mesh: &str| -> u64 {
        table4
            .iter()
            .filter(|&&i| cells[i].mesh == mesh)
            .filter_map(|&i| paper_counts("table4", &cells[i].key).0)
            .sum()
    };
    for drive in Drive::ALL {
        let Some(r) = counting_index(countings, rules::DEFAULT, drive, end) else {
            continue;
        };
        let ours = |mesh: Option<&str>| -> u64 {
            table4
                .iter()
                .filter(|&&i| mesh.is_none_or(|m| cells[i].mesh == m))
                .map(|&i| cells[i].counts[r].jams)
                .sum()
        };
        let mut row = vec![drive.name().to_owned()];
        for m in meshes {
            row.push(format!("{} ({})", ours(Some(m)), paper_sum(m)));
        }
        let all_paper: u64 = meshes.iter().map(|m| paper_sum(m)).sum();
        row.push(format!("{} ({all_paper})", ours(None)));
        t.row(row);
    }
    t.note("Each sum adds a mesh's jam counts over Table 4's rows (random error 0.035-0.065 of the pitch, no systematic error, G = 40 %), each of 200 trials. The paper's sums are of its own counts, printed in brackets.");
    t
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
fn limits_table(r: &EventRules, tol: f64) -> Table {
    let jam_paper = crate::paper::get("clearance", "jam_below").map(|r| r.value);
    let dis_paper = crate::paper::get("clearance", "disengage_above").map(|r| r.value);
    let mut t = Table::new(
        format!(
            "Ideal meshes' clearance limits under each rule, over all {} meshes (one turn of the larger gear, located to {} % of h): ours (the paper's section 3 / Appendix II)",
            r.meshes.len(),
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
    for (i, rule) in r.rules.iter().enumerate() {
        let jam = envelope(r.limits.iter().map(|m| m[i].jam_below));
        let dis = envelope(r.limits.iter().map(|m| m[i].disengage_above));
        t.row(vec![
            rule.clone(),
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
fn limits_csv(r: &EventRules) -> String {
    let mut s = String::from("mesh,rule,jam_below_percent,disengage_above_percent\n");
    let show = |v: Option<f64>| v.map_or_else(String::new, |v| fmt_f64(v, 3));
    for (mesh, per_rule) in r.meshes.iter().zip(&r.limits) {
        for (rule, l) in r.rules.iter().zip(per_rule) {
            s.push_str(&registry::csv_row!(
                mesh,
                rule,
                show(l.jam_below),
                show(l.disengage_above)
            ));
        }
    }
    s
}

/// Every cell's counts under every rule, with the paper's and the test's verdict.
fn cells_csv(cells: &[RuleCell], countings: &[Reading]) -> String {
    let mut s = String::from(
        "table,key,rule,drive,end,trials,jams,paper_jams,jams_consistent,disengagements,paper_disengagements,disengagements_consistent\n",
    );
    let show = |v: Option<u64>| v.map_or_else(String::new, |v| v.to_string());
    for p in cells {
        let paper = paper_counts(&p.table, &p.key);
        for (counting, c) in countings.iter().zip(&p.counts) {
            let verdict = |k: u64, q: Option<u64>| {
                q.map_or_else(String::new, |_| {
                    consistent_with_paper(k, c.trials, q).to_string()
                })
            };
            s.push_str(&registry::csv_row!(
                p.table,
                p.key,
                counting.rule_label,
                counting.drive,
                counting.end,
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
