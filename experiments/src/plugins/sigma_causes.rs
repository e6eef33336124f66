//! `sigma-causes`: why our σ differs from the paper's, by experiment. Two open differences:
//! Figure IV's σ has its minimum at 55-75 % clearance for every mesh where the paper
//! sees it "around 40% to 50%", and Table 1's σ is 1.21-1.27 times the paper's. Each candidate
//! reading of the paper's inputs and method (radii, tooth height, centre distance, how the
//! Theoretical Difference is sampled and summarised, the initial angles) is run side by side on
//! the same draws, so the table shows which one moves ours onto the paper's.

use std::collections::BTreeMap;

use registry::{Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use train::Gearing;

use study::pointers::POINTERS;
use study::readings::{
    GEOMETRY, Minimum, PointerSigma, Starts, figure_iv_minima, mechanism, table1_trials, tip_radii,
};

registry::params! {
    /// `trials`: Table 1 trials per reading (random initial angles; the same draws for every reading).
    const TRIALS = Param::new("trials", "2", "Table 1 trials per reading (random initial angles; the same draws for every reading)", registry::Kind::count(2, registry::MAX_TRIALS, "a pooled sigma needs two trials")).recorded();
    /// `clearance`: Table 1's clearance G of every mesh (before a reading's extra centre distance).
    /// Not the gearing group's `clearance` ([`study::gearing::CLEARANCE`]): this experiment runs the
    /// embedded gearings only, so its clearance is Table 1's input alone, under the same name.
    const TABLE1_CLEARANCE = Param::new("clearance", "40", "Table 1's clearance G of every mesh (before a reading's extra centre distance)", registry::Kind::positive(100.0, "% of the tooth height h")).unit("% of h").a_clearance();
}

/// `samples_per_engagement`: TD samples per tooth engagement of the busiest mesh (Table 1's default).
const SAMPLES_PER_ENGAGEMENT: Param = study::pointers::per_engagement(
    "16",
    "TD samples per tooth engagement of the busiest mesh (Table 1's default)",
);

registry::params! {
    /// `draws`: Figure IV with Case A errors: manufactured pairs per mesh (each swept over every G).
    const DRAWS = Param::new("draws", "3", "Figure IV with Case A errors: manufactured pairs per mesh (each swept over every G)", registry::Kind::count(1, registry::MAX_COUNT as u64, "a mean needs one draw"));
}

/// `samples`: TD samples per pair run of the Figure IV sweep (figIV's default).
const SAMPLES: Param = registry::samples(
    "2000",
    "TD samples per pair run of the Figure IV sweep (figIV's default)",
);

/// The settings: Table 1's trials, clearance and samples per engagement, and the Figure IV
/// sweep's Case A draws and samples per run.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Table 1 trials per reading ([`TRIALS`]).
    #[param(TRIALS)]
    pub trials: u64,
    /// Table 1's clearance G, % of h ([`TABLE1_CLEARANCE`]).
    #[param(TABLE1_CLEARANCE)]
    pub clearance: f64,
    /// TD samples per tooth engagement of the busiest mesh ([`SAMPLES_PER_ENGAGEMENT`]).
    #[param(SAMPLES_PER_ENGAGEMENT)]
    pub samples_per_engagement: usize,
    /// Figure IV with Case A errors: manufactured pairs per mesh ([`DRAWS`]).
    #[param(DRAWS)]
    pub draws: usize,
    /// TD samples per pair run of the Figure IV sweep ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
}

/// Each reading's Figure IV minima and Table 1 σ.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Results {
    /// Figure IV's meshes (the embedded Freeth 2006 gearing's, in its order).
    pub meshes: Vec<String>,
    /// Per column of Figure IV's table (the geometry readings of `GEOMETRY`, then Case A
    /// errors, then the start in the backlash), per mesh: where its σ(G) is smallest, how deep,
    /// and the largest G on the curve (% of h); `None` where no grid point runs.
    pub minima: Vec<Vec<Option<Minimum>>>,
    /// Table 1's rows, one per reading, in print order.
    pub table1: Vec<Table1Row>,
}

/// One reading's Table 1: σ of each pointer, the mean over the trials.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Table1Row {
    /// The reading, numbered as the table prints it.
    pub reading: String,
    /// Whether it keeps to the paper's inputs, and how.
    pub stated: String,
    /// Each pointer's mean σ over the trials, degrees, in [`POINTERS`]' order (`None`: no
    /// finite value).
    pub sigmas: Vec<Option<f64>>,
}

