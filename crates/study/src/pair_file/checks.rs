//! The checks of a pair file that need more than one field: every length and angle within the
//! solver's range, enough samples, and proportions a mesh of real teeth can have (teeth shorter
//! than the gear, tips clear of the other gear's valleys), each refused naming the field.

use super::*;

/// Every length of the file from [`geometry::MIN_LENGTH`] to [`geometry::MAX_LENGTH`] in its
/// own unit (an offset anything up to the largest): the answer is the same in any unit only within them (a
/// pair scaled by 2e152 or 1e-160 counted a disengagement its unscaled self did not). Refused
/// naming the field, the value and the range.
pub(super) fn lengths(file: &str, spec: &PairFile) -> Result<(), RunError> {
    let mut given: Vec<(String, f64, bool)> = Vec::new();
    for (role, g) in [("driver", &spec.driver), ("driven", &spec.driven)] {
        given.push((format!("{role}.tip_radius"), g.tip_radius, false));
        given.push((format!("{role}.root_radius"), g.root_radius, false));
        if let Some((x, y)) = g.eccentricity {
            given.push((format!("{role}.eccentricity"), x, true));
            given.push((format!("{role}.eccentricity"), y, true));
        }
        if let Some(a) = g.arbor {
            given.push((format!("{role}.arbor.offset"), a.offset, true));
        }
    }
    if let Some(d) = spec.centre_distance {
        given.push(("centre_distance".into(), d, false));
    }
    for (field, x, offset) in given {
        let a = x.abs();
        // An offset may be as small as it likes (it adds nothing beside the radii), not larger.
        let fits = if offset {
            a <= geometry::MAX_LENGTH
        } else {
            (geometry::MIN_LENGTH..=geometry::MAX_LENGTH).contains(&a)
        };
        // Non-finite and negative values are the gear's and the distance's own rules to name.
        if x.is_finite() && (x > 0.0 || offset) && !fits {
            let range = if offset {
                format!("at most {} either way", fmt_number(geometry::MAX_LENGTH))
            } else {
                format!(
                    "from {} to {}",
                    fmt_number(geometry::MIN_LENGTH),
                    fmt_number(geometry::MAX_LENGTH)
                )
            };
            return Err(RunError::bad(
                file,
                field,
                format!(
                    "must be {range} in the file's length unit (got {}): beyond that range a double cannot hold the products the contact conditions form, and the answer would depend on the unit; give the lengths in another unit",
                    fmt_number(x)
                ),
            ));
        }
    }
    Ok(())
}

/// Every angle of the file within [`MAX_ANGLE_DEG`] either way (and finite): beyond it a double
/// no longer holds an angle as finely as the solver places a contact, and a run from there ends
/// nowhere or gives another answer without a word. Refused naming the field, the value and the
/// limit.
pub(super) fn angles(file: &str, spec: &PairFile) -> Result<(), RunError> {
    let mut given: Vec<(String, f64)> = vec![("start_deg".into(), spec.start_deg)];
    for (role, g) in [("driver", &spec.driver), ("driven", &spec.driven)] {
        if let Some(tips) = &g.tips_deg {
            given.extend(
                tips.iter()
                    .enumerate()
                    .map(|(k, &a)| (format!("{role}.tips_deg[{k}]"), a)),
            );
        }
        if let Some(a) = g.arbor {
            given.push((format!("{role}.arbor.angle_deg"), a.angle_deg));
        }
    }
    if let StartSpec::AtRest { theta_deg } = spec.start {
        given.push(("start.theta_deg".into(), theta_deg));
    }
    for (field, angle) in given {
        if !angle.is_finite() {
            return Err(RunError::bad(
                file,
                field,
                "must be a finite number of degrees",
            ));
        }
        if angle.abs() > MAX_ANGLE_DEG {
            return Err(RunError::bad(
                file,
                field,
                format!(
                    "must be at most {} degrees either way (got {}): beyond, a double holds an angle more coarsely than the solver places a contact (at 1e16 degrees its steps are 2 degrees) and the run would end nowhere or give another answer; an angle a whole number of turns (360 degrees) smaller names the same position",
                    fmt_number(MAX_ANGLE_DEG),
                    fmt_number(angle)
                ),
            ));
        }
    }
    Ok(())
}

