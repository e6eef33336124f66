//! `tolerance`: each mesh's largest tolerable random error (no systematic error, G = 40 %, as in
//! Table 4) found by a sequential search instead of Table 4's fixed grid: bisection on the random
//! error, and at each probed value trials added a batch at a time until the jam rate is clearly
//! below or above the rule's threshold (exact 95 % interval), or the paper's count rule decides
//! at the cap. Compared with the grid-derived value (Table 4 by the rule) and the paper's E. max,
//! with the pair turns each needed.

use registry::{Context, Experiment, OutputFile, Param, Report, RunError, Table};
use stats::clopper_pearson95;

use crate::emax::{paper_random, show};
use study::cell::{CellRange, Counts, Purpose, label, run_cell_ranges};
use study::grids::CellSettings;
use study::tolerance::{self, RANDOM_STEP, RULE};

const SEARCH_LO: Param = Param {
    name: "search_lo",
    default: "0.02",
    unit: "pitch",
    help: "lower end of the searched random error (fraction of the pitch 360/N)",
    kind: study::tolerance::RANDOM_KIND,
};

const SEARCH_HI: Param = Param {
    name: "search_hi",
    default: "0.08",
    unit: "pitch",
    help: "upper end of the searched random error",
    kind: study::tolerance::RANDOM_KIND,
};

const RESOLUTION: Param = Param {
    name: "resolution",
    default: "0.0025",
    unit: "pitch",
    help: "the bisection stops when the bracket is at most this wide",
    kind: registry::Kind::positive(f64::INFINITY, ""),
};

const BATCH: Param = Param {
    name: "batch",
    default: "20",
    unit: "",
    help: "trials added to a probed value at a time",
    kind: registry::Kind::count(1, registry::MAX_TRIALS, ""),
};

const CAP: Param = Param {
    name: "cap",
    default: "200",
    unit: "",
    help: "most trials at one probed value, where the paper's count rule decides; also the trials per cell of the Table 4 grid compared with (the paper: 200)",
    kind: registry::Kind::count(1, registry::MAX_TRIALS, ""),
};

const PARAMS: &[Param] = &[SEARCH_LO, SEARCH_HI, RESOLUTION, RULE, BATCH, CAP];

registry::inventory::submit! {
    Experiment {
        id: "tolerance",
        title: "Largest tolerable random error of each mesh by a sequential search (bisection, trials added until the jam rate is clearly below or above the rule), against Table 4's grid",
        paper_item: "Section 5, Tables 4-5 (tolerance by sequential search; beyond the paper)",
        params: PARAMS,
        groups: &[study::gearing::GROUP, study::errors::GROUP, study::tolerance::RANDOM_GRID, study::events::GROUP],
        config: None,
        run,
    }
}

/// What the trials of one probed value say so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Decision {
    /// The jam rate is at most the rule: the value is tolerable.
    Below,
    /// The jam rate exceeds the rule: the value is not tolerable.
    Above,
    /// Not settled: run more trials.
    Continue,
}

/// The sequential test of one probed value after `trials` trials with `jams` jams, under a rule of
/// `rule_percent` % and at most `cap` trials:
/// - the exact (Clopper-Pearson) 95 % interval of the jam rate lies entirely below the threshold:
///   [`Decision::Below`]; entirely above: [`Decision::Above`];
/// - the count rule at the cap (at most ⌊rule·cap/100⌋ jams) is already settled whatever the
///   remaining trials give (too many jams already, or so few that even all remaining trials
///   jamming would pass): its answer;
/// - at the cap: the count rule;
/// - otherwise [`Decision::Continue`].
pub(crate) fn decide(jams: u64, trials: u64, rule_percent: f64, cap: u64) -> Decision {
    let allowed = tolerance::allowed_jams(cap, rule_percent);
    if trials >= cap {
        return if jams <= tolerance::allowed_jams(trials, rule_percent) {
            Decision::Below
        } else {
            Decision::Above
        };
    }
    if trials == 0 {
        return Decision::Continue;
    }
    let threshold = rule_percent / 100.0;
    let ci = clopper_pearson95(jams, trials);
    if ci.hi < threshold {
        return Decision::Below;
    }
    if ci.lo > threshold || jams > allowed {
        return Decision::Above;
    }
    if jams + (cap - trials) <= allowed {
        return Decision::Below;
    }
    Decision::Continue
}

/// One probed value and what its trials gave.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Probe {
    /// Random error (fraction of the pitch).
    pub value: f64,
    /// Trials run at it and their jams.
    pub counts: Counts,
    /// Below (tolerable) or Above; Continue while running.
    pub decision: Decision,
}

