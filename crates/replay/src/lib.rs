//! One trial of a per-mesh jam table rebuilt from its random stream, and the grammar of its cells.
//!
//! `cargo xtask replay` shows a trial's gears, initial angle and events, and writes the pair file
//! that reruns it with `run pair`.
//!
//! A cell is named as its table prints it, in the grammar its experiment registers beside itself
//! (a [`CellGrammar`], keyed by the experiment's id): `table3 B/m3-e3` (Case / mesh), `tableI
//! B/70/m3-e3` (Case / G / mesh), `table4 0.050/m3-e3` (random error / mesh), `table5
//! 0.050/0.7/e4-f1` (random error / systematic error / mesh: the mesh's E. max and a row of Table
//! 5). The cell is built from the experiment's own parameters (`--set` reaches them as in `run`),
//! so the trial is the one the table counted, in any run, sharded or not: a trial's stream
//! depends only on the cell's content, the seed and the trial index.

use std::collections::BTreeMap;
use std::f64::consts::TAU;
use std::fmt::Write as _;
use std::sync::LazyLock;

use contact::Solve;
use registry::{Context, OutputFile, Report, RunError, Table, fmt_f64};
use train::Gearing;

use study::cell::{CellSpec, Counting, Rebuilt, rebuild};
use study::drive::{Drive, Driver};
use study::grids::{CASES, CellSettings};

/// How the cells of a per-mesh table are named, what each one names and which of them the table
/// holds under a run's settings: an experiment whose trials can be replayed registers one in its
/// own file, beside its experiment (`experiments`' `replay_cells!` fills in the settings and the
/// check, which read the experiments' shared settings):
///
/// ```ignore
/// registry::register!(Table3);
/// crate::replay_cells! { "table3", "CASE/MESH, e.g. B/m3-e3" => cell }
/// ```
pub struct CellGrammar {
    /// The id of the experiment whose cells these are.
    pub experiment: &'static str,
    /// The form of a cell, with an example (`CASE/MESH, e.g. B/m3-e3`).
    pub form: &'static str,
    /// What the typed cell names, under the experiment's settings in the context.
    pub parse: for<'a> fn(&CellSettings, &CellText<'a>) -> Result<Cell<'a>, RunError>,
    /// The table's cell settings, read from a run's context (every replayable table counts its
    /// cells with the per-cell `trials` parameter).
    pub settings: fn(&Context) -> Result<CellSettings, RunError>,
    /// Refuses a cell (`experiment`, `cell`) the grammar reads but the table never runs under the
    /// context's settings (its cell settings given), naming the part typed and the table's values.
    pub holds: fn(&Context, &CellSettings, &str, &str) -> Result<(), RunError>,
}

registry::inventory::collect!(CellGrammar);

/// Every registered cell grammar by experiment id; a second grammar for one experiment is an
/// error naming it.
pub fn grammars() -> Result<BTreeMap<&'static str, &'static CellGrammar>, RunError> {
    let mut map = BTreeMap::new();
    for g in registry::inventory::iter::<CellGrammar> {
        if map.insert(g.experiment, g).is_some() {
            return Err(RunError::Internal(format!(
                "experiment `{}` registers two cell grammars",
                g.experiment
            )));
        }
    }
    Ok(map)
}

/// The experiments whose trials can be replayed, with the form of their cells, by id: the
/// registered [`CellGrammar`]s.
pub static REPLAYABLE: LazyLock<Vec<(&'static str, &'static str)>> = LazyLock::new(|| {
    registry::inventory::iter::<CellGrammar>
        .into_iter()
        .map(|g| (g.experiment, g.form))
        .collect::<BTreeMap<_, _>>()
        .into_iter()
        .collect()
});

/// A cell as typed, split at its `/`, with the helpers a grammar reads its parts with: each
/// refusal names the cell and its experiment.
pub struct CellText<'a> {
    id: &'a str,
    text: &'a str,
    form: &'static str,
    parts: Vec<&'a str>,
}

impl<'a> CellText<'a> {
    /// The parts of the cell between its `/`.
    pub fn parts(&self) -> &[&'a str] {
        &self.parts
    }

    /// The refusal of a cell that is not of the grammar's form.
    pub fn malformed(&self) -> RunError {
        self.bad(format!("must be {}", self.form))
    }

    /// The refusal of this cell for breaking `rule`.
    pub fn bad(&self, rule: impl Into<String>) -> RunError {
        bad_cell(self.id, self.text, rule)
    }

