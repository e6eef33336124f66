//! The RON loaders under fuzzing, and what must hold of whatever they return.
//!
//! Shared by `cargo xtask fuzz` (stable Rust, `src/fuzz.rs`) and the cargo-fuzz targets in
//! `fuzz/fuzz_targets/` (which include this file by path), so both check the same promises. A
//! target returns `Ok` with what the loader did (accepted, or refused with its message) or `Err`
//! naming a broken promise; a panic is left to the caller to catch.
//!
//! Promises checked, beyond "no panic":
//! - a refusal is one line that names the file (`fuzz.ron`);
//! - a field name that is not part of the format is refused, never silently ignored;
//! - an accepted gearing answers every query (`tip_radius` of every gear positive and finite,
//!   `mesh_ratio` and `mesh_geometry` of every mesh, `days_per_degree` finite where given);
//! - an accepted measured table holds only values its own checks accept, and applying each row
//!   to an ideal gear returns a gear or an error;
//! - an accepted pair config (`study::pair_file::prepare`) gives a mesh with at least 3 and at
//!   most `geometry::MAX_TEETH` teeth per gear, finite radii and a finite positive centre
//!   distance at which the gears can touch; every angle it gives (start, tips, arbor, at-rest
//!   start) is within `registry::MAX_ANGLE_DEG`; its samples number at least
//!   `registry::MIN_SAMPLES`, four or more per driver pitch; and (for gears of at most 2000
//!   teeth, so that an input stays fast) the mesh runs one driver pitch from the file's own
//!   start angle and start to a finite driven angle, ending where it was asked to.

use std::collections::BTreeSet;

use contact::Solve;

/// The file name the loaders are given; every refusal must name it.
pub const FILE: &str = "fuzz.ron";

/// What a loader did with one input.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Outcome {
    /// Accepted, and every promise about the result held.
    Accepted,
    /// Refused with this message.
    Refused(String),
}

/// A fuzz target: the loader on one input; `Err` names a broken promise.
pub type Target = fn(&str) -> Result<Outcome, String>;

/// Every target: name, function, and the shipped file that seeds its corpus.
pub const TARGETS: &[(&str, Target, &str)] = &[
    ("gearing", gearing, train::FREETH2006_RON),
    ("measured", measured, hypotheses::MEASURED_EXAMPLE),
    ("pair", pair, PAIR_EXAMPLE),
];

/// The shipped pair config, `experiments/data/pair-example.ron`.
const PAIR_EXAMPLE: &str = include_str!("../../experiments/data/pair-example.ron");

/// Field names of the pair config format (`experiments/data/pair-example.ron`).
const PAIR_FIELDS: &[&str] = &[
    "driver",
    "driven",
    "teeth",
    "tip_radius",
    "root_radius",
    "tips_deg",
    "eccentricity",
    "centre_distance",
    "clearance_percent",
    "start_deg",
    "run_deg",
    "sample_deg",
    "sense",
    "eccentricity_frame",
    "arbor",
    "offset",
    "angle_deg",
    "start",
    "touching",
    "at_rest",
    "theta_deg",
];

/// Field names of the gearing format (`crates/train/data/freeth2006.ron`).
const GEARING_FIELDS: &[&str] = &[
    "gears",
    "arbors",
    "meshes",
    "pointers",
    "name",
    "teeth",
    "measured_radius",
    "source",
    "label",
    "driver",
    "driven",
    "input",
    "days",
    "pin_and_slot",
    "pin_gear",
    "slot_gear",
    "turntable",
    "axis_offset",
    "pin_radius",
];

/// Field names of the measured-errors format (`crates/hypotheses/data/measured-example.ron`).
const MEASURED_FIELDS: &[&str] = &["split", "gears", "gear", "random", "systematic", "phase"];