/// The samples of pair.csv from which sigma, Dm and P are taken must describe the run: at least
/// [`SAMPLES_PER_TOOTH`] per driver pitch (the Theoretical Difference repeats every driver pitch,
/// and steps of a whole pitch, such as 360 degrees, see every tooth at the same phase: sigma 0),
/// and at least [`MIN_SAMPLES`] in all (a run of 1e-9 degrees has one sample). Refused naming the
/// field to change: `sample_deg` for a step too coarse for the teeth, else `run_deg` when it was
/// given, else `sample_deg`. `driving_teeth` are the driving gear's (the file's driver, or its
/// driven gear under `drive=other`): its angle is the one sampled.
pub(super) fn samples(
    file: &str,
    spec: &PairFile,
    run_deg: f64,
    driving_teeth: usize,
) -> Result<(), RunError> {
    let step = spec.sample_deg;
    let pitch = 360.0 / driving_teeth as f64;
    let finest = pitch / SAMPLES_PER_TOOTH as f64;
    if step > finest {
        return Err(RunError::bad(
            file,
            "sample_deg",
            format!(
                "must be at most {} degrees, a quarter of the driving gear's pitch 360/{} (got {}{}): sigma, Dm and P need {SAMPLES_PER_TOOTH} samples per tooth engagement, and steps of a whole pitch see every tooth at the same phase",
                fmt_number(finest),
                driving_teeth,
                fmt_number(step),
                if step == default_sample() {
                    ", the default"
                } else {
                    ""
                }
            ),
        ));
    }
    let count = (run_deg / step).floor() + 1.0;
    if count < MIN_SAMPLES as f64 {
        let why = format!(
            "{} degrees of driver angle in steps of {} give {} sample{} of the Theoretical Difference, and sigma, Dm and P need at least {MIN_SAMPLES}",
            fmt_number(run_deg),
            fmt_number(step),
            fmt_number(count),
            if count == 1.0 { "" } else { "s" }
        );
        let longest_step = run_deg / (MIN_SAMPLES - 1) as f64;
        return Err(match spec.run_deg {
            Some(_) => RunError::bad(
                file,
                "run_deg",
                format!(
                    "is too short: {why}; give a run_deg of at least {} degrees",
                    fmt_number(step * (MIN_SAMPLES - 1) as f64)
                ),
            ),
            None => RunError::bad(
                file,
                "sample_deg",
                format!(
                    "must be at most {} degrees: {why}",
                    fmt_number(longest_step)
                ),
            ),
        });
    }
    Ok(())
}

/// The tallest tooth, as a share of its tip radius: half (root radius at least half the tip
/// radius). Thorndike's example pair (`fig2`, R = 200, r = 100) is at this limit; the Freeth
/// gearing's teeth are 1.1 mm on radii of 3.4 to 65 mm (at most a third).
pub const MAX_TOOTH_HEIGHT_SHARE: f64 = 0.5;

/// How many times larger one gear's tooth pitch (2π·tip_radius/teeth) may be than the other's.
/// Gears that mesh have teeth of one size (the Freeth gearing's are fitted to one pitch).
pub const MAX_PITCH_RATIO: f64 = 10.0;

/// How many times taller one gear's teeth may be than the other's. The Freeth gearing's are all
/// one height.
pub const MAX_HEIGHT_RATIO: f64 = 4.0;

/// The proportions the solver's work per driver pitch depends on, checked in numbers without a
/// unit, so that a file in any length unit is judged alike. Beyond them the work of one pitch
/// grows without bound (a tip radius of 1.8e19 over a root radius of 180 took a minute): teeth
/// as tall as the gear are needles whose contacts the solver resolves a hair at a time, teeth
/// of very different sizes bring hundreds of teeth of one gear against one of the other, and
/// tips that reach below the other gear's valleys wherever the gears turn put one gear among
/// the other's teeth.
pub(super) fn proportions(file: &str, mesh: &Mesh, distance_field: &str) -> Result<(), RunError> {
    let gears = [("driver", mesh.driver()), ("driven", mesh.driven())];
    let largest = mesh.driver().tip_radius().max(mesh.driven().tip_radius());
    let smallest_deciding = geometry::MIN_DECIDING_SHARE * largest;
    for (which, g) in gears {
        tooth_height(file, (which, g), smallest_deciding)?;
    }
    let [(_, g1), (_, g2)] = gears;
    // The larger of the two is named: the gear whose size is out of line with the other's.
    let larger = |a: f64, b: f64| {
        if a >= b {
            ("driver", "driven", a, b)
        } else {
            ("driven", "driver", b, a)
        }
    };
    let pitch = |g: &Gear| TAU * g.tip_radius() / g.teeth() as f64;
    let (p1, p2) = (pitch(g1), pitch(g2));
    if p1.max(p2) > MAX_PITCH_RATIO * p1.min(p2) {
        let (big, small, pb, ps) = larger(p1, p2);
        return Err(RunError::bad(
            file,
            format!("{big}.tip_radius"),
            format!(
                "the gears' teeth must be of one size: the {big} gear's tooth pitch 2π·tip_radius/teeth = {} is more than {MAX_PITCH_RATIO} times the {small} gear's {} (meshing gears have teeth of one pitch)",
                fmt_number(pb),
                fmt_number(ps)
            ),
        ));
    }
    let (h1, h2) = (g1.tooth_height(), g2.tooth_height());
    if h1.max(h2) > MAX_HEIGHT_RATIO * h1.min(h2) {
        let (big, small, hb, hs) = larger(h1, h2);
        return Err(RunError::bad(
            file,
            format!("{big}.root_radius"),
            format!(
                "the gears' teeth must be of one size: the {big} gear's tooth height tip_radius - root_radius = {} is more than {MAX_HEIGHT_RATIO} times the {small} gear's {} (meshing gears have teeth of one height)",
                fmt_number(hb),
                fmt_number(hs)
            ),
        ));
    }
    tips_clear_valleys(file, mesh, distance_field, smallest_deciding)
}

