//! `pair`: any mesh described in a RON file (tooth counts, radii, optional measured tip angles and
//! eccentricity, centre distance or clearance): θ(φ), Theoretical Difference and every event.

use std::f64::consts::TAU;

use contact::{EventKind, Mesh, Start};
use geometry::{Gear, Vec2};
use registry::{
    Context, Experiment, OutputFile, Param, Report, RunError, Table, fmt_f64, fmt_number,
};
use serde::Deserialize;

use crate::common::{MAX_DATA_ROWS, Series, csv, deg, line_plot};

const EXAMPLE: &str = include_str!("../data/pair-example.ron");
const EXAMPLE_NAME: &str = "experiments/data/pair-example.ron";

registry::inventory::submit! {
    Experiment {
        id: "pair",
        title: "One mesh from a RON file: theta(phi), Theoretical Difference, jams and disengagements",
        paper_item: "sections 2-3 (any gear pair, e.g. measured from CT scans)",
        params: &[] as &[Param],
        config: Some("a mesh: driver and driven (teeth, tip_radius, root_radius, optional tips_deg, optional eccentricity), centre_distance or clearance_percent, start_deg, run_deg, sample_deg; see experiments/data/pair-example.ron"),
        run,
    }
}

/// One gear as written in the file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GearSpec {
    teeth: usize,
    tip_radius: f64,
    root_radius: f64,
    #[serde(default)]
    tips_deg: Option<Vec<f64>>,
    #[serde(default)]
    eccentricity: Option<(f64, f64)>,
}

/// The whole file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PairFile {
    driver: GearSpec,
    driven: GearSpec,
    #[serde(default)]
    centre_distance: Option<f64>,
    #[serde(default)]
    clearance_percent: Option<f64>,
    #[serde(default)]
    start_deg: f64,
    #[serde(default)]
    run_deg: Option<f64>,
    #[serde(default = "default_sample")]
    sample_deg: f64,
}

fn default_sample() -> f64 {
    0.1
}

/// The most work a pair run is given: driver pitches run times the larger tooth count, 4·10^6
/// (a turn of two 2000-tooth gears, a few minutes).
const MAX_WORK: f64 = 4.0e6;

/// The driver angle run when `run_deg` is not given: one turn of the gear with more teeth.
fn default_run_deg(driver_teeth: usize, driven_teeth: usize) -> f64 {
    360.0 * driver_teeth.max(driven_teeth) as f64 / driver_teeth as f64
}

fn gear(file: &str, which: &str, spec: &GearSpec) -> Result<Gear, RunError> {
    let field = |f: &str| format!("{which}.{f}");
    if spec.teeth < 3 {
        return Err(RunError::bad(
            file,
            field("teeth"),
            format!("must be at least 3 (got {})", spec.teeth),
        ));
    }
    if spec.teeth > geometry::MAX_TEETH {
        return Err(RunError::bad(
            file,
            field("teeth"),
            format!(
                "must be at most {} (the limit on teeth; got {})",
                geometry::MAX_TEETH,
                spec.teeth
            ),
        ));
    }
    let tips = match &spec.tips_deg {
        None => (0..spec.teeth)
            .map(|k| TAU * k as f64 / spec.teeth as f64)
            .collect(),
        Some(t) if t.len() != spec.teeth => {
            return Err(RunError::bad(
                file,
                field("tips_deg"),
                format!(
                    "must list exactly `teeth` = {} angles (got {})",
                    spec.teeth,
                    t.len()
                ),
            ));
        }
        Some(t) => t.iter().map(|a| a.to_radians()).collect(),
    };
    let (ex, ey) = spec.eccentricity.unwrap_or((0.0, 0.0));
    Gear::new(spec.tip_radius, spec.root_radius, tips, Vec2::new(ex, ey)).map_err(|e| {
        // Name the field as written in the file.
        let f = match e.field.as_str() {
            "rotation_centre" | "rotation_centre.x" | "rotation_centre.y" => {
                "eccentricity".to_string()
            }
            other if other.starts_with("tips[") => format!("tips_deg{}", &other[4..]),
            other => other.to_string(),
        };
        RunError::bad(file, field(&f), e.rule)
    })
}

