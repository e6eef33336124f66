//! Claims that rest on the per-mesh jam tables: Table 3 by the paper's 1 % rule, and which
//! meshes fail most.

use std::fmt::Write as _;

use crate::cell::Counts;
use crate::results::{CaseTable, JamRow};
use crate::tolerance::{PAPER_RULE_PERCENT, keeps_rule};

use super::{Judged, Verdict};

/// The chance that a mechanism of these meshes fails somewhere in one turn, if each mesh fails as
/// often as its cell did and independently of the others: 1 − ∏(1 − rate) - the paper's own
/// reasoning in its footnote on the 1 % rule (15 meshes at 1 % each: about 14 %). With the range
/// the meshes' 95 % Wilson bounds give.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MechanismFailure {
    /// From each mesh's rate.
    pub p: f64,
    /// From each mesh's lower Wilson bound.
    pub lo: f64,
    /// From each mesh's upper Wilson bound.
    pub hi: f64,
}

/// The failures of a cell: trials with a jam or a disengagement. A table that gives only the two
/// counts (the paper's) is read as at least the larger of them.
fn failures(c: &Counts) -> u64 {
    c.failures.max(c.jams).max(c.disengagements)
}

/// [`MechanismFailure`] of one row of a table.
pub fn mechanism_failure(row: &JamRow) -> MechanismFailure {
    let (mut p, mut lo, mut hi) = (1.0, 1.0, 1.0);
    for c in &row.cells {
        let w = stats::wilson95(failures(c), c.trials);
        p *= 1.0 - failures(c) as f64 / c.trials.max(1) as f64;
        lo *= 1.0 - w.lo;
        hi *= 1.0 - w.hi;
    }
    MechanismFailure {
        p: 1.0 - p,
        lo: 1.0 - lo,
        hi: 1.0 - hi,
    }
}

/// The meshes of `row` (labelled by `meshes`) that break the paper's 1 % rule, most failures
/// first, with their failures.
pub fn breaking(meshes: &[String], row: &JamRow) -> Vec<(String, u64)> {
    let mut out: Vec<(String, u64)> = meshes
        .iter()
        .zip(&row.cells)
        .filter(|(_, c)| !keeps_rule(c.jams, c.disengagements, c.trials, PAPER_RULE_PERCENT))
        .map(|(m, c)| (m.clone(), failures(c)))
        .collect();
    out.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
    out
}

/// What a table says of each Case, in the terms of the claim.
struct CaseReading {
    /// Case A: the meshes that break the rule.
    a: Vec<(String, u64)>,
    /// Case B: the meshes that break the rule, worst first.
    b: Vec<(String, u64)>,
    /// Cases C and D: the chance the mechanism fails.
    c: MechanismFailure,
    d: MechanismFailure,
}

fn read_cases(t: &CaseTable) -> Option<CaseReading> {
    let row = |label: &str| t.table.rows.iter().find(|r| r.label == label);
    Some(CaseReading {
        a: breaking(&t.table.meshes, row("A")?),
        b: breaking(&t.table.meshes, row("B")?),
        c: mechanism_failure(row("C")?),
        d: mechanism_failure(row("D")?),
    })
}

fn listed(meshes: &[(String, u64)], at_most: usize) -> String {
    if meshes.is_empty() {
        return "none".into();
    }
    let mut s: Vec<String> = meshes
        .iter()
        .take(at_most)
        .map(|(m, n)| format!("{m} ({n})"))
        .collect();
    if meshes.len() > at_most {
        s.push(format!("{} more", meshes.len() - at_most));
    }
    s.join(", ")
}

fn describe(r: &CaseReading, trials: u64, intervals: bool) -> String {
    let mut s = format!(
        "A breaks the rule in {}; B in {}",
        listed(&r.a, 4),
        listed(&r.b, 4)
    );
    for (case, m) in [("C", r.c), ("D", r.d)] {
        let _ = write!(s, "; {case} fails a mechanism {:.0} %", 100.0 * m.p);
        if intervals {
            let _ = write!(s, " [{:.0} .. {:.0}]", 100.0 * m.lo, 100.0 * m.hi);
        }
    }
    let _ = write!(s, " (failures of {trials} trials)");
    s
}

