//! The setting groups several experiments share, read once from the run's [`Context`] into the
//! structs `study` takes (`study` never sees a context): the gearing group (file, h, G), the
//! error group (hypothesis, its parameters, the split), the event rule, a jam table's cell
//! settings, the tolerance grids and rule. Each value is read by its declaration in `study`.

use hypotheses::Hypothesis;
use registry::{Context, Param, Report, RunError};
use rules::Rule;
use study::drive::Drive;
use study::grids::CellSettings;
use study::{drive, equal_pair, errors, events, gearing, limits, tolerance};

/// The gearing and its tooth height ([`gearing::SHAPE`]): loaded, and h checked against it.
pub fn shape(ctx: &Context) -> Result<gearing::Shape, RunError> {
    shape_with(ctx, &gearing::TOOTH_HEIGHT)
}

/// [`shape`] with the experiment's own tooth-height parameter `h` (one with its own help, e.g.
/// `clearance`'s "for both gears").
pub fn shape_with(ctx: &Context, h: &Param) -> Result<gearing::Shape, RunError> {
    gearing::Shape::load(ctx.text(&gearing::PARAM)?, ctx.get(h)?)
}

/// The gearing group ([`gearing::GROUP`]): the gearing, h and the clearance G of every mesh.
pub fn gearing(ctx: &Context) -> Result<gearing::Settings, RunError> {
    Ok(gearing::Settings::new(
        shape(ctx)?,
        ctx.get(&gearing::CLEARANCE)?,
    ))
}

/// The hypothesis the `hypothesis` parameter names.
pub fn hypothesis(ctx: &Context) -> Result<&'static dyn Hypothesis, RunError> {
    errors::lookup(ctx.text(&errors::PARAM)?)
}

/// The error group: the hypothesis ([`hypothesis`]), `hypothesis_params` parsed and the split
/// where the experiment declares it.
pub fn errors(ctx: &Context) -> Result<errors::Settings, RunError> {
    errors_for(ctx, hypothesis(ctx)?)
}

/// [`errors()`] with the hypothesis chosen by the experiment (one of its rows).
pub fn errors_for(
    ctx: &Context,
    hypothesis: &'static dyn Hypothesis,
) -> Result<errors::Settings, RunError> {
    let split = if ctx.holds(&errors::SPLIT) {
        Some(ctx.get(&errors::SPLIT)?)
    } else {
        None
    };
    let changed = ctx
        .changed()
        .into_iter()
        .map(|(k, v)| (k, v.to_owned()))
        .collect();
    errors::Settings::new(
        hypothesis,
        ctx.text(&errors::PARAMS_PARAM)?,
        split,
        changed,
        ctx.names(),
    )
}

/// The event rule the `events` parameter names.
pub fn rule(ctx: &Context) -> Result<Rule, RunError> {
    events::parse(ctx.text(&events::PARAM)?)
}

/// Which gear of each mesh drives ([`drive::GROUP`]): the listed driver where the experiment
/// declares no `drive`.
pub fn drive(ctx: &Context) -> Result<Drive, RunError> {
    if ctx.holds(&drive::PARAM) {
        Drive::parse(ctx.text(&drive::PARAM)?)
    } else {
        Ok(Drive::Listed)
    }
}

/// Where a pair trial's counting ends ([`study::trial_end`]): the whole turn where the
/// experiment declares no `end`.
pub fn trial_end(ctx: &Context) -> Result<study::trial_end::End, RunError> {
    if ctx.holds(&study::trial_end::PARAM) {
        study::trial_end::End::parse(ctx.text(&study::trial_end::PARAM)?)
    } else {
        Ok(study::trial_end::End::Turn)
    }
}

/// What every table of jam cells reads first ([`CellSettings`]): the gearing and h, G where the
/// experiment declares it, the error group, the event rule (the default where the experiment
/// declares none), which gear drives (the listed one where it declares no `drive`) and the
/// trials per cell, parameter `trials`.
pub fn cells(ctx: &Context, trials: &Param) -> Result<CellSettings, RunError> {
    let gearing = shape(ctx)?;
    let clearance = if ctx.holds(&gearing::CLEARANCE) {
        Some(ctx.get(&gearing::CLEARANCE)?)
    } else {
        None
    };
    let errors = errors(ctx)?;
    let rule = if ctx.holds(&events::PARAM) {
        rule(ctx)?
    } else {
        events::default_rule()?
    };
    Ok(CellSettings {
        gearing,
        clearance,
        errors,
        rule,
        drive: drive(ctx)?,
        end: trial_end(ctx)?,
        trials: ctx.get(trials)?,
    })
}

