//! The paper's jam protocol for one mesh on its own: each trial draws both gears' errors and an
//! initial angle, runs one full turn of the gear with more teeth, and notes whether it jammed and
//! whether it disengaged at least once.
//!
//! [`run_cells`] is the one place where such pair trials run (Tables 3, 4, 5, I and the
//! tolerances of Table 6 and Figure 6 all go through it). A trial's random stream is named by
//! the *content* of its cell (mesh, hypothesis, parameter values, h, G: [`Draws::Cell`]) and the
//! trial index, never by the cell's position in a table, so the same cell gives the same counts
//! in every experiment; a process-wide cache, keyed by a [`CellKey`], then lets an experiment
//! reuse cells another one has run (`cargo xtask run all`), with the same bits as running them
//! again.

use std::cell::Cell;
use std::collections::{HashMap, HashSet};
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::sync::{Mutex, OnceLock};

use contact::{Mesh, Solve, Start};
use geometry::Gear;
use hypotheses::{Hypothesis, Params};
use rand::Rng;
use registry::{Identity, RunError, Streams, TrialEngine, TrialMode, fmt_f64, fnv1a64};
use stats::{Proportion, wilson95};
use train::Gearing;

use crate::draws::Draws;
use crate::drive::{Drive, Driver};
use crate::errors;
use crate::gearing::GearingId;
use crate::trial_end::{End, Tally};

/// Trials per cell in the paper's Tables 3, 4, 5 and I: its counts are out of this.
pub const PAPER_TRIALS: u64 = 200;

/// One mesh under one set of errors: what a cell of Tables 3-5 and I needs.
#[derive(Clone)]
pub struct CellSpec {
    /// Mesh label.
    pub mesh: String,
    /// Error hypothesis.
    pub hypothesis: &'static dyn Hypothesis,
    /// Parameters of the hypothesis (every declared one has a value).
    pub params: Params,
    /// Tooth height h (mm).
    pub tooth_height: f64,
    /// Clearance G (% of h).
    pub clearance: f64,
    /// Which events count as jams and disengagements. Not part of [`CellSpec::canonical`]: the
    /// same gears and initial angles are counted under every rule.
    pub events: rules::Rule,
    /// Which gear drives. Not part of [`CellSpec::canonical`] either: the same gears and
    /// initial share of a pitch are run whichever gear drives.
    pub drive: Drive,
    /// Where a trial's counting ends (not part of [`CellSpec::canonical`]: a way of counting).
    pub end: End,
}

impl CellSpec {
    /// The cell's content as one line of text, e.g.
    /// `mesh=b2-c1;hypothesis=edmunds-split;random=0.04;split=0.5;systematic=0.0;h=1.1;G=40.0`:
    /// parameters sorted by name, numbers in Rust's shortest round-trip form (so two cells have
    /// the same text exactly when they hold the same values). It names the cell's random streams
    /// and its cache entry.
    pub fn canonical(&self) -> String {
        let mut s = format!("mesh={};hypothesis={}", self.mesh, self.hypothesis.name());
        for (k, v) in self.params.iter() {
            let _ = write!(s, ";{k}={v:?}");
        }
        let _ = write!(s, ";h={:?};G={:?}", self.tooth_height, self.clearance);
        s
    }
}

/// What the trials of one cell gave.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Counts {
    /// Trials with at least one jam.
    pub jams: u64,
    /// Trials with at least one disengagement.
    pub disengagements: u64,
    /// Trials with at least one jam or at least one disengagement (either failure).
    pub failures: u64,
    /// Trials run.
    pub trials: u64,
    /// Tooth engagements the trials stand for: each trial turns the gear with more teeth once
    /// (its run ends earlier once every rule has seen a jam and a disengagement, so fewer may be
    /// simulated).
    pub engagements: u64,
}

impl std::ops::AddAssign for Counts {
    /// Adds the counts of more trials of the same cell (another range of trial indices).
    fn add_assign(&mut self, more: Counts) {
        self.jams += more.jams;
        self.disengagements += more.disengagements;
        self.failures += more.failures;
        self.trials += more.trials;
        self.engagements += more.engagements;
    }
}