/// C5: "Cases C and D ... unusable. Case A presents no issues, while Case B is also likely too
/// problematic due to two specific gear pairs (M3-E3 and E4-F1)" (section 5, Table 3), by the
/// paper's 1 % rule. Four parts, each judged on `ours`: no mesh of Case A breaks the rule; Case B's
/// two worst meshes are the two the paper's own table makes worst (and both break the rule); a
/// mechanism of Case C's and of Case D's meshes fails more often than not ([`mechanism_failure`],
/// the paper's footnote's reasoning; "unusable"). The paper's figure is the same reading of its own
/// Table 3.
pub fn cases_by_the_rule(ours: &CaseTable, paper: &CaseTable) -> Judged {
    let (Some(o), Some(p)) = (read_cases(ours), read_cases(paper)) else {
        return Judged {
            verdict: Verdict::NotTestable,
            ours: "no Cases A-D (the hypothesis takes no Case's errors)".into(),
            paper: String::new(),
            reason: "the run's hypothesis does not take Edmunds' Cases".into(),
        };
    };
    let worst = |r: &CaseReading| -> Vec<String> {
        let mut two: Vec<String> = r.b.iter().take(2).map(|(m, _)| m.clone()).collect();
        two.sort();
        two
    };
    let (named, ours_two) = (worst(&p), worst(&o));
    let parts = [
        Verdict::from_bool(o.a.is_empty()),
        Verdict::from_bool(named.len() == 2 && named == ours_two),
        Verdict::from_bool(o.c.p > 0.5),
        Verdict::from_bool(o.d.p > 0.5),
    ];
    let words = [
        "A gives no trouble",
        "B fails through the paper's two worst meshes",
        "C is unusable",
        "D is unusable",
    ];
    let held: Vec<&str> = words
        .iter()
        .zip(parts)
        .filter(|(_, v)| *v == Verdict::Holds)
        .map(|(w, _)| *w)
        .collect();
    let failed: Vec<&str> = words
        .iter()
        .zip(parts)
        .filter(|(_, v)| *v != Verdict::Holds)
        .map(|(w, _)| *w)
        .collect();
    let trials = ours.table.counts().map(|c| c.trials).max().unwrap_or(0);
    let reason = if failed.is_empty() {
        format!("{}: all four parts hold", held.join(", "))
    } else {
        format!(
            "holds: {}; not: {}",
            if held.is_empty() {
                "none".into()
            } else {
                held.join(", ")
            },
            failed.join(", ")
        )
    };
    Judged {
        verdict: Verdict::of_parts(&parts),
        ours: describe(&o, trials, true),
        paper: describe(&p, 200, false),
        reason,
    }
}

/// Each mesh's failures pooled over every row of the table, as a rate.
fn pooled_rates(t: &CaseTable) -> Vec<f64> {
    (0..t.table.meshes.len())
        .map(|m| {
            let (f, n) = t
                .table
                .rows
                .iter()
                .filter_map(|r| r.cells.get(m))
                .fold((0, 0), |(f, n), c| (f + failures(c), n + c.trials));
            f as f64 / n.max(1) as f64
        })
        .collect()
}

fn rank_reading(t: &CaseTable, size: &[f64]) -> Option<(stats::Spearman, Vec<String>)> {
    let rates = pooled_rates(t);
    let s = stats::spearman(size, &rates)?;
    let mut order: Vec<usize> = (0..rates.len()).collect();
    order.sort_by(|&a, &b| rates[b].total_cmp(&rates[a]));
    let top = order
        .iter()
        .take(4)
        .map(|&i| t.table.meshes[i].clone())
        .collect();
    Some((s, top))
}

