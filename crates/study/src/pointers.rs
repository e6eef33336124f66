//! Pointer runs: each pointer's run length (in turns of b) and how finely its Theoretical
//! Difference is sampled, checked against the gearing.

use registry::{Context, Param, RunError};

/// The shortest run a `*_turns` parameter may ask for, in turns of b: 0.05 turn is 11 tooth
/// engagements of b1's mesh, about the fewest a σ of the pointer's error can be read from (at
/// 10^-300 turns every sample is at the same angle and σ is 0).
pub const MIN_TURNS: f64 = 0.05;

/// How finely the Theoretical Difference is sampled (table1 and table6).
pub const SAMPLES_PER_ENGAGEMENT: Param = Param {
    name: "samples_per_engagement",
    default: "16",
    unit: "",
    help: "TD samples per tooth engagement of the busiest mesh",
    kind: registry::Kind::count(
        registry::MIN_PER_ENGAGEMENT,
        registry::MAX_COUNT as u64,
        registry::MIN_PER_ENGAGEMENT_WHY,
    ),
};

/// Run length of the Lunar pointer.
pub const LUNAR_TURNS: Param = Param {
    name: "lunar_turns",
    default: "1",
    unit: "turns of b",
    help: "run length, Lunar (Table 1 caption: one turn of b2)",
    kind: registry::Kind::number(
        MIN_TURNS,
        100.0,
        "turns of b: a shorter run spans too few tooth engagements for a sigma",
    ),
};

/// Run length of the Metonic pointer.
pub const METONIC_TURNS: Param = Param {
    name: "metonic_turns",
    default: "3.8",
    unit: "turns of b",
    help: "run length, Metonic (caption: 3.8 turns)",
    kind: registry::Kind::number(
        MIN_TURNS,
        100.0,
        "turns of b: a shorter run spans too few tooth engagements for a sigma",
    ),
};

/// Run length of the Saros pointer.
pub const SAROS_TURNS: Param = Param {
    name: "saros_turns",
    default: "4.5",
    unit: "turns of b",
    help: "run length, Saros (caption: 4.5 turns)",
    kind: registry::Kind::number(
        MIN_TURNS,
        100.0,
        "turns of b: a shorter run spans too few tooth engagements for a sigma",
    ),
};

/// Run length of the Games pointer.
pub const GAMES_TURNS: Param = Param {
    name: "games_turns",
    default: "3.8",
    unit: "turns of b",
    help: "run length, Games (caption silent: as Metonic)",
    kind: registry::Kind::number(
        MIN_TURNS,
        100.0,
        "turns of b: a shorter run spans too few tooth engagements for a sigma",
    ),
};

/// Run length of the Exeligmos pointer.
pub const EXELIGMOS_TURNS: Param = Param {
    name: "exeligmos_turns",
    default: "4.5",
    unit: "turns of b",
    help: "run length, Exeligmos (caption silent: as Saros)",
    kind: registry::Kind::number(
        MIN_TURNS,
        100.0,
        "turns of b: a shorter run spans too few tooth engagements for a sigma",
    ),
};

/// The five pointers' run lengths and the TD sampling (Tables 1 and 6).
pub const RUN_LENGTHS: &[Param] = &[
    LUNAR_TURNS,
    METONIC_TURNS,
    SAROS_TURNS,
    GAMES_TURNS,
    EXELIGMOS_TURNS,
    SAMPLES_PER_ENGAGEMENT,
];

/// Pointers in the paper's column order, with the parameter holding each run length.
pub const POINTERS: [(&str, &str); 5] = [
    ("Lunar", "lunar_turns"),
    ("Metonic", "metonic_turns"),
    ("Saros", "saros_turns"),
    ("Games", "games_turns"),
    ("Exeligmos", "exeligmos_turns"),
];

/// A table's header over the five pointers, in the paper's column order (Tables 1 and 6).
pub const COLUMNS: [&str; 6] = [
    "",
    "Lunar",
    "Metonic",
    "Eclipse (Saros)",
    "Games",
    "Exeligmos",
];

/// (pointer, input turns, TD samples) for each (pointer, run-length parameter), checked.
pub fn pointer_runs<'a>(
    ctx: &Context,
    g: &train::Gearing,
    pointers: &[(&'a str, &str)],
    per: usize,
) -> Result<Vec<(&'a str, f64, usize)>, RunError> {
    let mut runs = Vec::new();
    for &(name, param) in pointers {
        let turns = ctx.f64(param)?;
        if g.pointer(name).is_none() {
            return Err(RunError::bad(
                "gearing",
                format!("pointer {name}"),
                "is missing from the gearing",
            ));
        }
        runs.push((name, turns, samples_for(g, name, turns, per)));
    }
    Ok(runs)
}

/// Samples needed so that the busiest mesh of a pointer's train gets `per` samples per tooth
/// engagement over `turns` input turns.
pub fn samples_for(g: &train::Gearing, pointer: &str, turns: f64, per: usize) -> usize {
    let mut arbor_turns = 1.0;
    let mut busiest: f64 = 1.0;
    for label in g
        .pointer(pointer)
        .map(|p| p.meshes.clone())
        .unwrap_or_default()
    {
        let (Some(m), Some(r)) = (g.mesh(&label), g.mesh_ratio(&label)) else {
            continue;
        };
        let teeth = g.gear(&m.driver).map_or(1.0, |x| f64::from(x.teeth));
        busiest = busiest.max(arbor_turns * teeth);
        arbor_turns *= r.to_f64();
    }
    ((busiest * turns * per as f64).ceil() as usize).max(100)
}
