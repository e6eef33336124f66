//! `jam-readings`: the jams of the paper's per-mesh tables (Table 3, Table 4 and Table I) counted
//! under the paper's kind of contact test beside our exact solver, with each reading's share of
//! the paper's jam counts that a two-sample test finds consistent with ours, per region.
//!
//! The paper's Python program "is based on detecting intersections between the areas of the
//! gears"; it turns the driver by steps and the driven gear on until the areas no longer
//! intersect. Each reading here is one contact test for every cell: our exact solver, or the
//! area test of `polycheck::stepped` (the driver turned by a fixed step, the driven gear turned
//! forward from where it was until the overlap area is at most a tolerance; a jam when no
//! driven position within the reach ahead gets below it) at one tolerance. Every reading runs
//! the same manufactured gears and initial angles of trial t (rebuilt from the cell's stream as
//! the tables build them), so the readings differ only by the contact test.

use polycheck::stepped::Stepping;
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use study::area_test::{Reading, run_all};
use study::cell::{CellSpec, PAPER_TRIALS, label};
use study::drive::DriveParams;
use study::errors::CaseParams;
use study::gearing::GearingParams;
use study::grids::CellSettings;
use study::results::jam_readings::{
    ContactReading, JamConsistency, JamReadings, ReadingCell, ReadingShares,
};
use study::tolerance::RandomGrid;

use presentation::cells::{
    PaperTable, consistent_with_paper, paper_counts, paper_table_cells, share,
};
use setting_groups::typed::{Gearing, cells};

registry::params! {
    /// `trials`: trials per cell (a screening count; the paper: 200).
    const TRIALS = Param::new("trials", "10", "trials per cell (a screening count; the paper: 200)", registry::Kind::count(1, registry::MAX_TRIALS, "")).recorded();
    /// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70).
    const CLEARANCES = Param::new("clearances", "10,40,70", "Table I's clearances G, comma-separated (the paper: 10, 40 and 70)", registry::Kind::Text).unit("% of h").a_clearance();
    /// `tolerances`: overlap areas the area test ignores, one reading each, comma-separated.
    const TOLERANCES = Param::new("tolerances", "0.0001,0.001,0.003", "overlap areas the area test ignores, one reading each, comma-separated", registry::Kind::Text).unit("mm^2");
    /// `steps_per_pitch`: driver steps per driver pitch of the area test (the driver turns by a fixed step).
    const STEPS_PER_PITCH = Param::new("steps_per_pitch", "20", "driver steps per driver pitch of the area test (the driver turns by a fixed step)", registry::Kind::count(2, 10_000, "a step of at most half a pitch"));
    /// `reach`: how far ahead the area test looks for a free driven position before calling a jam.
    const REACH = Param::new("reach", "1", "how far ahead the area test looks for a free driven position before calling a jam", registry::Kind::number(0.05, 10.0, "driven pitches")).unit("driven pitch");
    /// `search_steps`: steps per driven pitch of the area test's forward search (then bisected).
    const SEARCH_STEPS = Param::new("search_steps", "64", "steps per driven pitch of the area test's forward search (then bisected)", registry::Kind::count(4, 100_000, "a search step of at most a quarter pitch"));
}

/// The settings: trials per cell, Table I's clearances, the area test's tolerances and
/// stepping, the gearing with h and G, the Cases' errors, Table 4's grid and which gear drives.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
#[settings(check = check)]
pub struct Settings {
    /// Trials per cell ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// Table I's clearances, comma-separated, % of h ([`CLEARANCES`]).
    #[param(CLEARANCES)]
    pub clearances: String,
    /// The area test's tolerances, comma-separated, mm² ([`TOLERANCES`]).
    #[param(TOLERANCES)]
    pub tolerances: String,
    /// Driver steps per driver pitch of the area test ([`STEPS_PER_PITCH`]).
    #[param(STEPS_PER_PITCH)]
    pub steps_per_pitch: usize,
    /// How far ahead the area test looks, driven pitches ([`REACH`]).
    #[param(REACH)]
    pub reach: f64,
    /// Steps per driven pitch of the area test's forward search ([`SEARCH_STEPS`]).
    #[param(SEARCH_STEPS)]
    pub search_steps: usize,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// Table 4's grid of random errors.
    #[group]
    pub random: RandomGrid,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// The jams of Tables 3, 4 and I under each contact test.
pub struct JamReadingsExperiment;

impl registry::Experiment for JamReadingsExperiment {
    const ID: &'static str = "jam-readings";
    const TITLE: &'static str = "The jams of Tables 3, 4 and I under the paper's kind of contact test (stepped driver, overlap area up to a tolerance) beside our exact solver";
    const PAPER_ITEM: &'static str = "Tables 3, 4 and I, and section 3 (the area contact test)";
    const PLACE: Place = Place::Beyond(60);
    type Settings = Settings;
    type Results = JamReadings;

