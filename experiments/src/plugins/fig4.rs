//! `fig4`: one instance of the Lunar, Metonic and Saros Theoretical Difference over the first
//! turn of the solar pointer, ideal triangular teeth at G = 40 %.

use std::f64::consts::TAU;

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};

use crate::common::{Series, csv, line_plot};

registry::params! {
    /// `trial`: which trial's random initial angles (stream of the seed).
    const TRIAL = Param::new("trial", "0", "which trial's random initial angles (stream of the seed)", registry::Kind::count(0, u64::MAX, ""));
}

/// `samples`: samples over the solar turn.
const SAMPLES: Param = registry::samples("7200", "samples over the solar turn");

crate::experiment! {
    id: "fig4", paper_item: "Figure 4 (section 3)", run,
    title: "One instance of the Lunar, Metonic and Saros Theoretical Difference over the first solar turn",
    params: [TRIAL, SAMPLES], groups: [study::gearing::GROUP, study::events::GROUP],
}

const POINTERS: [(&str, &str); 3] = [("Lunar", "A"), ("Metonic", "B"), ("Saros", "C")];

fn run(ctx: &Context) -> Result<Report, RunError> {
    crate::settings::labelled(ctx, counted)
}

/// The experiment itself; [`run`] names the event rule in its tables' titles.
fn counted(ctx: &Context) -> Result<Report, RunError> {
    let s = crate::settings::gearing(ctx)?;
    let mech = study::pointers::ideal_mechanism(&s, &crate::settings::rule(ctx)?)?;
    let samples: usize = ctx.get(&SAMPLES)?;
    let names = POINTERS.map(|(name, _)| name);
    let runs = study::pointers::instance(&mech, &names, 1.0, ctx.seed(), ctx.get(&TRIAL)?);
    let psis: Vec<f64> = (0..samples)
        .map(|i| TAU * i as f64 / (samples - 1) as f64)
        .collect();
    let mut table = Table::new(
        "Figure 4: one instance over the first turn of the solar pointer (ideal teeth)",
        ["pointer", "sigma [deg]", "Dm [deg]", "mean P [deg]", "jams"],
    );
    let mut columns = Vec::new();
    let mut files = Vec::new();
    for ((name, panel), r) in POINTERS.into_iter().zip(runs) {
        let r = r.ok_or_else(|| {
            RunError::bad("gearing", format!("pointer {name}"), "is missing or broken")
        })?;
        let td: Vec<f64> = psis
            .iter()
            .map(|&p| r.theoretical_difference(p).to_degrees())
            .collect();
        let s = stats::pointer_stats(&td);
        table.row(vec![
            name.into(),
            fmt_f64(s.sigma, 4),
            fmt_f64(s.dm, 4),
            fmt_f64(s.mean, 4),
            r.first_stop().map_or_else(
                || "0".into(),
                |st| format!("day {:.1} at {}", st.day, st.mesh),
            ),
        ]);
        let svg = line_plot(
            &format!(
                "Figure 4 {panel}: {name} pointer, Theoretical Difference over one solar turn"
            ),
            "solar pointer (b arbor) angle [deg]",
            "Theoretical Difference [deg]",
            &[Series::in_degrees(name, &psis, &td)],
        )?;
        files.push(OutputFile::new(
            format!("fig4{}.svg", panel.to_lowercase()),
            svg,
        ));
        columns.push(td);
    }
    table.note("The paper's Figure 4 is one of its thirty instances; its text gives no numbers for it (Table 1 has the averages).");
    let rows = (0..samples).map(|i| {
        vec![
            psis[i].to_degrees(),
            columns[0][i],
            columns[1][i],
            columns[2][i],
        ]
    });
    files.push(OutputFile::new(
        "fig4.csv",
        csv(
            &[
                "solar_deg",
                "lunar_td_deg",
                "metonic_td_deg",
                "saros_td_deg",
            ],
            rows,
            9,
        ),
    ));
    Ok(Report {
        tables: vec![table],
        files,
        ..Default::default()
    })
}
