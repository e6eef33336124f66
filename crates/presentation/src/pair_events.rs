//! What happened at an event of one mesh's run, as every output of the pair tells it: the teeth
//! and contacts there, a lock's release and its size, the first lock after which the motion is
//! the paper's protocol, and the notes that explain them.

use contact::Trajectory;
use geometry::Vec2;

/// The tooth numbers an output shows for an event, (driver tooth, driven tooth): the numbering
/// of the user's file, which for a driven gear measured in its own sense is the solver's
/// mirrored.
pub type Teeth<'a> = &'a dyn Fn(&contact::Event) -> (i64, i64);

/// The solver's own tooth numbers of an event, each within one turn (0 to N - 1): the numbering
/// of a file whose tips run the driver's way, as `replay`'s `pair.ron` does.
pub fn solver_teeth(mesh: &contact::Mesh) -> impl Fn(&contact::Event) -> (i64, i64) + use<> {
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    move |e: &contact::Event| (e.driver_tooth.rem_euclid(n1), e.driven_tooth.rem_euclid(n2))
}

/// One contact drawn at an event: where the two teeth touch, the unit normal there (None where
/// the contact has none: a vertex on a vertex), and what it is.
#[derive(Debug, Clone, Copy)]
pub struct Contact {
    /// The contact point, world frame.
    pub point: Vec2,
    /// The unit common normal, where defined.
    pub normal: Option<Vec2>,
    /// `closing` (the contact of the event's two teeth: the one that closed at a lock or strike,
    /// the one lost at a gap or slip), `pushing` (the driver tooth pushing the driven gear when
    /// a lock closed) or `resumed` (the pair that drives it after a release).
    pub role: &'static str,
}

/// Whether driver tooth `j` pushes driven tooth `k` at (φ, θ): the upper end of their obstacle
/// is θ (to rounding).
fn pushes_at(mesh: &contact::Mesh, phi: f64, theta: f64, (j, k): (i64, i64)) -> bool {
    mesh.obstacle(phi, j, k)
        .is_some_and(|o| (o.hi - theta).abs() <= 1e-9 * (1.0 + theta.abs()))
}

/// The contact of driver tooth `j` and driven tooth `k` at (φ, θ), labelled `role`; where the
/// contact has no normal (tip on tip), the point half-way between the two tips, if they touch.
/// `None` where the two teeth do not touch at all: nothing to draw.
fn contact_at(
    mesh: &contact::Mesh,
    (phi, theta): (f64, f64),
    (j, k): (i64, i64),
    role: &'static str,
) -> Option<Contact> {
    if let Some((point, normal)) = mesh.contact_normal(phi, theta, j, k) {
        return Some(Contact {
            point,
            normal: Some(normal),
            role,
        });
    }
    let (driver, driven) = mesh.world_outlines(phi, theta);
    let (n1, n2) = (mesh.driver().teeth() as i64, mesh.driven().teeth() as i64);
    let tip1 = driver[2 * j.rem_euclid(n1) as usize];
    let tip2 = driven[2 * k.rem_euclid(n2) as usize];
    // Tips that touch, to rounding of the tooth's size.
    let size = mesh
        .driver()
        .tooth_height()
        .max(mesh.driven().tooth_height());
    ((tip1 - tip2).norm() <= 1e-6 * size).then(|| Contact {
        point: (tip1 + tip2) * 0.5,
        normal: None,
        role,
    })
}

