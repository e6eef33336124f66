//! Tolerances in units a person can measure on a gear, drawn the same way under every table that
//! prints one (Tables 4 and 5, Figure 6, the tolerance search, the clearance design): per gear,
//! the random error beside its fraction of the pitch as degrees of the gear's turn and
//! millimetres along the tip circle, and the systematic amplitude in degrees as the eccentricity
//! of the axis and the wave of the teeth in millimetres ([`study::units`]).

use registry::{Table, fmt_f64};
use study::cell::label;
use study::units::{GearSize, MeshGears};

/// One error as a table holds it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// This value.
    At(f64),
    /// Below the grid: even its smallest value, this one, breaks the rule.
    Below(f64),
    /// At least this: the top of the range searched, which kept the rule.
    AtLeast(f64),
    /// Not run, or not given.
    Missing,
}

impl Value {
    /// A tolerance read from a grid whose smallest value is `smallest`: `None` is below it.
    pub fn of(v: Option<f64>, smallest: Option<f64>) -> Value {
        match (v, smallest) {
            (Some(v), _) => Value::At(v),
            (None, Some(s)) => Value::Below(s),
            (None, None) => Value::Missing,
        }
    }

    /// The value printed with `show` (the value converted and formatted), `< ` before a value
    /// below the grid, `-` for none.
    fn cell(self, show: impl Fn(f64) -> String) -> String {
        match self {
            Value::At(v) => show(v),
            Value::Below(v) => format!("< {}", show(v)),
            Value::AtLeast(v) => format!(">= {}", show(v)),
            Value::Missing => "-".into(),
        }
    }
}

/// One row of a units table: one gear and the errors it is given.
#[derive(Debug, Clone, PartialEq)]
pub struct GearRow {
    /// What the row's errors belong to: the mesh, the gear's meshes, or a Case and mesh.
    pub label: String,
    /// The gear: its name, teeth and tip radius.
    pub gear: GearSize,
    /// The random error, fraction of the pitch 360/N.
    pub random: Value,
    /// The systematic amplitude A, degrees.
    pub systematic: Value,
}

/// Decimals of the degrees and millimetres printed: thousandths, a few micrometres, below any
/// measurement of the fragments.
const DECIMALS: usize = 3;

/// The columns of a units table whose first column is `what`; with the systematic columns when
/// `split` is given.
pub fn columns(what: &str, split: Option<f64>) -> Vec<String> {
    let mut c: Vec<String> = [
        what,
        "gear",
        "N",
        "R [mm]",
        "random [pitch]",
        "random [deg]",
        "random at tip [mm]",
    ]
    .map(String::from)
    .to_vec();
    if split.is_some() {
        c.extend(["systematic A [deg]", "eccentricity [mm]", "tooth wave [mm]"].map(String::from));
    }
    c
}

/// A row's cells: the gear, its random error three ways and, with `split`, its systematic
/// amplitude as degrees, eccentricity and wave.
fn cells(r: &GearRow, split: Option<f64>) -> Vec<String> {
    let g = &r.gear;
    let mut c = vec![
        r.label.clone(),
        g.gear.clone(),
        g.teeth.to_string(),
        fmt_f64(g.tip_radius, 2),
        r.random.cell(|v| label(v, 3)),
        r.random.cell(|v| fmt_f64(g.random(v).degrees, DECIMALS)),
        r.random.cell(|v| fmt_f64(g.random(v).tip_mm, DECIMALS)),
    ];
    if let Some(split) = split {
        c.push(r.systematic.cell(|a| label(a, 1)));
        c.push(
            r.systematic
                .cell(|a| fmt_f64(g.systematic(a, split).eccentricity_mm, DECIMALS)),
        );
        c.push(
            r.systematic
                .cell(|a| fmt_f64(g.systematic(a, split).wave_mm, DECIMALS)),
        );
    }
    c
}

/// The table of `rows` titled `title`, its first column `what`; with the systematic columns
/// when `split` (the share of A on the teeth) is given. Notes say how each column is computed.
pub fn table(title: String, what: &str, split: Option<f64>, rows: &[GearRow]) -> Table {
    let mut t = Table::new(title, columns(what, split));
    for r in rows {
        t.row(cells(r, split));
    }
    t.note("N: teeth; R: tip radius of the gearing the cells ran on (mm). Random error: the sd of a tip's angular position, as a fraction of the pitch 360/N, as degrees of the gear's turn (fraction x 360/N) and as millimetres along the tip circle (fraction x 2 pi R / N). `< x`: below the grid, whose smallest value x already breaks the rule.");
    if let Some(split) = split {
        t.note(format!(
            "Systematic amplitude A (degrees, the paper's once-per-turn error), split {split} on the teeth: the axis carries (1 - {split}) A, an eccentricity of the rotation centre R tan((1 - {split}) A); the teeth carry {split} A, a wave of the tips along the tip circle of R x {split} A (radians). The paper's example: 5 deg split 50/50 on a gear of R = 100 mm is an axis shift of about 4 mm."
        ));
    } else {
        t.note("No systematic error was run: the tolerance is the random error's alone.");
    }
    t
}

