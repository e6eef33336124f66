//! Choosing what to run and checking it first: experiment ids, `--set` and its shorthands, the config file, the inputs a run will read, `--out`.

use std::path::{Path, PathBuf};

use registry::{ConfigFile, Context, Entry, RunError};

use crate::args::RunArgs;
use crate::failure::Failure;
use crate::help::known;
use crate::progress;
use crate::shared::{Registry, default_out};

pub(crate) fn lookup(exps: &Registry, id: &str) -> Result<&'static Entry, Failure> {
    exps.get(id)
        .copied()
        .ok_or_else(|| Failure::Bad(format!("unknown experiment `{id}` ({})", known(exps))))
}

/// The experiments `ids` names, in order, without repeats (`run all` is handled by [`crate::execute::run_every`]).
pub(crate) fn select(exps: &Registry, ids: &[String]) -> Result<Vec<&'static Entry>, Failure> {
    let mut chosen: Vec<&'static Entry> = Vec::new();
    for id in ids {
        let e = lookup(exps, id)?;
        if !chosen.iter().any(|c| c.id == e.id) {
            chosen.push(e);
        }
    }
    Ok(chosen)
}

/// The file given with `--config`, read.
pub(crate) fn read_config(run: &RunArgs) -> Result<Option<ConfigFile>, Failure> {
    match &run.config {
        None => Ok(None),
        Some(path) => {
            let text =
                input_file::read_to_string(path, input_file::MAX_INPUT_BYTES).map_err(|e| {
                    Failure::Bad(format!("--config: {}: cannot read: {e}", path.display()))
                })?;
            Ok(Some(ConfigFile {
                path: path.clone(),
                text,
            }))
        }
    }
}

/// With several experiments each gets the `--set` keys it declares, but every key must be someone's.
pub(crate) fn check_sets(
    chosen: &[&'static Entry],
    sets: &[(String, String)],
) -> Result<(), Failure> {
    for (key, _) in sets {
        if !chosen.iter().any(|e| e.all_params().any(|p| p.name == key)) {
            return Err(Failure::Bad(format!(
                "--set: {key}: no selected experiment has this parameter"
            )));
        }
    }
    Ok(())
}

pub(crate) fn declares(e: &Entry, name: &str) -> bool {
    e.all_params().any(|p| p.name == name)
}

/// The `--set` pairs `e` declares.
pub(crate) fn declared_sets(e: &Entry, sets: &[(String, String)]) -> Vec<(String, String)> {
    sets.iter()
        .filter(|(k, _)| declares(e, k))
        .cloned()
        .collect()
}

/// The shorthand flags given, as (flag, the parameter it sets in `e`, value) for an experiment
/// `e`; `None` where `e` declares no parameter the flag sets.
pub(crate) fn shorthands(
    e: &Entry,
    run: &RunArgs,
) -> Vec<(&'static str, Option<(String, String)>)> {
    let mut out = Vec::new();
    let mut add = |flag: &'static str, key: &str, value: String| {
        out.push((flag, declares(e, key).then(|| (key.to_owned(), value))));
    };
    if let Some(n) = run.trials {
        add("--trials", "trials", n.to_string());
    }
    if let Some(g) = &run.gearing {
        add("--gearing", "gearing", g.display().to_string());
    }
    if let Some(h) = &run.hypothesis {
        add("--hypothesis", "hypothesis", h.clone());
    }
    if let Some(file) = &run.errors {
        let file = file.display().to_string();
        if declares(e, "measured") {
            add("--errors", "measured", file);
        } else {
            add("--errors", "hypothesis", format!("measured:{file}"));
        }
    }
    out
}

