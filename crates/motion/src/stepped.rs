//! The paper's kind of stepped area program (`polycheck::stepped`, which shares no code with the
//! contact solver) as a motion model: the driver turned by a fixed step, the driven gear placed
//! after each step and corrected where the overlap area of the two outlines exceeds a tolerance,
//! the run's events read off the steps.
//!
//! A step after which the test finds contact is drive (a tooth met the driven gear and turned
//! it); a stretch of steps without contact is a loss of drive, sized from the last step that met
//! to the next one (so its lost motion is a whole number of steps); a step with no free position
//! within the reach is a jam (a lock, the driven gear then let go to the first free position
//! ahead). The tooth pairs are not known to the area test: every event names pair (0, 0).

use geometry::Gear;
use polycheck::stepped::{Correction, GearOutline, SteppedPair, Stepping};

use crate::log::Log;
use crate::{Outcome, Path, Trial, Want};

/// The overlap area the program ignores (mm²): the tolerance at which the paper's kind of test
/// gives Table 1's σ (`contact-tolerance`), and `jam-readings`' smallest.
pub const TOLERANCE: f64 = 0.0001;

/// A stepped program: its correction, stepping and tolerance.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Program {
    /// Which way the driven gear is turned after a step.
    pub correction: Correction,
    /// Driver step, reach and search step (`jam-readings`' defaults: 20 steps a pitch, a reach
    /// of one driven pitch, 64 search steps a driven pitch).
    pub stepping: Stepping,
    /// Overlap area ignored (mm²).
    pub tolerance: f64,
}

impl Program {
    /// The program with `correction`, at the defaults of `jam-readings`.
    pub fn with(correction: Correction) -> Self {
        Self {
            correction,
            stepping: Stepping::default(),
            tolerance: TOLERANCE,
        }
    }
}

/// A gear's outline as the area test takes it: tips, valleys, their radii and the rotation
/// centre (curved flanks are taken as their chords).
pub fn outline(g: &Gear) -> GearOutline {
    let n = g.teeth() as i64;
    let e = g.rotation_centre();
    GearOutline {
        tips: g.tip_angles().to_vec(),
        valleys: g.valley_angles().to_vec(),
        tip_radii: (0..n).map(|k| g.tip_radius_of(k)).collect(),
        root_radii: (0..n).map(|k| g.root_radius_of(k)).collect(),
        rotation_centre: [e.x, e.y],
    }
}

/// Runs `trial` under `program` (the driven gear started touching, from 0, as the tables start).
pub fn run(trial: &Trial<'_>, want: Want<'_>, program: &Program) -> Outcome {
    let mesh = trial.mesh;
    let pair = SteppedPair::new(
        &outline(mesh.driver()),
        &outline(mesh.driven()),
        mesh.centre_distance(),
        program.tolerance,
        trial.tooth_height,
    );
    let (pitch, ratio) = (trial.driver_pitch(), trial.ratio());
    let Some(theta0) = pair.start(trial.phi0, 0.0, &program.stepping) else {
        let mut log = Log::new(trial.phi0, 0.0, pitch, ratio);
        log.blocked(trial.phi0, 0.0, (0, 0));
        let path = matches!(want, Want::Path).then(|| Path::Steps(vec![(trial.phi0, 0.0)]));
        return Outcome {
            events: log.finish(trial.phi0, 0.0),
            path,
        };
    };
    let mut log = Log::new(trial.phi0, theta0, pitch, ratio);
    let keep = matches!(want, Want::Path);
    let mut steps: Vec<(f64, f64)> = vec![(trial.phi0, theta0)];
    let (mut last, mut last_met) = ((trial.phi0, theta0), (trial.phi0, theta0));
    pair.trace(
        trial.phi0,
        trial.turn,
        0.0,
        &program.stepping,
        program.correction,
        |s| {
            if s.jam {
                log.lock(s.phi, s.jam_theta, s.theta, (0, 0));
                last_met = (s.phi, s.theta);
            } else if s.met {
                log.drive(s.phi, s.theta, (0, 0));
                last_met = (s.phi, s.theta);
            } else {
                log.lose(last_met.0, last_met.1, (0, 0));
            }
            last = (s.phi, s.theta);
            if keep {
                steps.push(last);
            }
            match want {
                Want::Path => true,
                Want::Events(answered) => !(log.settled() && answered(log.events())),
            }
        },
    );
    Outcome {
        events: log.finish(last.0, last.1),
        path: keep.then_some(Path::Steps(steps)),
    }
}
