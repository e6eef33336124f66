//! The files a run reads, named by its parameters (a gearing file, measured-error tables), and
//! their checks before anything runs: each must read and pass its rules, and a measured table
//! must name only gears of the gearing it is run with. The runner calls these for every
//! experiment it is about to run, knowing nothing of gearings or hypotheses itself.

use std::collections::BTreeSet;
use std::path::Path;

use registry::Context;
use train::Gearing;

/// The name both `failure` and `fig6` give their measured-errors table: each declares its own
/// `measured` (with its own help), and the runner checks the file whichever declares it.
pub const MEASURED: &str = "measured";

/// The value of the parameter called `name` where the experiment declares one: the runner
/// checks every experiment's inputs knowing nothing of their declarations (`failure` and `fig6`
/// each declare their own `measured`, with help of their own).
fn value(ctx: &Context, name: &str) -> Option<String> {
    ctx.values()
        .find(|(p, _)| p.name == name)
        .map(|(_, v)| v.to_owned())
}

/// The measured-error tables the `hypothesis` parameter names (its `measured:FILE` layers).
pub fn measured_in_hypothesis(hypothesis: &str) -> Vec<String> {
    hypotheses::stack_layers(hypothesis)
        .into_iter()
        .filter_map(|layer| layer.strip_prefix("measured:").map(str::to_owned))
        .collect()
}

/// The files this run reads, as (role, path): a gearing file (not an embedded gearing) and
/// every measured-error table, from the hypothesis or the `measured` parameter.
pub fn files(ctx: &Context) -> Vec<(&'static str, String)> {
    let mut files = Vec::new();
    if let Some(g) = value(ctx, study::gearing::PARAM.name)
        && Gearing::builtin(&g).is_none()
    {
        files.push(("gearing", g));
    }
    if let Some(h) = value(ctx, study::errors::PARAM.name) {
        files.extend(
            measured_in_hypothesis(&h)
                .into_iter()
                .map(|f| ("measured errors", f)),
        );
    }
    if let Some(m) = value(ctx, MEASURED)
        && hypotheses::measured_file_given(&m).is_some()
    {
        files.push(("measured errors", m.trim().to_owned()));
    }
    files
}

