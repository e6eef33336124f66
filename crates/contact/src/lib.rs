//! Exact push-model contact solver for one mesh of triangular-tooth gears: θ(φ), jams, disengagements.

mod mesh;
mod roots;
mod solver;

pub use mesh::{Mesh, MeshError, Obstacle};
pub use solver::{Event, EventKind, Motion, Segment, Start, Trajectory};
