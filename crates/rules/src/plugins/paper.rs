//! `paper`: the paper's own definitions, read from its sentences.

use crate::{About, Event, EventKind, Params, Plugin};

/// Jams as interference the driven gear cannot escape; disengagement as idle rotation.
struct Paper;

impl Plugin for Paper {
    const ABOUT: About = About {
        name: "paper",
        summary: "jam: lock, strike or blocked start (interference); disengagement: a slip - idle rotation of a driver pitch or more, or the tooth phase moved",
        details: "Written from the paper's sentences before comparing with its tables. Jam: 'teeth positioned too closely interfere with each other at all times ... the gears become jammed or locked' and Figure V_A, where 'another tip (II) makes contact with the face of a preceding tooth, preventing the movement of the driven gear' - a lock, and a start with no free position. The paper's program detects 'intersections between the areas of the gears' and lets 'the driven gear ... rotate freely if a jam ... was detected until movement was possible again', turning it forwards only: an incoming tooth meeting the front of a lagging driven tooth is an interference it cannot resolve by turning forwards, so a strike is a jam too. Disengagement: 'they lose contact ... and the program does not detect any tooth interference - this is what we refer to as decoupling or idle rotation', a gear that 'fails to transmit motion to the meshed pair', which 'would at least partially stop the indicators ... causing synchronization errors'. Idle rotation is the driver turning without transmitting: drive lost for a whole driver pitch or more, or resumed a tooth out of step (a slip). A hand-over gap after which the next tooth takes the driven gear up again in step transmits every tooth and is not counted; the paper's Table 4 says 'only jamming events were observed, which is expected given the absence of systematic error'.",
    };
    const JAMS: &str = "lock, strike, blocked start";
    const DISENGAGEMENTS: &str =
        "slip: idle rotation of a driver pitch or more, or the tooth phase moved";

    fn is_jam(e: &Event, _: &Params) -> bool {
        e.kind.is_contact_stop()
    }

    fn is_disengagement(e: &Event, _: &Params) -> bool {
        e.kind == EventKind::Slip
    }
}

crate::register!(Paper);
