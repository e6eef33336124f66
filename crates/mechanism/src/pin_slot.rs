//! The pin-and-slot lunar anomaly mechanism (Freeth 2006) in closed form.
//!
//! Two gears ride on a turntable on axes `e` apart. The pin gear carries a pin at radius `R`
//! from its axis; the pin engages a radial slot of the slot gear. Measure both gears' angles
//! relative to the turntable, in their (common) direction of rotation, from the line of centres
//! (pin gear axis towards slot gear axis). With the pin gear at angle `a` the pin sits at
//! `R (cos a, sin a)` from the pin gear's axis, and the slot gear, whose slot points at the pin,
//! is at
//!
//! ```text
//! b(a) = a + atan2(e sin a, R - e cos a)
//! ```
//!
//! [`slot_angle`]. The deviation `b - a` is largest, `asin(e / R)` ([`anomaly_amplitude`]), where
//! `cos a = e / R` (the pin sees the two axes at a right angle), and `b(a + 2 pi) = b(a) + 2 pi`:
//! over a turn the slot gear keeps the pin gear's mean rate.
//!
//! In a train ([`PinSlotTrain`]) the turntable turns at its own rate, so the pin mesh's driver
//! (Freeth 2006: e5, on the turntable's axis) is seen from the turntable: its angle relative to
//! the turntable is what turns the pin gear, and the slot gear's mesh partner (e6) is carried
//! round by the turntable on top of what the slot gear turns it. With `s = +1` when the
//! turntable turns the same way as the pin mesh's driver (`-1` the other way; every angle is
//! positive in its own gear's direction of rotation), the turntable angle `T` and the driver
//! angle `E`:
//!
//! ```text
//! pin gear   k = c1 (E - s T)                    c1 = ratio of the pin mesh
//! slot gear  b(k0 + k) - b(k0)                   k0 = the pin's phase at the start
//! output     s T + c2 (b(k0 + k) - b(k0))        c2 = ratio of the slot gear's mesh
//! pointer    c3 * output                         c3 = ratio of the meshes after it
//! ```
//!
//! The cosmos's devices (`train::PinDevice`) are the same geometry in b1's frame: a superior
//! planet's pin gear and slot gear ride on b1, which is the whole train's frame, so the
//! turntable stands still (`turntable_ratio` 0, [`PinSlotTrain::new`]); an inferior planet's (and
//! the true Sun's) pin drives a slotted follower on b's axis, further from the pin gear's axis
//! than the pin ([`follower_angle`]), so the follower swings about b1's direction instead of
//! turning round.

use std::f64::consts::TAU;

use train::Gearing;

/// Slot gear angle for pin gear angle `a` (radians), both relative to the turntable and measured
/// from the line of centres in the gears' direction of rotation; `offset` is the distance between
/// the axes and `pin_radius` the pin's distance from the pin gear's axis (any one length unit,
/// `offset < pin_radius`). A zero offset gives `a`: the rigid coupling.
#[must_use]
pub fn slot_angle(a: f64, offset: f64, pin_radius: f64) -> f64 {
    a + (offset * a.sin()).atan2(pin_radius - offset * a.cos())
}

/// A slotted follower's angle from the line of centres (the follower's axis towards the pin
/// gear's), for the pin gear at angle `a` from that line (both in the frame the axes are fixed
/// in): the direction of the pin seen from the follower's axis, `atan2(pin sin a, offset + pin cos
/// a)`, where `offset` is the distance between the axes and `pin_radius` the pin's from the pin
/// gear's axis (`pin_radius < offset`: the follower swings, never turns round). An inferior
/// planet's elongation from the mean Sun in the cosmos.
#[must_use]
pub fn follower_angle(a: f64, offset: f64, pin_radius: f64) -> f64 {
    (pin_radius * a.sin()).atan2(offset + pin_radius * a.cos())
}

