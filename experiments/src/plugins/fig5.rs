//! `fig5`: a 50:50 pair with random and systematic errors under three splits of the systematic
//! error (all eccentricity, 50/50, all sinusoid): Edmunds' model against triangular teeth.

use std::f64::consts::TAU;

use edmunds::RadialPair;
use geometry::Gear;
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64, fmt_number};
use serde::{Deserialize, Serialize};

use presentation::common::{Plot, Series, csv, drawable};
use setting_groups::typed::label;
use study::errors::{self, ErrorParams};
use study::events::EventParams;
use study::results::{SplitPairs, SplitRun};

/// `tip_radius`: R of both gears.
const TIP_RADIUS: Param = study::equal_pair::length("tip_radius", "200", "R of both gears");

/// `root_radius`: r of both gears.
const ROOT_RADIUS: Param = study::equal_pair::length("root_radius", "180", "r of both gears");

registry::params! {
    /// `clearance`: clearance G of the pair. Not the gearing group's `clearance`
    /// ([`study::gearing::CLEARANCE`], default 40): Figure 5 runs a pair of its own, not the
    /// gearing, with a default of its own (50 %) under the same name.
    const PAIR_CLEARANCE = Param::new("clearance", "50", "clearance G", registry::Kind::positive(100.0, "% of the tooth height h")).unit("% of h").a_clearance();
    /// `random`: random tooth error (sd).
    const RANDOM = Param::new("random", "0.05", "random tooth error (sd)", registry::Kind::number(0.0, hypotheses::MAX_RANDOM, "of the pitch")).unit("of the pitch");
    /// `systematic`: systematic error amplitude A.
    const SYSTEMATIC = Param::new("systematic", "0.6", "systematic error amplitude A", registry::Kind::number(0.0, 45.0, "deg")).unit("deg");
    /// `trial`: which trial's errors and initial angle (the engine's Figure 5 stream at that trial index).
    const TRIAL = Param::new("trial", "0", "which trial's errors and initial angle (the engine's Figure 5 stream at that trial index)", registry::Kind::count(0, u64::MAX, ""));
}

/// `samples`: samples over the turn.
const SAMPLES: Param = registry::samples("3600", "samples over the turn");

registry::params! {
    /// `teeth`: teeth of both gears.
    const TEETH = Param::new("teeth", "50", "teeth of both gears", registry::Kind::count(3, geometry::MAX_TEETH as u64, "a gear needs three teeth"));
}

/// Figure 5's settings: the pair, its clearance, the errors offered to the hypothesis, the
/// trial stream, the samples, the hypothesis and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Teeth of both gears ([`TEETH`]).
    #[param(TEETH)]
    pub teeth: usize,
    /// R of both gears ([`TIP_RADIUS`]).
    #[param(TIP_RADIUS)]
    pub tip_radius: f64,
    /// r of both gears ([`ROOT_RADIUS`]).
    #[param(ROOT_RADIUS)]
    pub root_radius: f64,
    /// Clearance G of the pair, % of h ([`PAIR_CLEARANCE`]).
    #[param(PAIR_CLEARANCE)]
    pub clearance: f64,
    /// Random tooth error (sd), share of the pitch ([`RANDOM`]).
    #[param(RANDOM)]
    pub random: f64,
    /// Systematic error amplitude A, degrees ([`SYSTEMATIC`]).
    #[param(SYSTEMATIC)]
    pub systematic: f64,
    /// Which trial's errors and initial angle ([`TRIAL`]).
    #[param(TRIAL)]
    pub trial: u64,
    /// Samples over the turn ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The hypothesis and its parameters.
    #[group]
    pub errors: ErrorParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Figure 5.
pub struct Fig5;

impl registry::Experiment for Fig5 {
    const ID: &'static str = "fig5";
    const TITLE: &'static str =
        "Edmunds' model against triangular teeth for three splits of the systematic error";
    const PAPER_ITEM: &'static str = "Figure 5 (section 4)";
    const PLACE: Place = Place::Paper(70);
    type Settings = Settings;
    type Results = SplitPairs;