    fn compute(s: &Settings, run: &Run) -> Result<JamReadings, RunError> {
        let cs = cells(
            Gearing::WithClearance(&s.gearing),
            &s.errors,
            None,
            Some(&s.drive),
            s.trials,
            s,
        )?;
        let (g, trials) = (cs.gearing(), cs.trials);
        let mut readings: Vec<Reading> = study::drive::Drive::ALL
            .into_iter()
            .map(Reading::Exact)
            .collect();
        readings.extend(
            tolerances(s)?
                .into_iter()
                .map(|t| Reading::Area(t, cs.drive)),
        );
        let cells = all_cells(s, &cs)?;
        let jams = run_all(
            run.engine(),
            g,
            &cells.runs,
            &readings,
            &stepping(s),
            trials,
        )?;
        let regions = regions(&cells);
        let shares = tallies(&cells, &regions, &jams, readings.len(), trials);
        Ok(JamReadings {
            trials,
            readings: readings.iter().map(|r| contact_reading(*r)).collect(),
            regions,
            shares,
            cells: cells
                .paper
                .iter()
                .map(|p| ReadingCell {
                    table: p.table.to_owned(),
                    key: p.key.clone(),
                    region: p.region.clone(),
                    mesh: p.mesh.clone(),
                    case_d: p.case_d,
                    jams: jams[p.run].clone(),
                })
                .collect(),
            cells_run: cells.runs.len(),
            meshes: g.meshes().iter().map(|m| m.label.clone()).collect(),
            seed: run.seed(),
        })
    }

