//! The positive real roots of a real polynomial, all of them, by the derivative cascade:
//! between two consecutive real roots of p′ the polynomial p is monotone, so it has at most one
//! root there, found where its sign changes; the roots of p′ come the same way from p″, down
//! to a linear polynomial (Collins & Loos, "Real zeros of polynomials", in *Computer Algebra*,
//! Springer 1983, §4; the classical isolation by Rolle's theorem). Each bracketed root is
//! refined by Newton's method safeguarded by bisection (Press et al., *Numerical Recipes*,
//! 3rd ed., §9.4 `rtsafe`), bisecting geometrically while a bracket spans decades.
//!
//! The roots are sought within the Fujiwara bounds of p's root moduli (Fujiwara 1916:
//! every root has |x| ≤ 2·max_j |c_j/c_n|^{1/(n−j)}, and by the reversed polynomial
//! |x| ≥ ½·1/max_j |c_j/c_0|^{1/j}), so a root of 1e-17 and one of 1e17 are both found to
//! full relative precision. A double root (a tangency) is found only where rounding leaves a
//! sign change; a pair of roots closer than the polynomial's rounding allows may be lost as a
//! pair, which the callers' confirmation by the point test guards.

/// Newton steps at most per root before the bracket is bisected to the end (each halves the
/// bracket at worst; quadratic convergence needs about six from a bracket of a few ulps'
/// worth of decades).
const MAX_STEPS: usize = 200;

/// Relative Newton step below which the root is taken (the next step's error, quadratic in
/// this one, is below the double's rounding).
const NEWTON_DONE: f64 = 1e-9;

/// The same for a derivative's roots, which only end the next level's brackets: after a step
/// of 1e-6 the error is of order 1e-12 relative, far below any sign test's resolution.
const BRACKET_DONE: f64 = 1e-6;

/// A bracket is bisected geometrically (at √(lo·hi)) while hi/lo exceeds this ratio: a root
/// at 1e-17 in a bracket reaching 1 is then found in a few dozen steps instead of 60
/// arithmetic halvings that never reach it.
const GEOMETRIC_RATIO: f64 = 8.0;

/// The distinct positive real roots of the polynomial with ascending coefficients `c`,
/// increasing (see the module doc). Exact zeros at x = 0 are not positive roots and are
/// dropped; an identically zero polynomial has none.
pub fn positive_roots(c: &[f64]) -> Vec<f64> {
    let Some(p) = normalized(c) else {
        return Vec::new();
    };
    let n = p.len() - 1;
    if n == 0 {
        return Vec::new();
    }
    let (lo, hi) = root_bounds(&p);
    // The cascade: derivatives[k] is the k-th derivative (scaled), down to the linear one.
    let mut chain = vec![p];
    while chain[chain.len() - 1].len() > 2 {
        let top = &chain[chain.len() - 1];
        chain.push(derivative(top));
    }
    let mut roots: Vec<f64> = Vec::new();
    for (level, q) in chain.iter().enumerate().rev() {
        let mut ends = Vec::with_capacity(roots.len() + 2);
        ends.push(lo);
        ends.extend(roots.iter().copied().filter(|&r| r > lo && r < hi));
        ends.push(hi);
        // a derivative's roots only bound the next level's brackets
        let done = if level == 0 {
            NEWTON_DONE
        } else {
            BRACKET_DONE
        };
        roots = roots_between_ends(q, &ends, done);
        roots.dedup();
    }
    roots
}

/// The polynomial without its exact zero roots (low zero coefficients) and its exact zero
/// leading coefficients, scaled so that its largest coefficient is 1; None when identically
/// zero or not finite.
fn normalized(c: &[f64]) -> Option<Vec<f64>> {
    let first = c.iter().position(|&x| x != 0.0)?;
    let last = c.iter().rposition(|&x| x != 0.0)?;
    let big = c.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    if !big.is_finite() || c.iter().any(|x| !x.is_finite()) {
        return None;
    }
    Some(c[first..=last].iter().map(|x| x / big).collect())
}

