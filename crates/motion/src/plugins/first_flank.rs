//! `first-flank`: both initial angles drawn; the driven gear, carried at the nominal ratio from
//! its own angle, keeps the flank it first meets - pushed by the driver's front flanks if a tooth
//! behind catches it up, held against their back flanks (run as the other gear driving) if it
//! runs into one ahead.

use crate::carry::{Carried, Placement, Side};
use crate::{Event, Mesh, Outcome, Path, Start, Trial, Want};
use contact::Solve;

fn run(trial: &Trial<'_>, want: Want<'_>) -> Outcome {
    let Some(drawn) = trial.drawn else {
        // The caller fixes the start touching a tooth behind: the push model.
        return push(
            trial.mesh,
            trial.phi0,
            trial.phi_end(),
            Start::Touching(0.0),
            want,
        );
    };
    let mesh = trial.mesh;
    let (phi0, end) = (trial.phi0, trial.phi_end());
    let Some(first) = Carried::first_flank(mesh, phi0, end, Placement::At(drawn)) else {
        // No flank met in the whole run (or the start is blocked): the carried motion itself.
        return crate::carry::outcome(trial, want, Placement::At(drawn));
    };
    let rest = match first.side {
        Side::Behind => push(mesh, first.phi, end, Start::At(first.theta), want),
        Side::Ahead => held_ahead(mesh, first.phi, first.theta, end, trial.ratio(), want),
    };
    let carried = Path::Carried {
        mesh: Box::new(mesh.clone()),
        pieces: vec![crate::Piece {
            phi_start: phi0,
            phi_end: first.phi,
            rule: crate::path::Rule::Carried {
                phi: phi0,
                theta: first.theta - trial.ratio() * (first.phi - phi0),
            },
        }],
    };
    // The approach to the first flank is where the drawn placement puts the gear in mesh, as
    // the push model's touching start does at once: no drive is lost there, so it is no idle
    // start (were it one, nearly every trial would disengage, against the paper's Table 4).
    Outcome {
        events: rest.events,
        path: rest.path.map(|then| Path::Joined {
            first: Box::new(carried),
            until: first.phi,
            then: Box::new(then),
        }),
    }
}

/// The push model on `mesh` from `phi0` to `end`.
fn push(mesh: &Mesh, phi0: f64, end: f64, start: Start, want: Want<'_>) -> Outcome {
    match want {
        Want::Path => {
            let t = mesh.solve(phi0..=end, start, Solve::path());
            Outcome {
                events: t.events().to_vec(),
                path: Some(Path::Exact(Box::new(t))),
            }
        }
        Want::Events(answered) => Outcome {
            events: mesh.solve(phi0..=end, start, Solve::events().until_answered(answered)),
            path: None,
        },
    }
}

/// The gear held against the driver's back flanks from (φ, θ) to `end`: the push model of the
/// other gear driving ([`Mesh::other_driving`]), which turns from θ by the ratio's share of the
/// rest of the run, the listed driver starting at φ. Gears that the mirrored mesh refuses cannot
/// turn: a blocked start.
fn held_ahead(mesh: &Mesh, phi: f64, theta: f64, end: f64, ratio: f64, want: Want<'_>) -> Outcome {
    let Ok(other) = mesh.other_driving() else {
        return Outcome {
            events: vec![blocked(phi, theta)],
            path: None,
        };
    };
    let mut out = push(
        &other,
        theta,
        theta + ratio * (end - phi),
        Start::At(phi),
        want,
    );
    out.path = out.path.map(|p| match p {
        Path::Exact(t) => Path::Inverse(t),
        p => p,
    });
    out
}

/// A blocked start at (φ, θ): gears that cannot be placed the other way round.
fn blocked(phi: f64, theta: f64) -> Event {
    Event::new(contact::EventKind::BlockedAtStart, phi, theta, (0, 0))
}

crate::model! {
    /// The driven gear keeps the flank it first meets.
    struct FirstFlank;
    name: "first-flank",
    summary: "both initial angles drawn: the driven gear, carried at the nominal ratio from its own angle, keeps the flank it first meets - pushed by the driver's front flanks (the push model) or held against their back flanks (the other gear driving)",
    details: "A mechanism for the paper's mix of jams between our two driving directions, without a coin: if its program placed both gears at drawn initial angles (not touching), the driven gear would meet one of the driver's flanks first. Placed at its own drawn angle (the nearest free position either way where that overlaps) and carried at the nominal ratio from there (`carried-drawn`), a gear that a driver tooth behind catches up is pushed from then on by the front flanks (the push model, from that contact); one that runs into a driver tooth ahead keeps leaning on the back flanks, held ahead as if it drove (run as the push model of the other gear driving, `contact::Mesh::other_driving`, from that contact, the listed driven gear turning by the ratio's share of the rest of the run; the measured jams of 'held ahead' and 'the other gear drives' agree). The approach from the drawn angle to the first flank places the gear in mesh, as the push model's touching start does at once, and is not an idle start (counted as one, it would make nearly every trial disengage, against the paper's Table 4); a gear that meets no flank in the whole run is carried throughout (an idle start). Where the caller fixes the start touching (Figure 2), it is the push model.",
}
