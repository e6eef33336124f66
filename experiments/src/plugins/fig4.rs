//! `fig4`: one instance of the Lunar, Metonic and Saros Theoretical Difference over the first
//! turn of the solar pointer, ideal triangular teeth at G = 40 %.

use std::f64::consts::TAU;

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{Series, csv, line_plot};
use setting_groups::typed::label;
use study::events::EventParams;
use study::gearing::GearingParams;

registry::params! {
    /// `trial`: which trial's random initial angles (the engine's stream of the ideal mechanism
    /// at that trial, Table 1's trial of the same index).
    const TRIAL = Param::new("trial", "0", "which trial's random initial angles (the engine's ideal-mechanism stream at that trial index: Table 1's trial)", registry::Kind::count(0, u64::MAX, ""));
}

/// `samples`: samples over the solar turn.
const SAMPLES: Param = registry::samples("7200", "samples over the solar turn");

/// Figure 4's settings: which trial, the samples, the gearing with h and G and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Which trial's random initial angles ([`TRIAL`]).
    #[param(TRIAL)]
    pub trial: u64,
    /// Samples over the solar turn ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The gearing, G and h.
    #[group]
    pub gearing: GearingParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Figure 4's results: each pointer's Theoretical Difference over the first solar turn.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// The solar pointer (b arbor) angle of every sample, radians.
    pub solar: Vec<f64>,
    /// Lunar, Metonic and Saros, in the panels' order.
    pub pointers: Vec<Instance>,
}

/// One pointer's panel of Figure 4.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Instance {
    /// The pointer's name.
    pub pointer: String,
    /// Its panel's letter (`A`, `B`, `C`).
    pub panel: String,
    /// The Theoretical Difference at each of [`Results::solar`], degrees.
    pub td: Vec<f64>,
    /// Its first jam, if any: the day of b and the mesh that jammed.
    pub first_jam: Option<(f64, String)>,
}

/// Figure 4.
pub struct Fig4;

impl registry::Experiment for Fig4 {
    const ID: &'static str = "fig4";
    const TITLE: &'static str = "One instance of the Lunar, Metonic and Saros Theoretical Difference over the first solar turn";
    const PAPER_ITEM: &'static str = "Figure 4 (section 3)";
    const PLACE: Place = Place::Paper(40);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        compute(s, run.seed())
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, None, figure(r)?)
    }
}

registry::register!(Fig4);

const POINTERS: [(&str, &str); 3] = [("Lunar", "A"), ("Metonic", "B"), ("Saros", "C")];

/// Every simulation of Figure 4: one instance of the mechanism, each pointer's TD sampled.
fn compute(s: &Settings, seed: u64) -> Result<Results, RunError> {
    let g = s.gearing.load()?;
    let mech = study::pointers::ideal_mechanism(&g, &s.events.rule()?)?;
    let samples = s.samples;
    let names = POINTERS.map(|(name, _)| name);
    let runs = study::pointers::instance(&mech, &names, 1.0, seed, s.trial);
    let solar: Vec<f64> = (0..samples)
        .map(|i| TAU * i as f64 / (samples - 1) as f64)
        .collect();
    let mut pointers = Vec::new();
    for ((name, panel), r) in POINTERS.into_iter().zip(runs) {
        let r = r.ok_or_else(|| {
            RunError::bad("gearing", format!("pointer {name}"), "is missing or broken")
        })?;
        pointers.push(Instance {
            pointer: name.to_owned(),
            panel: panel.to_owned(),
            td: solar
                .iter()
                .map(|&p| r.theoretical_difference(p).to_degrees())
                .collect(),
            first_jam: r.first_stop().map(|st| (st.day, st.mesh)),
        });
    }
    Ok(Results { solar, pointers })
}

/// The table, each panel's plot and fig4.csv, drawn from the results.
fn figure(r: &Results) -> Result<Report, RunError> {
    let psis = &r.solar;
    let mut table = Table::new(
        "Figure 4: one instance over the first turn of the solar pointer (ideal teeth)",
        ["pointer", "sigma [deg]", "Dm [deg]", "mean P [deg]", "jams"],
    );
    let mut files = Vec::new();
    for p in &r.pointers {
        let (name, panel, td) = (p.pointer.as_str(), p.panel.as_str(), &p.td);
        let s = stats::pointer_stats(td);
        table.row(vec![
            name.into(),
            fmt_f64(s.sigma, 4),
            fmt_f64(s.dm, 4),
            fmt_f64(s.mean, 4),
            p.first_jam.as_ref().map_or_else(
                || "0".into(),
                |(day, mesh)| format!("day {day:.1} at {mesh}"),
            ),
        ]);
        let svg = line_plot(
            &format!(
                "Figure 4 {panel}: {name} pointer, Theoretical Difference over one solar turn"
            ),
            "solar pointer (b arbor) angle [deg]",
            "Theoretical Difference [deg]",
            &[Series::in_degrees(name, psis, td)],
        )?;
        files.push(OutputFile::new(
            format!("fig4{}.svg", panel.to_lowercase()),
            svg,
        ));
    }
    table.note("The paper's Figure 4 is one of its thirty instances; its text gives no numbers for it (Table 1 has the averages).");
    let rows = (0..psis.len()).map(|i| {
        let mut row = vec![psis[i].to_degrees()];
        row.extend(r.pointers.iter().map(|p| p.td[i]));
        row
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