/// A refusal must be one non-empty line naming the file.
fn check_refusal(message: String) -> Result<Outcome, String> {
    if message.contains('\n') {
        return Err(format!("refusal is not one line: {message:?}"));
    }
    if !message.starts_with(FILE) {
        return Err(format!("refusal does not name the file first: {message:?}"));
    }
    Ok(Outcome::Refused(message))
}

/// Field names in `text` (identifiers followed by `:`), outside strings and comments.
pub fn field_names(text: &str) -> BTreeSet<String> {
    let b = text.as_bytes();
    let mut names = BTreeSet::new();
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
                i += 1;
            }
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'/' if b.get(i + 1) == Some(&b'*') => {
                let (mut depth, mut j) = (1, i + 2);
                while j < b.len() && depth > 0 {
                    if b[j] == b'/' && b.get(j + 1) == Some(&b'*') {
                        depth += 1;
                        j += 1;
                    } else if b[j] == b'*' && b.get(j + 1) == Some(&b'/') {
                        depth -= 1;
                        j += 1;
                    }
                    j += 1;
                }
                i = j;
            }
            c if c.is_ascii_alphabetic() || c == b'_' => {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                let mut j = i;
                while j < b.len() && b[j].is_ascii_whitespace() {
                    j += 1;
                }
                if b.get(j) == Some(&b':') && b.get(j + 1) != Some(&b':') {
                    names.insert(text[start..i].to_owned());
                }
            }
            _ => i += 1,
        }
    }
    names
}

/// An accepted input must not have carried a field outside the format.
fn check_fields(text: &str, known: &[&str]) -> Result<(), String> {
    match field_names(text)
        .into_iter()
        .find(|n| !known.contains(&n.as_str()))
    {
        Some(n) => Err(format!(
            "accepted a file with field `{n}`, which is not part of the format (a typo is silently ignored)"
        )),
        None => Ok(()),
    }
}

/// `train::Gearing::from_ron`, then every query on what it accepted.
pub fn gearing(text: &str) -> Result<Outcome, String> {
    let g = match train::Gearing::from_ron(FILE, text) {
        Ok(g) => g,
        Err(e) => return check_refusal(e.to_string()),
    };
    check_fields(text, GEARING_FIELDS)?;
    // Names reach tables, data files and terminals, and mesh labels name replayable cells.
    let names = g
        .gears()
        .iter()
        .map(|x| &x.name)
        .chain(g.meshes().iter().map(|m| &m.label))
        .chain(g.pointers().iter().map(|p| &p.name));
    for name in names {
        if name.chars().any(char::is_control) {
            return Err(format!(
                "accepted the name {name:?}, holding a control character"
            ));
        }
    }
    if let Some(m) = g.meshes().iter().find(|m| m.label.contains('/')) {
        return Err(format!(
            "accepted the mesh label {:?}, holding a /",
            m.label
        ));
    }
    for gear in g.gears() {
        match g.tip_radius(&gear.name) {
            Some(r) if r.is_finite() && r > 0.0 => {}
            other => {
                return Err(format!(
                    "accepted gear {} ({} teeth, measured radius {:?}) has tip radius {other:?}",
                    gear.name, gear.teeth, gear.measured_radius
                ));
            }
        }
    }
    for mesh in g.meshes() {
        if g.mesh_ratio(&mesh.label).is_none() {
            return Err(format!("accepted mesh {} has no ratio", mesh.label));
        }
        let Some(m) = g.mesh_geometry(&mesh.label, 1.1, 40.0) else {
            return Err(format!("accepted mesh {} has no geometry", mesh.label));
        };
        if !m.centre_distance.is_finite() {
            return Err(format!(
                "accepted mesh {} has centre distance {}",
                mesh.label, m.centre_distance
            ));
        }
    }
    for p in g.pointers() {
        // `None` is documented for a ratio that overflows u128.
        if let Some(r) = g.pointer_ratio(&p.name)
            && (r.num == 0 || r.den == 0)
        {
            return Err(format!("accepted pointer {} has ratio {r}", p.name));
        }
        if let Some(d) = g.days_per_degree(&p.name)
            && !(d.is_finite() && d > 0.0)
        {
            return Err(format!(
                "accepted pointer {} has {d} days per degree",
                p.name
            ));
        }
    }
    let _ = g.tip_radii();
    Ok(Outcome::Accepted)
}