/// Checks, before anything runs, every gearing file, error hypothesis and measured-errors table
/// the run was given: each must read and pass its rules (refused naming the file, the line or
/// item and the rule), and a measured table must name only gears of the run's gearing. `flags`
/// names what the user typed: (`--hypothesis` or `--errors`, `--set measured` or `--errors`).
/// `seen` skips what an earlier experiment of the same run already checked.
pub fn check(
    ctx: &Context,
    flags: (&str, &str),
    seen: &mut BTreeSet<(&'static str, String)>,
) -> Result<(), String> {
    let (hypothesis_flag, measured_flag) = flags;
    if let Some(g) = value(ctx, study::gearing::PARAM.name)
        && g.trim().is_empty()
    {
        return Err(registry::RunError::bad(
            "--set",
            study::gearing::PARAM.name,
            "must name an embedded gearing (freeth2006, freeth2021, freeth2021-cosmos, freeth2012-cosmos) or a RON file, not be empty",
        )
        .to_string());
    }
    names_no_file(ctx)?;
    if let Some(g) = value(ctx, study::gearing::PARAM.name)
        && Gearing::builtin(&g).is_none()
        && seen.insert(("gearing", g.clone()))
    {
        // Named by the setting, as the other files a run reads are (`--errors: FILE: ...`).
        Gearing::load(Path::new(&g))
            .map_err(|e| format!("--set: {}: {e}", study::gearing::PARAM.name))?;
    }
    if let Some(h) = value(ctx, study::errors::PARAM.name)
        && seen.insert(("hypothesis", h.clone()))
    {
        hypotheses::lookup(&h).map_err(|e| format!("{hypothesis_flag}: {e}"))?;
    }
    if let Some(m) = value(ctx, MEASURED)
        && hypotheses::measured_file_given(&m).is_some()
        && seen.insert((MEASURED, m.clone()))
    {
        hypotheses::measured_file(m.trim()).map_err(|e| format!("{measured_flag}: {e}"))?;
    }
    measured_gears_in_gearing(ctx, flags)?;
    shared_settings(ctx)
}

/// A name typed for a setting that takes a built-in name or a file (`gearing=freeth2021`,
/// `measured=none`) must not also be a file where the run starts: the built-in would be used
/// and the file ignored without a word (the two may give different results). Refused naming the
/// setting, the name and the file, and how to say which is meant. A name left at its default is
/// not checked: the user asked for no file.
fn names_no_file(ctx: &Context) -> Result<(), String> {
    for (name, typed) in ctx.given() {
        let builtin = match name {
            n if n == study::gearing::PARAM.name => Gearing::builtin(typed.trim()).is_some(),
            MEASURED => {
                hypotheses::measured_file_given(typed).is_none() && !typed.trim().is_empty()
            }
            _ => false,
        };
        if !builtin {
            continue;
        }
        let path = Path::new(typed.trim());
        if std::fs::metadata(path).is_ok_and(|m| !m.is_dir()) {
            let here = std::env::current_dir()
                .map(|d| d.join(path).display().to_string())
                .unwrap_or_else(|_| typed.trim().to_owned());
            let what = if name == MEASURED {
                "the setting for no table"
            } else {
                "an embedded gearing"
            };
            return Err(registry::RunError::bad(
                "--set",
                name,
                format!(
                    "`{}` is both {what} and a file in this folder ({here}), so it is unclear which is meant: write ./{} (or the file's full path) to read the file, or rename or move the file to use the built-in `{}`",
                    typed.trim(),
                    typed.trim(),
                    typed.trim()
                ),
            )
            .to_string());
        }
    }
    Ok(())
}

/// The settings that setting groups share and every experiment declaring them reads the same
/// way, checked as the experiment would check them when it starts: the `events` rule must
/// parse, and the `mesh` must be a mesh of the gearing. With `run all` a bad value is refused
/// before the first experiment computes, not by each experiment in turn after others ran.
fn shared_settings(ctx: &Context) -> Result<(), String> {
    if ctx.holds(&study::events::PARAM) {
        crate::read::rule(ctx).map_err(|e| e.to_string())?;
    }
    // The gearing's clearance, large enough for the solver to tell from touching.
    if ctx.holds(&study::gearing::CLEARANCE)
        && ctx.holds(&study::gearing::TOOTH_HEIGHT)
        && let Some(name) = value(ctx, study::gearing::PARAM.name)
    {
        let g = match Gearing::builtin(&name) {
            Some(g) => g,
            None => Gearing::load(Path::new(&name)).map_err(|e| e.to_string())?,
        };
        let read = |p: &registry::Param| ctx.get::<f64>(p).map_err(|e| e.to_string());
        let (h, clearance) = (
            read(&study::gearing::TOOTH_HEIGHT)?,
            read(&study::gearing::CLEARANCE)?,
        );
        study::gearing::check_clearance(&g, h, clearance, study::gearing::CLEARANCE.name)
            .map_err(|e| e.to_string())?;
    }
    if let Some(label) = value(ctx, study::limits::MESH.name)
        && let Some(gearing) = value(ctx, study::gearing::PARAM.name)
    {
        let g = match Gearing::builtin(&gearing) {
            Some(g) => g,
            None => Gearing::load(Path::new(&gearing)).map_err(|e| e.to_string())?,
        };
        if !g.meshes().iter().any(|m| m.label == label) {
            return Err(registry::RunError::bad(
                "--set",
                study::limits::MESH.name,
                format!("no mesh `{label}` in the gearing"),
            )
            .to_string());
        }
    }
    Ok(())
}

/// A measured-errors table given to an experiment that builds a gearing must name only gears of
/// that gearing: a row for another gear (a typo, another gearing's name) would be silently
/// unused. Refused naming the flag, the file, the gear and the gearing.
fn measured_gears_in_gearing(ctx: &Context, flags: (&str, &str)) -> Result<(), String> {
    let Some(gearing_name) = value(ctx, study::gearing::PARAM.name) else {
        return Ok(());
    };
    let from_hypothesis = value(ctx, study::errors::PARAM.name)
        .and_then(|h| measured_in_hypothesis(&h).into_iter().next());
    let (file, flag) = match (from_hypothesis, value(ctx, MEASURED)) {
        (Some(f), _) => (f, flags.0),
        (None, Some(m)) if hypotheses::measured_file_given(&m).is_some() => {
            (m.trim().to_owned(), flags.1)
        }
        _ => return Ok(()),
    };
    let Ok(h) = hypotheses::measured_file(&file) else {
        return Ok(()); // refused by `check` with its own message
    };
    let gearing = match Gearing::builtin(&gearing_name) {
        Some(g) => g,
        None => Gearing::load(Path::new(&gearing_name)).map_err(|e| e.to_string())?,
    };
    for (gear, _) in h.table().entries() {
        if gearing.gear(gear).is_none() {
            return Err(format!(
                "{flag}: {file}: gear {gear}: is not a gear of the gearing `{gearing_name}` ({} gears, e.g. {}), so its row would be silently unused",
                gearing.gears().len(),
                gearing
                    .gears()
                    .iter()
                    .take(3)
                    .map(|g| g.name.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ));
        }
    }
    // Every gear the run makes needs a row (the hypothesis refuses a gear without one, but only
    // once the run reaches it, after other Cases or experiments have been computed): the gears
    // of every mesh, or of the one mesh the run studies.
    let meshes: Vec<&train::MeshData> = match value(ctx, study::limits::MESH.name) {
        Some(label) => gearing
            .meshes()
            .iter()
            .filter(|m| m.label == label)
            .collect(),
        None => gearing.meshes().iter().collect(),
    };
    let listed: BTreeSet<&str> = h.table().entries().map(|(g, _)| g).collect();
    if let Some(gear) = meshes
        .iter()
        .flat_map(|m| [m.driver.as_str(), m.driven.as_str()])
        .find(|g| !listed.contains(g))
    {
        return Err(format!(
            "{flag}: {file}: gear {gear}: missing from the table: every gear the run makes needs a row (the gearing `{gearing_name}` meshes {gear})"
        ));
    }
    Ok(())
}
