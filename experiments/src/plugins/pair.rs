//! `pair`: any mesh described in a RON file (tooth counts, radii, optional measured tip angles and
//! eccentricity, centre distance or clearance): θ(φ), Theoretical Difference and every event.

use contact::Solve;
use registry::{OutputFile, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};

use presentation::common::{csv, deg};
use presentation::pair_svg::check_svg;
use setting_groups::typed::label;
use study::drive::{Drive, DriveParams};
use study::events::EventParams;
use study::pair_file::{Numbering, Prepared, default_run_deg, prepare};

const EXAMPLE: &str = include_str!("../../data/pair-example.ron");
const EXAMPLE_NAME: &str = "experiments/data/pair-example.ron";

/// The pair's settings: the event rule, and which gear drives and where counting ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// The event rule.
    #[group]
    pub events: EventParams,
    /// Which gear drives, where counting ends.
    #[group]
    pub drive: DriveParams,
}

/// The pair's results: the file as written, how the run numbers its teeth, and the run with its
/// samples.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Results {
    /// The pair file's name: the `--config` file as given, or the example's path.
    pub file: String,
    /// The pair as its file describes it, whichever gear drives (`pair-check.svg` draws it).
    pub as_written: Prepared,
    /// The file's numbering of the run's driver and of its driven gear.
    pub numbering: (Numbering, Numbering),
    /// The run: θ(φ), its segments and events, and the mesh it ran.
    pub traj: contact::Trajectory,
    /// The driver angle at the start φ0, radians.
    pub phi0: f64,
    /// The driven angle at the start θ0, radians.
    pub theta0: f64,
    /// How far the driver turned, degrees.
    pub run_deg: f64,
    /// A row per sample (degrees): φ − φ0, θ − θ0, the Theoretical Difference, φ and θ.
    pub rows: Vec<[f64; 5]>,
}

/// The pair.
pub struct Pair;

impl registry::Experiment for Pair {
    const ID: &'static str = "pair";
    const TITLE: &'static str =
        "One mesh from a RON file: theta(phi), Theoretical Difference, jams and disengagements";
    const PAPER_ITEM: &'static str = "sections 2-3 (any gear pair, e.g. measured from CT scans)";
    const PLACE: Place = Place::Paper(30);
    const CONFIG: Option<&'static str> = Some(CONFIG_HELP);
    type Settings = Settings;
    type Results = Results;

    fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
        compute(s, run)
    }

    fn report(s: &Settings, r: &Results) -> Result<Report, RunError> {
        label(&s.events, Some(&s.drive), figures(s, r)?)
    }
}

registry::register!(Pair);

/// What `cargo xtask help pair` says of the file: its fields, then every convention in a
/// sentence, so that someone with measurements can fill it in without reading the code.
const CONFIG_HELP: &str = "a mesh: driver and driven gear, each (teeth, tip_radius, root_radius, \
optional sense, tips_deg, eccentricity or arbor, eccentricity_frame), centre_distance or \
clearance_percent, start_deg, optional start, run_deg, sample_deg; see \
experiments/data/pair-example.ron. Conventions, one sentence each:
  - View: the mesh is seen from the side on which the driver turns counter-clockwise; the \
driver's arbor (rotation centre) is at the origin and the driven gear's at (D, 0), so +x runs \
along the line of centres from the driver to the driven gear and +y is 90 deg counter-clockwise \
from it.
  - Zero ray: each gear's tips_deg = 0 is a ray fixed in that gear, starting at its tip-circle \
centre; you choose it when you measure, and tooth angles, phi and theta are all counted from it.
  - phi (driver angle) is how far the driver has turned counter-clockwise, its own turning sense, \
from phi = 0, where its zero ray is parallel to +x, pointing at the driven gear.
  - theta (driven angle) is how far the driven gear has turned clockwise, its own turning sense, \
from theta = 0, where its zero ray is parallel to -x, pointing at the driver.
  - tips_deg are the angles of the tips about the tip-circle centre (the centre of the circle \
through the tips, not the arbor), one per tooth, strictly increasing, all within one turn of \
the first; tooth k is the k-th angle of your list, and every output numbers teeth that way.
  - sense: driver (the default) means tips_deg increase in the direction the driver turns, \
