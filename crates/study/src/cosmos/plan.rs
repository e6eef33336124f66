//! The plan of the cosmos display's gearing: each gear's pitch radius, each arbor's axis and each
//! mesh's centre distance at a clearance, the layout its picture is drawn from.

use super::*;

/// One gear of the plan: its name, teeth and pitch radius (mm).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannedGear {
    /// Gear name.
    pub name: String,
    /// Teeth.
    pub teeth: u32,
    /// Pitch radius at the run's h, mm (tip radius less h / 2).
    pub pitch_radius: f64,
}

/// One arbor of the plan: where its axis stands in b1's frame (mm, b's axis at the origin).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannedArbor {
    /// Arbor name.
    pub name: String,
    /// Its axis, mm.
    pub x: f64,
    /// Its axis, mm.
    pub y: f64,
    /// Whether it is the arbor of the gears fixed to the frame.
    pub fixed: bool,
    /// Its gears, in file order.
    pub gears: Vec<PlannedGear>,
}

/// One mesh of the plan: its label and the arbors of its driver and driven gear.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannedMesh {
    /// Mesh label.
    pub mesh: String,
    /// The driver's arbor.
    pub from: String,
    /// The driven gear's arbor.
    pub to: String,
}

/// A schematic plan of a cosmos train in b1's frame: every arbor at its true centre distance
/// (pitch radii plus the run's clearance) from the arbor that drives it, the directions chosen
/// for legibility (trains fanned out from the centre); the output tubes that turn on b's axis
/// stand where their mesh puts them, not at the centre.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrainPlan {
    /// b1's radius, mm: the carrier drawn round the centre.
    pub carrier_radius: f64,
    /// The fixed arbor, then each carried arbor, by name.
    pub arbors: Vec<PlannedArbor>,
    /// The meshes between placed arbors, in file order.
    pub meshes: Vec<PlannedMesh>,
}

/// Each carried arbor's axis (mm, b's axis at the origin) and the direction of the ray that
/// reached it, placed breadth-first from the fixed arbor at its centre distance from the arbor
/// that drives it; the first arbors fanned evenly round, each later one turned from its
/// parent's ray.
fn arbor_axes(
    g: &Gearing,
    clearance_mm: f64,
    pitch: &dyn Fn(&str) -> f64,
) -> std::collections::BTreeMap<String, (f64, f64, f64)> {
    let mut at = std::collections::BTreeMap::new();
    let Some(e) = g.epicyclic() else {
        return at;
    };
    at.insert(e.fixed.clone(), (0.0, 0.0, 0.0));
    let mut queue = std::collections::VecDeque::from([e.fixed.clone()]);
    while let Some(arbor) = queue.pop_front() {
        let (x, y, dir) = at[&arbor];
        let out: Vec<&train::MeshData> = g
            .meshes()
            .iter()
            .filter(|m| g.arbor_of(&m.driver) == Some(arbor.as_str()))
            .filter(|m| g.arbor_of(&m.driven).is_some_and(|a| !at.contains_key(a)))
            .collect();
        let n = out.len();
        for (k, m) in out.into_iter().enumerate() {
            let Some(next) = g.arbor_of(&m.driven) else {
                continue;
            };
            let d = pitch(&m.driver) + pitch(&m.driven) + clearance_mm;
            let a = if arbor == e.fixed {
                TAU * k as f64 / n.max(1) as f64 + 0.3
            } else {
                dir + 1.1 * (k as f64 - (n as f64 - 1.0) / 2.0) + 0.3
            };
            at.insert(next.to_owned(), (x + d * a.cos(), y + d * a.sin(), a));
            queue.push_back(next.to_owned());
        }
    }
    at
}

/// The plan of `g`'s cosmos train at clearance `clearance_mm` and tooth height `h` (mm).
pub fn plan(g: &Gearing, clearance_mm: f64, h: f64) -> TrainPlan {
    let pitch = |name: &str| g.tip_radius_at(name, h).map_or(0.0, |r| r - h / 2.0);
    let axes = arbor_axes(g, clearance_mm, &pitch);
    let fixed = g.epicyclic().map(|e| e.fixed.as_str());
    let arbors = axes
        .iter()
        .map(|(name, &(x, y, _))| PlannedArbor {
            name: name.clone(),
            x,
            y,
            fixed: Some(name.as_str()) == fixed,
            gears: g
                .arbor(name)
                .map(|a| a.gears.clone())
                .unwrap_or_default()
                .into_iter()
                .map(|gear| PlannedGear {
                    teeth: g.gear(&gear).map_or(0, |d| d.teeth),
                    pitch_radius: pitch(&gear),
                    name: gear,
                })
                .collect(),
        })
        .collect();
    let meshes = g
        .meshes()
        .iter()
        .filter_map(|m| {
            let (from, to) = (g.arbor_of(&m.driver)?, g.arbor_of(&m.driven)?);
            (axes.contains_key(from) && axes.contains_key(to)).then(|| PlannedMesh {
                mesh: m.label.clone(),
                from: from.to_owned(),
                to: to.to_owned(),
            })
        })
        .collect();
    TrainPlan {
        carrier_radius: g.fitted_radius("b1").unwrap_or(64.4),
        arbors,
        meshes,
    }
}