/// The search of one mesh: the bracket so far and the probes run.
#[derive(Debug, Clone)]
pub(crate) struct Search {
    lo: f64,
    hi: f64,
    resolution: f64,
    /// Largest value found tolerable.
    pub pass: Option<f64>,
    /// Smallest value found not tolerable.
    pub fail: Option<f64>,
    /// Every probe, in the order run; the last one may still be running.
    pub probes: Vec<Probe>,
}

impl Search {
    fn new(lo: f64, hi: f64, resolution: f64) -> Search {
        Search {
            lo,
            hi,
            resolution,
            pass: None,
            fail: None,
            probes: Vec::new(),
        }
    }

    /// The value to probe next, or `None` when the search is over. Bisection of
    /// [pass or lo, fail or hi] while it is wider than the resolution (assuming the jam rate
    /// grows with the error); then `lo` itself when nothing passed (is even `lo` too much?), and
    /// `hi` itself when nothing failed (does the mesh tolerate the whole range?).
    fn next_value(&self) -> Option<f64> {
        let lower = self.pass.unwrap_or(self.lo);
        let upper = self.fail.unwrap_or(self.hi);
        if upper - lower > self.resolution * (1.0 + 1e-9) {
            let mid = round9((lower + upper) / 2.0);
            if mid > lower && mid < upper {
                return Some(mid);
            }
        }
        if self.pass.is_none() && self.fail != Some(self.lo) {
            return Some(self.lo);
        }
        if self.fail.is_none() && self.pass != Some(self.hi) {
            return Some(self.hi);
        }
        None
    }

    /// Starts the next probe; `false` when the search is over.
    fn start_probe(&mut self) -> bool {
        match self.next_value() {
            Some(value) => {
                self.probes.push(Probe {
                    value,
                    counts: Counts::default(),
                    decision: Decision::Continue,
                });
                true
            }
            None => false,
        }
    }

    /// The probe running, if any.
    fn running(&self) -> Option<&Probe> {
        self.probes
            .last()
            .filter(|p| p.decision == Decision::Continue)
    }

    /// Adds a batch's counts to the running probe and applies the sequential test.
    fn add(&mut self, c: Counts, rule: f64, cap: u64) {
        let Some(p) = self.probes.last_mut() else {
            return;
        };
        p.counts.jams += c.jams;
        p.counts.disengagements += c.disengagements;
        p.counts.failures += c.failures;
        p.counts.trials += c.trials;
        p.counts.engagements += c.engagements;
        p.decision = decide(p.counts.jams, p.counts.trials, rule, cap);
        match p.decision {
            Decision::Below => self.pass = Some(p.value),
            Decision::Above => self.fail = Some(p.value),
            Decision::Continue => {}
        }
    }

    /// Pair turns run.
    pub fn trials(&self) -> u64 {
        self.probes.iter().map(|p| p.counts.trials).sum()
    }

    /// Tooth engagements simulated.
    pub fn engagements(&self) -> u64 {
        self.probes.iter().map(|p| p.counts.engagements).sum()
    }
}

/// `v` rounded to nine decimals (as the grids are), so a probed value has a short canonical text.
fn round9(v: f64) -> f64 {
    (v * 1e9).round() / 1e9
}

/// The search's parameters, checked.
struct Settings {
    lo: f64,
    hi: f64,
    resolution: f64,
    rule: f64,
    batch: u64,
    cap: u64,
}

fn settings(ctx: &Context) -> Result<Settings, RunError> {
    let (lo, hi) = (ctx.get::<f64>(&SEARCH_LO)?, ctx.get::<f64>(&SEARCH_HI)?);
    let resolution = ctx.get::<f64>(&RESOLUTION)?;
    let rule = ctx.get::<f64>(&RULE)?;
    let (batch, cap) = (ctx.get::<u64>(&BATCH)?, ctx.get::<u64>(&CAP)?);
    let short = registry::fmt_number;
    if hi.is_nan() || lo >= hi {
        // Name the one the user set: `search_hi` at or below the default low end, or
        // `search_lo` at or above the high end.
        let hi_set = ctx.changed().iter().any(|(k, _)| *k == SEARCH_HI.name);
        let (field, rule) = if hi_set {
            (
                SEARCH_HI.name,
                format!(
                    "must be greater than {} = {} (got {})",
                    SEARCH_LO.name,
                    short(lo),
                    short(hi)
                ),
            )
        } else {
            (
                SEARCH_LO.name,
                format!(
                    "must be less than {} = {} (got {})",
                    SEARCH_HI.name,
                    short(hi),
                    short(lo)
                ),
            )
        };
        return Err(RunError::bad("--set", field, rule));
    }
    if rule.is_nan() || rule <= 0.0 || rule >= 100.0 {
        return Err(RunError::bad(
            "--set",
            RULE.name,
            format!(
                "must be a percentage strictly between 0 and 100 (got {})",
                short(rule)
            ),
        ));
    }
    if cap < batch {
        return Err(RunError::bad(
            "--set",
            CAP.name,
            format!("must be at least {} = {batch} (got {cap})", BATCH.name),
        ));
    }
    Ok(Settings {
        lo,
        hi,
        resolution,
        rule,
        batch,
        cap,
    })
}

