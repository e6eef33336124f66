//! `contact-tolerance`: Figure IV under the paper's kind of contact test. Its Python program
//! detects "intersections between the areas of the gears"; if it ignored overlaps up to a small
//! area, a tip sinks into the flank it pushes and the teeth act shorter near their tips. Blunt
//! tips do the same by shape. This runs every mesh's ideal pair over the clearance grid under a
//! ladder of tolerances and of tip cuts (`polycheck::area`) and reports where σ is smallest,
//! whether it is largest at the smallest clearance, how σ at 40 % moves and where contact is
//! first lost: the features the paper describes for Figure IV.

use registry::{Context, OutputFile, Param, Report, RunError, Table, fmt_f64};
use study::area_test::{Point, Test, grid};
use study::limits::IdealPair;

use crate::common::{Series, semilog_plot};

registry::params! {
    /// `tolerance`: overlap area the contact test ignores, for the printed curves (the ladder is fixed).
    const TOLERANCE = Param::new("tolerance", "0.003", "overlap area the contact test ignores, for the printed curves (the ladder is fixed)", registry::Kind::positive(1.0, "mm^2")).unit("mm^2");
    /// `blunt`: depth cut flat off every tip, for the printed curves (the ladder is fixed).
    const BLUNT_PARAM = Param::new("blunt", "10", "depth cut flat off every tip, for the printed curves (the ladder is fixed)", registry::Kind::positive(50.0, "% of the tooth height h")).unit("% of h");
    /// `samples`: driver angles per driver pitch (an ideal pair repeats every driver pitch).
    const SAMPLES = Param::new("samples", "200", "driver angles per driver pitch (an ideal pair repeats every driver pitch)", registry::Kind::count(8, registry::MAX_COUNT as u64, "a sigma needs samples"));
}

crate::experiment! {
    id: "contact-tolerance", paper_item: "Figure IV and Appendix II (beyond the paper)", run,
    title: "Figure IV under an area contact test with a tolerance, or with blunt tips",
    params: [TOLERANCE, BLUNT_PARAM, SAMPLES], groups: [study::gearing::SHAPE],
}

/// Overlap areas ignored (mm²) in the ladder; 0 is the exact test.
const TOLERANCES: [f64; 6] = [0.0, 0.0001, 0.0003, 0.001, 0.003, 0.01];

/// Tip cuts in the ladder, % of h.
const BLUNT: [f64; 3] = [5.0, 10.0, 15.0];

/// What a test is, for titles; `h` (mm) gives the tip cut in mm.
fn test_name(test: &Test, h: f64) -> String {
    if test.tolerance > 0.0 {
        format!(
            "overlaps up to {} mm^2 ignored, sharp tips",
            fmt_f64(test.tolerance, 4)
        )
    } else if test.blunt > 0.0 {
        format!(
            "exact test, tips cut flat {} % of h ({} mm) below the apex",
            fmt_f64(test.blunt, 0),
            fmt_f64(test.blunt * h / 100.0, 3)
        )
    } else {
        "exact: any overlap is contact, sharp tips (ours)".into()
    }
}

/// The points of a curve that drive throughout (no jam, no lost contact).
fn driving(curve: &[Point]) -> Vec<(f64, f64)> {
    curve
        .iter()
        .filter(|p| p.sigma.is_finite() && !p.lost)
        .map(|p| (p.g, p.sigma))
        .collect()
}

/// What one mesh's curve shows: the G of the smallest σ, whether σ is largest at the smallest
/// G that drives, σ at 40 %, and the largest G that drives.
#[derive(Debug, Clone, Copy)]
struct Shape {
    minimum_at: f64,
    largest_first: bool,
    at_40: f64,
    last: f64,
}

fn shape(curve: &[Point]) -> Option<Shape> {
    let pts = driving(curve);
    let smallest = pts
        .iter()
        .copied()
        .reduce(|a, b| if b.1 < a.1 { b } else { a })?;
    let largest = pts
        .iter()
        .copied()
        .reduce(|a, b| if b.1 > a.1 { b } else { a })?;
    Some(Shape {
        minimum_at: smallest.0,
        largest_first: pts.first().is_some_and(|f| f.0 == largest.0),
        at_40: pts
            .iter()
            .find(|p| (p.0 - 40.0).abs() < 1e-9)
            .map_or(f64::NAN, |p| p.1),
        last: pts.iter().map(|p| p.0).fold(f64::NAN, f64::max),
    })
}