    fn compute(s: &Settings, run: &Run) -> Result<SplitPairs, RunError> {
        compute(s, run.seed())
    }

    fn report(s: &Settings, r: &SplitPairs) -> Result<Report, RunError> {
        label(&s.events, None, figure(r)?)
    }
}

registry::register!(Fig5);

const SPLITS: [(&str, f64); 3] = [
    ("A: all eccentricity", 0.0),
    ("B: 50/50", 0.5),
    ("C: all sinusoid", 1.0),
];

/// Below this Edmunds' σ (degrees) his pointer is exact: no ratio is printed.
const EDMUNDS_FLAT: f64 = 1e-9;

/// The axis ranges the three panels share (degrees): the driver angles, and every panel's
/// finite Theoretical Differences with a tenth of their span on each side.
fn shared_ranges(series: &[SplitRun], phis: &[f64]) -> ((f64, f64), (f64, f64)) {
    let x = phis.iter().map(|p| p.to_degrees());
    let x0 = x.clone().fold(f64::INFINITY, f64::min);
    let x1 = x.fold(f64::NEG_INFINITY, f64::max);
    let ys = series
        .iter()
        .flat_map(|s| s.edmunds_td.iter().chain(&s.triangular_td));
    let (mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY);
    for y in ys.filter(|y| y.is_finite()) {
        y0 = y0.min(*y);
        y1 = y1.max(*y);
    }
    if y0 > y1 {
        (y0, y1) = (0.0, 1.0);
    }
    let pad = ((y1 - y0) * 0.1).max(1e-3);
    (drawable(x0, x1), drawable(y0 - pad, y1 + pad))
}

/// The three panels' plots (fig5a-c.svg) and fig5.csv (every panel's curves over the driver
/// angles `phis`).
fn panels(series: &[SplitRun], phis: &[f64]) -> Result<Vec<OutputFile>, RunError> {
    let samples = phis.len();
    let (x_range, y_range) = shared_ranges(series, phis);
    let mut files = Vec::new();
    for (i, split) in series.iter().enumerate() {
        let (name, rad, tri) = (&split.name, &split.edmunds_td, &split.triangular_td);
        let label = ["a", "b", "c"][i];
        // The split's name starts with its panel letter ("A: all eccentricity"): the title
        // gives the letter once.
        let (letter, split) = name.split_once(": ").unwrap_or((name, ""));
        let title = format!("Figure 5 {letter}: Theoretical Difference, {split}");
        let curves = [
            Series::in_degrees("Edmunds (radial lines)", phis, rad),
            Series::in_degrees("triangular teeth", phis, tri),
        ];
        // One y range for the three panels, so that their curves compare at a glance.
        let svg = Plot::new(
            &title,
            "driver angle phi [deg]",
            "Theoretical Difference [deg]",
            &curves,
        )
        .ranges(x_range, y_range)
        .svg()?;
        files.push(OutputFile::new(format!("fig5{label}.svg"), svg));
    }
    let rows = (0..samples).map(|i| {
        let mut r = vec![phis[i].to_degrees()];
        r.extend(
            series
                .iter()
                .flat_map(|s| [s.edmunds_td[i], s.triangular_td[i]]),
        );
        r
    });
    files.push(OutputFile::new(
        "fig5.csv",
        csv(
            &[
                "phi_deg",
                "a_edmunds_deg",
                "a_triangular_deg",
                "b_edmunds_deg",
                "b_triangular_deg",
                "c_edmunds_deg",
                "c_triangular_deg",
            ],
            rows,
            9,
        ),
    ));
    Ok(files)
}

/// The values the hypothesis ran with, as the title names them (the split aside: each panel
/// has its own), e.g. "random 0.04 of the pitch, systematic 0.5 deg, ".
fn ran_values(ran: &[(String, f64)]) -> String {
    ran.iter()
        .map(|(k, v)| match k.as_str() {
            "random" => format!("random {} of the pitch, ", fmt_number(*v)),
            "systematic" => format!("systematic {} deg, ", fmt_number(*v)),
            _ => format!("{k} {}, ", fmt_number(*v)),
        })
        .collect()
}

