//! `motion-models`: every registered motion model (how the driven gear moves between and at its
//! contacts, `motion`) against the paper: the jams and disengagements of Tables 3, 4 and I
//! consistent with its counts, Table 4's jams summed per mesh, Figure 2 against Thorndike's
//! closed form, Table 1's five pointers and Figure IV's shape.
//!
//! Every model runs the same manufactured gears and driver initial angle of trial t as the
//! tables (the cell's stream, the listed driver driving); a model that places the driven gear
//! at an angle of its own draws it from a stream of its own.

use motion::Model;
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use study::cell::{CellSpec, Counts, PAPER_TRIALS};
use study::errors::CaseParams;
use study::events::EventParams;
use study::gearing::GearingParams;
use study::limits::IdealPair;
use study::motion_models::{Figure2, PointerSigma, SigmaPoint};
use study::pointers::{POINTERS, RunLengths};
use study::tolerance::RandomGrid;

use presentation::cells::{Tally, paper_counts, paper_table_cells, share};
use setting_groups::typed::{Gearing, cells};

registry::params! {
    /// `trials`: trials per cell of Tables 3, 4 and I (a screening count; the paper: 200).
    const TRIALS = Param::new("trials", "2", "trials per cell of Tables 3, 4 and I (the default is a smoke test of six models on 270 cells; the paper: 200)", registry::Kind::count(1, registry::MAX_TRIALS, "")).recorded();
    /// `models`: the motion models compared, comma-separated, or `all`.
    const MODELS = Param::new("models", "all", "the motion models compared, comma-separated, or `all` (every registered model)", registry::Kind::Text);
    /// `clearances`: Table I's clearances G, comma-separated (the paper: 10, 40 and 70).
    const CLEARANCES = Param::new("clearances", "10,40,70", "Table I's clearances G, comma-separated (the paper: 10, 40 and 70)", registry::Kind::Text).unit("% of h").a_clearance();
    /// `fig2_step`: Figure 2's sampling step.
    const FIG2_STEP = Param::new("fig2_step", "0.05", "Figure 2's sampling step", registry::Kind::number(0.001, 10.0, "degrees")).unit("deg");
    /// `pointer_trials`: Table 1's trials (the paper: 30).
    const POINTER_TRIALS = Param::new("pointer_trials", "1", "Table 1's trials, each with fresh random initial angles (the paper: 30)", registry::Kind::count(1, 10_000, ""));
    /// `fig_iv_clearances`: Figure IV's clearances G, comma-separated.
    const FIG_IV_CLEARANCES = Param::new("fig_iv_clearances", "10,40,70", "Figure IV's clearances G, comma-separated", registry::Kind::Text).unit("% of h");
    /// `fig_iv_samples`: Figure IV's TD samples per run.
    const FIG_IV_SAMPLES = Param::new("fig_iv_samples", "400", "Figure IV's TD samples per run", registry::Kind::count(2, 1_000_000, ""));
}

/// The settings: trials per cell, the models, Table I's clearances, Figure 2's step, Table 1's
/// trials, Figure IV's clearances and samples, the gearing with h and G, the Cases' errors,
/// Table 4's grid, the event rule and the pointers' run lengths.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Trials per cell of Tables 3, 4 and I ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// The motion models compared, comma-separated, or `all` ([`MODELS`]).
    #[param(MODELS)]
    pub models: String,
    /// Table I's clearances, comma-separated, % of h ([`CLEARANCES`]).
    #[param(CLEARANCES)]
    pub clearances: String,
    /// Figure 2's sampling step, degrees ([`FIG2_STEP`]).
    #[param(FIG2_STEP)]
    pub fig2_step: f64,
    /// Table 1's trials ([`POINTER_TRIALS`]).
    #[param(POINTER_TRIALS)]
    pub pointer_trials: u64,
    /// Figure IV's clearances, comma-separated, % of h ([`FIG_IV_CLEARANCES`]).
    #[param(FIG_IV_CLEARANCES)]
    pub fig_iv_clearances: String,
    /// Figure IV's TD samples per run ([`FIG_IV_SAMPLES`]).
    #[param(FIG_IV_SAMPLES)]
    pub fig_iv_samples: usize,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The split, the hypothesis and its parameters.
    #[group]
    pub errors: CaseParams,
    /// Table 4's grid of random errors.
    #[group]
    pub random: RandomGrid,
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// The five pointers' run lengths and TD samples per engagement (Table 1's).
    #[group]
    pub run_lengths: RunLengths,
}

