//! A second stability test, by the argument principle (Section V: stable iff every root of
//! p(z) lies inside the unit circle), that stays exact where the Schur–Cohn test on
//! z-coefficients cannot: fast sampling and slow modes put several roots within 10⁻⁵ of
//! z = 1, where the z-coefficients have lost the digits that place them.
//!
//! For real coefficients and no root on the circle, the phase of p(e^{iθ}) grows by π for
//! every root inside the circle as θ runs from 0 to π. Near z = 1 the family is evaluated in
//! the shifted variable w = e^{iθ} − 1 = −2 sin²(θ/2) + i sin θ ([`AffineFamily`]'s shifted
//! form, formed from E = Φ − I), elsewhere from the z-coefficients with z^k = e^{ikθ}; both
//! with a running bound on the rounding error. The step in θ follows the phase
//! (Δθ ≤ 0.3·|p|/|dp/dθ|, halved until the phase turns by less than π/3), so no root is
//! stepped over. Where |p| falls to its error bound on the way, double precision cannot
//! decide and the answer says so.

use num_complex::Complex64;
use serde::Serialize;

use crate::closed_loop::{AffineFamily, SHIFTED_THETA};
use crate::poly;
use crate::stability::Verdict;

/// The answer of the argument-principle test at one wall.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Winding {
    /// Roots inside the unit circle (the phase advance over [0, π] divided by π).
    pub inside: usize,
    /// Degree of p.
    pub degree: usize,
    /// Smallest |p(e^{iθ})| met along the circle, relative to its rounding-error bound there
    /// (below [`DECIDABLE`] the count cannot be trusted: a root is within rounding of the
    /// circle).
    pub margin: f64,
}

impl Winding {
    /// True when every root lies inside and the count is decided.
    pub fn stable(&self) -> bool {
        self.decided() && self.inside == self.degree
    }

    /// True when |p| stayed clearly above its rounding error all along the circle.
    pub fn decided(&self) -> bool {
        self.margin > DECIDABLE
    }
}

/// |p| must exceed its rounding-error bound by this factor along the whole circle for the
/// count to be decided (the bound is a first-order estimate; the factor covers its slack).
pub const DECIDABLE: f64 = 16.0;

/// Most steps along the half circle: 10⁶ leaves room for roots 10⁻¹² from the circle at any
/// degree; beyond it the count is reported undecided.
const MAX_STEPS: usize = 1_000_000;

/// p(e^{iθ}), its θ-derivative and a bound on its rounding error.
fn on_circle(fam: &AffineFamily, a: f64, b: f64, theta: f64) -> (Complex64, Complex64, f64) {
    let kf = fam.k as f64;
    let zk = Complex64::from_polar(1.0, theta * kf);
    let i = Complex64::i();
    let (x, dx_dtheta, core, pk, pb) = match &fam.shifted {
        Some(sh) if theta.abs() < SHIFTED_THETA => {
            let h = (0.5 * theta).sin();
            let w = Complex64::new(-2.0 * h * h, theta.sin());
            (w, i * (w + 1.0), &sh.p0_core, &sh.pk, &sh.pb)
        }
        _ => {
            let z = Complex64::from_polar(1.0, theta);
            (z, i * z, &fam.p0_core, &fam.pk, &fam.pb)
        }
    };
    let (c, dc) = poly::eval_with_derivative(core, x);
    let (k, dk) = poly::eval_with_derivative(pk, x);
    let (bb, db) = poly::eval_with_derivative(pb, x);
    let value = zk * c + k * a + bb * b;
    let deriv = i * kf * zk * c + (zk * dc + dk * a + db * b) * dx_dtheta;
    let r = x.norm();
    let abs = |p: &[f64]| p.iter().rev().fold(0.0, |acc, &q| acc * r + q.abs());
    let n = (core.len() + pk.len()) as f64;
    let err = 4.0 * n * f64::EPSILON * (abs(core) + a.abs() * abs(pk) + b.abs() * abs(pb));
    (value, deriv, err)
}

/// Counts the roots of p(z) = P0 + a·PK + b·PB inside the unit circle by the argument
/// principle (see the module doc).
pub fn winding(fam: &AffineFamily, a: f64, b: f64) -> Winding {
    let pi = std::f64::consts::PI;
    let degree = fam.degree();
    let undecided = Winding {
        inside: 0,
        degree,
        margin: 0.0,
    };
    let (mut f, mut df, err) = on_circle(fam, a, b, 0.0);
    let mut margin = f.norm() / err.max(f64::MIN_POSITIVE);
    let mut theta = 0.0;
    let mut phase = 0.0;
    let mut steps = 0;
    while theta < pi {
        steps += 1;
        if steps > MAX_STEPS || margin <= DECIDABLE {
            return undecided;
        }
        let mut h = (0.3 * f.norm() / df.norm().max(f64::MIN_POSITIVE)).min(pi - theta);
        loop {
            let (g, dg, e) = on_circle(fam, a, b, (theta + h).min(pi));
            let turn = (g / f).arg();
            if turn.abs() < pi / 3.0 || h < 1e-300 {
                theta = (theta + h).min(pi);
                phase += turn;
                margin = margin.min(g.norm() / e.max(f64::MIN_POSITIVE));
                f = g;
                df = dg;
                break;
            }
            h *= 0.5;
        }
    }
    let count = phase / pi;
    let inside = count.round();
    if (count - inside).abs() > 0.25 || inside < 0.0 || margin <= DECIDABLE {
        return undecided;
    }
    Winding {
        inside: inside as usize,
        degree,
        margin,
    }
}