/// Runs every mesh's search in lockstep: each round adds one batch of trials to every mesh's
/// running probe, all in one flat batch of the shared runner (as an input, never sharded: what
/// runs next depends on the counts), so the result does not depend on threads or shards.
fn search(ctx: &Context, cells: &CellSettings, s: &Settings) -> Result<Vec<Search>, RunError> {
    let clearance = cells.clearance()?;
    let meshes = cells.meshes();
    let mut searches: Vec<Search> = meshes
        .iter()
        .map(|_| Search::new(s.lo, s.hi, s.resolution))
        .collect();
    for sr in &mut searches {
        sr.start_probe();
    }
    loop {
        let mut ranges = Vec::new();
        let mut owners = Vec::new();
        for (m, sr) in searches.iter().enumerate() {
            let Some(p) = sr.running() else { continue };
            let params = cells
                .errors
                .params(&[("random", p.value), ("systematic", 0.0)])?;
            let start = p.counts.trials;
            let end = (start + s.batch).min(s.cap);
            ranges.push(CellRange {
                cell: cells.cell(&meshes[m], params, clearance),
                range: start..end,
            });
            owners.push(m);
        }
        if ranges.is_empty() {
            return Ok(searches);
        }
        let counts = run_cell_ranges(ctx.engine(), cells.gearing(), &ranges, Purpose::Input)?;
        for (&m, c) in owners.iter().zip(counts) {
            let sr = &mut searches[m];
            sr.add(c, s.rule, s.cap);
            if sr.running().is_none() {
                sr.start_probe();
            }
        }
    }
}

/// A search's result as printed: the largest tolerable value, `< lo` when even `lo` failed,
/// `>= hi` when even `hi` passed.
fn show_search(sr: &Search, s: &Settings) -> String {
    match sr.pass {
        Some(p) if sr.fail.is_none() => format!(">= {}", label(p, 3)),
        Some(p) => label(p, 3),
        None => format!("< {}", label(s.lo, 3)),
    }
}

/// The notes under the table: how the search brackets and decides, and what the grid ran; the
/// grid's step is `step`, and `inside` and `outside` count the paper's E. max within one
/// resolution of the search's and further.
fn explain(
    table: &mut Table,
    s: &Settings,
    grid: &study::grids::RandomGrid,
    step: f64,
    (inside, outside): (u64, u64),
) {
    let allowed = tolerance::allowed_jams(s.cap, s.rule);
    table.note(format!(
        "Search: bisection of [{}, {}] (assuming the jam rate grows with the error) until the bracket is at most {} wide; the value shown is the largest probed value found tolerable, so the mesh's limit lies between it and the next probed value that failed (CSV). `< {}`: even the lower end failed; `>= {}`: even the upper end passed.",
        label(s.lo, 3),
        label(s.hi, 3),
        label(s.resolution, 3),
        label(s.lo, 3),
        label(s.hi, 3),
    ));
    table.note(format!(
        "Sequential test at each probed value: {} trials at a time, stopping as soon as the exact (Clopper-Pearson) 95 % interval of the jam rate lies entirely below or above {} %, or the count rule at the cap is already settled (more than {allowed} jams); at {} trials the paper's rule decides (at most {allowed} jams). With a 1 % rule and a cap of 200 a tolerable value always runs to the cap (0 of n has an upper bound below 1 % only from n = 368), so the savings come from failing values stopped early and from fewer values probed.",
        s.batch, s.rule, s.cap,
    ));
    table.note(format!(
        "Grid: Table 4's cells ({} values from {} by {}, {} trials each) by the same rule; a probed value on the grid uses the same trial streams as the grid's cell. Paper's E. max within one resolution of the search's: {inside} meshes; further: {outside}.",
        grid.values.len(),
        grid.values.first().map_or_else(|| "-".into(), |v| label(*v, 3)),
        label(step, 3),
        s.cap,
    ));
}