    fn report(s: &Settings, r: &JamReadings) -> Result<Report, RunError> {
        let mut shares = shares_table(r);
        notes(&mut shares, s, r);
        Ok(Report {
            tables: vec![shares, mesh_table(r)],
            files: vec![OutputFile::new("jam-readings-cells.csv", cells_csv(r))],
            trials: r.cells_run as u64 * r.trials,
            ..Default::default()
        })
    }
}

registry::register!(JamReadingsExperiment);

/// Where a cell's paper counts are, the region it is tallied in, its mesh, and which of the
/// distinct cells run gives its counts (Table 3's cells are Table I's at G = 40 %).
struct PaperCell {
    table: &'static str,
    key: String,
    region: String,
    case_d: bool,
    mesh: String,
    run: usize,
}

/// The area test's stepping as set.
fn stepping(s: &Settings) -> Stepping {
    Stepping {
        steps_per_pitch: s.steps_per_pitch,
        reach: s.reach,
        search_steps: s.search_steps,
    }
}

/// A reading as stored: its name, its tolerance (none for the exact solver) and its drive.
fn contact_reading(r: Reading) -> ContactReading {
    match r {
        Reading::Exact(d) => ContactReading {
            name: format!("exact solver, drive {}", d.name()),
            tolerance: None,
            drive: d.name().to_owned(),
        },
        Reading::Area(t, d) => ContactReading {
            name: format!("area T = {} mm^2, drive {}", fmt_f64(t, 4), d.name()),
            tolerance: Some(t),
            drive: d.name().to_owned(),
        },
    }
}

/// The distinct cells run, and every paper cell with the index of the run that gives it.
struct Cells {
    runs: Vec<CellSpec>,
    paper: Vec<PaperCell>,
}

impl Cells {
    /// Adds a paper cell, running `spec` unless an equal cell (same content) is run already.
    fn add(&mut self, spec: CellSpec, table: &'static str, key: String, region: String) {
        let canonical = spec.canonical();
        let run = match self.runs.iter().position(|c| c.canonical() == canonical) {
            Some(i) => i,
            None => {
                self.runs.push(spec.clone());
                self.runs.len() - 1
            }
        };
        let case_d = key.starts_with("D.");
        self.paper.push(PaperCell {
            table,
            key,
            region,
            case_d,
            mesh: spec.mesh,
            run,
        });
    }
}

/// The cells of Tables 3 (Cases A-D at the clearance), 4 (the random grid) and I (Cases A-D at
/// each of its clearances), in the order of `event-rules`.
fn all_cells(s: &Settings, cs: &CellSettings) -> Result<Cells, RunError> {
    let clearance = cs.clearance()?;
    let clearances = study::gearing::clearance_list(&s.clearances, CLEARANCES.name, 200.0)?;
    let randoms = s.random.values(s)?;
    let mut out = Cells {
        runs: Vec::new(),
        paper: Vec::new(),
    };
    let region = |gc: f64| format!("G = {} %", label(gc, 0));
    for c in paper_table_cells(cs, &randoms, &clearances)? {
        let group = match c.table {
            PaperTable::Table3 { .. } => region(clearance),
            PaperTable::Table4 { .. } => "Table 4".into(),
            PaperTable::TableI { clearance, .. } => region(clearance),
        };
        out.add(c.cell, c.id, c.key, group);
    }
    Ok(out)
}

/// The settings' check across fields, before any work: the area readings' tolerances, each
/// once, at most [`MAX_TOLERANCES`].
fn check(s: &Settings, _: &registry::Context) -> Result<(), RunError> {
    if tolerances(s)?.len() > MAX_TOLERANCES {
        return Err(RunError::bad(
            "--set",
            TOLERANCES.name,
            format!("at most {MAX_TOLERANCES} tolerances"),
        ));
    }
    Ok(())
}

/// The most area readings a run counts: a trial's jams under every reading are bits of one
/// `u64`, and 63 readings are counted at most, the exact solver's drives among them.
const MAX_TOLERANCES: usize = 63 - study::drive::Drive::ALL.len();

/// The tolerances of the area readings, from a comma-separated parameter.
fn tolerances(s: &Settings) -> Result<Vec<f64>, RunError> {
    let text = &s.tolerances;
    let mut out: Vec<f64> = Vec::new();
    for part in text.split(',').map(str::trim) {
        let t = part
            .parse::<f64>()
            .ok()
            .filter(|t| t.is_finite() && *t >= 0.0 && *t <= 1.0)
            .ok_or_else(|| {
                RunError::bad(
                    "--set",
                    TOLERANCES.name,
                    format!("each must be a number from 0 to 1 mm^2 (got `{part}`)"),
                )
            })?;
        // A reading named twice would be one column twice over.
        if out.contains(&t) {
            return Err(RunError::bad(
                "--set",
                TOLERANCES.name,
                format!("names the tolerance {part} twice: give each once (got `{text}`)"),
            ));
        }
        out.push(t);
    }
    Ok(out)
}

/// Adds our count `ours` of `trials` against the paper's `paper` (of 200) to `x`.
fn add(x: &mut JamConsistency, ours: u64, trials: u64, paper: Option<u64>) {
    let Some(p) = paper else { return };
    x.compared += 1;
    if consistent_with_paper(ours, trials, paper) {
        x.consistent += 1;
    } else if ours as f64 / trials as f64 > p as f64 / PAPER_TRIALS as f64 {
        x.higher += 1;
    }
}

/// Of the counts the test separates, ours higher / lower (`-` for none).
fn differing(x: &JamConsistency) -> String {
    let d = x.compared - x.consistent;
    if d == 0 {
        "-".into()
    } else {
        format!("{} / {}", x.higher, d - x.higher)
    }
}

/// The regions in print order: Table 4, each clearance, then Case D (across clearances).
fn regions(cells: &Cells) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for p in &cells.paper {
        if !out.contains(&p.region) {
            out.push(p.region.clone());
        }
    }
    out.sort_by_key(|r| {
        (
            r != "Table 4",
            r.trim_start_matches("G = ").len(),
            r.clone(),
        )
    });
    out.push("Case D".into());
    out
}

