//! `clearance`: for ideal gears of one mesh, the clearance G (as % of the tooth height) below which
//! the pair jams and above which it disengages within a full turn of the larger gear.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{Series, csv, line_plot, paper_cell};
use setting_groups::typed::label;
use study::events::EventParams;
use study::gearing;
use study::limits::{IdealPair, boundary};
use study::results::{ClearanceLimits, ClearanceRun, TurnRun};

registry::params! {
    /// `tooth_height`: h = R - r for both gears (Efstathiou et al. 2012).
    const TOOTH_HEIGHT = Param::new("tooth_height", "1.1", "h = R - r for both gears (Efstathiou et al. 2012)", gearing::TOOTH_HEIGHT_KIND).unit("mm");
    /// `grid_step`: spacing of the printed sweep.
    const GRID_STEP = Param::new("grid_step", "5", "spacing of the printed sweep", registry::Kind::number(0.5, 50.0, "% of h")).unit("% of h");
}

/// `samples`: samples of the Theoretical Difference per run.
const SAMPLES: Param = registry::samples("3600", "samples of the Theoretical Difference per run");

/// The clearance limits' settings: the mesh, h, the sweep's spacing, the TD samples, the
/// gearing and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// The mesh, e.g. `b2-c1` ([`study::limits::MESH`]).
    #[param(study::limits::MESH)]
    pub mesh: String,
    /// h = R - r for both gears, mm ([`TOOTH_HEIGHT`]).
    #[param(TOOTH_HEIGHT)]
    pub tooth_height: f64,
    /// Spacing of the printed sweep, % of h ([`GRID_STEP`]).
    #[param(GRID_STEP)]
    pub grid_step: f64,
    /// Samples of the Theoretical Difference per run ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The gearing ([`gearing::PARAM`]).
    #[param(gearing::PARAM)]
    pub gearing: String,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// The clearance limits.
pub struct Clearance;

impl registry::Experiment for Clearance {
    const ID: &'static str = "clearance";
    const TITLE: &'static str =
        "Smallest clearance without a jam and largest without a disengagement, ideal gears";
    const PAPER_ITEM: &'static str =
        "Appendix II (and section 3): jam below about 10 %, disengagement above about 87 %";
    const PLACE: Place = Place::Paper(150);
    type Settings = Settings;
    type Results = ClearanceLimits;

    fn compute(s: &Settings, _: &Run) -> Result<ClearanceLimits, RunError> {
        compute(s)
    }

    fn report(s: &Settings, r: &ClearanceLimits) -> Result<Report, RunError> {
        label(&s.events, None, figure(r)?)
    }
}

registry::register!(Clearance);

/// Where the sweep brackets each limit: the last G that jammed (or overlapped at every tooth)
/// and the first that did not, the first G that disengaged and the last that did not before it.
#[derive(Default)]
struct Brackets {
    last_jam: Option<f64>,
    first_free: Option<f64>,
    first_dis: Option<f64>,
    last_engaged: Option<f64>,
}

impl Brackets {
    /// Notes the run at clearance `g` (`None`: the gears overlap at every tooth).
    fn note(&mut self, g: f64, run: Option<&TurnRun>) {
        let Some(t) = run else {
            self.last_jam = Some(g);
            return;
        };
        if t.jams > 0 {
            self.last_jam = Some(g);
        } else if self.first_free.is_none() {
            self.first_free = Some(g);
        }
        if t.disengagements > 0 {
            self.first_dis.get_or_insert(g);
        } else if self.first_dis.is_none() {
            self.last_engaged = Some(g);
        }
    }
}

/// The clearance limits, each bisected between the grid values that bracket it (a limit not
/// bracketed on the grid is not found): the smallest G without a jam, the largest without a
/// disengagement.
fn limits(
    setup: &IdealPair,
    rule: &rules::Rule,
    b: &Brackets,
) -> Result<(Option<f64>, Option<f64>), RunError> {
    let jam_limit = match (b.last_jam, b.first_free) {
        (Some(y), Some(n)) if y < n => Some(boundary(y, n, 1e-4, |g| setup.jams(g, rule))?),
        _ => None,
    };
    let dis_limit = match (b.first_dis, b.last_engaged) {
        (Some(y), Some(n)) if y > n => Some(boundary(y, n, 1e-4, |g| setup.disengages(g, rule))?),
        _ => None,
    };
    Ok((jam_limit, dis_limit))
}

