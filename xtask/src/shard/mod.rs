//! `run <id> --shard K/N` and `merge`: one shard's partial file, and the results of all of them joined
//! ([`partial`]: the partial file, how it is found, read and checked).

pub(crate) mod partial;

use std::path::{Path, PathBuf};

use registry::Context;

use crate::args::{MergeArgs, RunArgs};
use crate::compute::{execute, make_pool};
use crate::failure::Failure;
use crate::plan::{Planned, Target, as_typed, check_out, lookup};
use crate::print::Printer;
use crate::progress::note;
use crate::provenance;
use crate::shared::{Registry, default_out, default_threads, print, write_atomically};

/// `run <id> --shard K/N`: runs the experiment in shard mode, discards its report and writes
/// the recorded trials to `<out>/<id>/partial-K-of-N.json` (through a temporary file renamed
/// into place; other files of the directory are left alone, so shards may share it).
pub(crate) fn run_shard(
    planned: &Planned,
    ctx: Context,
    run: &RunArgs,
    pool: &rayon::ThreadPool,
    out: &Path,
) -> Result<(), Failure> {
    let e = planned.e;
    let registry::TrialMode::Shard(shard) = ctx.trial_mode() else {
        return Err(Failure::Internal(
            "internal error: a shard run without a shard".into(),
        ));
    };
    let mut partial = partial::Partial::new(e.id, run.seed, &planned.sets, ctx.config(), shard);
    partial.inputs = partial::input_files(&ctx);
    let dir = out.join(e.id);
    // Before anything is computed: the folder holds no other sharded run's partial files.
    partial::only_this_run(&dir, &partial, out)?;
    execute(e, &ctx, pool)
        .0
        .map_err(|err| as_typed(err, e.id, run))?;
    partial.batches = ctx.recorded();
    let text = partial.to_json()?;
    std::fs::create_dir_all(&dir).map_err(|err| {
        Failure::Internal(format!(
            "internal error: cannot create {}: {err}",
            dir.display()
        ))
    })?;
    registry::tidy(&dir)?;
    let path = dir.join(partial::file_name(shard));
    write_atomically(&path, &partial::KIND, text.as_bytes())?;
    let (mut here, mut whole) = (0, 0);
    for b in partial.batches.values() {
        if b.whole {
            whole += b.values.len();
        } else {
            here += b.values.len();
        }
    }
    let plural =
        |n: usize, one: &str, more: &str| format!("{n} {}", if n == 1 { one } else { more });
    note(&format!(
        "partial: {} (shard {shard} of {}: {}, {} computed here{}); join the {} with `cargo xtask merge`",
        path.display(),
        e.id,
        plural(partial.batches.len(), "trial batch", "trial batches"),
        plural(here, "trial", "trials"),
        if whole > 0 {
            format!(", {whole} more in batches every shard runs whole")
        } else {
            String::new()
        },
        plural(shard.count() as usize, "shard", "shards")
    ));
    if partial.batches.is_empty() {
        note(&format!(
            "note: {} runs no trials that shards can split: every shard computes all of it, and the merge computes it again",
            e.id
        ));
    }
    Ok(())
}

/// `merge`: finds and reads the partial files, checks that they come from one sharded command
/// and cover every shard once, replays the experiment from their records, then prints and
/// writes its results as `run` would. Nothing is written unless every check passes.
pub(crate) fn merge(exps: &Registry, m: &MergeArgs) -> Result<(), Failure> {
    let files = partial::find(&m.inputs)?;
    let mut parts = Vec::with_capacity(files.len());
    for f in files.clone() {
        let (partial, shard) = partial::read(&f)?;
        parts.push((f, partial, shard));
    }
    partial::agree(&parts)?;
    let (first_file, header) = parts
        .first()
        .map(|(f, p, _)| (f.clone(), p.clone()))
        .ok_or_else(|| Failure::Internal("internal error: no partial file".into()))?;
    let e = lookup(exps, &header.experiment)?;
    let records: Vec<registry::ShardRecords> = parts
        .into_iter()
        .map(|(f, p, shard)| registry::ShardRecords {
            source: f.display().to_string(),
            shard,
            records: p.batches,
        })
        .collect();
    let merged = registry::merge_records(&records)?;
    drop(records);
    let threads = m.threads.unwrap_or_else(default_threads);
    let ctx = Context::new(e, header.seed, threads, &header.sets, header.config_file())?
        .with_replay(merged);
    // The settings are this experiment's: now that the computation is known, it must be this
    // code's, on the files the shards read.
    partial::same_code(&first_file, &header)?;
    partial::same_inputs(&header)?;
    let flags = ("--hypothesis", "--set measured");
    setting_groups::inputs::check(&ctx, flags, &mut std::collections::BTreeSet::new())
        .map_err(|m| Failure::Bad(format!("merge: {m}")))?;
    let out = m.out.clone().unwrap_or_else(default_out);
    check_out(&out, &[Target::Results(e.id.to_owned())])?;
    keeps_partials(&out.join(e.id), &files, m.out.is_some())?;
    let pool = make_pool(threads)?;
    let report = execute(e, &ctx, &pool).0?;
    if let Some(batch) = ctx.unclaimed().first() {
        return Err(Failure::Bad(format!(
            "merge: batch `{batch}`: was recorded by the shards but not asked for by this run of {}: the shards ran different inputs or a different build",
            e.id
        )));
    }
    let config = header.config.as_ref().map(|c| PathBuf::from(&c.path));
    let report = provenance::stamp_outcome(&report, e, &ctx, &header.sets, config.as_deref());
    // Written before printed: a failed print must not cost the merged results.
    let dir = out.join(e.id);
    registry::write_results(&dir, &report)?;
    let mut stdout = |s: &str| print(s);
    let printed = Printer::new(m.format, false, &mut stdout).report(e, &report);
    note(&format!(
        "results: {} (merged from {} shards)",
        dir.display(),
        header.shards
    ));
    printed
}

/// A merge replaces `dir` (`<out>/<id>`) whole: refused (exit 2) when it holds one of the
/// partial files being merged, which the replacement would delete.
pub(crate) fn keeps_partials(
    dir: &Path,
    partials: &[PathBuf],
    out_given: bool,
) -> Result<(), Failure> {
    let Ok(dir) = std::fs::canonicalize(dir) else {
        return Ok(());
    };
    for f in partials {
        if let Ok(f) = std::fs::canonicalize(f)
            && f.starts_with(&dir)
        {
            return Err(Failure::Bad(format!(
                "--out: {}: the merge would replace {}, which holds the partial file {} being merged; give another --out{}",
                dir.parent().unwrap_or(&dir).display(),
                dir.display(),
                f.display(),
                if out_given {
                    ""
                } else {
                    " (the shards wrote into the default results folder)"
                }
            )));
        }
    }
    Ok(())
}
