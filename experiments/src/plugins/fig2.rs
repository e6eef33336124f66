//! `fig2`: θ(φ) and the Theoretical Difference of the paper's N = 8 example, simulated by the
//! exact contact solver and computed from Thorndike's closed forms, side by side.

use std::f64::consts::TAU;

use contact::{Solve, Start, Trajectory};
use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{MAX_DATA_ROWS, Series, csv, deg, line_plot, paper_cell};
use setting_groups::typed::label;
use study::equal_pair::{self, EqualPairParams};
use study::events::EventParams;

/// The most teeth fig2 simulates over a whole driver turn: 500 (a few minutes).
const MAX_TEETH: usize = 500;

registry::params! {
    /// `step`: driver angle between samples.
    const STEP = Param::new("step", "0.01", "driver angle between samples", registry::Kind::positive(10.0, "degrees")).unit("deg");
}

/// Figure 2's settings: the sampling step, the pair of equal gears and the event rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Driver angle between samples, degrees ([`STEP`]).
    #[param(STEP)]
    pub step: f64,
    /// The pair: teeth, R, r and D.
    #[group]
    pub pair: EqualPairParams,
    /// The event rule.
    #[group]
    pub events: EventParams,
}

/// Figure 2's results: one driver turn of the pair, simulated and in closed form.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// θ'(0), the driven angle at the start in Figure III's frame, radians.
    pub theta0: f64,
    /// Steps over the turn (the rows are one more).
    pub samples: usize,
    /// Largest |θ' simulated − θ' closed form| over the samples, radians.
    pub max_diff: f64,
    /// φ' of the switch from Phase 1 to Phase 2 (closed form), radians.
    pub phase_switch: f64,
    /// φ' at which the next tooth pair takes over (closed form), radians.
    pub handoff: f64,
    /// σ of the Theoretical Difference, degrees.
    pub sigma: f64,
    /// Mean P of the Theoretical Difference, degrees.
    pub mean: f64,
    /// Dm, the largest |TD|, degrees.
    pub dm: f64,
    /// Jams in the turn, as the event rule counts them.
    pub jams: usize,
    /// Disengagements in the turn, as the event rule counts them.
    pub disengagements: usize,
    /// A row per sample (degrees): φ, θ' simulated, θ' closed form, θ, TD.
    pub rows: Vec<[f64; 5]>,
}

/// Figure 2.
pub struct Fig2;

impl registry::Experiment for Fig2 {
    const ID: &'static str = "fig2";
    const TITLE: &'static str = "theta(phi) and Theoretical Difference of two N = 8 triangular-tooth gears, simulated vs closed form";
    const PAPER_ITEM: &'static str = "Figure 2 (section 2) and Figure III (Appendix I)";
    const PLACE: Place = Place::Paper(10);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, _: &Run) -> Result<Results, RunError> {
        compute(s)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, None, figure(r)?)
    }
}

registry::register!(Fig2);

/// Figure 2's numbers: θ'(0), the largest difference from the closed forms, the phase switch
/// and hand-off, the Theoretical Difference's statistics and the run's jams and disengagements.
fn summary_table(r: &Results) -> Table {
    let mut table = Table::new(
        "Figure 2: N1 = N2 = 8, R = 200, r = 100, D = 310 (G = 10 % of h), one driver turn",
        ["quantity", "ours", "paper", "unit"],
    );
    table.row(vec![
        "theta'(0) (Figure III frame)".into(),
        fmt_f64(deg(r.theta0), 4),
        paper_cell("fig2", "theta_prime_0", 2),
        "deg".into(),
    ]);
    table.row(vec![
        format!(
            "max |theta simulated - theta closed form| over {} samples",
            r.samples + 1
        ),
        below_power_of_ten(deg(r.max_diff)),
        "-".into(),
        "deg".into(),
    ]);
    let mut quantity = |q: &str, v: f64| {
        table.row(vec![q.into(), fmt_f64(v, 4), "-".into(), "deg".into()]);
    };
    quantity("Phase 1 -> Phase 2 switch phi'", deg(r.phase_switch));
    quantity("next tooth pair takes over at phi'", deg(r.handoff));
    quantity("Theoretical Difference sigma", r.sigma);
    quantity("Theoretical Difference mean P", r.mean);
    quantity("Theoretical Difference max |TD| (Dm)", r.dm);
    table.row(vec![
        "jams / disengagements".into(),
        format!("{} / {}", r.jams, r.disengagements),
        "-".into(),
        "".into(),
    ]);
    table.note("Simulated: exact push-model contact solver; closed form: Appendix I expressions [I] and [II] with the switch between them.");
    table.note(
        "TD = theta(phi) - (N1/N2) phi in the main-text frame (theta measured from theta'_o).",
    );
    table
}

