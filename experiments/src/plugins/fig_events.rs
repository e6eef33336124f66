//! `fig-events`: the paper's Figures V_A and V_B for one ideal mesh (default b2-c1): the mesh just
//! inside its jam limit at its first jam, and just beyond its disengagement limit at its first
//! disengagement, each drawn zoomed on the two teeth involved.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use setting_groups::typed::label;
use study::events::EventParams;
use study::gearing::ShapeParams;
use study::limits::IdealPair;

registry::params! {
    /// `margin`: how far inside the jam limit and beyond the disengagement limit the two runs are made.
    const MARGIN = Param::new("margin", "1", "how far inside the jam limit and beyond the disengagement limit the two runs are made", registry::Kind::number(0.01, 20.0, "% of h")).unit("% of h");
}

/// Figures V_A and V_B's settings: the mesh, the margin past its limits, the gearing and h, and
/// the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// The mesh, e.g. `b2-c1` ([`study::limits::MESH`]).
    #[param(study::limits::MESH)]
    pub mesh: String,
    /// How far past each limit the runs are made, % of h ([`MARGIN`]).
    #[param(MARGIN)]
    pub margin: f64,
    /// The gearing and h.
    #[group]
    pub shape: ShapeParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Figures V_A and V_B's results: the mesh and, for each figure, its limit and the run past it
/// with the event drawn.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Results {
    /// Teeth of the driver and of the driven gear.
    pub teeth: (usize, usize),
    /// Tooth height h, mm.
    pub tooth_height: f64,
    /// Figure V_A: the jam limit and the run just inside it.
    pub jam: FigureRun,
    /// Figure V_B: the disengagement limit and the run just beyond it.
    pub decoupling: FigureRun,
}

/// One figure's limit, the clearance run past it and the event drawn.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct FigureRun {
    /// The limit, % of h (`None`: not found).
    pub limit: Option<f64>,
    /// The clearance run, `margin` past the limit, % of h.
    pub at: Option<f64>,
    /// The run (one turn of the larger gear) and its first event of the figure's kind, if any.
    pub event: Option<(contact::Trajectory, contact::Event)>,
}

/// Figures V_A and V_B.
pub struct FigEvents;

impl registry::Experiment for FigEvents {
    const ID: &'static str = "fig-events";
    const TITLE: &'static str =
        "A jam and a decoupling of one ideal mesh, drawn at the instant they happen";
    const PAPER_ITEM: &'static str = "Figures V_A and V_B (Appendix II)";
    const PLACE: Place = Place::Paper(160);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, _: &Run) -> Result<Results, RunError> {
        compute(s)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, None, figures(s, r))
    }
}

registry::register!(FigEvents);

/// How closely the limits are located before stepping `margin` past them (% of h).
const LIMIT_TOLERANCE: f64 = 0.01;

/// Every simulation: the mesh's limits, then a run past each to its first event of that kind.
fn compute(s: &Settings) -> Result<Results, RunError> {
    let rule = s.events.rule()?;
    let shape = s.shape.load()?;
    let h = shape.tooth_height;
    let pair = IdealPair::named(&s.mesh, &shape.gearing, h)?;
    let (jam_limit, dis_limit) = pair.limits(LIMIT_TOLERANCE, &rule)?;
    let run = |figure: Figure, limit: Option<f64>| -> Result<FigureRun, RunError> {
        let at = limit.map(|l| match figure {
            Figure::Jam => l - s.margin,
            Figure::Decoupling => l + s.margin,
        });
        let event = match at {
            Some(gc) if gc > 0.0 => first_event(&pair, &rule, figure, gc)?,
            _ => None,
        };
        Ok(FigureRun { limit, at, event })
    };
    Ok(Results {
        teeth: (pair.n1, pair.n2),
        tooth_height: h,
        jam: run(Figure::Jam, jam_limit)?,
        decoupling: run(Figure::Decoupling, dis_limit)?,
    })
}

/// The run of `pair` at clearance `gc` and its first event counted as `figure`'s kind, if any.
fn first_event(
    pair: &IdealPair,
    rule: &rules::Rule,
    figure: Figure,
    gc: f64,
) -> Result<Option<(contact::Trajectory, contact::Event)>, RunError> {
    Ok(pair.run(gc)?.and_then(|t| {
        let e = t
            .events()
            .iter()
            .find(|e| match figure {
                Figure::Jam => rule.is_jam(e),
                Figure::Decoupling => rule.is_disengagement(e),
            })
            .cloned()?;
        Some((t, e))
    }))
}

