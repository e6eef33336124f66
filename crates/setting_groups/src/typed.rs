//! The typed form of the shared setting groups: what an experiment written as a
//! [`registry::Experiment`] reads its cells and labels from, given its settings struct.

use registry::{Report, RunError, Settings};
use study::drive::DriveParams;
use study::errors::ErrorParams;
use study::events::EventParams;
use study::gearing::{GearingParams, ShapeParams};
use study::grids::CellSettings;

/// The gearing of a jam table: with G (the gearing group) or without (the shape, the
/// experiment choosing its clearances itself).
pub enum Gearing<'a> {
    /// The gearing group: the gearing, h and G.
    WithClearance(&'a GearingParams),
    /// The gearing and h only.
    Shape(&'a ShapeParams),
}

/// What every table of jam cells reads first ([`CellSettings`]): the gearing and h (G where
/// the experiment declares it), the error group with its split, the event rule (the default
/// where the experiment declares none), which gear drives (the listed one where it declares
/// no `drive`), where counting ends, and `trials` per cell; `whole` is the experiment's
/// settings (whose values a hypothesis' parameters are checked against).
pub fn cells<S: Settings>(
    gearing: Gearing<'_>,
    errors: &study::errors::CaseParams,
    events: Option<&EventParams>,
    drive: Option<&DriveParams>,
    trials: u64,
    whole: &S,
) -> Result<CellSettings, RunError> {
    loaded_cells(gearing, errors.load(whole)?, events, drive, trials)
}

/// `report` with every table's title naming the event rule of the run, and the drive and end
/// where the experiment takes them ([`study::events::label`]).
pub fn label(
    events: &EventParams,
    drive: Option<&DriveParams>,
    report: Report,
) -> Result<Report, RunError> {
    let protocol = match drive {
        Some(d) => Some((d.drive()?, d.end()?)),
        None => None,
    };
    Ok(study::events::label(&events.rule()?, protocol, report))
}

/// The inputs in which settings `s` depart from the paper's (`name=value`): where any does,
/// no cell is compared with the paper's counts.
pub fn off_paper_inputs<S: Settings>(s: &S) -> Vec<String> {
    s.departures()
        .into_iter()
        .map(|(p, value)| format!("{}={value}", p.name))
        .collect()
}

/// [`cells`] for an experiment whose error group has no split ([`ErrorParams`]: a random
/// error alone, as Table 4 and what reads its grid run it).
pub fn unsplit_cells<S: Settings>(
    gearing: Gearing<'_>,
    errors: &ErrorParams,
    events: Option<&EventParams>,
    drive: Option<&DriveParams>,
    trials: u64,
    whole: &S,
) -> Result<CellSettings, RunError> {
    loaded_cells(gearing, errors.load(None, whole)?, events, drive, trials)
}

/// The cells' settings with the error group already loaded (with or without its split).
fn loaded_cells(
    gearing: Gearing<'_>,
    errors: study::errors::Settings,
    events: Option<&EventParams>,
    drive: Option<&DriveParams>,
    trials: u64,
) -> Result<CellSettings, RunError> {
    let (shape, clearance) = match gearing {
        Gearing::WithClearance(g) => (g.shape().load()?, Some(g.clearance)),
        Gearing::Shape(s) => (s.load()?, None),
    };
    Ok(CellSettings {
        gearing: shape,
        clearance,
        errors,
        rule: match events {
            Some(e) => e.rule()?,
            None => study::events::default_rule()?,
        },
        drive: drive.map_or(Ok(study::drive::Drive::Listed), DriveParams::drive)?,
        end: drive.map_or(Ok(study::trial_end::End::Turn), DriveParams::end)?,
        trials,
    })
}