/// Figure 2 A (θ against φ beside the ideal ratio) and B (the Theoretical Difference beside the
/// closed forms' and its mean), from the rows of fig2.csv.
fn plots(
    rows: &[[f64; 5]],
    theta0: f64,
    ratio: f64,
    mean: f64,
) -> Result<(String, String), RunError> {
    let plot_a = line_plot(
        "Figure 2 A: driven angle theta(phi), N = 8 pair",
        "driver angle phi [deg]",
        "driven angle theta [deg]",
        &[
            Series {
                label: "simulated",
                points: rows.iter().map(|r| (r[0], r[3])).collect(),
            },
            Series {
                label: "ideal (N1/N2) phi, equation [1]",
                points: rows.iter().map(|r| (r[0], ratio * r[0])).collect(),
            },
        ],
    )?;
    let plot_b = line_plot(
        "Figure 2 B: Theoretical Difference, N = 8 pair",
        "driver angle phi [deg]",
        "Theoretical Difference [deg]",
        &[
            Series {
                label: "simulated",
                points: rows.iter().map(|r| (r[0], r[4])).collect(),
            },
            Series {
                label: "closed form [I]/[II]",
                points: rows
                    .iter()
                    .map(|r| (r[0], r[2] - deg(theta0) - ratio * r[0]))
                    .collect(),
            },
            Series {
                label: "mean P",
                points: vec![(0.0, mean), (360.0, mean)],
            },
        ],
    )?;
    Ok((plot_a, plot_b))
}

/// Refused before the mesh is built: the work of a driver turn grows as teeth squared.
fn check_teeth(asked: usize) -> Result<(), RunError> {
    if asked > MAX_TEETH {
        return Err(RunError::bad(
            "--set",
            "teeth",
            format!(
                "must be at most {MAX_TEETH} for fig2 (got {asked}): the work of one driver turn grows as the square of the teeth, and 300 teeth already take about a minute"
            ),
        ));
    }
    Ok(())
}

/// Refused before anything runs: one driver turn in steps of `step` degrees must fit the data
/// rows' limit.
fn check_step(step: f64) -> Result<(), RunError> {
    if 360.0 / step > MAX_DATA_ROWS as f64 {
        return Err(RunError::bad(
            "--set",
            STEP.name,
            format!(
                "must be at least {} degrees: one driver turn in steps of {} would be more than {MAX_DATA_ROWS} rows of data, the limit",
                360.0 / MAX_DATA_ROWS as f64,
                registry::fmt_number(step)
            ),
        ));
    }
    Ok(())
}