/// Why our σ differs from the paper's.
pub struct SigmaCauses;

impl registry::Experiment for SigmaCauses {
    const ID: &'static str = "sigma-causes";
    const TITLE: &'static str = "Why our sigma differs from the paper's: Figure IV's minimum and Table 1's sigma under each candidate reading";
    const PAPER_ITEM: &'static str = "Table 1 and Figure IV (beyond the paper)";
    const PLACE: Place = Place::Beyond(80);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        let g = Gearing::freeth2006();
        let g2021 = Gearing::builtin("freeth2021").ok_or_else(|| {
            RunError::Internal("the embedded freeth2021 gearing is missing".into())
        })?;
        // ---- Figure IV: σ against G for each mesh under each geometry reading. ----
        let grid: Vec<f64> = (0..=16).map(|i| 20.0 + 5.0 * f64::from(i)).collect();
        let radii: Vec<BTreeMap<String, f64>> = GEOMETRY
            .iter()
            .map(|r| tip_radii(&g, &g2021, r.radii, r.tooth_height))
            .collect::<Result<_, _>>()?;
        let at = figure_iv_minima(run.engine(), &g, &radii, &grid, (s.draws, s.samples))?;
        let columns = GEOMETRY.len() + 2;
        let minima = (0..columns)
            .map(|ri| {
                (0..g.meshes().len())
                    .map(|mi| at.get(&(ri, mi)).copied().flatten())
                    .collect()
            })
            .collect();

        // ---- Table 1: σ of the five pointers under every reading. ----
        let per_trials = (s.samples_per_engagement, s.trials);
        let rows = table1_rows(run, &g, &radii, s.clearance, per_trials)?;
        Ok(Results {
            meshes: g.meshes().iter().map(|m| m.label.clone()).collect(),
            minima,
            table1: rows
                .into_iter()
                .map(|(reading, stated, sigmas)| Table1Row {
                    reading,
                    stated: stated.to_owned(),
                    sigmas: sigmas
                        .into_iter()
                        .map(|x| x.is_finite().then_some(x))
                        .collect(),
                })
                .collect(),
        })
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        let paper_from =
            presentation::paper::get("sigma-causes", "figIV.minimum_from").map(|r| r.value);
        let paper_to =
            presentation::paper::get("sigma-causes", "figIV.minimum_to").map(|r| r.value);
        let fig = figure_iv_table(r, s.draws, (paper_from, paper_to));
        let t1 = table1_table(&r.table1, s.trials, s.clearance, s.samples_per_engagement);
        Ok(Report {
            tables: vec![fig, t1],
            trials: s.trials * (GEOMETRY.len() as u64 + 2),
            ..Default::default()
        })
    }
}

registry::register!(SigmaCauses);

/// The run length of a pointer as `table1` runs it by default (the caption's turns of b).
fn caption_turns(p: &Param) -> Result<f64, RunError> {
    p.default
        .parse()
        .map_err(|_| RunError::Internal(format!("run length {} is not a number", p.name)))
}

