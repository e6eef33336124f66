//! The clearance search of `clearance-design`: for each (case, mesh), the clearance that
//! minimises the probability of a jam or a disengagement per pair run - a coarse grid of cells
//! through the shared cell runner, then extra trials around the coarse best - compared exactly,
//! as fractions, then by nearness to the reference clearance.

use registry::{RunError, TrialEngine};

use crate::cell::{CellRange, CellSpec, Counts, Purpose, run_cell_ranges, run_cells};
use crate::grids::{CASES, CellSettings};

/// What the search runs, checked by the experiment.
#[derive(Debug, Clone)]
pub struct Search {
    /// Coarse grid with the reference, ascending, without repeats.
    pub grid: Vec<f64>,
    /// The reference clearance (% of h).
    pub reference: f64,
    /// Pair runs per clearance of the coarse grid.
    pub coarse: u64,
    /// The refinement's step (% of h); 0: no refinement.
    pub step: f64,
    /// Pair runs per clearance compared at the refinement.
    pub refine: u64,
    /// Indices into `CASES`.
    pub cases: Vec<usize>,
}

/// `v` rounded to nine decimals, so a refined clearance has a short canonical text (35, not
/// 34.999999999999996).
pub fn round9(v: f64) -> f64 {
    (v * 1e9).round() / 1e9
}

/// Is clearance `a` with counts `ca` better than `b` with `cb`: a lower failure rate (compared
/// exactly, as fractions), then nearer the reference, then lower.
pub fn better(a: f64, ca: &Counts, b: f64, cb: &Counts, reference: f64) -> bool {
    let lhs = u128::from(ca.failures) * u128::from(cb.trials);
    let rhs = u128::from(cb.failures) * u128::from(ca.trials);
    if lhs != rhs {
        return lhs < rhs;
    }
    let (da, db) = ((a - reference).abs(), (b - reference).abs());
    if da != db {
        return da < db;
    }
    a < b
}

/// The best of `probes` (clearance, counts) by [`better`]; `None` for none.
pub fn pick(probes: &[(f64, Counts)], reference: f64) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, (g, c)) in probes.iter().enumerate() {
        if best.is_none_or(|b| better(*g, c, probes[b].0, &probes[b].1, reference)) {
            best = Some(i);
        }
    }
    best
}

/// The clearances the refinement compares: the coarse best, the best plus and minus `step`
/// (those above 0 and at most 100 % of h) and the reference; ascending, without repeats.
pub fn refine_values(best: f64, step: f64, reference: f64) -> Vec<f64> {
    let mut v: Vec<f64> = [best - step, best, best + step, reference]
        .into_iter()
        .map(round9)
        .filter(|&g| g > 0.0 && g <= 100.0)
        .collect();
    v.sort_by(f64::total_cmp);
    v.dedup();
    v
}

/// The search of one (case, mesh).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct MeshSearch {
    /// Index into `CASES`.
    pub case: usize,
    /// The mesh label.
    pub mesh: String,
    /// Every clearance tried, ascending, with its counts so far.
    pub probes: Vec<(f64, Counts)>,
    /// The coarse grid's counts, in the grid's order.
    pub coarse: Vec<Counts>,
    /// The coarse grid's best.
    pub coarse_best: f64,
    /// The clearances compared at the final stage (the whole grid without refinement).
    pub finalists: Vec<f64>,
    /// The chosen clearance.
    pub best: f64,
}

impl MeshSearch {
    /// The counts at clearance `g` (zero if never tried).
    pub fn at(&self, g: f64) -> Counts {
        self.probes
            .iter()
            .find(|p| p.0 == g)
            .map_or_else(Counts::default, |p| p.1)
    }

    /// Adds counts at `g`, trying it if new.
    pub fn add(&mut self, g: f64, c: Counts) {
        match self.probes.iter_mut().find(|p| p.0 == g) {
            Some(p) => p.1 += c,
            None => {
                self.probes.push((g, c));
                self.probes.sort_by(|a, b| a.0.total_cmp(&b.0));
            }
        }
    }

    /// Pair runs used.
    pub fn trials(&self) -> u64 {
        self.probes.iter().map(|p| p.1.trials).sum()
    }
}

/// The cell of `mesh` under case `ci` at clearance `g`: the same content (and so the same trial
/// streams and cache entry) as Table 3's and Table I's cells.
pub fn cell(cells: &CellSettings, ci: usize, mesh: &str, g: f64) -> Result<CellSpec, RunError> {
    let (_, systematic, random) = CASES[ci];
    let params = cells.errors.case_params((systematic, random))?;
    Ok(cells.cell(mesh, params, g))
}

