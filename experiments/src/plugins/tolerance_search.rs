//! `tolerance`: each mesh's largest tolerable random error (no systematic error, G = 40 %, as in
//! Table 4) found by a sequential search instead of Table 4's fixed grid: bisection on the random
//! error, and at each probed value trials added a batch at a time until the jam rate is clearly
//! below or above the rule's threshold (exact 95 % interval), or the paper's count rule decides
//! at the cap. Compared with the grid-derived value (Table 4 by the rule) and the paper's E. max,
//! with the pair turns each needed.

use registry::{Context, OutputFile, Param, Report, RunError, Table};

use crate::emax::{paper_random, show};
use study::cell::{Purpose, label};
use study::tolerance::{self, RANDOM_STEP, RULE};
use study::tolerance_search::{Search, Settings, search};

registry::params! {
    const SEARCH_LO = Param::new("search_lo", "0.02", "lower end of the searched random error (fraction of the pitch 360/N)", study::tolerance::RANDOM_KIND).unit("pitch");
    const SEARCH_HI = Param::new("search_hi", "0.08", "upper end of the searched random error", study::tolerance::RANDOM_KIND).unit("pitch");
    const RESOLUTION = Param::new("resolution", "0.0025", "the bisection stops when the bracket is at most this wide", registry::Kind::positive(f64::INFINITY, "")).unit("pitch");
    const BATCH = Param::new("batch", "20", "trials added to a probed value at a time", registry::Kind::count(1, registry::MAX_TRIALS, ""));
    const CAP = Param::new("cap", "200", "most trials at one probed value, where the paper's count rule decides; also the trials per cell of the Table 4 grid compared with (the paper: 200)", registry::Kind::count(1, registry::MAX_TRIALS, ""));
}

crate::experiment! {
    id: "tolerance", paper_item: "Section 5, Tables 4-5 (tolerance by sequential search; beyond the paper)", run,
    title: "Largest tolerable random error of each mesh by a sequential search (bisection, trials added until the jam rate is clearly below or above the rule), against Table 4's grid",
    params: [SEARCH_LO, SEARCH_HI, RESOLUTION, RULE, BATCH, CAP], groups: [study::gearing::GROUP, study::errors::GROUP, study::tolerance::RANDOM_GRID, study::events::GROUP, study::drive::GROUP],
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

/// The table's title and columns.
fn search_table(s: &Settings, clearance: f64) -> Table {
    Table::new(
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
    )
}

/// One mesh's probes, a CSV line each, in the order the search ran them.
fn probe_lines(mesh: &str, sr: &Search) -> String {
    let mut out = String::new();
    for (i, p) in sr.probes.iter().enumerate() {
        out.push_str(&registry::csv_row!(
            mesh,
            i + 1,
            p.value,
            p.counts.trials,
            p.counts.jams,
            p.counts.disengagements,
            format!("{:?}", p.decision)
        ));
    }
    out
}

/// Whether the search's tolerable value is within one resolution of the paper's `p`.
fn within_resolution(pass: Option<f64>, p: f64, resolution: f64) -> bool {
    pass.is_some_and(|o| (o - p).abs() <= resolution * (1.0 + 1e-9))
}

/// The last row: probes and pair turns summed over the meshes.
fn total_row(probes: usize, used: u64, grid: u64) -> Vec<String> {
    vec![
        "total".into(),
        String::new(),
        String::new(),
        String::new(),
        probes.to_string(),
        used.to_string(),
        grid.to_string(),
        format!("{:.0}", saved(used, grid)),
    ]
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The paper's E. max of a mesh, `*` where it is further than one resolution from the search's
/// (`agrees`: `None` where not compared).
fn paper_cell(paper: Option<f64>, agrees: Option<bool>) -> String {
    format!(
        "{}{}",
        paper.map_or_else(|| "-".into(), |p| label(p, 3)),
        if agrees == Some(false) { "*" } else { "" }
    )
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    // Table 4's grid runs `cap` trials a cell, the most a search's probe runs.
    let cells = crate::settings::cells(ctx, &CAP)?;
    let s = settings(ctx)?;
    let clearance = cells.clearance()?;
    // The grid's parameters are checked before anything runs.
    let values = crate::settings::random_grid(ctx)?;
    let searches = search(ctx.engine(), &cells, &s)?;
    let grid = study::grids::run_grid(ctx.engine(), &cells, values, s.cap, Purpose::Input)?;
    let grid_tolerable = grid.tolerable(s.cap, s.rule);
    let grid_per_mesh = grid.values.len() as u64 * s.cap;

    let mut table = search_table(&s, clearance);
    let mut csv = String::from(
        "mesh,search_emax,search_fail,grid_emax,paper_emax,probes,search_trials,grid_trials,saved_percent\n",
    );
    let mut probes_csv = String::from("mesh,probe,random,trials,jams,disengagements,decision\n");
    let off_paper = crate::cells::off_paper_inputs(ctx);
    let (mut inside, mut outside) = (0, 0);
    let (mut used_total, mut grid_total, mut probes_total) = (0, 0, 0);
    for ((mesh, sr), grid_value) in grid.meshes.iter().zip(&searches).zip(&grid_tolerable) {
        let paper = paper_random(mesh);
        // Compared only where the run's inputs are the paper's.
        let agrees = paper
            .filter(|_| off_paper.is_empty())
            .map(|p| within_resolution(sr.pass, p, s.resolution));
        inside += u64::from(agrees == Some(true));
        outside += u64::from(agrees == Some(false));
        let used = sr.trials();
        used_total += used;
        grid_total += grid_per_mesh;
        probes_total += sr.probes.len();
        table.row(vec![
            mesh.clone(),
            show_search(sr, &s),
            show(*grid_value, grid.values.first(), 3),
            paper_cell(paper, agrees),
            sr.probes.len().to_string(),
            used.to_string(),
            grid_per_mesh.to_string(),
            format!("{:.0}", saved(used, grid_per_mesh)),
        ]);
        let opt = |v: Option<f64>| v.map_or_else(String::new, |v| v.to_string());
        csv.push_str(&registry::csv_row!(
            mesh,
            opt(sr.pass),
            opt(sr.fail),
            opt(*grid_value),
            opt(paper),
            sr.probes.len(),
            used,
            grid_per_mesh,
            format!("{:.1}", saved(used, grid_per_mesh))
        ));
        probes_csv.push_str(&probe_lines(mesh, sr));
    }
    table.row(total_row(probes_total, used_total, grid_total));
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
        agreement: off_paper.is_empty().then_some(registry::Agreement {
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