/// Parses and checks a pair file, naming the file, the field (or line and column) and the rule.
pub fn load(file: &str, text: &str) -> Result<(Mesh, PairFile), RunError> {
    let spec: PairFile = ron::from_str(text).map_err(|e| {
        RunError::bad(
            file,
            format!("line {}, column {}", e.position.line, e.position.col),
            input_file::ron_rule(&e.code),
        )
    })?;
    let driver = gear(file, "driver", &spec.driver)?;
    let driven = gear(file, "driven", &spec.driven)?;
    let d = match (spec.centre_distance, spec.clearance_percent) {
        (Some(d), None) => d,
        (None, Some(g)) => {
            if !(g > 0.0 && g < 100.0) {
                return Err(RunError::bad(
                    file,
                    "clearance_percent",
                    format!(
                        "must be more than 0 and less than 100 (got {}): at 0 the tips reach the other gear's valleys, at 100 they only graze its tips",
                        fmt_number(g)
                    ),
                ));
            }
            let h = 0.5 * (driver.tooth_height() + driven.tooth_height());
            let d = geometry::centre_distance(driver.tip_radius(), driven.tip_radius(), h, g);
            if !d.is_finite() {
                let which = if driver.tip_radius() >= driven.tip_radius() {
                    "driver"
                } else {
                    "driven"
                };
                return Err(RunError::bad(
                    file,
                    format!("{which}.tip_radius"),
                    "is too large: the centre distance it gives with clearance_percent is not a finite number",
                ));
            }
            d
        }
        _ => {
            return Err(RunError::bad(
                file,
                "centre_distance",
                "give exactly one of centre_distance and clearance_percent",
            ));
        }
    };
    if !(spec.sample_deg > 0.0 && spec.sample_deg.is_finite()) {
        return Err(RunError::bad(
            file,
            "sample_deg",
            "must be a positive number of degrees",
        ));
    }
    if !spec.start_deg.is_finite() {
        return Err(RunError::bad(
            file,
            "start_deg",
            "must be a finite number of degrees",
        ));
    }
    if let Some(r) = spec.run_deg
        && !(r > 0.0 && r.is_finite() && r <= 360.0 * 1000.0)
    {
        return Err(RunError::bad(
            file,
            "run_deg",
            "must be a positive number of degrees, at most 360000",
        ));
    }
    let run_deg = spec
        .run_deg
        .unwrap_or_else(|| default_run_deg(spec.driver.teeth, spec.driven.teeth));
    if run_deg / spec.sample_deg > MAX_DATA_ROWS as f64 {
        return Err(RunError::bad(
            file,
            "sample_deg",
            format!(
                "must be at least {} degrees: {} degrees of driver angle in steps of {} would be more than {MAX_DATA_ROWS} rows of pair.csv, the limit",
                fmt_number(run_deg / MAX_DATA_ROWS as f64),
                fmt_number(run_deg),
                fmt_number(spec.sample_deg)
            ),
        ));
    }
    // The solver's work grows with the driver pitches run times the teeth in play: a turn of
    // two 500-tooth gears takes some 20 s, of two 2000-tooth gears minutes.
    let (n1, n2) = (spec.driver.teeth as f64, spec.driven.teeth as f64);
    let work = run_deg / 360.0 * n1 * n1.max(n2);
    if work > MAX_WORK {
        return Err(RunError::bad(
            file,
            "run_deg",
            format!(
                "{} degrees of a {n1}-tooth driver against {} teeth is {} driver pitches times teeth, more than the limit of {MAX_WORK} (minutes of computing; it grows as the square of the teeth per turn): give a shorter run_deg",
                fmt_number(run_deg),
                n1.max(n2),
                fmt_number(work.round())
            ),
        ));
    }
    // Gears that never touch: every tip of a gear lies within its largest tip radius of its
    // geometric centre, which is |e| from its rotation centre.
    let reach = driver.max_tip_radius()
        + driven.max_tip_radius()
        + driver.rotation_centre().norm()
        + driven.rotation_centre().norm();
    if d >= reach {
        let field = if spec.centre_distance.is_some() {
            "centre_distance"
        } else {
            "clearance_percent"
        };
        return Err(RunError::bad(
            file,
            field,
            format!(
                "the gears never touch: the centre distance {} is at least R1 + R2 + |e1| + |e2| = {}, so no tip reaches the other gear",
                fmt_number(d),
                fmt_number(reach)
            ),
        ));
    }
    let mesh = Mesh::new(driver, driven, d).map_err(|e| RunError::bad(file, e.field, e.rule))?;
    Ok((mesh, spec))
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    let (name, text) = match ctx.config() {
        Some(c) => (c.path.display().to_string(), c.text.as_str()),
        None => (EXAMPLE_NAME.to_string(), EXAMPLE),
    };
    let (mesh, spec) = load(&name, text)?;
    let (n1, n2) = (mesh.driver().teeth(), mesh.driven().teeth());
    let ratio = n1 as f64 / n2 as f64;
    let run_deg = spec.run_deg.unwrap_or_else(|| default_run_deg(n1, n2));
    let phi0 = spec.start_deg.to_radians();
    let phi_end = phi0 + run_deg.to_radians();
    let traj = mesh.run(phi0, phi_end, Start::Touching(0.0));
    let theta0 = traj.theta_at(phi0);
    let samples = (run_deg / spec.sample_deg).floor() as usize;
    let rows: Vec<Vec<f64>> = (0..=samples)
        .map(|i| {
            let phi = (phi0 + (i as f64 * spec.sample_deg).to_radians()).min(phi_end);
            let theta = traj.theta_at(phi) - theta0;
            vec![
                deg(phi - phi0),
                deg(theta),
                deg(theta - ratio * (phi - phi0)),
            ]
        })
        .collect();
    let td: Vec<f64> = rows.iter().map(|r| r[2]).collect();
    let s = stats::pointer_stats(&td);

    let mut summary = Table::new(format!("Mesh from {name}"), ["quantity", "value", "unit"]);
    let rowf = |t: &mut Table, q: &str, v: String, u: &str| t.row(vec![q.into(), v, u.into()]);
    rowf(&mut summary, "teeth N1 : N2", format!("{n1} : {n2}"), "");
    rowf(
        &mut summary,
        "centre distance D",
        fmt_f64(mesh.centre_distance(), 4),
        "length",
    );
    rowf(&mut summary, "driver angle run", fmt_f64(run_deg, 3), "deg");
    rowf(&mut summary, "jams", traj.jams().to_string(), "");
    rowf(
        &mut summary,
        "disengagements",
        traj.disengagements().to_string(),
        "",
    );
    rowf(
        &mut summary,
        "Theoretical Difference sigma",
        fmt_f64(s.sigma, 4),
        "deg",
    );
    rowf(
        &mut summary,
        "Theoretical Difference Dm",
        fmt_f64(s.dm, 4),
        "deg",
    );
    rowf(
        &mut summary,
        "Theoretical Difference mean P",
        fmt_f64(s.mean, 4),
        "deg",
    );

    let mut events = Table::new(
        "Events",
        [
            "phi [deg]",
            "kind",
            "driver tooth",
            "driven tooth",
            "theta [deg]",
            "theta after [deg]",
        ],
    );
    let mut ev_rows =
        String::from("phi_deg,kind,driver_tooth,driven_tooth,theta_deg,theta_after_deg\n");
    for e in traj.events() {
        let kind = match e.kind {
            EventKind::Jam => "jam",
            EventKind::Disengagement => "disengagement",
        };
        let j = e.driver_tooth.rem_euclid(n1 as i64);
        let k = e.driven_tooth.rem_euclid(n2 as i64);
        let cells = [
            format!("{:.9}", deg(e.phi - phi0)),
            kind.to_string(),
            j.to_string(),
            k.to_string(),
            format!("{:.9}", deg(e.theta - theta0)),
            format!("{:.9}", deg(e.theta_after - theta0)),
        ];
        ev_rows.push_str(&cells.join(","));
        ev_rows.push('\n');
        if events.rows.len() < 20 {
            events.row(vec![
                fmt_f64(deg(e.phi - phi0), 6),
                kind.into(),
                j.to_string(),
                k.to_string(),
                fmt_f64(deg(e.theta - theta0), 6),
                fmt_f64(deg(e.theta_after - theta0), 6),
            ]);
        }
    }
    if traj.events().len() > 20 {
        events.note(format!(
            "{} more in event-log.csv",
            traj.events().len() - 20
        ));
    }
    if traj.events().is_empty() {
        events.note("no jam and no disengagement");
    }
    let svg = line_plot(
        "Theoretical Difference of the mesh (sections 2-3)",
        "driver angle phi [deg]",
        "Theoretical Difference [deg]",
        &[Series {
            label: "simulated",
            points: rows.iter().map(|r| (r[0], r[2])).collect(),
        }],
    )?;
    let data = csv(&["phi_deg", "theta_deg", "td_deg"], rows.into_iter(), 9);
    Ok(Report {
        tables: vec![summary, events],
        files: vec![
            OutputFile::new("pair.csv", data),
            OutputFile::new("event-log.csv", ev_rows),
            OutputFile::new("pair.svg", svg),
        ],
        ..Default::default()
    })
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    #[test]
    fn example_loads() {
        assert!(load("x.ron", EXAMPLE).is_ok());
    }

    #[test]
    fn errors_name_file_field_and_rule() {
        let bad = |text: &str| load("m.ron", text).unwrap_err().to_string();
        let base = |driver: &str, extra: &str| {
            format!(
                "(driver: {driver}, driven: (teeth: 20, tip_radius: 10.0, root_radius: 9.0), {extra})"
            )
        };
        let ok_driver = "(teeth: 20, tip_radius: 10.0, root_radius: 9.0)";
        assert_eq!(
            bad(&base(
                "(teeth: 2, tip_radius: 10.0, root_radius: 9.0)",
                "clearance_percent: Some(40.0)"
            )),
            "m.ron: driver.teeth: must be at least 3 (got 2)"
        );
        assert!(
            bad(&base(
                "(teeth: 20, tip_radius: 10.0, root_radius: 10.0)",
                "clearance_percent: Some(40.0)"
            ))
            .starts_with("m.ron: driver.root_radius: must be less than tip_radius")
        );
        assert!(
            bad(&base(ok_driver, "centre_distance: Some(15.0)"))
                .starts_with("m.ron: centre_distance: must exceed")
        );
        assert!(bad(&base(ok_driver, "")).contains("give exactly one of"));
        assert!(
            bad(&base(ok_driver, "clearance_percent: Some(140.0)"))
                .starts_with("m.ron: clearance_percent:")
        );
        assert!(bad("(driver: (teeth: 20,").starts_with("m.ron: line 1, column"));
        assert_eq!(
            bad(&base(
                "(teeth: 1000000000, tip_radius: 10.0, root_radius: 9.0)",
                "clearance_percent: Some(40.0)"
            )),
            "m.ron: driver.teeth: must be at most 100000 (the limit on teeth; got 1000000000)"
        );
        assert_eq!(train::MAX_TEETH as usize, geometry::MAX_TEETH);
        assert!(
            bad(&base(
                "(teeth: 3, tip_radius: 10.0, root_radius: 9.0, tips_deg: Some([0.0, 10.0]))",
                "clearance_percent: Some(40.0)"
            ))
            .starts_with("m.ron: driver.tips_deg: must list exactly")
        );
    }
}
