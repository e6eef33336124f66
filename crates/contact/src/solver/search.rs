//! Plain one-dimensional searches the solver still uses where no root is solved for: the side of
//! a tooth pair born within a step, and the top of the pushing curves.

use super::LOCATE_TOL;

/// The bracket `(good, bad)`, at most `tol` wide, around the boundary between where `good` holds
/// (at `a`) and where it fails (at `b`).
pub(super) fn bracket(mut a: f64, mut b: f64, tol: f64, good: impl Fn(f64) -> bool) -> (f64, f64) {
    while b - a > tol {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if good(m) { a = m } else { b = m }
    }
    (a, b)
}

/// The boundary between where `good` holds (at `a`) and where it fails (at `b`), to LOCATE_TOL.
pub(super) fn bisect(mut a: f64, mut b: f64, good: impl Fn(f64) -> bool) -> f64 {
    while b - a > LOCATE_TOL {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if good(m) { a = m } else { b = m }
    }
    a
}

/// Where a function that rises and then falls (or ends, −∞) takes its largest value on [a, b].
///
/// Where the function ends (an obstacle vanishing as two tips slip apart) its last values may
/// flicker between finite and −∞ within rounding, as the contact roots graze: should the search
/// close in on −∞ there, the best finite point it evaluated is returned instead.
pub(super) fn golden_max(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    const R: f64 = 0.618_033_988_749_894_8;
    let best = std::cell::Cell::new((f64::NAN, f64::NEG_INFINITY));
    let f = |x: f64| {
        let y = f(x);
        if y > best.get().1 {
            best.set((x, y));
        }
        y
    };
    let mut x1 = b - R * (b - a);
    let mut x2 = a + R * (b - a);
    let mut f1 = f(x1);
    let mut f2 = f(x2);
    while b - a > LOCATE_TOL {
        if f1 < f2 {
            a = x1;
            x1 = x2;
            f1 = f2;
            x2 = a + R * (b - a);
            f2 = f(x2);
        } else {
            b = x2;
            x2 = x1;
            f2 = f1;
            x1 = b - R * (b - a);
            f1 = f(x1);
        }
        if x1 >= x2 {
            break;
        }
    }
    // The end points may be better than the interior (monotone on the bracket).
    let mid = 0.5 * (a + b);
    let (top, value) = [a, mid, b]
        .into_iter()
        .map(|p| (p, f(p)))
        .max_by(|p, q| p.1.total_cmp(&q.1))
        .unwrap_or((mid, f64::NEG_INFINITY));
    match best.get() {
        (x, y) if value == f64::NEG_INFINITY && y > value => x,
        _ => top,
    }
}