/// The table's title and columns.
fn figure_table(n: usize, big_r: f64, small_r: f64, values: &str, hypothesis: &str) -> Table {
    Table::new(
        format!(
            "Figure 5: {n}:{n} pair, R = {}, r = {}, {values}hypothesis {hypothesis}",
            fmt_number(big_r),
            fmt_number(small_r),
        ),
        [
            "split",
            "Edmunds sigma [deg]",
            "triangular sigma [deg]",
            "triangular/Edmunds",
            "jams",
            "disengagements",
        ],
    )
}

/// Refuses a hypothesis whose gears Edmunds' radial-line model cannot see.
fn edmunds_sees(hypothesis: &str, driver: &Gear, driven: &Gear) -> Result<(), RunError> {
    if let Some(what) = edmunds::unseen(driver).or_else(|| edmunds::unseen(driven)) {
        return Err(RunError::bad(
            "--hypothesis",
            hypothesis,
            format!(
                "makes gears with {what}, which Edmunds' radial-line model cannot take (it sees only each tip's angle about the axis), so Figure 5's comparison cannot hold: choose one that moves tips or the axis (edmunds-split, eccentric-only, sinusoid-only, measured)"
            ),
        ));
    }
    Ok(())
}

/// One split's row: both sigmas, their ratio where Edmunds' is not flat, and the events.
fn row_cells(
    name: &str,
    s_rad: f64,
    s_tri: f64,
    idle: bool,
    (jams, disengagements): (usize, usize),
) -> Vec<String> {
    vec![
        name.into(),
        fmt_f64(s_rad, 4),
        if idle {
            "- (never driven)".into()
        } else {
            fmt_f64(s_tri, 4)
        },
        if idle {
            "-".into()
        } else if s_rad > EDMUNDS_FLAT {
            fmt_f64(s_tri / s_rad, 3)
        } else {
            "n/a".into()
        },
        jams.to_string(),
        disengagements.to_string(),
    ]
}

/// The notes under the table: what both models share, and the marks the rows used.
fn add_notes(table: &mut Table, never_driven: bool, no_ratio: bool) {
    table.note("Both models run on the same manufactured gears and the same initial angle; one turn of the driver.");
    if never_driven {
        table.note("Never driven: no driver tooth reached the driven gear in the whole turn (an idle start, counted as a disengagement by every event rule), so its triangular-teeth sigma describes nothing and is not given.");
    }
    if no_ratio {
        table.note("n/a: Edmunds' sigma is 0 (gears with no tip or axis error keep his pointer exact), so the two cannot be compared by a ratio.");
    }
    table.note("The paper's claim: the split does not change the pointer's behaviour significantly. Its Figure 5 gives no numbers in the text.");
}

