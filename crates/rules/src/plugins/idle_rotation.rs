//! `idle-rotation`: disengagement as the paper's program could see it - the driver turning with
//! no tooth interference for a driver pitch or more, whatever the tooth phase afterwards.

use crate::{About, Event, Kind, Param, Params, Plugin};

registry::params! {
    /// `pitches`: the shortest idle rotation counted as a disengagement.
    const PITCHES = Param::new("pitches", "1", "the shortest idle rotation (drive lost, no contact pushing the driven gear) counted as a disengagement; 0 counts every loss of drive", Kind::number(0.0, 1000.0, "")).unit("driver pitches");
}

/// Jams as interference; disengagement as idle rotation of at least `pitches` driver pitches.
struct IdleRotation;

impl Plugin for IdleRotation {
    const ABOUT: About = About {
        name: "idle-rotation",
        summary: "jam: lock, strike or blocked start (interference); disengagement: drive lost for a driver pitch or more (idle rotation, the tooth phase afterwards ignored), an idle start included",
        details: "Disengagement read from the only definition the paper gives, in Appendix II: 'If the gears have a separation greater than this percentage, they lose contact before reaching 100% separation, and the program does not detect any tooth interference - this is what we refer to as decoupling or idle rotation', with Figure V_B, 'a decoupling situation in which a gear fails to transmit motion to the meshed pair'. The paper's program detected 'intersections between the areas of the gears'; what it could see of a loss of drive is how long the driver turned with no interference, not which tooth took the driven gear up afterwards. So a disengagement is any loss of drive (a gap or a slip) lasting at least `pitches` driver pitches (default 1: a whole tooth of the driver turned idle), whatever the tooth phase when drive resumes; a short loss that resumes a tooth out of step (which `paper` counts) is not one. A driven gear that no driver tooth pushes within that much of the start, or at all (an idle start), turned idle too and counts. Jams as under `paper`: a lock, a strike or a start with no free position ('teeth positioned too closely interfere with each other at all times ... the gears become jammed or locked', Figure V_A).",
    };
    const PARAMS: &[Param] = &[PITCHES];
    const JAMS: &str = "lock, strike, blocked start";
    const DISENGAGEMENTS: &str = "drive lost for a driver pitch or more (gap or slip, an idle start included), the tooth phase afterwards ignored";

    fn is_jam(e: &Event, _: &Params) -> bool {
        e.kind.is_contact_stop()
    }

    fn is_disengagement(e: &Event, params: &Params) -> bool {
        // A driven gear never pushed in the whole run turned idle throughout, even in a run
        // shorter than the threshold.
        let never_driven = e.idle_start && !e.resumed;
        e.kind.is_loss() && (e.lost_motion >= params.value(&PITCHES) || never_driven)
    }
}

crate::register!(IdleRotation);