own that they increase in the direction this gear turns; for the driver the two are the same, \
for the driven gear they are mirror images (own: clockwise in the view above).
  - eccentricity: Some((x, y)) is the arbor minus the tip-circle centre, in the frame named by \
eccentricity_frame; arbor: Some((offset: L, angle_deg: A)) gives the same point in polar form \
(L from the tip-circle centre, A from that frame's x axis towards its y axis); give at most one.
  - eccentricity_frame: tips (the default) has x along the gear's zero ray and y 90 deg from it in \
the sense of its tips_deg; world is the view's frame (x along the line of centres towards the \
driven gear, y 90 deg counter-clockwise) with the gears at phi = 0 and theta = 0.
  - start_deg is phi at the start of the run.
  - start: touching (the default) starts the driven gear from theta = 0, pushed forward to the \
first free position if it overlaps a driver tooth, else turned back until one of its teeth rests \
against a driver tooth; at_rest(theta_deg: T) starts it standing still at theta = T until the \
driver reaches it (refused if it overlaps the driver there); teeth(driver: j, driven: k) \
starts it with its tooth k resting against driver tooth j, being pushed, at the theta within half \
a turn of 0 (refused if they cannot touch at start_deg or the position overlaps another tooth).
  - Refused too, in one line naming the field and the rule, are proportions no meshing pair has \
(judged without a unit, so any length unit will do): teeth taller than half their tip radius \
(root_radius below tip_radius / 2), tooth pitches 2 pi tip_radius / teeth of the two gears more \
than 10 times apart, tooth heights tip_radius - root_radius more than 4 times apart, and \
eccentric tips that reach below the other gear's valleys at every angle (D + |e1| + |e2| at most \
the tip radius plus the other gear's root radius).
  - pair.csv: phi_minus_phi0_deg and theta_minus_theta0_deg are phi - phi0 and theta - theta0 \
(phi0 = start_deg, theta0 the driven angle at the start), td_deg = theta_minus_theta0_deg - \
(N1/N2) phi_minus_phi0_deg, and phi_abs_deg, \
theta_abs_deg are phi and theta themselves.
  - event-log.csv: the same relative angles, then the absolute ones, and tooth numbers as in your \
file.
  - pair-check.svg draws both gears at phi = 0 and theta = 0 with the axes, each zero ray, teeth 0 \
and 1 of each gear and the turning senses, so you can check your entry against your scan, and \
beneath them an inset per gear: its arbor against its tip-circle centre in its tips frame, the \
offset exaggerated by the factor it states.
  - pair.html: the run on one self-contained page - both gears turning with a slider over phi and \
a play button, the Theoretical Difference beneath with a cursor, every event a link that draws \
the gears at the event's own phi and theta, zoomed on its contacts (both of a lock), and a lock's \
release a link of its own (open it from disk; `#phi=X` opens it at phi - phi0 = X deg, \
`#event=N` at event N).";