/// The table and both pictures, drawn from the results.
fn figures(s: &Settings, r: &Results) -> Report {
    let (h, (n1, n2)) = (r.tooth_height, r.teeth);
    let mut table = Table::new(
        format!(
            "Figures V_A and V_B: {} ({n1}:{n2}), ideal teeth, h = {h} mm, one turn of the larger gear from driver angle 0",
            s.mesh
        ),
        [
            "figure",
            "limit G [% of h]",
            "run at G [% of h]",
            "event",
            "phi [deg]",
            "driver tooth",
            "driven tooth",
            "picture",
        ],
    );
    let mut files = Vec::new();
    let mesh = Mesh {
        label: &s.mesh,
        h,
        teeth: r.teeth,
        margin: s.margin,
    };
    for (figure, run) in [(Figure::Jam, &r.jam), (Figure::Decoupling, &r.decoupling)] {
        let (row, picture) = mesh.figure(figure, run);
        table.row(row);
        files.extend(picture);
    }
    table.note(format!(
        "Limits as `clearance` finds them (located to {LIMIT_TOLERANCE} % of h), then a run {} % of h inside the jam limit and beyond the disengagement limit; each picture shows the mesh at its first jam or disengagement, zoomed on the two teeth, with the contact point and its normal. The paper's Figure V_A shows a lock (one driver tip pushes a driven flank while another meets a preceding tooth), V_B tips that no longer reach each other.",
        s.margin
    ));
    Report {
        tables: vec![table],
        files,
        ..Default::default()
    }
}

/// Which of the two figures: V_A (a jam, just inside the jam limit) or V_B (a decoupling, just
/// beyond the disengagement limit).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Figure {
    /// Figure V_A.
    Jam,
    /// Figure V_B.
    Decoupling,
}

impl Figure {
    /// The figure's name in the table, its short name in the picture's title, and its file.
    fn names(self) -> (&'static str, &'static str, &'static str) {
        match self {
            Figure::Jam => ("V_A (a jam)", "V_A", "fig-V_A.svg"),
            Figure::Decoupling => ("V_B (a decoupling)", "V_B", "fig-V_B.svg"),
        }
    }
}

/// The mesh both figures draw.
struct Mesh<'a> {
    /// The mesh's label, e.g. `b2-c1`.
    label: &'a str,
    /// Tooth height h, mm.
    h: f64,
    /// Teeth of its driver and driven gear.
    teeth: (usize, usize),
    /// How far past each limit the run is made, % of h.
    margin: f64,
}

impl Mesh<'_> {
    /// `figure`'s table row and picture, from its run past its limit, drawn at its first event
    /// of the figure's kind (a row of dashes and no picture where none was found).
    fn figure(&self, figure: Figure, run: &FigureRun) -> (Vec<String>, Option<OutputFile>) {
        let (name, _, file) = figure.names();
        let mut row = vec![
            name.to_string(),
            run.limit.map_or_else(|| "-".into(), |l| fmt_f64(l, 2)),
            run.at.map_or_else(|| "-".into(), |g| fmt_f64(g, 2)),
        ];
        let Some((t, e)) = &run.event else {
            row.extend(["none found", "-", "-", "-", "-"].map(String::from));
            return (row, None);
        };
        let picture = self.picture(figure, run.at.unwrap_or_default(), t, e);
        let (n1, n2) = self.teeth;
        row.extend([
            e.label().to_string(),
            fmt_f64(e.phi.to_degrees(), 4),
            e.driver_tooth.rem_euclid(n1 as i64).to_string(),
            e.driven_tooth.rem_euclid(n2 as i64).to_string(),
            file.to_string(),
        ]);
        (row, Some(picture))
    }

    /// The picture of event `e` of run `t` at clearance `g`, titled with the mesh, its teeth and
    /// how far past its limit it ran.
    fn picture(
        &self,
        figure: Figure,
        g: f64,
        t: &contact::Trajectory,
        e: &contact::Event,
    ) -> OutputFile {
        let (_, short, file) = figure.names();
        let (counted, side) = match figure {
            Figure::Jam => (
                "jam",
                format!("{} % of h inside its jam limit", self.margin),
            ),
            Figure::Decoupling => (
                "disengagement",
                format!("{} % of h beyond its disengagement limit", self.margin),
            ),
        };
        let (n1, n2) = self.teeth;
        let title = format!(
            "Figure {short}: {} ({n1}:{n2}), ideal teeth, h = {} mm, G = {} % of h ({side})",
            self.label,
            self.h,
            fmt_f64(g, 2),
        );
        OutputFile::new(
            file,
            presentation::event_picture::event_svg(
                &title,
                t,
                e,
                counted,
                &presentation::pair_html::solver_teeth(t.mesh()),
            ),
        )
    }
}
