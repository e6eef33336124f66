//! `fig-events`: the paper's Figures V_A and V_B for one ideal mesh (default b2-c1): the mesh just
//! inside its jam limit at its first jam, and just beyond its disengagement limit at its first
//! disengagement, each drawn zoomed on the two teeth involved.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};

use study::gearing;

registry::params! {
    /// `margin`: how far inside the jam limit and beyond the disengagement limit the two runs are made.
    const MARGIN = Param::new("margin", "1", "how far inside the jam limit and beyond the disengagement limit the two runs are made", registry::Kind::number(0.01, 20.0, "% of h")).unit("% of h");
}

crate::experiment! {
    id: "fig-events", paper_item: "Figures V_A and V_B (Appendix II)", run,
    title: "A jam and a decoupling of one ideal mesh, drawn at the instant they happen",
    params: [study::limits::MESH, MARGIN], groups: [study::gearing::SHAPE, study::events::GROUP],
}

/// How closely the limits are located before stepping `margin` past them (% of h).
const LIMIT_TOLERANCE: f64 = 0.01;

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let rule = crate::settings::rule(ctx)?;
    let margin: f64 = ctx.get(&MARGIN)?;
    let gearing::Shape {
        gearing: g,
        tooth_height: h,
        ..
    } = crate::settings::shape(ctx)?;
    let label = ctx.text(&study::limits::MESH)?;
    let pair = crate::settings::ideal_pair(ctx, &g, h)?;
    let (jam_limit, dis_limit) = pair.limits(LIMIT_TOLERANCE, &rule)?;
    let mut table = Table::new(
        format!(
            "Figures V_A and V_B: {label} ({}:{}), ideal teeth, h = {h} mm, one turn of the larger gear from driver angle 0",
            pair.n1, pair.n2
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
        label,
        h,
        pair: &pair,
        rule: &rule,
        margin,
    };
    for (figure, limit) in [Figure::Jam, Figure::Decoupling]
        .into_iter()
        .zip([jam_limit, dis_limit])
    {
        let (row, picture) = mesh.figure(figure, limit)?;
        table.row(row);
        files.extend(picture);
    }
    table.note(format!(
        "Limits as `clearance` finds them (located to {LIMIT_TOLERANCE} % of h), then a run {margin} % of h inside the jam limit and beyond the disengagement limit; each picture shows the mesh at its first jam or disengagement, zoomed on the two teeth, with the contact point and its normal. The paper's Figure V_A shows a lock (one driver tip pushes a driven flank while another meets a preceding tooth), V_B tips that no longer reach each other."
    ));
    Ok(Report {
        tables: vec![table],
        files,
        ..Default::default()
    })
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

/// The mesh both figures draw, and how they are found.
struct Mesh<'a> {
    /// The mesh's label, e.g. `b2-c1`.
    label: &'a str,
    /// Tooth height h, mm.
    h: f64,
    /// Its two ideal gears.
    pair: &'a study::limits::IdealPair,
    /// The event rule that says what is a jam and what a disengagement.
    rule: &'a rules::Rule,
    /// How far past each limit the run is made, % of h.
    margin: f64,
}

impl Mesh<'_> {
    /// `figure`'s table row and picture: a run `margin` past its `limit`, drawn at its first
    /// event of the figure's kind (a row of dashes and no picture where none is found).
    fn figure(
        &self,
        figure: Figure,
        limit: Option<f64>,
    ) -> Result<(Vec<String>, Option<OutputFile>), RunError> {
        let (name, _, file) = figure.names();
        let at = limit.map(|l| match figure {
            Figure::Jam => l - self.margin,
            Figure::Decoupling => l + self.margin,
        });
        let mut row = vec![
            name.to_string(),
            limit.map_or_else(|| "-".into(), |l| fmt_f64(l, 2)),
            at.map_or_else(|| "-".into(), |g| fmt_f64(g, 2)),
        ];
        let found = match at {
            Some(gc) if gc > 0.0 => self.first_event(figure, gc)?,
            _ => None,
        };
        let Some((t, e)) = found else {
            row.extend(["none found", "-", "-", "-", "-"].map(String::from));
            return Ok((row, None));
        };
        let picture = self.picture(figure, at.unwrap_or_default(), &t, &e);
        row.extend([
            e.label().to_string(),
            fmt_f64(e.phi.to_degrees(), 4),
            e.driver_tooth.rem_euclid(self.pair.n1 as i64).to_string(),
            e.driven_tooth.rem_euclid(self.pair.n2 as i64).to_string(),
            file.to_string(),
        ]);
        Ok((row, Some(picture)))
    }

    /// The run at clearance `gc` and its first event counted as the figure's kind, if any.
    fn first_event(
        &self,
        figure: Figure,
        gc: f64,
    ) -> Result<Option<(contact::Trajectory, contact::Event)>, RunError> {
        Ok(self.pair.run(gc)?.and_then(|t| {
            let e = t
                .events()
                .iter()
                .find(|e| match figure {
                    Figure::Jam => self.rule.is_jam(e),
                    Figure::Decoupling => self.rule.is_disengagement(e),
                })
                .cloned()?;
            Some((t, e))
        }))
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
        let title = format!(
            "Figure {short}: {} ({}:{}), ideal teeth, h = {} mm, G = {} % of h ({side})",
            self.label,
            self.pair.n1,
            self.pair.n2,
            self.h,
            fmt_f64(g, 2),
        );
        OutputFile::new(
            file,
            crate::event_picture::event_svg(
                &title,
                t,
                e,
                counted,
                &crate::pair_html::solver_teeth(t.mesh()),
            ),
        )
    }
}
