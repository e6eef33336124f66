//! Claims that rest on the largest tolerable errors: the random error of Table 4 by the 1 % rule,
//! the systematic error of Table 5 on top of it, and Figure 6's comparison with Edmunds'
//! measurements.

use crate::cell::Counts;
use crate::results::{DerivedTolerances, GearTolerances, RandomErrorTable, RandomFrom};
use crate::tolerance::largest_tolerable;

use super::{Judged, Verdict};

/// A mesh's largest tolerable value along a grid by the paper's rule (jams within the rule at
/// every value up to it), and the cell that decides it: the first value that breaks the rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tolerable {
    /// The largest tolerable value (`None`: even the grid's smallest breaks the rule).
    pub value: Option<f64>,
    /// The first value breaking the rule with its counts (`None`: the whole grid keeps it).
    pub broken_at: Option<(f64, Counts)>,
}

/// [`Tolerable`] of one column of a grid: (value, counts) in ascending order of the value.
pub fn tolerable(column: &[(f64, Counts)], rule_percent: f64) -> Tolerable {
    let trials = column.iter().map(|(_, c)| c.trials).max().unwrap_or(0);
    let jams: Vec<(f64, u64)> = column.iter().map(|(v, c)| (*v, c.jams)).collect();
    let value = largest_tolerable(&jams, trials, rule_percent);
    let broken_at = column
        .iter()
        .find(|(v, _)| value.is_none_or(|t| *v > t))
        .copied();
    Tolerable { value, broken_at }
}

impl Tolerable {
    /// The value in `unit` with the deciding cell's share and its 95 % Wilson interval, e.g.
    /// `0.035 (at 0.040: 5/200 jammed, 2.5 % [1.1 .. 5.7])`.
    pub fn words(&self, decimals: usize, unit: &str) -> String {
        let v = show(self.value, decimals, unit);
        match self.broken_at {
            Some((at, c)) => {
                let w = stats::wilson95(c.jams, c.trials);
                format!(
                    "{v} (at {at:.decimals$}{unit}: {}/{} jammed, {:.1} % [{:.1} .. {:.1}])",
                    c.jams,
                    c.trials,
                    100.0 * c.jams as f64 / c.trials.max(1) as f64,
                    100.0 * w.lo,
                    100.0 * w.hi
                )
            }
            None => format!("{v} (the whole grid keeps the rule)"),
        }
    }
}

/// Each mesh's largest tolerable random error from Table 4's cells, in the table's mesh order.
pub fn random_tolerances(t: &RandomErrorTable, rule_percent: f64) -> Vec<(String, Tolerable)> {
    t.table
        .meshes
        .iter()
        .enumerate()
        .map(|(m, mesh)| {
            let column: Vec<(f64, Counts)> = t
                .random
                .iter()
                .zip(&t.table.rows)
                .filter_map(|(&e, r)| r.cells.get(m).map(|c| (e, *c)))
                .collect();
            (mesh.clone(), tolerable(&column, rule_percent))
        })
        .collect()
}

/// The smallest step of an ascending grid (0 for fewer than two values).
fn grid_step(values: &[f64]) -> f64 {
    values
        .windows(2)
        .map(|w| w[1] - w[0])
        .reduce(f64::min)
        .unwrap_or(0.0)
}

/// Within one step of the grid (values read off a grid can be no closer).
fn within_a_step(ours: Option<f64>, paper: Option<f64>, step: f64) -> bool {
    match (ours, paper) {
        (Some(o), Some(p)) => (o - p).abs() <= step + 1e-9,
        _ => false,
    }
}

fn value_of<'a>(row: &'a [(String, Tolerable)], mesh: &str) -> Option<&'a Tolerable> {
    row.iter().find(|(m, _)| m == mesh).map(|(_, t)| t)
}

fn paper_of(row: &[(String, Option<f64>)], mesh: &str) -> Option<f64> {
    row.iter().find(|(m, _)| m == mesh).and_then(|(_, v)| *v)
}

