//! Tolerances in units a person can measure on a gear: the random error (a fraction of the
//! pitch) as degrees and as millimetres of tip position, the systematic error (degrees of the
//! paper's once-per-turn sinusoid, split between the teeth and the axis) as the eccentricity of
//! the axis in millimetres and the wave of the teeth in millimetres at the tip.

use std::f64::consts::TAU;

use serde::{Deserialize, Serialize};

/// A random tooth error on one gear, three ways.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RandomInUnits {
    /// Standard deviation of a tip's angular position, as a fraction of the pitch (Edmunds).
    pub fraction: f64,
    /// The same in degrees of the gear's turn: fraction × 360° / N.
    pub degrees: f64,
    /// The same in millimetres along the tip circle: fraction × 2π R / N.
    pub tip_mm: f64,
}

/// The random error `fraction` of the pitch on a gear of `teeth` teeth and tip radius
/// `tip_radius` (mm).
pub fn random_error(fraction: f64, teeth: usize, tip_radius: f64) -> RandomInUnits {
    let pitch_rad = TAU / teeth as f64;
    RandomInUnits {
        fraction,
        degrees: (fraction * pitch_rad).to_degrees(),
        tip_mm: fraction * pitch_rad * tip_radius,
    }
}

/// A systematic error on one gear: the paper's amplitude and what it does to the gear.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SystematicInUnits {
    /// Amplitude A of the once-per-turn error, degrees (Edmunds' systematic error).
    pub degrees: f64,
    /// The share (1 − split)·A carried by the axis, as the distance of the rotation centre from
    /// the geometric centre: R·tan((1 − split)·A), mm.
    pub eccentricity_mm: f64,
    /// The share split·A carried by the teeth, as the amplitude of their wave along the tip
    /// circle: R·split·A in radians, mm.
    pub wave_mm: f64,
}

/// The systematic error of `degrees` with `split` of it on the sinusoid of the teeth (the paper:
/// 0.5), on a gear of tip radius `tip_radius` (mm).
pub fn systematic_error(degrees: f64, split: f64, tip_radius: f64) -> SystematicInUnits {
    SystematicInUnits {
        degrees,
        eccentricity_mm: hypotheses::eccentricity(tip_radius, (1.0 - split) * degrees),
        wave_mm: tip_radius * (split * degrees).to_radians(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_worked_example_of_the_axis_shift() {
        // Section 4: "a 5° error ... 2.5° results in an axis shift of approximately 4 mm in a gear
        // with a 10-centimeter radius".
        let s = systematic_error(5.0, 0.5, 100.0);
        assert!((s.eccentricity_mm - 4.366).abs() < 1e-3, "{s:?}");
        assert!((s.wave_mm - 4.363).abs() < 1e-3, "{s:?}");
        // All on the teeth: no eccentricity; all on the axis: no wave.
        assert_eq!(systematic_error(1.0, 1.0, 50.0).eccentricity_mm, 0.0);
        assert_eq!(systematic_error(1.0, 0.0, 50.0).wave_mm, 0.0);
    }

    #[test]
    fn a_random_error_is_a_share_of_the_pitch() {
        // Section 4's example: 1° on a 60-tooth gear is 1/6 of its 6° pitch.
        let r = random_error(1.0 / 6.0, 60, 30.0);
        assert!((r.degrees - 1.0).abs() < 1e-12, "{r:?}");
        // An arc of 1° at R = 30 mm.
        assert!((r.tip_mm - 30.0 * 1f64.to_radians()).abs() < 1e-12, "{r:?}");
        // A gear with twice the teeth has half the pitch: the same fraction is half the angle.
        assert!(
            (random_error(0.04, 120, 30.0).degrees * 2.0 - random_error(0.04, 60, 30.0).degrees)
                .abs()
                < 1e-12
        );
    }
}