/// A follower's largest swing either side of the line of centres, `asin(pin_radius / offset)`
/// radians, reached where the slot is tangent to the pin's circle (an inferior planet's greatest
/// elongation: Venus about 46 degrees).
#[must_use]
pub fn greatest_elongation(offset: f64, pin_radius: f64) -> f64 {
    (pin_radius / offset).asin()
}

/// The largest deviation of the slot gear from the pin gear, `asin(offset / pin_radius)`
/// radians, reached at `cos a = offset / pin_radius` (and its negative at the mirror angle).
#[must_use]
pub fn anomaly_amplitude(offset: f64, pin_radius: f64) -> f64 {
    (offset / pin_radius).asin()
}

/// The pin-and-slot placed in one pointer's train, with the exact ratios that give the pointer's
/// ideal motion: every gear perfect, the turntable at its mean rate from the gear ratios.
#[derive(Debug, Clone, PartialEq)]
pub struct PinSlotTrain {
    /// Index in the pointer's meshes of the mesh that drives the pin gear (Freeth 2006: e5-k1);
    /// the next mesh is the slot gear's (k2-e6).
    pub pin_stage: usize,
    /// Distance between the pin gear's and the slot gear's axes, mm.
    pub offset: f64,
    /// Distance of the pin from the pin gear's axis, mm.
    pub pin_radius: f64,
    /// The pin gear's angle from the line of centres at the start (radians).
    pub pin_phase: f64,
    /// Turntable turns per input turn, in the turntable's own direction (the exact ratio of the
    /// chain of meshes from the input arbor to the turntable).
    pub turntable_ratio: f64,
    /// `+1` if the turntable turns the same way as the pin mesh's driver, `-1` if not.
    pub turntable_sign: f64,
    /// Turns of the pin mesh's driver per input turn (meshes before the pin mesh).
    pub driver_ratio: f64,
    /// Ratio of the pin mesh (`c1`).
    pub pin_mesh_ratio: f64,
    /// Ratio of the slot gear's mesh (`c2`).
    pub slot_mesh_ratio: f64,
    /// Ratio of the meshes after the slot gear's mesh (`c3`; 1 if there are none).
    pub after_ratio: f64,
}

impl PinSlotTrain {
    /// The gearing's pin-and-slot in `pointer`'s train, the pin starting at `pin_phase` radians
    /// from the line of centres: the cosmos's slot-gear device of the pointer if it has one
    /// ([`PinSlotTrain::carried`]), else the lunar one; `None` if neither is in the pointer's
    /// train (a validated gearing guarantees the rest).
    #[must_use]
    pub fn new(gearing: &Gearing, pointer: &str, pin_phase: f64) -> Option<PinSlotTrain> {
        if let Some(d) = gearing.device(pointer) {
            return PinSlotTrain::carried(gearing, pointer, d, pin_phase);
        }
        let ps = gearing.pin_and_slot()?;
        let p = gearing.pointer(pointer)?;
        let pin_stage = p
            .meshes
            .iter()
            .position(|label| gearing.mesh(label).is_some_and(|m| m.driven == ps.pin_gear))?;
        let slot_label = p.meshes.get(pin_stage + 1)?;
        if gearing.mesh(slot_label)?.driver != ps.slot_gear {
            return None;
        }
        let product = |labels: &[String]| -> Option<f64> {
            labels
                .iter()
                .map(|l| gearing.mesh_ratio(l).map(train::Ratio::to_f64))
                .product()
        };
        let turntable_arbor = gearing.arbor_of(&ps.turntable)?;
        let path = gearing.mesh_path(&p.input, turntable_arbor)?;
        // Each external mesh reverses the sense of rotation: two arbors turned from the same
        // input turn the same way when their chains have the same parity.
        let same_way = path.len() % 2 == pin_stage % 2;
        Some(PinSlotTrain {
            pin_stage,
            offset: ps.axis_offset,
            pin_radius: ps.pin_radius,
            pin_phase,
            turntable_ratio: product(&path)?,
            turntable_sign: if same_way { 1.0 } else { -1.0 },
            driver_ratio: product(&p.meshes[..pin_stage])?,
            pin_mesh_ratio: product(&p.meshes[pin_stage..=pin_stage])?,
            slot_mesh_ratio: product(&p.meshes[pin_stage + 1..pin_stage + 2])?,
            after_ratio: product(&p.meshes[pin_stage + 2..])?,
        })
    }