/// Lower and upper bounds of the moduli of p's roots (Fujiwara), p with nonzero constant and
/// leading coefficients.
fn root_bounds(p: &[f64]) -> (f64, f64) {
    let n = p.len() - 1;
    // in logarithms: a leading or constant coefficient near underflow leaves the ratios finite
    let ln = |x: f64| x.abs().ln();
    let (l0, ln_n) = (ln(p[0]), ln(p[n]));
    let upper = (0..n)
        .filter(|&j| p[j] != 0.0)
        .map(|j| (ln(p[j]) - ln_n) / (n - j) as f64)
        .fold(f64::NEG_INFINITY, f64::max);
    let lower_inv = (1..=n)
        .filter(|&j| p[j] != 0.0)
        .map(|j| (ln(p[j]) - l0) / j as f64)
        .fold(f64::NEG_INFINITY, f64::max);
    // a hair outside the bounds so that a root on a bound still has its sign change inside
    let lo = (0.5 * 0.999) * (-lower_inv).exp();
    let hi = (2.0 * 1.001) * upper.exp();
    (
        lo.clamp(f64::MIN_POSITIVE, 1e300),
        hi.clamp(f64::MIN_POSITIVE, 1e300),
    )
}

/// p′ scaled by 1/n (the same roots, coefficients of p's size).
fn derivative(p: &[f64]) -> Vec<f64> {
    let n = (p.len() - 1) as f64;
    p.iter()
        .enumerate()
        .skip(1)
        .map(|(j, &c)| c * j as f64 / n)
        .collect()
}

/// p and p′ at every point of `xs`, scaled by a positive factor per point (which keeps
/// their signs and their ratio p/p′, all the iteration needs): by Horner's rule up to x = 1,
/// and beyond through the reversed polynomial in y = 1/x, p(x) = x^n·p_rev(y), so that no
/// power of a large x overflows. The points below 1 run side by side (independent
/// recurrences that the processor overlaps).
fn eval_many(p: &[f64], xs: &[f64], v: &mut Vec<f64>, d: &mut Vec<f64>) {
    v.clear();
    v.resize(xs.len(), 0.0);
    d.clear();
    d.resize(xs.len(), 0.0);
    for &c in p.iter().rev() {
        for ((vi, di), &x) in v.iter_mut().zip(d.iter_mut()).zip(xs) {
            let x = x.min(1.0);
            *di = *di * x + *vi;
            *vi = *vi * x + c;
        }
    }
    let n = (p.len() - 1) as f64;
    for ((vi, di), &x) in v.iter_mut().zip(d.iter_mut()).zip(xs) {
        if x > 1.0 {
            // p′(x) = x^{n−1}·(n·p_rev(y) − y·p_rev′(y)): scaled by x^{−n}, p′ becomes
            // (n·p_rev − y·p_rev′)/x
            let y = 1.0 / x;
            let (r, dr) = p
                .iter()
                .fold((0.0, 0.0), |(r, dr), &c| (r * y + c, dr * y + r));
            *vi = r;
            *di = (n * r - y * dr) * y;
        }
    }
}

/// A root's bracket during the safeguarded Newton iteration.
#[derive(Debug, Clone, Copy)]
struct Bracket {
    lo: f64,
    hi: f64,
    /// p(lo) > 0 (p(hi) is then negative).
    lo_positive: bool,
    /// The current iterate.
    x: f64,
    /// Relative Newton step below which the root is taken.
    done_rel: f64,
    /// The previous step's length (rtsafe's halving rule).
    last_step: f64,
    done: bool,
}

impl Bracket {
    /// The bracket [lo, hi] with p(lo) = flo, p(hi) = fhi of opposite signs, started at the
    /// secant point where it is narrow and at its geometric middle where it spans decades.
    fn new((lo, flo): (f64, f64), (hi, fhi): (f64, f64), done_rel: f64) -> Self {
        let x = if wide(lo, hi) {
            middle(lo, hi)
        } else {
            lo + (hi - lo) * (flo / (flo - fhi))
        };
        Self {
            lo,
            hi,
            lo_positive: flo > 0.0,
            x,
            done_rel,
            last_step: hi - lo,
            done: false,
        }
    }

    /// One safeguarded Newton step from p(x) = v, p′(x) = d: Newton while it stays inside and
    /// at least halves the step (Press et al. §9.4), else bisection.
    fn step(&mut self, v: f64, d: f64) {
        let x = self.x;
        if v == 0.0 {
            self.done = true;
            return;
        }
        if (v > 0.0) == self.lo_positive {
            self.lo = x;
        } else {
            self.hi = x;
        }
        if self.hi - self.lo <= 4.0 * f64::EPSILON * x.abs() {
            self.done = true;
            return;
        }
        let step = v / d;
        let newton = x - step;
        let (lo, hi) = (self.lo, self.hi);
        // quadratic convergence: the error after a step of 1e-9 is below rounding
        if step.abs() <= self.done_rel * x.abs() {
            self.done = true;
            self.x = newton.clamp(lo, hi);
            return;
        }
        if newton > lo && newton < hi && !wide(lo, hi) && step.abs() <= 0.5 * self.last_step {
            self.x = newton;
            self.last_step = step.abs();
        } else {
            self.x = middle(lo, hi);
            self.last_step = hi - lo;
        }
    }
}

