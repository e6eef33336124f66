//! Random cases for the property tests (`props.rs`): gear pairs as plain numbers (tooth errors,
//! eccentricity, asymmetric and out-of-round teeth, curved flanks), the solver's mesh and the
//! independent oracle's for each, and the proptest strategies that draw them.

use std::f64::consts::TAU;
use std::ops::Range;

use contact::{Mesh, Solve, Start, Trajectory};
use geometry::{Gear, Vec2};
use polycheck::{
    CurvedShape, GearShape, P2, outline_from_angles, outline_from_polar, outline_from_tips,
};
use proptest::prelude::*;

/// One gear of a case, as plain numbers.
#[derive(Debug, Clone)]
pub struct GearSpec {
    pub r_tip: f64,
    pub r_root: f64,
    /// Tip angles, radians, gear frame.
    pub tips: Vec<f64>,
    /// Rotation-centre offset from the geometric centre, gear frame, mm.
    pub ecc: P2,
    /// Explicit valley angles (asymmetric teeth), or `None` for valleys midway between tips.
    pub valleys: Option<Vec<f64>>,
    /// Per-tip and per-valley radii (a gear that is not round; only with `valleys`), or `None`
    /// for `r_tip` and `r_root` throughout.
    pub radii: Option<(Vec<f64>, Vec<f64>)>,
    /// Signed flank sagitta, mm (0: straight flanks).
    pub sagitta: f64,
}

impl GearSpec {
    /// `n` tips at `2 pi k / n + sigma * pitch * u[k]`, tip radius `n * module / 2`, tooth height
    /// `h`, rotation centre offset `e_frac * h` at angle `e_angle`.
    pub fn new(
        n: usize,
        module: f64,
        h: f64,
        sigma: f64,
        u: &[f64],
        e_frac: f64,
        e_angle: f64,
    ) -> Self {
        let r_tip = n as f64 * module / 2.0;
        let pitch = TAU / n as f64;
        let tips = (0..n)
            .map(|k| pitch * k as f64 + sigma * pitch * u[k])
            .collect();
        let e = e_frac * h;
        Self {
            r_tip,
            r_root: r_tip - h,
            tips,
            ecc: [e * e_angle.cos(), e * e_angle.sin()],
            valleys: None,
            radii: None,
            sagitta: 0.0,
        }
    }

    /// Each tip and valley radius moved by `sd * w` (w from `w_tip`, `w_root`) plus a
    /// once-per-turn lobe `lobe * cos(angle - lobe_angle)`. Needs explicit valleys.
    pub fn with_radii(
        mut self,
        sd: f64,
        w_tip: &[f64],
        w_root: &[f64],
        lobe: f64,
        lobe_angle: f64,
    ) -> Self {
        let valleys = self.valleys.clone().unwrap_or_default();
        let bump = |a: f64| lobe * (a - lobe_angle).cos();
        let tips = (self.tips.iter().zip(w_tip))
            .map(|(&a, w)| self.r_tip + sd * w + bump(a))
            .collect();
        let roots = (valleys.iter().zip(w_root))
            .map(|(&a, w)| self.r_root + sd * w + bump(a))
            .collect();
        self.radii = Some((tips, roots));
        self
    }

    /// Valley k moved to the fraction `0.5 + shift * v[k]` of the angular gap from tip k to
    /// tip k + 1 (the last gap wraps round).
    pub fn with_valleys(mut self, shift: f64, v: &[f64]) -> Self {
        let n = self.teeth();
        let valleys = (0..n)
            .map(|k| {
                let next = if k + 1 < n {
                    self.tips[k + 1]
                } else {
                    self.tips[0] + TAU
                };
                self.tips[k] + (0.5 + shift * v[k]) * (next - self.tips[k])
            })
            .collect();
        self.valleys = Some(valleys);
        self
    }

    pub fn gear(&self) -> Option<Gear> {
        let centre = Vec2::new(self.ecc[0], self.ecc[1]);
        let gear = match &self.valleys {
            None => Gear::new(self.r_tip, self.r_root, self.tips.clone(), centre),
            Some(v) => Gear::with_valleys(
                self.r_tip,
                self.r_root,
                self.tips.clone(),
                v.clone(),
                centre,
            ),
        };
        let gear = match &self.radii {
            None => gear.ok(),
            Some((tips, roots)) => gear.ok()?.with_radii(tips.clone(), roots.clone()).ok(),
        };
        gear?.with_flank_sagitta(self.sagitta).ok()
    }

    /// The oracle's gear, built from the angles of the case (not from the solver's [`Gear`]).
    pub fn shape(&self) -> GearShape {
        let outline = match (&self.valleys, &self.radii) {
            (None, _) => outline_from_tips(&self.tips, self.r_tip, self.r_root),
            (Some(v), None) => outline_from_angles(&self.tips, v, self.r_tip, self.r_root),
            (Some(v), Some((tips, roots))) => outline_from_polar(&self.tips, tips, v, roots),
        };
        GearShape {
            outline,
            rotation_centre_offset: self.ecc,
        }
    }