/// Every shorthand flag given must reach at least one of `chosen`.
pub(crate) fn check_shorthands(chosen: &[&'static Entry], run: &RunArgs) -> Result<(), Failure> {
    let Some(first) = chosen.first() else {
        return Ok(());
    };
    for (i, (flag, _)) in shorthands(first, run).into_iter().enumerate() {
        if !chosen.iter().any(|e| shorthands(e, run)[i].1.is_some()) {
            let wanted = match flag {
                "--trials" => "a `trials` parameter",
                "--gearing" => "a `gearing` parameter",
                "--hypothesis" => "a `hypothesis` parameter",
                _ => "a `measured` or `hypothesis` parameter",
            };
            let ids: Vec<&str> = chosen.iter().map(|e| e.id).collect();
            return Err(Failure::Bad(format!(
                "{flag}: no selected experiment has {wanted} (selected: {})",
                ids.join(", ")
            )));
        }
    }
    Ok(())
}

/// One selected experiment, ready to run: its context and the `--set` pairs it was given
/// (recorded in a shard's partial file).
pub(crate) struct Planned {
    pub(crate) e: &'static Entry,
    pub(crate) ctx: Context,
    pub(crate) sets: Vec<(String, String)>,
}

/// The contexts of `chosen`. `alone`: one experiment named on its own, which gets every `--set`
/// pair (an unknown key is refused naming its keys); otherwise each gets the keys it declares,
/// and every key must be someone's. Then the shorthands each declares; the config file goes to
/// those that take one. Everything the user gave is checked here, before anything runs:
/// [`preflight`].
pub(crate) fn plan(
    chosen: &[&'static Entry],
    run: &RunArgs,
    config: Option<&ConfigFile>,
    alone: bool,
    threads: usize,
) -> Result<Vec<Planned>, Failure> {
    if !alone {
        check_sets(chosen, &run.sets)?;
    }
    check_shorthands(chosen, run)?;
    let mut planned = Vec::with_capacity(chosen.len());
    for &e in chosen {
        let mut sets = if alone {
            run.sets.clone()
        } else {
            declared_sets(e, &run.sets)
        };
        sets.extend(shorthands(e, run).into_iter().filter_map(|(_, s)| s));
        let file = config.filter(|_| e.config.is_some()).cloned();
        let ctx = Context::new(e, run.seed, threads, &sets, file).map_err(|err| {
            let err = as_typed(err, e.id, run);
            if alone { err } else { of_experiment(err, e.id) }
        })?;
        let ctx = progress::attach(ctx);
        planned.push(Planned { e, ctx, sets });
    }
    preflight(&planned, run)?;
    // Every experiment's settings read and checked across their fields (a grid's end below its
    // start, a tolerance named twice) before any of them computes.
    for p in &planned {
        p.e.check_settings(&p.ctx).map_err(|err| {
            let err = as_typed(err, p.e.id, run);
            if alone {
                err
            } else {
                of_experiment(err, p.e.id)
            }
        })?;
    }
    // What runs but is probably not what was meant, said before it runs.
    for p in &planned {
        for w in crate::hints::warnings(p.e, &p.sets, p.ctx.config()) {
            progress::note(&w);
        }
    }
    Ok(planned)
}

/// Checks, before anything runs, what would otherwise fail only when an experiment reaches it
/// (and with `all`, after others had written their results): `--out` must not be a file, and
/// every gearing file, error hypothesis and measured-errors table the experiments were given
/// must read and pass its rules. Each is refused naming the file, the line or item and the rule.
pub(crate) fn preflight(planned: &[Planned], run: &RunArgs) -> Result<(), Failure> {
    let targets: Vec<Target> = match run.shard {
        Some(shard) => planned
            .iter()
            .map(|p| {
                Target::File(
                    format!("{}/{}", p.e.id, crate::shard::partial::file_name(shard)),
                    &crate::shard::partial::KIND,
                )
            })
            .collect(),
        None => planned
            .iter()
            .map(|p| Target::Results(p.e.id.to_owned()))
            .chain(
                run.is_all()
                    .then(|| {
                        [
                            Target::File("summary.md".into(), &crate::summary::MARKDOWN_KIND),
                            Target::File("summary.json".into(), &crate::summary::JSON_KIND),
                        ]
                    })
                    .into_iter()
                    .flatten(),
            )
            .collect(),
    };
    check_out(&run.out.clone().unwrap_or_else(default_out), &targets)?;
    let mut seen = std::collections::BTreeSet::new();
    // The flags the user typed, for the messages: `--errors` stands for both.
    let flags = if run.errors.is_some() {
        ("--errors", "--errors")
    } else {
        ("--hypothesis", "--set measured")
    };
    for p in planned {
        setting_groups::inputs::check(&p.ctx, flags, &mut seen)
            .map_err(|m| Failure::Bad(typed_flag(m, run)))?;
    }
    Ok(())
}

/// A refusal `msg` of `--set gearing` or `--set measured` said of the shorthand the user typed
/// for it (`--gearing`, `--errors`).
fn typed_flag(msg: String, run: &RunArgs) -> String {
    for (given, set, flag) in [
        (run.gearing.is_some(), "--set: gearing: ", "--gearing: "),
        (run.errors.is_some(), "--set: measured: ", "--errors: "),
    ] {
        if given && let Some(rest) = msg.strip_prefix(set) {
            return format!("{flag}{rest}");
        }
    }
    msg
}

/// What a command writes under `--out`, for [`check_out`] to check before anything is computed.
pub(crate) enum Target {
    /// `<out>/<id>`: an experiment's results, which replace the previous ones whole.
    Results(String),
    /// A file, as a path relative to `<out>`: `summary.md`, `index.html`, a shard's partial
    /// file; what is there must be a file of its kind ([`registry::check_replace`]).
    File(String, &'static registry::FileKind),
}

/// Checks, before anything is computed, that results can be written under `out` (`--out`,
/// [`writable_dir`]). Then puts back results a killed run left moved aside
/// ([`registry::tidy`]) and checks each of `targets`: a results folder `<out>/<id>` that exists
/// must be a directory whose previous results can be moved aside and removed, and a file must
/// not be a directory or lie below something that is not one. Refused (exit 2) naming `--out`,
/// the target and the reason; nothing is left behind by the check.
pub(crate) fn check_out(out: &Path, targets: &[Target]) -> Result<(), Failure> {
    let refuse = |why: String| Failure::Bad(format!("--out: {}: {why}", out.display()));
    writable_dir("--out", out)?;
    registry::tidy(out)?;
    check_targets(out, targets, &refuse)?;
    lock_targets(out, targets, &refuse)
}

/// Takes the run lock of every target ([`registry::lock_writing`]) for the rest of the run, so
/// that a second run writing the same results into the same `--out` is refused now, before it
/// computes anything, instead of replacing this one's results at the end without a word.
fn lock_targets(
    out: &Path,
    targets: &[Target],
    refuse: &dyn Fn(String) -> Failure,
) -> Result<(), Failure> {
    for t in targets {
        let (parent, name, shown) = match t {
            Target::Results(id) => (out.to_path_buf(), id.clone(), id.clone()),
            Target::File(rel, _) => {
                let path = out.join(rel);
                let name = path
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default();
                let parent = path
                    .parent()
                    .map_or_else(|| out.to_path_buf(), Path::to_path_buf);
                (parent, name, rel.clone())
            }
        };
        let what = format!(
            "a run writing {shown}, started {}",
            crate::provenance::utc_now()
        );
        if let Some(holder) = registry::lock_writing(&parent, &name, &what)? {
            return Err(refuse(format!(
                "{shown}: another run is writing there now ({holder}); two runs into one --out would leave only one's results: wait for it to end, or give another --out"
            )));
        }
    }
    Ok(())
}

/// Checks, before anything is computed, that files can be written in the folder `dir` given
/// with `flag` (`--out`, `--findings`): it is a directory, or can be created as one (every
/// missing folder on the way is created, by its name, inside a probe folder of this process and
/// removed again: a name the file system refuses, e.g. longer than it takes, is found here),
/// and a folder can be created in it. Refused (exit 2) naming the flag, the folder and the
/// reason; nothing is left behind.
pub(crate) fn writable_dir(flag: &str, out: &Path) -> Result<(), Failure> {
    let refuse = |why: String| Failure::Bad(format!("{flag}: {}: {why}", out.display()));
    if out.exists() && !out.is_dir() {
        return Err(refuse("exists and is not a directory".into()));
    }
    // The nearest folder that exists: where the first thing would be created. A path that
    // cannot be looked at for another reason than its absence (a loop of symbolic links) is
    // refused with that reason.
    let mut base = out.to_path_buf();
    let mut missing = Vec::new();
    while !base.as_os_str().is_empty() {
        match std::fs::symlink_metadata(&base) {
            Ok(_) => break,
            // Missing, below a file (said of the file below), or a name the probe below finds
            // too long.
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::NotFound
                        | std::io::ErrorKind::NotADirectory
                        | std::io::ErrorKind::InvalidFilename
                ) => {}
            Err(e) => return Err(refuse(format!("cannot be inspected ({e})"))),
        }
        missing.push(base.clone());
        base = base.parent().map(Path::to_path_buf).unwrap_or_default();
    }
    if base.as_os_str().is_empty() {
        base = PathBuf::from(".");
    }
    match std::fs::metadata(&base) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => {
            return Err(refuse(format!(
                "cannot be created: {} is not a directory",
                base.display()
            )));
        }
        Err(e) => {
            return Err(refuse(format!(
                "cannot be created: {} cannot be followed ({e})",
                base.display()
            )));
        }
    }
    // A probe folder in the nearest existing one, and in it the missing folders by their names,
    // as writing would create them; then all removed. The probe is this process's own, so runs
    // checking the same new `--out` at once (shards starting together) never meet.
    let probe = probe_name(&base, "out");
    std::fs::create_dir(&probe).map_err(|e| {
        refuse(format!(
            "cannot write results there (creating a folder in {} fails: {e})",
            base.display()
        ))
    })?;
    let mut inside = probe.clone();
    let mut failed = None;
    for dir in missing.iter().rev() {
        let Some(name) = dir.file_name() else {
            continue;
        };
        inside.push(name);
        if let Err(e) = std::fs::create_dir(&inside) {
            failed = Some(format!("cannot be created ({}: {e})", dir.display()));
            break;
        }
    }
    let _ = std::fs::remove_dir_all(&probe);
    match failed {
        Some(why) => Err(refuse(why)),
        None => Ok(()),
    }
}

/// [`check_out`]'s check of each target under `out`.
fn check_targets(
    out: &Path,
    targets: &[Target],
    refuse: &dyn Fn(String) -> Failure,
) -> Result<(), Failure> {
    for t in targets {
        match t {
            Target::Results(id) => {
                let dir = out.join(id);
                match std::fs::symlink_metadata(&dir) {
                    Ok(m) if !m.is_dir() => {
                        return Err(refuse(format!(
                            "{id}: exists and is not a directory, where the results of {id} go"
                        )));
                    }
                    Ok(_) => {
                        keeps_partials(&dir, id, out, refuse)?;
                        registry::results_replaceable(&dir)
                            .map_err(|why| refuse(format!("{id}: {why}")))?;
                        replaceable(&dir).map_err(|why| {
                            refuse(format!(
                                "{id}: the previous results cannot be replaced: {why}"
                            ))
                        })?;
                    }
                    Err(_) => {}
                }
            }
            Target::File(rel, kind) => {
                let path = out.join(rel);
                if let Some(parent) = path.parent()
                    && parent != out
                    && std::fs::symlink_metadata(parent).is_ok_and(|m| !m.is_dir())
                {
                    return Err(refuse(format!(
                        "{}: exists and is not a directory, where {rel} is written",
                        parent.strip_prefix(out).unwrap_or(parent).display()
                    )));
                }
                match std::fs::symlink_metadata(&path) {
                    Ok(m) if m.is_dir() => {
                        return Err(refuse(format!(
                            "{rel}: exists and is a directory, where a file is written"
                        )));
                    }
                    Ok(_) => {
                        registry::check_replace(&path, kind)
                            .map_err(|why| refuse(format!("{rel}: {why}")))?;
                        replaceable_file(&path)
                            .map_err(|why| refuse(format!("{rel}: cannot be replaced: {why}")))?;
                    }
                    Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                        return Err(refuse(format!("{rel}: cannot be inspected ({e})")));
                    }
                    Err(_) => {
                        if let Some(parent) = path.parent().filter(|p| p.is_dir()) {
                            probe_folder(parent).map_err(|e| {
                                refuse(format!(
                                    "{rel}: cannot be written (creating a folder in {} fails: {e})",
                                    parent.display()
                                ))
                            })?;
                        }
                    }
                }
            }
        }
    }
    Ok(())
}

