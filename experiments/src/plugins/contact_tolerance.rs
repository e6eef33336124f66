//! `contact-tolerance`: Figure IV under the paper's kind of contact test. Its Python program
//! detects "intersections between the areas of the gears"; if it ignored overlaps up to a small
//! area, a tip sinks into the flank it pushes and the teeth act shorter near their tips. Blunt
//! tips do the same by shape. This runs every mesh's ideal pair over the clearance grid under a
//! ladder of tolerances and of tip cuts (`polycheck::area`) and reports where σ is smallest,
//! whether it is largest at the smallest clearance, how σ at 40 % moves and where contact is
//! first lost: the features the paper describes for Figure IV.

use registry::{OutputFile, Param, Place, Report, Run, RunError, Table, fmt_f64};
use serde::{Deserialize, Serialize};
use study::area_test::{Point, Test, grid};
use study::gearing::ShapeParams;
use study::limits::IdealPair;
use study::results::contact_tolerance::{
    AreaTest, ContactTolerance, CurveShape, Spread, TestCurves, TestSummary,
};

use presentation::common::{Series, semilog_plot};

registry::params! {
    /// `tolerance`: overlap area the contact test ignores, for the printed curves (the ladder is fixed).
    const TOLERANCE = Param::new("tolerance", "0.003", "overlap area the contact test ignores, for the printed curves (the ladder is fixed)", registry::Kind::positive(1.0, "mm^2")).unit("mm^2");
    /// `blunt`: depth cut flat off every tip, for the printed curves (the ladder is fixed).
    const BLUNT_PARAM = Param::new("blunt", "10", "depth cut flat off every tip, for the printed curves (the ladder is fixed)", registry::Kind::positive(50.0, "% of the tooth height h")).unit("% of h");
    /// `samples`: driver angles per driver pitch (an ideal pair repeats every driver pitch).
    const SAMPLES = Param::new("samples", "200", "driver angles per driver pitch (an ideal pair repeats every driver pitch)", registry::Kind::count(8, registry::MAX_COUNT as u64, "a sigma needs samples"));
}

/// The settings: the tolerance and the tip cut of the printed curves, driver angles per pitch,
/// and the gearing with h.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, registry::Settings)]
pub struct Settings {
    /// Overlap area ignored for the printed curves, mm² ([`TOLERANCE`]).
    #[param(TOLERANCE)]
    pub tolerance: f64,
    /// Depth cut off every tip for the printed curves, % of h ([`BLUNT_PARAM`]).
    #[param(BLUNT_PARAM)]
    pub blunt: f64,
    /// Driver angles per driver pitch ([`SAMPLES`]).
    #[param(SAMPLES)]
    pub samples: usize,
    /// The gearing and h.
    #[group]
    pub shape: ShapeParams,
}

/// Figure IV under an area contact test with a tolerance, or with blunt tips.
pub struct ContactToleranceExperiment;

impl registry::Experiment for ContactToleranceExperiment {
    const ID: &'static str = "contact-tolerance";
    const TITLE: &'static str =
        "Figure IV under an area contact test with a tolerance, or with blunt tips";
    const PAPER_ITEM: &'static str = "Figure IV and Appendix II (beyond the paper)";
    const PLACE: Place = Place::Beyond(90);
    type Settings = Settings;
    type Results = ContactTolerance;

    fn compute(s: &Settings, run: &Run) -> Result<ContactTolerance, RunError> {
        let shape = s.shape.load()?;
        let (g, h) = (&shape.gearing, shape.tooth_height);
        let chosen = chosen(s);
        let tests = ladder(&chosen);
        let meshes: Vec<(String, IdealPair)> = g
            .meshes()
            .iter()
            .map(|m| {
                IdealPair::of_mesh(g, &m.label, h)
                    .map(|p| (m.label.clone(), p))
                    .ok_or_else(|| RunError::Internal(format!("no mesh {}", m.label)))
            })
            .collect::<Result<_, _>>()?;

        // ---- Every (test, mesh) curve, through the trial engine. ----
        let pairs: Vec<IdealPair> = meshes.iter().map(|(_, p)| *p).collect();
        let curves = study::area_test::curves(run.engine(), &tests, &pairs, s.samples)?;
        let n = meshes.len();
        let of = |ti: usize, mi: usize| curves[ti * n + mi].as_slice();
        let chosen_curves = chosen
            .iter()
            .map(|c| {
                let ti = tests.iter().position(|t| t == c).unwrap_or(0);
                TestCurves {
                    test: area_test(*c),
                    sigma: (0..n).map(|mi| driving_sigmas(of(ti, mi))).collect(),
                }
            })
            .collect();
        Ok(ContactTolerance {
            meshes: meshes.into_iter().map(|(l, _)| l).collect(),
            clearances: grid(),
            tests: summaries(&tests, n, &of),
            curves: chosen_curves,
        })
    }

