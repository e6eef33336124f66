//! What the `claims` ledger shows: a row per claim of the paper with the paper's figure, ours,
//! the verdict and its reason under each reading; the verdicts alone (the README's Findings);
//! Case B's meshes on the trains' picture; the tolerances behind C7 and C8 per gear.

use registry::{Report, Table};
use study::claims::{Ledger, MeshStanding};

use crate::train_picture::{Margin, MeshMargin};

/// What the ledger was asked to run, as its titles name it.
#[derive(Debug, Clone, Copy)]
pub struct Asked<'a> {
    /// Trials per cell of the per-mesh tables.
    pub trials: u64,
    /// Trials of Tables 1 and 2 and runs of the failure study; 0: each experiment's own.
    pub runs: u64,
    /// The error hypothesis.
    pub hypothesis: &'a str,
}

/// The ledger's report from its results `r`, run as `asked`: the ledger, the findings, Case B's
/// meshes on the trains' picture and the tolerances behind C7 and C8 in units of each gear.
pub fn report(r: &Ledger, asked: Asked<'_>) -> Report {
    let ledger = ledger_table(asked, r);
    let train = crate::train_picture::train_svg(
        &train::Gearing::freeth2006(),
        &margins(&r.case_b),
        "The Lunar, Metonic, Saros, Games and Exeligmos trains: each mesh under Edmunds' Case B at G = 40 %",
        &[
            (
                Margin::Clear,
                "keeps the paper's 1 % rule with room: no failure in the trials",
            ),
            (Margin::Near, "keeps the rule: at most 1 % of trials failed"),
            (
                Margin::Failing,
                "breaks the rule: more than 1 % of trials jammed or disengaged",
            ),
        ],
    );
    let mut tables = vec![ledger, findings(asked, r)];
    if let Some((t, split)) = &r.tolerances {
        tables.push(crate::units::derived_tolerances_table(
            "The tolerances behind C7 and C8 in units of each gear: Table 5's largest tolerable random error and systematic amplitude on top of it, as run".to_string(),
            t,
            *split,
        ));
    }
    Report {
        tables,
        files: vec![registry::OutputFile::new("train.svg", train)],
        ..Default::default()
    }
}

fn margins(case_b: &[MeshStanding]) -> Vec<MeshMargin> {
    case_b
        .iter()
        .map(|m| MeshMargin {
            label: m.mesh.clone(),
            verdict: Some(if !m.keeps_rule {
                Margin::Failing
            } else if m.failures > 0 {
                Margin::Near
            } else {
                Margin::Clear
            }),
            text: format!("B: {}/{}", m.failures, m.trials),
        })
        .collect()
}

/// The verdicts alone, one line per claim and a column per reading: the README's Findings.
fn findings(s: Asked<'_>, r: &Ledger) -> Table {
    let mut columns = vec!["claim".to_owned(), "the paper says".to_owned()];
    columns.extend(r.readings.iter().map(|name| match name.as_str() {
        "as run" => "verdict".to_owned(),
        other => format!("under {other}"),
    }));
    let mut t = Table::new(
        format!(
            "Findings: the paper's claims, our verdicts ({} trials per cell, {})",
            s.trials,
            runs_words(s.runs)
        ),
        columns,
    );
    for c in &r.claims {
        let mut row = vec![c.id.clone(), c.words.clone()];
        row.extend(c.under.iter().map(|v| v.words().to_owned()));
        t.row(row);
    }
    t.note("Each verdict, its figures and its reason: `cargo xtask run claims` (the first table of its report).");
    t
}

/// What the ledger's `runs` set, in the title's words.
fn runs_words(runs: u64) -> String {
    if runs == 0 {
        "Tables 1 and 2 and the failure study at their own counts".into()
    } else {
        format!("{runs} trials of Tables 1 and 2 and runs of the failure study")
    }
}

/// The ledger as a table: a row per claim, a column per reading.
fn ledger_table(s: Asked<'_>, r: &Ledger) -> Table {
    let mut columns = vec![
        "claim",
        "the paper says",
        "where",
        "paper",
        "ours",
        "verdict",
        "why",
    ]
    .into_iter()
    .map(String::from)
    .collect::<Vec<_>>();
    columns.extend(
        r.readings
            .iter()
            .skip(1)
            .map(|name| format!("under {name}")),
    );
    let mut t = Table::new(
        format!(
            "The paper's claims and what we find ({} trials per cell, {}, hypothesis {})",
            s.trials,
            runs_words(s.runs),
            s.hypothesis
        ),
        columns,
    );
    for c in &r.claims {
        let mut row = vec![
            c.id.clone(),
            c.words.clone(),
            c.place.clone(),
            c.judged.paper.clone(),
            c.judged.ours.clone(),
            c.judged.verdict.words().to_owned(),
            c.judged.reason.clone(),
        ];
        row.extend(c.under.iter().skip(1).map(|v| v.words().to_owned()));
        t.row(row);
    }
    t.note("Verdicts: holds, holds in part (some parts, or the direction but not the size), differs, not testable (the data the claim rests on is not available). Each is computed by the run from the other experiments' results; `why` gives the rule.");
    t
}
