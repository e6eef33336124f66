//! `clearance`: for ideal gears of one mesh, the clearance G (as % of the tooth height) below which
//! the pair jams and above which it disengages within a full turn of the larger gear.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};

use crate::common::{Series, csv, line_plot, paper_cell};
use study::gearing;
use study::limits::{IdealPair, boundary};

registry::params! {
    /// `tooth_height`: h = R - r for both gears (Efstathiou et al. 2012).
    const TOOTH_HEIGHT = Param::new("tooth_height", "1.1", "h = R - r for both gears (Efstathiou et al. 2012)", gearing::TOOTH_HEIGHT_KIND).unit("mm");
    /// `grid_step`: spacing of the printed sweep.
    const GRID_STEP = Param::new("grid_step", "5", "spacing of the printed sweep", registry::Kind::number(0.5, 50.0, "% of h")).unit("% of h");
}

/// `samples`: samples of the Theoretical Difference per run.
const SAMPLES: Param = registry::samples("3600", "samples of the Theoretical Difference per run");

crate::experiment! {
    id: "clearance", paper_item: "Appendix II (and section 3): jam below about 10 %, disengagement above about 87 %", run,
    title: "Smallest clearance without a jam and largest without a disengagement, ideal gears",
    params: [study::limits::MESH, TOOTH_HEIGHT, GRID_STEP, SAMPLES, gearing::PARAM], groups: [study::events::GROUP],
}

/// The clearance limits, each bisected between the grid values that bracket it: `jams` is the
/// last G that jammed and the first that did not, `disengages` the first G that disengaged and
/// the last that did not (a limit not bracketed on the grid is not found).
fn limits_table(
    setup: &IdealPair,
    rule: &rules::Rule,
    (last_jam, first_free): (Option<f64>, Option<f64>),
    (first_dis, last_engaged): (Option<f64>, Option<f64>),
) -> Result<Table, RunError> {
    let mut limits = Table::new(
        "Clearance limits (bisection to 1e-4 % of h)",
        ["limit", "ours [% of h]", "paper [% of h]"],
    );
    let jam_limit = match (last_jam, first_free) {
        (Some(y), Some(n)) if y < n => Some(boundary(y, n, 1e-4, |g| setup.jams(g, rule))?),
        _ => None,
    };
    let dis_limit = match (first_dis, last_engaged) {
        (Some(y), Some(n)) if y > n => Some(boundary(y, n, 1e-4, |g| setup.disengages(g, rule))?),
        _ => None,
    };
    let show =
        |x: Option<f64>| x.map_or_else(|| "not found on the grid".to_string(), |v| fmt_f64(v, 2));
    limits.row(vec![
        "smallest G running a full turn without a jam".into(),
        show(jam_limit),
        paper_cell("clearance", "jam_below", 0),
    ]);
    limits.row(vec![
        "largest G running a full turn without a disengagement".into(),
        show(dis_limit),
        paper_cell("clearance", "disengage_above", 0),
    ]);
    limits.note("Ours: exact push-model contact; the paper located its limits with an area-intersection program (Appendix II).");
    limits.note("Radii: one least-squares module per group of meshed gears (crates/train), R1/R2 = N1/N2 exactly; r = R - h; D = R1 + R2 - h + G.");
    Ok(limits)
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let rule = crate::settings::rule(ctx)?;
    let h: f64 = ctx.get(&TOOTH_HEIGHT)?;
    let grid_step: f64 = ctx.get(&GRID_STEP)?;
    let samples: usize = ctx.get(&SAMPLES)?;
    // The gearing checked against this experiment's own tooth height.
    let g = crate::settings::shape_with(ctx, &TOOTH_HEIGHT)?.gearing;
    let label = ctx.text(&study::limits::MESH)?;
    let setup = crate::settings::ideal_pair(ctx, &g, h)?;
    let IdealPair { n1, n2, r1, r2, .. } = setup;

    let mut grid = Table::new(
        format!(
            "Clearance sweep: {label} ({n1}:{n2}), R1 = {} mm, R2 = {} mm, h = {h} mm, one turn of the larger gear",
            fmt_f64(r1, 4),
            fmt_f64(r2, 4)
        ),
        SWEEP_COLUMNS,
    );
    let mut rows = Vec::new();
    let mut sigma_points = Vec::new();
    let steps = (100.0 / grid_step).floor() as usize;
    let mut first_free: Option<f64> = None;
    let mut last_jam: Option<f64> = None;
    let mut first_dis: Option<f64> = None;
    let mut last_engaged: Option<f64> = None;
    for i in 0..=steps {
        let g = grid_step * i as f64;
        let d = setup.centre_distance(g);
        match setup.run(g)? {
            None => {
                grid.row(vec![
                    fmt_f64(g, 2),
                    fmt_f64(d, 4),
                    "overlap at every tooth".into(),
                    "-".into(),
                    "-".into(),
                    "-".into(),
                ]);
                last_jam = Some(g);
                rows.push(vec![g, d, f64::NAN, f64::NAN, f64::NAN, f64::NAN]);
            }
            Some(t) => {
                let s = setup.td_sigma(&t, samples);
                let (j, dis) = study::events::counts(&rule, &t);
                if j > 0 {
                    last_jam = Some(g);
                } else if first_free.is_none() {
                    first_free = Some(g);
                }
                if dis > 0 {
                    first_dis.get_or_insert(g);
                } else if first_dis.is_none() {
                    last_engaged = Some(g);
                }
                grid.row(vec![
                    fmt_f64(g, 2),
                    fmt_f64(d, 4),
                    j.to_string(),
                    dis.to_string(),
                    fmt_f64(s.sigma, 5),
                    fmt_f64(s.dm, 5),
                ]);
                rows.push(vec![g, d, j as f64, dis as f64, s.sigma, s.dm]);
                if j == 0 && dis == 0 {
                    sigma_points.push((g, s.sigma));
                }
            }
        }
    }

    let limits = limits_table(
        &setup,
        &rule,
        (last_jam, first_free),
        (first_dis, last_engaged),
    )?;
    report(limits, grid, rows, sigma_points)
}

/// The sweep table's columns.
const SWEEP_COLUMNS: [&str; 6] = [
    "G [% of h]",
    "D [mm]",
    "jams",
    "disengagements",
    "TD sigma [deg]",
    "TD Dm [deg]",
];

/// The report: both tables, the sweep as CSV and the sigma plot of the runs without events.
fn report(
    limits: Table,
    grid: Table,
    rows: Vec<Vec<f64>>,
    sigma_points: Vec<(f64, f64)>,
) -> Result<Report, RunError> {
    let svg = line_plot(
        "Clearance sweep (Appendix II, Figure IV style): TD sigma of the driven gear",
        "clearance G [% of tooth height]",
        "standard deviation of the Theoretical Difference [deg]",
        &[Series {
            label: "sigma (runs without events)",
            points: sigma_points,
        }],
    )?;
    let data = csv(
        &[
            "g_percent",
            "centre_distance_mm",
            "jams",
            "disengagements",
            "td_sigma_deg",
            "td_dm_deg",
        ],
        rows.into_iter(),
        9,
    );
    Ok(Report {
        tables: vec![limits, grid],
        files: vec![
            OutputFile::new("clearance.csv", data),
            OutputFile::new("clearance.svg", svg),
        ],
        ..Default::default()
    })
}
