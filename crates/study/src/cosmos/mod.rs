//! The cosmos display, beyond the paper: the planetary gearing of Freeth et al. 2021 (and of
//! Freeth & Jones 2012) put through the paper's tests. Every cosmos mesh runs as an ordinary
//! pair in b1's frame (`train::Epicyclic`), so the per-mesh machinery of Tables 3-5 and the
//! whole-mechanism study apply as they are; what is new is the display.
//!
//! - [`outputs`]: each output's exact period relation, from the tooth counts, and its device.
//! - [`display_rows`]: each planet's pointer over a year and over its period relation, ideal
//!   triangular teeth and Edmunds' Cases A-D: σ, Dm and P of its Theoretical Difference before
//!   its pin-and-slot device (the gear train alone) and after it (what the pointer shows), so
//!   the error the device adds or removes is their ratio.
//! - [`mesh_tolerances`]: each cosmos mesh's largest tolerable random and systematic error by
//!   the paper's rule (Tables 4-5), in the paper's units, degrees and millimetres.
//! - [`failure`]: the 30-run study of whole mechanisms (the back and the cosmos), per train the
//!   first jam within a year, with Kaplan-Meier curves and their bands.
//! - [`compute`]: all of it for each gearing, and the 2021 display beside the 2012 one.

mod display;
mod plan;

use std::f64::consts::TAU;

use mechanism::{Mechanism, PointerRun, pin_slot};
use rand::Rng;
use registry::{RunError, TrialEngine, TrialRng};
use serde::{Deserialize, Serialize};
use train::{DeviceKind, Gearing, Rate};

use crate::cell::Purpose;
use crate::draws::Draws;
use crate::grids::{CASES, CellSettings};
use crate::pointers::PointerTrial;
use crate::whole_mechanism::{self, Clearances, Input, Study, TRAINS, Train};

pub use display::{DisplayRow, PlanetTrial, display_rows};
pub use plan::{PlannedArbor, PlannedGear, PlannedMesh, TrainPlan, plan};

/// The cosmos's trains in the failure study: one per pointer of the display (a gearing without
/// one, FJ12 without the nodes, leaves it out).
pub const COSMOS_TRAINS: [Train; 7] = [
    ("Mercury", &["Mercury"]),
    ("Venus", &["Venus"]),
    ("Sun", &["Sun"]),
    ("Mars", &["Mars"]),
    ("Jupiter", &["Jupiter"]),
    ("Saturn", &["Saturn"]),
    ("Nodes", &["Nodes"]),
];

/// Everything the cosmos study takes, read once by the experiment.
pub struct Settings {
    /// The gearings (each with its file as typed and h), in the order to report them.
    pub gearings: Vec<crate::gearing::Shape>,
    /// Clearance G of every mesh, % of h.
    pub clearance: f64,
    /// The error hypothesis (Edmunds' split model) the Cases are made with.
    pub errors: crate::errors::Settings,
    /// The event rule that counts a jam.
    pub rule: rules::Rule,
    /// Trials per (planet, input, run length) of the display study.
    pub display_trials: u64,
    /// The longest "period" run, years: each planet runs its period relation or this.
    pub period_cap_years: f64,
    /// TD samples per tooth engagement of the busiest mesh of a train.
    pub samples_per_engagement: usize,
    /// Trials per cell of the tolerance grids.
    pub cell_trials: u64,
    /// The random-error grid (fractions of the pitch) and the systematic grid (degrees).
    pub grids: (Vec<f64>, Vec<f64>),
    /// The tolerance rule, % of trials that may jam.
    pub rule_percent: f64,
    /// Whole-mechanism runs per Case.
    pub failure_runs: u64,
    /// Horizon of each whole-mechanism run, days of b.
    pub days: f64,
    /// Indices into [`CASES`] of the Cases run.
    pub cases: Vec<usize>,
}

/// A mean over trials with its 95 % Student-t interval.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Interval {
    /// The mean.
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
    /// Lower end.
    #[serde(with = "registry::f64_bits")]
    pub lo: f64,
    /// Upper end.
    #[serde(with = "registry::f64_bits")]
    pub hi: f64,
    /// Values it was made from.
    pub n: usize,
}