/// What every model gave: the paper's cells counted, Figure 2 against the closed form, Table
/// 1's pointers and Figure IV's σ.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Results {
    /// The seed every trial's stream comes from.
    pub seed: u64,
    /// The models compared, in the order of every per-model list: (name, what the driven gear
    /// does).
    pub models: Vec<(String, String)>,
    /// Distinct cells run (Table 3's are Table I's at G = 40 %).
    pub cells_run: usize,
    /// Every paper cell of Tables 3, 4 and I, with our counts under each model.
    pub cells: Vec<ModelCell>,
    /// Per model: Figure 2's pair against Thorndike's closed form.
    pub figure2: Vec<Figure2>,
    /// Per model, per trial, per pointer of [`POINTERS`]: Table 1's σ (degrees).
    pub pointer_sigmas: Vec<Vec<Vec<PointerSigma>>>,
    /// Figure IV's meshes (the gearing's, in its order).
    pub meshes: Vec<String>,
    /// Figure IV's clearances G, % of h.
    pub fig_iv_clearances: Vec<f64>,
    /// Per model, per mesh, per clearance: σ of the driven gear (degrees) and how the run ended.
    pub fig_iv: Sweeps,
}

/// A cell of the paper's tables, where its counts are, and ours under each model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelCell {
    /// The table: `table3`, `table4` or `tableI`.
    pub table: String,
    /// Its key in the paper's reference file.
    pub key: String,
    /// Its mesh (driver-driven).
    pub mesh: String,
    /// Our counts under each model, in [`Results::models`]' order.
    pub counts: Vec<Counts>,
}

/// The motion models compared.
pub struct MotionModels;

impl registry::Experiment for MotionModels {
    const ID: &'static str = "motion-models";
    const TITLE: &'static str = "Motion models of the driven gear (pushed, carried at the nominal ratio, stepped the paper's way) against the paper's jams, Figure 2, Table 1 and Figure IV";
    const PAPER_ITEM: &'static str =
        "Tables 1, 3, 4, I and Figures 2, IV (how the driven gear moves, beyond the paper)";
    const PLACE: Place = Place::Beyond(70);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        motion::link();
        let models = models(s)?;
        let cs = cell_settings(s)?;
        let (g, trials, rule) = (cs.gearing(), cs.trials, cs.rule.clone());
        let (runs, paper) = all_cells(s, &cs)?;
        let counts =
            study::motion_models::cell_counts(run.engine(), g, &runs, &models, &rule, trials)?;
        let figure2: Vec<Figure2> = models
            .iter()
            .map(|m| study::motion_models::figure2(m, s.fig2_step))
            .collect::<Result<_, _>>()?;
        let pointer_sigmas = pointer_sigmas(s, run, &models, &rule)?;
        let (meshes, fig_iv_clearances, fig_iv) = fig_iv_sweeps(s, run, &models, &rule)?;
        Ok(Results {
            seed: run.seed(),
            models: models
                .iter()
                .map(|m| (m.name().to_string(), m.definition().summary().to_string()))
                .collect(),
            cells_run: runs.len(),
            cells: paper
                .into_iter()
                .map(|p| ModelCell {
                    table: p.table.to_owned(),
                    key: p.key,
                    mesh: p.mesh,
                    counts: counts[p.run].clone(),
                })
                .collect(),
            figure2,
            pointer_sigmas,
            meshes,
            fig_iv_clearances,
            fig_iv,
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let trials = s.trials;
        let tallies = tallies(&r.cells, r.models.len());
        let mut counts_t = counts_table(&r.models, &tallies, trials);
        counts_t.note(format!(
            "Rule {}; gearing {}, h = {} mm, hypothesis {}; seed {}.",
            s.events.rule()?.label(),
            s.gearing.gearing,
            fmt_f64(s.gearing.tooth_height, 2),
            s.errors.errors.hypothesis,
            r.seed
        ));
        Ok(Report {
            tables: vec![
                models_table(&r.models),
                counts_t,
                table4_sums(r, trials),
                figure2_table(&r.models, &r.figure2, s.fig2_step),
                table1_table(&r.models, &r.pointer_sigmas, s.pointer_trials),
                fig_iv_table(r),
            ],
            files: vec![
                OutputFile::new("motion-models-cells.csv", cells_csv(r)),
                OutputFile::new("motion-models-fig-iv.csv", fig_iv_csv(r)),
            ],
            trials: r.cells_run as u64 * trials,
            ..Default::default()
        })
    }
}

