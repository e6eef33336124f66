//! The paper's tables and figures as experiments: one file each in `src/plugins/`, registered with `inventory`.
//!
//! An experiment is a leaf: it reads its settings, calls the `study` crate (which owns every
//! simulation) and formats tables and figures. No experiment imports another; what several of
//! them show alike lives in the presentation modules below. Adding an experiment is one file in
//! `src/plugins/` (`build.rs` declares it) plus its snapshot.

pub mod cells;
pub mod common;
pub mod emax;
pub mod pair_html;
pub mod paper;
pub mod replay;

mod plugins {
    include!(concat!(env!("OUT_DIR"), "/plugins.rs"));
}

/// Does nothing; calling it makes a binary link this crate, and with it every experiment it registers.
pub fn link() {}

/// Forgets the per-mesh jam cells this process has run (see `study::cell::run_cells`), so that
/// the next experiment computes them again: for benchmarks, which must time the work itself.
pub fn forget_cached_cells() {
    study::cell::forget_cache();
}
