//! The Lunar pointer without and with the pin-and-slot (`lunar-anomaly`): the same gears and
//! initial angles run both ways, trial by trial, on table2's streams (a Case's
//! [`Draws::Case`], trial), so that without the pin-and-slot a Case's trials are table2's
//! triangular ones.

use hypotheses::{Hypothesis, Params};
pub use mechanism::PinSlotTrain;
use mechanism::{Mechanism, PointerRun};
use registry::{RunError, Streams, TrialEngine, TrialRng};
use serde::{Deserialize, Serialize};
use train::Gearing;

use crate::draws::Draws;

/// TD statistics of one run, as table1 and table2 keep them. NaN (a run that stopped at once)
/// cannot go through JSON: stored as bits.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct RunStats {
    /// σ of the Theoretical Difference up to the first jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Dm up to the first jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub dm: f64,
    /// |P|, the absolute oscillation mean.
    #[serde(with = "registry::f64_bits")]
    pub p: f64,
    /// The run jammed.
    pub jammed: bool,
}

impl RunStats {
    fn of(run: &PointerRun, samples: usize) -> RunStats {
        let s = run.stats(samples);
        RunStats {
            sigma: s.sigma,
            dm: s.dm,
            p: s.mean.abs(),
            jammed: run.first_stop().is_some(),
        }
    }
}

/// One trial of one row: the same gears and initial angles without and with the pin-and-slot.
/// The default (another shard's trial, see `TrialEngine::trials`) reads as zeros.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct AnomalyTrial {
    /// Without the pin-and-slot.
    pub rigid: RunStats,
    /// With it, against the anomaly-bearing ideal.
    pub pin_slot: RunStats,
}

/// The mechanisms of the study: the gearing at h and G, its file as typed (named if it has no
/// pin-and-slot), the hypothesis, the event rule, and each row's draws with its parameters
/// (`None`: ideal teeth).
pub struct Rows<'a> {
    /// The gearing.
    pub gearing: &'a Gearing,
    /// The gearing as typed.
    pub file: &'a str,
    /// Tooth height h (mm) of every gear.
    pub tooth_height: f64,
    /// Clearance G (% of h) of every mesh.
    pub clearance: f64,
    /// The hypothesis the rows' gears are made with.
    pub hypothesis: &'a dyn Hypothesis,
    /// The event rule that stops the pointer.
    pub rule: &'a rules::Rule,
    /// Each row: what its trials draw (a Case's [`Draws::Case`], as table2's; ideal teeth
    /// [`Draws::IdealMechanism`]) and its parameters (`None`: ideal teeth).
    pub rows: Vec<(Draws<'a>, Option<Params>)>,
}

impl Rows<'_> {
    /// The ideal mechanism, jams counted by the rule.
    fn ideal(&self) -> Result<Mechanism, RunError> {
        let mech = Mechanism::ideal(self.gearing, self.tooth_height, self.clearance)
            .map_err(crate::gearing::mechanism_error)?;
        Ok(mech.with_rule(self.rule.clone()))
    }

    /// `mech` with the pin-and-slot in.
    fn pinned(&self, mech: Mechanism) -> Result<Mechanism, RunError> {
        crate::gearing::with_pin_and_slot(self.file, mech, true)
    }

    /// The pin-and-slot train of `pointer`, from the ideal gears; a gearing without a
    /// pin-and-slot, or a pointer whose train does not run through the pin gear, is refused.
    pub fn train(&self, pointer: &str) -> Result<PinSlotTrain, RunError> {
        let ideal_on = self.pinned(self.ideal()?)?;
        ideal_on.pin_slot_for(pointer).ok_or_else(|| {
            RunError::bad(
                self.file,
                "pin_and_slot",
                format!("the {pointer} pointer's train does not run through the pin gear"),
            )
        })
    }

    /// Trial `t` of row `ri`: its mechanism (without the pin-and-slot) and the RNG left ready
    /// for the initial angles.
    fn build(
        &self,
        ideal: &Mechanism,
        streams: Streams,
        ri: usize,
        t: u64,
    ) -> Result<(Mechanism, TrialRng), RunError> {
        let Some((draws, params)) = self.rows.get(ri) else {
            return Err(RunError::Internal(format!("row {ri}")));
        };
        // One stream per (row, trial): errors first, then initial angles (table2's order).
        let mut rng = draws.stream(streams, t);
        let Some(p) = params else {
            return Ok((ideal.clone(), rng));
        };
        let mech = crate::errors::made_mechanism(
            (self.gearing, self.tooth_height, self.clearance),
            self.hypothesis,
            |_| Ok(p),
            &mut rng,
        )?;
        Ok((mech.with_rule(self.rule.clone()), rng))
    }

    /// `trials` trials of every row (row-major, in trial order, as the batch `key` of
    /// [`TrialEngine::trials`]): `pointer` over `turns` input turns to its first jam without and
    /// with the pin-and-slot, from the same initial angles, `samples` TD samples each.
    pub fn trials(
        &self,
        engine: &TrialEngine,
        key: &str,
        pointer: &str,
        (turns, samples): (f64, usize),
        trials: u64,
    ) -> Result<Vec<AnomalyTrial>, RunError> {
        let ideal = self.ideal()?;
        engine.trials(key, self.rows.len() as u64 * trials, |j| {
            let (ri, t) = ((j / trials) as usize, j % trials);
            let (mech, rng) = self.build(&ideal, engine.streams(), ri, t)?;
            let on = self.pinned(mech.clone())?;
            // The same gears and initial angles for both, on purpose: a paired comparison of
            // the train without and with the pin-and-slot.
            let missing = || RunError::bad("gearing", format!("pointer {pointer}"), "is missing");
            let rigid = mech
                .run_pointer_to_first_jam(pointer, turns, &mut rng.clone())
                .ok_or_else(missing)?;
            let pinned = on
                .run_pointer_to_first_jam(pointer, turns, &mut rng.clone())
                .ok_or_else(missing)?;
            Ok(AnomalyTrial {
                rigid: RunStats::of(&rigid, samples),
                pin_slot: RunStats::of(&pinned, samples),
            })
        })
    }

    /// Trial `t` of row `ri` with the pin-and-slot: `pointer` over `turns` input turns, to its
    /// first jam.
    pub fn trajectory(
        &self,
        seed: u64,
        (ri, t): (usize, u64),
        pointer: &str,
        turns: f64,
    ) -> Result<PointerRun, RunError> {
        let (mech, rng) = self.build(&self.ideal()?, Streams::new(seed), ri, t)?;
        let on = self.pinned(mech)?;
        on.run_pointer_to_first_jam(pointer, turns, &mut rng.clone())
            .ok_or_else(|| RunError::bad("gearing", format!("pointer {pointer}"), "is missing"))
    }
}