registry::register!(MotionModels);

/// Table 4's meshes whose jams the paper's text sets apart, in the order the sums are printed.
const TABLE4_MESHES: [&str; 7] = [
    "d2-e2", "e4-f1", "c2-d1", "m2-n1", "h2-i1", "g2-h1", "m3-e3",
];

/// The cells' settings: the gearing with G, the Cases' errors, the event rule, the listed
/// driver, and the trials per cell.
fn cell_settings(s: &Settings) -> Result<study::grids::CellSettings, RunError> {
    cells(
        Gearing::WithClearance(&s.gearing),
        &s.errors,
        Some(&s.events),
        None,
        s.trials,
        s,
    )
}

/// Table 1's pointers under every model: per model, per trial, per pointer.
fn pointer_sigmas(
    s: &Settings,
    run: &Run,
    models: &[Model],
    rule: &rules::Rule,
) -> Result<Vec<Vec<Vec<PointerSigma>>>, RunError> {
    let gearing = s.gearing.load()?;
    let mech = study::pointers::ideal_mechanism(&gearing, rule)?;
    let per = s.run_lengths.samples_per_engagement;
    let runs = study::pointers::pointer_runs(&gearing.gearing, &s.run_lengths.turns(), per)?;
    study::motion_models::pointer_sigmas(
        run.engine(),
        &mech,
        &runs,
        models,
        s.pointer_trials,
        gearing.tooth_height,
    )
}

/// Figure IV's σ per model, per mesh, per clearance.
pub type Sweeps = Vec<Vec<Vec<SigmaPoint>>>;

/// Figure IV's sweep under every model: the meshes, the clearances, and per model, per mesh,
/// per clearance the σ.
fn fig_iv_sweeps(
    s: &Settings,
    run: &Run,
    models: &[Model],
    rule: &rules::Rule,
) -> Result<(Vec<String>, Vec<f64>, Sweeps), RunError> {
    let gearing = s.gearing.load()?;
    let g = &gearing.gearing;
    let clearances =
        study::gearing::clearance_list(&s.fig_iv_clearances, FIG_IV_CLEARANCES.name, 200.0)?;
    let labels: Vec<String> = g.meshes().iter().map(|m| m.label.clone()).collect();
    let pairs: Vec<IdealPair> = labels
        .iter()
        .map(|l| IdealPair::named(l, g, gearing.tooth_height))
        .collect::<Result<_, _>>()?;
    let sweeps = study::motion_models::sigma_sweep(
        run.engine(),
        &pairs,
        &clearances,
        models,
        rule,
        s.fig_iv_samples,
    )?;
    Ok((labels, clearances, sweeps))
}

