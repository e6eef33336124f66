//! Exact push-model contact solver for one mesh of triangular-tooth gears: θ(φ), jams, disengagements.

mod certify;
mod closing;
mod held;
mod meet;
mod mesh;
mod roots;
mod solver;
mod tooth;

pub use mesh::{Mesh, MeshError, Obstacle, tooth_pair_evaluations};
pub use solver::{
    Answered, Event, EventKind, Motion, Segment, SolverStats, Start, StopAt, Trajectory,
    solver_stats,
};