/// C6: "gear pairs in which one of the gears has a large number of teeth and, therefore, a large
/// radius (such as D2-E2, M3-E3, E4-F1, and L2-M1) tend to produce more jamming and/or
/// disengagement events" (section 5, Table 3), because the eccentric half of the systematic error
/// grows with the radius. Judged on the mechanism it names: Spearman's rank correlation, over the
/// meshes, between `larger_radius` (mm, the larger tip radius of each mesh, in the table's mesh
/// order) and the mesh's failure rate pooled over Cases A-D. Holds if positive and significant at
/// 5 %, holds in part if positive only, differs otherwise.
pub fn large_gears_fail_more(ours: &CaseTable, paper: &CaseTable, larger_radius: &[f64]) -> Judged {
    let describe = |r: &Option<(stats::Spearman, Vec<String>)>| match r {
        Some((s, top)) => format!(
            "rank correlation of failures with the larger gear's radius {:.2} (p = {:.3}); most failing: {}",
            s.rho,
            s.p,
            top.join(", ")
        ),
        None => "no ranks (every mesh alike)".into(),
    };
    let (o, p) = (
        rank_reading(ours, larger_radius),
        rank_reading(paper, larger_radius),
    );
    let (verdict, reason) = match &o {
        Some((s, _)) if s.rho > 0.0 && s.p < 0.05 => (
            Verdict::Holds,
            "failures rise with the larger gear's radius, significantly at 5 %".to_owned(),
        ),
        Some((s, _)) if s.rho > 0.0 => (
            Verdict::HoldsInPart,
            format!(
                "failures rise with the radius, but not significantly (p = {:.2})",
                s.p
            ),
        ),
        _ => (
            Verdict::Differs,
            "failures do not rise with the larger gear's radius".to_owned(),
        ),
    };
    Judged {
        verdict,
        ours: describe(&o),
        paper: describe(&p),
        reason,
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::results::JamTable;

    fn cell(jams: u64) -> Counts {
        Counts {
            jams,
            disengagements: 0,
            failures: jams,
            trials: 200,
            engagements: 0,
        }
    }

    /// Three meshes; Case rows given as jams per mesh.
    fn table(rows: [[u64; 3]; 4]) -> CaseTable {
        let meshes = vec!["x".to_owned(), "y".to_owned(), "z".to_owned()];
        let labels = ["A", "B", "C", "D"].map(String::from).to_vec();
        let counts: Vec<Counts> = rows.iter().flatten().map(|&j| cell(j)).collect();
        CaseTable {
            table: JamTable::from_counts(meshes, labels, &counts),
            cases_apply: true,
            hypothesis: "edmunds-split".into(),
            clearance: 40.0,
        }
    }

    #[test]
    fn the_four_parts_of_the_cases_claim_each_move_the_verdict() {
        let paper = table([[0, 0, 0], [150, 90, 1], [200, 200, 5], [200, 200, 200]]);
        let same = cases_by_the_rule(&paper, &paper);
        assert_eq!(same.verdict, Verdict::Holds, "{same:?}");
        // Case A breaks the rule in one mesh: in part.
        let a_breaks = table([[3, 0, 0], [150, 90, 1], [200, 200, 5], [200, 200, 200]]);
        assert_eq!(
            cases_by_the_rule(&a_breaks, &paper).verdict,
            Verdict::HoldsInPart
        );
        // Case B worst through another mesh.
        let b_other = table([[0, 0, 0], [150, 1, 90], [200, 200, 5], [200, 200, 200]]);
        assert_eq!(
            cases_by_the_rule(&b_other, &paper).verdict,
            Verdict::HoldsInPart
        );
        // Nothing fails anywhere: A holds, the rest differ.
        let ideal = table([[0, 0, 0]; 4]);
        let j = cases_by_the_rule(&ideal, &paper);
        assert_eq!(j.verdict, Verdict::HoldsInPart, "{j:?}");
        assert!(j.reason.contains("not: B fails"), "{}", j.reason);
    }

    #[test]
    fn failures_rising_with_size_hold_and_falling_ones_differ() {
        let rising = table([[1, 5, 20], [2, 10, 40], [3, 20, 80], [4, 30, 160]]);
        let j = large_gears_fail_more(&rising, &rising, &[10.0, 20.0, 50.0]);
        // Three meshes: rho = 1, so p = 0.
        assert_eq!(j.verdict, Verdict::Holds, "{j:?}");
        let j = large_gears_fail_more(&rising, &rising, &[50.0, 20.0, 10.0]);
        assert_eq!(j.verdict, Verdict::Differs, "{j:?}");
    }

    #[test]
    fn a_mechanism_of_meshes_at_one_percent_fails_about_one_time_in_seven() {
        // The paper's footnote: 15 pairs at 1 % each, about 14 %.
        let row = JamRow {
            label: "x".into(),
            cells: vec![cell(2); 15],
        };
        let m = mechanism_failure(&row);
        assert!((m.p - 0.140).abs() < 0.001, "{m:?}");
        assert!(m.lo < m.p && m.p < m.hi);
    }
}