/// The summary of a run: the mesh, the angles it ran through and from, its events as `rule`
/// counts them, and the Theoretical Difference's statistics `s` (none for a driven gear never
/// pushed).
fn summary_table(r: &Results, rule: &rules::Rule, s: &stats::PointerStats) -> Table {
    let (name, traj, run_deg, phi0, theta0) = (&r.file, &r.traj, r.run_deg, r.phi0, r.theta0);
    let mesh = traj.mesh();
    let (n1, n2) = (mesh.driver().teeth(), mesh.driven().teeth());
    let mut summary = Table::new(format!("Mesh from {name}"), ["quantity", "value", "unit"]);
    let rowf = |t: &mut Table, q: &str, v: String, u: &str| t.row(vec![q.into(), v, u.into()]);
    rowf(&mut summary, "teeth N1 : N2", format!("{n1} : {n2}"), "");
    rowf(
        &mut summary,
        "centre distance D",
        fmt_f64(mesh.centre_distance(), 4),
        "length",
    );
    rowf(&mut summary, "driver angle run", fmt_f64(run_deg, 3), "deg");
    rowf(
        &mut summary,
        "driver angle at the start phi0 (absolute)",
        fmt_f64(deg(phi0), 6),
        "deg",
    );
    rowf(
        &mut summary,
        "driven angle at the start theta0 (absolute)",
        fmt_f64(deg(theta0), 6),
        "deg",
    );
    let (jams, disengagements) = study::events::counts(rule, traj);
    rowf(&mut summary, "jams", jams.to_string(), "");
    rowf(
        &mut summary,
        "disengagements",
        disengagements.to_string(),
        "",
    );
    // A driven gear that never moved has no Theoretical Difference to speak of: its "sigma" would
    // be the driver's own turning.
    let stat = |v: f64| {
        if traj.never_driven() {
            "- (never driven)".to_string()
        } else {
            fmt_f64(v, 4)
        }
    };
    rowf(
        &mut summary,
        "Theoretical Difference sigma",
        stat(s.sigma),
        "deg",
    );
    rowf(&mut summary, "Theoretical Difference Dm", stat(s.dm), "deg");
    rowf(
        &mut summary,
        "Theoretical Difference P (absolute mean)",
        stat(s.mean.abs()),
        "deg",
    );
    rowf(
        &mut summary,
        "Theoretical Difference mean (signed)",
        stat(s.mean),
        "deg",
    );
    if traj.never_driven() {
        summary.note("The driven gear was never pushed: no driver tooth reached it in the whole run (an idle start, counted as a disengagement by every event rule), so sigma, Dm and P are not given.");
    }
    summary.note("P is the absolute value of the mean Theoretical Difference, as the paper's P (\"the average absolute value of the oscillation mean\"; averaged over trials in its tables); the signed mean says on which side of the ideal pointer the driven gear runs.");
    summary.note(ABSOLUTE_NOTE);
    summary
}

/// Every simulation: the pair file read (under `drive`), run and sampled.
fn compute(s: &Settings, run: &Run) -> Result<Results, RunError> {
    // A rule that cannot be read is refused before the file is.
    s.events.rule()?;
    let (file, as_written, prepared) = pair_file(s, run)?;
    let sim = simulate(&prepared);
    Ok(Results {
        file,
        as_written,
        numbering: (prepared.driver, prepared.driven),
        traj: sim.traj,
        phi0: sim.phi0,
        theta0: sim.theta0,
        run_deg: sim.run_deg,
        rows: sim.rows,
    })
}

/// The tables and every file, drawn from the results.
fn figures(s: &Settings, r: &Results) -> Result<Report, RunError> {
    let rule = s.events.rule()?;
    let td: Vec<f64> = r.rows.iter().map(|row| row[2]).collect();
    let stats = stats::pointer_stats(&td);
    let mut summary = summary_table(r, &rule, &stats);
    if let Some(note) = before_first_lock(r) {
        summary.note(note);
    }
    let (events, ev_rows) = event_log(&r.traj, &rule, (r.phi0, r.theta0), r.numbering);
    // pair-check.svg draws the file as written; its start line gives the file's own angles (with
    // the driven gear driving, the run's phi is the file's theta and the other way round).
    let start = match s.drive.drive()? {
        Drive::Other => (r.theta0, r.phi0),
        _ => (r.phi0, r.theta0),
    };
    let ([data, td, page], pictures) = run_files(r, &rule)?;
    let check = OutputFile::new("pair-check.svg", check_svg(&r.file, &r.as_written, start));
    let mut files = vec![
        data,
        OutputFile::new("event-log.csv", ev_rows),
        td,
        check,
        page,
    ];
    files.extend(pictures);
    Ok(Report {
        tables: vec![summary, events],
        files,
        ..Default::default()
    })
}

/// The pair file (the `--config` file, or the example) as written and as run under `drive`,
/// with its name.
fn pair_file(s: &Settings, run: &Run) -> Result<(String, Prepared, Prepared), RunError> {
    let (name, text) = match run.config() {
        Some(c) => (c.path.display().to_string(), c.text.as_str()),
        None => (EXAMPLE_NAME.to_string(), EXAMPLE),
    };
    let drive = s.drive.drive()?;
    let as_written = prepare(&name, text)?;
    let prepared = match drive {
        Drive::Listed => as_written.clone(),
        Drive::Other => as_written.clone().other_driving(&name)?,
        Drive::Either => {
            return Err(RunError::bad(
                "--set",
                study::drive::PARAM.name,
                "must be listed or other for a pair file: either draws the driver per trial from a table's random streams, and a pair file is one run",
            ));
        }
    };
    Ok((name, as_written, prepared))
}