/// The smallest of the values (a value below the grid is the smallest), with the meshes at it.
fn smallest(row: &[(String, Option<f64>)]) -> (Option<f64>, Vec<String>) {
    let low = row
        .iter()
        .map(|(_, v)| *v)
        .min_by(|a, b| match (a, b) {
            (None, None) => std::cmp::Ordering::Equal,
            (None, _) => std::cmp::Ordering::Less,
            (_, None) => std::cmp::Ordering::Greater,
            (Some(x), Some(y)) => x.total_cmp(y),
        })
        .flatten();
    let at = row
        .iter()
        .filter(|(_, v)| match (v, low) {
            (Some(v), Some(l)) => (v - l).abs() < 1e-9,
            (None, None) => true,
            _ => false,
        })
        .map(|(m, _)| m.clone())
        .collect();
    (low, at)
}

fn show(v: Option<f64>, decimals: usize, unit: &str) -> String {
    v.map_or_else(
        || "below the grid".into(),
        |v| format!("{v:.decimals$}{unit}"),
    )
}

/// The words of a judge with parts: which parts hold and which do not.
fn parts_reason(words: &[&str], parts: &[Verdict]) -> String {
    let pick = |hold: bool| -> Vec<&str> {
        words
            .iter()
            .zip(parts)
            .filter(|(_, v)| (**v == Verdict::Holds) == hold)
            .map(|(w, _)| *w)
            .collect()
    };
    let (held, not) = (pick(true), pick(false));
    if not.is_empty() {
        format!("all hold: {}", held.join("; "))
    } else if held.is_empty() {
        format!("none holds: {}", not.join("; "))
    } else {
        format!("holds: {}; not: {}", held.join("; "), not.join("; "))
    }
}

/// The meshes a claim on tolerances names: the one the paper makes the least tolerant and the
/// one it makes the most.
#[derive(Debug, Clone, Copy)]
pub struct Named<'a> {
    /// The least tolerant mesh the claim names (`m2-n1`, `d2-e2`).
    pub least: &'a str,
    /// The most tolerant mesh it names (`b2-c1`, `e1-b3`).
    pub most: &'a str,
}

/// C7: "the uniform random error ... must not exceed 0.04 ... m2-n1 ... no more than 0.04 ...
/// b2-c1 up to 0.055" (section 5, Table 4, Table 5's row E. max). Ours: each mesh's largest
/// tolerable random error read from Table 4's cells (`ours`) by the rule of `rule_percent` %,
/// each with the cell that breaks it and that cell's 95 % Wilson interval; the paper's, its E. max
/// row (`paper`, by mesh). Three parts: no mesh of ours tolerates less than the paper's smallest
/// E. max; the least tolerant mesh named tolerates no more than the paper's value for it; the
/// most tolerant one named is within one grid step of the paper's.
pub fn random_limits(
    ours: &RandomErrorTable,
    paper: &[(String, Option<f64>)],
    named: Named,
    rule_percent: f64,
) -> Judged {
    let row = random_tolerances(ours, rule_percent);
    let values: Vec<(String, Option<f64>)> =
        row.iter().map(|(m, t)| (m.clone(), t.value)).collect();
    let (our_low, our_at) = smallest(&values);
    let (paper_low, paper_at) = smallest(paper);
    let step = grid_step(&ours.random);
    let least = value_of(&row, named.least);
    let most = value_of(&row, named.most);
    let parts = [
        Verdict::from_bool(match (our_low, paper_low) {
            (Some(o), Some(p)) => o >= p - 1e-9,
            _ => false,
        }),
        Verdict::from_bool(
            least
                .and_then(|t| t.value)
                .is_none_or(|o| paper_of(paper, named.least).is_some_and(|p| o <= p + 1e-9)),
        ),
        Verdict::from_bool(within_a_step(
            most.and_then(|t| t.value),
            paper_of(paper, named.most),
            step,
        )),
    ];
    let trials = ours.table.counts().map(|c| c.trials).max().unwrap_or(0);
    let named_words =
        |t: Option<&Tolerable>| t.map_or_else(|| "not run".into(), |t| t.words(3, ""));
    Judged {
        verdict: Verdict::of_parts(&parts),
        ours: format!(
            "smallest E. max {} ({}); {} {}; {} {} (rule {rule_percent} % of {trials} trials)",
            show(our_low, 3, ""),
            our_at.join(", "),
            named.least,
            named_words(least),
            named.most,
            named_words(most)
        ),
        paper: format!(
            "smallest E. max {} ({}); {} {}; {} {}",
            show(paper_low, 3, ""),
            paper_at.join(", "),
            named.least,
            show(paper_of(paper, named.least), 3, ""),
            named.most,
            show(paper_of(paper, named.most), 3, "")
        ),
        reason: parts_reason(
            &[
                "no mesh below the paper's smallest E. max",
                &format!("{} no more than the paper's", named.least),
                &format!("{} within a grid step of the paper's", named.most),
            ],
            &parts,
        ),
    }
}