/// A deterministic stand-in for a random number generator (splitmix64).
struct Stream(u64);

impl hypotheses::rand::RngCore for Stream {
    fn next_u32(&mut self) -> u32 {
        (self.next_u64() >> 32) as u32
    }

    fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn fill_bytes(&mut self, dest: &mut [u8]) {
        for chunk in dest.chunks_mut(8) {
            let bytes = self.next_u64().to_le_bytes();
            chunk.copy_from_slice(&bytes[..chunk.len()]);
        }
    }
}

/// `hypotheses::measured_from_ron`, then every row checked and applied to an ideal gear.
pub fn measured(text: &str) -> Result<Outcome, String> {
    use hypotheses::Hypothesis as _;

    let table = match hypotheses::measured_from_ron(FILE, text) {
        Ok(t) => t,
        Err(e) => return check_refusal(e.to_string()),
    };
    check_fields(text, MEASURED_FIELDS)?;
    if !(0.0..=1.0).contains(&table.split()) {
        return Err(format!("accepted table split {}", table.split()));
    }
    let gear = geometry::Gear::ideal(24, 10.0, 9.0)
        .map_err(|e| format!("the fuzzer's own ideal gear: {e}"))?;
    let hypothesis = table.hypothesis();
    let params = hypotheses::Params::new(&hypothesis, &[])
        .map_err(|e| format!("default params of measured: {e}"))?;
    let mut rng = Stream(1);
    for (name, _) in table.entries() {
        let errors = table
            .errors(name)
            .map_err(|e| format!("accepted gear {name} has no errors: {e}"))?;
        if let Err(e) = errors.check(&format!("{FILE}: gear {name}")) {
            return Err(format!("accepted gear {name} fails its own check: {e}"));
        }
        // Either outcome is fine; only a panic or a non-finite gear is not.
        if let Ok(g) = hypothesis.apply(&gear, name, &params, &mut rng)
            && g.tip_angles().iter().any(|a| !a.is_finite())
        {
            return Err(format!("gear {name} manufactured with non-finite tips"));
        }
    }
    Ok(Outcome::Accepted)
}

/// The angles and samples of an accepted pair file: every angle within the limit, and enough
/// samples for sigma, Dm and P.
fn pair_angles(spec: &study::pair_file::PairFile) -> Result<(), String> {
    let mut angles = vec![("start_deg", spec.start_deg)];
    for g in [&spec.driver, &spec.driven] {
        angles.extend(g.tips_deg.iter().flatten().map(|&a| ("tips_deg", a)));
    }
    if let study::pair_file::StartSpec::AtRest { theta_deg } = spec.start {
        angles.push(("start.theta_deg", theta_deg));
    }
    if let Some((field, a)) = angles
        .into_iter()
        .find(|(_, a)| !(a.is_finite() && a.abs() <= registry::MAX_ANGLE_DEG))
    {
        return Err(format!("accepted {field} {a}, beyond the limit on angles"));
    }
    let run = spec
        .run_deg
        .unwrap_or_else(|| study::pair_file::default_run_deg(spec.driver.teeth, spec.driven.teeth));
    let samples = (run / spec.sample_deg).floor() + 1.0;
    let pitch = 360.0 / spec.driver.teeth as f64;
    if samples < registry::MIN_SAMPLES as f64 || spec.sample_deg * 4.0 > pitch * (1.0 + 1e-12) {
        return Err(format!(
            "accepted sample_deg {} over run_deg {run} ({samples} samples, driver pitch {pitch})",
            spec.sample_deg
        ));
    }
    Ok(())
}

