//! Roots of the characteristic polynomial p(z) for the stability test of Section V.
//!
//! Two independent root finders on ascending real coefficients:
//!
//! - [`aberth`]: the Aberth–Ehrlich simultaneous iteration, started on circles read off the
//!   Newton polygon of the coefficient moduli and stopped root by root on the backward error.
//!   p(z) = z^{d+1} D(z) + N(z)((α + β) z − β) has six nonzero coefficients whatever the delay,
//!   so p and p′ are evaluated on the nonzero terms only (powers by squaring); a sweep costs
//!   O(n²) for the pairwise Aberth sums alone, and a degree of 2003 (d = 2000) takes a few
//!   tens of milliseconds.
//! - [`companion`]: eigenvalues of the dense companion matrix (nalgebra's real Schur
//!   decomposition, O(n³)); the independent cross-check.
//!
//! [`inclusion_radii`] bounds the error of any set of root approximations.

use nalgebra::{DMatrix, Schur};
use num_complex::Complex64;

use crate::error::{Error, Result};

/// Most Aberth–Ehrlich sweeps before giving up. From starting points on the Newton-polygon
/// circles the iteration needs 5–30 sweeps up to degree 2003; 500 leaves room for clustered
/// roots (linear convergence on clusters) and still ends in well under a second at d = 2000.
pub const MAX_SWEEPS: usize = 500;

/// Factor on the running error bound of the evaluation of p: a root is accepted once
/// |p(z)| ≤ EVAL_NOISE · ops · ε · Σ|c_k||z|^k, the size of the rounding error of the
/// evaluation itself (about 2ε per complex multiply-add, `ops` of them), below which the
/// computed value carries no more information about the root.
const EVAL_NOISE: f64 = 2.0;

/// Angle offset of the starting points on each circle (Bini's choice): it keeps the starting
/// points off the real axis and off any symmetry of the roots, where the iteration could stall.
const START_ANGLE: f64 = 0.7;

/// Relative move of an approximation that has met another one, so that the two separate
/// again: large enough to give them distinct Aberth sums, small against the spacing of the
/// starting points.
const NUDGE: f64 = 1e-3;

/// A root approximation with a bound on its error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RootEstimate {
    /// The approximation.
    pub z: Complex64,
    /// Radius of a disc about `z` that contains a root of p, allowing for the rounding
    /// error of evaluating p (see [`inclusion_radii`]).
    pub radius: f64,
    /// First-order estimate of the error of `z`: (|p(z)| + rounding bound)/|p′(z)|, the size
    /// of the Newton correction that the rounding of p still allows. For a simple root the
    /// error is this to first order; `radius` (n times it) holds rigorously.
    pub error: f64,
}

/// The nonzero terms of a polynomial, highest exponent first, ready for evaluation with
/// gaps, together with the polynomial's degree.
#[derive(Debug, Clone)]
struct Terms {
    /// (exponent, coefficient), exponents strictly decreasing.
    terms: Vec<(u32, f64)>,
    /// Number of rounding errors that the evaluation can accumulate on its largest term.
    ops: f64,
    /// No exponent missing: [`Terms::eval_dense`].
    dense: bool,
}

/// p(z), p′(z) and the running error bound of the computed p(z).
#[derive(Debug, Clone, Copy)]
struct Eval {
    p: Complex64,
    dp: Complex64,
    noise: f64,
}

impl Terms {
    fn new(terms: Vec<(u32, f64)>, degree: usize) -> Self {
        // z^g by squaring carries a relative error of about g rounding errors (each squaring
        // doubles the error of the one before), as g steps of Horner's scheme would: about
        // one operation per degree plus one per term.
        let ops = (degree + terms.len()) as f64;
        // every exponent from the degree down to 0 present
        let dense = terms.len() == degree + 1;
        Self { terms, ops, dense }
    }

