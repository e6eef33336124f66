//! Exact push-model contact solver for one mesh of triangular-tooth gears: θ(φ), jams, disengagements.
//!
//! # The model
//!
//! The driven gear stays put until a driver tooth pushes it, then moves only as far as it must
//! to stay clear. At a driver angle φ every driver tooth j makes, for every driven tooth k, an
//! obstacle: a closed interval `[lo, hi]` of driven angles at which the two teeth overlap
//! ([`Mesh::obstacle`]). The driven angle θ never lies strictly inside one. Obstacles *behind* θ
//! (hi ≤ θ) push it: θ is the running maximum of their upper ends. Obstacles *ahead* (lo ≥ θ) are
//! driver teeth the driven tooth is moving towards. So the driven gear is **pushed** (θ follows a
//! pushing pair's contact curve), **at rest** (θ constant) or **held** (jammed, with no free
//! position ahead), and each event ends one of these states:
//!
//! - an obstacle ahead reaches θ (a **closing**): a **lock** if a pair touches behind at that
//!   moment (held on both sides), a **strike** if nothing does (the push model would have to turn
//!   it backwards);
//! - the pushing obstacle stops rising (its tips slip past each other) while no other driver tooth
//!   touches: a **gap**, sized when drive resumes and called a **slip** if it lasted a driver
//!   pitch or more or moved the tooth phase;
//! - no free driven position at the start: **blocked at start**.
//!
//! After a lock or strike the driven gear is let go to the next free position ahead; where there
//! is none it is **held** until one appears. Which of these events a table counts as a jam or a
//! disengagement is an event rule's call (the `rules` crate), not the solver's.
//!
//! Every event is a root of the contact conditions - a vertex of one tooth on a flank (line or
//! arc) of the other, each F(φ, θ) = 0 with F bilinear in the cosines and sines of the two angles
//! (`src/meet.rs`, the conditions of an obstacle's ends in `src/mesh/conditions.rs`) - found as a
//! root, not by sampling. Between events θ(φ) is a constant or the maximum of closed-form contact
//! curves, exact at every φ ([`Trajectory::theta_at`]).
//!
//! # Where each is decided
//!
//! | what | where (files under `src/`) |
//! |---|---|
//! | the main loop: the driver walked in steps of a quarter of its pitch (only to bound the tooth pairs looked at together: no result depends on it), each step taken by the driven gear's `Drive` - held, pushed (offered to the speed layer first) or at rest - exactly unless the speed layer took it | `Mesh::walk` and `Run::advance` in `solver/mod.rs` |
//! | one exact step: the pairs near the gear sorted behind or ahead, the path planned from those behind (push, gap, rest, push again) | `Run::exact_step`, `Run::plan_step` in `solver/step.rs` |
//! | a closing: the first root where a lower-end condition of a pair ahead holds together with a condition of the path, the sign of the backlash read once between consecutive roots | `closing::first_closing` in `closing.rs`, asked by `first_jam` in `solver/step.rs` |
//! | a lock or a strike: the closing judged (a pair touching behind, or none), the gear let go to the next free position or held | `Run::jam` in `solver/step.rs`; the free position, or the chain of obstacles that holds, by `Mesh::free_or_cover_in` in `solver/cover.rs` |
//! | a gap: where the pushing curves stop rising, by golden-section search refined by bisection on the sign of the closed-form slope where a curve peaks smoothly | `Run::plan_step` in `solver/step.rs`, `Mesh::smooth_peak` in `solver/mod.rs`, the searches in `solver/search.rs`; sized (gap or slip) by `Run::resume_drive` in `solver/mod.rs` |
//! | a held gear: held while the chain of obstacles that closes up over its turn holds, let go at the first root where a joint of the chain may give way (each joint's roots its own) | `Run::held_step` in `solver/mod.rs`, on `held::first_change` in `held.rs` |
//! | a pair behind reaching a gear at rest (drive resumed) | `closing::first_reach` in `closing.rs` |
//! | blocked at start, the idle-start candidate | `Run::start`, `Run::record_idle_start` in `solver/mod.rs` |
//!
//! # Layers
//!
//! The **exact core** is everything above: it alone decides every result. The **speed layer**
//! (`src/speed/`, the `speed` feature, on by default) sits on top of it: per run a `Certifier`
//! (`speed/mod.rs`), passed to each step of the run, proves where it can that part of an exact
//! search would find nothing, and the core leaves that part out - a pushed gear's step free of events (`speed/certified.rs`, on
//! the bounds of `speed/certify.rs`), the joints of a held gear's chain that hold through a step
//! (`speed/held.rs`: a proof per joint that moves with its links' overlap, in a queue ordered by
//! where each proof ends), the contact conditions a closing's search need not take (those that
//! hold nowhere near the step's path). The core offers it that work through one trait,
//! `Shortcut` (`solver/shortcut.rs`), and never names it: the run holds no state of the layer,
//! and the layer keeps its own (its proofs; its counts, `speed_stats`). [`Mesh::solve`]
//! (`entry.rs`), the one public way to run a mesh, builds the layer for each run, or leaves it out
//! ([`Solve::exact_core`]). No result depends on it: `tests/differential.rs` holds runs with and
//! without it (and with a 64-times-finer step) to the same events, and `cargo test -p contact
//! --no-default-features` tests the core without it (CI runs it, and clippy on it).
//! The workspace's tidy test (`xtask/tests/tidy/`) checks that no layer names one above it.

mod closing;
mod entry;
mod held;
mod meet;
mod mesh;
mod roots;
mod solver;
#[cfg(feature = "speed")]
mod speed;
mod stats;
mod tooth;

pub use entry::{Events, Keep, Path, Solve};
pub use mesh::{Mesh, MeshError, Obstacle, tooth_pair_evaluations};
pub use solver::{Answered, Event, EventKind, Motion, Segment, Start, StopAt, Trajectory};
#[cfg(feature = "speed")]
pub use speed::{SpeedStats, speed_stats};
pub use stats::{SolverStats, solver_stats};
