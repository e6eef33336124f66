//! `fig3`: the Theoretical Difference of the N = 8 example from three initial angles: the pointer
//! lagging, centred (mean zero, the paper's optimum) and leading.

use std::f64::consts::TAU;

use contact::{Solve, Start, Trajectory};
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{Series, csv, deg, line_plot};
use study::equal_pair::{EqualPair, EqualPairParams};

registry::params! {
    /// `pitches`: length of each run.
    const PITCHES = Param::new("pitches", "3", "length of each run", registry::Kind::count(1, registry::MAX_COUNT as u64, "a run spans at least one tooth")).unit("driver teeth");
}

/// `samples`: samples per run.
const SAMPLES: Param = registry::samples("1200", "samples per run");

/// Figure 3's settings: the length of each run, its samples and the pair of equal gears.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Length of each run, driver teeth ([`PITCHES`]).
    #[param(PITCHES)]
    pub pitches: usize,
    /// Samples per run ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The pair: teeth, R, r and D.
    #[group]
    pub pair: EqualPairParams,
}

/// Figure 3's results: the Theoretical Difference from each of three initial angles.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// Driver angle from the initial angle of every sample, radians (the same for each run).
    pub phis: Vec<f64>,
    /// The runs: leading, centred, lagging.
    pub runs: Vec<InitialAngle>,
}

/// One run of Figure 3.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct InitialAngle {
    /// Its name, e.g. `A: leading`.
    pub name: String,
    /// The initial driver angle φ'_o, radians.
    pub phi_o: f64,
    /// The driven angle there θ'_o, radians.
    pub theta_o: f64,
    /// The Theoretical Difference at each of [`Results::phis`], degrees.
    pub td: Vec<f64>,
}

/// Figure 3.
pub struct Fig3;

impl registry::Experiment for Fig3 {
    const ID: &'static str = "fig3";
    const TITLE: &'static str =
        "Theoretical Difference for three initial angles: lagging, centred, leading";
    const PAPER_ITEM: &'static str = "Figure 3 (section 2)";
    const PLACE: Place = Place::Paper(20);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, _: &Run) -> Result<Results, RunError> {
        compute(s)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        figure(s, r)
    }
}

registry::register!(Fig3);

/// Number of points used to find the extreme and centred initial angles over one pitch.
const SCAN: usize = 4000;

/// The initial driver angles within a pitch `p1` from which the pointer leads most, is centred
/// and lags most, read off the long run `long`: f(x) = θ'(x) - ratio x is periodic in the
/// driver pitch, and a run starting at φ'_o has mean Theoretical Difference C - f(φ'_o), C the
/// mean of f.
fn initial_angles(long: &Trajectory, p1: f64, ratio: f64) -> (f64, f64, f64) {
    let f = |x: f64| long.theta_at(x) - ratio * x;
    let xs: Vec<f64> = (0..SCAN).map(|i| p1 * i as f64 / SCAN as f64).collect();
    let fs: Vec<f64> = xs.iter().map(|&x| f(x)).collect();
    let mean_f = fs.iter().sum::<f64>() / SCAN as f64;
    let arg = |better: fn(f64, f64) -> bool| {
        let mut best = 0;
        for i in 1..SCAN {
            if better(fs[i], fs[best]) {
                best = i;
            }
        }
        xs[best]
    };
    let leading = arg(|a, b| a < b);
    let lagging = arg(|a, b| a > b);
    // Centred: the first crossing of f through its mean after the minimum, refined by bisection.
    let mut centred = leading;
    for s in 0..SCAN {
        let (a, b) = (
            leading + p1 * s as f64 / SCAN as f64,
            leading + p1 * (s + 1) as f64 / SCAN as f64,
        );
        if f(a) <= mean_f && f(b) > mean_f {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..60 {
                let m = 0.5 * (lo + hi);
                if f(m) <= mean_f { lo = m } else { hi = m }
            }
            centred = lo % p1;
            break;
        }
    }
    (leading, centred, lagging)
}

/// Refuses a pair whose driver never pushes the driven gear: there is no curve to show.
fn check_driven(long: &Trajectory) -> Result<(), RunError> {
    if long.never_driven() {
        return Err(RunError::bad(
            "--set",
            "centre_distance",
            "puts the gears out of reach: no driver tooth ever pushes the driven gear, so there is no Theoretical Difference to show (bring the centre distance below the sum of the tip radii)",
        ));
    }
    Ok(())
}

