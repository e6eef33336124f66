//! Pointer runs: each pointer's run length (in turns of b) and how finely its Theoretical
//! Difference is sampled, checked against the gearing.

use std::collections::BTreeMap;
use std::f64::consts::TAU;

use hypotheses::{Hypothesis, Params};
use mechanism::{Mechanism, Model};
use registry::{Param, RunError, Streams, TrialEngine};
use serde::{Deserialize, Serialize};
use train::Gearing;

use crate::draws::Draws;

/// The shortest run a `*_turns` parameter may ask for, in turns of b: 0.05 turn is 11 tooth
/// engagements of b1's mesh, about the fewest a σ of the pointer's error can be read from (at
/// 10^-300 turns every sample is at the same angle and σ is 0).
pub const MIN_TURNS: f64 = 0.05;

/// The values a `*_turns` parameter takes.
pub const TURNS_KIND: registry::Kind = registry::Kind::number(
    MIN_TURNS,
    100.0,
    "turns of b: a shorter run spans too few tooth engagements for a sigma",
);

/// A pointer's run length in turns of b: parameter `name` with `default` and `help`.
pub const fn turns(name: &'static str, default: &'static str, help: &'static str) -> Param {
    Param {
        name,
        default,
        unit: "turns of b",
        help,
        kind: TURNS_KIND,
        reading: false,
        clearance: false,
        recorded: false,
    }
}

/// How finely the Theoretical Difference is sampled, `samples_per_engagement`, with `default`
/// and `help`.
pub const fn per_engagement(default: &'static str, help: &'static str) -> Param {
    Param {
        name: "samples_per_engagement",
        default,
        unit: "",
        help,
        kind: registry::Kind::count(
            registry::MIN_PER_ENGAGEMENT,
            registry::MAX_COUNT as u64,
            registry::MIN_PER_ENGAGEMENT_WHY,
        ),
        reading: false,
        clearance: false,
        recorded: false,
    }
}

/// How finely the Theoretical Difference is sampled (table1 and table6).
pub const SAMPLES_PER_ENGAGEMENT: Param =
    per_engagement("16", "TD samples per tooth engagement of the busiest mesh");

/// Run length of the Lunar pointer.
pub const LUNAR_TURNS: Param = turns(
    "lunar_turns",
    "1",
    "run length, Lunar (Table 1 caption: one turn of b2)",
);

/// Run length of the Metonic pointer.
pub const METONIC_TURNS: Param = turns(
    "metonic_turns",
    "3.8",
    "run length, Metonic (caption: 3.8 turns)",
);

/// Run length of the Saros pointer.
pub const SAROS_TURNS: Param = turns(
    "saros_turns",
    "4.5",
    "run length, Saros (caption: 4.5 turns)",
);

/// Run length of the Games pointer.
pub const GAMES_TURNS: Param = turns(
    "games_turns",
    "3.8",
    "run length, Games (caption silent: as Metonic)",
);

/// Run length of the Exeligmos pointer.
pub const EXELIGMOS_TURNS: Param = turns(
    "exeligmos_turns",
    "4.5",
    "run length, Exeligmos (caption silent: as Saros)",
);

/// The five pointers' run lengths and the TD sampling (Tables 1 and 6).
pub const RUN_LENGTHS: &[Param] = &[
    LUNAR_TURNS,
    METONIC_TURNS,
    SAROS_TURNS,
    GAMES_TURNS,
    EXELIGMOS_TURNS,
    SAMPLES_PER_ENGAGEMENT,
];

/// The five pointers' run lengths and the TD sampling as typed ([`RUN_LENGTHS`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct RunLengths {
    /// Lunar pointer, turns of b ([`LUNAR_TURNS`]).
    #[param(LUNAR_TURNS)]
    pub lunar_turns: f64,
    /// Metonic pointer ([`METONIC_TURNS`]).
    #[param(METONIC_TURNS)]
    pub metonic_turns: f64,
    /// Saros pointer ([`SAROS_TURNS`]).
    #[param(SAROS_TURNS)]
    pub saros_turns: f64,
    /// Games pointer ([`GAMES_TURNS`]).
    #[param(GAMES_TURNS)]
    pub games_turns: f64,
    /// Exeligmos pointer ([`EXELIGMOS_TURNS`]).
    #[param(EXELIGMOS_TURNS)]
    pub exeligmos_turns: f64,
    /// TD samples per tooth engagement of the busiest mesh ([`SAMPLES_PER_ENGAGEMENT`]).
    #[param(SAMPLES_PER_ENGAGEMENT)]
    pub samples_per_engagement: usize,
}