/// Each mesh's largest tolerable systematic amplitude in Table 5's rows, with the deciding cell.
pub fn systematic_tolerances(t: &DerivedTolerances, rule_percent: f64) -> Vec<(String, Tolerable)> {
    t.meshes
        .iter()
        .enumerate()
        .map(|(m, mesh)| {
            let column: Vec<(f64, Counts)> = t
                .rows
                .iter()
                .filter_map(|r| r.cells.get(m).copied().flatten().map(|c| (r.systematic, c)))
                .collect();
            let found = if mesh.random.is_none() || column.is_empty() {
                Tolerable {
                    value: None,
                    broken_at: None,
                }
            } else {
                tolerable(&column, rule_percent)
            };
            (mesh.mesh.clone(), found)
        })
        .collect()
}

/// C8: "the systematic error ... from 0.1° (d2-e2) to 0.6° (e1-b3)" (section 5, Table 5). Ours:
/// each mesh's largest tolerable systematic amplitude in Table 5's rows (`ours`) by the rule,
/// with the cell that breaks it; the paper's, the same rule on its own counts (`paper`, by mesh).
/// Like for like only where the random E. max under it is the paper's row (`--set emax=paper`):
/// the figure says which. Three parts: no mesh of ours tolerates less than the paper's smallest;
/// the two named meshes within one grid step of the paper's values for them.
pub fn systematic_limits(
    ours: &DerivedTolerances,
    paper: &[(String, Option<f64>)],
    named: Named,
    rule_percent: f64,
) -> Judged {
    let row = systematic_tolerances(ours, rule_percent);
    let values: Vec<(String, Option<f64>)> =
        row.iter().map(|(m, t)| (m.clone(), t.value)).collect();
    let (our_low, our_at) = smallest(&values);
    let (paper_low, _) = smallest(paper);
    let below = values
        .iter()
        .filter(|(_, v)| match (v, paper_low) {
            (Some(v), Some(p)) => *v < p - 1e-9,
            (None, _) => true,
            _ => false,
        })
        .map(|(m, _)| m.clone())
        .collect::<Vec<_>>();
    let step = grid_step(&ours.systematic_values());
    let pick = |mesh: &str| value_of(&row, mesh);
    let parts = [
        Verdict::from_bool(paper_low.is_some() && below.is_empty()),
        Verdict::from_bool(within_a_step(
            pick(named.least).and_then(|t| t.value),
            paper_of(paper, named.least),
            step,
        )),
        Verdict::from_bool(within_a_step(
            pick(named.most).and_then(|t| t.value),
            paper_of(paper, named.most),
            step,
        )),
    ];
    let like_for_like = ours
        .meshes
        .iter()
        .all(|m| m.random_from == RandomFrom::Paper);
    let words = |t: Option<&Tolerable>| t.map_or_else(|| "not run".into(), |t| t.words(1, "°"));
    Judged {
        verdict: Verdict::of_parts(&parts),
        ours: format!(
            "smallest {} ({}); below the paper's smallest: {}; {} {}; {} {} ({})",
            show(our_low, 1, "°"),
            our_at.join(", "),
            if below.is_empty() {
                "none".to_owned()
            } else {
                below.join(", ")
            },
            named.least,
            words(pick(named.least)),
            named.most,
            words(pick(named.most)),
            if like_for_like {
                "at the paper's E. max, like for like"
            } else {
                "at our own E. max from Table 4, not the paper's"
            }
        ),
        paper: format!(
            "smallest {}; {} {}; {} {} (by the rule on its own counts)",
            show(paper_low, 1, "°"),
            named.least,
            show(paper_of(paper, named.least), 1, "°"),
            named.most,
            show(paper_of(paper, named.most), 1, "°")
        ),
        reason: parts_reason(
            &[
                "no mesh below the paper's smallest",
                &format!("{} within a grid step", named.least),
                &format!("{} within a grid step", named.most),
            ],
            &parts,
        ),
    }
}

