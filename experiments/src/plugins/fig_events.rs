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
    let cases = [
        (
            "V_A (a jam)",
            jam_limit.map(|l| l - margin),
            true,
            "fig-V_A.svg",
        ),
        (
            "V_B (a decoupling)",
            dis_limit.map(|l| l + margin),
            false,
            "fig-V_B.svg",
        ),
    ];
    for ((figure, at, jam, file), limit) in cases.into_iter().zip([jam_limit, dis_limit]) {
        let mut row = vec![
            figure.to_string(),
            limit.map_or_else(|| "-".into(), |l| fmt_f64(l, 2)),
            at.map_or_else(|| "-".into(), |g| fmt_f64(g, 2)),
        ];
        let found = match at {
            Some(gc) if gc > 0.0 => pair.run(gc)?.and_then(|t| {
                let e = t
                    .events()
                    .iter()
                    .find(|e| {
                        if jam {
                            rule.is_jam(e)
                        } else {
                            rule.is_disengagement(e)
                        }
                    })
                    .cloned()?;
                Some((t, e))
            }),
            _ => None,
        };
        match found {
            Some((t, e)) => {
                let counted = if jam { "jam" } else { "disengagement" };
                let g = at.unwrap_or_default();
                let side = if jam {
                    format!("{margin} % of h inside its jam limit")
                } else {
                    format!("{margin} % of h beyond its disengagement limit")
                };
                let picture_title = format!(
                    "Figure {}: {label} ({}:{}), ideal teeth, h = {h} mm, G = {} % of h ({side})",
                    figure.split(' ').next().unwrap_or(figure),
                    pair.n1,
                    pair.n2,
                    fmt_f64(g, 2),
                );
                files.push(OutputFile::new(
                    file,
                    crate::event_picture::event_svg(
                        &picture_title,
                        &t,
                        &e,
                        counted,
                        &crate::pair_html::solver_teeth(t.mesh()),
                    ),
                ));
                row.extend([
                    e.label().to_string(),
                    fmt_f64(e.phi.to_degrees(), 4),
                    e.driver_tooth.rem_euclid(pair.n1 as i64).to_string(),
                    e.driven_tooth.rem_euclid(pair.n2 as i64).to_string(),
                    file.to_string(),
                ]);
            }
            None => row.extend([
                "none found".to_string(),
                "-".into(),
                "-".into(),
                "-".into(),
                "-".into(),
            ]),
        }
        table.row(row);
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