/// The models named by `models` (`all`: every registered one, in name order).
fn models(s: &Settings) -> Result<Vec<Model>, RunError> {
    let text = &s.models;
    let bad = |e: motion::ModelError| RunError::bad("--set", MODELS.name, e.to_string());
    if text.trim() == "all" {
        return Model::all().map_err(bad);
    }
    let mut out: Vec<Model> = Vec::new();
    for name in text.split(',') {
        let m = Model::parse(name).map_err(bad)?;
        if out.contains(&m) {
            return Err(RunError::bad(
                "--set",
                MODELS.name,
                format!("names `{}` twice", m.name()),
            ));
        }
        out.push(m);
    }
    Ok(out)
}

/// A cell of the paper's tables and where its counts are.
struct PaperCell {
    table: &'static str,
    key: String,
    mesh: String,
    /// Which distinct cell run gives its counts (Table 3's are Table I's at G = 40 %).
    run: usize,
}

/// The distinct cells of Tables 3, 4 and I and every paper cell with the run that gives it.
fn all_cells(
    s: &Settings,
    cs: &study::grids::CellSettings,
) -> Result<(Vec<CellSpec>, Vec<PaperCell>), RunError> {
    let clearances = study::gearing::clearance_list(&s.clearances, CLEARANCES.name, 200.0)?;
    let randoms = s.random.values(s)?;
    let (mut runs, mut paper): (Vec<CellSpec>, Vec<PaperCell>) = (Vec::new(), Vec::new());
    for c in paper_table_cells(cs, &randoms, &clearances)? {
        let canonical = c.cell.canonical();
        let run = match runs.iter().position(|r| r.canonical() == canonical) {
            Some(i) => i,
            None => {
                runs.push(c.cell.clone());
                runs.len() - 1
            }
        };
        paper.push(PaperCell {
            table: c.id,
            key: c.key,
            mesh: c.cell.mesh,
            run,
        });
    }
    Ok((runs, paper))
}

/// Per model: the tally of Tables 3, 4 and I, and of all three.
fn tallies(cells: &[ModelCell], models: usize) -> Vec<[Tally; 4]> {
    let mut out = vec![[Tally::default(); 4]; models];
    for p in cells {
        let theirs = paper_counts(&p.table, &p.key);
        let t = ["table3", "table4", "tableI"]
            .iter()
            .position(|&id| id == p.table)
            .unwrap_or(0);
        for (m, tally) in out.iter_mut().enumerate() {
            tally[t].add(&p.counts[m], theirs);
            tally[3].add(&p.counts[m], theirs);
        }
    }
    out
}

/// The verdict of a model's counts: Table 4's jams consistent in at least 95 of 105, and of all
/// 345 at least 280 jams and 320 disengagements.
fn reproduces(t: &[Tally; 4]) -> bool {
    let all = &t[3];
    t[1].jams_consistent * 105 >= 95 * t[1].jams_compared
        && all.jams_consistent * 345 >= 280 * all.jams_compared
        && all.dis_consistent * 345 >= 320 * all.dis_compared
}

/// The models' tallies against the paper's counts, with the verdict.
fn counts_table(models: &[(String, String)], tallies: &[[Tally; 4]], trials: u64) -> Table {
    let mut t = Table::new(
        format!(
            "The paper's counts of Tables 3, 4 and I consistent with ours under each motion model (Fisher's exact two-sample test at 5 %; ours {trials} trials per cell, the paper's 200)"
        ),
        [
            "model",
            "Table 3 jams",
            "Table 3 dis.",
            "Table 4 jams",
            "Table I jams",
            "Table I dis.",
            "all jams",
            "all dis.",
            "reproduces the counts",
        ],
    );
    for ((name, _), tally) in models.iter().zip(tallies) {
        let s = |x: &Tally, jams: bool| {
            if jams {
                share(x.jams_consistent, x.jams_compared)
            } else {
                share(x.dis_consistent, x.dis_compared)
            }
        };
        t.row(vec![
            name.clone(),
            s(&tally[0], true),
            s(&tally[0], false),
            s(&tally[1], true),
            s(&tally[2], true),
            s(&tally[2], false),
            s(&tally[3], true),
            s(&tally[3], false),
            if reproduces(tally) { "yes" } else { "no" }.to_string(),
        ]);
    }
    t.note("Reproduces the counts: Table 4's jams consistent in at least 95 of 105 cells, and of all 345 cells at least 280 jam counts and 320 disengagement counts consistent. Table 4's disengagements are all 0 in the paper and are compared within `all dis.`.");
    t.note(power_note(trials));
    t.note("Cells: Table 3 (Cases A-D at G = 40 %), Table 4 (random error only, its grid of rows) and Table I (Cases A-D at its clearances), each mesh on its own, the listed driver driving, one turn of the larger gear, the paper's initial angle drawn per trial; every model runs the same gears and driver angle of trial t. Table I's 40 % rows are Table 3's cells, printed twice by the paper and compared twice.");
    t
}