impl Interval {
    /// The mean of the finite `values` with its interval (NaN when there are none).
    pub fn of(values: impl Iterator<Item = f64>) -> Interval {
        let v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
        let e = stats::mean_ci95(&v);
        Interval {
            mean: e.mean,
            lo: e.lo,
            hi: e.hi,
            n: e.n,
        }
    }

    /// [`Interval::of`] for a quantity that cannot be negative (a σ, a Dm, a |P|): the
    /// Student-t interval's lower end clipped at 0, as few trials reach below it.
    pub fn of_nonnegative(values: impl Iterator<Item = f64>) -> Interval {
        let mut i = Interval::of(values);
        i.lo = i.lo.max(0.0);
        i
    }
}

/// One output of the display: its exact rates and its device.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Output {
    /// The pointer (or differential).
    pub name: String,
    /// The device: `follower`, `slot gear`, `differential` or `none`.
    pub device: String,
    /// The synodic (or the device's input) rate relative to b1, turns a year, exact.
    pub synodic: Option<String>,
    /// The pointer's mean rate in the frame of the mechanism, turns a year, exact.
    pub rate: String,
    /// Years of the period relation: the denominator of the rate that repeats.
    pub period_years: u64,
    /// The device's largest swing of the pointer from its mean (greatest elongation, or the
    /// equation of the anomaly), degrees.
    pub amplitude_deg: Option<f64>,
    /// Pin radius and axis offset, mm.
    pub pin_mm: Option<(f64, f64)>,
}

/// The rate of `pointer`'s device input (the pin gear) relative to b1, or of its arbor.
fn device_rate(g: &Gearing, pointer: &str) -> Option<Rate> {
    let arbor = match g.device(pointer) {
        Some(d) => g.arbor_of(&d.pin_gear)?,
        None => g.pointer_arbor(pointer)?,
    };
    g.relative_rate(arbor)
}

/// The display's pointers: those run in b1's frame, in file order.
pub fn cosmos_pointers(g: &Gearing) -> Vec<&str> {
    g.pointers()
        .iter()
        .map(|p| p.name.as_str())
        .filter(|p| g.is_epicyclic_pointer(p))
        .collect()
}

/// Years of `pointer`'s period relation: the denominator of its device's input rate relative to
/// b1 (a planet's synodic relation), or of its own rate where it has no device (the nodes).
pub fn period_years(g: &Gearing, pointer: &str) -> Option<u64> {
    let rate = match g.device(pointer) {
        Some(_) => device_rate(g, pointer)?,
        None => g.pointer_rate(pointer)?,
    };
    u64::try_from(rate.den).ok()
}

/// Every output of the display, then the differentials: rates exact, from the tooth counts.
pub fn outputs(g: &Gearing) -> Vec<Output> {
    let mut out: Vec<Output> = cosmos_pointers(g)
        .into_iter()
        .filter_map(|p| {
            let d = g.device(p);
            let (device, amplitude) = match d.map(|d| (d.kind, d.axis_offset, d.pin_radius)) {
                Some((DeviceKind::Follower, offset, pin)) => (
                    "follower",
                    Some(pin_slot::greatest_elongation(offset, pin).to_degrees()),
                ),
                Some((DeviceKind::SlotGear, offset, pin)) => (
                    "slot gear",
                    Some(pin_slot::anomaly_amplitude(offset, pin).to_degrees()),
                ),
                None => ("none", None),
            };
            // A follower swings about b1: its mean rate is b1's, one turn a year.
            let rate = match d.map(|d| d.kind) {
                Some(DeviceKind::Follower) => Rate::ONE,
                _ => g.pointer_rate(p)?,
            };
            Some(Output {
                name: p.to_owned(),
                device: device.to_owned(),
                synodic: d.and_then(|_| device_rate(g, p)).map(|r| r.to_string()),
                rate: rate.to_string(),
                period_years: period_years(g, p)?,
                amplitude_deg: amplitude,
                pin_mm: d.map(|d| (d.pin_radius, d.axis_offset)),
            })
        })
        .collect();
    for d in g.differentials() {
        if let Some(rate) = g.differential_rate(&d.name) {
            out.push(Output {
                name: d.name.clone(),
                device: "differential".into(),
                synodic: None,
                rate: rate.to_string(),
                period_years: u64::try_from(rate.den).unwrap_or(0),
                amplitude_deg: None,
                pin_mm: None,
            });
        }
    }
    out
}

