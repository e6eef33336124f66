//! `claims`: the paper's claims, each with the paper's figure, ours (with its uncertainty) and a
//! verdict with its reason, computed from the other experiments' typed results; one column per
//! reading of the paper says whether the verdict changes under it.
//!
//! The ledger runs nothing of its own: it asks the registry for the results of the experiments a
//! claim rests on (Table 3, Table 4, ...) under each reading, read from the results folder when a
//! run with the same settings and seed is there, else computed (once per process).

use registry::{Param, Place, Report, Run, RunError};
use serde::{Deserialize, Serialize};
use study::claims::tolerances::Named;
use study::claims::{ClaimRow, Judged, Ledger as Results, MeshStanding, Verdict};
use study::errors::ErrorParams;
use study::results::{
    CasePointers, CaseTable, DerivedTolerances, FailureStudy, GearTolerances, IdealPointers,
    RandomErrorTable, SigmaAgainstClearance, SplitPairs,
};
use study::tolerance::PAPER_RULE_PERCENT;

use presentation::reports::claims::{self, Asked};

registry::params! {
    const RUNS = Param::new("runs", "0", "trials of the pointer tables (Tables 1 and 2) and runs of the whole-mechanism study (failure) the ledger reads; 0: each experiment's own default (Table 1 and the failure study: the paper's 30; Table 2: 20)", registry::Kind::count(0, registry::MAX_TRIALS, ""));
    const MEASURED = Param::new("measured", "", "Edmunds' per-gear measured errors (RON, the `measured` hypothesis' format), passed to Figure 6 and the failure study; empty: none (their claims are then not testable)", registry::Kind::Text);
    const ONLY = Param::new("only", "", "the claims to judge, comma-separated ids (C1,C7); empty: every claim", registry::Kind::Text);
}

/// The ledger's settings: the trials of the per-mesh tables it reads and the runs of the pointer
/// tables and the failure study, the measured errors given, the claims asked for, and the error
/// hypothesis the gears are made with (the paper's, Edmunds' split, by default).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell of the per-mesh tables ([`study::grids::TRIALS`]).
    #[param(study::grids::TRIALS)]
    pub trials: u64,
    /// Trials of Tables 1 and 2 and runs of the failure study; 0: their own ([`RUNS`]).
    #[param(RUNS)]
    pub runs: u64,
    /// Edmunds' measured errors for Figure 6 and the failure study ([`MEASURED`]).
    #[param(MEASURED)]
    pub measured: String,
    /// The claims to judge; empty: all ([`ONLY`]).
    #[param(ONLY)]
    pub only: String,
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
        sets: &[(&setting_groups::emax::EMAX, "paper")],
    },
];

/// A claim of the paper: our words for it, where the paper makes it, and its judge.
struct Claim {
    id: &'static str,
    words: &'static str,
    place: &'static str,
    judge: fn(&Evidence, &[ClaimRow]) -> Result<Judged, RunError>,
}