impl RunLengths {
    /// (pointer, input turns) for each pointer of [`POINTERS`], in its order.
    pub fn turns(&self) -> Vec<(&'static str, f64)> {
        let turns = [
            self.lunar_turns,
            self.metonic_turns,
            self.saros_turns,
            self.games_turns,
            self.exeligmos_turns,
        ];
        POINTERS.iter().map(|&(name, _)| name).zip(turns).collect()
    }
}

/// Pointers in the paper's column order, with the parameter holding each run length.
pub const POINTERS: [(&str, &Param); 5] = [
    ("Lunar", &LUNAR_TURNS),
    ("Metonic", &METONIC_TURNS),
    ("Saros", &SAROS_TURNS),
    ("Games", &GAMES_TURNS),
    ("Exeligmos", &EXELIGMOS_TURNS),
];

/// A table's header over the five pointers, in the paper's column order (Tables 1 and 6).
pub const COLUMNS: [&str; 6] = [
    "",
    "Lunar",
    "Metonic",
    "Eclipse (Saros)",
    "Games",
    "Exeligmos",
];

/// (pointer, input turns, TD samples) for each (pointer, input turns), checked.
pub fn pointer_runs<'a>(
    g: &train::Gearing,
    pointers: &[(&'a str, f64)],
    per: usize,
) -> Result<Vec<(&'a str, f64, usize)>, RunError> {
    let mut runs = Vec::new();
    for &(name, turns) in pointers {
        if g.pointer(name).is_none() {
            return Err(RunError::bad(
                "gearing",
                format!("pointer {name}"),
                "is missing from the gearing",
            ));
        }
        runs.push((name, turns, samples_for(g, name, turns, per)));
    }
    Ok(runs)
}

/// Samples needed so that the busiest mesh of a pointer's train gets `per` samples per tooth
/// engagement over `turns` input turns.
pub fn samples_for(g: &train::Gearing, pointer: &str, turns: f64, per: usize) -> usize {
    let mut arbor_turns = 1.0;
    let mut busiest: f64 = 1.0;
    for label in g
        .pointer(pointer)
        .map(|p| p.meshes.clone())
        .unwrap_or_default()
    {
        let (Some(m), Some(r)) = (g.mesh(&label), g.mesh_ratio(&label)) else {
            continue;
        };
        let teeth = g.gear(&m.driver).map_or(1.0, |x| f64::from(x.teeth));
        busiest = busiest.max(arbor_turns * teeth);
        arbor_turns *= r.to_f64();
    }
    ((busiest * turns * per as f64).ceil() as usize).max(100)
}

/// One pointer's run of one trial: its σ, Dm and mean, and whether it stopped. A pointer that
/// could not run has NaN statistics, which JSON cannot carry: they are recorded as bits.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PointerTrial {
    /// σ of the Theoretical Difference (degrees).
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Dm, the largest deviation from the mean (degrees).
    #[serde(with = "registry::f64_bits")]
    pub dm: f64,
    /// Mean of the Theoretical Difference (degrees).
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
    /// The run jammed (or could not run).
    pub stopped: bool,
}

impl PointerTrial {
    /// A run's statistics, and whether it stopped.
    pub fn new(s: stats::PointerStats, stopped: bool) -> Self {
        PointerTrial {
            sigma: s.sigma,
            dm: s.dm,
            mean: s.mean,
            stopped,
        }
    }
}

/// The ideal mechanism of the gearing at its h and G, stopping where `rule` counts a jam.
pub fn ideal_mechanism(
    s: &crate::gearing::Settings,
    rule: &rules::Rule,
) -> Result<Mechanism, RunError> {
    let mech = Mechanism::ideal(&s.gearing, s.tooth_height, s.clearance)
        .map_err(crate::gearing::mechanism_error)?;
    Ok(mech.with_rule(rule.clone()))
}