/// The Theoretical Difference's statistics up to the run's first lock, in a note: those of the
/// whole run include the motion the paper's protocol gives after it. `None` without a lock.
fn before_first_lock(run: &Results) -> Option<String> {
    let events = run.traj.events();
    let first = &events[presentation::pair_html::first_lock(events)?];
    let at = deg(first.phi - run.phi0);
    let td: Vec<f64> = run
        .rows
        .iter()
        .filter(|r| r[0] <= at)
        .map(|r| r[2])
        .collect();
    let up_to = if td.len() >= 2 {
        let s = stats::pointer_stats(&td);
        format!(
            "up to it, sigma = {} deg, Dm = {} deg, P = {} deg",
            fmt_f64(s.sigma, 4),
            fmt_f64(s.dm, 4),
            fmt_f64(s.mean.abs(), 4)
        )
    } else {
        "it comes before the second sample, so there is nothing to measure before it".to_owned()
    };
    Some(format!(
        "The run's first lock is at phi - phi0 = {} deg: sigma, Dm and P above include the motion after it, which is the paper's protocol (the driven gear let go to the next free position and driven on), not a physical motion; {up_to}.",
        fmt_f64(at, 6)
    ))
}

/// One run of the pair and its samples.
struct Sampled {
    /// The contact motion.
    traj: contact::Trajectory,
    /// The driver angle at the start, radians.
    phi0: f64,
    /// The driven angle at the start, radians.
    theta0: f64,
    /// How far the driver turns, degrees.
    run_deg: f64,
    /// A row per sample: φ − φ0, θ − θ0, the Theoretical Difference, φ and θ, degrees.
    rows: Vec<[f64; 5]>,
}

/// The run the file asks for, sampled every `sample_deg` of the driver.
fn simulate(prepared: &Prepared) -> Sampled {
    let (mesh, spec) = (&prepared.mesh, &prepared.spec);
    let (n1, n2) = (mesh.driver().teeth(), mesh.driven().teeth());
    let ratio = n1 as f64 / n2 as f64;
    let run_deg = spec.run_deg.unwrap_or_else(|| default_run_deg(n1, n2));
    let phi0 = spec.start_deg.to_radians();
    let phi_end = phi0 + run_deg.to_radians();
    let traj = mesh.solve(phi0..=phi_end, prepared.start, Solve::path());
    let theta0 = traj.theta_at(phi0);
    let samples = (run_deg / spec.sample_deg).floor() as usize;
    let rows: Vec<[f64; 5]> = (0..=samples)
        .map(|i| {
            let phi = (phi0 + (i as f64 * spec.sample_deg).to_radians()).min(phi_end);
            let theta_abs = traj.theta_at(phi);
            let theta = theta_abs - theta0;
            [
                deg(phi - phi0),
                deg(theta),
                deg(theta - ratio * (phi - phi0)),
                deg(phi),
                deg(theta_abs),
            ]
        })
        .collect();
    Sampled {
        traj,
        phi0,
        theta0,
        run_deg,
        rows,
    }
}

/// The run's own files: pair.csv, the Theoretical Difference (pair.svg) and the page
/// (pair.html), then a picture per event, every tooth numbered as the file numbers it.
fn run_files(
    run: &Results,
    rule: &rules::Rule,
) -> Result<([OutputFile; 3], Vec<OutputFile>), RunError> {
    let (name, traj, (driver, driven)) = (&run.file, &run.traj, run.numbering);
    let svg = presentation::td_plot::td_plot(
        &format!("the mesh from {name}"),
        traj,
        &|e| counted_as(rule, e),
        &run.rows.iter().map(|r| (r[0], r[2])).collect::<Vec<_>>(),
    )?;
    let data = csv(
        &[
            "phi_minus_phi0_deg",
            "theta_minus_theta0_deg",
            "td_deg",
            "phi_abs_deg",
            "theta_abs_deg",
        ],
        run.rows.iter().map(|row| row.to_vec()),
        9,
    );
    // A driven gear measured in its own sense is numbered the other way round in the solver.
    let numbered = |e: &contact::Event| (driver.user(e.driver_tooth), driven.user(e.driven_tooth));
    let title = format!("Mesh from {name}");
    let page = presentation::pair_html::page(&title, traj, &|e| counted_as(rule, e), &numbered);
    let pictures = presentation::event_picture::event_pictures(
        &title,
        traj,
        &|e| counted_as(rule, e),
        &numbered,
    );
    Ok((
        [
            OutputFile::new("pair.csv", data),
            OutputFile::new("pair.svg", svg),
            OutputFile::new("pair.html", page),
        ],
        pictures
            .into_iter()
            .map(|(n, svg)| OutputFile::new(n, svg))
            .collect(),
    ))
}