    /// A cosmos device of kind `SlotGear` in `pointer`'s train, in the frame the train runs in
    /// (b1's), where the pin and slot gears' axes stand still: the turntable's rate is zero.
    /// `None` for a follower (it drives no mesh) or a device not in the pointer's train.
    #[must_use]
    pub fn carried(
        gearing: &Gearing,
        pointer: &str,
        device: &train::PinDevice,
        pin_phase: f64,
    ) -> Option<PinSlotTrain> {
        if device.kind != train::DeviceKind::SlotGear {
            return None;
        }
        let p = gearing.pointer(pointer)?;
        let pin_stage = p.meshes.iter().position(|label| {
            gearing
                .mesh(label)
                .is_some_and(|m| m.driven == device.pin_gear)
        })?;
        let product = |labels: &[String]| -> Option<f64> {
            labels
                .iter()
                .map(|l| gearing.mesh_ratio(l).map(train::Ratio::to_f64))
                .product()
        };
        Some(PinSlotTrain {
            pin_stage,
            offset: device.axis_offset,
            pin_radius: device.pin_radius,
            pin_phase,
            turntable_ratio: 0.0,
            turntable_sign: 1.0,
            driver_ratio: product(&p.meshes[..pin_stage])?,
            pin_mesh_ratio: product(&p.meshes[pin_stage..=pin_stage])?,
            slot_mesh_ratio: product(p.meshes.get(pin_stage + 1..pin_stage + 2)?)?,
            after_ratio: product(&p.meshes[pin_stage + 2..])?,
        })
    }

    /// The turntable's angle, seen in the sense of the pin mesh's driver (`s T`), after the input
    /// has turned `psi` radians.
    #[must_use]
    pub fn turntable_angle(&self, psi: f64) -> f64 {
        self.turntable_sign * self.turntable_ratio * psi
    }

    /// The pin mesh's driver angle relative to the turntable, from its absolute angle `x`.
    #[must_use]
    pub fn into_turntable(&self, x: f64, psi: f64) -> f64 {
        x - self.turntable_angle(psi)
    }

    /// The slot gear mesh's driven angle back in the fixed frame, from its angle `x` relative
    /// to the turntable.
    #[must_use]
    pub fn out_of_turntable(&self, x: f64, psi: f64) -> f64 {
        x + self.turntable_angle(psi)
    }

    /// The slot gear's rotation when the pin gear has turned `k` radians from the start (both
    /// relative to the turntable).
    #[must_use]
    pub fn slot_change(&self, k: f64) -> f64 {
        slot_angle(self.pin_phase + k, self.offset, self.pin_radius)
            - slot_angle(self.pin_phase, self.offset, self.pin_radius)
    }

    /// The pointer's ideal rotation (radians) after the input has turned `psi`: perfect gears,
    /// the turntable at its mean rate, the anomaly of the pin-and-slot included.
    #[must_use]
    pub fn ideal_pointer_angle(&self, psi: f64) -> f64 {
        let driver = self.driver_ratio * psi;
        let pin = self.pin_mesh_ratio * self.into_turntable(driver, psi);
        let output = self.out_of_turntable(self.slot_mesh_ratio * self.slot_change(pin), psi);
        self.after_ratio * output
    }

    /// The pointer's mean rate (turns per input turn): with 50:50 gears on the turntable
    /// (`c1 c2 = 1`) the ratio of the rigid train.
    #[must_use]
    pub fn mean_ratio(&self) -> f64 {
        let c12 = self.pin_mesh_ratio * self.slot_mesh_ratio;
        self.after_ratio
            * (c12 * self.driver_ratio + (1.0 - c12) * self.turntable_sign * self.turntable_ratio)
    }

