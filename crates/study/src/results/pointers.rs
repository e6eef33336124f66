//! The pointers' errors over many trials: Table 1 (ideal teeth), each trial's statistics kept,
//! with the estimates (mean and 95 % interval over trials) drawn from them.

use serde::{Deserialize, Serialize};
use stats::{Estimate, mean_ci95};
use train::Ratio;

use crate::pointers::PointerTrial;

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