/// What a count of `trials` can tell apart from the paper's counts of 200: the range of our
/// counts the two-sample test finds consistent with its 2 and its 100 of 200.
fn power_note(trials: u64) -> String {
    let range = |paper: u64| {
        let ks: Vec<u64> = (0..=trials)
            .filter(|&k| presentation::cells::consistent_with_paper(k, trials, Some(paper)))
            .collect();
        match (ks.first(), ks.last()) {
            (Some(lo), Some(hi)) => format!("{lo} to {hi}"),
            _ => "none".to_string(),
        }
    };
    format!(
        "Power: with {trials} trials a cell, our counts from {} of {trials} are consistent with the paper's 2 of {PAPER_TRIALS}, and from {} with its 100 of {PAPER_TRIALS}: fewer trials make every share higher and the verdict weaker; it means something at {PAPER_TRIALS} trials (`--set trials={PAPER_TRIALS}`).",
        range(2),
        range(100)
    )
}

/// Table 4's jams summed over its rows, per mesh, under each model and in the paper.
fn table4_sums(r: &Results, trials: u64) -> Table {
    let mut head = vec!["model".to_string()];
    head.extend(TABLE4_MESHES.iter().map(|m| m.to_string()));
    head.push("all 15 meshes".into());
    let mut t = Table::new(
        format!(
            "Table 4's jams summed over its rows, per mesh (ours scaled to {PAPER_TRIALS} trials a cell from {trials})"
        ),
        head,
    );
    let scale = PAPER_TRIALS as f64 / trials as f64;
    let sum = |mesh: Option<&str>, value: &dyn Fn(&ModelCell) -> Option<u64>| -> u64 {
        r.cells
            .iter()
            .filter(|p| p.table == "table4" && mesh.is_none_or(|m| p.mesh == m))
            .filter_map(value)
            .sum()
    };
    let mut row = vec!["paper".to_string()];
    for mesh in TABLE4_MESHES.iter().map(Some).chain([None]) {
        row.push(sum(mesh.copied(), &|p| paper_counts(&p.table, &p.key).0).to_string());
    }
    t.row(row);
    for (m, (model, _)) in r.models.iter().enumerate() {
        let mut row = vec![model.clone()];
        for mesh in TABLE4_MESHES.iter().map(Some).chain([None]) {
            let ours = sum(mesh.copied(), &|p| Some(p.counts[m].jams));
            row.push(fmt_f64(ours as f64 * scale, 0));
        }
        t.row(row);
    }
    t.note(format!(
        "The paper's sums are its own Table 4 counts added up (paper.ron); its text singles out these meshes (largest and smallest tolerances). {} meshes in the gearing.",
        r.meshes.len()
    ));
    t
}

