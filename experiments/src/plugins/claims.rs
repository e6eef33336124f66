//! `claims`: the paper's claims, each with the paper's figure, ours (with its uncertainty) and a
//! verdict with its reason, computed from the other experiments' typed results; one column per
//! reading of the paper says whether the verdict changes under it.
//!
//! The ledger runs nothing of its own: it asks the registry for the results of the experiments a
//! claim rests on (Table 3, Table 4, ...) under each reading, read from the results folder when a
//! run with the same settings and seed is there, else computed (once per process).

use registry::{Param, Place, Report, Run, RunError, Table};
use serde::{Deserialize, Serialize};
use study::claims::{ClaimRow, Judged, Ledger as Results, MeshStanding};
use study::errors::ErrorParams;
use study::results::CaseTable;

use presentation::train_picture::{Margin, MeshMargin};

/// The ledger's settings: the trials of the per-mesh tables it reads, and the error hypothesis
/// their gears are made with (the paper's, Edmunds' split, by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell of the per-mesh tables ([`study::grids::TRIALS`]).
    #[param(study::grids::TRIALS)]
    pub trials: u64,
    /// The hypothesis (and its parameters) the per-mesh tables' gears are made with.
    #[group]
    pub errors: ErrorParams,
}

/// One reading of the paper: the settings it changes in every experiment that takes them.
struct Reading {
    /// As the column is headed.
    name: &'static str,
    /// (declaration, value) pairs.
    sets: &'static [(&'static Param, &'static str)],
}

/// The readings the project has, each a column of the ledger: the run as the paper's defaults
/// read it, then which gear drives, where a trial's counting ends and the paper's own E. max row.
const READINGS: [Reading; 4] = [
    Reading {
        name: "as run",
        sets: &[],
    },
    Reading {
        name: "drive=either",
        sets: &[(&study::drive::PARAM, "either")],
    },
    Reading {
        name: "end=first-disengagement",
        sets: &[(&study::trial_end::PARAM, "first-disengagement")],
    },
    Reading {
        name: "emax=paper",
        sets: &[(&crate::emax::EMAX, "paper")],
    },
];

/// A claim of the paper: our words for it, where the paper makes it, and its judge.
struct Claim {
    id: &'static str,
    words: &'static str,
    place: &'static str,
    judge: fn(&Evidence) -> Result<Judged, RunError>,
}

/// The claims, in the order the paper's argument makes them.
const CLAIMS: &[Claim] = &[
    Claim {
        id: "C5",
        words: "by the 1 % rule, Cases C and D are unusable, Case A has no issues, Case B is problematic through m3-e3 and e4-f1",
        place: "section 5, Table 3",
        judge: |e| {
            let paper = paper_case_table(&e.table3()?);
            Ok(study::claims::cells::cases_by_the_rule(
                &e.table3()?,
                &paper,
            ))
        },
    },
    Claim {
        id: "C6",
        words: "pairs with a large gear (d2-e2, m3-e3, e4-f1, l2-m1) fail more, as the eccentricity grows with the radius",
        place: "section 5, Table 3's text",
        judge: |e| {
            let ours = e.table3()?;
            let radii = larger_radii(&ours)?;
            Ok(study::claims::cells::large_gears_fail_more(
                &ours,
                &paper_case_table(&ours),
                &radii,
            ))
        },
    },
];

/// What a claim's judge may ask for: the results of the experiments it rests on, under one
/// reading.
struct Evidence<'a> {
    run: &'a Run<'a>,
    settings: &'a Settings,
    reading: &'a Reading,
}

impl Evidence<'_> {
    /// Experiment `id`'s results under the ledger's settings and this reading (each set only
    /// where the experiment takes it).
    fn results<T: serde::de::DeserializeOwned>(&self, id: &str) -> Result<T, RunError> {
        let entry = registry::experiments()
            .map_err(|e| RunError::Internal(e.to_string()))?
            .get(id)
            .copied()
            .ok_or_else(|| RunError::Internal(format!("claims: no experiment `{id}`")))?;
        let mut sets: Vec<(&Param, String)> = vec![
            (&study::grids::TRIALS, self.settings.trials.to_string()),
            (
                &study::errors::PARAM,
                self.settings.errors.hypothesis.clone(),
            ),
            (
                &study::errors::PARAMS_PARAM,
                self.settings.errors.hypothesis_params.clone(),
            ),
        ];
        sets.extend(self.reading.sets.iter().map(|&(p, v)| (p, v.to_owned())));
        sets.retain(|(p, _)| entry.declares(p));
        Ok(self.run.results_of::<T>(id, &sets)?.0)
    }

    fn table3(&self) -> Result<CaseTable, RunError> {
        self.results("table3")
    }
}