    /// Case `name`'s (systematic, random) errors.
    pub fn case(&self, name: &str) -> Result<(f64, f64), RunError> {
        CASES
            .iter()
            .find(|(c, _, _)| c.eq_ignore_ascii_case(name))
            .map(|&(_, s, r)| (s, r))
            .ok_or_else(|| self.bad(format!("`{name}` is not a Case (A, B, C or D)")))
    }

    /// The hypothesis parameters Case `name` sets under settings `s`: its random and
    /// systematic errors, and the settings' split.
    pub fn case_errors(
        &self,
        s: &CellSettings,
        name: &str,
    ) -> Result<Vec<(&'static str, f64)>, RunError> {
        let (systematic, random) = self.case(name)?;
        Ok(vec![
            ("random", random),
            ("systematic", systematic),
            ("split", s.errors.split()?),
        ])
    }

    /// A number typed in the cell, checked against the kind of the grid parameter it stands
    /// for (`run` checks the same values with the same rules).
    pub fn number(&self, what: &str, kind: &registry::Kind, text: &str) -> Result<f64, RunError> {
        let text = text.trim();
        kind.check(text)
            .map_err(|rule| self.bad(format!("{what} `{text}`: {rule}")))?;
        text.parse::<f64>()
            .map_err(|_| self.bad(format!("{what} `{text}` is not a number")))
    }

    /// A clearance G typed in the cell: above 0 and at most what Table I's `clearances` take.
    pub fn clearance(&self, text: &str) -> Result<f64, RunError> {
        study::gearing::clearance_value(text, study::gearing::MAX_LISTED_CLEARANCE)
            .map_err(|rule| self.bad(format!("G `{}`: {rule}", text.trim())))
    }
}

/// What a cell names: one mesh under the paper's jam protocol.
pub struct Cell<'a> {
    /// The mesh, as typed (checked against the gearing afterwards).
    pub mesh: &'a str,
    /// The hypothesis parameters the cell sets, beside the hypothesis's defaults and `--set`.
    pub errors: Vec<(&'static str, f64)>,
    /// The clearance G, percent.
    pub clearance: f64,
    /// The hypothesis parameters typed in the cell: (parameter, what the cell calls it, the
    /// text typed), so that a value the hypothesis refuses is named as the part of the cell it
    /// was typed in.
    pub typed: Vec<Typed<'a>>,
}

/// A hypothesis parameter typed in a cell: (parameter, what the cell calls it, the text typed).
pub type Typed<'a> = (&'static str, &'static str, &'a str);

/// How many failing trials a listing shows of each kind.
const LISTED: usize = 20;

fn bad_cell(id: &str, cell: &str, rule: impl Into<String>) -> RunError {
    RunError::bad("replay", format!("cell `{cell}` of {id}"), rule)
}

/// `id`'s cell grammar, or an error naming the experiments that can be replayed.
fn grammar(id: &str) -> Result<&'static CellGrammar, RunError> {
    let all = grammars()?;
    all.get(id).copied().ok_or_else(|| {
        let known: Vec<String> = all
            .values()
            .map(|g| format!("{} ({})", g.experiment, g.form))
            .collect();
        RunError::bad(
            "replay",
            format!("experiment `{id}`"),
            format!("has no replayable trials; these do: {}", known.join(", ")),
        )
    })
}

/// The cell `cell` of experiment `id`, built from the experiment's settings `s`, and checked as
/// `run` checks its cells ([`study::cell::check`], under `seed`): a value the user typed in the
/// cell that breaks a rule is named as typed (`random error `0.5``).
pub fn cell_spec(s: &CellSettings, seed: u64, id: &str, cell: &str) -> Result<CellSpec, RunError> {
    let (spec, typed) = unchecked_cell_spec(s, id, cell)?;
    let g = s.gearing();
    study::cell::check(g, &spec, seed).map_err(|e| typed_part(e, id, cell, &typed))?;
    Ok(spec)
}

/// A hypothesis' refusal of a value the user typed in the cell (`typed`, as [`Cell::typed`]),
/// said of that part of the cell; any other error as it is.
fn typed_part(e: RunError, id: &str, cell: &str, typed: &[(&str, &str, &str)]) -> RunError {
    let RunError::BadInput { field, rule, .. } = &e else {
        return e;
    };
    for &(key, name, text) in typed {
        if field == key || field.ends_with(&format!(": {key}")) {
            return bad_cell(id, cell, format!("{name} `{}`: {rule}", text.trim()));
        }
    }
    e
}

