//! Computing one experiment: the thread pool, and one run caught if it panics.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::Instant;

use registry::{Context, Entry, Outcome, RunError};

use crate::failure::Failure;
use crate::progress;

pub(crate) fn make_pool(threads: usize) -> Result<rayon::ThreadPool, Failure> {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .thread_name(|i| format!("xtask-worker-{i}"))
        .build()
        .map_err(|e| Failure::Internal(format!("cannot start {threads} threads: {e}")))
}

/// Runs `e` in `pool`: its report and data (a panic is an internal error) and the wall time in
/// seconds.
pub(crate) fn execute(
    e: &Entry,
    ctx: &Context,
    pool: &rayon::ThreadPool,
) -> (Result<Outcome, RunError>, f64) {
    let _span = tracing::info_span!("run", id = e.id).entered();
    tracing::info!(seed = ctx.seed(), threads = ctx.threads(), "start");
    progress::experiment_starts();
    let start = Instant::now();
    let result = progress::watch(e.id, || {
        pool.install(|| catch_unwind(AssertUnwindSafe(|| (e.run)(ctx, ctx.engine()))))
    })
    .unwrap_or_else(|_| {
        Err(RunError::Internal(format!(
            "experiment `{}` panicked",
            e.id
        )))
    });
    let seconds = start.elapsed().as_secs_f64();
    tracing::info!(seconds, "done");
    (result, seconds)
}
