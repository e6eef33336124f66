//! Exact push-model contact solver for one mesh of triangular-tooth gears: θ(φ), jams, disengagements.
//!
//! The push model, solved exactly: the driven gear stays put until a driver tooth pushes it, then
//! moves only as far as it must to stay clear.
//!
//! At a driver angle φ every driver tooth j makes, for every driven tooth k, an obstacle: a closed
//! interval `[lo, hi]` of driven angles at which the two teeth overlap (see [`Mesh::obstacle`]).
//! The driven angle θ never lies strictly inside one. Obstacles *behind* θ (hi ≤ θ) push it: θ is
//! the running maximum of their upper ends. Obstacles *ahead* (lo ≥ θ) are driver teeth the driven
//! tooth is moving towards. Hence the events, each classified from the contact motion:
//!
//! - an obstacle ahead reaches θ: a **lock** if a pair touches behind at that moment (held on both
//!   sides), a **strike** if nothing does (the push model would have to turn it backwards);
//! - the pushing obstacle stops rising (its tips slip past each other) while no other driver tooth
//!   touches: a **gap**, sized when drive resumes and called a **slip** if it lasted a driver
//!   pitch or more or moved the tooth phase;
//! - no free driven position at the start: **blocked at start**.
//!
//! After a lock or strike the driven gear is let go to the next free position ahead; where there
//! is none it is **held** until one appears, at the first root where the obstacles that close up
//! over its turn may give way (`held.rs`, on the exact conditions of `meet.rs`).
//!
//! Which of these a table counts as a jam or a disengagement is an event rule's call (the `rules`
//! crate), not the solver's.
//!
//! **How a step finds them** (`step.rs`). The driver turns in steps of a quarter of its pitch
//! (only to bound the tooth pairs looked at together: no result depends on it). Between events
//! θ(φ) is a constant (at rest) or the maximum of closed-form contact curves (pushed), exact at
//! every φ. Each event is a root of the contact conditions of `meet.rs` - a vertex on a flank
//! line or arc, every one F(φ, θ) = 0 - and is found as one:
//!
//! - a driver tooth ahead closing on the path, a pair behind reaching a gear at rest: the first
//!   root where a condition of the pair meets one of the path's, the sign of the gap checked
//!   between consecutive roots (`closing.rs`);
//! - a held gear let go: the first root where the obstacles that hold it may give way
//!   (`held.rs`);
//! - where the pushing curves stop rising (a gap): golden-section search, refined where a curve
//!   peaks smoothly by bisection on the sign of its closed-form slope (`Mesh::smooth_peak`),
//!   decided by samples at the middle and end of the step; and the side of a pair born within a
//!   step, by bisection on its existence (`search.rs`).
//!
//! **The speed layer** (`certified.rs`, straight flanks): a pushed gear's step is first tried on a
//! certificate, bounds on the contact conditions over the box of the step's driver angles and
//! the driven angles it can reach (`certify.rs`) that prove every tooth pair near the gear either
//! stays clear of it or, behind it, only pushes it forwards; then no event lies in the step and
//! it ends where the pushing curves end. It changes no result: `tests/differential.rs` holds the
//! runs with and without it (and with a 64-times finer step) to the same events.

mod closing;
mod entry;
mod held;
mod meet;
mod mesh;
mod roots;
mod solver;
#[cfg(feature = "speed")]
mod speed;
mod tooth;

pub use mesh::{Mesh, MeshError, Obstacle, tooth_pair_evaluations};
pub use solver::{
    Answered, Event, EventKind, Motion, Segment, SolverStats, Start, StopAt, Trajectory,
    solver_stats,
};