/// The (unchecked) spec of cell `cell` of experiment `id` under settings `s`, and the parameters
/// typed in it: what the cell names, before [`CellGrammar::holds`] and [`cell_spec`]'s checks.
///
/// # Errors
/// An experiment without a grammar, a malformed cell, a mesh not in the gearing, a value the
/// hypothesis refuses (named as typed).
pub fn unchecked_cell_spec<'a>(
    s: &CellSettings,
    id: &'a str,
    cell: &'a str,
) -> Result<(CellSpec, Vec<Typed<'a>>), RunError> {
    let grammar = grammar(id)?;
    let text = CellText {
        id,
        text: cell,
        form: grammar.form,
        parts: cell.split('/').collect(),
    };
    let g = s.gearing();
    let Cell {
        mesh,
        errors,
        clearance,
        typed,
    } = (grammar.parse)(s, &text)?;
    if g.mesh(mesh).is_none() {
        let meshes: Vec<&str> = g.meshes().iter().map(|m| m.label.as_str()).collect();
        return Err(bad_cell(
            id,
            cell,
            format!(
                "no mesh `{mesh}` in the gearing (its meshes: {})",
                meshes.join(", ")
            ),
        ));
    }
    // A value the hypothesis refuses is named as the part of the cell it was typed in.
    let params = s
        .errors
        .params(&errors)
        .map_err(|e| typed_part(e, id, cell, &typed))?;
    let spec = s.cell(mesh, params, clearance);
    Ok((spec, typed))
}

/// Replays trial `trial` of `cell` of experiment `id` (its events and the pair file that reruns
/// it), or, with no trial, lists which of the experiment's trials of that cell failed.
///
/// Errors: an experiment without replayable trials, a malformed cell, a mesh not in the
/// gearing, a trial index at or beyond the experiment's trial count.
pub fn replay(ctx: &Context, id: &str, cell: &str, trial: Option<u64>) -> Result<Report, RunError> {
    let grammar = grammar(id)?;
    let s = (grammar.settings)(ctx)?;
    // A cell the table holds under these settings, before its gears are made.
    (grammar.holds)(ctx, &s, id, cell)?;
    let spec = cell_spec(&s, ctx.seed(), id, cell)?;
    let (g, trials) = (s.gearing(), s.trials);
    match trial {
        Some(t) if t >= trials => Err(RunError::bad(
            "replay",
            format!("trial {t}"),
            format!(
                "must be below {id}'s {trials} trials (0 to {})",
                trials.saturating_sub(1)
            ),
        )),
        Some(t) => one_trial(ctx, g, &spec, id, cell, t),
        None => listing(ctx, g, &spec, id, cell, trials),
    }
}

/// The events of one trial, and its pair file: checked first, by the loader `run pair` uses,
/// so that a replay never writes a pair file `run pair` refuses ([`refused_pair_file`]).
fn one_trial(
    ctx: &Context,
    g: &Gearing,
    spec: &CellSpec,
    id: &str,
    cell: &str,
    t: u64,
) -> Result<Report, RunError> {
    let seed = ctx.seed();
    let rebuilt = rebuild(g, spec, seed, t)?;
    let pair = pair_file(&rebuilt, &drive_note(g, spec, &rebuilt));
    if let Ok(text) = &pair {
        study::pair_file::prepare("pair.ron", text)
            .map_err(|e| refused_pair_file(ctx, e, id, cell, t))?;
    }
    // The run `pair.html` and `run pair --config pair.ron` show: its start gives θ0.
    let traj = rebuilt.mesh.as_ref().map(|mesh| {
        mesh.solve(
            rebuilt.phi0..=rebuilt.phi0 + rebuilt.turn,
            contact::Start::Touching(0.0),
            Solve::path(),
        )
    });
    let mut table = events_table(g, spec, &rebuilt, traj.as_ref(), (id, cell, t, seed));
    let mut files = Vec::new();
    if let (Some(mesh), Some(traj)) = (&rebuilt.mesh, &traj) {
        trial_files(
            &mut table,
            &mut files,
            mesh,
            traj,
            spec,
            &format!("{id} {cell}, trial {t} (seed {seed})"),
        );
    }
    match pair {
        Ok(ron) => {
            table.note("pair.ron rebuilds this trial for `cargo xtask run pair --config pair.ron` (edit it to change one thing and rerun).");
            files.push(OutputFile::new("pair.ron", ron));
        }
        Err(why) => table.note(format!("No pair file: {why}.")),
    }
    Ok(Report {
        tables: vec![table],
        files,
        ..Default::default()
    })
}