/// Results replace the folder `dir` (`<out>/<id>`) whole: refused (exit 2) when it holds the
/// partial files of a sharded run (`run <id> --shard K/N --out <out>`), which the replacement
/// would delete before they are merged.
fn keeps_partials(
    dir: &Path,
    id: &str,
    out: &Path,
    refuse: &dyn Fn(String) -> Failure,
) -> Result<(), Failure> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Ok(());
    };
    let mut partials: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| crate::shard::partial::parse_name(n).is_some())
        .collect();
    if partials.is_empty() {
        return Ok(());
    }
    partials.sort();
    Err(refuse(format!(
        "{id} holds the partial file{} {} of a sharded run, which writing the results of {id} there would delete: merge them into another folder first (cargo xtask merge {} --out OTHER), or give another --out",
        if partials.len() == 1 { "" } else { "s" },
        partials.join(", "),
        out.join(id).display()
    )))
}

/// A hidden name in `dir` for a probe, of the kind [`registry::tidy`] removes if a kill leaves it.
fn probe_name(dir: &Path, what: &str) -> PathBuf {
    dir.join(format!(
        ".xtask-{what}-check.tmp-{}-{}",
        std::process::id(),
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.subsec_nanos())
    ))
}

/// Creates a folder in `dir` and removes it.
fn probe_folder(dir: &Path) -> std::io::Result<()> {
    let probe = probe_name(dir, "out");
    std::fs::create_dir(&probe)?;
    let _ = std::fs::remove_dir(&probe);
    Ok(())
}