/// The share of a grid's `grid` trials a search saved by running `used` (%; 0 for no grid).
fn saved(used: u64, grid: u64) -> f64 {
    if grid == 0 {
        0.0
    } else {
        100.0 * (1.0 - used as f64 / grid as f64)
    }
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    // Table 4's grid runs `cap` trials a cell, the most a search's probe runs.
    let cells = crate::settings::cells(ctx, &CAP)?;
    let s = settings(ctx)?;
    let clearance = cells.clearance()?;
    // The grid's parameters are checked before anything runs.
    let values = crate::settings::random_grid(ctx)?;
    let searches = search(ctx, &cells, &s)?;
    let grid = study::grids::run_grid(ctx.engine(), &cells, values, s.cap, Purpose::Input)?;
    let grid_tolerable = grid.tolerable(s.cap, s.rule);
    let grid_per_mesh = grid.values.len() as u64 * s.cap;

    let mut table = Table::new(
        format!(
            "Largest tolerable random error of each mesh (rule {} %, no systematic error, G = {clearance} %) [fraction of the pitch]: sequential search against Table 4's grid and the paper's E. max; * where the paper's is more than one resolution ({}) from the search's",
            s.rule,
            label(s.resolution, 3),
        ),
        vec![
            "mesh",
            "search",
            "grid",
            "paper",
            "probes",
            "search pair turns",
            "grid pair turns",
            "saved %",
        ],
    );
    let mut csv = String::from(
        "mesh,search_emax,search_fail,grid_emax,paper_emax,probes,search_trials,grid_trials,saved_percent\n",
    );
    let mut probes_csv = String::from("mesh,probe,random,trials,jams,disengagements,decision\n");
    let (mut inside, mut outside) = (0, 0);
    let (mut used_total, mut grid_total, mut probes_total) = (0, 0, 0);
    for ((mesh, sr), grid_value) in grid.meshes.iter().zip(&searches).zip(&grid_tolerable) {
        let paper = paper_random(mesh);
        let agrees = paper.map(|p| {
            sr.pass
                .is_some_and(|o| (o - p).abs() <= s.resolution * (1.0 + 1e-9))
        });
        match agrees {
            Some(true) => inside += 1,
            Some(false) => outside += 1,
            None => {}
        }
        let used = sr.trials();
        used_total += used;
        grid_total += grid_per_mesh;
        probes_total += sr.probes.len();
        table.row(vec![
            mesh.clone(),
            show_search(sr, &s),
            show(*grid_value, grid.values.first(), 3),
            format!(
                "{}{}",
                paper.map_or_else(|| "-".into(), |p| label(p, 3)),
                if agrees == Some(false) { "*" } else { "" }
            ),
            sr.probes.len().to_string(),
            used.to_string(),
            grid_per_mesh.to_string(),
            format!("{:.0}", saved(used, grid_per_mesh)),
        ]);
        let opt = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
        csv.push_str(&format!(
            "{mesh},{},{},{},{},{},{used},{grid_per_mesh},{:.1}\n",
            opt(sr.pass),
            opt(sr.fail),
            opt(*grid_value),
            opt(paper),
            sr.probes.len(),
            saved(used, grid_per_mesh)
        ));
        for (i, p) in sr.probes.iter().enumerate() {
            probes_csv.push_str(&format!(
                "{mesh},{},{},{},{},{},{:?}\n",
                i + 1,
                p.value,
                p.counts.trials,
                p.counts.jams,
                p.counts.disengagements,
                p.decision
            ));
        }
    }
    table.row(vec![
        "total".into(),
        String::new(),
        String::new(),
        String::new(),
        probes_total.to_string(),
        used_total.to_string(),
        grid_total.to_string(),
        format!("{:.0}", saved(used_total, grid_total)),
    ]);
    let step = ctx.get::<f64>(&RANDOM_STEP)?;
    explain(&mut table, &s, &grid, step, (inside, outside));
    let trials = used_total + grid.all().map(|c| c.trials).sum::<u64>();
    let engagements = searches.iter().map(Search::engagements).sum::<u64>()
        + grid.all().map(|c| c.engagements).sum::<u64>();
    Ok(Report {
        tables: vec![table],
        files: vec![
            OutputFile::new("tolerance.csv", csv),
            OutputFile::new("tolerance-probes.csv", probes_csv),
        ],
        trials,
        engagements,
        agreement: Some(registry::Agreement {
            consistent: inside,
            differ: outside,
        }),
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn sequential_decisions() {
        use Decision::{Above, Below, Continue};
        // Rule 1 %, cap 200: 2 jams allowed at the cap.
        assert_eq!(decide(0, 0, 1.0, 200), Continue);
        assert_eq!(decide(0, 20, 1.0, 200), Continue);
        assert_eq!(decide(1, 20, 1.0, 200), Continue);
        // 2 of 20: the exact interval starts at 1.2 % > 1 %.
        assert!(clopper_pearson95(2, 20).lo > 0.01);
        assert_eq!(decide(2, 20, 1.0, 200), Above);
        // 2 of 100: the interval holds 1 %, and the cap's rule is not settled.
        assert_eq!(decide(2, 100, 1.0, 200), Continue);
        // 3 jams: the cap's rule can no longer pass.
        assert_eq!(decide(3, 180, 1.0, 200), Above);
        // At the cap: the paper's count rule.
        assert_eq!(decide(2, 200, 1.0, 200), Below);
        assert_eq!(decide(3, 200, 1.0, 200), Above);
        assert_eq!(decide(0, 200, 1.0, 200), Below);
        // A larger cap: 0 of 400 lies below 1 % (upper bound 0.92 %) before the cap.
        assert!(clopper_pearson95(0, 400).hi < 0.01);
        assert_eq!(decide(0, 400, 1.0, 1000), Below);
        assert_eq!(decide(0, 360, 1.0, 1000), Continue);
        // So few trials left that the cap's rule passes whatever they give: 10 % of 20 allows 2.
        assert_eq!(decide(0, 18, 10.0, 20), Below);
        assert_eq!(decide(1, 18, 10.0, 20), Continue);
    }

    #[test]
    fn bisection_brackets_a_monotone_threshold() {
        // A mesh that tolerates up to 0.047: every value at most that passes.
        let mut sr = Search::new(0.02, 0.08, 0.0025);
        let mut seen = Vec::new();
        while sr.start_probe() {
            let v = sr.probes.last().unwrap().value;
            seen.push(v);
            let jams = if v <= 0.047 { 0 } else { 10 };
            sr.add(
                Counts {
                    jams,
                    trials: 200,
                    ..Counts::default()
                },
                1.0,
                200,
            );
            assert!(seen.len() < 20);
        }
        assert_eq!(seen, vec![0.05, 0.035, 0.0425, 0.04625, 0.048125]);
        assert_eq!(sr.pass, Some(0.04625));
        assert_eq!(sr.fail, Some(0.048125));

        // Everything fails: the lower end is probed and fails.
        let mut all_fail = Search::new(0.02, 0.08, 0.01);
        while all_fail.start_probe() {
            all_fail.add(
                Counts {
                    jams: 5,
                    trials: 20,
                    ..Counts::default()
                },
                1.0,
                200,
            );
        }
        assert_eq!(all_fail.pass, None);
        assert_eq!(all_fail.fail, Some(0.02));
        // Everything passes: the upper end is probed and passes.
        let mut all_pass = Search::new(0.02, 0.08, 0.01);
        while all_pass.start_probe() {
            all_pass.add(
                Counts {
                    trials: 200,
                    ..Counts::default()
                },
                1.0,
                200,
            );
        }
        assert_eq!(all_pass.pass, Some(0.08));
        assert_eq!(all_pass.fail, None);
    }

    fn run_with(sets: &[(&str, &str)]) -> Result<Report, RunError> {
        crate::run("tolerance", 2025, 2, sets)
    }

    #[test]
    fn a_tiny_search_runs_end_to_end() {
        let sets = [
            ("search_lo", "0.03"),
            ("search_hi", "0.07"),
            ("resolution", "0.02"),
            ("batch", "5"),
            ("cap", "10"),
            ("rule", "10"),
            ("random_from", "0.05"),
            ("random_to", "0.05"),
        ];
        let report = run_with(&sets).unwrap();
        let table = &report.tables[0];
        assert_eq!(table.rows.len(), 16, "15 meshes and the total");
        let total = table.rows.last().unwrap();
        assert_eq!(total[0], "total");
        assert_eq!(
            total[6],
            (15 * 10).to_string(),
            "one grid value of 10 trials"
        );
        let used: u64 = total[5].parse().unwrap();
        assert!(used > 0 && used <= 15 * 3 * 10, "{used}");
        assert_eq!(report.trials, used + 150);
        assert_eq!(report, run_with(&sets).unwrap(), "deterministic");
    }

    #[test]
    fn bad_parameters_are_bad_input() {
        for (k, v) in [
            ("search_hi", "0.02"),
            ("resolution", "0"),
            ("rule", "0"),
            ("rule", "100"),
            ("batch", "0"),
            ("cap", "10"),
        ] {
            let e = run_with(&[(k, v)]).unwrap_err();
            assert_eq!(e.exit_code(), 2, "{k}={v}");
            assert!(e.to_string().contains(k), "{k}={v}: {e}");
        }
    }
}