/// One gear of a mesh: name, teeth and tip radius at the run's h (mm).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct MeshGear {
    /// Gear name.
    pub name: String,
    /// Teeth.
    pub teeth: u32,
    /// Tip radius, mm.
    pub tip_radius: f64,
}

/// One cosmos mesh's tolerances by the paper's rule, in its units, degrees and millimetres.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshTolerance {
    /// Mesh label.
    pub mesh: String,
    /// Its driver and driven gear.
    pub gears: (MeshGear, MeshGear),
    /// The display's pointers whose trains run through it.
    pub pointers: Vec<String>,
    /// The margin its source states over the pitch radii, mm.
    pub margin_mm: Option<f64>,
    /// Largest tolerable random error, fraction of the pitch (None: below the grid).
    pub random: Option<f64>,
    /// The same in degrees of each gear (driver, driven).
    pub random_deg: Option<(f64, f64)>,
    /// The same as tip displacement of each gear, mm.
    pub random_mm: Option<(f64, f64)>,
    /// Largest tolerable systematic amplitude on top of it, degrees (None: below the grid or not
    /// run).
    pub systematic: Option<f64>,
    /// The eccentricity that amplitude gives each gear's axis (the split's share), mm.
    pub eccentricity_mm: Option<(f64, f64)>,
    /// Table 3's cells of the mesh: each Case at the run's G.
    pub cases: Vec<CaseCount>,
}

/// One mesh under one of Edmunds' Cases, Table 3's protocol: trials with a jam, with a
/// disengagement, and whether the cell keeps the paper's rule.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseCount {
    /// `A`..`D`.
    pub case: String,
    /// Trials with at least one jam.
    pub jams: u64,
    /// Trials with at least one disengagement.
    pub disengagements: u64,
    /// Trials.
    pub trials: u64,
    /// At most the rule's share of trials jammed and at most as many disengaged.
    pub keeps: bool,
}

/// The display's meshes of `g`, in file order: those within the epicyclic system.
pub fn cosmos_meshes(g: &Gearing) -> Vec<String> {
    g.meshes()
        .iter()
        .filter(|m| g.arbor_of(&m.driver).is_some_and(|a| g.in_epicyclic(a)))
        .map(|m| m.label.clone())
        .collect()
}

/// Each cosmos mesh's tolerances (Tables 4-5's grids and rule, the cells through the shared
/// runner), with the totals of the cells run.
pub fn mesh_tolerances(
    engine: &TrialEngine,
    s: &Settings,
    shape: &crate::gearing::Shape,
) -> Result<(Vec<MeshTolerance>, stats_totals::Totals), RunError> {
    let cells = CellSettings {
        gearing: shape.clone(),
        clearance: Some(s.clearance),
        errors: s.errors.clone(),
        rule: s.rule.clone(),
        drive: crate::drive::Drive::Listed,
        end: crate::trial_end::End::Turn,
        trials: s.cell_trials,
    };
    let g = &shape.gearing;
    let meshes = cosmos_meshes(g);
    let t = crate::grids::derive_of(
        engine,
        &cells,
        meshes.clone(),
        s.grids.clone(),
        s.rule_percent,
        Purpose::Own,
        None,
    )?;
    let cases = case_counts(engine, s, &cells, &meshes)?;
    let totals = stats_totals::Totals::of(t.all().chain(cases.iter().flatten().map(|c| &c.1)));
    let split = s.errors.split()?;
    let h = shape.tooth_height;
    let rows = meshes
        .iter()
        .enumerate()
        .filter_map(|(m, label)| {
            let mesh = g.mesh(label)?;
            let gear = |name: &str| -> Option<MeshGear> {
                Some(MeshGear {
                    name: name.to_owned(),
                    teeth: g.gear(name)?.teeth,
                    tip_radius: g.tip_radius_at(name, h)?,
                })
            };
            let (a, b) = (gear(&mesh.driver)?, gear(&mesh.driven)?);
            let both = |f: &dyn Fn(&MeshGear) -> f64| (f(&a), f(&b));
            let random = t.random[m];
            let systematic = t.systematic[m];
            Some(MeshTolerance {
                mesh: label.clone(),
                pointers: pointers_through(g, label),
                margin_mm: mesh.margin,
                random,
                random_deg: random
                    .map(|e| both(&|x| crate::tolerance::random_error_deg(e, x.teeth))),
                random_mm: random.map(|e| {
                    both(&|x| crate::tolerance::random_error_mm(e, x.tip_radius, x.teeth))
                }),
                systematic,
                eccentricity_mm: systematic.map(|a_deg| {
                    both(&|x| {
                        crate::tolerance::systematic_eccentricity_mm(a_deg, split, x.tip_radius)
                    })
                }),
                gears: (a, b),
                cases: cases
                    .iter()
                    .map(|row| {
                        let (case, n) = (&row[m].0, row[m].1);
                        let allowed = crate::tolerance::allowed_jams(n.trials, s.rule_percent);
                        CaseCount {
                            case: case.clone(),
                            jams: n.jams,
                            disengagements: n.disengagements,
                            trials: n.trials,
                            keeps: n.jams <= allowed && n.disengagements <= allowed,
                        }
                    })
                    .collect(),
            })
        })
        .collect();
    Ok((rows, totals))
}

