//! The display's pointers: each planet over a year and over its period relation, ideal teeth and
//! Edmunds' Cases A-D, its Theoretical Difference before its pin-and-slot device (the train
//! alone) and after it (what the pointer shows).

use super::*;

/// One planet of one display trial: its pointer before and after its device.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct PlanetTrial {
    /// The gear train alone (the slot gear rigid on its pin gear; the pin gear's own angle
    /// where a follower follows it): σ, Dm, P of its TD, degrees.
    pub train: PointerTrial,
    /// What the pointer shows, through its device, against the device's ideal output.
    pub display: PointerTrial,
    /// Day of the train's first jam within the run (None: it ran through).
    pub jam_day: Option<f64>,
}

/// The inputs of the display study: ideal teeth, then each Case asked for.
fn display_inputs(s: &Settings) -> Result<Vec<(String, Option<hypotheses::Params>)>, RunError> {
    let mut inputs = vec![("ideal".to_owned(), None)];
    for &ci in &s.cases {
        let (case, systematic, random) = CASES[ci];
        let p = s.errors.case_params((systematic, random))?;
        inputs.push((format!("Case {case}"), Some(p)));
    }
    Ok(inputs)
}

/// The mechanism of one trial: ideal, or every gear made under `params` from `rng` (in the
/// gearing's gear order), jams counted by the rule.
fn made(
    s: &Settings,
    shape: &crate::gearing::Shape,
    params: Option<&hypotheses::Params>,
    rng: &mut TrialRng,
) -> Result<Mechanism, RunError> {
    let (g, h) = (&shape.gearing, shape.tooth_height);
    let mech = match params {
        None => Mechanism::build(g, h, s.clearance, |_, gear| Ok(gear))
            .map_err(|e| crate::errors::unplaceable(&e))?,
        Some(p) => {
            crate::errors::made_mechanism((g, h, s.clearance), s.errors.hypothesis, |_| Ok(p), rng)?
        }
    };
    Ok(mech.with_rule(s.rule.clone()))
}

/// σ, Dm and P (degrees) of a follower's TD over `samples` input angles up to the run's first
/// jam: the follower's angle from the pin gear's actual angle less that from its ideal one, the
/// pin starting `phase` radians from the line of centres and turning the way `sign` says.
pub(super) fn follower_stats(
    run: &PointerRun,
    device: &train::PinDevice,
    sign: f64,
    phase: f64,
    samples: usize,
) -> stats::PointerStats {
    let end = run.first_stop().map_or(run.input_range, |s| s.input_angle);
    let n = samples.max(2);
    let f =
        |a: f64| pin_slot::follower_angle(phase + sign * a, device.axis_offset, device.pin_radius);
    let acc: stats::Accumulator = (0..n)
        .map(|i| {
            let psi = end * i as f64 / (n - 1) as f64;
            (f(run.pointer_angle(psi)) - f(run.ideal_angle(psi))).to_degrees()
        })
        .collect();
    acc.stats()
}

/// One planet of one trial on `mech` (its devices out) and `with` (in): the initial angles
/// drawn from `rng`, the same for both, then the follower's phase.
pub(super) fn planet_trial(
    (mech, with): (&Mechanism, &Mechanism),
    pointer: &str,
    turns: f64,
    samples: usize,
    rng: &mut TrialRng,
) -> Result<PlanetTrial, RunError> {
    let g = mech.gearing();
    let missing = || RunError::bad("gearing", format!("pointer {pointer}"), "is missing");
    let device = g.device(pointer);
    let slot = device.is_some_and(|d| d.kind == DeviceKind::SlotGear);
    let rigid = mech
        .run_pointer_to_first_jam(pointer, turns, &mut rng.clone())
        .ok_or_else(missing)?;
    let shown = if slot {
        with.run_pointer_to_first_jam(pointer, turns, rng)
            .ok_or_else(missing)?
    } else {
        // No mesh after a follower: the same run, the same draws taken from the stream.
        mech.run_pointer_to_first_jam(pointer, turns, rng)
            .ok_or_else(missing)?
    };
    let phase = rng.random::<f64>() * TAU;
    let stop = |r: &PointerRun| r.first_stop().map(|s| s.day);
    let train = PointerTrial::new(rigid.stats(samples), stop(&rigid).is_some());
    let display = match device {
        Some(d) if d.kind == DeviceKind::Follower => {
            let sign = device_rate(g, pointer).map_or(1.0, |r| r.to_f64().signum());
            follower_stats(&shown, d, sign, phase, samples)
        }
        _ => shown.stats(samples),
    };
    Ok(PlanetTrial {
        train,
        display: PointerTrial::new(display, stop(&shown).is_some()),
        jam_day: stop(&shown),
    })
}