    /// Horner's scheme over the nonzero terms: across a gap of g exponents
    /// P ← P z^g + c and P′ ← P′ z^g + g P z^{g−1}.
    fn eval(&self, z: Complex64) -> Eval {
        let az = z.norm();
        if self.dense {
            return self.eval_dense(z, az);
        }
        let (mut e, c0) = self.terms[0];
        let mut p = Complex64::new(c0, 0.0);
        let mut dp = Complex64::new(0.0, 0.0);
        let mut abs = c0.abs();
        for &(k, c) in &self.terms[1..] {
            let g = e - k;
            let (zg1, zg) = powers(z, g);
            dp = dp * zg + p * (g as f64) * zg1;
            p = p * zg + c;
            abs = abs * az.powi(g as i32) + c.abs();
            e = k;
        }
        if e > 0 {
            let (ze1, ze) = powers(z, e);
            dp = dp * ze + p * (e as f64) * ze1;
            p *= ze;
            abs *= az.powi(e as i32);
        }
        let noise = EVAL_NOISE * self.ops * f64::EPSILON * abs;
        Eval { p, dp, noise }
    }
}

impl Terms {
    /// [`Terms::eval`] where every exponent is present (no gaps): plain Horner steps, the
    /// same operations as the gap-1 case of the general loop.
    fn eval_dense(&self, z: Complex64, az: f64) -> Eval {
        let c0 = self.terms[0].1;
        let mut p = Complex64::new(c0, 0.0);
        let mut dp = Complex64::new(0.0, 0.0);
        let mut abs = c0.abs();
        for &(_, c) in &self.terms[1..] {
            dp = dp * z + p;
            p = p * z + c;
            abs = abs * az + c.abs();
        }
        let noise = EVAL_NOISE * self.ops * f64::EPSILON * abs;
        Eval { p, dp, noise }
    }
}

/// (z^{g−1}, z^g) for g ≥ 1.
fn powers(z: Complex64, g: u32) -> (Complex64, Complex64) {
    if g == 1 {
        (Complex64::new(1.0, 0.0), z)
    } else {
        let zg1 = z.powu(g - 1);
        (zg1, zg1 * z)
    }
}

/// Complex division by Smith's algorithm: no overflow or underflow of |b|² in between.
fn cdiv(a: Complex64, b: Complex64) -> Complex64 {
    if b.re.abs() >= b.im.abs() {
        let r = b.im / b.re;
        let den = b.re + b.im * r;
        Complex64::new((a.re + a.im * r) / den, (a.im - a.re * r) / den)
    } else {
        let r = b.re / b.im;
        let den = b.re * r + b.im;
        Complex64::new((a.re * r + a.im) / den, (a.im * r - a.re) / den)
    }
}

/// The Newton step of one root approximation, evaluated where it is stable: on p itself
/// inside the unit disc, on the reversed polynomial z^n p(1/z) outside it (no overflow of
/// z^n at high degree).
#[derive(Debug, Clone, Copy)]
struct Newton {
    /// p(z)/p′(z) (infinite when p′(z) = 0).
    ratio: Complex64,
    /// |p(z)| + its rounding error bound, divided by |p′(z)|.
    ratio_bound: f64,
    /// True when |p(z)| is within the rounding error of its evaluation.
    converged: bool,
}

/// A polynomial prepared for evaluation inside and outside the unit disc.
#[derive(Debug, Clone)]
struct Prepared {
    degree: usize,
    forward: Terms,
    reversed: Terms,
}

impl Prepared {
    /// `c` ascending, c[0] ≠ 0 and c[n] ≠ 0, all finite.
    fn new(c: &[f64]) -> Self {
        let n = c.len() - 1;
        let nonzero = || c.iter().enumerate().filter(|(_, x)| **x != 0.0);
        let forward: Vec<(u32, f64)> = nonzero().rev().map(|(k, &x)| (k as u32, x)).collect();
        let reversed: Vec<(u32, f64)> = nonzero().map(|(k, &x)| ((n - k) as u32, x)).collect();
        Self {
            degree: n,
            forward: Terms::new(forward, n),
            reversed: Terms::new(reversed, n),
        }
    }

    fn newton(&self, z: Complex64) -> Newton {
        if z.norm_sqr() <= 1.0 {
            let e = self.forward.eval(z);
            Newton {
                ratio: cdiv(e.p, e.dp),
                ratio_bound: (e.p.norm() + e.noise) / e.dp.norm(),
                converged: e.p.norm() <= e.noise,
            }
        } else {
            // p(z) = z^n r(w), w = 1/z: p/p′ = z r / (n r − w r′).
            let w = cdiv(Complex64::new(1.0, 0.0), z);
            let e = self.reversed.eval(w);
            let den = e.p * self.degree as f64 - w * e.dp;
            Newton {
                ratio: cdiv(z * e.p, den),
                ratio_bound: z.norm() * (e.p.norm() + e.noise) / den.norm(),
                converged: e.p.norm() <= e.noise,
            }
        }
    }
}