/// Table 1's trials: `trials` runs of the ideal mechanism `mech`, each from random initial
/// angles drawn from its own stream (trial t of [`Draws::IdealMechanism`]), every pointer of
/// `runs` (pointer, input turns, samples) in turn on that stream; in trial order, whatever the
/// threads, as the batch `key` of [`TrialEngine::trials`].
pub fn ideal_trials(
    engine: &TrialEngine,
    key: &str,
    mech: &Mechanism,
    runs: &[(&str, f64, usize)],
    trials: u64,
) -> Result<Vec<Vec<PointerTrial>>, RunError> {
    engine.trials(key, trials, |t| {
        let mut rng = engine.stream(Draws::IdealMechanism.identity(), t);
        Ok(runs
            .iter()
            .map(
                |&(name, turns, samples)| match mech.run_pointer(name, turns, &mut rng) {
                    Some(r) => PointerTrial::new(r.stats(samples), r.first_stop().is_some()),
                    None => PointerTrial::new(stats::PointerStats::NAN, true),
                },
            )
            .collect())
    })
}

/// One pointer of one trial run to its first jam (statistics up to it), as [`TrialEngine::trials`]
/// records it (for shards and their merge); NaN statistics (a run that stops at once) are
/// recorded as bits.
#[derive(Debug, Clone, Copy, Default, Serialize, Deserialize)]
pub struct ToFirstJam {
    /// σ of the Theoretical Difference up to the jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub sigma: f64,
    /// Dm up to the jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub dm: f64,
    /// Mean up to the jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub mean: f64,
    /// The pointer jammed.
    pub jammed: bool,
    /// Tooth engagements of the pointer's train up to the jam.
    pub engaged: u64,
}

/// The mechanism and its errors, as [`tolerated_trials`] builds it: the gearing at h and G, each
/// gear made under the hypothesis with its own parameters (by gear name), jams counted by the
/// rule.
pub struct Manufactured<'a> {
    /// The gearing.
    pub gearing: &'a Gearing,
    /// Tooth height h (mm) of every gear.
    pub tooth_height: f64,
    /// Clearance G (% of h) of every mesh.
    pub clearance: f64,
    /// The hypothesis every gear is made with.
    pub hypothesis: &'a dyn Hypothesis,
    /// Each gear's parameters; a gear without is an internal error.
    pub params: &'a BTreeMap<String, Params>,
    /// The event rule that stops a pointer.
    pub rule: &'a rules::Rule,
}

/// Table 6's trials: `trials` mechanisms as `m` makes them, each from its own stream (trial t
/// of [`Draws::Tolerated`]: every gear's errors, then the initial angles), every pointer of `runs`
/// (pointer, input turns, samples) run to its first jam; in trial order, whatever the threads,
/// as the batch `key` of [`TrialEngine::trials`].
pub fn tolerated_trials(
    engine: &TrialEngine,
    key: &str,
    m: &Manufactured<'_>,
    runs: &[(&str, f64, usize)],
    trials: u64,
) -> Result<Vec<Vec<ToFirstJam>>, RunError> {
    engine.trials(key, trials, |t| {
        // One stream per trial: every gear's errors, then the initial angles.
        let mut rng = engine.stream(Draws::Tolerated.identity(), t);
        let mech = crate::errors::made_mechanism(
            (m.gearing, m.tooth_height, m.clearance),
            m.hypothesis,
            |name| {
                m.params
                    .get(name)
                    .ok_or_else(|| format!("gear {name} has no tolerance"))
            },
            &mut rng,
        )?
        .with_rule(m.rule.clone());
        let mut out = Vec::new();
        for &(name, turns, samples) in runs {
            let Some(run) = mech.run_pointer_to_first_jam(name, turns, &mut rng) else {
                return Err(RunError::bad(
                    "gearing",
                    format!("pointer {name}"),
                    "is missing",
                ));
            };
            // A jam stops the pointer: statistics up to it (as table2 does).
            let stop = run.first_stop();
            let end = stop.as_ref().map_or(run.input_range, |s| s.input_angle);
            let engaged: f64 = run
                .stages
                .iter()
                .enumerate()
                .map(|(i, s)| {
                    let teeth = mech.mesh(&s.label).map_or(0, |m| m.driver().teeth());
                    run.arbor_angle(end, i).abs() / TAU * teeth as f64
                })
                .sum();
            let s = run.stats(samples);
            out.push(ToFirstJam {
                sigma: s.sigma,
                dm: s.dm,
                mean: s.mean,
                jammed: stop.is_some(),
                engaged: engaged.round() as u64,
            });
        }
        Ok(out)
    })
}

