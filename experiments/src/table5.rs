//! `table5`: each mesh's largest tolerable random error, derived from Table 4's results by the
//! paper's 1 % rule, then jams / disengagements with systematic errors of 0.1 to 1.1° (split
//! 50/50) on top of it, 200 trials per cell.

use hypotheses::Hypothesis;
use registry::{Context, Experiment, OutputFile, Param, Report, RunError, Table};
use train::Gearing;

use crate::errors;
use crate::gearing;
use crate::pair_jams::{
    CSV_COLUMNS, CellSpec, Counts, PAPER_TRIALS, Stage, Tally, cell_text, csv_columns, label,
    paper_counts, run_cells,
};
use crate::table4::{self, RandomGrid, TRIALS};
use crate::tolerance::{
    self, RANDOM_FROM, RANDOM_STEP, RANDOM_TO, RULE, SYSTEMATIC_FROM, SYSTEMATIC_STEP,
    SYSTEMATIC_TO,
};

/// Where each mesh's random error comes from: derived, as the paper did, or the paper's own row.
pub(crate) const EMAX: Param = Param {
    name: "emax",
    default: "derived",
    unit: "",
    help: "each mesh's random error (row E. max): `derived` from Table 4's grid by the rule, as the paper did, or `paper`, the paper's own E. max row, so that every cell is run on the paper's inputs and compared like for like",
};

/// The `emax` parameter: `true` for the paper's own E. max row.
pub(crate) fn emax_from_paper(ctx: &Context) -> Result<bool, RunError> {
    match ctx.param(EMAX.name)? {
        "derived" => Ok(false),
        "paper" => Ok(true),
        other => Err(RunError::bad(
            "--set",
            EMAX.name,
            format!("must be `derived` or `paper` (got `{other}`)"),
        )),
    }
}

/// Each mesh's random error from the paper's E. max row; an error naming the first mesh the
/// paper gives none for (a custom gearing).
fn paper_emax_row(meshes: &[String]) -> Result<Vec<Option<f64>>, RunError> {
    meshes
        .iter()
        .map(|m| {
            paper_random(m).map(Some).ok_or_else(|| {
                RunError::bad(
                    "--set",
                    EMAX.name,
                    format!("`paper` needs the paper's E. max of every mesh, and it gives none for mesh {m}"),
                )
            })
        })
        .collect()
}

const PARAMS: &[Param] = &[
    TRIALS,
    RULE,
    EMAX,
    RANDOM_FROM,
    RANDOM_TO,
    RANDOM_STEP,
    SYSTEMATIC_FROM,
    SYSTEMATIC_TO,
    SYSTEMATIC_STEP,
    gearing::CLEARANCE,
    gearing::TOOTH_HEIGHT,
    errors::SPLIT,
    errors::PARAM,
    errors::PARAMS_PARAM,
    gearing::PARAM,
    crate::events::PARAM,
];

registry::inventory::submit! {
    Experiment {
        id: "table5",
        title: "Largest tolerable random error of each mesh (from Table 4 by the 1 % rule), then jams and disengagements against the systematic error",
        paper_item: "Table 5 (section 5)",
        params: PARAMS,
        config: None,
        run,
    }
}

/// Each mesh's tolerances, with the cells they were derived from.
pub(crate) struct Tolerances {
    /// Table 4's cells.
    pub random_grid: RandomGrid,
    /// Largest tolerable random error per mesh (`None`: even the grid's smallest fails).
    pub random: Vec<Option<f64>>,
    /// Systematic amplitudes of the grid (degrees), ascending.
    pub sys_values: Vec<f64>,
    /// `sys_counts[row][mesh]`, at the mesh's largest tolerable random error; `None` where that
    /// is below the grid (nothing run).
    pub sys_counts: Vec<Vec<Option<Counts>>>,
    /// Largest tolerable systematic amplitude per mesh; `None` when even the grid's smallest
    /// fails or the random error is below its grid.
    pub systematic: Vec<Option<f64>>,
}

impl Tolerances {
    /// Every cell run, for the report's trial and engagement totals.
    pub fn all(&self) -> impl Iterator<Item = &Counts> {
        self.random_grid
            .all()
            .chain(self.sys_counts.iter().flatten().flatten())
    }
}