/// What the cell's event rule counts an event as: `jam`, `disengagement` or `-`.
fn counted_by(spec: &CellSpec, e: &contact::Event) -> &'static str {
    if spec.events.is_jam(e) {
        "jam"
    } else if spec.events.is_disengagement(e) {
        "disengagement"
    } else {
        "-"
    }
}

/// The trial's events, one a row: where, what, what the rule counts it as, its teeth, its
/// angles, its size in driven pitches and whether the paper's protocol after the first lock
/// led to it; titled with the trial and what it did ([`ReplayedTrial`] reads the title back).
fn events_table(
    g: &Gearing,
    spec: &CellSpec,
    rebuilt: &Rebuilt,
    traj: Option<&contact::Trajectory>,
    (id, cell, t, seed): (&str, &str, u64, u64),
) -> Table {
    let events = rebuilt.events();
    let (jam, dis) = if rebuilt.mesh.is_none() {
        (true, false)
    } else {
        Counting::of(spec).tally(&events)
    };
    let mut table = Table::new(
        format!(
            "{id} {cell}, trial {t} (seed {seed}): {} [events: {}; drive: {}, {} drove{}]",
            verdict(jam, dis),
            spec.events.label(),
            spec.drive.name(),
            driving_gear(g, spec, rebuilt),
            end_tag(spec),
        ),
        [
            "phi - phi0 [deg]",
            "phi [deg]",
            "kind",
            "counted as",
            "driver tooth",
            "driven tooth",
            "theta - theta0 [deg]",
            "theta [deg]",
            "size",
            "motion",
        ],
    );
    let theta0 = traj.map(|tr| tr.theta_at(rebuilt.phi0));
    let (n1, n2) = rebuilt.mesh.as_ref().map_or((1, 1), |m| {
        (m.driver().teeth() as i64, m.driven().teeth() as i64)
    });
    let first = presentation::pair_html::first_lock(&events);
    for (i, e) in events.iter().enumerate() {
        // An idle start has no teeth: none touches the driven gear.
        let idle = presentation::pair_html::is_idle_start(e);
        let tooth = |t: i64, n: i64| {
            if idle {
                "-".to_string()
            } else {
                t.rem_euclid(n).to_string()
            }
        };
        table.row(vec![
            fmt_f64((e.phi - rebuilt.phi0).to_degrees(), 6),
            fmt_f64(e.phi.to_degrees(), 6),
            e.label().into(),
            counted_by(spec, e).into(),
            tooth(e.driver_tooth, n1),
            tooth(e.driven_tooth, n2),
            theta0.map_or_else(|| "-".into(), |t0| fmt_f64((e.theta - t0).to_degrees(), 6)),
            fmt_f64(e.theta.to_degrees(), 6),
            presentation::pair_html::size_text(e, n2 as usize),
            presentation::pair_html::motion_word(i, first).into(),
        ]);
    }
    events_notes(&mut table, g, spec, rebuilt, n2 as usize);
    table
}

/// The notes under a replayed trial's events: the cell and the start, which gear drove, the
/// angles, the sizes, the motion after the first lock and the releases.
fn events_notes(table: &mut Table, g: &Gearing, spec: &CellSpec, rebuilt: &Rebuilt, n2: usize) {
    let events = rebuilt.events();
    table.note(format!(
        "Cell: {}. Initial driver angle phi0 = {} deg; one full turn of the gear with more teeth ({} deg of the driver). Teeth numbered 0 to N - 1 as in pair.ron's tips_deg; an idle start has none (`-`): no tooth touches the driven gear.",
        spec.canonical(),
        fmt_f64(rebuilt.phi0.to_degrees(), 9),
        fmt_f64(rebuilt.turn.to_degrees(), 6),
    ));
    table.note(drive_note(g, spec, rebuilt));
    table.note(presentation::pair_html::ANGLES_NOTE);
    table.note("size: a release's (lock, strike) or a loss of drive's (gap, slip) effect on the driven gear, in driven pitches: how far ahead of the ideal ratio the gear was when drive resumed (behind it, for a loss), and the change of tooth phase.");
    if presentation::pair_html::first_lock(&events).is_some() {
        table.note(presentation::pair_html::MOTION_NOTE);
        table.note(presentation::pair_html::PROTOCOL_NOTE);
    }
    if let Some(n) = presentation::pair_html::releases_note(&events, n2) {
        table.note(n);
    }
}