/// Per reading: the tally of each region (last: Case D) and of all the paper's jam counts.
fn tallies(
    cells: &Cells,
    regions: &[String],
    jams: &[Vec<u64>],
    readings: usize,
    trials: u64,
) -> Vec<ReadingShares> {
    let empty = ReadingShares {
        per_region: vec![JamConsistency::default(); regions.len()],
        all: JamConsistency::default(),
    };
    let mut out = vec![empty; readings];
    for p in &cells.paper {
        let paper = paper_counts(p.table, &p.key).0;
        let i = regions.iter().position(|r| *r == p.region).unwrap_or(0);
        for (r, x) in out.iter_mut().enumerate() {
            let ours = jams[p.run][r];
            add(&mut x.per_region[i], ours, trials, paper);
            if p.case_d {
                add(&mut x.per_region[regions.len() - 1], ours, trials, paper);
            }
            add(&mut x.all, ours, trials, paper);
        }
    }
    out
}

/// The shares table: one row per reading, a column per region and one for all.
fn shares_table(r: &JamReadings) -> Table {
    let mut head = vec!["reading".to_string()];
    head.extend(r.regions.iter().map(|x| format!("{x} jams")));
    head.push("all jams".into());
    head.push("differing: ours higher / lower".into());
    let mut t = Table::new(
        format!(
            "The paper's jam counts consistent with ours under each contact test (Fisher's exact two-sample test at 5 %; ours {} trials per cell, the paper's 200)",
            r.trials
        ),
        head,
    );
    for (reading, x) in r.readings.iter().zip(&r.shares) {
        let mut row = vec![reading.name.clone()];
        row.extend(x.per_region.iter().map(|x| share(x.consistent, x.compared)));
        row.push(share(x.all.consistent, x.all.compared));
        row.push(differing(&x.all));
        t.row(row);
    }
    t
}

/// Where the differences lie: per mesh, per reading, the consistent share and the separated
/// counts split into ours higher / lower.
fn mesh_table(r: &JamReadings) -> Table {
    let mut head = vec!["mesh".to_string()];
    head.extend(
        r.readings
            .iter()
            .map(|x| format!("{}: consistent; higher / lower", x.name)),
    );
    let mut t = Table::new(
        "Where the jam counts differ, per mesh (all regions): the paper's counts consistent with ours; of the others, ours higher / lower",
        head,
    );
    for m in &r.meshes {
        let mut per = vec![JamConsistency::default(); r.readings.len()];
        for p in r.cells.iter().filter(|p| p.mesh == *m) {
            let paper = paper_counts(&p.table, &p.key).0;
            for (x, &ours) in per.iter_mut().zip(&p.jams) {
                add(x, ours, r.trials, paper);
            }
        }
        let mut row = vec![m.clone()];
        row.extend(
            per.iter()
                .map(|x| format!("{}; {}", share(x.consistent, x.compared), differing(x))),
        );
        t.row(row);
    }
    t.note("Higher / lower compares the rates (ours of this run's trials, the paper's of 200) of the counts the two-sample test separates.");
    t
}

/// Every paper cell's jam counts under every reading, with the paper's and the test's verdict.
fn cells_csv(r: &JamReadings) -> String {
    let trials = r.trials;
    let mut s =
        String::from("table,key,region,mesh,reading,trials,jams,paper_jams,jams_consistent\n");
    for p in &r.cells {
        let paper = paper_counts(&p.table, &p.key).0;
        for (reading, &ours) in r.readings.iter().zip(&p.jams) {
            let verdict = paper.map_or_else(String::new, |_| {
                consistent_with_paper(ours, trials, paper).to_string()
            });
            s.push_str(&registry::csv_row!(
                p.table,
                p.key,
                p.region,
                p.mesh,
                reading.name,
                trials,
                ours,
                paper.map_or_else(String::new, |v| v.to_string()),
                verdict,
            ));
        }
    }
    s
}