/// The claims, in the order the paper's argument makes them.
const CLAIMS: &[Claim] = &[
    Claim {
        id: "C1",
        words: "ideal triangular teeth alone give pointer errors about seven times smaller than Edmunds' errors do",
        place: "conclusions; Table 1 against Table 2",
        judge: |e, _| {
            Ok(study::claims::pointers::ideal_teeth_negligible(
                &e.results::<IdealPointers>("table1")?,
                &e.results::<CasePointers>("table2")?,
                &paper_sigmas()?,
            ))
        },
    },
    Claim {
        id: "C2",
        words: "gears jam below about 10 % of h and disengage above about 87-90 %; G = 40 % is close to the best, the smallest sigma at 40-50 %",
        place: "section 3, Appendix II, Figure IV",
        judge: |e, _| {
            let mut j = study::claims::pointers::clearance_limits(
                &e.results::<SigmaAgainstClearance>("figIV")?,
                paper_clearance()?,
            );
            j.reason.push_str("; no column for the paper's contact tolerance: it is a contact model of its own (overlaps up to an area ignored, `contact-tolerance`), not a setting Figure IV or the jam tables take");
            Ok(j)
        },
    },
    Claim {
        id: "C3",
        words: "with Edmunds' errors, triangular teeth give pointer errors not significantly different from his radial model",
        place: "conclusions; Table 2, Figure 5",
        judge: |e, _| {
            Ok(study::claims::pointers::same_as_edmunds(
                &e.results::<CasePointers>("table2")?,
            ))
        },
    },
    Claim {
        id: "C4",
        words: "how the systematic error is split (eccentricity or tooth wave) does not matter significantly",
        place: "section 4, Figure 5",
        judge: |e, _| {
            Ok(study::claims::pointers::split_does_not_matter(
                &e.results::<SplitPairs>("fig5")?,
            ))
        },
    },
    Claim {
        id: "C5",
        words: "by the 1 % rule, Cases C and D are unusable, Case A gives no trouble, Case B is problematic through m3-e3 and e4-f1",
        place: "section 5, Table 3",
        judge: |e, _| {
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
        judge: |e, _| {
            let ours = e.table3()?;
            let radii = larger_radii(&ours)?;
            Ok(study::claims::cells::large_gears_fail_more(
                &ours,
                &paper_case_table(&ours),
                &radii,
            ))
        },
    },
    Claim {
        id: "C7",
        words: "a uniform random error must not exceed 0.04 of the pitch; m2-n1 tolerates no more than 0.04, b2-c1 up to 0.055",
        place: "section 5, Table 4 (Table 5's row E. max)",
        judge: |e, _| {
            let ours = e.results::<RandomErrorTable>("table4")?;
            let paper = paper_random_row(&ours.table.meshes);
            let named = Named {
                least: "m2-n1",
                most: "b2-c1",
            };
            Ok(study::claims::tolerances::random_limits(
                &ours,
                &paper,
                named,
                PAPER_RULE_PERCENT,
            ))
        },
    },
    Claim {
        id: "C8",
        words: "the tolerable systematic error ranges from 0.1 deg (d2-e2) to 0.6 deg (e1-b3), like for like",
        place: "section 5, Table 5",
        judge: |e, _| {
            let ours = e.results::<DerivedTolerances>("table5")?;
            let values = ours.systematic_values();
            let paper: Vec<(String, Option<f64>)> = ours
                .meshes
                .iter()
                .map(|m| {
                    let p =
                        presentation::emax::paper_systematic(&m.mesh, &values, PAPER_RULE_PERCENT);
                    (m.mesh.clone(), p.flatten())
                })
                .collect();
            let named = Named {
                least: "d2-e2",
                most: "e1-b3",
            };
            Ok(study::claims::tolerances::systematic_limits(
                &ours,
                &paper,
                named,
                PAPER_RULE_PERCENT,
            ))
        },
    },
    Claim {
        id: "C9",
        words: "Edmunds' measured errors typically exceed the tolerable ones",
        place: "section 5, Figure 6",
        judge: |e, _| {
            let range = (
                paper_value("fig6", "edmunds_random_from")?,
                paper_value("fig6", "edmunds_random_to")?,
            );
            Ok(study::claims::tolerances::measured_exceed_tolerable(
                &e.results::<GearTolerances>("fig6")?,
                range,
            ))
        },
    },
    Claim {
        id: "C10",
        words: "30 whole mechanisms with Edmunds' errors: 90 % jam; the Lunar train stops after about 129 days, Metonic and Games 234, Saros and Exeligmos 121",
        place: "section 5, after Figure 6",
        judge: |e, _| {
            Ok(study::claims::mechanism::thirty_runs(
                &e.results::<FailureStudy>("failure")?,
                &paper_runs()?,
            ))
        },
    },
    Claim {
        id: "C11",
        words: "with Edmunds' errors the mechanism generally stops before the Sun pointer has turned a third (120 deg)",
        place: "introduction, conclusions",
        judge: |e, _| {
            Ok(study::claims::mechanism::stops_within_a_third(
                &e.results::<FailureStudy>("failure")?,
                paper_value("failure", "stop_angle")?,
            ))
        },
    },
    Claim {
        id: "C12",
        words: "the conclusion: either the mechanism never worked, or its errors were smaller than Edmunds measured",
        place: "abstract, conclusions",
        judge: |e, rows| {
            let supporting: Vec<(&str, Verdict)> = rows
                .iter()
                .filter(|r| CONCLUSION_RESTS_ON.contains(&r.id.as_str()))
                .map(|r| (r.id.as_str(), r.under[e.index]))
                .collect();
            Ok(study::claims::mechanism::the_conclusion(
                &e.results::<FailureStudy>("failure")?,
                &supporting,
            ))
        },
    },
];

/// The claims the conclusion (C12) rests on: the Cases by the rule, the tolerances, the measured
/// errors and the whole mechanisms.
const CONCLUSION_RESTS_ON: [&str; 6] = ["C5", "C7", "C8", "C9", "C10", "C11"];

/// What a claim's judge may ask for: the results of the experiments it rests on, under one
/// reading.
struct Evidence<'a> {
    run: &'a Run<'a>,
    settings: &'a Settings,
    reading: &'a Reading,
    /// The reading's column, in [`READINGS`]' order.
    index: usize,
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
        sets.extend(self.by_name(entry));
        Ok(self.run.results_of::<T>(id, &sets)?.0)
    }

    /// The ledger's settings that experiments declare each with a declaration of its own, set by
    /// its name: the runs of the pointer tables and the failure study (their `trials`, which is
    /// not the per-cell [`study::grids::TRIALS`]), and the measured table of Figure 6 and the
    /// failure study.
    fn by_name(&self, entry: &registry::Entry) -> Vec<(&'static Param, String)> {
        let s = self.settings;
        entry
            .all_params()
            .filter_map(|q| {
                if q.counts_trials() && *q != study::grids::TRIALS && s.runs > 0 {
                    Some((q, s.runs.to_string()))
                } else if q.name == setting_groups::inputs::MEASURED
                    && !s.measured.trim().is_empty()
                {
                    Some((q, s.measured.clone()))
                } else {
                    None
                }
            })
            .collect()
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

/// The paper's value of `quantity` in experiment `id` (`paper.ron`).
fn paper_value(id: &str, quantity: &str) -> Result<f64, RunError> {
    presentation::paper::get(id, quantity)
        .map(|r| r.value)
        .ok_or_else(|| RunError::Internal(format!("paper.ron has no {id} {quantity}")))
}

/// (pointer, σ with ideal teeth in Table 1, σ of Edmunds' Case A in Table 2) for every pointer
/// both give.
fn paper_sigmas() -> Result<Vec<(String, f64, f64)>, RunError> {
    let out: Vec<(String, f64, f64)> = ["Lunar", "Metonic", "Saros"]
        .iter()
        .filter_map(|p| {
            let ideal = presentation::paper::get("table1", &format!("{p}.sigma"))?.value;
            let case_a = presentation::paper::get("table2", &format!("A.{p}.sigma"))?.value;
            Some(((*p).to_owned(), ideal, case_a))
        })
        .collect();
    if out.is_empty() {
        return Err(RunError::Internal(
            "paper.ron gives no pointer's sigma in both Table 1 and Table 2".into(),
        ));
    }
    Ok(out)
}

fn paper_clearance() -> Result<study::claims::pointers::PaperClearance, RunError> {
    Ok(study::claims::pointers::PaperClearance {
        jam_below: paper_value("clearance", "jam_below")?,
        disengage_above: paper_value("clearance", "disengage_above")?,
        minimum_from: paper_value("sigma-causes", "figIV.minimum_from")?,
        minimum_to: paper_value("sigma-causes", "figIV.minimum_to")?,
    })
}

/// The paper's E. max row for `meshes` (`None` for a mesh it gives none for).
fn paper_random_row(meshes: &[String]) -> Vec<(String, Option<f64>)> {
    meshes
        .iter()
        .map(|m| (m.clone(), presentation::emax::paper_random(m)))
        .collect()
}

/// The paper's 30-run study: the share that jammed and each train's mean day.
fn paper_runs() -> Result<study::claims::mechanism::PaperRuns, RunError> {
    let runs = study::whole_mechanism::RUNS_DEFAULT
        .parse()
        .map_err(|e| RunError::Internal(format!("the paper's runs: {e}")))?;
    let mean_days = study::whole_mechanism::TRAINS
        .iter()
        .map(|(train, _)| {
            paper_value("failure", &format!("{train}.mean_days")).map(|d| ((*train).to_owned(), d))
        })
        .collect::<Result<_, _>>()?;
    Ok(study::claims::mechanism::PaperRuns {
        jammed_percent: paper_value("failure", "mechanisms_jammed")?,
        runs,
        mean_days,
    })
}

/// The claims `only` asks for (every claim when it is empty); an unknown id is refused.
fn chosen(only: &str) -> Result<Vec<&'static Claim>, RunError> {
    let ids: Vec<&str> = only
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    for id in &ids {
        if !CLAIMS.iter().any(|c| c.id.eq_ignore_ascii_case(id)) {
            let known: Vec<&str> = CLAIMS.iter().map(|c| c.id).collect();
            return Err(RunError::bad(
                "--set",
                ONLY.name,
                format!("no claim `{id}`; the claims are {}", known.join(", ")),
            ));
        }
    }
    Ok(CLAIMS
        .iter()
        .filter(|c| ids.is_empty() || ids.iter().any(|id| c.id.eq_ignore_ascii_case(id)))
        .collect())
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
        for c in chosen(&s.only)? {
            let row = judge_everywhere(c, s, run, &claims)?;
            claims.push(row);
        }
        let as_run = Evidence {
            run,
            settings: s,
            reading: &READINGS[0],
            index: 0,
        };
        // Table 5's tolerances in units of the gears, where the ledger judged them (C8).
        let judged_tolerances = claims.iter().any(|c| c.id == "C8");
        let tolerances = if judged_tolerances {
            Some((
                as_run.results::<DerivedTolerances>("table5")?,
                table5_split()?,
            ))
        } else {
            None
        };
        Ok(Results {
            claims,
            readings: READINGS.iter().map(|r| r.name.to_owned()).collect(),
            case_b: case_b(&as_run.table3()?),
            tolerances,
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        Ok(claims::report(
            r,
            Asked {
                trials: s.trials,
                runs: s.runs,
                hypothesis: &s.errors.hypothesis,
            },
        ))
    }
}

registry::register!(Claims);

/// The systematic split Table 5 runs at when the ledger asks for it (its default).
fn table5_split() -> Result<f64, RunError> {
    study::errors::SPLIT
        .default
        .parse()
        .map_err(|_| RunError::Internal("the split's default is no number".into()))
}

/// Claim `c` judged as run and its verdict under every other reading.
/// `before`: the claims judged before it.
fn judge_everywhere(
    c: &Claim,
    s: &Settings,
    run: &Run,
    before: &[ClaimRow],
) -> Result<ClaimRow, RunError> {
    let mut under = Vec::with_capacity(READINGS.len());
    let mut judged = None;
    for (index, reading) in READINGS.iter().enumerate() {
        let evidence = Evidence {
            run,
            settings: s,
            reading,
            index,
        };
        let j = (c.judge)(&evidence, before)?;
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
