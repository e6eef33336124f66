//! `fig3`: the Theoretical Difference of the N = 8 example from three initial angles: the pointer
//! lagging, centred (mean zero, the paper's optimum) and leading.

use std::f64::consts::TAU;

use contact::{Solve, Start, Trajectory};
use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};

use crate::common::{Series, csv, deg, line_plot};
use study::equal_pair;

registry::params! {
    /// `pitches`: length of each run.
    const PITCHES = Param::new("pitches", "3", "length of each run", registry::Kind::count(1, registry::MAX_COUNT as u64, "a run spans at least one tooth")).unit("driver teeth");
}

/// `samples`: samples per run.
const SAMPLES: Param = registry::samples("1200", "samples per run");

crate::experiment! {
    id: "fig3", paper_item: "Figure 3 (section 2)", run,
    title: "Theoretical Difference for three initial angles: lagging, centred, leading",
    params: [PITCHES, SAMPLES], groups: [study::equal_pair::GROUP],
}

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

fn run(ctx: &Context) -> Result<Report, RunError> {
    let equal_pair::EqualPair { teeth: n, mesh, .. } = crate::settings::equal_pair(ctx)?;
    let pitches: usize = ctx.get(&PITCHES)?;
    let samples: usize = ctx.get(&SAMPLES)?;
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

    let mut table = fig3_table(pitches);
    let mut series = Vec::new();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let phis: Vec<f64> = (0..samples)
        .map(|i| pitches as f64 * p1 * i as f64 / (samples - 1) as f64)
        .collect();
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
        table.row(td_row(name, phi_o, theta_o, &td));
        series.push(Series {
            label: name,
            points: phis
                .iter()
                .map(|&p| deg(p))
                .zip(td.iter().copied())
                .collect(),
        });
        columns.push(td);
    }
    table.note("The paper's Figure 3 gives no numbers in its text; the three curves are written to fig3.csv and fig3.svg.");
    table.note("Leading/lagging: the initial driver angle within one pitch that puts the mean Theoretical Difference highest/lowest; centred: mean zero.");
    let svg = line_plot(
        "Figure 3: Theoretical Difference for three initial angles, N = 8 pair",
        "driver angle phi from the initial angle [deg]",
        "Theoretical Difference [deg]",
        &series,
    )?;
    let rows =
        (0..samples).map(|i| vec![deg(phis[i]), columns[0][i], columns[1][i], columns[2][i]]);
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
