//! The pointers' errors over many trials: Table 1 (ideal teeth) and Table 2 (Edmunds' Cases under
//! his radial-line model and with triangular teeth), each trial's statistics kept, with the
//! estimates (mean and 95 % interval over trials) drawn from them.

use serde::{Deserialize, Serialize};
use stats::{Estimate, mean_ci95};
use train::Ratio;

use crate::pointers::{BothModels, PointerTrial};

/// Table 1's results: σ, Dm and P of each pointer of the ideal mechanism, trial by trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IdealPointers {
    /// Clearance G of every mesh, % of the tooth height h.
    pub clearance: f64,
    /// Tooth height h of every gear, mm.
    pub tooth_height: f64,
    /// Trials (mechanisms run, each from fresh random initial angles).
    pub trials: usize,
    /// Each pointer, in the paper's column order.
    pub pointers: Vec<IdealPointer>,
}

/// One pointer of Table 1: its train, its run and every trial's statistics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IdealPointer {
    /// The pointer's name (`Lunar`, `Metonic`, ...).
    pub pointer: String,
    /// Run length, turns of the b arbor (the input).
    pub turns: f64,
    /// Theoretical Difference samples over the run.
    pub samples: usize,
    /// Meshes in the pointer's train.
    pub meshes: usize,
    /// Turns of the pointer per turn of b, exact (`None`: the gearing cannot give it).
    pub ratio: Option<Ratio>,
    /// Days shown by one degree of the pointer, from its exact ratio with 365.25 days per turn
    /// of b (`None`: a pointer whose degrees the paper does not convert to days).
    pub days_per_degree: Option<f64>,
    /// Each trial's σ, Dm and mean of the Theoretical Difference (degrees) and whether the
    /// pointer jammed, in trial order (a trial another shard ran reads as zeros).
    pub trials: Vec<PointerTrial>,
}

impl IdealPointer {
    /// σ of the Theoretical Difference, degrees: mean over trials with its 95 % interval.
    pub fn sigma(&self) -> Estimate {
        mean_ci95(&self.sigmas())
    }

    /// Dm, the largest |TD|, degrees: mean over trials with its 95 % interval.
    pub fn dm(&self) -> Estimate {
        mean_ci95(&self.dms())
    }

    /// P, the absolute value of the oscillation mean (Table 1's caption), degrees: mean over
    /// trials with its 95 % interval.
    pub fn p(&self) -> Estimate {
        mean_ci95(&self.ps())
    }

    /// Each trial's σ, degrees.
    pub fn sigmas(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.sigma).collect()
    }

    /// Each trial's Dm, degrees.
    pub fn dms(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.dm).collect()
    }

    /// Each trial's P (|mean TD|), degrees.
    pub fn ps(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.mean.abs()).collect()
    }

    /// Trials in which the pointer jammed (or could not run).
    pub fn jammed(&self) -> usize {
        self.trials.iter().filter(|t| t.stopped).count()
    }
}

/// Table 2's results: Edmunds' Cases A-D, each pointer's σ and Dm under his radial-line model
/// and with triangular teeth on the same manufactured gears, trial by trial.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CasePointers {
    /// Clearance G of every mesh with triangular teeth, % of the tooth height h.
    pub clearance: f64,
    /// Trials per Case (each with fresh errors and initial angles).
    pub trials: usize,
    /// Whether the Lunar train ran with the pin-and-slot (beyond the paper).
    pub pin_and_slot: bool,
    /// The pointers, in the table's column order, with the days one degree of each shows
    /// (`None` where the paper does not convert its degrees to days).
    pub pointers: Vec<(String, Option<f64>)>,
    /// Cases A-D, in order.
    pub cases: Vec<CaseRun>,
}

/// One Case of Table 2.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CaseRun {
    /// The Case's letter (`A`-`D`).
    pub case: String,
    /// Edmunds' systematic error amplitude, degrees.
    pub systematic: f64,
    /// Edmunds' random tooth error (sd), share of the pitch.
    pub random: f64,
    /// Each pointer's trials, in [`CasePointers::pointers`]' order.
    pub pointers: Vec<CasePointer>,
}

/// One pointer of one Case: every trial under both contact models.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CasePointer {
    /// The pointer's name.
    pub pointer: String,
    /// Each trial: σ and Dm (degrees) under Edmunds' model (through any jam) and with
    /// triangular teeth (up to the first jam), and whether the triangular teeth jammed.
    pub trials: Vec<BothModels>,
}

impl CasePointer {
    /// Edmunds' σ (radial-line model), degrees, each trial.
    pub fn edmunds_sigmas(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.edmunds_sigma).collect()
    }

    /// Edmunds' Dm, degrees, each trial.
    pub fn edmunds_dms(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.edmunds_dm).collect()
    }

    /// σ with triangular teeth, degrees, each trial.
    pub fn triangular_sigmas(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.triangular_sigma).collect()
    }

    /// Dm with triangular teeth, degrees, each trial.
    pub fn triangular_dms(&self) -> Vec<f64> {
        self.trials.iter().map(|t| t.triangular_dm).collect()
    }

    /// Edmunds' σ, degrees: mean over trials with its 95 % interval.
    pub fn edmunds_sigma(&self) -> Estimate {
        mean_ci95(&self.edmunds_sigmas())
    }

    /// Edmunds' Dm, degrees: mean over trials with its 95 % interval.
    pub fn edmunds_dm(&self) -> Estimate {
        mean_ci95(&self.edmunds_dms())
    }

    /// σ with triangular teeth, degrees: mean over trials with its 95 % interval.
    pub fn triangular_sigma(&self) -> Estimate {
        mean_ci95(&self.triangular_sigmas())
    }

    /// Dm with triangular teeth, degrees: mean over trials with its 95 % interval.
    pub fn triangular_dm(&self) -> Estimate {
        mean_ci95(&self.triangular_dms())
    }

    /// Triangular minus Edmunds' σ, degrees: the mean of the trial-by-trial differences with its
    /// 95 % interval (both models run on the same gears in each trial).
    pub fn sigma_difference(&self) -> Estimate {
        paired_difference(&self.triangular_sigmas(), &self.edmunds_sigmas())
    }

    /// Triangular minus Edmunds' Dm, degrees, as [`CasePointer::sigma_difference`].
    pub fn dm_difference(&self) -> Estimate {
        paired_difference(&self.triangular_dms(), &self.edmunds_dms())
    }

    /// Trials in which the triangular teeth jammed.
    pub fn jammed(&self) -> usize {
        self.trials.iter().filter(|t| t.jammed).count()
    }
}

/// The mean of the trial-by-trial differences `a - b`, with its 95 % interval.
fn paired_difference(a: &[f64], b: &[f64]) -> Estimate {
    mean_ci95(&a.iter().zip(b).map(|(x, y)| x - y).collect::<Vec<_>>())
}
