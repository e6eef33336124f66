//! The failure study's results (section 5's 30-run study, `failure`): per input (one of
//! Edmunds' Cases, or a measured table of per-gear errors) every run's first jam of each train,
//! and per train the share of runs jamming within a year with its interval, the days of the
//! first jams (mean with its interval, median) and the Kaplan-Meier curve of runs not yet jammed.
//!
//! Days are days of the b arbor (the solar pointer), 365.25 d per turn.

use serde::{Deserialize, Serialize};

use crate::whole_mechanism::{
    Input, Jam, MechanismRun, Summary, TRAINS, jam_of, mean_days, summarise, train_names,
};

/// The failure study: every input's runs and what they show.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FailureStudy {
    /// Horizon of every run, days of b.
    pub horizon: f64,
    /// Runs per input.
    pub runs_per_input: u64,
    /// The inputs in the order they ran: the Cases asked for, then the measured table if given.
    pub inputs: Vec<FailureInput>,
}

/// One input of the study: a Case or a measured table, its runs and their summary per train.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FailureInput {
    /// `A`-`D` (a Case) or `measured`.
    pub label: String,
    /// The input as the survival plots' legends name it (the Case with its errors, or
    /// `measured table FILE`).
    pub legend: String,
    /// Whether it is a measured table (the column compared with the paper's numbers) rather than
    /// one of Edmunds' Cases (shown for orientation).
    pub measured: bool,
    /// The hypothesis that made its gears.
    pub hypothesis: String,
    /// The hypothesis' parameter values (name, value in the parameter's own unit), by name.
    pub params: Vec<(String, f64)>,
    /// Every run, in trial order.
    pub runs: Vec<FailureRun>,
    /// Per train of [`TRAINS`] in their order, then the mechanism (a jam in any train).
    pub trains: Vec<TrainSummary>,
}

/// One whole-mechanism run of an input.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct FailureRun {
    /// Per train of [`TRAINS`], then the mechanism: the first jam within the horizon (its day of
    /// b and the mesh that jammed), `None` where the train ran to the horizon.
    pub first_jams: Vec<Option<Jam>>,
    /// Tooth engagements simulated: each mesh's driver turns times its teeth, summed over the
    /// meshes, up to the horizon or the mesh's first jam.
    pub engagements: f64,
    /// Where the gears could not be placed (bodies overlapping at every angle): the mesh and the
    /// rule; such a run counts as jammed at day 0.
    pub unplaceable: Option<String>,
    /// σ of the Lunar pointer's Theoretical Difference over the run up to its first jam,
    /// degrees (`None`: it jammed at once, or the gears could not be placed).
    pub lunar_sigma: Option<f64>,
}

/// What one input's runs show of one train (or of the mechanism).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TrainSummary {
    /// The train (`Lunar`, `Metonic/Games`, `Saros/Exeligmos`) or the mechanism row.
    pub train: String,
    /// Runs whose first jam came within one year of b, of every run, with the 95 %
    /// Clopper-Pearson interval.
    pub within_year: Share,
    /// Day of b of each first jam within the horizon, in trial order (runs without one left out).
    pub days: Vec<f64>,
    /// Mean of [`TrainSummary::days`] with its 95 % Student-t interval clipped to 0 .. horizon,
    /// days of b; `None` when no run jammed (the interval is the mean itself for one jam).
    pub mean_day: Option<MeanDay>,
    /// Median of [`TrainSummary::days`], days of b; `None` when no run jammed.
    pub median_day: Option<f64>,
    /// The meshes that jammed first, each with its runs, most frequent first (ties by name).
    pub first_meshes: Vec<(String, usize)>,
    /// The Kaplan-Meier curve of runs not yet jammed, from day 0 to the horizon: one step per
    /// day on which runs jammed.
    pub survival: Vec<SurvivalStep>,
}

/// A count of runs out of all, with its 95 % Clopper-Pearson interval.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Share {
    /// Runs counted (e.g. jammed within a year).
    pub k: u64,
    /// Runs in all.
    pub n: u64,
    /// Lower end of the interval of the share, a fraction from 0 to 1.
    pub lo: f64,
    /// Upper end of the interval of the share, a fraction from 0 to 1.
    pub hi: f64,
}