impl Counts {
    /// 95 % Wilson interval of the jam count.
    pub fn jam_interval(&self) -> Proportion {
        wilson95(self.jams, self.trials)
    }

    /// 95 % Wilson interval of the disengagement count.
    pub fn dis_interval(&self) -> Proportion {
        wilson95(self.disengagements, self.trials)
    }
}

/// A cell checked and sized, ready for its trials.
struct Prepared<'a> {
    spec: &'a CellSpec,
    canonical: String,
    /// The identity of the cell's streams ([`Draws::Cell`]).
    identity: Identity,
    driver_name: String,
    driven_name: String,
    driver: Gear,
    driven: Gear,
    centre_distance: f64,
    larger_teeth: u64,
}

fn prepare<'a>(g: &Gearing, spec: &'a CellSpec) -> Result<Prepared<'a>, RunError> {
    let m = g.mesh(&spec.mesh).ok_or_else(|| {
        RunError::bad(
            "--set",
            "mesh",
            format!("no mesh `{}` in the gearing", spec.mesh),
        )
    })?;
    let geo = g
        .mesh_geometry(&spec.mesh, spec.tooth_height, spec.clearance)
        .ok_or_else(|| {
            RunError::bad("gearing", format!("mesh {}", spec.mesh), "cannot be sized")
        })?;
    let ideal = |name: &str| {
        g.ideal_gear(name, spec.tooth_height)
            .ok_or_else(|| {
                RunError::bad("gearing", format!("mesh {}", spec.mesh), "cannot be sized")
            })?
            .map_err(|e| RunError::bad("gearing", format!("mesh {}", spec.mesh), e.to_string()))
    };
    let (driver, driven) = (ideal(&m.driver)?, ideal(&m.driven)?);
    let larger = geo.driver_teeth.max(geo.driven_teeth);
    let canonical = spec.canonical();
    Ok(Prepared {
        spec,
        identity: Draws::Cell(&canonical).identity(),
        canonical,
        driver_name: m.driver.clone(),
        driven_name: m.driven.clone(),
        driver,
        driven,
        centre_distance: geo.centre_distance,
        larger_teeth: u64::from(larger),
    })
}

/// Trial `t` of a cell rebuilt from its stream, as every table ran it.
pub struct Rebuilt {
    /// The meshed gears (with their errors), the gear that drove first, or `None` when their
    /// bodies would overlap at every angle (a large eccentricity at a small clearance): they
    /// cannot turn, which is a jam. With the other gear driving this is
    /// [`Mesh::other_driving`] of the listed mesh: each gear seen from its other face.
    pub mesh: Option<Mesh>,
    /// The driving gear's initial angle φ0 (radians).
    pub phi0: f64,
    /// The driving gear's rotation in the trial: one full turn of the gear with more teeth.
    pub turn: f64,
    /// Which gear of the mesh drove the trial.
    pub driver: Driver,
}

impl Rebuilt {
    /// The trial's events (none for gears that cannot turn: see [`Rebuilt::mesh`]).
    pub fn events(&self) -> Vec<contact::Event> {
        self.mesh.as_ref().map_or_else(Vec::new, |mesh| {
            mesh.solve(
                self.phi0..=self.phi0 + self.turn,
                Start::Touching(0.0),
                Solve::events(),
            )
        })
    }
}

/// Rebuilds trial `t` of `cell` under `seed` exactly as the tables ran it: the same stream (named
/// by the cell's content and `t`), both gears' errors, then the initial angle. `trial` is built
/// on it, so a replayed trial cannot drift from the one a table counted.
///
/// Errors: a mesh missing from the gearing; a gear the hypothesis cannot manufacture.
pub fn rebuild(g: &Gearing, cell: &CellSpec, seed: u64, t: u64) -> Result<Rebuilt, RunError> {
    rebuild_prepared(&prepare(g, cell)?, seed, t)
}

/// Checks `cell` as every command that runs or names it does, before any trial runs: its mesh
/// is in the gearing and can be sized, and the hypothesis manufactures both gears of trial 0
/// under `seed` (its parameters' ranges, e.g. a random error above 0.1 of the pitch). `run`
/// ([`run_cells`]) and `replay` share it, so a cell one refuses the other refuses too.
///
/// Errors: those of [`rebuild`].
pub fn check(g: &Gearing, cell: &CellSpec, seed: u64) -> Result<(), RunError> {
    rebuild(g, cell, seed, 0).map(|_| ())
}

