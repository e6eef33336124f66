//! `contact-tolerance`'s results: Figure IV (σ of each ideal mesh's driven gear against the
//! clearance G) under the paper's kind of contact test - overlaps up to an area ignored, or tips
//! cut blunt - and what each test's curves show of the features the paper describes: where σ is
//! smallest, whether it is largest at the smallest clearance, how σ at 40 % moves, and where
//! contact is first lost.

use serde::{Deserialize, Serialize};

/// Every test's summary over the meshes, and the curves of the two tests the settings choose.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ContactTolerance {
    /// The ideal meshes (the gearing's, in its order).
    pub meshes: Vec<String>,
    /// The clearance grid every curve is run over, % of h.
    pub clearances: Vec<f64>,
    /// The ladder of tests (the exact test first), then any chosen test not on it.
    pub tests: Vec<TestSummary>,
    /// The chosen tests' curves: the chosen tolerance, then the chosen tip cut.
    pub curves: Vec<TestCurves>,
}

/// One contact test: an overlap area ignored or a tip cut (a ladder's test sets at most one).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct AreaTest {
    /// Overlap area the test ignores, mm² (0: any overlap is contact).
    pub tolerance: f64,
    /// Depth cut flat off every tip, % of the tooth height h (0: sharp tips).
    pub blunt: f64,
}

/// What the fifteen curves of one test show, beside the paper's description of Figure IV.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TestSummary {
    /// The test.
    pub test: AreaTest,
    /// Per mesh: what its curve shows (`None`: it drives at no clearance of the grid).
    pub shapes: Vec<Option<CurveShape>>,
    /// Meshes whose smallest σ lies within the paper's range ('a minimum occurs around 40% to
    /// 50%', the reference file's `figIV.minimum_from` to `figIV.minimum_to`; none counted
    /// where it holds no range).
    pub minimum_in_paper_range: usize,
    /// The clearance of the smallest σ over the meshes with a curve, % of h.
    pub minimum_at: Option<Spread>,
    /// Meshes whose σ is largest at the smallest clearance that drives ('a maximum value when
    /// the separation is minimal').
    pub largest_first: usize,
    /// σ at 40 % over the exact test's σ at 40 %, over the meshes with both.
    pub ratio_at_40: Option<Spread>,
    /// The largest clearance that drives without losing contact, % of h, over the meshes.
    pub last_driving: Option<Spread>,
}

/// What one mesh's curve shows (only clearances at which the pair drives throughout: no jam,
/// no lost contact).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct CurveShape {
    /// The clearance of the smallest σ, % of h.
    pub minimum_at: f64,
    /// Whether σ is largest at the smallest clearance that drives.
    pub largest_first: bool,
    /// σ at G = 40 %, degrees (`None`: the pair does not drive there).
    pub at_40: Option<f64>,
    /// The largest clearance that drives, % of h.
    pub last: f64,
}

/// A spread of values over the meshes: the middle one and the range.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Spread {
    /// The middle value (of an even count, the upper of the two middle ones).
    pub middle: f64,
    /// The smallest value.
    pub lo: f64,
    /// The largest value.
    pub hi: f64,
}

/// One test's curves, as Figure IV plots them.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TestCurves {
    /// The test.
    pub test: AreaTest,
    /// Per mesh, per clearance of [`ContactTolerance::clearances`]: σ of the driven gear's
    /// Theoretical Difference, degrees (`None`: the pair jams, never touches or loses contact).
    pub sigma: Vec<Vec<Option<f64>>>,
}

impl Spread {
    /// The spread of the finite `values` (`None` when there are none).
    pub fn of(values: impl Iterator<Item = f64>) -> Option<Spread> {
        let mut v: Vec<f64> = values.filter(|x| x.is_finite()).collect();
        v.sort_by(f64::total_cmp);
        Some(Spread {
            middle: *v.get(v.len() / 2)?,
            lo: *v.first()?,
            hi: *v.last()?,
        })
    }
}