/// How many events the printed event table shows; `event-log.csv` has every one.
const EVENTS_SHOWN: usize = 20;

/// What `rule` counts an event as: `jam`, `disengagement` or `-` (reported, not a failure).
fn counted_as(rule: &rules::Rule, e: &contact::Event) -> &'static str {
    if rule.is_jam(e) {
        "jam"
    } else if rule.is_disengagement(e) {
        "disengagement"
    } else {
        "-"
    }
}

/// The event table (first [`EVENTS_SHOWN`]), `event-log.csv` (every event: kind, what the rule
/// counts it as, and its sizes). Angles relative to the start (φ0, θ0); teeth within one turn
/// (none for an idle start, where no tooth touches).
fn event_log(
    traj: &contact::Trajectory,
    rule: &rules::Rule,
    start: (f64, f64),
    numbering: (Numbering, Numbering),
) -> (Table, String) {
    let n2 = traj.mesh().driven().teeth();
    let mut events = Table::new(
        "Events (kind from the contact motion, and what the rule counts it as)",
        [
            "phi - phi0 [deg]",
            "phi [deg]",
            "kind",
            "counted as",
            "driver tooth",
            "driven tooth",
            "theta - theta0 [deg]",
            "theta after - theta0 [deg]",
            "size",
            "motion",
        ],
    );
    let mut ev_rows = String::from(
        "phi_minus_phi0_deg,kind,counted_as,driver_tooth,driven_tooth,theta_minus_theta0_deg,theta_after_minus_theta0_deg,lost_motion_pitches,resumed,phase_shift,lag_deg,wedge_angle_deg,phi_abs_deg,theta_abs_deg,theta_after_abs_deg,ahead_of_ideal_driven_pitches,after_first_lock,release_phi_minus_phi0_deg,release_theta_abs_deg\n",
    );
    let first = presentation::pair_html::first_lock(traj.events());
    for (i, e) in traj.events().iter().enumerate() {
        let counted = counted_as(rule, e);
        let teeth = user_teeth(e, numbering);
        let mut fields = log_line(e, counted, &teeth, start).to_vec();
        fields.extend(protocol_cells(
            traj,
            e,
            first.is_some_and(|f| i > f),
            start.0,
        ));
        ev_rows.push_str(&registry::csv_line(fields));
        if events.rows.len() < EVENTS_SHOWN {
            let mut row = table_row(e, counted, &teeth, start, n2);
            row.push(presentation::pair_html::motion_word(i, first).into());
            events.row(row);
        }
    }
    add_event_notes(&mut events, traj);
    // The table is an excerpt of event-log.csv: the run writes the events once.
    (events.data_in("event-log.csv"), ev_rows)
}

/// An event's driver and driven tooth as the user wrote them (a driven gear measured in its own
/// sense is numbered the other way round inside the solver); none (empty) for an idle start.
fn user_teeth(e: &contact::Event, (driver, driven): (Numbering, Numbering)) -> (String, String) {
    if presentation::pair_html::is_idle_start(e) {
        (String::new(), String::new())
    } else {
        (
            driver.user(e.driver_tooth).to_string(),
            driven.user(e.driven_tooth).to_string(),
        )
    }
}

/// An event's line of `event-log.csv`, as its cells.
fn log_line(
    e: &contact::Event,
    counted: &str,
    (j, k): &(String, String),
    (phi0, theta0): (f64, f64),
) -> [String; 15] {
    [
        format!("{:.9}", deg(e.phi - phi0)),
        e.label().to_string(),
        counted.to_string(),
        j.clone(),
        k.clone(),
        format!("{:.9}", deg(e.theta - theta0)),
        format!("{:.9}", deg(e.theta_after - theta0)),
        format!("{:.9}", e.lost_motion),
        e.resumed.to_string(),
        e.phase_shift.to_string(),
        format!("{:.9}", deg(e.lag)),
        e.wedge_angle
            .map_or_else(String::new, |a| format!("{:.9}", deg(a))),
        format!("{:.9}", deg(e.phi)),
        format!("{:.9}", deg(e.theta)),
        format!("{:.9}", deg(e.theta_after)),
    ]
}