/// Figure 2's pair under each model against the closed form.
fn figure2_table(models: &[(String, String)], rows: &[Figure2], step: f64) -> Table {
    let mut t = Table::new(
        format!(
            "Figure 2's pair (N1 = N2 = 8, R = 200, r = 100, D = 310) against Thorndike's closed form [I]/[II], one driver turn sampled every {} deg",
            fmt_f64(step, 3)
        ),
        [
            "model",
            "max |theta - closed form| [deg]",
            "at its own steps [deg]",
            "TD sigma [deg]",
            "closed form's TD sigma [deg]",
            "on the closed form",
        ],
    );
    for ((name, _), r) in models.iter().zip(rows) {
        let own = r.max_diff_own.unwrap_or(r.max_diff);
        t.row(vec![
            name.clone(),
            below_or(r.max_diff),
            r.max_diff_own.map_or_else(|| "-".to_string(), below_or),
            fmt_f64(r.sigma, 4),
            fmt_f64(r.closed_sigma, 4),
            if own < 0.01 * r.closed_sigma {
                "yes"
            } else {
                "no"
            }
            .to_string(),
        ]);
    }
    t.note("Start: phi' = 0, the driven gear touching a driver tooth behind (theta'o = theta'(0), the paper's Figure III frame); a model that would place the driven gear at its own drawn angle starts so here. A stepped program knows the driven angle at its steps only (joined by straight lines between them), so its difference is also given at its steps. On the closed form: the largest difference (at its own steps, where it has them) below 1 % of the closed form's TD sigma.");
    t
}

/// A difference in degrees: `< 1e-N` below 1e-6 (stable across machines), else 4 decimals.
fn below_or(x: f64) -> String {
    if x < 1e-6 {
        if x == 0.0 {
            return "0".into();
        }
        return format!("< 1e{}", x.log10().floor() as i32 + 1);
    }
    fmt_f64(x, 4)
}

/// Table 1's five pointers under each model beside the paper's σ.
fn table1_table(
    models: &[(String, String)],
    sigmas: &[Vec<Vec<PointerSigma>>],
    trials: u64,
) -> Table {
    let mut head = vec!["model".to_string()];
    head.extend(
        POINTERS
            .iter()
            .map(|(p, _)| format!("{p} sigma: ours / paper")),
    );
    let mut t = Table::new(
        format!(
            "Table 1: sigma of the five pointers' Theoretical Difference with ideal teeth, mean of {trials} trials [deg], ours / paper (ratio)"
        ),
        head,
    );
    for ((name, _), per_trial) in models.iter().zip(sigmas) {
        let mut row = vec![name.clone()];
        for (i, (name, _)) in POINTERS.iter().enumerate() {
            let values: Vec<f64> = per_trial.iter().map(|t| t[i].sigma).collect();
            let mean = values.iter().sum::<f64>() / values.len().max(1) as f64;
            let paper =
                presentation::paper::get("table1", &format!("{name}.sigma")).map(|r| r.value);
            row.push(match paper {
                Some(p) => format!(
                    "{} / {} ({})",
                    fmt_f64(mean, 4),
                    fmt_f64(p, 3),
                    fmt_f64(mean / p, 2)
                ),
                None => fmt_f64(mean, 4),
            });
        }
        t.row(row);
    }
    t.note("Each pointer's train composed mesh by mesh under the model: each mesh's driver runs from an initial angle drawn uniformly within its pitch (in chain order from the trial's stream, as Table 1 draws them, so the push model's row is Table 1's runs), its driven angle is the next mesh's driver angle, and the pointer's TD is sampled evenly over the run, through any jam. A model that places the driven gear at its own angle draws it from a stream of its own.");
    t
}