/// "median (lo-hi)" of finite values, `decimals` places; "-" for none.
fn spread(values: impl Iterator<Item = f64>, decimals: usize) -> String {
    let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
    v.sort_by(f64::total_cmp);
    match (v.first(), v.last()) {
        (Some(lo), Some(hi)) => format!(
            "{} ({}-{})",
            fmt_f64(v[v.len() / 2], decimals),
            fmt_f64(*lo, decimals),
            fmt_f64(*hi, decimals)
        ),
        _ => "-".into(),
    }
}

fn run(ctx: &Context) -> Result<Report, RunError> {
    let study::gearing::Shape {
        gearing: g,
        tooth_height: h,
        ..
    } = crate::settings::shape(ctx)?;
    let samples: usize = ctx.get(&SAMPLES)?;
    let chosen = [
        Test {
            tolerance: ctx.get(&TOLERANCE)?,
            blunt: 0.0,
        },
        Test {
            tolerance: 0.0,
            blunt: ctx.get(&BLUNT_PARAM)?,
        },
    ];
    let mut tests: Vec<Test> = TOLERANCES
        .iter()
        .map(|&tolerance| Test {
            tolerance,
            blunt: 0.0,
        })
        .chain(BLUNT.iter().map(|&blunt| Test {
            tolerance: 0.0,
            blunt,
        }))
        .collect();
    for c in chosen {
        if !tests.contains(&c) {
            tests.push(c);
        }
    }
    let meshes: Vec<(String, IdealPair)> = g
        .meshes()
        .iter()
        .map(|m| {
            IdealPair::of_mesh(&g, &m.label, h)
                .map(|p| (m.label.clone(), p))
                .ok_or_else(|| RunError::Internal(format!("no mesh {}", m.label)))
        })
        .collect::<Result<_, _>>()?;

    // ---- Every (test, mesh) curve, through the trial engine. ----
    let pairs: Vec<IdealPair> = meshes.iter().map(|(_, p)| *p).collect();
    let curves = study::area_test::curves(ctx.engine(), &tests, &pairs, samples)?;
    let of = |ti: usize, mi: usize| &curves[ti * meshes.len() + mi];

    let paper_from = crate::paper::get("sigma-causes", "figIV.minimum_from").map(|r| r.value);
    let paper_to = crate::paper::get("sigma-causes", "figIV.minimum_to").map(|r| r.value);
    let paper_last = crate::paper::get("clearance", "disengage_above").map(|r| r.value);
    let (from, to) = (paper_from.unwrap_or(f64::NAN), paper_to.unwrap_or(f64::NAN));

    let summary = summary_table(&tests, h, &meshes, &of, (from, to), paper_last);
    let mut tables = vec![summary];
    let mut files = Vec::new();
    for c in chosen {
        let ti = tests.iter().position(|t| *t == c).unwrap_or(0);
        let (table, svg) = curves_table(c, h, &meshes, |mi| of(ti, mi), samples)?;
        tables.push(table);
        let name = if c.blunt > 0.0 { "blunt" } else { "tolerance" };
        files.push(OutputFile::new(
            format!("contact-tolerance-{name}.svg"),
            svg,
        ));
    }
    Ok(Report {
        tables,
        files,
        ..Default::default()
    })
}