    /// The oracle's arc-flanked gear (the same vertices as [`GearSpec::shape`]).
    pub fn curved_shape(&self) -> CurvedShape {
        let shape = self.shape();
        CurvedShape {
            vertices: shape.outline,
            sagitta: self.sagitta,
            rotation_centre_offset: shape.rotation_centre_offset,
        }
    }

    pub fn teeth(&self) -> usize {
        self.tips.len()
    }

    pub fn pitch(&self) -> f64 {
        TAU / self.teeth() as f64
    }
}

/// Most teeth of a generated gear.
pub const MAX_TEETH: usize = 60;

/// A random mesh and run. Every field is drawn independently (no dependent strategies), so that
/// shrinking keeps the case consistent; the gears are derived from it.
#[derive(Debug, Clone)]
pub struct Case {
    pub driver: GearSpec,
    pub driven: GearSpec,
    /// Tooth height h, mm (both gears).
    pub h: f64,
    /// Clearance G in percent of h.
    pub g_percent: f64,
    /// First driver angle of the run, radians.
    pub phi0: f64,
    /// Length of the run in driver pitches.
    pub pitches: u32,
    /// Initial guess for `Start::Touching`.
    pub guess: f64,
}

impl Case {
    pub fn centre_distance(&self) -> f64 {
        geometry::centre_distance(self.driver.r_tip, self.driven.r_tip, self.h, self.g_percent)
    }

    pub fn phi_end(&self) -> f64 {
        self.phi0 + f64::from(self.pitches) * self.driver.pitch()
    }

    /// The solver's mesh, or `None` if a constructor refuses the geometry.
    pub fn mesh(&self) -> Option<Mesh> {
        Mesh::new(
            self.driver.gear()?,
            self.driven.gear()?,
            self.centre_distance(),
        )
        .ok()
    }

    /// The oracle's mesh, placed independently of the solver: polygons for straight flanks,
    /// exact arcs as soon as either gear has curved ones.
    pub fn oracle(&self) -> Oracle {
        if self.driver.sagitta == 0.0 && self.driven.sagitta == 0.0 {
            Oracle::Straight(polycheck::Mesh {
                driver: self.driver.shape(),
                driven: self.driven.shape(),
                centre_distance: self.centre_distance(),
            })
        } else {
            Oracle::Curved(polycheck::CurvedMesh {
                driver: self.driver.curved_shape(),
                driven: self.driven.curved_shape(),
                centre_distance: self.centre_distance(),
            })
        }
    }

    pub fn run(&self, mesh: &Mesh) -> Trajectory {
        mesh.solve(
            self.phi0..=self.phi_end(),
            Start::Touching(self.guess),
            Solve::path(),
        )
    }
}

/// The independent oracle of a case.
pub enum Oracle {
    /// Straight flanks: polygons.
    Straight(polycheck::Mesh),
    /// Curved flanks: exact arcs.
    Curved(polycheck::CurvedMesh),
}

impl Oracle {
    pub fn penetration_at(&self, phi: f64, theta: f64) -> f64 {
        match self {
            Self::Straight(m) => m.penetration_at(phi, theta),
            Self::Curved(m) => m.penetration_at(phi, theta),
        }
    }

    pub fn distance_at(&self, phi: f64, theta: f64) -> f64 {
        match self {
            Self::Straight(m) => m.distance_at(phi, theta),
            Self::Curved(m) => m.distance_at(phi, theta),
        }
    }
}

/// Which errors a random case has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Errors {
    /// Ideal gears.
    None,
    /// Tooth (tip angle) errors only.
    Teeth,
    /// Tooth errors and eccentricity of one or both gears.
    All,
}

/// Random cases with the given kind of errors.
pub fn cases(
    errors_kind: Errors,
    g_percent: Range<f64>,
    pitches: Range<u32>,
) -> impl Strategy<Value = Case> {
    let teeth = (8usize..=60, 8usize..=60, 0.4..1.0f64, 0.6..1.4f64);
    let errors = (
        0.0..0.15f64,
        0.0..0.15f64,
        prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
        prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
    );
    let ecc = (0u8..4, 0.0..0.3f64, 0.0..TAU, 0.0..0.3f64, 0.0..TAU);
    let run = (g_percent, 0.0..TAU, pitches, 0.0..TAU);
    (teeth, errors, ecc, run)
        .prop_filter("h < 0.3 R for both gears", |&((n1, n2, m, h), ..)| {
            h < 0.3 * (n1.min(n2) as f64 * m / 2.0)
        })
        .prop_map(
            move |(
                (n1, n2, m, h),
                (s1, s2, u1, u2),
                (which, f1, a1, f2, a2),
                (g_percent, phi0, pitches, guess),
            )| {
                let (s1, s2, f1, f2) = match errors_kind {
                    Errors::None => (0.0, 0.0, 0.0, 0.0),
                    Errors::Teeth => (s1, s2, 0.0, 0.0),
                    Errors::All => (
                        s1,
                        s2,
                        if which & 1 != 0 { f1 } else { 0.0 },
                        if which & 2 != 0 { f2 } else { 0.0 },
                    ),
                };
                Case {
                    driver: GearSpec::new(n1, m, h, s1, &u1, f1, a1),
                    driven: GearSpec::new(n2, m, h, s2, &u2, f2, a2),
                    h,
                    g_percent,
                    phi0,
                    pitches,
                    guess,
                }
            },
        )
}