/// Figure IV's shape under one model: meshes with σ smallest at 40-50 %, meshes with σ
/// largest at the smallest clearance with a σ, and the median of the largest clearance with a σ.
fn fig_iv_table(r: &Results) -> Table {
    let (labels, clearances) = (&r.meshes, &r.fig_iv_clearances);
    let mut t = Table::new(
        format!(
            "Figure IV's shape: sigma of each ideal mesh's driven gear against G = {} %",
            clearances
                .iter()
                .map(|c| fmt_f64(*c, 0))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        [
            "model",
            "meshes with a sigma",
            "smallest at 40-50 %",
            "largest at the smallest G",
            "G of the smallest sigma (median)",
            "largest G with a sigma (median)",
        ],
    );
    for ((name, _), per_pair) in r.models.iter().zip(&r.fig_iv) {
        let mut with = 0;
        let (mut min_mid, mut max_low) = (0, 0);
        let (mut argmins, mut lasts) = (Vec::new(), Vec::new());
        for pts in per_pair {
            let valid: Vec<(f64, f64)> = clearances
                .iter()
                .zip(pts)
                .filter(|(_, p)| p.sigma.is_finite())
                .map(|(&g, p)| (g, p.sigma))
                .collect();
            if valid.is_empty() {
                continue;
            }
            with += 1;
            let min = valid
                .iter()
                .copied()
                .min_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((f64::NAN, f64::NAN));
            let max = valid
                .iter()
                .copied()
                .max_by(|a, b| a.1.total_cmp(&b.1))
                .unwrap_or((f64::NAN, f64::NAN));
            min_mid += usize::from((40.0..=50.0).contains(&min.0));
            max_low += usize::from(max.0 == valid[0].0);
            argmins.push(min.0);
            lasts.push(valid[valid.len() - 1].0);
        }
        t.row(vec![
            name.clone(),
            format!("{with} of {}", labels.len()),
            format!("{min_mid} of {with}"),
            format!("{max_low} of {with}"),
            median(&mut argmins).map_or_else(|| "-".into(), |v| fmt_f64(v, 1)),
            median(&mut lasts).map_or_else(|| "-".into(), |v| fmt_f64(v, 1)),
        ]);
    }
    t.note("Figure IV (Appendix II): 'a maximum value when the separation is minimal, close to 10%. Then, a minimum occurs around 40% to 50% separation', and 'no values exceeding 87%'. Each run: the mesh's ideal gears, one turn of the larger gear from phi = 0 with the driven gear touching; no sigma where the run jams under the rule or no tooth ever moves the driven gear (a run that disengages keeps its sigma).");
    t
}

fn median(v: &mut [f64]) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// The models compared and what each does.
fn models_table(models: &[(String, String)]) -> Table {
    let mut t = Table::new(
        "The motion models compared (`motion`, one plugin file each)",
        ["model", "what the driven gear does"],
    );
    for (name, summary) in models {
        t.row(vec![name.clone(), summary.clone()]);
    }
    t.note(format!(
        "Default: {} (every other table runs it).",
        motion::DEFAULT
    ));
    t
}

/// Every cell under every model, as CSV.
fn cells_csv(r: &Results) -> String {
    let mut s = String::from("table,key,mesh,model,trials,jams,dis,paper_jams,paper_dis\n");
    for p in &r.cells {
        let (pj, pd) = paper_counts(&p.table, &p.key);
        let show = |v: Option<u64>| v.map_or_else(String::new, |v| v.to_string());
        for ((model, _), c) in r.models.iter().zip(&p.counts) {
            s.push_str(&registry::csv_row!(
                p.table,
                p.key,
                p.mesh,
                model,
                c.trials,
                c.jams,
                c.disengagements,
                show(pj),
                show(pd)
            ));
        }
    }
    s
}

/// Figure IV's σ under every model, as CSV.
fn fig_iv_csv(r: &Results) -> String {
    let mut s = String::from("model,mesh,clearance,sigma_deg,jammed,disengaged\n");
    for ((model, _), per_pair) in r.models.iter().zip(&r.fig_iv) {
        for (label, pts) in r.meshes.iter().zip(per_pair) {
            for (g, p) in r.fig_iv_clearances.iter().zip(pts) {
                let sigma = if p.sigma.is_finite() {
                    p.sigma.to_string()
                } else {
                    String::new()
                };
                s.push_str(&registry::csv_row!(
                    model,
                    label,
                    g,
                    sigma,
                    p.jammed,
                    p.disengaged
                ));
            }
        }
    }
    s
}

#[cfg(test)]
#[path = "../plugin_tests/motion_models.rs"]
mod tests;
