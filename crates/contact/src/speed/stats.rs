//! What the speed layer took over from the exact core in the runs on a thread: counts for
//! benchmarks and profiling, beside the core's own (`stats.rs`).

use std::cell::Cell;

/// What the speed layer took over in the runs on this thread, for benchmarks and profiling.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct SpeedStats {
    /// Steps the speed layer took on a certificate.
    pub certified: u64,
    /// Tooth-pair evaluations made by certified steps.
    pub certified_evaluations: u64,
    /// Certificates tried and not found.
    pub refused: u64,
    /// Tooth-pair evaluations made by those attempts.
    pub refused_evaluations: u64,
    /// Joints of held gears' chains proved to hold through a step, each time one was.
    pub joints_proved: u64,
}

thread_local! {
    static STATS: Cell<SpeedStats> = const {
        Cell::new(SpeedStats {
            certified: 0,
            certified_evaluations: 0,
            refused: 0,
            refused_evaluations: 0,
            joints_proved: 0,
        })
    };
}

/// The speed layer's counts of the runs on this thread so far.
pub fn speed_stats() -> SpeedStats {
    STATS.with(Cell::get)
}

/// Updates this thread's speed-layer counts.
pub(super) fn count(update: impl FnOnce(&mut SpeedStats)) {
    STATS.with(|c| {
        let mut st = c.get();
        update(&mut st);
        c.set(st);
    });
}