/// What trial `t` of a cell draws from its stream, in order: both gears' errors (listed driver
/// first), the initial angle as a share of a turn (the driving gear starts at that share of its
/// own pitch), and the coin that picks the driver under [`Drive::Either`]. The coin is drawn
/// last, so every other draw is the same whichever gear drives.
pub struct Drawn {
    driver: Gear,
    driven: Gear,
    /// A uniform draw times 2π: the driving gear starts at this over its tooth count.
    start: f64,
    coin: Driver,
    centre_distance: f64,
    larger_teeth: u64,
}

/// Trial `t` of `cell` under `seed` as drawn, before a driver is chosen: every counting of the
/// trial, whichever gear drives, starts from these draws ([`Drawn::driven_by`]).
///
/// Errors: those of [`rebuild`].
pub fn draw_trial(g: &Gearing, cell: &CellSpec, seed: u64, t: u64) -> Result<Drawn, RunError> {
    draw(&prepare(g, cell)?, seed, t)
}

fn draw(p: &Prepared<'_>, seed: u64, t: u64) -> Result<Drawn, RunError> {
    // One stream per (cell content, trial).
    let mut rng = Streams::new(seed).stream(p.identity, t);
    let spec = p.spec;
    let driver = errors::make(
        spec.hypothesis,
        &p.driver,
        &p.driver_name,
        &spec.params,
        &mut rng,
    )?;
    let driven = errors::make(
        spec.hypothesis,
        &p.driven,
        &p.driven_name,
        &spec.params,
        &mut rng,
    )?;
    let start = rng.random::<f64>() * TAU;
    let coin = if rng.random::<bool>() {
        Driver::Other
    } else {
        Driver::Listed
    };
    Ok(Drawn {
        driver,
        driven,
        start,
        coin,
        centre_distance: p.centre_distance,
        larger_teeth: p.larger_teeth,
    })
}

impl Drawn {
    /// The gear the trial's coin picks under [`Drive::Either`].
    pub fn coin(&self) -> Driver {
        self.coin
    }

    /// The trial with `driver` driving: the mesh as that gear drives it, its initial angle and
    /// its rotation for one turn of the larger gear.
    pub fn driven_by(&self, driver: Driver) -> Rebuilt {
        let listed = Mesh::new(
            self.driver.clone(),
            self.driven.clone(),
            self.centre_distance,
        )
        .ok();
        let (mesh, teeth) = match driver {
            Driver::Listed => (listed, self.driver.teeth() as f64),
            Driver::Other => (
                listed.and_then(|m| m.other_driving().ok()),
                self.driven.teeth() as f64,
            ),
        };
        Rebuilt {
            mesh,
            phi0: self.start / teeth,
            turn: TAU * self.larger_teeth as f64 / teeth,
            driver,
        }
    }
}

fn rebuild_prepared(p: &Prepared<'_>, seed: u64, t: u64) -> Result<Rebuilt, RunError> {
    let drawn = draw(p, seed, t)?;
    Ok(drawn.driven_by(p.spec.drive.driver(drawn.coin)))
}

/// How a table counts a cell's trials: which events count as jams and disengagements (the
/// rule), which gear drives, and where a trial's counting ends.
#[derive(Debug, Clone, PartialEq)]
pub struct Counting {
    /// The event rule.
    pub rule: rules::Rule,
    /// Which gear drives.
    pub drive: Drive,
    /// Where a trial's counting ends.
    pub end: End,
}

impl Counting {
    /// The counting a cell names itself: its own rule, drive and end.
    pub fn of(cell: &CellSpec) -> Counting {
        Counting {
            rule: cell.events.clone(),
            drive: cell.drive,
            end: cell.end,
        }
    }

    /// `tally` after `events`, in order, as this counting counts them.
    pub fn tally_on(&self, tally: Tally, events: &[contact::Event]) -> Tally {
        events.iter().fold(tally, |t, e| {
            t.after(self.end, self.rule.is_jam(e), self.rule.is_disengagement(e))
        })
    }

