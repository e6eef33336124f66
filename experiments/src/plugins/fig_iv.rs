//! `figIV`: σ of each driven gear's Theoretical Difference against the clearance G, for ideal
//! gears of the mechanism's meshes, with each pair's jam and disengagement limits.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Settings as _, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{Limit, LimitKind, Plot, Series};
use setting_groups::typed::label;
use study::events::EventParams;
use study::gearing::ShapeParams;
use study::limits::IdealPair;
use study::results::{MeshSweep, SigmaAgainstClearance};

registry::params! {
    /// `from`: first clearance of the sweep.
    const FROM = Param::new("from", "10", "first clearance of the sweep", registry::Kind::number(0.0, 100.0, "% of h")).unit("% of h");
    /// `to`: last clearance of the sweep.
    const TO = Param::new("to", "90", "last clearance of the sweep", registry::Kind::number(0.0, 100.0, "% of h")).unit("% of h");
    /// `step`: clearance step.
    const STEP = Param::new("step", "5", "clearance step", registry::Kind::number(0.25, 50.0, "% of h")).unit("% of h");
}

/// `samples`: TD samples per run.
const SAMPLES: Param = registry::samples("2000", "TD samples per run");

/// Figure IV's settings: the sweep of clearances, the TD samples, the gearing and h, and the
/// event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// First clearance of the sweep, % of h ([`FROM`]).
    #[param(FROM)]
    pub from: f64,
    /// Last clearance of the sweep, % of h ([`TO`]).
    #[param(TO)]
    pub to: f64,
    /// Clearance step, % of h ([`STEP`]).
    #[param(STEP)]
    pub step: f64,
    /// TD samples per run ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The gearing and h.
    #[group]
    pub shape: ShapeParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Figure IV.
pub struct FigIv;

impl registry::Experiment for FigIv {
    const ID: &'static str = "figIV";
    const TITLE: &'static str = "sigma of the driven gear against clearance G for the mechanism's meshes (semi-log), with jam and disengagement limits";
    const PAPER_ITEM: &'static str = "Figure IV (Appendix II)";
    const PLACE: Place = Place::Paper(140);
    type Settings = Settings;
    type Results = SigmaAgainstClearance;

    fn compute(s: &Settings, _: &Run) -> Result<SigmaAgainstClearance, RunError> {
        compute(s)
    }

    fn report(s: &Settings, r: &SigmaAgainstClearance) -> Result<Report, RunError> {
        label(&s.events, None, figure(r)?)
    }
}

registry::register!(FigIv);

/// `from` must not exceed `to`; the error names the one the user set: `to` below the default
/// `from`, or `from` above `to`.
fn check_range(s: &Settings) -> Result<(), RunError> {
    let (from, to) = (s.from, s.to);
    if from > to {
        let mut changed = Vec::new();
        s.changed(&mut changed);
        let to_set = changed.iter().any(|(p, _)| p.name == TO.name);
        let (field, rule) = if to_set {
            (
                "to",
                format!(
                    "must be at least from = {} (got {})",
                    registry::fmt_number(from),
                    registry::fmt_number(to)
                ),
            )
        } else {
            (
                "from",
                format!(
                    "must be at most to = {} (got {})",
                    registry::fmt_number(to),
                    registry::fmt_number(from)
                ),
            )
        };
        return Err(RunError::bad("--set", field, rule));
    }
    Ok(())
}

/// The sweep: σ of each mesh at each clearance, as a table and as figIV.csv.
fn sweep_table(r: &SigmaAgainstClearance) -> (Table, String) {
    let h = r.tooth_height;
    let mut header = vec!["G [% of h]".to_string()];
    header.extend(r.meshes.iter().map(|m| m.mesh.clone()));
    let mut sweep = Table::new(
        format!(
            "Figure IV: sigma of the driven gear's Theoretical Difference [deg], ideal gears, h = {h} mm, one turn of the larger gear"
        ),
        header.clone(),
    );
    let mut csv = registry::csv_line(&header);
    for (i, &c) in r.clearances.iter().enumerate() {
        let mut row = vec![fmt_f64(c, 1)];
        let mut line = vec![c.to_string()];
        for m in &r.meshes {
            row.push(m.sigma[i].map_or_else(|| "-".to_string(), |s| format!("{s:.2e}")));
            line.push(m.sigma[i].map_or_else(String::new, |s| s.to_string()));
        }
        sweep.row(row);
        csv.push_str(&registry::csv_line(line));
    }
    sweep.note(
        "'-': the full turn jammed or disengaged (no sigma), or the gears overlap at every tooth.",
    );
    sweep.note("The paper's Figure IV shows twelve pairs without listing them in its text; all fifteen meshes are shown here.");
    (sweep, csv)
}

/// Every mesh of the gearing as an ideal pair of tooth height `h`, with its label.
fn mesh_pairs(g: &train::Gearing, h: f64) -> Result<Vec<(String, IdealPair)>, RunError> {
    let mut pairs = Vec::new();
    for m in g.meshes() {
        let pair = IdealPair::of_mesh(g, &m.label, h).ok_or_else(|| {
            RunError::bad("gearing", format!("mesh {}", m.label), "cannot be sized")
        })?;
        pairs.push((m.label.clone(), pair));
    }
    Ok(pairs)
}

