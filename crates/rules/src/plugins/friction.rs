//! `friction`: beyond the paper, which is frictionless - a single contact may wedge.

use crate::{About, Event, EventKind, Kind, Param, Params, Plugin};

registry::params! {
    /// `mu`: the coefficient of friction at the teeth.
    const MU = Param::new("mu", "0.2", "coefficient of friction at the teeth (bronze on bronze about 0.2)", Kind::number(0.0, 10.0, ""));
}

/// Whether a strike wedges: the line from the contact point to the driven gear's centre lies
/// inside the friction cone (half-angle atan μ) about the contact normal. A tip meeting a tip
/// has no normal (None): any line lies in its cone of normals, so it wedges.
fn wedges(e: &Event, mu: f64) -> bool {
    e.wedge_angle.is_none_or(|a| a <= mu.atan())
}

/// A strike wedges when the contact can carry the driver's push straight into the driven
/// arbor.
struct Friction;

impl Plugin for Friction {
    const ABOUT: About = About {
        name: "friction",
        summary: "as sync, but a strike that wedges (the arbor inside the friction cone of the contact) is a jam",
        details: "Beyond the paper, whose program is frictionless. With friction coefficient mu, the force at a single contact may lie anywhere in the cone of half-angle atan(mu) about the contact normal. When the line from the contact point to the driven gear's rotation centre lies inside that cone, the force can pass through the driven arbor: the driven gear is not turned and the driver cannot advance - the contact wedges, a jam. A strike (an incoming driver tooth meeting the front of a lagging driven tooth) is therefore a jam when it wedges; otherwise the free driven gear is knocked back, and it fails only if its tooth phase moved (as in sync). Locks and blocked starts are jams; slips are disengagements; hand-over gaps are lost motion. Exact from the contact geometry: the solver reports, at each lock and strike, the angle between the contact normal and the line to the driven centre. With mu = 0 it counts as sync.",
    };
    const PARAMS: &[Param] = &[MU];
    const JAMS: &str = "as `sync`, and a strike whose contact wedges (the driven arbor inside the friction cone about the contact normal)";
    const DISENGAGEMENTS: &str = "as `sync`";

    fn is_jam(e: &Event, p: &Params) -> bool {
        match e.kind {
            EventKind::Lock | EventKind::BlockedAtStart => true,
            EventKind::Strike => p.value(&MU) > 0.0 && wedges(e, p.value(&MU)),
            _ => false,
        }
    }

    fn is_disengagement(e: &Event, p: &Params) -> bool {
        match e.kind {
            EventKind::Slip => true,
            EventKind::Strike => !Self::is_jam(e, p) && e.phase_shift != 0,
            _ => false,
        }
    }
}

crate::register!(Friction);