    /// (jammed, disengaged) in a trial with these events, as this counting counts them.
    pub fn tally(&self, events: &[contact::Event]) -> (bool, bool) {
        let t = self.tally_on(Tally::default(), events);
        (t.jam, t.disengaged)
    }

    /// The cache key's part for this counting.
    fn key(&self) -> String {
        let end = match self.end {
            End::Turn => String::new(),
            e => format!("|end={}", e.name()),
        };
        format!(
            "events={}|drive={}{end}",
            self.rule.label(),
            self.drive.name()
        )
    }
}

/// One trial of cell `p`, counted under every counting of `countings` (at most [`MAX_RULES`]):
/// bit `2r` of the result is "jammed at least once under counting r", bit `2r + 1` "disengaged
/// at least once". The gears do not depend on the countings: each gear that drives under some
/// counting runs once, and every counting it drives under is counted on that run.
fn trial(
    p: &Prepared<'_>,
    seed: u64,
    t: u64,
    countings: &[Counting],
) -> Result<RuleBits, RunError> {
    let draws = draw(p, seed, t)?;
    let mut bits = 0;
    for driver in Driver::BOTH {
        let under: Vec<usize> = (0..countings.len())
            .filter(|&r| countings[r].drive.driver(draws.coin) == driver)
            .collect();
        if under.is_empty() {
            continue;
        }
        let mine: Vec<&Counting> = under.iter().map(|&r| &countings[r]).collect();
        let run = draws.driven_by(driver);
        let tallies = match run.mesh.as_ref() {
            Some(mesh) => tallies_to_answer(mesh, &run, &mine).0,
            // Gears that overlap at every tooth are jammed under any counting.
            None => vec![Tally::default().after(End::Turn, true, false); mine.len()],
        };
        for (&r, t) in under.iter().zip(&tallies) {
            bits |= (u64::from(t.jam) | u64::from(t.disengaged) << 1) << (2 * r);
        }
    }
    Ok(bits)
}

/// Each counting's tally of a trial: the events of its whole turn (the run keeps no segments),
/// but the run ends once every counting's tally is closed (a turn's once it has seen a jam and
/// a disengagement; a first event's at its first), as later events cannot change it. The
/// tallies are kept as the events are sized, each event counted once.
fn tallies_to_answer(
    mesh: &Mesh,
    rebuilt: &Rebuilt,
    countings: &[&Counting],
) -> (Vec<Tally>, Vec<contact::Event>) {
    let (tallies, counted) = (
        std::cell::RefCell::new(vec![Tally::default(); countings.len()]),
        Cell::new(0),
    );
    let gather = |events: &[contact::Event]| {
        let new = &events[counted.get()..];
        let mut all = tallies.borrow_mut();
        for (t, c) in all.iter_mut().zip(countings) {
            *t = c.tally_on(*t, new);
        }
        counted.set(events.len());
        all.iter().all(|t| t.closed)
    };
    let (phi0, end) = (rebuilt.phi0, rebuilt.phi0 + rebuilt.turn);
    let events = mesh.solve(
        phi0..=end,
        Start::Touching(0.0),
        Solve::events().until_answered(&gather),
    );
    // Events sized after the last call (if any) are counted too.
    let mut all = tallies.into_inner();
    let rest = &events[counted.get().min(events.len())..];
    for (t, c) in all.iter_mut().zip(countings) {
        *t = c.tally_on(*t, rest);
    }
    (all, events)
}

/// One trial of a flat batch under several countings: see [`trial`].
type RuleBits = u64;

/// Most countings (rule and drive) one batch counts under (two bits each in a `RuleBits`).
pub const MAX_RULES: usize = 32;

/// Counting `r`'s (jammed, disengaged) in a [`RuleBits`].
fn under(o: RuleBits, r: usize) -> (bool, bool) {
    (o >> (2 * r) & 1 == 1, o >> (2 * r + 1) & 1 == 1)
}