/// A mean day with its 95 % interval.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct MeanDay {
    /// The mean, days of b.
    pub mean: f64,
    /// Lower end of the interval, days of b (at least 0).
    pub lo: f64,
    /// Upper end of the interval, days of b (at most the horizon).
    pub hi: f64,
    /// Days averaged (runs that jammed within the horizon).
    pub n: usize,
}

/// One step of a Kaplan-Meier curve.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct SurvivalStep {
    /// The day of b the step starts.
    pub day: f64,
    /// Runs not yet jammed from that day on, % of all runs.
    pub survival: f64,
    /// Lower end of its 95 % (Clopper-Pearson) band, %.
    pub lo: f64,
    /// Upper end of its 95 % band, %.
    pub hi: f64,
}

impl Share {
    /// As `stats`' proportion, for its point estimate and printing.
    pub fn proportion(&self) -> stats::Proportion {
        stats::Proportion {
            k: self.k,
            n: self.n,
            lo: self.lo,
            hi: self.hi,
        }
    }
}

impl From<stats::Proportion> for Share {
    fn from(p: stats::Proportion) -> Share {
        Share {
            k: p.k,
            n: p.n,
            lo: p.lo,
            hi: p.hi,
        }
    }
}

impl SurvivalStep {
    /// As `stats`' step, for reading and drawing the curve.
    pub fn step(&self) -> stats::Step {
        stats::Step {
            day: self.day,
            survival: self.survival,
            lo: self.lo,
            hi: self.hi,
        }
    }
}

impl FailureRun {
    /// Run `o` as stored: each train's first jam within `horizon` days of b.
    pub fn of(o: &MechanismRun, horizon: f64) -> FailureRun {
        FailureRun {
            first_jams: (0..=TRAINS.len())
                .map(|ti| jam_of(o, ti).filter(|j| j.day <= horizon).cloned())
                .collect(),
            engagements: o.engagements,
            unplaceable: o.unplaceable.clone(),
            lunar_sigma: o.lunar_sigma,
        }
    }
}

impl TrainSummary {
    /// Train `ti` (`TRAINS.len()`: the mechanism) of `runs`, `summary` being its
    /// [`summarise`]d row.
    fn of(ti: usize, name: &str, summary: &Summary, runs: &[MechanismRun], horizon: f64) -> Self {
        let times: Vec<Option<f64>> = runs.iter().map(|o| jam_of(o, ti).map(|j| j.day)).collect();
        let mean_day = (!summary.days.is_empty()).then(|| {
            let e = mean_days(&summary.days, horizon);
            MeanDay {
                mean: e.mean,
                lo: e.lo,
                hi: e.hi,
                n: e.n,
            }
        });
        TrainSummary {
            train: name.to_owned(),
            within_year: summary.year.into(),
            days: summary.days.clone(),
            mean_day,
            median_day: stats::median(&summary.days),
            first_meshes: summary.meshes.clone(),
            survival: stats::kaplan_meier(&times, horizon)
                .into_iter()
                .map(|s| SurvivalStep {
                    day: s.day,
                    survival: s.survival,
                    lo: s.lo,
                    hi: s.hi,
                })
                .collect(),
        }
    }

    /// Every train of `runs` (runs to `horizon` days of b), then the mechanism.
    pub fn every_train(runs: &[MechanismRun], horizon: f64) -> Vec<TrainSummary> {
        summarise(runs, horizon)
            .iter()
            .zip(train_names())
            .enumerate()
            .map(|(ti, (s, name))| TrainSummary::of(ti, name, s, runs, horizon))
            .collect()
    }
}

impl FailureInput {
    /// Input `input`'s `runs` (to `horizon` days of b) as stored; `measured`: whether it is the
    /// measured table.
    pub fn new(
        input: &Input<'_>,
        measured: bool,
        runs: &[MechanismRun],
        horizon: f64,
    ) -> FailureInput {
        FailureInput {
            label: input.label.clone(),
            legend: input.legend.clone(),
            measured,
            hypothesis: input.hypothesis.name().to_owned(),
            params: input
                .params
                .iter()
                .map(|(k, v)| (k.to_owned(), v))
                .collect(),
            runs: runs.iter().map(|o| FailureRun::of(o, horizon)).collect(),
            trains: TrainSummary::every_train(runs, horizon),
        }
    }
}