/// Where the two gears' outlines come nearest at (φ, θ): the points on the driver and on the
/// driven gear, and the teeth whose tips are nearest them (the solver's numbers).
pub fn nearest_approach(mesh: &contact::Mesh, phi: f64, theta: f64) -> (Vec2, Vec2, i64, i64) {
    let (driver, driven) = mesh.world_outlines(phi, theta);
    let on_segment = |p: Vec2, a: Vec2, b: Vec2| {
        let ab = b - a;
        let t = ((p - a).dot(&ab) / ab.dot(&ab)).clamp(0.0, 1.0);
        a + ab * t
    };
    let mut best = (f64::INFINITY, Vec2::new(0.0, 0.0), Vec2::new(0.0, 0.0));
    let mut consider = |from: &[Vec2], to: &[Vec2], swap: bool| {
        for &p in from {
            for (i, &a) in to.iter().enumerate() {
                let q = on_segment(p, a, to[(i + 1) % to.len()]);
                let d = (p - q).norm();
                if d < best.0 {
                    best = if swap { (d, q, p) } else { (d, p, q) };
                }
            }
        }
    };
    consider(&driver, &driven, false);
    consider(&driven, &driver, true);
    let nearest_tip = |outline: &[Vec2], p: Vec2| {
        (0..outline.len() / 2)
            .min_by(|&a, &b| {
                (outline[2 * a] - p)
                    .norm()
                    .total_cmp(&(outline[2 * b] - p).norm())
            })
            .unwrap_or(0) as i64
    };
    let (_, p1, p2) = best;
    (p1, p2, nearest_tip(&driver, p1), nearest_tip(&driven, p2))
}

/// Is `e` an idle start (a slip from the start: no driver tooth moved the driven gear within a
/// driver pitch of it, or at all)? It has no contact: its teeth are the pair that would push
/// next, if any, which does not touch the gear.
pub fn is_idle_start(e: &contact::Event) -> bool {
    e.idle_start && e.kind == contact::EventKind::Slip
}

/// The contacts of event `e` at its own (φ, θ): the event's pair, and at a lock (or a strike
/// while pushed) the pair that was pushing, so that both sides of the driven tooth show. None
/// for an idle start, where no tooth touches the driven gear.
pub fn contacts_at_event(traj: &Trajectory, e: &contact::Event) -> Vec<Contact> {
    if is_idle_start(e) {
        return Vec::new();
    }
    let mesh = traj.mesh();
    let pair = (e.driver_tooth, e.driven_tooth);
    let mut out: Vec<Contact> = contact_at(mesh, (e.phi, e.theta), pair, "closing")
        .into_iter()
        .collect();
    if e.kind.is_contact_stop() {
        // The pushing pair: of the pairs pushing on the segment that ends at the event, the one
        // whose contact holds θ there.
        let pusher = traj
            .segments()
            .iter()
            .rev()
            .filter(|s| s.phi_start < e.phi && s.phi_end >= e.phi - 1e-12)
            .find_map(|s| match &s.motion {
                contact::Motion::Push(pairs) => pairs
                    .iter()
                    .copied()
                    .find(|&p| p != pair && pushes_at(mesh, e.phi, e.theta, p)),
                _ => None,
            });
        if let Some(p) = pusher {
            out.extend(contact_at(mesh, (e.phi, e.theta), p, "pushing"));
        }
    }
    out
}

/// A release of the driven gear after a lock or strike: where (φ, absolute) and to what θ it
/// was let go, and the contact that drives it from there. A gear let go at once is released
/// at the event's own φ; one held with no free position ahead is let go where its hold gives
/// way, further on.
pub struct Release {
    /// Driver angle of the release, radians.
    pub phi: f64,
    /// Driven angle after it, radians.
    pub theta: f64,
    /// The contact that drives the gear after it (none where it is not known).
    pub contacts: Vec<Contact>,
}

/// Where a lock or strike lets the driven gear go, when it moves it at all: at once, to
/// `theta_after`; or, held from the event on, where the hold gives way (the end of the held
/// stretch, where the driven angle steps on).
pub fn release_of(traj: &Trajectory, e: &contact::Event) -> Option<Release> {
    if !e.kind.is_contact_stop() {
        return None;
    }
    let (phi, theta) = if e.theta_after != e.theta {
        (e.phi, e.theta_after)
    } else {
        held_release(traj, e)?
    };
    let mesh = traj.mesh();
    let contacts = e
        .resumed_by
        .filter(|&p| pushes_at(mesh, phi, theta, p))
        .and_then(|p| contact_at(mesh, (phi, theta), p, "resumed"))
        .into_iter()
        .collect();
    Some(Release {
        phi,
        theta,
        contacts,
    })
}

