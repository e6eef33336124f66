//! Edmunds' error-propagation model: teeth as radial lines, the driven gear set by the engaged pair at the line of centres.
//!
//! Edmunds (2011) treats each gear as radial lines, one per tooth, at the tooth's (displaced)
//! angular position about the gear's axis; tooth shape plays no part. The engaged pair is the
//! driver tooth nearest the line of centres and its partner on the driven gear; between tooth
//! changes the pair rolls at the nominal ratio. So with driver tooth j at angle α_j and driven
//! tooth k at α_k (both about their rotation centres, in this project's frame: driver tooth j
//! stands α_j + φ from the line of centres, driven tooth k stands θ − α_k from it),
//!
//! ```text
//! θ(φ) = α_k + (N1/N2)·(φ + α_j),   j the driver tooth nearest the line, k = c − j,
//! ```
//!
//! where the constant c fixes which teeth mesh. It applies to the same manufactured gears as the
//! triangular-tooth model (tip angles and eccentric centres), so the two can be compared trial by
//! trial: an eccentric centre enters through the tips' angles about the rotation centre.

use std::f64::consts::TAU;

use geometry::Gear;

/// Tip angles of a gear about its rotation centre, one per tooth, increasing, unwrapped from tip 0.
fn radial_angles(g: &Gear) -> Vec<f64> {
    let e = g.rotation_centre();
    let mut out = Vec::with_capacity(g.teeth());
    for k in 0..g.teeth() as i64 {
        let v = g.tip(k) - e;
        let a = v.y.atan2(v.x);
        // Unwrap next to the geometric tip angle (the eccentric shift is far below half a turn).
        let nominal = g.tip_angle(k);
        out.push(
            nominal + (a - nominal + std::f64::consts::PI).rem_euclid(TAU) - std::f64::consts::PI,
        );
    }
    out
}

/// What a gear has that the radial-line model cannot take, in words (`None`: nothing). The model
/// sees each tip's angle about the rotation centre and nothing else, so valleys off the midway
/// between their tips, radii that differ from tooth to tooth and curved flanks all run as if the
/// gear were ideal: comparing it with the triangular teeth on such gears compares nothing.
pub fn unseen(g: &Gear) -> Option<&'static str> {
    if g.flank_sagitta() != 0.0 {
        return Some("curved flanks");
    }
    let n = g.teeth() as i64;
    if (0..n)
        .any(|k| g.tip_radius_of(k) != g.tip_radius() || g.root_radius_of(k) != g.root_radius())
    {
        return Some("radii that differ from tooth to tooth");
    }
    let (tips, valleys) = (g.tip_angles(), g.valley_angles());
    let off_midway = (0..tips.len()).any(|k| {
        let next = tips.get(k + 1).copied().unwrap_or(tips[0] + TAU);
        (valleys[k] - 0.5 * (tips[k] + next)).abs() > 1e-9
    });
    off_midway.then_some("valleys off the midway between their tips")
}

/// One mesh in Edmunds' model.
#[derive(Debug, Clone)]
pub struct RadialPair {
    driver: Vec<f64>,
    driven: Vec<f64>,
    ratio: f64,
    /// j + k of every engaged pair.
    pairing: i64,
}

impl RadialPair {
    /// The pair of `driver` and `driven`, starting at driver angle `phi0` with the driver tooth
    /// nearest the line of centres engaged with driven tooth 0.
    pub fn new(driver: &Gear, driven: &Gear, phi0: f64) -> Self {
        let mut p = Self {
            driver: radial_angles(driver),
            driven: radial_angles(driven),
            ratio: driver.teeth() as f64 / driven.teeth() as f64,
            pairing: 0,
        };
        p.pairing = p.engaged(phi0);
        p
    }

    /// Angle of unwrapped tooth `k` of a gear with radial angles `a`.
    fn angle(a: &[f64], k: i64) -> f64 {
        let n = a.len() as i64;
        a[k.rem_euclid(n) as usize] + TAU * k.div_euclid(n) as f64
    }

    /// The driver tooth nearest the line of centres at driver angle φ.
    fn engaged(&self, phi: f64) -> i64 {
        let n = self.driver.len() as i64;
        let pitch = TAU / n as f64;
        let guess = (-phi / pitch).round() as i64;
        (guess - 2..=guess + 2)
            .min_by(|&a, &b| {
                let da = (Self::angle(&self.driver, a) + phi).abs();
                let db = (Self::angle(&self.driver, b) + phi).abs();
                da.total_cmp(&db)
            })
            .unwrap_or(guess)
    }

    /// Driven angle θ at driver angle φ.
    pub fn theta(&self, phi: f64) -> f64 {
        let j = self.engaged(phi);
        let k = self.pairing - j;
        Self::angle(&self.driven, k) + self.ratio * (phi + Self::angle(&self.driver, j))
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;
    use geometry::Vec2;

    #[test]
    fn ideal_gears_follow_the_ratio_exactly() {
        let a = Gear::ideal(64, 15.4, 14.3).unwrap();
        let b = Gear::ideal(38, 9.15, 8.05).unwrap();
        let p = RadialPair::new(&a, &b, 0.01);
        let t0 = p.theta(0.01);
        for i in 0..500 {
            let phi = 0.01 + i as f64 * 0.013;
            assert!((p.theta(phi) - t0 - (64.0 / 38.0) * (phi - 0.01)).abs() < 1e-12);
        }
    }

    #[test]
    fn a_displaced_driven_tooth_shifts_the_driven_gear_while_it_is_engaged() {
        let a = Gear::ideal(20, 10.0, 9.0).unwrap();
        let mut tips: Vec<f64> = (0..20).map(|k| TAU * k as f64 / 20.0).collect();
        tips[1] += 0.01;
        let b = Gear::new(10.0, 9.0, tips, Vec2::zeros()).unwrap();
        let p = RadialPair::new(&a, &b, 0.0);
        let pitch = TAU / 20.0;
        // Driver tooth -1 reaches the line at φ = pitch and engages driven tooth 1.
        assert!((p.theta(pitch) - p.theta(0.0) - pitch - 0.01).abs() < 1e-12);
        assert!((p.theta(2.0 * pitch) - p.theta(0.0) - 2.0 * pitch).abs() < 1e-12);
    }
}