/// Table 3's cells of `meshes` (each Case asked for, at the run's G), through the shared runner:
/// `result[case][mesh]`, each with its Case's name.
fn case_counts(
    engine: &TrialEngine,
    s: &Settings,
    cells: &CellSettings,
    meshes: &[String],
) -> Result<Vec<Vec<(String, crate::cell::Counts)>>, RunError> {
    let mut specs = Vec::new();
    for &ci in &s.cases {
        let (_, systematic, random) = CASES[ci];
        let p = s.errors.case_params((systematic, random))?;
        specs.extend(meshes.iter().map(|m| cells.cell(m, p.clone(), s.clearance)));
    }
    let counts =
        crate::cell::run_cells(engine, cells.gearing(), &specs, s.cell_trials, Purpose::Own)?;
    Ok(s.cases
        .iter()
        .zip(counts.chunks(meshes.len().max(1)))
        .map(|(&ci, row)| row.iter().map(|c| (CASES[ci].0.to_owned(), *c)).collect())
        .collect())
}

/// The display's pointers whose trains run through mesh `label`.
fn pointers_through(g: &Gearing, label: &str) -> Vec<String> {
    cosmos_pointers(g)
        .into_iter()
        .filter(|p| {
            g.pointer(p)
                .is_some_and(|x| x.meshes.iter().any(|m| m == label))
        })
        .map(str::to_owned)
        .collect()
}

/// Totals of trials and tooth engagements, for the report.
pub mod stats_totals {
    use serde::{Deserialize, Serialize};

    /// Trials and tooth engagements run.
    #[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
    pub struct Totals {
        /// Trials.
        pub trials: u64,
        /// Tooth engagements.
        pub engagements: u64,
    }

    impl Totals {
        /// The totals of `cells`.
        pub fn of<'a>(cells: impl Iterator<Item = &'a crate::cell::Counts>) -> Totals {
            cells.fold(Totals::default(), |t, c| Totals {
                trials: t.trials + c.trials,
                engagements: t.engagements + c.engagements,
            })
        }
    }
}

/// One step of a Kaplan-Meier curve: from `day` on, `survival` % of the runs had no jam yet,
/// with the 95 % band.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Step {
    /// Day of b the step starts.
    pub day: f64,
    /// Runs not yet jammed, %.
    pub survival: f64,
    /// Lower end of the 95 % band, %.
    pub lo: f64,
    /// Upper end, %.
    pub hi: f64,
}

/// One train (or the whole mechanism) under one Case in the failure study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainSurvival {
    /// The train, or [`whole_mechanism::MECHANISM`].
    pub train: String,
    /// `Case X`.
    pub input: String,
    /// Runs jammed within the horizon.
    pub jammed: u64,
    /// Runs.
    pub runs: u64,
    /// The 95 % Clopper-Pearson interval of the share jammed.
    pub share: (f64, f64),
    /// Mean day of the first jam of the runs that jammed, with its interval.
    pub mean_day: Interval,
    /// Median day of those.
    pub median_day: Option<f64>,
    /// Meshes that jammed first, most often first.
    pub meshes: Vec<(String, usize)>,
    /// The Kaplan-Meier curve.
    pub curve: Vec<Step>,
}

/// The trains of `g`'s failure study: the paper's, then the display's it has.
pub fn trains_of(g: &Gearing) -> Vec<Train> {
    TRAINS
        .iter()
        .chain(COSMOS_TRAINS.iter())
        .filter(|(_, ps)| ps.iter().all(|p| g.pointer(p).is_some()))
        .copied()
        .collect()
}