/// Where a gear held at event `e` is let go: the first segment after the held stretch that
/// starts at the event, where the driven angle has stepped on. None where the gear was not
/// held there, or is held to the end of the run.
fn held_release(traj: &Trajectory, e: &contact::Event) -> Option<(f64, f64)> {
    let segments = traj.segments();
    let first = segments.partition_point(|s| s.phi_end <= e.phi);
    let held = segments.get(first..)?;
    if !held
        .first()
        .is_some_and(|s| s.motion == contact::Motion::Held)
    {
        return None;
    }
    held.iter()
        .find(|s| s.motion != contact::Motion::Held)
        .filter(|s| s.theta_start > e.theta)
        .map(|s| (s.phi_start, s.theta_start))
}

/// Why a lock's release moves the driven gear on, in a sentence for the outputs that show a
/// release.
pub const RELEASE_NOTE: &str = "A lock's release: the driven gear, held from both sides, is let go to the next position ahead at which no driver tooth overlaps it, as the paper's program did (\"allowing the driven gear to rotate freely ... until movement was possible again\"); that is usually a fraction of a driven pitch, but where eccentricity brings the gears too close for the teeth to pass (Case D, large systematic errors) the next free position can be a pitch or many pitches ahead, so the Theoretical Difference jumps by as much. The jump changes no jam count (a trial that locked has jammed).";

/// The index of a run's first lock: the motion after it is the paper's protocol, not a
/// physical one ([`PROTOCOL_NOTE`]).
pub fn first_lock(events: &[contact::Event]) -> Option<usize> {
    events
        .iter()
        .position(|e| e.kind == contact::EventKind::Lock)
}

/// What the outputs say of the motion after a run's first lock.
pub const PROTOCOL_NOTE: &str = "After the first lock the motion is the paper's protocol, not a physical one: a real mechanism stops at a lock (its driven gear is held from both sides), but the paper's program, and this one, let the driven gear go to the next free position ahead and drive it on, so that one run counts every failure of its turn. The events after the first lock, their releases and the Theoretical Difference there (greyed in pair.svg and pair.html) show that protocol: a release of many driven pitches is the gear let go past teeth it could not pass. The trial jammed at its first lock; a disengagement after it is counted under the protocol, as the paper counted (end=first-event counts only the first failure).";

/// The motion column of an event table: how the driven gear came to event `i` of a run whose
/// first lock is event `first` ([`first_lock`]).
pub fn motion_word(i: usize, first: Option<usize>) -> &'static str {
    match first {
        Some(f) if i == f => "driven; first lock: the protocol after it",
        Some(f) if i > f => "protocol (after the first lock)",
        _ => "driven",
    }
}

/// The note on an event table's motion column.
pub const MOTION_NOTE: &str = "motion: `driven` up to the first lock; `protocol (after the first lock)` for the events the paper's protocol of releases led to, which a real mechanism, stopped at its first lock, would not reach.";

/// How many driven pitches event `e` left the driven gear ahead of the ideal ratio by the time
/// drive resumed (`-lag`; behind it for a gap or slip, a negative), for a gear of `n2` teeth.
pub fn ahead_pitches(e: &contact::Event, n2: usize) -> f64 {
    -e.lag.to_degrees() / (360.0 / n2 as f64)
}

/// A lock's or strike's release in words, sized in driven pitches of a gear of `n2` teeth: how
/// far ahead of the ideal ratio it left the driven gear by the time drive resumed, let go at
/// once or after being held, and the change of tooth phase.
pub fn release_text(e: &contact::Event, n2: usize) -> String {
    let ahead = -e.lag.to_degrees();
    let pitches = ahead_pitches(e, n2);
    if !e.resumed {
        return format!("held to the end of the run, {}", off_ideal(pitches, ahead));
    }
    let how = if e.lost_motion > 0.0 {
        format!("held {:.3} driver pitch, then let go", e.lost_motion)
    } else {
        "released at once".to_owned()
    };
    format!(
        "{how}: {}, tooth phase {:+}",
        off_ideal(pitches, ahead),
        e.phase_shift
    )
}