/// Three significant digits: a length computed from the file's, for a message.
fn short(x: f64) -> String {
    fmt_number(format!("{x:.2e}").parse().unwrap_or(x))
}

/// Gear `which`'s tooth height against its tip radius: tall enough for the solver to tell from
/// rounding (`smallest_deciding`, a length), at most half the tip radius.
fn tooth_height(
    file: &str,
    (which, g): (&str, &Gear),
    smallest_deciding: f64,
) -> Result<(), RunError> {
    let (big_r, small_r) = (g.tip_radius(), g.root_radius());
    if big_r - small_r < smallest_deciding {
        return Err(RunError::bad(
            file,
            format!("{which}.root_radius"),
            format!(
                "leaves a tooth height tip_radius - root_radius of {}, less than {} of the larger tip radius ({}): a tooth that low is below what the solver can tell from rounding, and its jams would be noise",
                short(big_r - small_r),
                fmt_number(geometry::MIN_DECIDING_SHARE),
                short(smallest_deciding)
            ),
        ));
    }
    if big_r - small_r > MAX_TOOTH_HEIGHT_SHARE * big_r {
        return Err(RunError::bad(
            file,
            format!("{which}.root_radius"),
            format!(
                "must be at least half of tip_radius ({}; got {}): the tooth height tip_radius - root_radius may be at most half the tip radius (Thorndike's example pair, R = 200 and r = 100, is at this limit; the Freeth gearing's teeth are at most a third of their radius)",
                fmt_number(MAX_TOOTH_HEIGHT_SHARE * big_r),
                fmt_number(small_r)
            ),
        ));
    }
    Ok(())
}

/// The clearance G > 0 of eccentric gears where they are farthest apart, and large enough for
/// the solver to tell from touching (`smallest_deciding`, a length); refused naming
/// `distance_field`.
fn tips_clear_valleys(
    file: &str,
    mesh: &Mesh,
    distance_field: &str,
    smallest_deciding: f64,
) -> Result<(), RunError> {
    let (g1, g2) = (mesh.driver(), mesh.driven());
    // The clearance G > 0 of eccentric gears: their tip circles' centres are at most
    // D + |e1| + |e2| apart, so at or below R + r the tips of one gear reach below the other's
    // valleys at every angle (concentric gears are refused so by `Mesh::new`).
    let farthest =
        mesh.centre_distance() + g1.rotation_centre().norm() + g2.rotation_centre().norm();
    for (tips, valleys, g, other) in [("driver", "driven", g1, g2), ("driven", "driver", g2, g1)] {
        let deepest = g.max_tip_radius() + other.min_root_radius();
        if farthest > deepest && farthest - deepest < smallest_deciding {
            return Err(RunError::bad(
                file,
                distance_field,
                format!(
                    "leaves the {tips} gear's tips {} from the {valleys} gear's valleys where the gears are farthest apart, less than {} of the larger tip radius ({}): a clearance that small is below what the solver can tell from touching, and its jams would be noise",
                    short(farthest - deepest),
                    fmt_number(geometry::MIN_DECIDING_SHARE),
                    short(smallest_deciding)
                ),
            ));
        }
        if farthest <= deepest {
            return Err(RunError::bad(
                file,
                distance_field,
                format!(
                    "the {tips} gear's tips reach below the {valleys} gear's valleys at every angle: even where the gears are farthest apart their tip-circle centres are D + |e1| + |e2| = {} apart, at most the {tips} tip radius plus the {valleys} root radius, {} (clearance G must be above 0 there)",
                    fmt_number(farthest),
                    fmt_number(deepest)
                ),
            ));
        }
    }
    Ok(())
}