/// C9: "the actual gear errors typically exceed the tolerable limits" (section 5, Figure 6).
/// Testable where Figure 6 ran with a measured table (`measured`): holds if more than half of the
/// measured gears exceed their tolerable random error (a gear below the grid exceeds it), in part
/// if some do, differs if none. Without one: not testable, and the figure shows our tolerable
/// range beside Edmunds' published range of random errors (`edmunds`, from, to).
pub fn measured_exceed_tolerable(ours: &GearTolerances, edmunds: (f64, f64)) -> Judged {
    let tolerable: Vec<f64> = ours.gears.iter().filter_map(|g| g.tolerable).collect();
    let lo = tolerable.iter().copied().reduce(f64::min);
    let hi = tolerable.iter().copied().reduce(f64::max);
    let below_grid = ours.gears.iter().filter(|g| g.tolerable.is_none()).count();
    let under_from = ours
        .gears
        .iter()
        .filter(|g| g.tolerable.is_none_or(|t| t < edmunds.0))
        .count();
    let range = format!(
        "tolerable random error {} to {} of the pitch over {} gears ({below_grid} below the grid); {under_from} tolerate less than Edmunds' lowest, {:.2}",
        show(lo, 3, ""),
        show(hi, 3, ""),
        ours.gears.len(),
        edmunds.0
    );
    let paper = format!(
        "measured errors typically above the tolerable; Edmunds' range {:.2} to {:.2} of the pitch",
        edmunds.0, edmunds.1
    );
    let measured: Vec<(&str, f64, Option<f64>)> = ours
        .gears
        .iter()
        .filter_map(|g| g.measured.map(|m| (g.paper_name.as_str(), m, g.tolerable)))
        .collect();
    if measured.is_empty() {
        return Judged {
            verdict: Verdict::NotTestable,
            ours: range,
            paper,
            reason: "Edmunds' per-gear measurements are not published openly, so no gear's can be held against its tolerable error; give them with --set measured=FILE".into(),
        };
    }
    let exceed: Vec<&str> = measured
        .iter()
        .filter(|(_, m, t)| t.is_none_or(|t| *m > t))
        .map(|(g, _, _)| *g)
        .collect();
    let verdict = if 2 * exceed.len() > measured.len() {
        Verdict::Holds
    } else if exceed.is_empty() {
        Verdict::Differs
    } else {
        Verdict::HoldsInPart
    };
    Judged {
        verdict,
        ours: format!(
            "{} of {} measured gears exceed their tolerable error ({}); {range}",
            exceed.len(),
            measured.len(),
            exceed.join(", ")
        ),
        paper,
        reason: "more than half of the measured gears above their tolerable random error holds; some, in part".into(),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use crate::results::{GearRandom, JamRow, JamTable, MeshTolerance, SystematicRow};

    fn cell(jams: u64) -> Counts {
        Counts {
            jams,
            disengagements: 0,
            failures: jams,
            trials: 200,
            engagements: 0,
        }
    }

    /// Table 4 at 0.035, 0.040, ..., 0.055 for meshes m2-n1 and b2-c1, jams per row.
    fn table4(jams: &[[u64; 2]]) -> RandomErrorTable {
        let random: Vec<f64> = (0..jams.len()).map(|i| 0.035 + 0.005 * i as f64).collect();
        RandomErrorTable {
            random: random.clone(),
            table: JamTable {
                meshes: vec!["m2-n1".into(), "b2-c1".into()],
                rows: jams
                    .iter()
                    .zip(&random)
                    .map(|(j, e)| JamRow {
                        label: format!("{e:.3}"),
                        cells: j.iter().map(|&k| cell(k)).collect(),
                    })
                    .collect(),
            },
            clearance: 40.0,
            gears: Vec::new(),
        }
    }

    const NAMED: Named = Named {
        least: "m2-n1",
        most: "b2-c1",
    };

    #[test]
    fn the_random_limits_hold_at_the_papers_values_and_differ_far_from_them() {
        let paper = vec![
            ("m2-n1".to_owned(), Some(0.040)),
            ("b2-c1".to_owned(), Some(0.055)),
        ];
        // m2-n1 breaks the rule at 0.045, b2-c1 at 0.060: the paper's E. max exactly.
        let like = table4(&[[0, 0], [2, 0], [5, 1], [9, 1], [20, 2], [30, 9]]);
        let j = random_limits(&like, &paper, NAMED, 1.0);
        assert_eq!(j.verdict, Verdict::Holds, "{j:?}");
        assert!(
            j.ours.contains("m2-n1 0.040 (at 0.045: 5/200"),
            "{}",
            j.ours
        );
        // Nothing jams: every mesh tolerates the whole grid, m2-n1 more than the paper allows
        // (b2-c1 one step above the paper's, within a step).
        let ideal = table4(&[[0, 0]; 6]);
        let j = random_limits(&ideal, &paper, NAMED, 1.0);
        assert_eq!(j.verdict, Verdict::HoldsInPart, "{j:?}");
        // Everything jams: both below the grid.
        let worn = table4(&[[50, 50]; 6]);
        let j = random_limits(&worn, &paper, NAMED, 1.0);
        assert_eq!(j.verdict, Verdict::HoldsInPart, "{j:?}");
        assert!(j.reason.contains("not: no mesh below"), "{}", j.reason);
    }

    fn table5(jams: &[[u64; 2]], from: RandomFrom) -> DerivedTolerances {
        let meshes = ["d2-e2", "e1-b3"];
        DerivedTolerances {
            random_grid: RandomErrorTable::default(),
            meshes: meshes
                .iter()
                .map(|m| MeshTolerance {
                    mesh: (*m).into(),
                    random: Some(0.045),
                    random_from: from,
                    systematic: None,
                })
                .collect(),
            rows: jams
                .iter()
                .enumerate()
                .map(|(i, j)| SystematicRow {
                    systematic: 0.1 * (i + 1) as f64,
                    cells: j.iter().map(|&k| Some(cell(k))).collect(),
                })
                .collect(),
        }
    }

    #[test]
    fn the_systematic_limits_hold_at_the_papers_values_and_differ_below_them() {
        let named = Named {
            least: "d2-e2",
            most: "e1-b3",
        };
        let paper = vec![
            ("d2-e2".to_owned(), Some(0.1)),
            ("e1-b3".to_owned(), Some(0.6)),
        ];
        let rows = |d: [u64; 7], e: [u64; 7]| -> Vec<[u64; 2]> {
            d.iter().zip(e).map(|(&a, b)| [a, b]).collect()
        };
        let like = table5(
            &rows([1, 5, 9, 9, 9, 9, 9], [0, 0, 1, 1, 2, 2, 9]),
            RandomFrom::Paper,
        );
        let j = systematic_limits(&like, &paper, named, 1.0);
        assert_eq!(j.verdict, Verdict::Holds, "{j:?}");
        assert!(j.ours.contains("like for like"), "{}", j.ours);
        // d2-e2 fails at the smallest amplitude, e1-b3 at 0.2: both far below the paper's.
        let worse = table5(
            &rows([5, 9, 9, 9, 9, 9, 9], [0, 9, 9, 9, 9, 9, 9]),
            RandomFrom::Grid,
        );
        let j = systematic_limits(&worse, &paper, named, 1.0);
        assert_eq!(j.verdict, Verdict::Differs, "{j:?}");
        assert!(j.ours.contains("not the paper's"), "{}", j.ours);
    }

    fn gears(values: &[(Option<f64>, Option<f64>)]) -> GearTolerances {
        GearTolerances {
            random_grid: RandomErrorTable::default(),
            gears: values
                .iter()
                .enumerate()
                .map(|(i, &(tolerable, measured))| GearRandom {
                    gear: format!("g{i}"),
                    paper_name: format!("g{i}"),
                    source: String::new(),
                    meshes: vec![],
                    tolerable,
                    measured,
                })
                .collect(),
            measured: None,
        }
    }

    #[test]
    fn measured_errors_are_judged_only_where_given() {
        let none = gears(&[(Some(0.04), None), (None, None)]);
        let j = measured_exceed_tolerable(&none, (0.04, 0.08));
        assert_eq!(j.verdict, Verdict::NotTestable);
        assert!(
            j.ours
                .contains("0.040 to 0.040 of the pitch over 2 gears (1 below"),
            "{}",
            j.ours
        );
        let high = gears(&[(Some(0.04), Some(0.06)), (Some(0.05), Some(0.07))]);
        assert_eq!(
            measured_exceed_tolerable(&high, (0.04, 0.08)).verdict,
            Verdict::Holds
        );
        let low = gears(&[(Some(0.04), Some(0.02)), (Some(0.05), Some(0.03))]);
        assert_eq!(
            measured_exceed_tolerable(&low, (0.04, 0.08)).verdict,
            Verdict::Differs
        );
    }
}