/// Two rows per mesh, driver then driven, each with the mesh's errors `values(mesh index)`;
/// `gears` in the meshes' order (empty in results stored before sizes were kept: no rows).
pub fn per_mesh(gears: &[MeshGears], values: impl Fn(usize) -> (Value, Value)) -> Vec<GearRow> {
    let mut rows = Vec::new();
    for (m, mesh) in gears.iter().enumerate() {
        let (random, systematic) = values(m);
        for g in mesh.gears() {
            rows.push(GearRow {
                label: mesh.mesh.clone(),
                gear: g.clone(),
                random,
                systematic,
            });
        }
    }
    rows
}

/// The size of the gear the mesh labels write `name`, from the meshes' gears.
pub fn gear_named<'a>(gears: &'a [MeshGears], name: &str) -> Option<&'a GearSize> {
    gears
        .iter()
        .flat_map(MeshGears::gears)
        .find(|g| g.gear == name)
}

/// Each gear once, in the order of first appearance in the meshes, with the meshes it is in.
pub fn gears_once(gears: &[MeshGears]) -> Vec<(GearSize, Vec<String>)> {
    let mut out: Vec<(GearSize, Vec<String>)> = Vec::new();
    for mesh in gears {
        for g in mesh.gears() {
            match out.iter_mut().find(|(x, _)| x.gear == g.gear) {
                Some((_, ms)) => ms.push(mesh.mesh.clone()),
                None => out.push((g.clone(), vec![mesh.mesh.clone()])),
            }
        }
    }
    out
}

/// The E. max of each mesh of a per-mesh tolerance table in units of its gears: Table 4's and
/// the tolerance search's (random only, `split` `None`), Table 5's (random and systematic, with
/// the split it ran at).
pub fn emax_table(
    title: String,
    gears: &[MeshGears],
    split: Option<f64>,
    values: impl Fn(usize) -> (Value, Value),
) -> Table {
    table(title, "mesh", split, &per_mesh(gears, values))
}

/// Each mesh's E. max of Table 5 (`t`: its largest tolerable random error, and the systematic
/// amplitude on top of it), per gear in mm and degrees, the systematic error split `split`.
pub fn derived_tolerances_table(
    title: String,
    t: &study::results::DerivedTolerances,
    split: f64,
) -> Table {
    let smallest_random = t.random_grid.random.first().copied();
    let smallest_sys = t.rows.first().map(|r| r.systematic);
    emax_table(title, &t.random_grid.gears, Some(split), |m| {
        let tol = &t.meshes[m];
        let systematic = match tol.random {
            Some(_) => Value::of(tol.systematic, smallest_sys),
            None => Value::Missing,
        };
        (Value::of(tol.random, smallest_random), systematic)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn gear() -> GearSize {
        GearSize {
            gear: "b2".into(),
            teeth: 64,
            tip_radius: 15.0,
        }
    }

    #[test]
    fn a_row_converts_as_study_units_does() {
        let row = GearRow {
            label: "b2-c1".into(),
            gear: gear(),
            random: Value::At(0.05),
            systematic: Value::At(0.4),
        };
        let cells = cells(&row, Some(0.5));
        let r = study::units::random_error(0.05, 64, 15.0);
        let s = study::units::systematic_error(0.4, 0.5, 15.0);
        assert_eq!(cells[5], fmt_f64(r.degrees, DECIMALS));
        assert_eq!(cells[6], fmt_f64(r.tip_mm, DECIMALS));
        assert_eq!(cells[8], fmt_f64(s.eccentricity_mm, DECIMALS));
        assert_eq!(cells[9], fmt_f64(s.wave_mm, DECIMALS));
        assert_eq!(cells.len(), columns("mesh", Some(0.5)).len());
        // Random only: no systematic columns.
        assert_eq!(super::cells(&row, None).len(), 7);
    }

    #[test]
    fn below_the_grid_and_missing_print_as_such() {
        let row = GearRow {
            label: "m".into(),
            gear: gear(),
            random: Value::of(None, Some(0.035)),
            systematic: Value::Missing,
        };
        let c = cells(&row, Some(0.5));
        assert_eq!(c[4], "< 0.035");
        assert!(c[5].starts_with("< "), "{c:?}");
        assert_eq!(c[8], "-");
    }
}