    fn report(s: &Settings, r: &ContactTolerance) -> Result<Report, RunError> {
        let h = s.shape.tooth_height;
        let mut tables = vec![summary_table(r, h)];
        let mut files = Vec::new();
        for c in &r.curves {
            let (table, svg) = curves_table(r, c, h, s.samples)?;
            tables.push(table);
            let name = if c.test.blunt > 0.0 {
                "blunt"
            } else {
                "tolerance"
            };
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
}

registry::register!(ContactToleranceExperiment);

/// Overlap areas ignored (mm²) in the ladder; 0 is the exact test.
const TOLERANCES: [f64; 6] = [0.0, 0.0001, 0.0003, 0.001, 0.003, 0.01];

/// Tip cuts in the ladder, % of h.
const BLUNT: [f64; 3] = [5.0, 10.0, 15.0];

/// The two tests whose curves are printed: the set tolerance, then the set tip cut.
fn chosen(s: &Settings) -> [Test; 2] {
    [
        Test {
            tolerance: s.tolerance,
            blunt: 0.0,
        },
        Test {
            tolerance: 0.0,
            blunt: s.blunt,
        },
    ]
}

/// The ladder of tolerances (the exact test first), then of tip cuts, then the chosen tests not
/// on it.
fn ladder(chosen: &[Test]) -> Vec<Test> {
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
        if !tests.contains(c) {
            tests.push(*c);
        }
    }
    tests
}

/// A test as stored.
fn area_test(t: Test) -> AreaTest {
    AreaTest {
        tolerance: t.tolerance,
        blunt: t.blunt,
    }
}

/// What a test is, for titles; `h` (mm) gives the tip cut in mm.
fn test_name(test: &AreaTest, h: f64) -> String {
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

/// σ at each point of a curve where the pair drives throughout (no jam, no lost contact).
fn driving_sigmas(curve: &[Point]) -> Vec<Option<f64>> {
    curve
        .iter()
        .map(|p| (p.sigma.is_finite() && !p.lost).then_some(p.sigma))
        .collect()
}

/// What one mesh's curve shows: the G of the smallest σ, whether σ is largest at the smallest
/// G that drives, σ at 40 %, and the largest G that drives.
fn shape(curve: &[Point]) -> Option<CurveShape> {
    let pts = driving(curve);
    let smallest = pts
        .iter()
        .copied()
        .reduce(|a, b| if b.1 < a.1 { b } else { a })?;
    let largest = pts
        .iter()
        .copied()
        .reduce(|a, b| if b.1 > a.1 { b } else { a })?;
    Some(CurveShape {
        minimum_at: smallest.0,
        largest_first: pts.first().is_some_and(|f| f.0 == largest.0),
        at_40: pts.iter().find(|p| (p.0 - 40.0).abs() < 1e-9).map(|p| p.1),
        last: pts.iter().map(|p| p.0).fold(f64::NAN, f64::max),
    })
}

/// Per test: what the `n` meshes' curves (`of(test, mesh)`) show beside the paper's description.
fn summaries<'a>(
    tests: &[Test],
    n: usize,
    of: &dyn Fn(usize, usize) -> &'a [Point],
) -> Vec<TestSummary> {
    let paper = |q: &str| presentation::paper::get("sigma-causes", q).map(|r| r.value);
    let from = paper("figIV.minimum_from").unwrap_or(f64::NAN);
    let to = paper("figIV.minimum_to").unwrap_or(f64::NAN);
    let exact: Vec<f64> = (0..n)
        .map(|mi| shape(of(0, mi)).and_then(|s| s.at_40).unwrap_or(f64::NAN))
        .collect();
    tests
        .iter()
        .enumerate()
        .map(|(ti, test)| {
            let shapes: Vec<Option<CurveShape>> = (0..n).map(|mi| shape(of(ti, mi))).collect();
            let found = shapes.iter().flatten();
            TestSummary {
                test: area_test(*test),
                minimum_in_paper_range: found
                    .clone()
                    .filter(|s| from <= s.minimum_at && s.minimum_at <= to)
                    .count(),
                minimum_at: Spread::of(found.clone().map(|s| s.minimum_at)),
                largest_first: found.clone().filter(|s| s.largest_first).count(),
                ratio_at_40: Spread::of(
                    shapes
                        .iter()
                        .zip(&exact)
                        .map(|(s, e)| s.and_then(|s| s.at_40).unwrap_or(f64::NAN) / e),
                ),
                last_driving: Spread::of(found.map(|s| s.last)),
                shapes,
            }
        })
        .collect()
}

/// "middle (lo-hi)", `decimals` places; "-" for none.
fn spread(s: Option<Spread>, decimals: usize) -> String {
    s.map_or_else(
        || "-".into(),
        |s| {
            format!(
                "{} ({}-{})",
                fmt_f64(s.middle, decimals),
                fmt_f64(s.lo, decimals),
                fmt_f64(s.hi, decimals)
            )
        },
    )
}

/// The ladder: per test, what the fifteen curves show beside the paper's description.
fn summary_table(r: &ContactTolerance, h: f64) -> Table {
    let paper = |id: &str, q: &str| presentation::paper::get(id, q).map(|r| r.value);
    let from = paper("sigma-causes", "figIV.minimum_from").unwrap_or(f64::NAN);
    let to = paper("sigma-causes", "figIV.minimum_to").unwrap_or(f64::NAN);
    let paper_last = paper("clearance", "disengage_above");
    let n = r.meshes.len();
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
    for x in &r.tests {
        t.row(vec![
            test_name(&x.test, h),
            format!("{} of {n}", x.minimum_in_paper_range),
            spread(x.minimum_at, 0),
            format!("{} of {n}", x.largest_first),
            spread(x.ratio_at_40, 2),
            spread(x.last_driving, 0),
        ]);
    }
    t.note("Each mesh's ideal pair (radii as crates/train sizes them) over one driver pitch from driver angle 0, started in contact (an ideal pair repeats every driver pitch); the driven angle is where the test stops reporting contact, found by bisection on the overlap area (polycheck::area), not by a fixed step. A G drives when the pair neither jams nor loses contact at any sample.");
    t.note("The exact test's row is our contact solver's Figure IV (figIV's sweep, to sampling), computed here by polygons: a unit test holds the two within 1 %.");
    t.note("sigma at 40 % is what Table 1 sees (G = 40 % throughout): sigma-causes' Table 1 shows the factor by which ours exceeds the paper's, to compare with this ratio.");
    t
}

/// One test's σ(G) for every mesh, as Figure IV plots it, with its SVG.
fn curves_table(
    r: &ContactTolerance,
    c: &TestCurves,
    h: f64,
    samples: usize,
) -> Result<(Table, String), RunError> {
    let mut header = vec!["G [% of h]".to_string()];
    header.extend(r.meshes.iter().cloned());
    let mut t = Table::new(
        format!(
            "Figure IV under one test - {}: sigma of the driven gear's Theoretical Difference [deg], h = {h} mm",
            test_name(&c.test, h)
        ),
        header,
    );
    for (k, g) in r.clearances.iter().enumerate() {
        let mut row = vec![fmt_f64(*g, 0)];
        for sigma in &c.sigma {
            row.push(sigma[k].map_or_else(|| "-".into(), |s| format!("{s:.2e}")));
        }
        t.row(row);
    }
    t.note(format!(
        "'-': the pair jams, never touches or loses contact within the pitch ({samples} samples per driver pitch)."
    ));
    let series: Vec<Series<'_>> = r
        .meshes
        .iter()
        .zip(&c.sigma)
        .map(|(label, sigma)| Series {
            label: label.as_str(),
            points: r
                .clearances
                .iter()
                .zip(sigma)
                .filter_map(|(&g, s)| s.map(|s| (g, s)))
                .collect(),
        })
        .collect();
    let svg = semilog_plot(
        &format!("Figure IV under {}", test_name(&c.test, h)),
        "clearance G [% of tooth height]",
        "sigma [deg], logarithmic scale",
        &series,
    )?;
    Ok((t, svg))
}