    /// The anomaly on the pointer (radians): its ideal rotation minus its mean motion.
    #[must_use]
    pub fn anomaly(&self, psi: f64) -> f64 {
        self.ideal_pointer_angle(psi) - self.mean_ratio() * psi
    }

    /// Input turns in one period of the anomaly: one turn of the pin gear relative to the
    /// turntable (Freeth 2006: the anomalistic month).
    #[must_use]
    pub fn anomaly_period_turns(&self) -> f64 {
        1.0 / (self.pin_mesh_ratio
            * (self.driver_ratio - self.turntable_sign * self.turntable_ratio))
            .abs()
    }

    /// The anomaly's amplitude on the pointer (radians), from the geometry.
    #[must_use]
    pub fn pointer_amplitude(&self) -> f64 {
        self.after_ratio * self.slot_mesh_ratio * anomaly_amplitude(self.offset, self.pin_radius)
    }

    /// Input radians in one anomaly period.
    #[must_use]
    pub fn anomaly_period(&self) -> f64 {
        self.anomaly_period_turns() * TAU
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, reason = "tests")]
    use super::*;

    const E: f64 = 1.1;
    const R: f64 = 9.6;

    #[test]
    fn amplitude_is_asin_offset_over_radius_exactly() {
        let a = anomaly_amplitude(E, R);
        assert_eq!(a, (E / R).asin());
        // Reached where the pin sees the axes at a right angle, and its mirror image.
        let at = (E / R).acos();
        assert!((slot_angle(at, E, R) - at - a).abs() < 1e-15);
        assert!((slot_angle(-at, E, R) + at + a).abs() < 1e-15);
        // Never exceeded: a dense scan of one turn.
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=100_000 {
            let x = TAU * f64::from(i) / 100_000.0;
            let d = slot_angle(x, E, R) - x;
            lo = lo.min(d);
            hi = hi.max(d);
        }
        assert!(hi <= a + 1e-15 && hi > a - 1e-9, "{hi} vs {a}");
        assert!(lo >= -a - 1e-15 && lo < -a + 1e-9, "{lo} vs {a}");
        // Freeth 2006's geometry: about 6.6 degrees.
        assert!((a.to_degrees() - 6.579).abs() < 1e-3, "{}", a.to_degrees());
    }

    #[test]
    fn mean_rate_is_kept_over_a_turn_and_the_slot_never_turns_back() {
        for i in 0..100 {
            let x = -7.0 + 0.3 * f64::from(i);
            let turn = slot_angle(x + TAU, E, R) - slot_angle(x, E, R);
            assert!((turn - TAU).abs() < 1e-12, "{x}: {turn}");
            // Slope between R/(R+e) and R/(R-e).
            let h = 1e-6;
            let slope = (slot_angle(x + h, E, R) - slot_angle(x - h, E, R)) / (2.0 * h);
            assert!(
                slope > R / (R + E) - 1e-6 && slope < R / (R - E) + 1e-6,
                "{slope}"
            );
        }
        // On the line of centres the pin and the slot agree.
        assert_eq!(slot_angle(0.0, E, R), 0.0);
        assert!((slot_angle(std::f64::consts::PI, E, R) - std::f64::consts::PI).abs() < 1e-15);
    }

    #[test]
    fn zero_offset_is_the_rigid_coupling() {
        for i in 0..50 {
            let x = -3.0 + 0.37 * f64::from(i);
            assert_eq!(slot_angle(x, 0.0, R), x);
        }
        assert_eq!(anomaly_amplitude(0.0, R), 0.0);
        let g = Gearing::freeth2006();
        let mut t = PinSlotTrain::new(&g, "Lunar", 0.4).unwrap();
        t.offset = 0.0;
        let ratio = g.pointer_ratio("Lunar").unwrap().to_f64();
        for i in 0..50 {
            let psi = 0.17 * f64::from(i);
            assert!((t.ideal_pointer_angle(psi) - ratio * psi).abs() < 1e-12);
        }
    }

    #[test]
    fn freeth_lunar_train_shows_the_anomalistic_month() {
        let g = Gearing::freeth2006();
        let t = PinSlotTrain::new(&g, "Lunar", 0.0).unwrap();
        assert_eq!(t.pin_stage, 3);
        // b -> e3 and b -> e5 both through three meshes: the turntable turns the way e5 does.
        assert_eq!(t.turntable_sign, 1.0);
        assert!((t.turntable_ratio - (64.0 * 53.0 * 27.0) / (38.0 * 96.0 * 223.0)).abs() < 1e-15);
        // The apsidal line: about 8.88 years per turn of the turntable.
        assert!((1.0 / t.turntable_ratio - 8.883).abs() < 1e-3);
        let ratio = g.pointer_ratio("Lunar").unwrap().to_f64();
        assert!((t.mean_ratio() - ratio).abs() < 1e-12);
        // The anomalistic month (27.5545 d): sidereal minus apsidal rate.
        let days = t.anomaly_period_turns() * train::DAYS_PER_TURN;
        assert!((days - 27.554).abs() < 1e-3, "{days}");
        // Over whole anomaly periods the pointer is back on its mean motion.
        let p = t.anomaly_period();
        for n in 1..=3 {
            let psi = p * f64::from(n);
            assert!((t.anomaly(psi)).abs() < 1e-9, "{}", t.anomaly(psi));
        }
        // The pointer's anomaly spans +- asin(1.1/9.6) over a period.
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=20_000 {
            let a = t.anomaly(p * f64::from(i) / 20_000.0);
            lo = lo.min(a);
            hi = hi.max(a);
        }
        let amp = t.pointer_amplitude();
        assert!(
            (hi - amp).abs() < 1e-6 && (lo + amp).abs() < 1e-6,
            "{lo} {hi}"
        );
        // Other pointers do not run through it.
        assert!(PinSlotTrain::new(&g, "Metonic", 0.0).is_none());
    }

    #[test]
    fn a_follower_swings_by_the_greatest_elongation() {
        // Freeth 2021's Venus: pin 20.01 mm, axes 27.8 mm apart: 46 degrees either side.
        let (d, p) = (27.8, 20.01);
        let e = greatest_elongation(d, p);
        assert!((e.to_degrees() - 46.0).abs() < 0.05, "{}", e.to_degrees());
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..=100_000 {
            let x = follower_angle(TAU * f64::from(i) / 100_000.0, d, p);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        assert!((hi - e).abs() < 1e-8 && (lo + e).abs() < 1e-8, "{lo} {hi}");
        // On the line of centres, pin outward or inward: the follower on the line.
        assert_eq!(follower_angle(0.0, d, p), 0.0);
        assert!(follower_angle(std::f64::consts::PI, d, p).abs() < 1e-15);
    }

    #[test]
    fn cosmos_slot_gears_turn_in_b1s_frame() {
        let g = Gearing::builtin("freeth2021-cosmos").unwrap();
        let t = PinSlotTrain::new(&g, "Mars", 0.3).unwrap();
        assert_eq!((t.pin_stage, t.offset, t.pin_radius), (2, 6.58, 10.0));
        assert_eq!(t.turntable_ratio, 0.0);
        // The mean rate is the rigid train's: 133/284 relative to b1.
        let ratio = g.pointer_ratio("Mars").unwrap().to_f64();
        assert!((t.mean_ratio() - ratio).abs() < 1e-15);
        assert!((ratio - 133.0 / 284.0).abs() < 1e-15);
        // The anomaly's period is the synodic period, 284/133 years.
        assert!((t.anomaly_period_turns() - 284.0 / 133.0).abs() < 1e-12);
        // A follower drives no mesh; the Lunar train keeps its own device.
        assert!(PinSlotTrain::new(&g, "Venus", 0.0).is_none());
        assert_eq!(PinSlotTrain::new(&g, "Lunar", 0.0).unwrap().pin_stage, 3);
    }
}