/// The files of a replayed trial that ran (`pair.html`, a picture per event), and the notes
/// they need under the table: the polygon oracle's check, the pictures written, a release.
fn trial_files(
    table: &mut Table,
    files: &mut Vec<OutputFile>,
    mesh: &contact::Mesh,
    traj: &contact::Trajectory,
    spec: &CellSpec,
    title: &str,
) {
    let counted = |e: &contact::Event| counted_by(spec, e);
    table.note(oracle_note(mesh, traj));
    let teeth = presentation::pair_html::solver_teeth(mesh);
    files.push(OutputFile::new(
        "pair.html",
        presentation::pair_html::page(title, traj, &counted, &teeth),
    ));
    for (name, svg) in presentation::event_picture::event_pictures(title, traj, &counted, &teeth) {
        files.push(OutputFile::new(name, svg));
    }
    if let Some(n) = presentation::event_picture::pictures_note(traj.events().len()) {
        table.note(n);
    }
    if traj
        .events()
        .iter()
        .any(|e| e.kind.is_contact_stop() && presentation::pair_html::moves_pointer(e))
    {
        table.note(presentation::pair_html::RELEASE_NOTE);
    }
}

/// Settings that do not reach a trial's gears: never the cause of a refused pair file.
const NOT_GEARS: [&str; 2] = ["trials", "events"];

/// The pair file of trial `t` refused by `run pair`'s loader (`refusal`), as the user's error:
/// one line naming the setting typed that made it (`--set: tooth_height=2: ...`; the one the
/// refused field follows from when it was typed, else every one typed that shapes the gears, else
/// the cell) and the rule.
fn refused_pair_file(ctx: &Context, refusal: RunError, id: &str, cell: &str, t: u64) -> RunError {
    let RunError::BadInput { field, rule, .. } = &refusal else {
        return refusal;
    };
    let typed: Vec<(&str, &str)> = ctx
        .changed()
        .into_iter()
        .filter(|(name, _)| !NOT_GEARS.contains(name))
        .collect();
    // The setting the refused field follows from: tooth heights from `tooth_height`, the
    // centre distance from `clearance`.
    let cause = if field.ends_with("root_radius") || field.ends_with("tip_radius") {
        "tooth_height"
    } else if field == "centre_distance" || field == "clearance_percent" {
        "clearance"
    } else {
        ""
    };
    let named: Vec<String> = match typed.iter().find(|(name, _)| *name == cause) {
        Some(&(name, value)) => vec![format!("{name}={}", value.trim())],
        None => typed
            .iter()
            .map(|(name, value)| format!("{name}={}", value.trim()))
            .collect(),
    };
    let what = format!(
        "trial {t} of {id} {cell} would be written as a pair file that `run pair` refuses ({field}: {rule}); nothing written"
    );
    if named.is_empty() {
        RunError::bad("replay", format!("cell `{cell}` of {id}"), what)
    } else {
        RunError::bad("--set", named.join(", "), what)
    }
}

/// Driver angles of a replayed turn at which the polygon oracle checks the teeth.
const ORACLE_SAMPLES: usize = 20_000;