/// The paper's Table 3, laid out as ours is (its meshes and Cases), from the reference file.
fn paper_case_table(ours: &CaseTable) -> CaseTable {
    let mut paper = ours.clone();
    for row in &mut paper.table.rows {
        for (mesh, cell) in ours.table.meshes.iter().zip(&mut row.cells) {
            let (j, d) =
                presentation::cells::paper_counts("table3", &format!("{}.{mesh}", row.label));
            *cell = study::cell::Counts {
                jams: j.unwrap_or(0),
                disengagements: d.unwrap_or(0),
                failures: j.unwrap_or(0).max(d.unwrap_or(0)),
                trials: study::cell::PAPER_TRIALS,
                engagements: 0,
            };
        }
    }
    paper
}

/// Each mesh's larger tip radius (mm) in the default gearing, in the table's mesh order.
fn larger_radii(t: &CaseTable) -> Result<Vec<f64>, RunError> {
    let g = train::Gearing::freeth2006();
    t.table
        .meshes
        .iter()
        .map(|label| {
            let m = g.mesh(label).ok_or_else(|| {
                RunError::Internal(format!("claims: mesh {label} is not in freeth2006"))
            })?;
            let r = |gear: &str| g.tip_radius(gear).unwrap_or(0.0);
            Ok(r(&m.driver).max(r(&m.driven)))
        })
        .collect()
}

/// The ledger of the paper's claims.
pub struct Claims;

impl registry::Experiment for Claims {
    const ID: &'static str = "claims";
    const TITLE: &'static str = "What the paper claims, and what we find: each claim with the paper's figure, ours and a verdict, under each reading";
    const PAPER_ITEM: &'static str = "Abstract, sections 2-6 (the claims)";
    const PLACE: Place = Place::Paper(0);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        let mut claims = Vec::with_capacity(CLAIMS.len());
        for c in CLAIMS {
            claims.push(judge_everywhere(c, s, run)?);
        }
        let as_run = Evidence {
            run,
            settings: s,
            reading: &READINGS[0],
        };
        Ok(Results {
            claims,
            readings: READINGS.iter().map(|r| r.name.to_owned()).collect(),
            case_b: case_b(&as_run.table3()?),
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let ledger = ledger_table(s, r);
        let train = presentation::train_picture::train_svg(
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
        Ok(Report {
            tables: vec![ledger],
            files: vec![registry::OutputFile::new("train.svg", train)],
            ..Default::default()
        })
    }
}

registry::register!(Claims);

/// Claim `c` judged as run and its verdict under every other reading.
fn judge_everywhere(c: &Claim, s: &Settings, run: &Run) -> Result<ClaimRow, RunError> {
    let mut under = Vec::with_capacity(READINGS.len());
    let mut judged = None;
    for reading in &READINGS {
        let j = (c.judge)(&Evidence {
            run,
            settings: s,
            reading,
        })?;
        under.push(j.verdict);
        judged.get_or_insert(j);
    }
    let judged = judged.ok_or_else(|| RunError::Internal("claims: no reading".into()))?;
    Ok(ClaimRow {
        id: c.id.to_owned(),
        words: c.words.to_owned(),
        place: c.place.to_owned(),
        judged,
        under,
    })
}

/// Case B's meshes with their failures.
fn case_b(t: &CaseTable) -> Vec<MeshStanding> {
    let Some(row) = t.table.rows.iter().find(|r| r.label == "B") else {
        return Vec::new();
    };
    t.table
        .meshes
        .iter()
        .zip(&row.cells)
        .map(|(m, c)| MeshStanding {
            mesh: m.clone(),
            failures: c.failures,
            trials: c.trials,
            keeps_rule: presentation::cells::keeps_rule(
                c.jams,
                c.disengagements,
                c.trials,
                presentation::cells::PAPER_RULE_PERCENT,
            ),
        })
        .collect()
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

/// The ledger as a table: a row per claim, a column per reading.
fn ledger_table(s: &Settings, r: &Results) -> Table {
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
            "The paper's claims and what we find ({} trials per cell, hypothesis {})",
            s.trials, s.errors.hypothesis
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