/// Runs Table 4's grid, derives each mesh's largest tolerable random error by `rule` %, then runs
/// the systematic grid on top of it (split by the `split` parameter) and derives the largest
/// tolerable systematic amplitude the same way. Every cell goes through the shared runner, so
/// cells Table 4 or Table 5 already ran in this process are not run again.
///
/// With `--set emax=paper` the random errors are the paper's own E. max row instead and Table
/// 4's grid is not run (`random_grid` then has the grid's values but no counts).
pub(crate) fn derive(
    ctx: &Context,
    g: &Gearing,
    hyp: &'static dyn Hypothesis,
    trials: u64,
    rule: f64,
    stage: Stage,
) -> Result<Tolerances, RunError> {
    // Every parameter checked before anything runs.
    let sys_values = tolerance::grid(ctx, &SYSTEMATIC_FROM, &SYSTEMATIC_TO, &SYSTEMATIC_STEP)?;
    let (h, clearance, split) = (
        ctx.f64("tooth_height")?,
        ctx.f64("clearance")?,
        ctx.f64("split")?,
    );
    if !(0.0..=1.0).contains(&split) {
        return Err(RunError::bad(
            "--set",
            "split",
            format!("must be between 0 and 1 (got {split})"),
        ));
    }
    let (random_grid, random) = if emax_from_paper(ctx)? {
        let meshes: Vec<String> = g.meshes().iter().map(|m| m.label.clone()).collect();
        let random = paper_emax_row(&meshes)?;
        let values = tolerance::grid(ctx, &RANDOM_FROM, &RANDOM_TO, &RANDOM_STEP)?;
        let grid = RandomGrid {
            values,
            meshes,
            counts: Vec::new(),
        };
        (grid, random)
    } else {
        let grid = table4::run_grid(ctx, g, hyp, trials, Stage::Input)?;
        let random = grid.tolerable(trials, rule);
        (grid, random)
    };
    let mut cells = Vec::new();
    let mut index = Vec::new();
    for &s in &sys_values {
        for (m, mesh) in random_grid.meshes.iter().enumerate() {
            let Some(e) = random[m] else {
                index.push(None);
                continue;
            };
            let params = errors::params(
                ctx,
                hyp,
                &[("random", e), ("systematic", s), ("split", split)],
            )?;
            index.push(Some(cells.len()));
            cells.push(CellSpec {
                mesh: mesh.clone(),
                hypothesis: hyp,
                params,
                tooth_height: h,
                clearance,
                events: crate::events::chosen(ctx)?,
            });
        }
    }
    let flat = run_cells(ctx, g, &cells, trials, stage)?;
    let n = random_grid.meshes.len();
    let sys_counts: Vec<Vec<Option<Counts>>> = index
        .chunks(n)
        .map(|row| row.iter().map(|i| i.map(|i| flat[i])).collect())
        .collect();
    let systematic = (0..n)
        .map(|m| {
            random[m]?;
            let column: Vec<(f64, u64)> = sys_values
                .iter()
                .zip(&sys_counts)
                .filter_map(|(&s, row)| row[m].map(|c| (s, c.jams)))
                .collect();
            tolerance::largest_tolerable(&column, trials, rule)
        })
        .collect();
    Ok(Tolerances {
        random_grid,
        random,
        sys_values,
        sys_counts,
        systematic,
    })
}

/// The paper's largest tolerable random error of `mesh` (Table 5, row E. max).
pub(crate) fn paper_random(mesh: &str) -> Option<f64> {
    crate::paper::get("table5", &format!("emax.{mesh}")).map(|r| r.value)
}

/// The largest tolerable systematic amplitude the paper's own Table 5 counts give for `mesh` by
/// the same rule (the paper states it in words for two meshes only); `None` when the paper has
/// no count for some value of the grid.
pub(crate) fn paper_systematic(mesh: &str, sys_values: &[f64], rule: f64) -> Option<Option<f64>> {
    let column: Option<Vec<(f64, u64)>> = sys_values
        .iter()
        .map(|&s| {
            paper_counts("table5", &format!("{}.{mesh}", label(s, 1)))
                .0
                .map(|j| (s, j))
        })
        .collect();
    column.map(|c| tolerance::largest_tolerable(&c, PAPER_TRIALS, rule))
}