/// The notes saying what produced every number.
fn notes(t: &mut Table, s: &Settings, r: &JamReadings) {
    t.note("Rule: a jam is a trial in which the contact test finds no free forward position for the driven gear at least once (exact solver: a lock, a strike or a blocked start; area test: after a driver step, no driven position within the reach ahead has an overlap area at most T). Gears whose bodies overlap at every angle are a jam under every reading.");
    t.note(format!("Drive: the exact solver's rows differ by which gear of each mesh drives, not by the contact test: `listed` (the first gear of the mesh's name, as the train runs; the paper names the driver first, as Freeth et al. do, and does not say which gear its program turned), `other` (the second, both gears still turning their own way, started at the same share of its own pitch, over one turn of the larger gear) and `either` (drawn per trial from the trial's own stream). The area test runs with the drive `--set drive=` names ({}).", s.drive.drive));
    t.note(format!(
        "Area test (polycheck::stepped): the driver turns by fixed steps of 1/{} of its pitch over one turn of the gear with more teeth; after each step the driven gear is turned forward from where it was until the overlap area of the two outlines is at most T (searched in steps of 1/{} of a driven pitch up to {} driven pitches ahead, then bisected); it starts touching, turned back from angle 0 until the area exceeds T (pushed forward if it already does), as the solver starts. Straight flanks; tips, valleys, per-tooth radii and rotation centres as manufactured.",
        s.steps_per_pitch,
        s.search_steps,
        fmt_f64(s.reach, 2)
    ));
    t.note(format!(
        "Gearing {} (Freeth 2006 by default), h = {} mm, hypothesis {}, split {}; errors per Case as Edmunds' (A: 0 deg, 0.04; B: 0.5 deg, 0.04; C: 1 deg, 0.04; D: 2 deg, 0.08 of the pitch); Table 4: random error only, {} to {} of the pitch by {}, at G = {} %. Every reading runs the same gears and initial angle of trial t (the cell's stream, as the tables build them); seed {}.",
        s.gearing.gearing,
        fmt_f64(s.gearing.tooth_height, 2),
        s.errors.errors.hypothesis,
        fmt_f64(s.errors.split, 2),
        s.random.random_from,
        s.random.random_to,
        s.random.random_step,
        fmt_f64(s.gearing.clearance, 0),
        r.seed,
    ));
    t.note(power_note(r.trials));
    t.note(format!(
        "{} paper cells ({} distinct cells run: Table 3's are Table I's at G = 40 %, the paper printed them twice and each printing is compared). Case D: its cells at every clearance, also counted in their G column. All: every paper jam count once.",
        r.cells.len(),
        r.cells_run
    ));
}

/// What a count of `trials` can tell apart from a count of 200: the range of our counts the
/// two-sample test finds consistent with the paper's 2 and 100 of 200. Fewer trials make the
/// test weaker and every share higher, so a screen ranks readings against each other (on the
/// same gears); it does not say how close one comes to the paper at 200 trials.
fn power_note(trials: u64) -> String {
    let consistent = |paper: u64| {
        let ks: Vec<u64> = (0..=trials)
            .filter(|&k| consistent_with_paper(k, trials, Some(paper)))
            .collect();
        match (ks.first(), ks.last()) {
            (Some(lo), Some(hi)) => format!("{lo} to {hi}"),
            _ => "none".to_string(),
        }
    };
    format!(
        "Power: with {trials} trials per cell, a count of ours from {} of {trials} is consistent with the paper's 2 of {PAPER_TRIALS}, and from {} with its 100 of {PAPER_TRIALS}. The shares rise as trials fall, so at a screening count they rank the readings (which run the same gears) rather than measure how close one comes to the paper; confirm with `--set trials=200` (the exact solver at 200 trials is what Tables 3, 4, I and event-rules report).",
        consistent(2),
        consistent(100),
    )
}