/// Checks the coefficients and splits off the exact roots at z = 0 (zero trailing
/// coefficients): returns the number of zero roots and the rest, whose constant term is
/// nonzero.
fn split_zero_roots(c: &[f64]) -> Result<(usize, &[f64])> {
    if let Some((k, x)) = c.iter().enumerate().find(|(_, x)| !x.is_finite()) {
        return Err(Error::Numerical(format!(
            "polynomial coefficient c[{k}] = {x} is not finite"
        )));
    }
    match c.last() {
        None => Err(Error::Numerical("polynomial has no coefficients".into())),
        Some(0.0) => Err(Error::Numerical(
            "leading coefficient of the polynomial is zero".into(),
        )),
        Some(_) => {
            let zeros = c.iter().take_while(|x| **x == 0.0).count();
            Ok((zeros, &c[zeros..]))
        }
    }
}

/// Starting points of the Aberth iteration: for each edge i → j of the upper convex hull of
/// the points (k, log|c_k|) (the Newton polygon), j − i points evenly spaced on the circle of
/// radius (|c_i|/|c_j|)^{1/(j−i)}, which holds about j − i roots.
fn starting_points(c: &[f64]) -> Vec<Complex64> {
    let n = c.len() - 1;
    let pts: Vec<(f64, f64)> = c
        .iter()
        .enumerate()
        .filter(|(_, x)| **x != 0.0)
        .map(|(k, x)| (k as f64, x.abs().ln()))
        .collect();
    let mut hull: Vec<(f64, f64)> = Vec::with_capacity(pts.len());
    for &q in &pts {
        while hull.len() >= 2 {
            let (o, a) = (hull[hull.len() - 2], hull[hull.len() - 1]);
            // Drop a when it lies on or below the chord o → q (not a strict upper-hull turn).
            if (a.0 - o.0) * (q.1 - o.1) - (a.1 - o.1) * (q.0 - o.0) >= 0.0 {
                hull.pop();
            } else {
                break;
            }
        }
        hull.push(q);
    }
    let mut out = Vec::with_capacity(n);
    for w in hull.windows(2) {
        let m = (w[1].0 - w[0].0) as usize;
        let radius = ((w[0].1 - w[1].1) / m as f64).exp();
        // Each circle turned by its share of the full turn so far: no two circles of equal
        // radius start on the same points.
        let turn = out.len() as f64 / n as f64;
        for t in 0..m {
            let angle = std::f64::consts::TAU * (t as f64 / m as f64 + turn) + START_ANGLE;
            out.push(crate::circle::polar(radius, angle));
        }
    }
    out
}

/// Σ_{j≠i} 1/(z_i − z_j) over the current approximations, kept as separate real and
/// imaginary parts (re, im) so that the loop vectorizes.
fn aberth_sum(i: usize, re: &[f64], im: &[f64]) -> Complex64 {
    let (x, y) = (re[i], im[i]);
    let (a, b) = reciprocal_sum(x, y, &re[..i], &im[..i]);
    let (c, d) = reciprocal_sum(x, y, &re[i + 1..], &im[i + 1..]);
    Complex64::new(a + c, b + d)
}

/// Σ_j 1/((x + iy) − (re_j + i im_j)) in four independent lanes.
fn reciprocal_sum(x: f64, y: f64, re: &[f64], im: &[f64]) -> (f64, f64) {
    const LANES: usize = 4;
    let (mut sr, mut si) = ([0.0_f64; LANES], [0.0_f64; LANES]);
    let (rc, mc) = (re.chunks_exact(LANES), im.chunks_exact(LANES));
    let (rr, mr) = (rc.remainder(), mc.remainder());
    for (a, b) in rc.zip(mc) {
        for l in 0..LANES {
            let (dx, dy) = (x - a[l], y - b[l]);
            let q = 1.0 / (dx * dx + dy * dy);
            sr[l] += dx * q;
            si[l] -= dy * q;
        }
    }
    for (a, b) in rr.iter().zip(mr) {
        let (dx, dy) = (x - a, y - b);
        let q = 1.0 / (dx * dx + dy * dy);
        sr[0] += dx * q;
        si[0] -= dy * q;
    }
    (sr.iter().sum(), si.iter().sum())
}

