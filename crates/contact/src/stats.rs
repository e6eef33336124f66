//! How the exact core took the steps of the runs on a thread, and searched held gears' joints:
//! counts for benchmarks and profiling. (The speed layer keeps its own, `speed/stats.rs`.)

use std::cell::Cell;

/// How the exact core took the steps of the runs on this thread, for benchmarks and profiling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolverStats {
    /// Steps taken exactly (no certificate tried, or none found), while the driven gear was free.
    pub bracketed: u64,
    /// Searches of a held gear's chain for where it may give way.
    pub held_searches: u64,
    /// Joints of held gears' chains those searches searched.
    pub joints_searched: u64,
}

thread_local! {
    static STATS: Cell<SolverStats> = const {
        Cell::new(SolverStats {
            bracketed: 0,
            held_searches: 0,
            joints_searched: 0,
        })
    };
}

/// The exact core's step counts of the runs on this thread so far.
pub fn solver_stats() -> SolverStats {
    STATS.with(Cell::get)
}

/// Updates this thread's step counts.
pub(crate) fn count(update: impl FnOnce(&mut SolverStats)) {
    STATS.with(|c| {
        let mut st = c.get();
        update(&mut st);
        c.set(st);
    });
}