/// The limits beside the paper's.
fn limits_table(r: &ClearanceLimits) -> Table {
    let mut limits = Table::new(
        "Clearance limits (bisection to 1e-4 % of h)",
        ["limit", "ours [% of h]", "paper [% of h]"],
    );
    let show =
        |x: Option<f64>| x.map_or_else(|| "not found on the grid".to_string(), |v| fmt_f64(v, 2));
    limits.row(vec![
        "smallest G running a full turn without a jam".into(),
        show(r.jam_limit),
        paper_cell("clearance", "jam_below", 0),
    ]);
    limits.row(vec![
        "largest G running a full turn without a disengagement".into(),
        show(r.disengagement_limit),
        paper_cell("clearance", "disengage_above", 0),
    ]);
    limits.note("Ours: exact push-model contact; the paper located its limits with an area-intersection program (Appendix II).");
    limits.note("Radii: one least-squares module per group of meshed gears (crates/train), R1/R2 = N1/N2 exactly; r = R - h; D = R1 + R2 - h + G.");
    limits
}

/// Every simulation: the sweep of G over 0-100 % of h, then the limits it brackets.
fn compute(s: &Settings) -> Result<ClearanceLimits, RunError> {
    let rule = s.events.rule()?;
    let h = s.tooth_height;
    // The gearing checked against this experiment's own tooth height.
    let g = gearing::Shape::load(&s.gearing, h)?.gearing;
    let setup = IdealPair::named(&s.mesh, &g, h)?;
    let steps = (100.0 / s.grid_step).floor() as usize;
    let mut b = Brackets::default();
    let mut sweep = Vec::new();
    for i in 0..=steps {
        let g = s.grid_step * i as f64;
        let run = setup.run(g)?.map(|t| {
            let st = setup.td_sigma(&t, s.samples);
            let (jams, disengagements) = study::events::counts(&rule, &t);
            TurnRun {
                jams,
                disengagements,
                sigma: st.sigma,
                dm: st.dm,
            }
        });
        b.note(g, run.as_ref());
        sweep.push(ClearanceRun {
            clearance: g,
            centre_distance: setup.centre_distance(g),
            run,
        });
    }
    let (jam_limit, disengagement_limit) = limits(&setup, &rule, &b)?;
    let IdealPair { n1, n2, r1, r2, .. } = setup;
    Ok(ClearanceLimits {
        mesh: s.mesh.clone(),
        teeth: (n1, n2),
        tip_radii: (r1, r2),
        tooth_height: h,
        sweep,
        jam_limit,
        disengagement_limit,
    })
}

/// The sweep as a table, its rows for clearance.csv and the σ of the runs without events.
fn sweep_table(r: &ClearanceLimits) -> (Table, Vec<Vec<f64>>, Vec<(f64, f64)>) {
    let ((n1, n2), (r1, r2), h) = (r.teeth, r.tip_radii, r.tooth_height);
    let mut grid = Table::new(
        format!(
            "Clearance sweep: {} ({n1}:{n2}), R1 = {} mm, R2 = {} mm, h = {h} mm, one turn of the larger gear",
            r.mesh,
            fmt_f64(r1, 4),
            fmt_f64(r2, 4)
        ),
        SWEEP_COLUMNS,
    );
    let mut rows = Vec::new();
    let mut sigma_points = Vec::new();
    for c in &r.sweep {
        let (g, d) = (c.clearance, c.centre_distance);
        let Some(t) = c.run else {
            grid.row(vec![
                fmt_f64(g, 2),
                fmt_f64(d, 4),
                "overlap at every tooth".into(),
                "-".into(),
                "-".into(),
                "-".into(),
            ]);
            rows.push(vec![g, d, f64::NAN, f64::NAN, f64::NAN, f64::NAN]);
            continue;
        };
        grid.row(vec![
            fmt_f64(g, 2),
            fmt_f64(d, 4),
            t.jams.to_string(),
            t.disengagements.to_string(),
            fmt_f64(t.sigma, 5),
            fmt_f64(t.dm, 5),
        ]);
        rows.push(vec![
            g,
            d,
            t.jams as f64,
            t.disengagements as f64,
            t.sigma,
            t.dm,
        ]);
        if t.jams == 0 && t.disengagements == 0 {
            sigma_points.push((g, t.sigma));
        }
    }
    (grid, rows, sigma_points)
}

/// Both tables, clearance.csv and clearance.svg, drawn from the results.
fn figure(r: &ClearanceLimits) -> Result<Report, RunError> {
    let (grid, rows, sigma_points) = sweep_table(r);
    report(limits_table(r), grid, rows, sigma_points)
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