/// One Aberth–Ehrlich update of approximation i: whether p(z_i) is already within its
/// rounding error (the update is still applied), and the new approximation
/// z − N/(1 − N s), N = p/p′, s = Σ_{j≠i} 1/(z_i − z_j).
fn aberth_update(poly: &Prepared, i: usize, re: &[f64], im: &[f64]) -> (bool, Complex64) {
    let z = Complex64::new(re[i], im[i]);
    let nw = poly.newton(z);
    let s = aberth_sum(i, re, im);
    // As −1/s when p′ = 0.
    let step = if nw.ratio.is_finite() {
        cdiv(nw.ratio, Complex64::new(1.0, 0.0) - nw.ratio * s)
    } else {
        cdiv(Complex64::new(-1.0, 0.0), s)
    };
    let next = if step.is_finite() {
        z - step
    } else if z.norm() > 0.0 {
        // Two approximations met (the Aberth sum is infinite): move this one off.
        z * crate::circle::polar(1.0 + NUDGE, 1.0)
    } else {
        Complex64::new(NUDGE, NUDGE)
    };
    (nw.converged, next)
}

/// All complex roots of the polynomial with ascending real coefficients `c` (c[n] ≠ 0) by
/// the Aberth–Ehrlich iteration (Jacobi form), each with an inclusion radius. Roots at z = 0 (zero trailing coefficients) are exact.
/// Fails with [`Error::Numerical`] on non-finite or zero leading coefficients, and when some
/// approximations do not reach the backward-error tolerance within [`MAX_SWEEPS`] sweeps.
pub fn aberth(c: &[f64]) -> Result<Vec<RootEstimate>> {
    let (zeros, rest) = split_zero_roots(c)?;
    let mut out = vec![
        RootEstimate {
            z: Complex64::new(0.0, 0.0),
            radius: 0.0,
            error: 0.0,
        };
        zeros
    ];
    let n = rest.len() - 1;
    if n == 0 {
        return Ok(out);
    }
    let poly = Prepared::new(rest);
    let start = starting_points(rest);
    let mut re: Vec<f64> = start.iter().map(|z| z.re).collect();
    let mut im: Vec<f64> = start.iter().map(|z| z.im).collect();
    let mut done = vec![false; n];
    let mut left = n;
    let mut next: Vec<(usize, bool, Complex64)> = Vec::with_capacity(n);
    for _ in 0..MAX_SWEEPS {
        // Jacobi sweep: every active approximation against the same snapshot (at degree 2003
        // this takes a third of the sweeps of the Gauss–Seidel form).
        next.clear();
        next.extend((0..n).filter(|&i| !done[i]).map(|i| {
            let (converged, z) = aberth_update(&poly, i, &re, &im);
            (i, converged, z)
        }));
        for &(i, converged, z) in &next {
            (re[i], im[i]) = (z.re, z.im);
            if converged {
                done[i] = true;
                left -= 1;
            }
        }
        if left == 0 {
            break;
        }
    }
    if left > 0 {
        return Err(Error::Numerical(format!(
            "Aberth–Ehrlich root finder: {left} of the {n} roots of a degree-{n} polynomial \
             did not reach the rounding level of p within {MAX_SWEEPS} sweeps"
        )));
    }
    let roots: Vec<Complex64> = re
        .iter()
        .zip(&im)
        .map(|(&x, &y)| Complex64::new(x, y))
        .collect();
    out.extend(roots.iter().map(|&z| {
        let error = error_of(&poly, z);
        RootEstimate {
            z,
            radius: poly.degree as f64 * error,
            error,
        }
    }));
    Ok(out)
}

/// n · (|p| + rounding bound)/|p′| at each approximation: by a classical result
/// (a disc of radius n|p(z)/p′(z)| about any z contains a root of p), a disc that contains a
/// root of every polynomial within the rounding error of p.
fn radii_of(poly: &Prepared, roots: &[Complex64]) -> Vec<f64> {
    roots
        .iter()
        .map(|&z| poly.degree as f64 * error_of(poly, z))
        .collect()
}

/// (|p| + rounding bound)/|p′| at z (infinite where p′ vanishes).
fn error_of(poly: &Prepared, z: Complex64) -> f64 {
    let e = poly.newton(z).ratio_bound;
    if e.is_nan() { f64::INFINITY } else { e }
}

