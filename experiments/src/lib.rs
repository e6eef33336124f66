//! The paper's tables and figures as experiments, one file each, registered with `inventory`.

pub mod common;
pub mod paper;

mod clearance;
mod clearance_design;
mod equal_pair;
mod errors;
mod event_rules;
mod events;
mod failure;
mod fig2;
mod fig3;
mod fig4;
mod fig5;
mod fig6;
mod fig_events;
mod fig_iv;
mod gearing;
mod limits;
mod lunar_anomaly;
pub mod pair;
mod pair_html;
mod pair_jams;
pub mod replay;
mod sensitivity;
mod sigma_causes;
mod table1;
mod table2;
mod table3;
mod table4;
mod table5;
mod table6;
mod table_i;
mod tolerance;
mod tolerance_search;

/// Does nothing; calling it makes a binary link this crate, and with it every experiment it registers.
pub fn link() {}

/// Forgets the per-mesh jam cells this process has run (see `pair_jams::run_cells`), so that
/// the next experiment computes them again: for benchmarks, which must time the work itself.
pub fn forget_cached_cells() {
    pair_jams::forget_cache();
}
