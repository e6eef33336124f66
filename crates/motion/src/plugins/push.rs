//! `push`: the exact solver's push model, unchanged (the default).

use crate::{Mesh, Outcome, Path, Start, Trial, Want};
use contact::Solve;

fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
    let mesh: &Mesh = trial.mesh;
    let (phi0, end) = (trial.phi0, trial.phi_end());
    match want {
        Want::Path => {
            let t = mesh.solve(phi0..=end, Start::Touching(0.0), Solve::path());
            Outcome {
                events: t.events().to_vec(),
                path: Some(Path::Exact(Box::new(t))),
            }
        }
        Want::Events(answered) => Outcome {
            events: mesh.solve(
                phi0..=end,
                Start::Touching(0.0),
                Solve::events().until_answered(answered),
            ),
            path: None,
        },
    }
}

crate::model! {
    /// The driven gear as the exact solver moves it.
    struct Push;
    name: "push",
    summary: "pushed by the driver's front flanks and at rest between pushes; let go to the next free position ahead after a jam (the exact solver, the default)",
    details: "The exact contact solver's model (`contact::Mesh::solve`): the driven gear stands still until a driver tooth behind it pushes it, then moves only as far as it must to stay clear, so that θ is the running maximum of the upper ends of the obstacles behind it. A driver tooth ahead closing on it is a lock (if a pair touches behind) or a strike (if none does: the push model would have to turn it back); either way it is let go to the next free position ahead, as the paper's program let 'the driven gear ... rotate freely if a jam ... was detected until movement was possible again'. It starts touching a driver tooth behind it (turned back from angle 0, or pushed clear). Every table of the toolkit runs it.",
}