/// What a cell's counts depend on, and so what the cache holds them under: the cell's content
/// (which names its streams), how its trials are counted, the seed, the trial count and the
/// gearing.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct CellKey {
    /// The cell's canonical text ([`CellSpec::canonical`]).
    pub cell: String,
    /// The counting's part ([`Counting`]: rule, drive, end).
    pub counting: String,
    /// The run's seed.
    pub seed: u64,
    /// Trials of the cell.
    pub trials: u64,
    /// The gearing the cell's mesh is taken from.
    pub gearing: GearingId,
}

impl std::fmt::Display for CellKey {
    /// The key as one line, the text a batch of cells is named by (hashed).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let CellKey {
            cell,
            counting,
            seed,
            trials,
            gearing,
        } = self;
        write!(
            f,
            "{cell}|{counting}|seed={seed}|trials={trials}|gearing={gearing:016x}"
        )
    }
}

/// Counts of every cell run in this process, by cache key (see [`run_cells`]).
fn cache() -> &'static Mutex<HashMap<CellKey, Counts>> {
    static CACHE: OnceLock<Mutex<HashMap<CellKey, Counts>>> = OnceLock::new();
    CACHE.get_or_init(|| Mutex::new(HashMap::new()))
}

/// What a set of cells is to the experiment that runs them: its own result, or an input from
/// which later cells are derived (Table 4's grid inside Table 5, Table 5's inside Table 6).
///
/// Under `--shard K/N` an experiment's own cells are split between the shards; its inputs are
/// computed whole by every shard ([`TrialEngine::trials_whole`]), because the cells derived from them
/// must be the same in every shard.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// The experiment's own result (sharded).
    Own,
    /// An input to cells run later in the same experiment (never sharded).
    Input,
}

/// Empties the cache of cell counts.
pub fn forget_cache() {
    cache().lock().unwrap_or_else(|e| e.into_inner()).clear();
}

/// Runs `trials` trials of every cell and returns each cell's counts, in the order of `cells`.
///
/// Every (cell, trial) job runs in one flat parallel batch through [`TrialEngine::trials`] (or
/// [`TrialEngine::trials_whole`] for a [`Purpose::Input`]) and is collected in order, so the counts
/// do not depend on the thread count, and a run split into shards and merged gives the same
/// counts. Trial `t` of a cell draws from the stream of ([`Draws::Cell`]`(cell.canonical())`,
/// `t`): the same cell gives the same counts in any experiment. Counts are cached for the life
/// of the process under a [`CellKey`] (the cell's canonical text, the counting, the seed, the
/// trial count and the gearing's identity),
/// so a cell another experiment has already run (Table 5 reusing Table 4, Table I's G = 40 % rows
/// reusing Table 3) costs nothing and gives the same bits; a shard's partial counts are never
/// cached. [`Counts::engagements`] is counted whether or not the cell came from the cache, so a
/// report does not depend on what ran before it.
///
/// Errors: `trials == 0`; a mesh missing from the gearing; a gear the hypothesis cannot
/// manufacture (the first such trial in cell and trial order).
pub fn run_cells(
    engine: &TrialEngine,
    g: &Gearing,
    cells: &[CellSpec],
    trials: u64,
    purpose: Purpose,
) -> Result<Vec<Counts>, RunError> {
    let per_rule = run_cells_counted(engine, g, cells, None, trials, purpose)?;
    Ok(per_rule.into_iter().map(|mut c| c.swap_remove(0)).collect())
}