/// Runs the search of every (case, mesh): the coarse grid through the shared cell runner (so
/// cells other experiments ran with the same trial count come from the cache), then the
/// refinement's extra trials as ranges of the same cells, all as inputs (never sharded: the
/// choices feed the failure study).
pub fn search(
    engine: &TrialEngine,
    c: &CellSettings,
    s: &Search,
) -> Result<Vec<MeshSearch>, RunError> {
    let (g, meshes) = (c.gearing(), c.meshes());
    let mut searches = Vec::new();
    let mut cells = Vec::new();
    for &ci in &s.cases {
        for m in &meshes {
            searches.push(MeshSearch {
                case: ci,
                mesh: m.clone(),
                probes: Vec::new(),
                coarse: Vec::new(),
                coarse_best: s.reference,
                finalists: Vec::new(),
                best: s.reference,
            });
            for &v in &s.grid {
                cells.push(cell(c, ci, m, v)?);
            }
        }
    }
    let counts = run_cells(engine, g, &cells, s.coarse, Purpose::Input)?;
    for (sr, row) in searches.iter_mut().zip(counts.chunks(s.grid.len())) {
        for (&v, c) in s.grid.iter().zip(row) {
            sr.add(v, *c);
        }
        sr.coarse = row.to_vec();
        let i = pick(&sr.probes, s.reference)
            .ok_or_else(|| RunError::Internal(format!("no clearance tried for {}", sr.mesh)))?;
        sr.coarse_best = sr.probes[i].0;
        sr.finalists = if s.step > 0.0 {
            refine_values(sr.coarse_best, s.step, s.reference)
        } else {
            s.grid.clone()
        };
    }
    if s.step > 0.0 {
        let mut ranges = Vec::new();
        let mut owners = Vec::new();
        for (k, sr) in searches.iter().enumerate() {
            for &v in &sr.finalists {
                let have = sr.at(v).trials;
                if have < s.refine {
                    ranges.push(CellRange {
                        cell: cell(c, sr.case, &sr.mesh, v)?,
                        range: have..s.refine,
                    });
                    owners.push((k, v));
                }
            }
        }
        if !ranges.is_empty() {
            let more = run_cell_ranges(engine, g, &ranges, Purpose::Input)?;
            for (&(k, v), c) in owners.iter().zip(more) {
                searches[k].add(v, c);
            }
        }
    }
    for sr in &mut searches {
        let finalists: Vec<(f64, Counts)> = sr.finalists.iter().map(|&v| (v, sr.at(v))).collect();
        let i = pick(&finalists, s.reference)
            .ok_or_else(|| RunError::Internal(format!("no finalist for {}", sr.mesh)))?;
        sr.best = finalists[i].0;
    }
    Ok(searches)
}

/// The clearance design's parameters, checked by the experiment: the search's ([`Search`]) and
/// the failure study's (runs per case and setting, horizon in days of b).
pub struct Design {
    /// Coarse grid with the reference, ascending, without repeats.
    pub grid: Vec<f64>,
    /// The reference clearance (% of h).
    pub reference: f64,
    /// Pair runs per clearance of the coarse grid.
    pub coarse: u64,
    /// The refinement's step (% of h); 0: no refinement.
    pub step: f64,
    /// Pair runs per clearance compared at the refinement.
    pub refine: u64,
    /// Whole-mechanism runs per case and setting of the failure study.
    pub runs: u64,
    /// Horizon of each whole-mechanism run, days of b.
    pub days: f64,
    /// Indices into `CASES`.
    pub cases: Vec<usize>,
}

impl Design {
    /// What the clearance search runs.
    pub fn search(&self) -> Search {
        Search {
            grid: self.grid.clone(),
            reference: self.reference,
            coarse: self.coarse,
            step: self.step,
            refine: self.refine,
            cases: self.cases.clone(),
        }
    }

    /// Trials per compared clearance at the final stage.
    pub fn final_trials(&self) -> u64 {
        if self.step > 0.0 {
            self.refine
        } else {
            self.coarse
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn counts(failures: u64, trials: u64) -> Counts {
        Counts {
            failures,
            trials,
            ..Counts::default()
        }
    }

    #[test]
    fn the_lowest_rate_wins_then_the_nearest_to_the_reference_then_the_lower() {
        let p = |v: &[(f64, u64, u64)]| -> Vec<(f64, Counts)> {
            v.iter().map(|&(g, f, n)| (g, counts(f, n))).collect()
        };
        // Lowest rate, compared as fractions: 1 of 40 beats 1 of 20.
        assert_eq!(
            pick(&p(&[(30.0, 1, 20), (40.0, 2, 20), (50.0, 1, 40)]), 40.0),
            Some(2)
        );
        // A tie at zero: the reference itself.
        assert_eq!(
            pick(&p(&[(30.0, 0, 20), (40.0, 0, 20), (50.0, 0, 20)]), 40.0),
            Some(1)
        );
        // A tie between 35 and 45, both 5 from the reference: the lower.
        assert_eq!(
            pick(&p(&[(35.0, 1, 40), (40.0, 3, 40), (45.0, 1, 40)]), 40.0),
            Some(0)
        );
        // A tie between 30 and 45: the nearer to 40.
        assert_eq!(pick(&p(&[(30.0, 0, 20), (45.0, 0, 20)]), 40.0), Some(1));
        assert_eq!(pick(&[], 40.0), None);
    }

    #[test]
    fn refinement_brackets_the_coarse_best_and_keeps_the_reference() {
        assert_eq!(refine_values(30.0, 5.0, 40.0), [25.0, 30.0, 35.0, 40.0]);
        assert_eq!(refine_values(40.0, 5.0, 40.0), [35.0, 40.0, 45.0]);
        // Within (0, 100] only.
        assert_eq!(refine_values(100.0, 5.0, 40.0), [40.0, 95.0, 100.0]);
        assert_eq!(refine_values(5.0, 5.0, 40.0), [5.0, 10.0, 40.0]);
        // Rounded to a short canonical value.
        assert_eq!(refine_values(0.3, 0.1, 0.3), [0.2, 0.3, 0.4]);
    }
}
