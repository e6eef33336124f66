//! Unit tests of `src/roots.rs`, compiled as its `tests` module: the circle-segment and
//! circle-circle crossings against worked cases.

use super::*;

#[test]
fn unit_circle_crosses_horizontal_segment() {
    let mut pts = Vec::new();
    circle_segment(
        Vec2::zeros(),
        1.0,
        Vec2::new(-2.0, 0.0),
        Vec2::new(2.0, 0.0),
        0.0625,
        |x| pts.push(x),
    );
    pts.sort_by(|p, q| p.x.total_cmp(&q.x));
    assert_eq!(pts.len(), 2);
    assert!((pts[0].x + 1.0).abs() < 1e-15 && (pts[1].x - 1.0).abs() < 1e-15);
}

#[test]
fn segment_ending_inside_gives_one_crossing() {
    let mut n = 0;
    circle_segment(
        Vec2::zeros(),
        1.0,
        Vec2::new(0.0, 0.0),
        Vec2::new(2.0, 0.0),
        0.25,
        |_| n += 1,
    );
    assert_eq!(n, 1);
}

#[test]
fn far_segment_gives_none() {
    let mut n = 0;
    circle_segment(
        Vec2::zeros(),
        1.0,
        Vec2::new(-2.0, 3.0),
        Vec2::new(2.0, 3.0),
        0.0625,
        |_| n += 1,
    );
    assert_eq!(n, 0);
}

#[test]
fn circles_cross_at_the_closed_form_points() {
    // |X| = 5 and |X − (8, 0)| = 5: X = (4, ±3).
    let mut pts = Vec::new();
    circle_circle(Vec2::zeros(), 25.0, Vec2::new(8.0, 0.0), 5.0, |x| {
        pts.push(x)
    });
    pts.sort_by(|p, q| p.y.total_cmp(&q.y));
    assert_eq!(pts.len(), 2);
    assert!((pts[0] - Vec2::new(4.0, -3.0)).norm() < 1e-14, "{pts:?}");
    assert!((pts[1] - Vec2::new(4.0, 3.0)).norm() < 1e-14, "{pts:?}");
    let mut n = 0;
    circle_circle(Vec2::zeros(), 1.0, Vec2::new(3.0, 0.0), 1.0, |_| n += 1);
    circle_circle(Vec2::zeros(), 1.0, Vec2::zeros(), 1.0, |_| n += 1);
    circle_circle(Vec2::zeros(), 1.0, Vec2::new(0.2, 0.0), 0.5, |_| n += 1);
    assert_eq!(n, 0);
}