/// One driver turn in steps of `step` degrees: the data rows (phi, simulated and closed-form
/// theta', theta, TD, in degrees), the TD series and the largest gap between the two theta'.
fn sample(
    traj: &Trajectory,
    pair: &thorndike::Pair,
    step: f64,
    samples: usize,
    ratio: f64,
) -> (Vec<[f64; 5]>, Vec<f64>, f64) {
    let theta0 = traj.theta_at(0.0);
    let mut rows = Vec::with_capacity(samples + 1);
    let mut max_diff: f64 = 0.0;
    let mut td = Vec::with_capacity(samples + 1);
    for i in 0..=samples {
        let phi = (i as f64 * step).to_radians().min(TAU);
        let sim = traj.theta_at(phi);
        let closed = thorndike::theta_prime(pair, phi);
        max_diff = max_diff.max((sim - closed).abs());
        let t = sim - theta0 - ratio * phi;
        td.push(deg(t));
        rows.push([deg(phi), deg(sim), deg(closed), deg(sim - theta0), deg(t)]);
    }
    (rows, td, max_diff)
}

/// Every simulation of Figure 2: one driver turn of the pair, sampled beside the closed forms.
fn compute(s: &Settings) -> Result<Results, RunError> {
    // Refused before the mesh is built: the work of a driver turn grows as teeth squared.
    check_teeth(s.pair.teeth)?;
    let equal_pair::EqualPair {
        teeth: n,
        tip_radius: big_r,
        root_radius: small_r,
        centre_distance: d,
        mesh,
    } = s.pair.build()?;
    check_step(s.step)?;
    let teeth = u32::try_from(n).map_err(|_| RunError::bad("--set", "teeth", "too many teeth"))?;
    let pair =
        thorndike::Pair::new(teeth, teeth, big_r, small_r, big_r, small_r, d).map_err(|e| {
            RunError::bad(
                "--set",
                "centre_distance",
                format!("closed forms do not apply: {e}"),
            )
        })?;

    // Figure III frame: phi'_o = 0, theta'_o = theta'(0); one full driver turn.
    let traj = mesh.solve(0.0..=TAU, Start::Touching(0.0), Solve::path());
    if traj.never_driven() {
        return Err(RunError::bad(
            "--set",
            "centre_distance",
            "puts the gears out of reach: no driver tooth ever pushes the driven gear, so there is no theta(phi) to show (bring the centre distance below the sum of the tip radii)",
        ));
    }
    let samples = (360.0 / s.step).round() as usize;
    let ratio = 1.0; // N1 = N2
    let (rows, td, max_diff) = sample(&traj, &pair, s.step, samples, ratio);
    let stats = stats::pointer_stats(&td);
    let (jams, disengagements) = study::events::counts(&s.events.rule()?, &traj);
    Ok(Results {
        theta0: traj.theta_at(0.0),
        samples,
        max_diff,
        phase_switch: thorndike::phase_switch(&pair),
        handoff: thorndike::handoff(&pair),
        sigma: stats.sigma,
        mean: stats.mean,
        dm: stats.dm,
        jams,
        disengagements,
        rows,
    })
}

/// The table, fig2.csv and both plots, drawn from the results.
fn figure(r: &Results) -> Result<Report, RunError> {
    let ratio = 1.0; // N1 = N2
    let table = summary_table(r);
    let (plot_a, plot_b) = plots(&r.rows, r.theta0, ratio, r.mean)?;
    let data = csv(
        &[
            "phi_deg",
            "theta_prime_sim_deg",
            "theta_prime_closed_deg",
            "theta_deg",
            "td_deg",
        ],
        r.rows.iter().map(|row| row.to_vec()),
        12,
    );
    Ok(Report {
        tables: vec![table],
        files: vec![
            OutputFile::new("fig2.csv", data),
            OutputFile::new("fig2a.svg", plot_a),
            OutputFile::new("fig2b.svg", plot_b),
        ],
        ..Default::default()
    })
}

/// "< 1e-N" for the smallest power of ten above `x`: stable across machines where the last bits of
/// libm differ, and still a failing number if the agreement were lost.
fn below_power_of_ten(x: f64) -> String {
    if x == 0.0 {
        return "0".into();
    }
    format!("< 1e{}", x.log10().floor() as i32 + 1)
}