/// The ladder: per test, what the fifteen curves show beside the paper's description.
fn summary_table<'a>(
    tests: &[Test],
    h: f64,
    meshes: &[(String, IdealPair)],
    of: &dyn Fn(usize, usize) -> &'a Vec<Point>,
    (from, to): (f64, f64),
    paper_last: Option<f64>,
) -> Table {
    let n = meshes.len();
    let mut t = Table::new(
        format!(
            "Figure IV under each contact test: ideal gears of the {n} meshes, h = {h} mm, G = 10-100 % of h by 5"
        ),
        [
            "contact test".to_string(),
            format!(
                "meshes with the smallest sigma at {}-{} % (paper: 'a minimum occurs around' there)",
                fmt_f64(from, 0),
                fmt_f64(to, 0)
            ),
            "G of the smallest sigma: median (range)".to_string(),
            "meshes with the largest sigma at the smallest G that drives (paper: 'a maximum value when the separation is minimal')".to_string(),
            "sigma at 40 % / exact test's sigma at 40 %: median (range)".to_string(),
            format!(
                "largest G that drives without losing contact: median (range) [paper: none above {}]",
                paper_last.map_or_else(|| "?".into(), |v| fmt_f64(v, 0))
            ),
        ],
    );
    let exact: Vec<f64> = (0..n)
        .map(|mi| shape(of(0, mi)).map_or(f64::NAN, |s| s.at_40))
        .collect();
    for (ti, test) in tests.iter().enumerate() {
        let shapes: Vec<Option<Shape>> = (0..n).map(|mi| shape(of(ti, mi))).collect();
        let found = shapes.iter().flatten();
        let inside = found
            .clone()
            .filter(|s| from <= s.minimum_at && s.minimum_at <= to)
            .count();
        let first = found.clone().filter(|s| s.largest_first).count();
        t.row(vec![
            test_name(test, h),
            format!("{inside} of {n}"),
            spread(found.clone().map(|s| s.minimum_at), 0),
            format!("{first} of {n}"),
            spread(
                shapes
                    .iter()
                    .zip(&exact)
                    .map(|(s, e)| s.map_or(f64::NAN, |s| s.at_40 / e)),
                2,
            ),
            spread(found.map(|s| s.last), 0),
        ]);
    }
    t.note("Each mesh's ideal pair (radii as crates/train sizes them) over one driver pitch from driver angle 0, started in contact (an ideal pair repeats every driver pitch); the driven angle is where the test stops reporting contact, found by bisection on the overlap area (polycheck::area), not by a fixed step. A G drives when the pair neither jams nor loses contact at any sample.");
    t.note("The exact test's row is our contact solver's Figure IV (figIV's sweep, to sampling), computed here by polygons: a unit test holds the two within 1 %.");
    t.note("sigma at 40 % is what Table 1 sees (G = 40 % throughout): sigma-causes' Table 1 shows the factor by which ours exceeds the paper's, to compare with this ratio.");
    t
}

/// One test's σ(G) for every mesh, as Figure IV plots it, with its SVG.
fn curves_table<'a>(
    test: Test,
    h: f64,
    meshes: &[(String, IdealPair)],
    of: impl Fn(usize) -> &'a Vec<Point>,
    samples: usize,
) -> Result<(Table, String), RunError> {
    let mut header = vec!["G [% of h]".to_string()];
    header.extend(meshes.iter().map(|(l, _)| l.clone()));
    let mut t = Table::new(
        format!(
            "Figure IV under one test - {}: sigma of the driven gear's Theoretical Difference [deg], h = {h} mm",
            test_name(&test, h)
        ),
        header,
    );
    for (k, g) in grid().into_iter().enumerate() {
        let mut row = vec![fmt_f64(g, 0)];
        for mi in 0..meshes.len() {
            let p = of(mi)[k];
            row.push(if p.sigma.is_finite() && !p.lost {
                format!("{:.2e}", p.sigma)
            } else {
                "-".into()
            });
        }
        t.row(row);
    }
    t.note(format!(
        "'-': the pair jams, never touches or loses contact within the pitch ({samples} samples per driver pitch)."
    ));
    let series: Vec<Series<'_>> = meshes
        .iter()
        .enumerate()
        .map(|(mi, (label, _))| Series {
            label: label.as_str(),
            points: driving(of(mi)),
        })
        .collect();
    let svg = semilog_plot(
        &format!("Figure IV under {}", test_name(&test, h)),
        "clearance G [% of tooth height]",
        "sigma [deg], logarithmic scale",
        &series,
    )?;
    Ok((t, svg))
}