/// Random cases with tooth errors and eccentricity (as [`Errors::All`]) whose valleys are also
/// displaced off-centre in their tip gaps, by up to `0.45` of the gap either way (asymmetric
/// teeth). A separate strategy, so that the cases of the other tests stay as they were.
pub fn asymmetric_cases(pitches: Range<u32>) -> impl Strategy<Value = Case> {
    asymmetric_cases_at(15.0..85.0, pitches)
}

/// [`asymmetric_cases`] with the clearance drawn from `g_percent`.
pub fn asymmetric_cases_at(
    g_percent: Range<f64>,
    pitches: Range<u32>,
) -> impl Strategy<Value = Case> {
    let shifts = (
        0.0..0.45f64,
        0.0..0.45f64,
        prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
        prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
    );
    (cases(Errors::All, g_percent, pitches), shifts).prop_map(|(mut case, (s1, s2, v1, v2))| {
        case.driver = case.driver.with_valleys(s1, &v1);
        case.driven = case.driven.with_valleys(s2, &v2);
        case
    })
}

/// Asymmetric cases (see [`asymmetric_cases`]) whose gears are also not round: every tip and
/// valley radius off by up to `0.1 h` times a draw in [−1, 1], plus a once-per-turn lobe of up
/// to `0.1 h`.
pub fn non_circular_cases(pitches: Range<u32>) -> impl Strategy<Value = Case> {
    non_circular_cases_at(15.0..85.0, pitches)
}

/// [`non_circular_cases`] with the clearance drawn from `g_percent`.
pub fn non_circular_cases_at(
    g_percent: Range<f64>,
    pitches: Range<u32>,
) -> impl Strategy<Value = Case> {
    let radial = || {
        (
            0.0..0.1f64,
            prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
            prop::collection::vec(-1.0..=1.0f64, MAX_TEETH),
            0.0..0.1f64,
            0.0..TAU,
        )
    };
    (asymmetric_cases_at(g_percent, pitches), radial(), radial()).prop_map(
        |(mut case, (s1, t1, r1, l1, a1), (s2, t2, r2, l2, a2))| {
            let h = case.h;
            case.driver = case.driver.with_radii(s1 * h, &t1, &r1, l1 * h, a1);
            case.driven = case.driven.with_radii(s2 * h, &t2, &r2, l2 * h, a2);
            case
        },
    )
}

/// Largest flank sagitta drawn, as a fraction of the tooth height h, either sign; cases whose
/// sagittas break a rule of `Gear::with_flank_sagitta` are rejected (the rules bind at a few
/// percent of h for the slender teeth generated here).
pub const MAX_SAGITTA: f64 = 0.05;

/// `case` with flank sagittas `u · MAX_SAGITTA · h` (u in [−1, 1], drawn per gear: convex and
/// concave, alike or mixed).
pub fn with_sagittas(base: impl Strategy<Value = Case>) -> impl Strategy<Value = Case> {
    (base, -1.0..=1.0f64, -1.0..=1.0f64).prop_map(|(mut case, u1, u2)| {
        case.driver.sagitta = u1 * MAX_SAGITTA * case.h;
        case.driven.sagitta = u2 * MAX_SAGITTA * case.h;
        case
    })
}

/// Curved flanks on gears with tooth errors and eccentricity (as [`Errors::All`]).
pub fn curved_cases(pitches: Range<u32>) -> impl Strategy<Value = Case> {
    with_sagittas(cases(Errors::All, 15.0..85.0, pitches))
}

/// Curved flanks on asymmetric gears that are not round (see [`non_circular_cases`]).
pub fn curved_non_circular_cases(pitches: Range<u32>) -> impl Strategy<Value = Case> {
    with_sagittas(non_circular_cases(pitches))
}

/// Every kind of case above - tooth errors and eccentricity, asymmetric teeth, gears not round,
/// straight or curved flanks - at a clearance drawn from all of `g_percent`.
pub fn every_kind_of_case(
    g_percent: Range<f64>,
    pitches: Range<u32>,
) -> impl Strategy<Value = Case> {
    prop_oneof![
        cases(Errors::All, g_percent.clone(), pitches.clone()),
        asymmetric_cases_at(g_percent.clone(), pitches.clone()),
        non_circular_cases_at(g_percent.clone(), pitches.clone()),
        with_sagittas(cases(Errors::All, g_percent.clone(), pitches.clone())),
        with_sagittas(non_circular_cases_at(g_percent, pitches)),
    ]
}