/// The failure study of one gearing: `failure_runs` whole mechanisms per Case, the devices
/// left out as the paper leaves the lunar one out (a jam falls at the same driver angle; only
/// its day moves), per train (then the mechanism) the first jam within the horizon.
pub fn failure(
    engine: &TrialEngine,
    s: &Settings,
    shape: &crate::gearing::Shape,
) -> Result<(Vec<TrainSurvival>, stats_totals::Totals), RunError> {
    let (g, h) = (&shape.gearing, shape.tooth_height);
    let trains = trains_of(g);
    let clearances = Clearances::Uniform(s.clearance);
    whole_mechanism::check_trains(g, h, &clearances, &trains)?;
    let inputs = s
        .cases
        .iter()
        .map(|&ci| whole_mechanism::case_input(&s.errors, ci, clearances.clone()))
        .collect::<Result<Vec<Input<'_>>, _>>()?;
    let names: Vec<&str> = trains.iter().map(|t| t.0).collect();
    let key = format!(
        "{}, trains {names:?}",
        whole_mechanism::batch_key(&shape.file, &inputs, s.failure_runs, h, s.clearance, s.days)?
    );
    let study = Study {
        gearing: g,
        trains: &trains,
        h,
        days: s.days,
        events: &s.rule,
    };
    let runs = whole_mechanism::run_study_of(engine, &study, &inputs, s.failure_runs, &key)?;
    let totals = stats_totals::Totals {
        trials: runs.len() as u64,
        engagements: runs.iter().map(|o| o.engagements).sum::<f64>().round() as u64,
    };
    let mut rows = Vec::new();
    for (inp, chunk) in inputs
        .iter()
        .zip(runs.chunks(s.failure_runs.max(1) as usize))
    {
        let summaries = whole_mechanism::summarise_trains(chunk, s.days, trains.len());
        let labels = names
            .iter()
            .copied()
            .chain(std::iter::once(whole_mechanism::MECHANISM));
        for (ti, (name, sum)) in labels.zip(&summaries).enumerate() {
            let times: Vec<Option<f64>> = chunk
                .iter()
                .map(|o| {
                    whole_mechanism::jam_of_in(o, ti, trains.len())
                        .map(|j| j.day)
                        .filter(|d| *d <= s.days)
                })
                .collect();
            rows.push(TrainSurvival {
                train: name.to_owned(),
                input: format!("Case {}", inp.label),
                jammed: sum.days.len() as u64,
                runs: chunk.len() as u64,
                share: (sum.year.lo, sum.year.hi),
                mean_day: {
                    // Clipped to the days a jam can have, 0 to the horizon.
                    let e = whole_mechanism::mean_days(&sum.days, s.days);
                    Interval {
                        mean: e.mean,
                        lo: e.lo,
                        hi: e.hi,
                        n: e.n,
                    }
                },
                median_day: stats::median(&sum.days),
                meshes: sum.meshes.clone(),
                curve: stats::kaplan_meier(&times, s.days)
                    .into_iter()
                    .map(|k| Step {
                        day: k.day,
                        survival: k.survival,
                        lo: k.lo,
                        hi: k.hi,
                    })
                    .collect(),
            });
        }
    }
    Ok((rows, totals))
}

/// Everything the study found for one gearing.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GearingResults {
    /// The gearing as typed (an embedded name or a file).
    pub gearing: String,
    /// Its outputs' exact rates and devices.
    pub outputs: Vec<Output>,
    /// Its display study.
    pub display: Vec<DisplayRow>,
    /// Its cosmos meshes' tolerances, in file order.
    pub meshes: Vec<MeshTolerance>,
    /// Its failure study, train by train within each Case.
    pub failure: Vec<TrainSurvival>,
    /// Where its cosmos arbors stand, for the picture of the train.
    pub plan: TrainPlan,
}

impl GearingResults {
    /// The cosmos meshes from the least tolerant: smallest random tolerance first (below the
    /// grid before any value), then smallest systematic one.
    pub fn limiting(&self) -> Vec<&MeshTolerance> {
        let key = |x: Option<f64>| x.unwrap_or(f64::NEG_INFINITY);
        let mut v: Vec<&MeshTolerance> = self.meshes.iter().collect();
        v.sort_by(|a, b| {
            key(a.random)
                .total_cmp(&key(b.random))
                .then(key(a.systematic).total_cmp(&key(b.systematic)))
                .then(a.mesh.cmp(&b.mesh))
        });
        v
    }
}