/// The report: both tables, the sweep and the limits as CSV, and Figure IV with each mesh's
/// limits on its curve.
fn report(
    tables: [Table; 2],
    csv: String,
    lim_csv: String,
    series: &[Series<'_>],
    drawn_limits: &[Limit],
) -> Result<Report, RunError> {
    let svg = Plot::new(
        "Figure IV: sigma of the driven gear against clearance (semi-logarithmic)",
        "clearance G [% of tooth height]",
        "sigma [deg], logarithmic scale",
        series,
    )
    .log_y()
    .limits(
        drawn_limits,
        "jam limit: the smallest G without a jam (figIV-limits.csv)",
        "disengagement limit: the largest G without a disengagement",
    )
    .svg()?;
    Ok(Report {
        tables: tables.into(),
        files: vec![
            OutputFile::new("figIV.csv", csv),
            OutputFile::new("figIV-limits.csv", lim_csv),
            OutputFile::new("figIV.svg", svg),
        ],
        ..Default::default()
    })
}

/// Every simulation of Figure IV: σ of every mesh at every clearance, and each mesh's limits.
fn compute(s: &Settings) -> Result<SigmaAgainstClearance, RunError> {
    let rule = s.events.rule()?;
    let shape = s.shape.load()?;
    let (g, h) = (&shape.gearing, shape.tooth_height);
    check_range(s)?;
    let (from, to, step) = (s.from, s.to, s.step);
    let clearances: Vec<f64> = (0..)
        .map(|i| from + step * f64::from(i))
        .take_while(|&c| c <= to + 1e-9)
        .collect();
    let pairs = mesh_pairs(g, h)?;
    // Every (mesh, clearance) run and every mesh's limits are independent: run in parallel,
    // collected in order.
    let ideal: Vec<IdealPair> = pairs.iter().map(|(_, p)| *p).collect();
    let grid = study::limits::sigma_sweep(&ideal, &clearances, &rule, s.samples)?;
    let limits = study::limits::all_limits(&ideal, 1e-2, &rule);
    let mut meshes = Vec::new();
    for ((label, _), (l, sigma)) in pairs.into_iter().zip(limits.into_iter().zip(grid)) {
        let (jam, dis) = l?;
        meshes.push(MeshSweep {
            mesh: label,
            smallest_sigma_at: MeshSweep::smallest_sigma(&clearances, &sigma),
            sigma,
            jam_limit: jam,
            disengagement_limit: dis,
        });
    }
    Ok(SigmaAgainstClearance {
        tooth_height: h,
        clearances,
        meshes,
    })
}

/// Both tables, the CSV files and Figure IV, drawn from the results.
fn figure(r: &SigmaAgainstClearance) -> Result<Report, RunError> {
    let (sweep, csv) = sweep_table(r);
    let mut lim = Table::new(
        "Clearance limits of each pair (bisection to 0.01 % of h)",
        [
            "mesh",
            "no jam from [% of h]",
            "no disengagement up to [% of h]",
        ],
    );
    let mut lim_csv = String::from("mesh,jam_below_percent,disengage_above_percent\n");
    let mut series = Vec::new();
    let mut drawn_limits = Vec::new();
    for (k, m) in r.meshes.iter().enumerate() {
        let (label, jam, dis) = (&m.mesh, m.jam_limit, m.disengagement_limit);
        // Each mesh's limits, as computed above, on its curve: `[` where it stops jamming, `]`
        // where it starts to disengage.
        for (x, kind) in [(jam, LimitKind::Lower), (dis, LimitKind::Upper)] {
            if let Some(x) = x {
                drawn_limits.push(Limit { series: k, x, kind });
            }
        }
        let show = |x: Option<f64>| x.map_or_else(|| "-".to_string(), |v| fmt_f64(v, 2));
        let jam_cell = match jam {
            Some(v) if v <= 0.01 => "no jam at any G > 0".to_string(),
            other => show(other),
        };
        lim.row(vec![label.clone(), jam_cell, show(dis)]);
        lim_csv.push_str(&registry::csv_row!(
            label,
            jam.map_or(String::new(), |v| v.to_string()),
            dis.map_or(String::new(), |v| v.to_string())
        ));
        // Drawn only where the pair runs: between its jam and disengagement limits.
        let points: Vec<(f64, f64)> = r
            .clearances
            .iter()
            .zip(&m.sigma)
            .filter_map(|(&c, s)| s.map(|v| (c, v)))
            .collect();
        series.push(Series {
            label: label.as_str(),
            points,
        });
    }
    lim.note(
        "The paper (Appendix II): no values below 10 % (jam) and none above 87 % (decoupling).",
    );
    report([lim, sweep], csv, lim_csv, &series, &drawn_limits)
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    #[test]
    fn the_figure_draws_each_meshs_limits_on_its_curve() {
        let report = crate::run("figIV", 1, 2, &[("step", "40")]).unwrap();
        let csv = report
            .files
            .iter()
            .find(|f| f.name == "figIV-limits.csv")
            .unwrap();
        // One limit per non-empty field of figIV-limits.csv.
        let limits = String::from_utf8_lossy(&csv.contents)
            .lines()
            .skip(1)
            .flat_map(|l| l.split(',').skip(1).map(str::to_owned).collect::<Vec<_>>())
            .filter(|v| !v.is_empty())
            .count();
        assert!(limits >= 15, "{limits}");
        let svg = report.files.iter().find(|f| f.name == "figIV.svg").unwrap();
        let svg = String::from_utf8_lossy(&svg.contents);
        // A bracket per limit on the plot, one of each kind in the legend.
        assert_eq!(svg.matches("stroke-width=\"2.5\"").count(), limits + 2);
        assert!(svg.contains(">jam limit: the smallest G without a jam"));
        assert!(svg.contains(">disengagement limit: the largest G without a disengagement"));
        assert_eq!(svg.matches("<g class=\"series\"").count(), 15);
    }
}
