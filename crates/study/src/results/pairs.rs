//! One pair of gears at a time: Figure 5 (three splits of the systematic error, Edmunds' model
//! against triangular teeth), Figure IV (σ against the clearance G for ideal gears of every mesh,
//! with each pair's limits) and the clearance limits of one mesh (Appendix II).

use serde::{Deserialize, Serialize};

/// Figure 5's results: a pair of equal gears made with random and systematic errors, the
/// systematic error split three ways, each run under Edmunds' radial-line model and with
/// triangular teeth on the same gears from the same initial angle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SplitPairs {
    /// Teeth of each gear.
    pub teeth: usize,
    /// Tip radius R of both gears, mm.
    pub tip_radius: f64,
    /// Root radius r of both gears, mm.
    pub root_radius: f64,
    /// The hypothesis the gears were made with.
    pub hypothesis: String,
    /// The hypothesis' parameters as they ran, split aside (each split has its own), in its
    /// order, e.g. (`random`, 0.05 of the pitch), (`systematic`, 0.6 degrees).
    pub values: Vec<(String, f64)>,
    /// Driver angle of every sample from the initial angle, radians (one turn).
    pub driver_angles: Vec<f64>,
    /// The three splits, in the figure's order.
    pub splits: Vec<SplitRun>,
}

/// One split of Figure 5.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SplitRun {
    /// The split as the figure names it, e.g. `A: all eccentricity`.
    pub name: String,
    /// Share of the systematic error on the sinusoid of tip position (0: all eccentricity,
    /// 1: all sinusoid).
    pub sinusoid_share: f64,
    /// The Theoretical Difference under Edmunds' model at each of
    /// [`SplitPairs::driver_angles`], degrees.
    pub edmunds_td: Vec<f64>,
    /// The Theoretical Difference with triangular teeth at each driver angle, degrees.
    pub triangular_td: Vec<f64>,
    /// σ of [`SplitRun::edmunds_td`], degrees.
    pub edmunds_sigma: f64,
    /// σ of [`SplitRun::triangular_td`], degrees (meaningless where never driven).
    pub triangular_sigma: f64,
    /// No driver tooth reached the driven gear in the whole turn (triangular teeth).
    pub never_driven: bool,
    /// Jams in the turn with triangular teeth, as the event rule counts them.
    pub jams: usize,
    /// Disengagements in the turn with triangular teeth, as the event rule counts them.
    pub disengagements: usize,
}

impl SplitPairs {
    /// The largest and smallest σ with triangular teeth over the splits that were driven,
    /// degrees: how far the split moves the pointer's error (the paper's claim is that it does
    /// not, significantly). `None` when no split was driven.
    pub fn triangular_sigma_range(&self) -> Option<(f64, f64)> {
        let driven = self
            .splits
            .iter()
            .filter(|s| !s.never_driven)
            .map(|s| s.triangular_sigma);
        let lo = driven.clone().reduce(f64::min)?;
        let hi = driven.reduce(f64::max)?;
        Some((lo, hi))
    }
}

/// Figure IV's results: σ of each driven gear's Theoretical Difference against the clearance G,
/// for ideal gears of every mesh of the gearing, with each pair's limits.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SigmaAgainstClearance {
    /// Tooth height h of every gear, mm.
    pub tooth_height: f64,
    /// The clearances swept, % of h, in order.
    pub clearances: Vec<f64>,
    /// Every mesh, in the gearing's order.
    pub meshes: Vec<MeshSweep>,
}

/// One mesh of Figure IV.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MeshSweep {
    /// The mesh's label, driver-driven (e.g. `b2-c1`).
    pub mesh: String,
    /// σ of the driven gear's Theoretical Difference over one turn of the larger gear at each
    /// of [`SigmaAgainstClearance::clearances`], degrees; `None` where the turn jammed or
    /// disengaged, or the gears overlap at every tooth.
    pub sigma: Vec<Option<f64>>,
    /// The smallest G running a full turn without a jam, % of h (bisected to 0.01 % of h;
    /// `None`: not found).
    pub jam_limit: Option<f64>,
    /// The largest G running a full turn without a disengagement, % of h (`None`: not found).
    pub disengagement_limit: Option<f64>,
    /// The swept G with the smallest σ, % of h (`None`: no clearance ran clean).
    pub smallest_sigma_at: Option<f64>,
}

impl MeshSweep {
    /// The swept clearance (of `clearances`, the sweep's) with the smallest σ, % of h.
    pub fn smallest_sigma(clearances: &[f64], sigma: &[Option<f64>]) -> Option<f64> {
        clearances
            .iter()
            .zip(sigma)
            .filter_map(|(&g, s)| s.map(|s| (g, s)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(g, _)| g)
    }
}

/// The clearance limits of one mesh of ideal gears (Appendix II): a sweep of G over 0-100 % of
/// h, then each limit bisected between the swept values that bracket it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClearanceLimits {
    /// The mesh's label, driver-driven.
    pub mesh: String,
    /// Teeth of the driver and of the driven gear.
    pub teeth: (usize, usize),
    /// Tip radii R1 and R2, mm.
    pub tip_radii: (f64, f64),
    /// Tooth height h of both gears, mm.
    pub tooth_height: f64,
    /// The sweep, in order of G.
    pub sweep: Vec<ClearanceRun>,
    /// The smallest G running a full turn without a jam, % of h (bisected to 1e-4 % of h;
    /// `None`: not bracketed on the sweep).
    pub jam_limit: Option<f64>,
    /// The largest G running a full turn without a disengagement, % of h (`None`: not
    /// bracketed on the sweep).
    pub disengagement_limit: Option<f64>,
}

/// One clearance of the sweep of [`ClearanceLimits`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ClearanceRun {
    /// Clearance G, % of h.
    pub clearance: f64,
    /// Centre distance D at that clearance, mm.
    pub centre_distance: f64,
    /// The turn's events and Theoretical Difference; `None` where the gears overlap at every
    /// tooth (no run).
    pub run: Option<TurnRun>,
}

/// One turn of the larger gear of an ideal pair.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TurnRun {
    /// Jams, as the event rule counts them.
    pub jams: usize,
    /// Disengagements, as the event rule counts them.
    pub disengagements: usize,
    /// σ of the driven gear's Theoretical Difference, degrees.
    pub sigma: f64,
    /// Dm, the largest |TD|, degrees.
    pub dm: f64,
}