/// The Schur–Cohn recursion (see [`crate::stability::schur_stable`]) with the growth factor of
/// its rounding errors, κ = Π_j (1 + |k_j|)/(1 − |k_j|) over the reflection coefficients k_j
/// (each step b_j = a_{j+1} − k·a_{n−1−j} cancels when |k| is near 1). Returns (stable, κ);
/// κ is infinite when a reflection coefficient reaches 1 within rounding.
pub fn schur_with_condition(c: &[f64]) -> (bool, f64) {
    let (stable, kappa, _) = schur_checked(&mut c.to_vec());
    (stable, kappa)
}

/// Degrees up to this run the recursion on a stack buffer (maps call it once per point, where
/// a heap allocation would cost as much as the recursion itself).
const STACK_DEGREE: usize = 63;

/// The recursion with a stack buffer for small degrees; also whether every step's decision
/// (the side of 1 of each |k_j|) is sure by [`STEP_SAFETY`] over its rounding bound.
fn schur_checked(c: &mut [f64]) -> (bool, f64, bool) {
    if c.len() <= STACK_DEGREE + 1 {
        let mut scratch = [0.0; STACK_DEGREE + 1];
        schur_recursion(c, &mut scratch[..c.len()])
    } else {
        let mut scratch = vec![0.0; c.len()];
        schur_recursion(c, &mut scratch)
    }
}

/// A step's decision 1 − |k_j| > 0 is sure when the gap exceeds this many times its
/// first-order rounding bound κ_j·n·ε (κ_j the growth factor of the steps before: the
/// reduced coefficients, and so k_j, carry relative errors of about κ_j·n·ε).
const STEP_SAFETY: f64 = 64.0;

/// The recursion of [`schur_with_condition`] on two buffers of p's length (both overwritten):
/// (stable, κ, every decision sure).
fn schur_recursion<'a>(mut a: &'a mut [f64], mut b: &'a mut [f64]) -> (bool, f64, bool) {
    let mut n = a.len() - 1;
    let nf = n as f64;
    let mut kappa = 1.0_f64;
    let mut sure_all = true;
    while n > 0 {
        let an = a[n];
        if !an.is_finite() || an == 0.0 {
            return (false, f64::INFINITY, false);
        }
        let k = a[0] / an;
        if k.is_nan() {
            return (false, f64::INFINITY, false);
        }
        let gap = 1.0 - k.abs();
        let bound = STEP_SAFETY * f64::EPSILON * kappa * nf;
        if gap <= 0.0 {
            // unstable, unless the coefficient is 1 only by rounding
            let sure = -gap > bound;
            return (
                false,
                if sure { kappa } else { f64::INFINITY },
                sure && sure_all,
            );
        }
        sure_all &= gap > bound;
        kappa *= (1.0 + k.abs()) / gap;
        for j in 0..n {
            b[j] = a[j + 1] - k * a[n - 1 - j];
        }
        std::mem::swap(&mut a, &mut b);
        n -= 1;
    }
    (true, kappa, sure_all)
}

/// The verdict at one wall (Section V: stable iff every root of p = P0 + a·PK + b·PB lies
/// strictly inside the unit circle): the Schur–Cohn test where every step's decision is sure
/// over its rounding bound ([`STEP_SAFETY`]), the argument principle ([`winding`]) where it is not (walls within
/// rounding of the boundary, clusters of roots near z = 1); `Marginal` where the argument
/// principle cannot decide either (a root within rounding of the circle). `coeffs` is a
/// scratch buffer of length degree + 1 (overwritten).
pub fn verdict_at(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> Verdict {
    fam.coefficients_into(a, b, coeffs);
    let (stable, _, sure) = schur_checked(coeffs);
    if sure {
        return if stable {
            Verdict::Stable
        } else {
            Verdict::Unstable
        };
    }
    let w = winding(fam, a, b);
    match (w.decided(), w.stable()) {
        (false, _) => Verdict::Marginal,
        (true, true) => Verdict::Stable,
        (true, false) => Verdict::Unstable,
    }
}

/// True iff [`verdict_at`] says stable (a wall within rounding of the boundary is not).
pub fn stable_at(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> bool {
    verdict_at(fam, a, b, coeffs) == Verdict::Stable
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{PlantParams, PolyFamily};

    #[test]
    fn counts_agree_with_the_schur_test_on_the_paper_loop() {
        let fam = PolyFamily::new(PlantParams::new(1e-3, 0.015).unwrap(), 2).unwrap();
        for &(a, b, stable) in &[(0.03, 0.3, true), (0.2, 0.3, false), (-0.01, 0.2, false)] {
            let w = winding(&fam, a, b);
            assert!(w.decided(), "{a} {b}: {w:?}");
            assert_eq!(w.stable(), stable, "{a} {b}: {w:?}");
            let c = fam.coefficients(a, b);
            assert_eq!(crate::stability::schur_stable(&c), stable);
        }
    }
}
