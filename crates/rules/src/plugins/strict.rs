//! `strict`: every stop and every loss of contact counts.

use crate::{About, Event, Params, Plugin};

/// The solver's counts before the taxonomy: every lock, strike and blocked start is a jam,
/// every hand-over gap and slip a disengagement.
struct Strict;

impl Plugin for Strict {
    const ABOUT: About = About {
        name: "strict",
        summary: "jam: lock, strike or blocked start; disengagement: any loss of contact, however brief (gap or slip)",
        details: "Every contact that stops the driver in the push model is a jam: a lock (held from both sides), a strike (an incoming driver tooth meeting the front of a lagging driven tooth, which the push model would have to turn backwards) and a start with no free position. Every moment the pushing tooth slips past its driven tooth with no other tooth touching is a disengagement, including a brief hand-over gap after which the next tooth picks the driven gear up again in step. These were the toolkit's counts before the event taxonomy; they read the paper's 'the program does not detect any tooth interference' as any instant without contact.",
    };
    const JAMS: &str = "lock, strike, blocked start";
    const DISENGAGEMENTS: &str = "gap, slip (any instant without contact)";

    fn is_jam(e: &Event, _: &Params) -> bool {
        e.kind.is_contact_stop()
    }

    fn is_disengagement(e: &Event, _: &Params) -> bool {
        e.kind.is_loss()
    }
}

crate::register!(Strict);