/// `study::pair_file::prepare`, then the accepted mesh checked and run over one driver pitch
/// from the file's start angle and start.
pub fn pair(text: &str) -> Result<Outcome, String> {
    let prepared = match study::pair_file::prepare(FILE, text) {
        Ok(p) => p,
        Err(e) => return check_refusal(e.to_string()),
    };
    check_fields(text, PAIR_FIELDS)?;
    pair_angles(&prepared.spec)?;
    let mesh = &prepared.mesh;
    let d = mesh.centre_distance();
    if !(d.is_finite() && d > 0.0) {
        return Err(format!("accepted centre distance {d}"));
    }
    let mut reach = d;
    let largest = mesh.driver().tip_radius().max(mesh.driven().tip_radius());
    for (which, g) in [("driver", mesh.driver()), ("driven", mesh.driven())] {
        if !(3..=geometry::MAX_TEETH).contains(&g.teeth()) {
            return Err(format!("accepted {which} with {} teeth", g.teeth()));
        }
        // Lengths within the range where the answer is the same in every unit, and no tooth
        // too low to tell from rounding.
        if !(geometry::MIN_LENGTH..=geometry::MAX_LENGTH).contains(&g.tip_radius())
            || g.tip_radius() - g.root_radius() < geometry::MIN_DECIDING_SHARE * largest
        {
            return Err(format!(
                "accepted {which} with radii {} and {} (the larger tip radius {largest})",
                g.tip_radius(),
                g.root_radius()
            ));
        }
        if !(g.tip_radius().is_finite() && g.root_radius().is_finite()) {
            return Err(format!(
                "accepted {which} with radii {} and {}",
                g.tip_radius(),
                g.root_radius()
            ));
        }
        reach -= g.max_tip_radius() + g.rotation_centre().norm();
    }
    if reach >= 0.0 {
        return Err(format!(
            "accepted gears that never touch (centre distance {d} exceeds their reach by {reach})"
        ));
    }
    if mesh.driver().teeth().max(mesh.driven().teeth()) > 2000 {
        return Ok(Outcome::Accepted);
    }
    let pitch = std::f64::consts::TAU / mesh.driver().teeth() as f64;
    let phi0 = prepared.spec.start_deg.to_radians();
    let traj = mesh.solve(phi0..=phi0 + pitch, prepared.start, Solve::path());
    let theta = traj.theta_at(phi0 + pitch);
    if !theta.is_finite() {
        return Err(format!("the accepted mesh ran to driven angle {theta}"));
    }
    if traj.phi_end() < phi0 + pitch * (1.0 - 1e-9) {
        return Err(format!(
            "the accepted mesh's run from {} deg ended at {} deg, short of one driver pitch",
            prepared.spec.start_deg,
            traj.phi_end().to_degrees()
        ));
    }
    Ok(Outcome::Accepted)
}

#[cfg(test)]
#[allow(clippy::unwrap_used)] // Reason: tests fail loudly on purpose.
mod tests {
    use super::*;

    #[test]
    fn shipped_files_are_accepted() {
        for (name, target, seed) in TARGETS {
            assert_eq!(target(seed), Ok(Outcome::Accepted), "{name}");
        }
    }

    #[test]
    fn field_names_skip_strings_and_comments() {
        let names = field_names(
            "( a: 1, // b: 2\n \"c: 3\", /* d: /* e: */ f: */ g : Some(h), i::j, k_2:\"x\\\"l: \")",
        );
        let got: Vec<&str> = names.iter().map(String::as_str).collect();
        assert_eq!(got, ["a", "g", "k_2"]);
    }

    #[test]
    fn refusals_must_be_one_line_naming_the_file() {
        assert!(check_refusal(format!("{FILE}: x: y")).is_ok());
        assert!(check_refusal(format!("{FILE}: x\ny")).is_err());
        assert!(check_refusal("other.ron: x".into()).is_err());
    }
}
