//! The sequential search of `tolerance`: each mesh's largest tolerable random error, by
//! bisection on the error, with trials added a batch at a time at each probed value until the
//! exact 95 % interval of the jam rate is clearly below or above the rule's threshold, or the
//! count rule decides at the cap.

use registry::{RunError, TrialEngine};
use stats::clopper_pearson95;

use crate::cell::{CellRange, Counts, Purpose, run_cell_ranges};
use crate::grids::CellSettings;
use crate::tolerance;

/// What the trials of one probed value say so far.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Decision {
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
pub fn decide(jams: u64, trials: u64, rule_percent: f64, cap: u64) -> Decision {
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
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Probe {
    /// Random error (fraction of the pitch).
    pub value: f64,
    /// Trials run at it and their jams.
    pub counts: Counts,
    /// Below (tolerable) or Above; Continue while running.
    pub decision: Decision,
}

/// The search of one mesh: the bracket so far and the probes run.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Search {
    /// Lower end of the searched range.
    pub lo: f64,
    /// Upper end of the searched range.
    pub hi: f64,
    /// Bisection stops at a bracket this narrow.
    pub resolution: f64,
    /// Largest value found tolerable.
    pub pass: Option<f64>,
    /// Smallest value found not tolerable.
    pub fail: Option<f64>,
    /// Every probe, in the order run; the last one may still be running.
    pub probes: Vec<Probe>,
}

impl Search {
    /// A search of [`lo`, `hi`] down to `resolution`, nothing probed yet.
    pub fn new(lo: f64, hi: f64, resolution: f64) -> Search {
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
    pub fn next_value(&self) -> Option<f64> {
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
    pub fn start_probe(&mut self) -> bool {
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
    pub fn running(&self) -> Option<&Probe> {
        self.probes
            .last()
            .filter(|p| p.decision == Decision::Continue)
    }

    /// Adds a batch's counts to the running probe and applies the sequential test.
    pub fn add(&mut self, c: Counts, rule: f64, cap: u64) {
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

/// The search's parameters, checked by the experiment.
pub struct Settings {
    /// Lower end of the searched random error (fraction of the pitch).
    pub lo: f64,
    /// Upper end.
    pub hi: f64,
    /// Bisection stops at a bracket this narrow.
    pub resolution: f64,
    /// The tolerance rule (% of trials jamming).
    pub rule: f64,
    /// Trials added to a probe at a time.
    pub batch: u64,
    /// Most trials at one probe.
    pub cap: u64,
}

/// Runs every mesh's search in lockstep: each round adds one batch of trials to every mesh's
/// running probe, all in one flat batch of the shared runner (as an input, never sharded: what
/// runs next depends on the counts), so the result does not depend on threads or shards.
pub fn search(
    engine: &TrialEngine,
    cells: &CellSettings,
    s: &Settings,
) -> Result<Vec<Search>, RunError> {
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
        let counts = run_cell_ranges(engine, cells.gearing(), &ranges, Purpose::Input)?;
        for (&m, c) in owners.iter().zip(counts) {
            let sr = &mut searches[m];
            sr.add(c, s.rule, s.cap);
            if sr.running().is_none() {
                sr.start_probe();
            }
        }
    }
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
}