/// What the polygon oracle (`polycheck`, which shares no code with the solver) says of the
/// replayed run: the deepest interpenetration of the two gears' outlines at evenly spaced driver
/// angles of the turn, the driven gear where the run puts it, held stretches (where the push
/// model lets a jammed gear overlap) left out. Rounding gives about 1e-14 mm; a run that lets a
/// tooth pass through the driven gear shows here, if the passage is not briefer than the spacing.
fn oracle_note(mesh: &contact::Mesh, traj: &contact::Trajectory) -> String {
    let (driver, driven) = (mesh.driver(), mesh.driven());
    if driver.flank_sagitta() != 0.0 || driven.flank_sagitta() != 0.0 {
        return "Polygon oracle: not run (curved flanks; polycheck's outlines are straight-flanked).".into();
    }
    let shape = |g: &geometry::Gear| polycheck::GearShape {
        outline: g.outline().iter().map(|v| [v.x, v.y]).collect(),
        rotation_centre_offset: [g.rotation_centre().x, g.rotation_centre().y],
    };
    let oracle = polycheck::Mesh {
        driver: shape(driver),
        driven: shape(driven),
        centre_distance: mesh.centre_distance(),
    };
    // The held stretches, gathered once (a turn has thousands of segments, few of them held).
    let held_spans: Vec<_> = traj
        .segments()
        .iter()
        .filter(|s| s.motion == contact::Motion::Held)
        .map(|s| s.phi_start..=s.phi_end)
        .collect();
    let held = |phi: f64| held_spans.iter().any(|span| span.contains(&phi));
    let (phi0, phi1) = (traj.phi_start(), traj.phi_end());
    let deepest = (0..=ORACLE_SAMPLES)
        .map(|i| phi0 + (phi1 - phi0) * i as f64 / ORACLE_SAMPLES as f64)
        .filter(|&phi| !held(phi))
        .map(|phi| {
            let theta = traj.theta_at(phi);
            (oracle.penetration_at(phi, theta), phi, theta)
        })
        .fold((0.0, phi0, traj.theta_at(phi0)), |a, b| {
            if b.0 > a.0 { b } else { a }
        });
    format!(
        "Polygon oracle (polycheck, no code shared with the solver): at {ORACLE_SAMPLES} driver angles of the turn, held stretches left out, the teeth interpenetrate by at most {:.1e} mm (phi {} deg, theta {} deg); rounding gives about 1e-14 mm.",
        deepest.0,
        fmt_f64(deepest.1.to_degrees(), 6),
        fmt_f64(deepest.2.to_degrees(), 6),
    )
}

/// The verdicts a replayed trial's title gives, by what the trial did (jammed, disengaged).
const VERDICTS: [(&str, bool, bool); 4] = [
    ("jammed and disengaged", true, true),
    ("jammed", true, false),
    ("disengaged", false, true),
    ("neither jammed nor disengaged", false, false),
];

fn verdict(jam: bool, dis: bool) -> &'static str {
    VERDICTS
        .iter()
        .find(|v| (v.1, v.2) == (jam, dis))
        .map_or("?", |v| v.0)
}

/// A replayed trial as its table's title names it (`table3 D/m3-e3, trial 0 (seed 2025):
/// disengaged [...]`, as [`replay`] writes it): the experiment, the cell, the trial and what it
/// did, so that a page linking to the trial can say it is one of the failure it links from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ReplayedTrial {
    /// The experiment whose cell it is.
    pub experiment: String,
    /// The cell as typed.
    pub cell: String,
    /// The trial's index.
    pub trial: u64,
    /// Whether the trial jammed (as its table counts it).
    pub jammed: bool,
    /// Whether it disengaged.
    pub disengaged: bool,
}

impl ReplayedTrial {
    /// Reads a title [`replay`] wrote for one trial; `None` for any other text.
    pub fn from_title(title: &str) -> Option<Self> {
        let (head, rest) = title.split_once(", trial ")?;
        let (experiment, cell) = head.split_once(' ')?;
        let (trial, rest) = rest.split_once(' ')?;
        let (_, rest) = rest.split_once("): ")?;
        let said = rest.split(" [").next()?;
        let &(_, jammed, disengaged) = VERDICTS.iter().find(|v| v.0 == said)?;
        Some(Self {
            experiment: experiment.to_owned(),
            cell: cell.to_owned(),
            trial: trial.parse().ok()?,
            jammed,
            disengaged,
        })
    }
}

/// What makes trial `t` of cell `cell` of experiment `id` (under the settings of `ctx`) the
/// trial it is, whichever table counts it: the cell's content, the gearing, how its events are
/// counted (rule, drive, end) and the seed. Two cells of two tables with the same key (Table
/// 3's `B/m3-e3` and Table I's `B/40/m3-e3`) have the same trials, index for index, counted
/// alike, so a replay of one is a replay of the other.
pub fn trial_key(ctx: &Context, id: &str, cell: &str) -> Result<String, RunError> {
    let s = (grammar(id)?.settings)(ctx)?;
    let (spec, _) = unchecked_cell_spec(&s, id, cell)?;
    Ok(format!(
        "{};gearing={};events={};drive={}{};seed={}",
        spec.canonical(),
        s.gearing.file,
        spec.events.label(),
        spec.drive.name(),
        end_tag(&spec),
        ctx.seed()
    ))
}

/// The file of a listing that names every failed trial of the cell, one line each:
/// `trial,jammed,disengaged`.
pub const FAILED_TRIALS_CSV: &str = "failed-trials.csv";