/// One row of the display study: a planet under one input over one run length.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DisplayRow {
    /// The pointer.
    pub planet: String,
    /// `ideal` or `Case X`.
    pub input: String,
    /// Whether this is the run over the period relation (else over a year).
    pub period: bool,
    /// Years run (a year, or the period relation capped).
    pub years: f64,
    /// Trials.
    pub trials: u64,
    /// Trials whose train jammed within the run (statistics run up to the jam, as Table 2's).
    pub jammed: u64,
    /// σ of the gear train's TD alone, degrees.
    pub train_sigma: Interval,
    /// σ of what the pointer shows, degrees.
    pub sigma: Interval,
    /// Dm of what the pointer shows, degrees.
    pub dm: Interval,
    /// P, the mean of |mean| of what the pointer shows, degrees.
    pub p: Interval,
    /// σ shown / σ of the train: what the device multiplies the train's error by.
    #[serde(with = "registry::f64_bits")]
    pub gain: f64,
}

/// Rows of one input and run length: a batch of `trials` trials, each one mechanism on which
/// every planet runs in turn, trial t drawn from trial t of the input's [`Draws::Cosmos`]
/// (both run lengths of an input on the same gears, on purpose: a year and the period relation
/// compared on one set of mechanisms).
fn display_batch(
    engine: &TrialEngine,
    s: &Settings,
    shape: &crate::gearing::Shape,
    input: &(String, Option<hypotheses::Params>),
    period: bool,
) -> Result<Vec<DisplayRow>, RunError> {
    let g = &shape.gearing;
    let runs: Vec<(&str, f64, usize)> = cosmos_pointers(g)
        .into_iter()
        .map(|p| {
            let years = match (period, period_years(g, p)) {
                (true, Some(y)) => (y as f64).min(s.period_cap_years),
                _ => 1.0,
            };
            let samples = crate::pointers::samples_for(g, p, years, s.samples_per_engagement);
            (p, years, samples)
        })
        .collect();
    let key = format!(
        "cosmos display: gearing {}, {} {:?}, h = {} mm, G = {} %, events {}, runs {runs:?}, {} trials",
        shape.file,
        input.0,
        input.1.as_ref().map(|p| p.iter().collect::<Vec<_>>()),
        shape.tooth_height,
        s.clearance,
        s.rule.label(),
        s.display_trials,
    );
    let draws = Draws::Cosmos { input: &input.0 }.identity();
    let per_trial = engine.trials(&key, s.display_trials, |t| {
        let mut rng = engine.stream(draws, t);
        let mech = made(s, shape, input.1.as_ref(), &mut rng)?;
        let with = mech
            .clone()
            .with_pin_and_slot(true)
            .map_err(crate::gearing::mechanism_error)?;
        runs.iter()
            .map(|&(p, years, samples)| planet_trial((&mech, &with), p, years, samples, &mut rng))
            .collect::<Result<Vec<_>, _>>()
    })?;
    Ok(runs
        .iter()
        .enumerate()
        .map(|(k, &(p, years, _))| display_row(p, &input.0, (period, years), &per_trial, k))
        .collect())
}

/// The row of planet `k` from every trial's results.
fn display_row(
    planet: &str,
    input: &str,
    (period, years): (bool, f64),
    per_trial: &[Vec<PlanetTrial>],
    k: usize,
) -> DisplayRow {
    let col: Vec<&PlanetTrial> = per_trial.iter().filter_map(|t| t.get(k)).collect();
    let train_sigma = Interval::of_nonnegative(col.iter().map(|t| t.train.sigma));
    let sigma = Interval::of_nonnegative(col.iter().map(|t| t.display.sigma));
    DisplayRow {
        planet: planet.to_owned(),
        input: input.to_owned(),
        period,
        years,
        trials: col.len() as u64,
        jammed: col.iter().filter(|t| t.jam_day.is_some()).count() as u64,
        train_sigma,
        sigma,
        dm: Interval::of_nonnegative(col.iter().map(|t| t.display.dm)),
        p: Interval::of_nonnegative(col.iter().map(|t| t.display.mean.abs())),
        gain: sigma.mean / train_sigma.mean,
    }
}

/// The display study of one gearing: every planet, input and run length (a year, then the
/// period relation capped).
pub fn display_rows(
    engine: &TrialEngine,
    s: &Settings,
    shape: &crate::gearing::Shape,
) -> Result<Vec<DisplayRow>, RunError> {
    let inputs = display_inputs(s)?;
    let mut rows = Vec::new();
    for period in [false, true] {
        for input in &inputs {
            rows.extend(display_batch(engine, s, shape, input, period)?);
        }
    }
    Ok(rows)
}
