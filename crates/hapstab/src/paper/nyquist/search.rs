//! The one-dimensional searches of the region computations: golden-section extrema and
//! bisection of a predicate, to 1e-12 relative.

/// Golden-section maximum of f on [a, b] to 1e-12 of the angle: (argmax, max).
pub(super) fn golden_max(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    crate::extremum::golden_max(f, a, b, 1e-12 * (a.abs() + b.abs()).max(1e-300))
}

/// Bisection between `a` (pred false) and `b` (pred true) to 1e-12 relative; returns the
/// point on the true side.
pub(super) fn bisect_pred(mut a: f64, mut b: f64, pred: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m == a || m == b || (b - a).abs() <= 1e-12 * (a.abs() + b.abs()).max(1e-300) {
            break;
        }
        if pred(m) {
            b = m;
        } else {
            a = m;
        }
    }
    b
}

/// Golden-section minimization of `f` on [a, b].
pub(super) fn golden_min(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let (x, v) = golden_max(a, b, |t| -f(t));
    (x, -v)
}