/// The same as JSON: `{"experiment", "cell", "seed", "trials", "jammed": [...], "disengaged": [...]}`.
pub const FAILED_TRIALS_JSON: &str = "failed-trials.json";

/// The trials of the cell that failed, by kind: the printed table shows the first [`LISTED`]
/// of each and says where the rest are; [`FAILED_TRIALS_CSV`] and [`FAILED_TRIALS_JSON`] list
/// every one.
fn listing(
    ctx: &Context,
    g: &Gearing,
    spec: &CellSpec,
    id: &str,
    cell: &str,
    trials: u64,
) -> Result<Report, RunError> {
    let seed = ctx.seed();
    // Through the trial engine like every trial loop (one stream per trial, in trial order).
    let key = format!("replay listing of {}", spec.canonical());
    let outcomes: Vec<(bool, bool)> = ctx.trials(&key, trials, |t| {
        let r = rebuild(g, spec, seed, t)?;
        Ok(if r.mesh.is_none() {
            (true, false)
        } else {
            Counting::of(spec).tally(&r.events())
        })
    })?;
    let which = |f: fn(&(bool, bool)) -> bool| -> Vec<u64> {
        (0..trials)
            .zip(&outcomes)
            .filter(|(_, o)| f(o))
            .map(|(t, _)| t)
            .collect()
    };
    let (jammed, disengaged) = (which(|o| o.0), which(|o| o.1));
    let shown = |all: &[u64]| -> String {
        if all.is_empty() {
            return "-".into();
        }
        let mut s = all
            .iter()
            .take(LISTED)
            .map(u64::to_string)
            .collect::<Vec<_>>()
            .join(", ");
        if all.len() > LISTED {
            let _ = write!(
                s,
                ", ... ({} more: every one in {FAILED_TRIALS_CSV})",
                all.len() - LISTED
            );
        }
        s
    };
    let mut table = Table::new(
        format!(
            "{id} {cell}: the trials that failed, of {trials} (seed {seed}) [events: {}; drive: {}{}]",
            spec.events.label(),
            spec.drive.name(),
            end_tag(spec)
        ),
        ["failure", "trials", "trial indices"],
    );
    table.row(vec!["jam".into(), jammed.len().to_string(), shown(&jammed)]);
    table.row(vec![
        "disengagement".into(),
        disengaged.len().to_string(),
        shown(&disengaged),
    ]);
    table.note(format!(
        "Every failed trial, one line each, in {FAILED_TRIALS_CSV} (trial,jammed,disengaged) and {FAILED_TRIALS_JSON}; this table shows the first {LISTED} of each kind."
    ));
    table.note(format!(
        "Replay one: cargo xtask replay {id} {cell} TRIAL (with the same --seed and --set as the table's run)."
    ));
    let mut csv = String::from("trial,jammed,disengaged\n");
    for (t, (j, d)) in (0..trials).zip(&outcomes) {
        if *j || *d {
            csv.push_str(&registry::csv_row!(t, j, d));
        }
    }
    let list = |v: &[u64]| v.iter().map(u64::to_string).collect::<Vec<_>>().join(", ");
    let json = format!(
        "{{\n  \"experiment\": {},\n  \"cell\": {},\n  \"seed\": {seed},\n  \"trials\": {trials},\n  \"jammed\": [{}],\n  \"disengaged\": [{}]\n}}",
        json_string(id),
        json_string(cell),
        list(&jammed),
        list(&disengaged)
    );
    Ok(Report {
        tables: vec![table.data_in(FAILED_TRIALS_CSV)],
        files: vec![
            OutputFile::new(FAILED_TRIALS_CSV, csv),
            OutputFile::new(FAILED_TRIALS_JSON, json + "\n"),
        ],
        trials,
        ..Default::default()
    })
}

/// `s` as a JSON string: quoted, with quotes, backslashes and control characters escaped.
fn json_string(s: &str) -> String {
    let mut o = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => o.push_str("\\\""),
            '\\' => o.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(o, "\\u{:04x}", c as u32);
            }
            c => o.push(c),
        }
    }
    o.push('"');
    o
}