/// Every simulation of Figure 5: the pair made three times from one stream, each split run
/// under both models.
fn compute(s: &Settings, seed: u64) -> Result<SplitPairs, RunError> {
    let rule = s.events.rule()?;
    let (n, big_r, small_r) = (s.teeth, s.tip_radius, s.root_radius);
    let ideal =
        Gear::ideal(n, big_r, small_r).map_err(|e| RunError::bad("--set", e.field, e.rule))?;
    // Two equal gears of height R - r at the chosen clearance.
    let pair = study::limits::IdealPair {
        n1: n,
        n2: n,
        r1: big_r,
        r2: big_r,
        h: big_r - small_r,
    };
    let errors = s.errors.load(None, s)?;
    let h = errors.hypothesis;
    let samples = s.samples;
    registry::samples_cover(SAMPLES.name, samples, n, TEETH.name)?;
    let phis: Vec<f64> = (0..samples)
        .map(|i| TAU * i as f64 / (samples - 1) as f64)
        .collect();
    let offered = [(RANDOM.name, s.random), (SYSTEMATIC.name, s.systematic)];
    // The title names the values the hypothesis ran with (a `hypothesis_params` value replaces
    // the experiment's own), and only those it takes.
    let ran = errors.params(&offered)?;
    let mut splits = Vec::new();
    for (name, split) in SPLITS {
        let p = errors.params(&[offered[0], offered[1], ("split", split)])?;
        // The same stream for every split: only the split changes between the panels.
        let (driver, driven, phi0) = errors::made_pair(h, &ideal, &p, seed, s.trial)?;
        edmunds_sees(h.name(), &driver, &driven)?;
        let tri = pair.run_made((&driver, &driven), s.clearance, phi0)?;
        let rad = RadialPair::new(&driver, &driven, phi0);
        let td = |f: &dyn Fn(f64) -> f64| -> Vec<f64> {
            let t0 = f(phi0);
            phis.iter()
                .map(|&p| (f(phi0 + p) - t0 - p).to_degrees())
                .collect()
        };
        let (edmunds_td, triangular_td) = (td(&|p| rad.theta(p)), td(&|p| tri.theta_at(p)));
        let (jams, disengagements) = study::events::counts(&rule, &tri);
        splits.push(SplitRun {
            name: name.to_owned(),
            sinusoid_share: split,
            edmunds_sigma: stats::pointer_stats(&edmunds_td).sigma,
            triangular_sigma: stats::pointer_stats(&triangular_td).sigma,
            edmunds_td,
            triangular_td,
            never_driven: tri.never_driven(),
            jams,
            disengagements,
        });
    }
    Ok(SplitPairs {
        teeth: n,
        tip_radius: big_r,
        root_radius: small_r,
        hypothesis: h.name().to_owned(),
        values: ran
            .iter()
            .filter(|(k, _)| *k != "split")
            .map(|(k, v)| (k.to_owned(), v))
            .collect(),
        driver_angles: phis,
        splits,
    })
}

/// The table, the three panels and fig5.csv, drawn from the results.
fn figure(r: &SplitPairs) -> Result<Report, RunError> {
    let values = ran_values(&r.values);
    let mut table = figure_table(r.teeth, r.tip_radius, r.root_radius, &values, &r.hypothesis);
    let mut no_ratio = false;
    let mut never_driven = false;
    for split in &r.splits {
        let idle = split.never_driven;
        never_driven |= idle;
        let counts = (split.jams, split.disengagements);
        let (s_rad, s_tri) = (split.edmunds_sigma, split.triangular_sigma);
        let cells = row_cells(&split.name, s_rad, s_tri, idle, counts);
        no_ratio |= cells[3] == "n/a";
        table.row(cells);
    }
    add_notes(&mut table, never_driven, no_ratio);
    let files = panels(&r.splits, &r.driver_angles)?;
    Ok(Report {
        tables: vec![table],
        files,
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]

    /// The y tick labels of a panel (the numbers written at the left axis).
    fn y_ticks(svg: &str) -> Vec<String> {
        svg.split("<text")
            .skip(1)
            .filter(|t| t.contains("text-anchor=\"end\""))
            .filter_map(|t| Some(t[t.find('>')? + 1..t.find("</text>")?].trim().to_owned()))
            .filter(|t| t.parse::<f64>().is_ok())
            .collect()
    }

    #[test]
    fn the_three_panels_share_one_y_range_and_name_their_letter_once() {
        let r = crate::run("fig5", 2025, 1, &[("samples", "400")]).unwrap();
        let panels: Vec<(String, String)> = r
            .files
            .iter()
            .filter(|f| f.name.ends_with(".svg"))
            .map(|f| {
                (
                    f.name.clone(),
                    String::from_utf8(f.contents.clone()).unwrap(),
                )
            })
            .collect();
        assert_eq!(panels.len(), 3);
        let first = y_ticks(&panels[0].1);
        assert!(first.len() >= 4, "{first:?}");
        for ((name, svg), letter) in panels.iter().zip(["A", "B", "C"]) {
            assert_eq!(y_ticks(svg), first, "{name}: its own y range");
            let title = format!("Figure 5 {letter}: Theoretical Difference, ");
            assert!(svg.contains(&title), "{name}");
            assert!(
                !svg.contains(&format!("{title}{letter}:")),
                "{name}: letter twice"
            );
        }
    }
}