/// Whether the file `path` could be removed or renamed over: a second name for it can be made
/// and removed beside it (which an immutable or append-only file, or a folder that cannot be
/// written, refuses).
fn replaceable_file(path: &Path) -> Result<(), String> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let link = probe_name(dir, "link");
    std::fs::hard_link(path, &link)
        .map_err(|e| format!("{} cannot be removed ({e})", path.display()))?;
    let _ = std::fs::remove_file(&link);
    Ok(())
}

/// Whether the results folder `dir` could be moved aside and removed: every folder in it can be
/// written and every file in it removed (see [`replaceable_file`]).
fn replaceable(dir: &Path) -> Result<(), String> {
    probe_folder(dir).map_err(|e| format!("{} cannot be written ({e})", dir.display()))?;
    let entries = std::fs::read_dir(dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    for entry in entries {
        let entry = entry.map_err(|e| format!("{}: {e}", dir.display()))?;
        let path = entry.path();
        let meta =
            std::fs::symlink_metadata(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        if meta.is_dir() {
            replaceable(&path)?;
        } else {
            replaceable_file(&path)?;
        }
    }
    Ok(())
}

/// A `--set` value refused by one of several experiments it went to (`run all --set trials=1`):
/// the refusal names that experiment, since the others took the value.
fn of_experiment(e: RunError, id: &str) -> RunError {
    match e {
        RunError::BadInput {
            source,
            field,
            rule,
        } if source == "--set" => RunError::BadInput {
            source,
            field,
            rule: format!("{rule}, for experiment {id}"),
        },
        other => other,
    }
}

/// `e` (of experiment `id`) as the user typed it: a refusal reached through a shorthand names
/// the shorthand (`--trials`, `--gearing`, `--errors`), not the `--set` or `--hypothesis` it
/// stands for.
pub(crate) fn as_typed(e: RunError, id: &str, run: &RunArgs) -> RunError {
    let RunError::BadInput {
        source,
        field,
        rule,
    } = e
    else {
        return e;
    };
    let shorthand = match (source.as_str(), field.as_str()) {
        ("--hypothesis", _) if run.errors.is_some() => Some(("--errors", field.clone())),
        ("--set", "trials") if run.trials.is_some() => Some(("--trials", id.to_owned())),
        ("--set", "gearing") if run.gearing.is_some() => Some(("--gearing", id.to_owned())),
        ("--set", "measured") if run.errors.is_some() => Some(("--errors", id.to_owned())),
        _ => None,
    };
    match shorthand {
        Some((flag, field)) => RunError::bad(flag, field, rule),
        None => RunError::BadInput {
            source,
            field,
            rule,
        },
    }
}
