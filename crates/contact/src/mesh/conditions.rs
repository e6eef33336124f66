//! The contact conditions of each end of a tooth pair's obstacle, as `meet.rs` solves them: a
//! vertex of one tooth on a flank (line or circle) of the other, and two arc flanks tangent.

use geometry::Vec2;
use smallvec::SmallVec;

use super::{End, Mesh, Placed};
use crate::meet::Condition;

/// One flank of a tooth as the contact conditions see it: a line (unit normal `n`, `n·x = h`,
/// gear frame from the rotation centre) or a circle (an arc's centre and radius).
#[derive(Debug, Clone, Copy)]
enum FlankShape {
    Line { n: Vec2, h: f64 },
    Circle { centre: Vec2, radius: f64 },
}

impl Placed {
    /// The shapes of tooth k's two flanks (gear frame).
    fn flank_shapes(&self, k: i64) -> [FlankShape; 2] {
        if !self.arcs.is_empty() {
            return self.arcs[self.idx(k)].map(|a| FlankShape::Circle {
                centre: a.centre,
                radius: a.radius,
            });
        }
        let v = self.tooth(k);
        [(v[0], v[1]), (v[1], v[2])].map(|(a, b)| {
            let e = b - a;
            let n = Vec2::new(e.y, -e.x) / e.norm();
            FlankShape::Line { n, h: n.dot(&a) }
        })
    }
}

/// A set of the contact conditions of one tooth pair, one bit each: bit `2i + g` for the
/// driver's vertex i (valley k−1, tip k, valley k) on the driven tooth's flank g, bit
/// `6 + 2i + g` for the driven vertex i on the driver tooth's flank g. (Where flanks are arcs,
/// the conditions of two flanks tangent are always in it.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ConditionSet(pub(crate) u16);

impl ConditionSet {
    /// Every condition.
    pub(crate) const ALL: Self = Self(u16::MAX);

    /// Whether the condition of vertex `i` on flank `g` is in the set (a driver vertex on a
    /// driven flank, or with `driven_vertex` a driven vertex on a driver flank).
    fn has(self, driven_vertex: bool, i: usize, g: usize) -> bool {
        let bit = 6 * usize::from(driven_vertex) + 2 * i + g;
        self.0 & (1 << bit) != 0
    }
}

impl Mesh {
    /// The contact conditions (`meet.rs`) of which one end of the obstacle of driver tooth `j`
    /// against driven tooth `k` is a root wherever the obstacle is wider than a just-met one: at
    /// the upper end the driver tooth's flank 1 (tip to the valley after it) meets the driven
    /// tooth's flank 1, at the lower end flank 0 meets flank 0; so an end of each tooth's flank
    /// of that end (that can reach the other gear) on the other tooth's flank, and, where flanks
    /// are arcs, every vertex on either flank and the two flanks tangent. An obstacle only just
    /// met - a tip crossing the corner of one flank twice - may have both ends on one side:
    /// [`Mesh::conditions_of_both_sides`] covers it.
    pub(crate) fn conditions(&self, j: i64, k: i64, end: End) -> SmallVec<[Condition; 8]> {
        let f = match end {
            End::Lower => 0,
            End::Upper => 1,
        };
        self.conditions_on(j, k, f..f + 1, ConditionSet::ALL)
    }

    /// The conditions of both sides of the (j, k) obstacle: either end of it is always a root of
    /// one of these (a lock of the wider class was missed where the lower end of a just-met
    /// obstacle lay on the side of its upper end).
    pub(crate) fn conditions_of_both_sides(&self, j: i64, k: i64) -> SmallVec<[Condition; 8]> {
        self.conditions_on(j, k, 0..2, ConditionSet::ALL)
    }

    /// [`Mesh::conditions_of_both_sides`] of the set `set` alone.
    pub(crate) fn conditions_in(
        &self,
        (j, k): (i64, i64),
        set: ConditionSet,
    ) -> SmallVec<[Condition; 8]> {
        self.conditions_on(j, k, 0..2, set)
    }

    /// [`Mesh::conditions`] for the flanks `sides` (0, 1 or both), of the set `set`.
    fn conditions_on(
        &self,
        j: i64,
        k: i64,
        sides: std::ops::Range<usize>,
        set: ConditionSet,
    ) -> SmallVec<[Condition; 8]> {
        let d = self.centre_distance;
        let (da, _) = self.driver.data(j);
        let (db, _) = self.driven.data(k);
        let (sa, sb) = (self.driver.flank_shapes(j), self.driven.flank_shapes(k));
        let mut out = SmallVec::new();
        // Straight flank g runs from vertex g to vertex g + 1, and only its ends touch the
        // other tooth's flank g; a curved flank may bulge past its ends: every vertex and both
        // flanks of each tooth are taken then.
        let sides = if self.curved { 0..2 } else { sides };
        for g in sides {
            let vertices = if self.curved { 0..3 } else { g..g + 2 };
            for i in vertices {
                if da.reaches[i] && set.has(false, i, g) {
                    out.push(vertex_on(sb[g], da.v[i], d, true));
                }
                if db.reaches[i] && set.has(true, i, g) {
                    out.push(vertex_on(sa[g], db.v[i], d, false));
                }
            }
        }
        let flanks = 0..2;
        for ga in flanks.clone() {
            for gb in flanks.clone() {
                flanks_tangent(sa[ga], sb[gb], d, &mut out);
            }
        }
        out
    }
}

/// A vertex of one gear (the driver's if `driver_vertex`) on a flank of the other.
fn vertex_on(flank: FlankShape, v: Vec2, d: f64, driver_vertex: bool) -> Condition {
    match (flank, driver_vertex) {
        (FlankShape::Line { n, h }, true) => Condition::driver_point_on_line(v, n, h, d),
        (FlankShape::Line { n, h }, false) => Condition::driven_point_on_line(v, n, h, d),
        (FlankShape::Circle { centre, radius }, true) => {
            Condition::points_apart(v, centre, radius, d)
        }
        (FlankShape::Circle { centre, radius }, false) => {
            Condition::points_apart(centre, v, radius, d)
        }
    }
}

/// A driver flank `a` tangent to a driven flank `b` where one is an arc: an arc's centre at its
/// radius from a line, or the two arcs' centres at the sum or difference of their radii.
fn flanks_tangent(a: FlankShape, b: FlankShape, d: f64, out: &mut SmallVec<[Condition; 8]>) {
    match (a, b) {
        (FlankShape::Line { .. }, FlankShape::Line { .. }) => {}
        (FlankShape::Circle { centre, radius }, FlankShape::Line { n, h }) => {
            for off in [radius, -radius] {
                out.push(Condition::driver_point_on_line(centre, n, h + off, d));
            }
        }
        (FlankShape::Line { n, h }, FlankShape::Circle { centre, radius }) => {
            for off in [radius, -radius] {
                out.push(Condition::driven_point_on_line(centre, n, h + off, d));
            }
        }
        (
            FlankShape::Circle {
                centre: ca,
                radius: ra,
            },
            FlankShape::Circle {
                centre: cb,
                radius: rb,
            },
        ) => {
            for r in [ra + rb, (ra - rb).abs()] {
                out.push(Condition::points_apart(ca, cb, r, d));
            }
        }
    }
}