/// A train of two gearings compared under one Case: jammed within the horizon, and Fisher's
/// exact two-sided p-value of the two counts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Comparison {
    /// The train (a planet, or the mechanism).
    pub train: String,
    /// `Case X`.
    pub input: String,
    /// (jammed, runs) of each gearing, in the settings' order.
    pub counts: Vec<(u64, u64)>,
    /// Fisher's exact two-sided p-value (the first two gearings).
    pub p_value: f64,
}

/// Every result of the study.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    /// Per gearing, in the settings' order.
    pub gearings: Vec<GearingResults>,
    /// The first two gearings' trains side by side, where both have them.
    pub compared: Vec<Comparison>,
    /// Trials and tooth engagements run (display trials counted as trials only).
    pub totals: stats_totals::Totals,
}

/// The first two gearings' failure studies train by train, where both have the train.
fn compare(gearings: &[GearingResults]) -> Vec<Comparison> {
    let [a, b, ..] = gearings else {
        return Vec::new();
    };
    a.failure
        .iter()
        .filter_map(|x| {
            let y = b
                .failure
                .iter()
                .find(|y| y.train == x.train && y.input == x.input)?;
            Some(Comparison {
                train: x.train.clone(),
                input: x.input.clone(),
                counts: vec![(x.jammed, x.runs), (y.jammed, y.runs)],
                p_value: stats::fisher_exact_two_sided(x.jammed, x.runs, y.jammed, y.runs),
            })
        })
        .collect()
}

