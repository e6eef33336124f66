//! The paper's tables and figures as experiments: one file each in `src/plugins/`, registered with `inventory`.
//!
//! An experiment is a leaf: it reads its settings (the groups several share through
//! `setting_groups`), calls the `study` crate (which owns every simulation) and draws its tables
//! and figures through the `presentation` crate. No experiment imports another; beside the
//! plugins is only their registration (`replay_cells!`, the grammar of a replayable table's
//! cells). Adding an experiment is one file in `src/plugins/` (`build.rs` declares it) plus its
//! snapshot.

mod register;

pub(crate) use register::replay_cells;

mod plugins {
    include!(concat!(env!("OUT_DIR"), "/plugins.rs"));
}

/// Does nothing; calling it makes a binary link this crate, and with it every experiment it registers.
pub fn link() {}

/// Forgets the per-mesh jam cells this process has run (see `study::cell::run_cells`) and the
/// results it has computed ([`registry::forget_computed`]), so that the next experiment computes
/// them again: for benchmarks, which must time the work itself.
pub fn forget_cached_cells() {
    study::cell::forget_cache();
    registry::forget_computed();
}

/// The context registered experiment `id` runs in with `seed`, `threads` and the `--set` pairs
/// `sets`, built as the runner builds it (the same checks of every value).
///
/// Errors: an unregistered id, or a value [`registry::Context::new`] refuses.
pub fn context(
    id: &str,
    seed: u64,
    threads: usize,
    sets: &[(&str, &str)],
) -> Result<(&'static registry::Entry, registry::Context), registry::RunError> {
    link();
    let map = registry::experiments().map_err(|e| registry::RunError::Internal(e.to_string()))?;
    let exp = *map.get(id).ok_or_else(|| {
        registry::RunError::bad("experiment", id, "is not registered (cargo xtask list)")
    })?;
    let sets: Vec<(String, String)> = sets
        .iter()
        .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
        .collect();
    Ok((
        exp,
        registry::Context::new(exp, seed, threads, &sets, None)?,
    ))
}

/// Runs registered experiment `id` in a pool of `threads` threads (see [`context`]): how tests
/// and benchmarks run one experiment without the runner.
pub fn run(
    id: &str,
    seed: u64,
    threads: usize,
    sets: &[(&str, &str)],
) -> Result<registry::Report, registry::RunError> {
    Ok(outcome(id, seed, threads, sets)?.report)
}

/// [`run`], with the experiment's stored data (its settings and results) beside the report.
pub fn outcome(
    id: &str,
    seed: u64,
    threads: usize,
    sets: &[(&str, &str)],
) -> Result<registry::Outcome, registry::RunError> {
    let (exp, ctx) = context(id, seed, threads, sets)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| registry::RunError::Internal(format!("thread pool: {e}")))?;
    pool.install(|| (exp.run)(&ctx, ctx.engine()))
}