/// The trial as a `pair` file: explicit tip angles and arbor offsets in the solver's frame
/// (the driver's sense, the tips frame), the centre distance, the initial driver angle and the
/// run's length. Gears the pair format cannot describe (per-tooth radii, curved flanks, valleys
/// off the middle) give the reason instead.
fn pair_file(r: &Rebuilt, drive: &str) -> Result<String, String> {
    let mesh = r
        .mesh
        .as_ref()
        .ok_or("the gears overlap at every angle, so there is no run to rerun")?;
    let mut s =
        String::from("// Rebuilt by `cargo xtask replay`: one trial of a per-mesh table.\n");
    for line in presentation::common::wrap_at_spaces(drive, 96) {
        let _ = writeln!(s, "// {line}");
    }
    s.push_str("(\n");
    for (name, gear) in [("driver", mesh.driver()), ("driven", mesh.driven())] {
        describable(name, gear)?;
        let tips: Vec<String> = gear
            .tip_angles()
            .iter()
            .map(|a| format!("{:?}", a.to_degrees()))
            .collect();
        let c = gear.rotation_centre();
        let _ = writeln!(
            s,
            "    {name}: (\n        teeth: {},\n        tip_radius: {:?},\n        root_radius: {:?},\n        tips_deg: Some([{}]),\n        eccentricity: Some(({:?}, {:?})),\n    ),",
            gear.teeth(),
            gear.tip_radius(),
            gear.root_radius(),
            tips.join(", "),
            c.x,
            c.y
        );
    }
    let _ = writeln!(
        s,
        "    centre_distance: Some({:?}),\n    start_deg: {:?},\n    run_deg: Some({:?}),\n    start: touching,\n)",
        mesh.centre_distance(),
        r.phi0.to_degrees(),
        r.turn.to_degrees()
    );
    Ok(s)
}

/// `; end: NAME` where a trial's counting ends before its whole turn, else nothing.
fn end_tag(spec: &CellSpec) -> String {
    match spec.end {
        study::trial_end::End::Turn => String::new(),
        e => format!("; end: {}", e.name()),
    }
}

/// The gear of the cell's mesh that drove trial `r`, by name (`b2`, or `c1` when the listed
/// driven gear drove).
fn driving_gear(g: &Gearing, spec: &CellSpec, r: &Rebuilt) -> String {
    let Some(m) = g.mesh(&spec.mesh) else {
        return "?".into();
    };
    match r.driver {
        Driver::Listed => m.driver.clone(),
        Driver::Other => m.driven.clone(),
    }
}

/// Which gear drove the trial and why, and how the outputs name its gears and teeth.
fn drive_note(g: &Gearing, spec: &CellSpec, r: &Rebuilt) -> String {
    let gear = driving_gear(g, spec, r);
    let why = match spec.drive {
        Drive::Listed => "drive=listed: the mesh's listed driver drives every trial".to_string(),
        Drive::Other => "drive=other: the mesh's listed driven gear drives every trial".to_string(),
        Drive::Either => format!(
            "drive=either: the trial's coin (drawn from its own stream after its gears and initial angle) picked the {}",
            match r.driver {
                Driver::Listed => "listed driver",
                Driver::Other => "listed driven gear",
            }
        ),
    };
    match r.driver {
        Driver::Listed => format!("Driver: {gear} ({why})."),
        Driver::Other => format!(
            "Driver: {gear} ({why}); both gears turn their own way as in the train, so here `driver` is {gear} and `driven` the mesh's listed driver, each seen from its other face: tooth k here (and in pair.ron) is tooth N - 1 - k of the gear as the table's cell made it, and phi and theta are {gear}'s and its partner's own angles."
        ),
    }
}

/// Whether the pair format can describe `gear`: one tip and one root radius, straight flanks,
/// each valley half-way between its tips.
fn describable(name: &str, gear: &geometry::Gear) -> Result<(), String> {
    let n = gear.teeth() as i64;
    let round = (0..n).all(|k| {
        gear.tip_radius_of(k) == gear.tip_radius() && gear.root_radius_of(k) == gear.root_radius()
    });
    if !round {
        return Err(format!("the {name} has teeth of different heights"));
    }
    if gear.flank_sagitta() != 0.0 {
        return Err(format!("the {name}'s flanks are curved"));
    }
    let mid = gear
        .tip_angles()
        .iter()
        .zip(gear.valley_angles())
        .enumerate()
        .all(|(k, (&a, &v))| {
            let next = if k + 1 < gear.teeth() {
                gear.tip_angles()[k + 1]
            } else {
                gear.tip_angles()[0] + TAU
            };
            (v - 0.5 * (a + next)).abs() < 1e-12
        });
    if !mid {
        return Err(format!(
            "the {name}'s valleys are not half-way between its tips"
        ));
    }
    Ok(())
}