/// A tolerance as printed: the value, or `< smallest` when below the grid.
pub(crate) fn show(v: Option<f64>, smallest: Option<&f64>, decimals: usize) -> String {
    match (v, smallest) {
        (Some(v), _) => label(v, decimals),
        (None, Some(s)) => format!("< {}", label(*s, decimals)),
        (None, None) => "-".into(),
    }
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::events::label(ctx, counted(ctx)?)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let g = gearing::load(ctx)?;
    let hyp = errors::chosen(ctx)?;
    let trials = table4::trials(ctx, TRIALS.name)?;
    let rule = tolerance::rule(ctx)?;
    let (clearance, split) = (ctx.f64("clearance")?, ctx.f64("split")?);
    let t = derive(ctx, &g, hyp, trials, rule, Stage::Own)?;
    let given = emax_from_paper(ctx)?;
    let meshes = &t.random_grid.meshes;
    let allowed = tolerance::allowed_jams(trials, rule);

    let mut header = vec!["E. sys [deg]".to_string()];
    header.extend(meshes.iter().cloned());
    let mut table = Table::new(
        format!(
            "Table 5: trials (of {trials}) with at least one jam / disengagement against the systematic error (share {split} on the sinusoid, the rest on the axis) at each mesh's largest tolerable random error (row E. max{}), G = {clearance} %: ours (paper); * where a two-sample test separates our count from the paper's (E. max: differs)",
            if given {
                ": the paper's own, emax=paper"
            } else {
                ""
            }
        ),
        header,
    );
    let mut csv = format!("systematic,mesh,random,{CSV_COLUMNS}\n");
    let mut emax_csv = String::from(
        "mesh,random_emax,paper_random_emax,systematic_emax_deg,paper_systematic_emax_deg_by_rule\n",
    );
    let mut row = vec!["E. max (random)".to_string()];
    let mut same = 0;
    for (m, mesh) in meshes.iter().enumerate() {
        let ours = t.random[m];
        let paper = paper_random(mesh);
        let differs = paper.is_some_and(|p| ours.is_none_or(|o| (o - p).abs() > 1e-9));
        if paper.is_some() && !differs {
            same += 1;
        }
        row.push(format!(
            "{} ({}){}",
            show(ours, t.random_grid.values.first(), 3),
            paper.map_or_else(|| "-".into(), |p| label(p, 3)),
            if differs { "*" } else { "" }
        ));
    }
    table.row(row);
    let mut tally = Tally::default();
    for (s, counts) in t.sys_values.iter().zip(&t.sys_counts) {
        let key = label(*s, 1);
        let mut row = vec![key.clone()];
        for (m, mesh) in meshes.iter().enumerate() {
            let Some(c) = &counts[m] else {
                row.push("-".into());
                continue;
            };
            let paper = paper_counts("table5", &format!("{key}.{mesh}"));
            row.push(cell_text(c, paper, &mut tally));
            let random = t.random[m].map_or_else(String::new, |e| e.to_string());
            csv.push_str(&format!(
                "{key},{mesh},{random},{}\n",
                csv_columns(c, paper)
            ));
        }
        table.row(row);
    }
    let mut row = vec!["E. max (systematic)".to_string()];
    for (m, mesh) in meshes.iter().enumerate() {
        let ours = if t.random[m].is_some() {
            show(t.systematic[m], t.sys_values.first(), 1)
        } else {
            "-".into()
        };
        let paper = paper_systematic(mesh, &t.sys_values, rule);
        let paper_text = match paper {
            Some(p) => show(p, t.sys_values.first(), 1),
            None => "-".into(),
        };
        row.push(format!("{ours} ({paper_text})"));
        emax_csv.push_str(&format!(
            "{mesh},{},{},{},{}\n",
            t.random[m].map_or_else(String::new, |v| v.to_string()),
            paper_random(mesh).map_or_else(String::new, |v| v.to_string()),
            t.systematic[m].map_or_else(String::new, |v| v.to_string()),
            paper.flatten().map_or_else(String::new, |v| v.to_string()),
        ));
    }
    table.row(row);
    table.note(tally.note());
    if given {
        table.note("E. max (random): the paper's own row (emax=paper), not derived from Table 4: every cell runs on the paper's inputs, so all of them are compared like for like.");
    } else {
        table.note(format!(
        "E. max (random): the largest random error of Table 4's grid up to which every value has at most {allowed} of {trials} trials jammed (rule {rule} %); ours agree with the paper's row for {same} of {} meshes. Below the grid: `< {}`, and the column is not run.",
        meshes.len(),
        t.random_grid
            .values
            .first()
            .map_or_else(|| "-".into(), |v| label(*v, 3)),
    ));
    }
    table.note(format!(
        "E. max (systematic): the same rule on this table's jams (disengagements are not counted, as in the paper); in brackets the value the paper's own counts give by that rule (its text: e1-b3 up to 0.6, d2-e2 up to 0.1). `< {}`: even the smallest amplitude fails.",
        t.sys_values
            .first()
            .map_or_else(|| "-".into(), |v| label(*v, 1)),
    ));
    table.note("Systematic amplitude A split as in the paper: split x A on a sinusoid of tip positions, the rest an eccentric axis R tan((1 - split) A); random error as a fraction of the pitch.");
    Ok(Report {
        tables: vec![table],
        files: vec![
            OutputFile::new("table5-data.csv", csv),
            OutputFile::new("table5-emax.csv", emax_csv),
        ],
        trials: t.all().map(|c| c.trials).sum(),
        engagements: t.all().map(|c| c.engagements).sum(),
        agreement: Some(tally.agreement()),
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use registry::Context;

    /// Table 5's E. max row at a reduced size: three random values, one systematic value, 20
    /// trials per cell (so 1 % allows no jam and 5 % allows one). Returns the row of the printed table.
    fn emax_row(rule: &str) -> Vec<String> {
        crate::link();
        let map = registry::experiments().unwrap();
        let exp = map["table5"];
        let set = |k: &str, v: &str| (k.to_string(), v.to_string());
        let overrides = [
            set("trials", "20"),
            set("rule", rule),
            set("random_from", "0.04"),
            set("random_to", "0.06"),
            set("random_step", "0.01"),
            set("systematic_from", "0.1"),
            set("systematic_to", "0.1"),
        ];
        let ctx = Context::new(exp, 2025, 2, &overrides, None).unwrap();
        let report = (exp.run)(&ctx).unwrap();
        report.tables[0].rows[0].clone()
    }

    #[test]
    fn emax_paper_runs_on_the_papers_own_row() {
        crate::link();
        let map = registry::experiments().unwrap();
        let exp = map["table5"];
        let set = |k: &str, v: &str| (k.to_string(), v.to_string());
        let overrides = [
            set("trials", "4"),
            set("emax", "paper"),
            set("systematic_from", "0.1"),
            set("systematic_to", "0.1"),
        ];
        let ctx = Context::new(exp, 2025, 2, &overrides, None).unwrap();
        let report = (exp.run)(&ctx).unwrap();
        let t = &report.tables[0];
        assert!(
            t.title.contains("the paper's own, emax=paper"),
            "{}",
            t.title
        );
        // Every mesh's E. max is the paper's: printed beside itself, never marked.
        for (cell, mesh) in t.rows[0].iter().skip(1).zip(t.columns.iter().skip(1)) {
            let paper = super::paper_random(mesh).unwrap();
            assert_eq!(
                cell,
                &format!("{} ({})", super::label(paper, 3), super::label(paper, 3)),
                "{mesh}"
            );
        }
        // No Table 4 grid was run: only the systematic row's 15 cells of 4 trials.
        assert_eq!(report.trials, 15 * 4);
        let bad = [set("emax", "derive")];
        let ctx = Context::new(exp, 2025, 2, &bad, None).unwrap();
        let e = (exp.run)(&ctx).err().unwrap();
        assert_eq!(e.exit_code(), 2);
        assert!(
            e.to_string().contains("must be `derived` or `paper`"),
            "{e}"
        );
    }

    #[test]
    fn a_looser_rule_moves_the_derived_e_max_row() {
        let one = emax_row("1");
        let again = emax_row("1");
        let five = emax_row("5");
        assert_eq!(one, again, "the same rule gives the same row");
        assert_ne!(one, five, "a looser rule must tolerate more somewhere");
        // No value tolerated under the strict rule is lost under the looser one.
        for (a, b) in one.iter().zip(&five).skip(1) {
            let value = |s: &str| s.split(' ').next().unwrap().parse::<f64>().ok();
            if let (Some(x), Some(y)) = (value(a), value(b)) {
                assert!(y >= x, "{a} -> {b}");
            }
        }
    }
}