/// One pointer of one trial under both contact models, as [`TrialEngine::trials`] records it;
/// NaN statistics are recorded as bits.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct BothModels {
    /// σ under Edmunds' radial-line model, through any jams (degrees).
    #[serde(with = "registry::f64_bits")]
    pub edmunds_sigma: f64,
    /// Dm under Edmunds' model (degrees).
    #[serde(with = "registry::f64_bits")]
    pub edmunds_dm: f64,
    /// σ with triangular teeth, up to the first jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub triangular_sigma: f64,
    /// Dm with triangular teeth, up to the first jam (degrees).
    #[serde(with = "registry::f64_bits")]
    pub triangular_dm: f64,
    /// The triangular teeth jammed.
    pub jammed: bool,
}

/// A Case's mechanism as [`both_model_trials`] builds it: the gearing at h and G, every gear
/// made under the hypothesis with one set of parameters, jams counted by the rule, the
/// pin-and-slot in or out.
pub struct CaseMechanism<'a> {
    /// The gearing, and its file as typed (named if it lacks the pin-and-slot).
    pub gearing: (&'a Gearing, &'a str),
    /// Tooth height h (mm) of every gear.
    pub tooth_height: f64,
    /// Clearance G (% of h) of every mesh.
    pub clearance: f64,
    /// The hypothesis every gear is made with, and its parameters.
    pub errors: (&'a dyn Hypothesis, &'a Params),
    /// The event rule that stops a pointer.
    pub rule: &'a rules::Rule,
    /// Whether the Lunar train includes the pin-and-slot.
    pub pin_and_slot: bool,
}

/// Table 2's trials of one Case: `trials` mechanisms as `m` makes them, trial t from trial t
/// of the Case's stream `draws` ([`Draws::Case`]: the gears' errors, then the initial angles),
/// every pointer of `runs` run from the same initial angles under Edmunds' model and with
/// triangular teeth; in trial order, whatever the threads, as the batch `key` of
/// [`TrialEngine::trials`].
pub fn both_model_trials(
    engine: &TrialEngine,
    key: &str,
    draws: Draws<'_>,
    m: &CaseMechanism<'_>,
    runs: &[(&str, f64, usize)],
    trials: u64,
) -> Result<Vec<Vec<BothModels>>, RunError> {
    let ((g, file), (hyp, p)) = (m.gearing, m.errors);
    let identity = draws.identity();
    engine.trials(key, trials, |t| {
        // One stream per (case, trial): errors first, then initial angles.
        let mut rng = engine.stream(identity, t);
        let mech = crate::errors::made_mechanism(
            (g, m.tooth_height, m.clearance),
            hyp,
            |_| Ok(p),
            &mut rng,
        )?;
        let mech = crate::gearing::with_pin_and_slot(
            file,
            mech.with_rule(m.rule.clone()),
            m.pin_and_slot,
        )?;
        let mut out = Vec::new();
        for &(name, turns, samples) in runs {
            // The same initial angles for both models, on purpose: a paired comparison of the
            // two contact models on the same gears.
            let mut rng_edmunds = rng.clone();
            let edm = mech.run_pointer_with(name, turns, &mut rng_edmunds, Model::Edmunds);
            let tri = mech.run_pointer_to_first_jam(name, turns, &mut rng);
            let (Some(edm), Some(tri)) = (edm, tri) else {
                return Err(RunError::bad(
                    "gearing",
                    format!("pointer {name}"),
                    "is missing",
                ));
            };
            // A jam stops the pointer: triangular statistics run up to it.
            let (se, st) = (edm.stats_through_jams(samples), tri.stats(samples));
            out.push(BothModels {
                edmunds_sigma: se.sigma,
                edmunds_dm: se.dm,
                triangular_sigma: st.sigma,
                triangular_dm: st.dm,
                jammed: tri.first_stop().is_some(),
            });
        }
        Ok(out)
    })
}

/// One instance of the ideal mechanism `mech` (Figure 4): each of `pointers` run over `turns`
/// input turns in turn, all on the one stream of trial `trial` of [`Draws::IdealMechanism`]
/// (Table 1's trial; each pointer's initial angles drawn after the previous pointer's); `None`
/// for a pointer the gearing lacks.
pub fn instance(
    mech: &Mechanism,
    pointers: &[&str],
    turns: f64,
    seed: u64,
    trial: u64,
) -> Vec<Option<mechanism::PointerRun>> {
    let mut rng = Draws::IdealMechanism.stream(Streams::new(seed), trial);
    pointers
        .iter()
        .map(|name| mech.run_pointer(name, turns, &mut rng))
        .collect()
}