/// The table's title and columns.
fn fig3_table(pitches: usize) -> Table {
    Table::new(
        format!(
            "Figure 3: Theoretical Difference from three initial angles ({pitches} driver teeth each)"
        ),
        [
            "initial angle",
            "phi'_o [deg]",
            "theta'_o [deg]",
            "mean P [deg]",
            "sigma [deg]",
            "min [deg]",
            "max [deg]",
        ],
    )
}

/// One initial angle's row: where it starts, and its Theoretical Difference's statistics.
fn td_row(name: &str, phi_o: f64, theta_o: f64, td: &[f64]) -> Vec<String> {
    let s = stats::pointer_stats(td);
    let (mn, mx) = td
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    vec![
        name.into(),
        fmt_f64(deg(phi_o), 4),
        fmt_f64(deg(theta_o), 4),
        fmt_f64(s.mean, 4),
        fmt_f64(s.sigma, 4),
        fmt_f64(mn, 4),
        fmt_f64(mx, 4),
    ]
}

/// Every simulation of Figure 3: the long run that finds the three initial angles, then a run
/// from each.
fn compute(s: &Settings) -> Result<Results, RunError> {
    let EqualPair { teeth: n, mesh, .. } = s.pair.build()?;
    let (pitches, samples) = (s.pitches, s.samples);
    registry::samples_cover("samples", samples, pitches, "pitches")?;
    let p1 = TAU / n as f64;
    let ratio = 1.0; // equal gears

    // f(x) = theta'(x) - ratio x is periodic in the driver pitch; a run starting at phi'_o has mean
    // Theoretical Difference C - f(phi'_o), C the mean of f. So the pointer leads most from the
    // minimum of f, lags most from its maximum, and is centred where f equals its mean.
    let long = mesh.solve(
        0.0..=(pitches + 2) as f64 * p1,
        Start::Touching(0.0),
        Solve::path(),
    );
    check_driven(&long)?;
    let (leading, centred, lagging) = initial_angles(&long, p1, ratio);
    let phis: Vec<f64> = (0..samples)
        .map(|i| pitches as f64 * p1 * i as f64 / (samples - 1) as f64)
        .collect();
    let mut runs = Vec::new();
    for (name, phi_o) in [
        ("A: leading", leading),
        ("B: centred", centred),
        ("C: lagging", lagging),
    ] {
        let t: Trajectory = mesh.solve(
            phi_o..=phi_o + pitches as f64 * p1,
            Start::Touching(long.theta_at(phi_o)),
            Solve::path(),
        );
        let theta_o = t.theta_at(phi_o);
        let td: Vec<f64> = phis
            .iter()
            .map(|&p| deg(t.theta_at(phi_o + p) - theta_o - ratio * p))
            .collect();
        runs.push(InitialAngle {
            name: name.to_owned(),
            phi_o,
            theta_o,
            td,
        });
    }
    Ok(Results { phis, runs })
}

/// The table, fig3.csv and fig3.svg, drawn from the results.
fn figure(s: &Settings, r: &Results) -> Result<Report, RunError> {
    let phis = &r.phis;
    let mut table = fig3_table(s.pitches);
    let mut series = Vec::new();
    for run in &r.runs {
        table.row(td_row(&run.name, run.phi_o, run.theta_o, &run.td));
        series.push(Series {
            label: &run.name,
            points: phis
                .iter()
                .map(|&p| deg(p))
                .zip(run.td.iter().copied())
                .collect(),
        });
    }
    table.note("The paper's Figure 3 gives no numbers in its text; the three curves are written to fig3.csv and fig3.svg.");
    table.note("Leading/lagging: the initial driver angle within one pitch that puts the mean Theoretical Difference highest/lowest; centred: mean zero.");
    let svg = line_plot(
        "Figure 3: Theoretical Difference for three initial angles, N = 8 pair",
        "driver angle phi from the initial angle [deg]",
        "Theoretical Difference [deg]",
        &series,
    )?;
    let rows = (0..phis.len()).map(|i| {
        let mut row = vec![deg(phis[i])];
        row.extend(r.runs.iter().map(|run| run.td[i]));
        row
    });
    let data = csv(
        &[
            "phi_deg",
            "td_leading_deg",
            "td_centred_deg",
            "td_lagging_deg",
        ],
        rows,
        12,
    );
    Ok(Report {
        tables: vec![table],
        files: vec![
            OutputFile::new("fig3.csv", data),
            OutputFile::new("fig3.svg", svg),
        ],
        ..Default::default()
    })
}