/// The cells `event-log.csv` adds after [`log_line`]'s: how far the event
/// left the driven gear ahead of the ideal ratio (driven pitches), whether it came after the
/// first lock (the paper's protocol), and where a release let the gear go (empty without one).
fn protocol_cells(
    traj: &contact::Trajectory,
    e: &contact::Event,
    after: bool,
    phi0: f64,
) -> Vec<String> {
    let n2 = traj.mesh().driven().teeth();
    let (release_phi, release_theta) = presentation::pair_html::release_of(traj, e).map_or_else(
        || (String::new(), String::new()),
        |r| {
            (
                format!("{:.9}", deg(r.phi - phi0)),
                format!("{:.9}", deg(r.theta)),
            )
        },
    );
    vec![
        format!("{:.9}", presentation::pair_html::ahead_pitches(e, n2)),
        after.to_string(),
        release_phi,
        release_theta,
    ]
}

/// An event's row of the printed table (`-` for a tooth it has none of).
fn table_row(
    e: &contact::Event,
    counted: &str,
    (j, k): &(String, String),
    (phi0, theta0): (f64, f64),
    n2: usize,
) -> Vec<String> {
    let shown = |t: &str| {
        if t.is_empty() {
            "-".to_string()
        } else {
            t.to_string()
        }
    };
    vec![
        fmt_f64(deg(e.phi - phi0), 6),
        fmt_f64(deg(e.phi), 6),
        e.label().into(),
        counted.into(),
        shown(j),
        shown(k),
        fmt_f64(deg(e.theta - theta0), 6),
        fmt_f64(deg(e.theta_after - theta0), 6),
        presentation::pair_html::size_text(e, n2),
    ]
}

/// The notes under the event table: the angles, what is not shown, and what the events need
/// explained (a lock's release, an idle start, the pictures).
fn add_event_notes(events: &mut Table, traj: &contact::Trajectory) {
    events.note(presentation::pair_html::ANGLES_NOTE);
    if traj.events().len() > EVENTS_SHOWN {
        events.note(format!(
            "{} more in event-log.csv (every event, one a line)",
            traj.events().len() - EVENTS_SHOWN
        ));
    }
    if traj
        .events()
        .iter()
        .any(|e| e.kind.is_contact_stop() && presentation::pair_html::moves_pointer(e))
    {
        events.note(presentation::pair_html::RELEASE_NOTE);
    }
    if let Some(n) =
        presentation::pair_html::releases_note(traj.events(), traj.mesh().driven().teeth())
    {
        events.note(n);
    }
    if presentation::pair_html::first_lock(traj.events()).is_some() {
        events.note(presentation::pair_html::MOTION_NOTE);
        events.note(presentation::pair_html::PROTOCOL_NOTE);
    }
    if traj
        .events()
        .iter()
        .any(presentation::pair_html::is_idle_start)
    {
        events.note("An idle start has no driver or driven tooth (`-`): no tooth touches the driven gear; its picture shows where the two gears come nearest.");
    }
    if let Some(n) = presentation::event_picture::pictures_note(traj.events().len()) {
        events.note(n);
    }
    if traj.events().is_empty() {
        events.note("no event: the driven gear was driven throughout");
    }
}

/// The note under the summary table: the frames of the absolute angles.
const ABSOLUTE_NOTE: &str = "absolute angles: phi is how far the driver's zero ray (its tips_deg = 0) has turned, in the driver's turning sense, from pointing along the line of centres at the driven gear; theta is how far the driven gear's zero ray has turned, in its own turning sense, from pointing at the driver; pair.csv has both relative to the start (phi_minus_phi0_deg, theta_minus_theta0_deg) and absolute (phi_abs_deg, theta_abs_deg)";

#[cfg(test)]
#[path = "../plugin_tests/pair.rs"]
mod tests;