/// `X driven pitches ahead of the ideal (D deg)`, or behind it for a negative `pitches`.
fn off_ideal(pitches: f64, degrees: f64) -> String {
    let side = if pitches < 0.0 { "behind" } else { "ahead of" };
    format!(
        "{:.2} driven pitches {side} the ideal ({:.3} deg)",
        pitches.abs(),
        degrees.abs()
    )
}

/// An event's size in words, in driven pitches of a gear of `n2` teeth where it moves the
/// pointer: a release ([`release_text`]) and its wedge angle, a loss of drive's lost motion,
/// lag and tooth phase, an idle start's wait.
pub fn size_text(e: &contact::Event, n2: usize) -> String {
    use contact::EventKind;
    let pitch = 360.0 / n2 as f64;
    match e.kind {
        EventKind::Lock | EventKind::Strike => {
            let wedge = e.wedge_angle.map_or_else(
                || "tip on tip".to_string(),
                |a| format!("wedge {:.1} deg", a.to_degrees()),
            );
            format!("{}, {wedge}", release_text(e, n2))
        }
        EventKind::Slip if e.idle_start && !e.resumed => format!(
            "never pushed: idle for the whole run ({:.3} driver pitches)",
            e.lost_motion
        ),
        EventKind::Slip if e.idle_start => format!(
            "first pushed {:.3} driver pitches after the start, lag {:.3} deg ({:.2} driven pitches)",
            e.lost_motion,
            e.lag.to_degrees(),
            e.lag.to_degrees() / pitch
        ),
        EventKind::Gap | EventKind::Slip => format!(
            "lost motion {:.3} driver pitch{}, lag {:.3} deg ({:.2} driven pitches), tooth phase {:+}",
            e.lost_motion,
            if e.resumed { "" } else { " (not resumed)" },
            e.lag.to_degrees(),
            e.lag.to_degrees() / pitch,
            e.phase_shift
        ),
        EventKind::BlockedAtStart => "no free position".to_string(),
    }
}

/// Whether event `e` moved the driven gear off the ideal ratio by a release or a change of
/// tooth phase: the events [`releases_note`] counts.
pub fn moves_pointer(e: &contact::Event) -> bool {
    e.phase_shift != 0 || (e.kind.is_contact_stop() && e.lag != 0.0)
}

/// The releases and tooth-phase shifts of a run in one sentence: how many, and how far in all
/// they put the driven gear (of `n2` teeth) ahead of the ideal ratio, in driven pitches; `None`
/// for a run with neither.
pub fn releases_note(events: &[contact::Event], n2: usize) -> Option<String> {
    let moved: Vec<&contact::Event> = events.iter().filter(|e| moves_pointer(e)).collect();
    if moved.is_empty() {
        return None;
    }
    let released = moved.iter().filter(|e| e.kind.is_contact_stop()).count();
    let ahead: f64 = moved
        .iter()
        .filter(|e| e.kind.is_contact_stop())
        .map(|e| ahead_pitches(e, n2))
        .sum();
    let phase: i64 = moved.iter().map(|e| e.phase_shift).sum();
    Some(format!(
        "Releases and tooth-phase shifts (each event's size column, in driven pitches): {released} release{} of a lock or strike, putting the driven gear {ahead:.2} driven pitches ahead of the ideal ratio in all; {} event{} that changed the tooth phase, {phase:+} teeth in all.",
        if released == 1 { "" } else { "s" },
        moved.iter().filter(|e| e.phase_shift != 0).count(),
        if moved.iter().filter(|e| e.phase_shift != 0).count() == 1 {
            ""
        } else {
            "s"
        },
    ))
}