/// A bracket spans decades (bisected geometrically).
fn wide(lo: f64, hi: f64) -> bool {
    lo > 0.0 && hi > GEOMETRIC_RATIO * lo
}

/// The bisection point: geometric across decades, arithmetic otherwise.
fn middle(lo: f64, hi: f64) -> f64 {
    if wide(lo, hi) {
        (lo * hi).sqrt()
    } else {
        0.5 * (lo + hi)
    }
}

/// The roots of p between consecutive `ends` (increasing, p monotone between them): one where
/// the sign changes, refined by safeguarded Newton steps taken for every bracket at once.
fn roots_between_ends(p: &[f64], ends: &[f64], done_rel: f64) -> Vec<f64> {
    let (mut v, mut d) = (Vec::new(), Vec::new());
    eval_many(p, ends, &mut v, &mut d);
    let mut roots = Vec::new();
    let mut brackets: Vec<Bracket> = Vec::new();
    for i in 1..ends.len() {
        let (flo, fhi) = (v[i - 1], v[i]);
        if flo == 0.0 {
            roots.push(ends[i - 1]);
        } else if fhi != 0.0 && (flo > 0.0) != (fhi > 0.0) {
            brackets.push(Bracket::new((ends[i - 1], flo), (ends[i], fhi), done_rel));
        }
    }
    if v.last() == Some(&0.0) {
        roots.extend(ends.last());
    }
    let mut xs = Vec::with_capacity(brackets.len());
    let mut active: Vec<usize> = (0..brackets.len()).collect();
    for _ in 0..MAX_STEPS {
        if active.is_empty() {
            break;
        }
        // only the brackets still iterating are evaluated
        xs.clear();
        xs.extend(active.iter().map(|&i| brackets[i].x));
        eval_many(p, &xs, &mut v, &mut d);
        for (&i, (&vi, &di)) in active.iter().zip(v.iter().zip(&d)) {
            brackets[i].step(vi, di);
        }
        active.retain(|&i| !brackets[i].done);
    }
    roots.extend(brackets.iter().map(|b| b.x.clamp(b.lo, b.hi)));
    roots.sort_by(f64::total_cmp);
    roots
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Ascending coefficients of Π (x − r).
    fn from_roots(rs: &[f64]) -> Vec<f64> {
        rs.iter()
            .fold(vec![1.0], |p, &r| crate::poly::mul(&p, &[-r, 1.0]))
    }

    #[test]
    fn finds_every_positive_root_to_full_precision() {
        let rs = [1e-12, 3e-5, 0.5, 0.75, 2.0, 7e3];
        let mut p = from_roots(&rs);
        // a complex pair and a negative root that must not be reported
        p = crate::poly::mul(&p, &[2.0, 1.0, 1.0]);
        p = crate::poly::mul(&p, &[3.0, 1.0]);
        let got = positive_roots(&p);
        assert_eq!(got.len(), rs.len(), "{got:?}");
        for (g, r) in got.iter().zip(rs) {
            assert!((g - r).abs() <= 1e-12 * r, "{g} vs {r}");
        }
    }

    #[test]
    fn close_pairs_and_wide_scales() {
        // Wilkinson-like cluster: roots 1, 1 + 1e-6 and widely scaled ones
        let rs = [1e-15, 1.0, 1.000001, 1e15];
        let got = positive_roots(&from_roots(&rs));
        assert_eq!(got.len(), 4, "{got:?}");
        for (g, r) in got.iter().zip(rs) {
            assert!((g - r).abs() <= 1e-9 * r, "{g} vs {r}");
        }
    }

    #[test]
    fn no_positive_roots() {
        assert!(positive_roots(&[1.0, 2.0, 1.0]).is_empty()); // (x + 1)²
        assert!(positive_roots(&[0.0, 0.0, 1.0]).is_empty()); // x²
        assert!(positive_roots(&[0.0; 4]).is_empty());
        assert!(positive_roots(&[5.0]).is_empty());
        assert_eq!(positive_roots(&[-2.0, 1.0]), vec![2.0]);
    }
}