/// The whole study: for each gearing its outputs, display study, mesh tolerances and failure
/// study; then the first two side by side.
pub fn compute(engine: &TrialEngine, s: &Settings) -> Result<Results, RunError> {
    let mut gearings = Vec::new();
    let mut totals = stats_totals::Totals::default();
    for shape in &s.gearings {
        let display = display_rows(engine, s, shape)?;
        let (meshes, cells) = mesh_tolerances(engine, s, shape)?;
        let (failure, runs) = failure(engine, s, shape)?;
        totals.trials += display.iter().map(|r| r.trials).sum::<u64>() + cells.trials + runs.trials;
        totals.engagements += cells.engagements + runs.engagements;
        gearings.push(GearingResults {
            gearing: shape.file.clone(),
            outputs: outputs(&shape.gearing),
            display,
            meshes,
            failure,
            plan: plan(
                &shape.gearing,
                s.clearance / 100.0 * shape.tooth_height,
                shape.tooth_height,
            ),
        });
    }
    Ok(Results {
        compared: compare(&gearings),
        gearings,
        totals,
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::display::{follower_stats, planet_trial};
    use super::*;
    use registry::Streams;

    #[test]
    fn outputs_carry_the_exact_period_relations() {
        let g = Gearing::builtin("freeth2021-cosmos").unwrap();
        let out = outputs(&g);
        let find = |n: &str| out.iter().find(|o| o.name == n).unwrap();
        assert_eq!(find("Venus").synodic.as_deref(), Some("289/462"));
        assert_eq!(find("Venus").period_years, 462);
        assert!((find("Venus").amplitude_deg.unwrap() - 46.0).abs() < 0.05);
        assert_eq!(find("Mars").rate, "151/284");
        assert_eq!(find("Nodes").rate, "-5/93");
        assert_eq!(find("Nodes").period_years, 93);
        assert_eq!(find("Moon phase").rate, "235/19");
        assert_eq!(find("Sun").synodic.as_deref(), Some("-1/1"));
        let j = Gearing::builtin("freeth2012-cosmos").unwrap();
        assert_eq!(period_years(&j, "Mercury"), Some(33));
        assert_eq!(cosmos_meshes(&j).len(), 10);
        assert_eq!(trains_of(&j).len(), 3 + 6);
        assert_eq!(trains_of(&g).len(), 3 + 7);
    }

    #[test]
    fn the_plan_puts_each_arbor_at_its_centre_distance() {
        let g = Gearing::builtin("freeth2021-cosmos").unwrap();
        let (h, clearance_mm) = (1.1, 0.44);
        let p = plan(&g, clearance_mm, h);
        // Every carried arbor and the fixed one are placed.
        assert_eq!(p.arbors.len(), 1 + g.epicyclic().unwrap().arbors.len());
        assert_eq!(p.arbors.iter().filter(|a| a.fixed).count(), 1);
        let at = |n: &str| p.arbors.iter().find(|a| a.name == n).unwrap();
        // Each arbor is its mesh's centre distance from the arbor that drives it.
        let (a, b) = (at("frame"), at("ve1"));
        let d = (a.x - b.x).hypot(a.y - b.y);
        let want = 0.25 * (51.0 + 44.0) + clearance_mm;
        assert!((d - want).abs() < 1e-9, "{d} vs {want}");
        // Every cosmos mesh is drawn, and no mesh of the back.
        let drawn: Vec<&str> = p.meshes.iter().map(|m| m.mesh.as_str()).collect();
        assert_eq!(drawn, cosmos_meshes(&g));
    }

    /// The ideal cosmos of `name` at h 1.1 mm, G 40 %: without and with its devices.
    fn ideal(name: &str) -> (Mechanism, Mechanism) {
        let g = Gearing::builtin(name).unwrap();
        let m = Mechanism::ideal(&g, 1.1, 40.0).unwrap();
        (m.clone(), m.with_pin_and_slot(true).unwrap())
    }

    #[test]
    fn a_follower_scales_the_trains_error_by_its_slope() {
        let (m, with) = ideal("freeth2021-cosmos");
        let d = m.gearing().device("Venus").unwrap().clone();
        // The follower's slope d(elongation)/d(pin angle) lies between d / (D + d) and
        // d / (D - d): Venus 0.42 to 2.57.
        let (lo, hi) = (
            d.pin_radius / (d.axis_offset + d.pin_radius),
            d.pin_radius / (d.axis_offset - d.pin_radius),
        );
        for t in 0..3 {
            let mut rng = Draws::Cosmos { input: "ideal" }.stream(Streams::new(5), t);
            let p = planet_trial((&m, &with), "Venus", 0.6, 4000, &mut rng).unwrap();
            assert!(p.jam_day.is_none());
            // The slope is taken over a finite error (a secant, not the tangent): 2 % slack.
            let ratio = p.display.dm / p.train.dm;
            assert!(
                ratio > 0.98 * lo && ratio < 1.02 * hi,
                "{ratio} outside {lo} .. {hi}"
            );
            assert!(p.train.sigma > 0.0 && p.display.sigma > 0.0);
        }
        // Sampled at the run's two ends only: the start has no error, the end's is scaled.
        let mut rng = Draws::Cosmos { input: "ideal" }.stream(Streams::new(5), 9);
        let run = m.run_pointer("Venus", 0.6, &mut rng).unwrap();
        let shown = follower_stats(&run, &d, 1.0, 0.3, 2);
        assert!(shown.dm <= 1.02 * hi * run.stats(2).dm, "{shown:?}");
    }

    #[test]
    fn a_slot_gear_runs_against_its_anomaly_bearing_ideal() {
        let (m, with) = ideal("freeth2021-cosmos");
        let d = m.gearing().device("Mars").unwrap().clone();
        let mut rng = Draws::Cosmos { input: "ideal" }.stream(Streams::new(3), 0);
        let p = planet_trial((&m, &with), "Mars", 0.5, 4000, &mut rng).unwrap();
        // Shown against the ideal with the anomaly (41 degrees of it): only the tooth play
        // is left, scaled by the slot's slope, R / (R + e) to R / (R - e).
        let (lo, hi) = (
            d.pin_radius / (d.pin_radius + d.axis_offset),
            d.pin_radius / (d.pin_radius - d.axis_offset),
        );
        assert!(p.display.dm < hi * p.train.dm + 0.05, "{p:?}");
        assert!(p.display.dm > lo * p.train.dm * 0.5, "{p:?}");
        assert!(p.display.dm < 2.0, "{p:?}");
        // The same draws: the device run is the rigid run's gears and initial angles.
        let mut again = Draws::Cosmos { input: "ideal" }.stream(Streams::new(3), 0);
        let q = planet_trial((&m, &with), "Mars", 0.5, 4000, &mut again).unwrap();
        assert_eq!(p.display.sigma.to_bits(), q.display.sigma.to_bits());
    }
}