/// Inclusion radii of root approximations `roots` of the polynomial with ascending real
/// coefficients `c`: about each approximation z, a disc of radius n(|p(z)| + e)/|p′(z)|,
/// where e bounds the rounding error of the computed p(z), contains a root of p. Exact zero
/// roots (where trailing coefficients vanish) get radius 0.
pub fn inclusion_radii(c: &[f64], roots: &[Complex64]) -> Result<Vec<f64>> {
    let (zeros, rest) = split_zero_roots(c)?;
    if rest.len() == 1 {
        return Ok(vec![0.0; roots.len()]);
    }
    let poly = Prepared::new(rest);
    let mut radii = radii_of(&poly, roots);
    for (r, z) in radii.iter_mut().zip(roots) {
        if zeros > 0 && *z == Complex64::new(0.0, 0.0) {
            *r = 0.0;
        }
    }
    Ok(radii)
}

/// All complex roots of the polynomial with ascending real coefficients `c` (leading ≠ 0):
/// eigenvalues of the companion matrix by nalgebra's real Schur decomposition. O(n³) time and
/// O(n²) memory: the independent cross-check of [`aberth`].
pub fn companion(c: &[f64]) -> Result<Vec<Complex64>> {
    let (zeros, rest) = split_zero_roots(c)?;
    let mut out = vec![Complex64::new(0.0, 0.0); zeros];
    let n = rest.len() - 1;
    if n == 0 {
        return Ok(out);
    }
    let lead = rest[n];
    let mut m = DMatrix::<f64>::zeros(n, n);
    for j in 0..n {
        m[(0, j)] = -rest[n - 1 - j] / lead;
    }
    for i in 1..n {
        m[(i, i - 1)] = 1.0;
    }
    let schur = Schur::try_new(m, f64::EPSILON, 10_000 * n.max(10)).ok_or_else(|| {
        Error::Numerical(format!(
            "the eigenvalues of the degree-{n} companion matrix did not converge"
        ))
    })?;
    out.extend(
        schur
            .complex_eigenvalues()
            .iter()
            .map(|z| Complex64::new(z.re, z.im)),
    );
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_spread_over_six_decades() {
        let c = crate::poly::from_real_roots(&[1e-3, 10.0, -1e3]);
        let r = aberth(&c).unwrap();
        let mut m: Vec<f64> = r.iter().map(|e| e.z.norm()).collect();
        m.sort_by(f64::total_cmp);
        assert!((m[0] - 1e-3).abs() < 1e-17, "{m:?}");
        assert!((m[1] - 10.0).abs() < 1e-13, "{m:?}");
        assert!((m[2] - 1e3).abs() < 1e-11, "{m:?}");
        for e in &r {
            assert!(e.radius < 1e-12 * e.z.norm(), "{r:?}");
        }
    }

    /// z^20 − 1/2: one Newton-polygon edge over the whole degree, whose starting points must
    /// still be distinct; the roots are 2^{−1/20} e^{2πik/20}.
    #[test]
    fn roots_of_unity_scaled() {
        let mut c = vec![0.0; 21];
        (c[0], c[20]) = (-0.5, 1.0);
        let r = aberth(&c).unwrap();
        let modulus = 0.5f64.powf(1.0 / 20.0);
        for k in 0..20 {
            let w = crate::circle::polar(modulus, std::f64::consts::TAU * k as f64 / 20.0);
            let near = r.iter().filter(|e| (e.z - w).norm() < 1e-14).count();
            assert_eq!(near, 1, "root {w}: {r:?}");
        }
    }

    #[test]
    fn zero_roots_are_exact() {
        let r = aberth(&[0.0, 0.0, -1.0, 1.0]).unwrap();
        assert_eq!(
            r.iter().filter(|e| e.z == Complex64::new(0.0, 0.0)).count(),
            2
        );
        assert!(r.iter().any(|e| (e.z - 1.0).norm() < 1e-15));
    }

    #[test]
    fn bad_coefficients_are_errors() {
        assert!(matches!(aberth(&[1.0, 0.0]), Err(Error::Numerical(_))));
        assert!(matches!(aberth(&[f64::NAN, 1.0]), Err(Error::Numerical(_))));
        assert!(matches!(aberth(&[]), Err(Error::Numerical(_))));
    }
}