/// [`run_cells`] counted under each of `countings` at once (the cells' own rule and drive are
/// then ignored; `None`: each cell's own): `result[cell][counting]`. Each gear that drives
/// under some counting runs each trial once, whatever the number of rules, and every (cell,
/// counting) count is cached, so an experiment run afterwards under one of the countings finds
/// its cells already run.
///
/// More than [`MAX_RULES`] countings are counted [`MAX_RULES`] at a time, each batch running
/// the trials again.
///
/// Errors: those of [`run_cells`]; an empty list of countings.
pub fn run_cells_counted(
    engine: &TrialEngine,
    g: &Gearing,
    cells: &[CellSpec],
    countings: Option<&[Counting]>,
    trials: u64,
    purpose: Purpose,
) -> Result<Vec<Vec<Counts>>, RunError> {
    if let Some(all) = countings.filter(|c| c.len() > MAX_RULES) {
        let mut out: Vec<Vec<Counts>> = vec![Vec::new(); cells.len()];
        for chunk in all.chunks(MAX_RULES) {
            let part = run_cells_counted(engine, g, cells, Some(chunk), trials, purpose)?;
            for (o, p) in out.iter_mut().zip(part) {
                o.extend(p);
            }
        }
        return Ok(out);
    }
    let whole = purpose == Purpose::Input;
    let partial = matches!(engine.mode(), TrialMode::Shard(_)) && !whole;
    let batch = |key: &str, n, f: &(dyn Fn(u64) -> Result<RuleBits, RunError> + Sync + Send)| {
        if whole {
            engine.trials_whole(key, n, f)
        } else {
            engine.trials(key, n, f)
        }
    };
    run_cells_under(g, cells, countings, trials, engine.seed(), !partial, batch)
}

/// A batch runner: `run_batch(key, n, f)` returns `f(t)` for t in 0..n in order.
trait RunBatch:
    FnOnce(
    &str,
    u64,
    &(dyn Fn(u64) -> Result<RuleBits, RunError> + Sync + Send),
) -> Result<Vec<RuleBits>, RunError>
{
}

impl<F> RunBatch for F where
    F: FnOnce(
        &str,
        u64,
        &(dyn Fn(u64) -> Result<RuleBits, RunError> + Sync + Send),
    ) -> Result<Vec<RuleBits>, RunError>
{
}

/// [`run_cells`] with the batch runner and the use of the cache given.
#[cfg(test)]
fn run_cells_with(
    g: &Gearing,
    cells: &[CellSpec],
    trials: u64,
    seed: u64,
    use_cache: bool,
    run_batch: impl RunBatch,
) -> Result<Vec<Counts>, RunError> {
    let per_rule = run_cells_under(g, cells, None, trials, seed, use_cache, run_batch)?;
    Ok(per_rule.into_iter().map(|mut c| c.swap_remove(0)).collect())
}

/// [`run_cells_counted`] with the batch runner and the use of the cache given.
fn run_cells_under(
    g: &Gearing,
    cells: &[CellSpec],
    countings: Option<&[Counting]>,
    trials: u64,
    seed: u64,
    use_cache: bool,
    run_batch: impl RunBatch,
) -> Result<Vec<Vec<Counts>>, RunError> {
    if trials == 0 {
        return Err(RunError::bad("--set", "trials", "must be at least 1"));
    }
    if countings.is_some_and(|r| r.is_empty() || r.len() > MAX_RULES) {
        return Err(RunError::Internal(format!(
            "cells are counted under 1 to {MAX_RULES} countings at once"
        )));
    }
    let prepared: Vec<Prepared<'_>> = cells
        .iter()
        .map(|c| prepare(g, c))
        .collect::<Result<_, _>>()?;
    // Every cell checked before any runs, as `replay` checks the one it names ([`check`]).
    for p in &prepared {
        rebuild_prepared(p, seed, 0)?;
    }
    let countings_of: Vec<Vec<Counting>> = cells
        .iter()
        .map(|c| countings.map_or_else(|| vec![Counting::of(c)], <[_]>::to_vec))
        .collect();
    let keys = cache_keys(GearingId::of(g)?, &prepared, &countings_of, trials, seed);
    let mut known: HashMap<CellKey, Counts> = HashMap::new();
    if use_cache {
        let cached = cache().lock().unwrap_or_else(|e| e.into_inner());
        for k in keys.iter().flatten() {
            if let Some(c) = cached.get(k) {
                known.insert(k.clone(), *c);
            }
        }
    }
    // Cells with a count still missing, each once even if listed twice (same keys).
    let mut todo: Vec<usize> = Vec::new();
    let mut queued: HashSet<&[CellKey]> = HashSet::new();
    for (i, ks) in keys.iter().enumerate() {
        let missing = ks.iter().any(|k| !known.contains_key(k));
        if missing && queued.insert(ks) {
            todo.push(i);
        }
    }
    let outcomes = run_todo(
        &prepared,
        &countings_of,
        &keys,
        &todo,
        trials,
        seed,
        run_batch,
    )?;
    count_outcomes(&prepared, &keys, &todo, &outcomes, trials, &mut known);
    if use_cache {
        let mut cached = cache().lock().unwrap_or_else(|e| e.into_inner());
        for &i in &todo {
            for k in &keys[i] {
                if let Some(c) = known.get(k) {
                    cached.insert(k.clone(), *c);
                }
            }
        }
    }
    keys.iter()
        .map(|ks| {
            ks.iter()
                .map(|k| {
                    known
                        .get(k)
                        .copied()
                        .ok_or_else(|| RunError::Internal(format!("cell {k} was not run")))
                })
                .collect()
        })
        .collect()
}