/// The list of clearances (% of h) parameter `p` holds, each above 0 and at most `max`.
pub fn clearance_list(ctx: &Context, p: &Param, max: f64) -> Result<Vec<f64>, RunError> {
    gearing::clearance_list(ctx.text(p)?, p.name, max)
}

/// The grid from..=to by step the three parameters hold ([`tolerance::grid`]).
pub fn grid(ctx: &Context, from: &Param, to: &Param, step: &Param) -> Result<Vec<f64>, RunError> {
    let changed: Vec<&str> = ctx.changed().into_iter().map(|(k, _)| k).collect();
    tolerance::grid(
        (from, ctx.get(from)?),
        (to, ctx.get(to)?),
        (step, ctx.get(step)?),
        &changed,
    )
}

/// The random-error grid ([`tolerance::RANDOM_GRID`], Table 4's rows).
pub fn random_grid(ctx: &Context) -> Result<Vec<f64>, RunError> {
    grid(
        ctx,
        &tolerance::RANDOM_FROM,
        &tolerance::RANDOM_TO,
        &tolerance::RANDOM_STEP,
    )
}

/// The systematic-error grid ([`tolerance::SYSTEMATIC_GRID`], Table 5's rows).
pub fn systematic_grid(ctx: &Context) -> Result<Vec<f64>, RunError> {
    grid(
        ctx,
        &tolerance::SYSTEMATIC_FROM,
        &tolerance::SYSTEMATIC_TO,
        &tolerance::SYSTEMATIC_STEP,
    )
}

/// The paper's pair of equal gears ([`equal_pair::GROUP`]), built.
pub fn equal_pair(ctx: &Context) -> Result<equal_pair::EqualPair, RunError> {
    equal_pair::build(
        ctx.get(&equal_pair::TEETH)?,
        ctx.get(&equal_pair::TIP_RADIUS)?,
        ctx.get(&equal_pair::ROOT_RADIUS)?,
        ctx.get(&equal_pair::CENTRE_DISTANCE)?,
    )
}

/// The ideal pair of the mesh the `mesh` parameter names, of gearing `g` with teeth of height `h`.
pub fn ideal_pair(
    ctx: &Context,
    g: &train::Gearing,
    h: f64,
) -> Result<limits::IdealPair, RunError> {
    limits::IdealPair::named(ctx.text(&limits::MESH)?, g, h)
}

/// (pointer, input turns) for each (pointer, run-length parameter).
pub fn turns<'a>(
    ctx: &Context,
    pointers: &[(&'a str, &Param)],
) -> Result<Vec<(&'a str, f64)>, RunError> {
    pointers
        .iter()
        .map(|&(name, p)| Ok((name, ctx.get(p)?)))
        .collect()
}

/// Runs `experiment` and names the event rule in its tables' titles, and which gear drove where
/// the experiment takes `drive` ([`events::label`]): how an experiment that counts events
/// registers its `run`.
pub fn labelled(
    ctx: &Context,
    experiment: fn(&Context) -> Result<Report, RunError>,
) -> Result<Report, RunError> {
    let report = experiment(ctx)?;
    label(ctx, report)
}

/// `report` with every table's title naming the event rule of the run, and the drive where the
/// experiment takes one ([`events::label`]).
pub fn label(ctx: &Context, report: Report) -> Result<Report, RunError> {
    let protocol = if ctx.holds(&drive::PARAM) {
        Some((drive(ctx)?, trial_end(ctx)?))
    } else {
        None
    };
    Ok(events::label(&rule(ctx)?, protocol, report))
}

/// The typed form of the groups above: what an experiment written as a [`registry::Experiment`]
/// reads its cells and labels from, given its settings struct.
pub mod typed {
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
}
