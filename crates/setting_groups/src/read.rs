//! The setting groups several experiments share, read from a run's [`Context`] by their
//! declarations in `study` into the structs `study` takes (`study` never sees a context): the
//! gearing (file, h), the error group (hypothesis, its parameters, the split), the event rule,
//! a jam table's cell settings, the tolerance grids. What the runner's checks of a run's inputs
//! and `replay`'s reading of a table's cells go through; an experiment reads its own settings
//! struct ([`crate::typed`]).

use hypotheses::Hypothesis;
use registry::{Context, Param, RunError};
use rules::Rule;
use study::drive::Drive;
use study::grids::CellSettings;
use study::{drive, errors, events, gearing, tolerance};

/// The gearing and its tooth height ([`gearing::SHAPE`]): loaded, and h checked against it.
pub fn shape(ctx: &Context) -> Result<gearing::Shape, RunError> {
    shape_with(ctx, &gearing::TOOTH_HEIGHT)
}

/// [`shape`] with the experiment's own tooth-height parameter `h` (one with its own help, e.g.
/// `clearance`'s "for both gears").
pub fn shape_with(ctx: &Context, h: &Param) -> Result<gearing::Shape, RunError> {
    gearing::Shape::load(ctx.text(&gearing::PARAM)?, ctx.get(h)?)
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