/// One key per (cell, counting) of `prepared` under `countings_of`: what the cache holds, naming
/// the cell, the counting, the seed, the trials and the gearing.
fn cache_keys(
    gearing: GearingId,
    prepared: &[Prepared<'_>],
    countings_of: &[Vec<Counting>],
    trials: u64,
    seed: u64,
) -> Vec<Vec<CellKey>> {
    prepared
        .iter()
        .zip(countings_of)
        .map(|(p, cs)| {
            cs.iter()
                .map(|c| CellKey {
                    cell: p.canonical.clone(),
                    counting: c.key(),
                    seed,
                    trials,
                    gearing,
                })
                .collect()
        })
        .collect()
}

/// The counts of the cells `todo` from their trials' `outcomes` (in (cell, trial) order), one
/// per counting, put in `known` under their keys.
fn count_outcomes(
    prepared: &[Prepared<'_>],
    keys: &[Vec<CellKey>],
    todo: &[usize],
    outcomes: &[RuleBits],
    trials: u64,
    known: &mut HashMap<CellKey, Counts>,
) {
    for (n, &i) in todo.iter().enumerate() {
        let start = n * trials as usize;
        for (r, k) in keys[i].iter().enumerate() {
            let mut c = Counts {
                trials,
                engagements: trials * prepared[i].larger_teeth,
                ..Counts::default()
            };
            for &o in &outcomes[start..start + trials as usize] {
                let (jam, dis) = under(o, r);
                c.jams += u64::from(jam);
                c.disengagements += u64::from(dis);
                c.failures += u64::from(jam || dis);
            }
            known.insert(k.clone(), c);
        }
    }
}

/// Runs every trial of the cells `todo` in one flat batch named by everything that determines
/// it (the cells' keys, in order); the outcomes in (cell, trial) order.
fn run_todo(
    prepared: &[Prepared<'_>],
    countings_of: &[Vec<Counting>],
    keys: &[Vec<CellKey>],
    todo: &[usize],
    trials: u64,
    seed: u64,
    run_batch: impl RunBatch,
) -> Result<Vec<RuleBits>, RunError> {
    // Job n is trial n % trials of cell todo[n / trials]: every cell runs the same trials, so
    // the (cell, trial) list is arithmetic, not a vector (10^6 trials of 256 cells would be 4 GB).
    let jobs = todo.len() as u64 * trials;
    if jobs == 0 {
        return Ok(Vec::new());
    }
    let mut names = String::new();
    for &i in todo {
        for k in &keys[i] {
            let _ = writeln!(names, "{k}");
        }
    }
    let batch = format!(
        "pair-cells/{}-cells-of-{trials}/{:016x}",
        todo.len(),
        fnv1a64(names.as_bytes())
    );
    let job = |n: u64| -> Result<RuleBits, RunError> {
        let (i, t) = (todo[(n / trials) as usize], n % trials);
        trial(&prepared[i], seed, t, &countings_of[i])
    };
    run_batch(&batch, jobs, &job)
}

/// Trials `range` (indices, e.g. `40..60`) of one cell: a stretch of a cell's trials, for a
/// search that adds trials to a cell a batch at a time.
#[derive(Clone)]
pub struct CellRange {
    /// The cell.
    pub cell: CellSpec,
    /// Trial indices to run.
    pub range: std::ops::Range<u64>,
}

/// Runs trial indices `start..end` of each cell of `ranges` and returns each range's counts, in
/// the order of `ranges`.
///
/// Trial `t` of a cell draws from the same stream as in [`run_cells`], so the counts of ranges
/// `0..a` and `a..b` of a cell add up to what `run_cells` gives that cell with `b` trials. All
/// ranges run in one flat batch through [`TrialEngine::trials`] (or [`TrialEngine::trials_whole`] for an
/// [`Purpose::Input`]: a search that decides from the counts what to run next must use it), named
/// by every cell's canonical text, the seed, the gearing and the index range. Nothing is
/// cached.
///
/// Errors: an empty range; a mesh missing from the gearing; a gear the hypothesis cannot
/// manufacture (the first such trial in range and trial order).
pub fn run_cell_ranges(
    engine: &TrialEngine,
    g: &Gearing,
    ranges: &[CellRange],
    purpose: Purpose,
) -> Result<Vec<Counts>, RunError> {
    let whole = purpose == Purpose::Input;
    run_cell_ranges_with(g, ranges, engine.seed(), |key, n, f| {
        if whole {
            engine.trials_whole(key, n, f)
        } else {
            engine.trials(key, n, f)
        }
    })
}

/// [`run_cell_ranges`] with the batch runner given (as in [`run_cells_with`]).
fn run_cell_ranges_with(
    g: &Gearing,
    ranges: &[CellRange],
    seed: u64,
    run_batch: impl RunBatch,
) -> Result<Vec<Counts>, RunError> {
    if let Some(r) = ranges.iter().find(|r| r.range.is_empty()) {
        return Err(RunError::bad(
            "--set",
            "trials",
            format!(
                "the trial range {}..{} of mesh {} is empty",
                r.range.start, r.range.end, r.cell.mesh
            ),
        ));
    }
    let prepared: Vec<Prepared<'_>> = ranges
        .iter()
        .map(|r| prepare(g, &r.cell))
        .collect::<Result<_, _>>()?;
    let gearing_id = GearingId::of(g)?;
    let mut names = String::new();
    let mut jobs: Vec<(usize, u64)> = Vec::new();
    for (i, (r, p)) in ranges.iter().zip(&prepared).enumerate() {
        let _ = writeln!(
            names,
            "{}|seed={seed}|gearing={gearing_id:016x}|trials={}..{}",
            p.canonical, r.range.start, r.range.end
        );
        jobs.extend(r.range.clone().map(|t| (i, t)));
    }
    let batch = format!(
        "pair-ranges/{}-ranges-{}-trials/{:016x}",
        ranges.len(),
        jobs.len(),
        fnv1a64(names.as_bytes())
    );
    let outcomes: Vec<RuleBits> = if jobs.is_empty() {
        Vec::new()
    } else {
        let job = |n: u64| -> Result<RuleBits, RunError> {
            let (i, t) = jobs[n as usize];
            trial(
                &prepared[i],
                seed,
                t,
                std::slice::from_ref(&Counting::of(prepared[i].spec)),
            )
        };
        run_batch(&batch, jobs.len() as u64, &job)?
    };
    let mut counts: Vec<Counts> = ranges
        .iter()
        .zip(&prepared)
        .map(|(r, p)| {
            let n = r.range.end - r.range.start;
            Counts {
                trials: n,
                engagements: n * p.larger_teeth,
                ..Counts::default()
            }
        })
        .collect();
    for (&(i, _), &o) in jobs.iter().zip(&outcomes) {
        let (jam, dis) = under(o, 0);
        counts[i].jams += u64::from(jam);
        counts[i].disengagements += u64::from(dis);
        counts[i].failures += u64::from(jam || dis);
    }
    Ok(counts)
}

/// A grid value as printed and as keyed in `paper.ron`: at least `min_decimals` decimals, more
/// if needed to give the value back exactly (0.04 → `0.040` with 3, 0.0375 → `0.0375`).
pub fn label(v: f64, min_decimals: usize) -> String {
    for d in min_decimals..=12 {
        let s = fmt_f64(v, d);
        if s.parse::<f64>()
            .is_ok_and(|x| (x - v).abs() <= 1e-12 * v.abs().max(1.0))
        {
            return s;
        }
    }
    v.to_string()
}

#[cfg(test)]
mod tests;