/// Mean over trials of one field, for pointer `i`.
fn mean_of(trials: &[Vec<PointerSigma>], i: usize, f: impl Fn(&PointerSigma) -> f64) -> f64 {
    let v: Vec<f64> = trials
        .iter()
        .map(|t| t.get(i).map_or(f64::NAN, &f))
        .collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// σ of every trial's samples pooled into one series: (1/T) Σ σ_t² + (1/T) Σ (m_t - m̄)², exact
/// because every trial has the same number of samples.
fn pooled(trials: &[Vec<PointerSigma>], i: usize) -> f64 {
    let m = mean_of(trials, i, |p| p.mean);
    let v = mean_of(trials, i, |p| {
        p.sigma * p.sigma + (p.mean - m) * (p.mean - m)
    });
    v.sqrt()
}

/// Each pointer's run as table1 runs it by default, times `span`: (pointer, input turns).
fn turns(span: f64) -> Result<Vec<(&'static str, f64)>, RunError> {
    POINTERS
        .iter()
        .map(|&(name, param)| Ok((name, caption_turns(param)? * span)))
        .collect()
}

/// "median (lowest-highest)" of sorted values, `digits` after the point; "-" for none.
fn median_range(sorted: &[f64], digits: usize) -> String {
    match (sorted.first(), sorted.last()) {
        (Some(lo), Some(hi)) => format!(
            "{} ({}-{})",
            fmt_f64(sorted[sorted.len() / 2], digits),
            fmt_f64(*lo, digits),
            fmt_f64(*hi, digits)
        ),
        _ => "-".into(),
    }
}

/// Figure IV's notes: what each column reads, and what G and a mesh's minimum are.
fn figure_iv_notes(fig: &mut Table, draws: usize, case_a: usize, in_backlash: usize) {
    for (i, r) in GEOMETRY.iter().enumerate() {
        fig.note(format!(
            "({}) {} [paper's inputs: {}]",
            i + 1,
            r.name,
            r.stated
        ));
    }
    fig.note(format!(
        "({}) the gears of (1) with Case A errors (edmunds-split: random 0.04 of the pitch, no systematic error): mean sigma of {draws} manufactured pairs per mesh, each swept over every G from one random initial angle, through jams [paper's inputs: no: Figure IV is read as ideal]",
        case_a + 1
    ));
    fig.note(format!(
        "({}) the gears of (1), ideal, with the driven gear at rest half-way through the backlash at the start (not touching): it waits until a driver tooth takes it up, and that lost motion is part of the run [paper's inputs: another reading (the paper's initial angles are drawn; this one puts the driven gear mid-way)]",
        in_backlash + 1
    ));
    fig.note("G is the clearance of the paper's formula, D = R1 + R2 - h + G (reading (6) adds its extra centre distance to it; reading (7) reads G in % of the flank length); a mesh's minimum is the grid point of its smallest sigma of the driven gear's Theoretical Difference over one turn of the larger gear (ideal gears: figIV's runs, from driver angle 0, at grid points that run without a jam or disengagement; '-': none does).");
}

/// Figure IV's table: each mesh's clearance of the smallest σ under each column (`at`), and
/// per column how many fall within the paper's range, their range, the depth of the minimum
/// and the largest clearance that runs.
fn figure_iv_table(
    r: &Results,
    draws: usize,
    (paper_from, paper_to): (Option<f64>, Option<f64>),
) -> Table {
    let at = |ri: usize, mi: usize| r.minima.get(ri).and_then(|c| c.get(mi)).copied().flatten();
    let meshes = r.meshes.len();
    let (case_a, in_backlash) = (GEOMETRY.len(), GEOMETRY.len() + 1);
    let columns = in_backlash + 1;
    let mut header = vec!["mesh".to_string()];
    header.extend((1..=columns).map(|i| format!("({i})")));
    let mut fig = Table::new(
        "Figure IV: the clearance G [% of h] of the smallest sigma of each mesh under each reading (G = 20-100 % by 5)",
        header,
    );
    for (mi, m) in r.meshes.iter().enumerate() {
        let mut row = vec![m.clone()];
        for ri in 0..columns {
            row.push(at(ri, mi).map_or_else(|| "-".into(), |m| fmt_f64(m.at, 0)));
        }
        fig.row(row);
    }
    let mut inside = vec![format!(
        "minimum within the paper's {}-{} %",
        paper_from.map_or_else(|| "?".into(), |v| fmt_f64(v, 0)),
        paper_to.map_or_else(|| "?".into(), |v| fmt_f64(v, 0))
    )];
    let mut range = vec!["range of the minima".to_string()];
    let mut depth = vec!["sigma at 40 % / smallest sigma: median (range)".to_string()];
    let mut runs = vec![format!(
        "largest G that runs without a jam or disengagement: median (range) [paper: none above {}]",
        presentation::paper::get("clearance", "disengage_above")
            .map_or_else(|| "?".into(), |r| fmt_f64(r.value, 0))
    )];
    for ri in 0..columns {
        let found: Vec<Minimum> = (0..meshes).filter_map(|mi| at(ri, mi)).collect();
        let cs: Vec<f64> = found.iter().map(|m| m.at).collect();
        let mut lasts: Vec<f64> = found.iter().map(|m| m.last).collect();
        lasts.sort_by(f64::total_cmp);
        runs.push(if ri == case_a {
            "-".into()
        } else {
            median_range(&lasts, 0)
        });
        let mut ds: Vec<f64> = found
            .iter()
            .map(|m| m.depth)
            .filter(|d| d.is_finite())
            .collect();
        ds.sort_by(f64::total_cmp);
        depth.push(median_range(&ds, 2));
        let n_in = match (paper_from, paper_to) {
            (Some(a), Some(b)) => cs.iter().filter(|&&c| a <= c && c <= b).count().to_string(),
            _ => "-".into(),
        };
        inside.push(format!("{n_in} of {meshes}"));
        let lo = cs.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = cs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        range.push(format!("{}-{}", fmt_f64(lo, 0), fmt_f64(hi, 0)));
    }
    fig.row(inside);
    fig.row(range);
    fig.row(depth);
    fig.row(runs);
    figure_iv_notes(&mut fig, draws, case_a, in_backlash);
    fig
}

/// One row of the Table 1 comparison: the reading, whether it keeps to the paper's inputs, and
/// each pointer's mean σ.
type Row = (String, &'static str, Vec<f64>);

/// Each pointer's mean σ over the trials, by `f` of each trial's pointer statistics.
fn sigmas(trials: &[Vec<PointerSigma>], f: impl Fn(&PointerSigma) -> f64) -> Vec<f64> {
    (0..POINTERS.len())
        .map(|i| mean_of(trials, i, &f))
        .collect()
}

/// The trials of one reading.
type Trials = Vec<Vec<PointerSigma>>;

/// Table 1's σ under each geometry reading, on its own gears, and the first reading's trials
/// (the baseline the other readings are taken on).
fn geometry_rows(
    run: &Run,
    g: &Gearing,
    radii: &[BTreeMap<String, f64>],
    clearance: f64,
    (per, trials): (usize, u64),
) -> Result<(Vec<Row>, Option<Trials>), RunError> {
    let mut rows: Vec<Row> = Vec::new();
    let mut baseline: Option<Vec<Vec<PointerSigma>>> = None;
    for (ri, r) in GEOMETRY.iter().enumerate() {
        let mech = mechanism(g, &radii[ri], r, clearance)?;
        let key = format!(
            "sigma-causes: table1 trials, reading ({}) {}, G = {clearance} %, {per} samples per engagement, random starts",
            ri + 1,
            r.name
        );
        let t = table1_trials(
            run.engine(),
            &key,
            g,
            &mech,
            Starts::Random,
            &turns(1.0)?,
            per,
            trials,
        )?;
        rows.push((
            format!("({}) {}", ri + 1, r.name),
            r.stated,
            sigmas(&t, |p| p.sigma),
        ));
        if ri == 0 {
            baseline = Some(t);
        }
    }
    Ok((rows, baseline))
}

/// Table 1's σ under every reading: the geometry readings on their own gears (tip radii
/// `radii`), then the sampling, statistic, span and start readings on the first one's, each
/// over `trials` trials at `per` samples per engagement.
fn table1_rows(
    run: &Run,
    g: &Gearing,
    radii: &[BTreeMap<String, f64>],
    clearance: f64,
    (per, trials): (usize, u64),
) -> Result<Vec<Row>, RunError> {
    let (mut rows, baseline) = geometry_rows(run, g, radii, clearance, (per, trials))?;
    let base = baseline.ok_or_else(|| RunError::Internal("no baseline reading".into()))?;
    // (GEOMETRY.len() + 1) and (+ 2) are Figure IV's Case A and backlash columns, not run here.
    let next = GEOMETRY.len() + 3;
    rows.push((
        format!("({next}) TD sampled once per engagement of the busiest mesh (on (1))"),
        "another reading (paper silent)",
        sigmas(&base, |p| p.sigma_coarse),
    ));
    rows.push((
        format!(
            "({}) TD sampled {} times per engagement (on (1))",
            next + 1,
            2 * per
        ),
        "another reading (paper silent)",
        sigmas(&base, |p| p.sigma_fine),
    ));
    rows.push((
        format!(
            "({}) sigma of all trials' samples pooled, not averaged per trial (on (1))",
            next + 2
        ),
        "another reading",
        (0..POINTERS.len()).map(|i| pooled(&base, i)).collect(),
    ));
    let mech = mechanism(g, &radii[0], &GEOMETRY[0], clearance)?;
    let halved = table1_trials(
        run.engine(),
        &format!(
            "sigma-causes: table1 trials, reading (1) with every run half as long, G = {clearance} %, {per} samples per engagement, random starts"
        ),
        g,
        &mech,
        Starts::Random,
        &turns(0.5)?,
        per,
        trials,
    )?;
    rows.push((
        format!(
            "({}) every run half the caption's length (on (1))",
            next + 3
        ),
        "no: caption's lengths",
        sigmas(&halved, |p| p.sigma),
    ));
    let zero = table1_trials(
        run.engine(),
        &format!(
            "sigma-causes: table1 trials, reading (1) with every mesh from driver angle 0, G = {clearance} %, {per} samples per engagement"
        ),
        g,
        &mech,
        Starts::Zero,
        &turns(1.0)?,
        per,
        trials,
    )?;
    rows.push((
        format!(
            "({}) every mesh starts at driver angle 0 (on (1))",
            next + 4
        ),
        "no: paper draws them",
        sigmas(&zero, |p| p.sigma),
    ));
    Ok(rows)
}

/// The Table 1 comparison: each reading's σ of every pointer beside the paper's, with the
/// ratio's range over Lunar to Games.
fn table1_table(rows: &[Table1Row], trials: u64, clearance: f64, per: usize) -> Table {
    let mut header = vec!["reading".to_string(), "paper's inputs".to_string()];
    header.extend(
        POINTERS
            .iter()
            .map(|(n, _)| format!("{n} sigma [deg] (ours/paper)")),
    );
    header.push("ours/paper, Lunar to Games".into());
    let mut t1 = Table::new(
        format!(
            "Table 1: sigma of each pointer [deg], mean of {trials} trials (the same draws for every reading), and ours/paper"
        ),
        header,
    );
    let paper: Vec<Option<f64>> = POINTERS
        .iter()
        .map(|(n, _)| presentation::paper::get("table1", &format!("{n}.sigma")).map(|r| r.value))
        .collect();
    let mut paper_row = vec!["paper (Table 1)".to_string(), "-".to_string()];
    paper_row.extend(
        paper
            .iter()
            .map(|p| p.map_or_else(|| "-".into(), |v| fmt_f64(v, 3))),
    );
    paper_row.push("-".into());
    for r in rows {
        let mut row = vec![r.reading.clone(), r.stated.clone()];
        let mut ratios = Vec::new();
        // A σ stored as none was not finite: printed as it was computed.
        let sig = r.sigmas.iter().map(|s| s.unwrap_or(f64::NAN));
        for (i, s) in sig.enumerate() {
            let ratio = paper[i].map(|p| s / p);
            if i < 4
                && let Some(q) = ratio
            {
                ratios.push(q);
            }
            row.push(format!(
                "{} ({})",
                fmt_f64(s, 4),
                ratio.map_or_else(|| "-".into(), |q| fmt_f64(q, 2))
            ));
        }
        let (lo, hi) = ratios
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &q| {
                (a.min(q), b.max(q))
            });
        row.push(format!("{}-{}", fmt_f64(lo, 2), fmt_f64(hi, 2)));
        t1.row(row);
    }
    t1.row(paper_row);
    t1.note(format!(
        "Ideal gears, G = {clearance} % (plus the reading's extra centre distance), runs of the caption's length (Lunar 1, Metonic and Games 3.8, Saros and Exeligmos 4.5 turns of b), {per} TD samples per engagement of the busiest mesh unless the reading says otherwise; sigma per trial, then the mean over trials, as table1."
    ));
    t1.note("Ours/paper, Lunar to Games: the smallest and largest ours/paper of the Lunar, Metonic, Saros and Games pointers (the 1.21-1.27 that first prompted this study; Exeligmos, 1.8, has a cause of its own: see table1's note).");
    t1
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn pooled_sigma_is_the_sigma_of_all_samples_together() {
        let a = [0.1, -0.3, 0.25, 0.05];
        let b = [1.0, 1.2, 0.7, 0.9];
        let trial = |x: &[f64]| {
            let s = stats::pointer_stats(x);
            vec![PointerSigma {
                sigma: s.sigma,
                mean: s.mean,
                ..Default::default()
            }]
        };
        let all: Vec<f64> = a.iter().chain(&b).copied().collect();
        let want = stats::pointer_stats(&all).sigma;
        let got = pooled(&[trial(&a), trial(&b)], 0);
        assert!((got - want).abs() < 1e-12, "{got} vs {want}");
    }
}
