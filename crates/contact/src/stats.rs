//! How the steps of the runs on a thread were taken, and the held gears' joints searched: counts
//! for benchmarks and profiling, kept by the core and the speed layer alike.

use std::cell::Cell;

/// How the steps of the runs on this thread were taken, for benchmarks and profiling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SolverStats {
    /// Steps the speed layer took on a certificate.
    pub certified: u64,
    /// Tooth-pair evaluations made by certified steps.
    pub certified_evaluations: u64,
    /// Certificates tried and not found.
    pub refused: u64,
    /// Tooth-pair evaluations made by those attempts.
    pub refused_evaluations: u64,
    /// Steps taken exactly (no certificate tried, or none found), while the driven gear was free.
    pub bracketed: u64,
    /// Searches of a held gear's chain for where it may give way.
    pub held_searches: u64,
    /// Joints of held gears' chains those searches searched.
    pub joints_searched: u64,
    /// Joints the speed layer proved to hold through a step, each time it did.
    pub joints_proved: u64,
}

thread_local! {
    static STATS: Cell<SolverStats> = const {
        Cell::new(SolverStats {
            certified: 0,
            certified_evaluations: 0,
            refused: 0,
            refused_evaluations: 0,
            bracketed: 0,
            held_searches: 0,
            joints_searched: 0,
            joints_proved: 0,
        })
    };
}

/// The step counts of the runs on this thread so far.
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
