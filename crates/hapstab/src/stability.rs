//! The stability test of Section V: stable iff every root of p(z) lies strictly inside the
//! unit circle.
//!
//! Two independent methods: the Schur–Cohn recursion (an algebraic test, no roots, O(n²)),
//! used as the fast path and for the verdict, and the roots themselves (Aberth–Ehrlich
//! iteration of [`crate::polyroots`], with error bounds) for the spectral radius. A full
//! [`Analysis`] reconciles the two so that its verdict never contradicts its radius.

use num_complex::Complex64;
use serde::Serialize;

use crate::closed_loop::{AffineFamily, ClosedLoop, PolyFamily};
use crate::error::{Error, Result};
use crate::params::Normalized;
use crate::polyroots::{RootEstimate, aberth, companion};

/// Half-width of the marginal band in spectral radius: a point is `Marginal` when the
/// spectral radius lies in [1 − MARGINAL_BAND, 1 + MARGINAL_BAND), so the band is 1e-10 wide.
pub const MARGINAL_BAND: f64 = 5e-11;

/// Stability verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// All roots strictly inside the circle of radius 1 − [`MARGINAL_BAND`].
    Stable,
    /// Some root on the unit circle within [`MARGINAL_BAND`], or the Schur–Cohn test and the
    /// spectral radius on different sides with the radius within its error of that band,
    /// where double precision cannot tell the side (see [`reconcile`]).
    Marginal,
    /// Some root outside the circle of radius 1 + [`MARGINAL_BAND`].
    Unstable,
}

impl Verdict {
    /// The lowercase name used in JSON.
    pub fn as_str(&self) -> &'static str {
        match self {
            Verdict::Stable => "stable",
            Verdict::Marginal => "marginal",
            Verdict::Unstable => "unstable",
        }
    }
}

const STACK: usize = 64;

/// Schur–Cohn test on ascending coefficients `c` (degree n = c.len() − 1, c[n] ≠ 0): true iff
/// every root lies strictly inside the unit circle. Each step divides out one reflection
/// coefficient k = c0/cn (|k| < 1 is necessary) and keeps (cn·c(z) − c0·c*(z))/z.
pub fn schur_stable(c: &[f64]) -> bool {
    schur_stable_scaled(c, 1.0)
}

/// Schur–Cohn test of c(r·z): true iff every root of c lies strictly inside |z| < r.
pub fn schur_stable_scaled(c: &[f64], r: f64) -> bool {
    let n = c.len();
    if n <= STACK {
        let mut a = [0.0_f64; STACK];
        let mut b = [0.0_f64; STACK];
        schur_core(c, r, &mut a[..n], &mut b[..n])
    } else {
        let mut a = vec![0.0; n];
        let mut b = vec![0.0; n];
        schur_core(c, r, &mut a, &mut b)
    }
}

fn schur_core(c: &[f64], r: f64, a: &mut [f64], b: &mut [f64]) -> bool {
    let mut scale = 1.0;
    for (ai, ci) in a.iter_mut().zip(c) {
        *ai = ci * scale;
        scale *= r;
    }
    let mut n = c.len() - 1;
    let (mut a, mut b) = (a, b);
    while n > 0 {
        let an = a[n];
        if !an.is_finite() || an == 0.0 {
            return false;
        }
        let k = a[0] / an;
        if k.is_nan() || k.abs() >= 1.0 {
            return false;
        }
        for j in 0..n {
            b[j] = a[j + 1] - k * a[n - 1 - j];
        }
        std::mem::swap(&mut a, &mut b);
        n -= 1;
    }
    true
}

/// Verdict from the algebraic test alone, with the marginal band of [`MARGINAL_BAND`].
pub fn classify(c: &[f64]) -> Verdict {
    if schur_stable_scaled(c, 1.0 - MARGINAL_BAND) {
        Verdict::Stable
    } else if schur_stable_scaled(c, 1.0 + MARGINAL_BAND) {
        Verdict::Marginal
    } else {
        Verdict::Unstable
    }
}

/// Spectral radius by bisection on the Schur–Cohn test of c(r z), with no root finding:
/// the smallest r for which every root lies inside |z| < r, to about 1e-15 relative.
pub fn spectral_radius_schur(c: &[f64]) -> f64 {
    let n = c.len() - 1;
    let lead = c[n].abs();
    let mut hi = 1.0 + c[..n].iter().map(|x| (x / lead).abs()).fold(0.0, f64::max);
    let mut lo = 0.0;
    while hi - lo > 1e-15 * hi {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if schur_stable_scaled(c, mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// Horner evaluation of p and p' at z for ascending real coefficients.
fn horner(c: &[f64], z: Complex64) -> (Complex64, Complex64) {
    let mut p = Complex64::new(0.0, 0.0);
    let mut dp = Complex64::new(0.0, 0.0);
    for &ci in c.iter().rev() {
        dp = dp * z + p;
        p = p * z + ci;
    }
    (p, dp)
}

/// Orders roots largest modulus first, then by decreasing imaginary part.
fn sort_roots(r: &mut [Complex64]) {
    r.sort_by(|a, b| b.norm().total_cmp(&a.norm()).then(b.im.total_cmp(&a.im)));
}

/// All complex roots of the polynomial with ascending real coefficients `c` (leading ≠ 0),
/// largest modulus first, by the Aberth–Ehrlich iteration ([`crate::polyroots::aberth`]):
/// O(n²) per sweep, about 70 ms at degree 2003 (d = 2000).
pub fn roots(c: &[f64]) -> Result<Vec<Complex64>> {
    let mut r: Vec<Complex64> = aberth(c)?.iter().map(|e| e.z).collect();
    sort_roots(&mut r);
    Ok(r)
}

/// As [`roots`] by the independent slow path: eigenvalues of the companion matrix
/// ([`crate::polyroots::companion`], O(n³)), each polished by Newton steps that are kept only
/// while they reduce |p|. The cross-check of [`roots`] in the tests.
pub fn roots_companion(c: &[f64]) -> Result<Vec<Complex64>> {
    let mut r = companion(c)?;
    for z in r.iter_mut() {
        *z = polish(c, *z);
    }
    sort_roots(&mut r);
    Ok(r)
}

fn polish(c: &[f64], mut z: Complex64) -> Complex64 {
    let (mut p, _) = horner(c, z);
    for _ in 0..4 {
        let (_, dp) = horner(c, z);
        if dp.norm() == 0.0 {
            break;
        }
        let cand = z - p / dp;
        let (pc, _) = horner(c, cand);
        if pc.norm() < p.norm() {
            z = cand;
            p = pc;
        } else {
            break;
        }
    }
    z
}

/// The full answer of the stability test of Section V for one parameter set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Analysis {
    /// Stable / marginal / unstable: the Schur–Cohn test with the marginal band, reconciled
    /// with the spectral radius (see [`Analysis::of_poly`]).
    pub verdict: Verdict,
    /// Largest root modulus of p(z) (from the roots).
    pub spectral_radius: f64,
    /// Estimated error of `spectral_radius`: the first-order (Newton) error of the roots with
    /// the rounding of p included ([`crate::polyroots::RootEstimate::error`]); the rigorous
    /// inclusion discs are at most the degree times wider.
    pub spectral_radius_error: f64,
    /// Roots of p(z), largest modulus first.
    pub roots: Vec<Complex64>,
}

/// The verdict that a spectral radius ρ gives with the marginal band of [`MARGINAL_BAND`].
pub fn verdict_of_radius(rho: f64) -> Verdict {
    if rho < 1.0 - MARGINAL_BAND {
        Verdict::Stable
    } else if rho < 1.0 + MARGINAL_BAND {
        Verdict::Marginal
    } else {
        Verdict::Unstable
    }
}

/// Reconciles the Schur–Cohn verdict with the spectral radius ρ ± `error` of the roots:
/// their common answer when they agree; `Marginal` when they are consistent but the radius
/// lies in the marginal band (a root inside the circle by less than [`MARGINAL_BAND`], which
/// the algebraic test still calls stable) or within its error of the other side (double
/// precision cannot decide); an [`Error::Numerical`] naming both when they differ by more
/// than the rounding allows.
pub fn reconcile(algebraic: Verdict, rho: f64, error: f64) -> Result<Verdict> {
    if algebraic == verdict_of_radius(rho) {
        return Ok(algebraic);
    }
    let consistent = match algebraic {
        Verdict::Stable => rho - error < 1.0,
        Verdict::Unstable => rho + error > 1.0,
        Verdict::Marginal => {
            rho - error < 1.0 + MARGINAL_BAND && rho + error >= 1.0 - MARGINAL_BAND
        }
    };
    if consistent {
        Ok(Verdict::Marginal)
    } else {
        Err(Error::Numerical(format!(
            "the Schur–Cohn test says {} but the roots give spectral radius {rho} ± {error:e}",
            algebraic.as_str()
        )))
    }
}

impl Analysis {
    /// Runs the point test and the root finder on the closed loop of `params` (the paper's
    /// loop through [`Analysis::of_family`]).
    pub fn new(params: Normalized) -> Result<Self> {
        let params = params.validated()?;
        let fam = PolyFamily::new(params.plant(), params.d)?;
        Self::of_family(&fam, params.alpha, params.beta)
    }

    /// The full answer for the wall (a, b) of a loop's family: the verdict of
    /// [`crate::argument::verdict_at`] (Schur–Cohn where well-conditioned, the argument
    /// principle where not), the roots by Aberth–Ehrlich with those near z = 1 polished in the
    /// shifted variable (where z-coefficients have lost their digits), and the two reconciled
    /// ([`reconcile`]) so that the verdict never contradicts the radius reported with it.
    pub fn of_family(fam: &AffineFamily, a: f64, b: f64) -> Result<Self> {
        let mut c = fam.coefficients(a, b);
        let mut estimates = aberth(&c)?;
        polish_near_one(fam, a, b, &mut estimates);
        let algebraic = crate::argument::verdict_at(fam, a, b, &mut c);
        Self::from_estimates(algebraic, &estimates)
    }

    /// As [`Analysis::of_family`] for bare ascending coefficients (no shifted form): the
    /// Schur–Cohn verdict ([`classify`]), the roots with their inclusion radii
    /// ([`crate::polyroots::aberth`]), and the two reconciled ([`reconcile`]).
    pub fn of_poly(c: &[f64]) -> Result<Self> {
        Self::from_estimates(classify(c), &aberth(c)?)
    }

    fn from_estimates(algebraic: Verdict, estimates: &[RootEstimate]) -> Result<Self> {
        let top = estimates
            .iter()
            .max_by(|a, b| a.z.norm().total_cmp(&b.z.norm()));
        let spectral_radius = top.map_or(0.0, |e| e.z.norm());
        // To first order every root lies within its error of its approximation, so ρ lies
        // between the largest |z| − e and the largest |z| + e.
        let upper = estimates
            .iter()
            .map(|e| e.z.norm() + e.error)
            .fold(0.0, f64::max);
        let spectral_radius_error = (upper - spectral_radius).max(top.map_or(0.0, |e| e.error));
        let verdict = reconcile(algebraic, spectral_radius, spectral_radius_error)?;
        let mut roots: Vec<Complex64> = estimates.iter().map(|e| e.z).collect();
        sort_roots(&mut roots);
        Ok(Self {
            verdict,
            spectral_radius,
            spectral_radius_error,
            roots,
        })
    }

    /// True iff the verdict is `Stable`.
    pub fn stable(&self) -> bool {
        self.verdict == Verdict::Stable
    }
}

/// Roots closer to z = 1 than this are polished in the shifted variable w = z − 1.
const POLISH_RADIUS: f64 = 0.5;

/// Refines the roots near z = 1 by Aberth–Ehrlich steps in the shifted variable
/// (p(1 + w) from [`AffineFamily::parts_shifted_with_derivative`], free of the cancellation
/// of z-coefficients), all other roots held fixed; each root's error becomes its last
/// correction or the rounding of p at it over |p′|, whichever is larger.
fn polish_near_one(fam: &AffineFamily, a: f64, b: f64, est: &mut [RootEstimate]) {
    let Some(sh) = fam.shifted.as_ref() else {
        return;
    };
    let near: Vec<usize> = (0..est.len())
        .filter(|&i| (est[i].z - 1.0).norm() < POLISH_RADIUS)
        .collect();
    if near.is_empty() {
        return;
    }
    let mut w: Vec<Complex64> = est.iter().map(|e| e.z - 1.0).collect();
    let mut err = vec![0.0; est.len()];
    for _ in 0..POLISH_SWEEPS {
        let mut biggest = 0.0_f64;
        for &i in &near {
            let [(p0, d0), (pk, dk), (pb, db)] = fam.parts_shifted_with_derivative(w[i]);
            let (p, dp) = (p0 + pk * a + pb * b, d0 + dk * a + db * b);
            if dp.norm() == 0.0 {
                continue;
            }
            let n = p / dp;
            let sum: Complex64 = (0..w.len())
                .filter(|&j| j != i)
                .map(|j| (w[i] - w[j]).inv())
                .sum();
            let step = n / (1.0 - n * sum);
            if !step.re.is_finite() || !step.im.is_finite() {
                continue;
            }
            w[i] -= step;
            let r = w[i].norm();
            let abs = |c: &[f64]| c.iter().rev().fold(0.0, |acc, &q| acc * r + q.abs());
            let rounding = 4.0
                * (sh.p0_core.len() + sh.pk.len()) as f64
                * f64::EPSILON
                * (abs(&sh.p0_core) * (1.0 + r).powi(fam.k as i32)
                    + a.abs() * abs(&sh.pk)
                    + b.abs() * abs(&sh.pb));
            err[i] = step.norm().max(rounding / dp.norm());
            biggest = biggest.max(step.norm() / w[i].norm().max(f64::MIN_POSITIVE));
        }
        if biggest < 4.0 * f64::EPSILON {
            break;
        }
    }
    for &i in &near {
        est[i].z = w[i] + 1.0;
        est[i].error = err[i];
    }
}

/// Polishing sweeps near z = 1: Aberth steps converge cubically from the z-domain roots;
/// clusters converge more slowly, and their error estimate says so.
const POLISH_SWEEPS: usize = 12;

/// Fast stability check of one normalized parameter set by the Schur–Cohn test (strict:
/// every root inside |z| < 1).
pub fn is_stable(params: &Normalized) -> Result<bool> {
    let cl = ClosedLoop::new(*params)?;
    Ok(schur_stable(&cl.poly))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn poly_from_roots(rs: &[f64]) -> Vec<f64> {
        let mut c = vec![1.0];
        for &r in rs {
            let mut n = vec![0.0; c.len() + 1];
            for (i, ci) in c.iter().enumerate() {
                n[i + 1] += ci;
                n[i] -= r * ci;
            }
            c = n;
        }
        c
    }

    #[test]
    fn schur_on_known_roots() {
        assert!(schur_stable(&poly_from_roots(&[0.5, -0.9, 0.99])));
        assert!(!schur_stable(&poly_from_roots(&[0.5, -1.01, 0.2])));
        assert!(!schur_stable(&poly_from_roots(&[0.5, 1.0, 0.2])));
        assert_eq!(
            classify(&poly_from_roots(&[0.5, 1.0 + 1e-8])),
            Verdict::Unstable
        );
        assert_eq!(
            classify(&poly_from_roots(&[0.5, 1.0 - 1e-8])),
            Verdict::Stable
        );
        assert_eq!(classify(&poly_from_roots(&[0.5, 1.0])), Verdict::Marginal);
        let rho = spectral_radius_schur(&poly_from_roots(&[0.3, -0.7, 0.25]));
        assert!((rho - 0.7).abs() < 1e-14, "{rho}");
    }

    #[test]
    fn roots_of_known_polynomial() {
        let r = roots(&poly_from_roots(&[0.5, -0.25, 0.75])).unwrap();
        let mut re: Vec<f64> = r.iter().map(|z| z.re).collect();
        re.sort_by(f64::total_cmp);
        assert!((re[0] + 0.25).abs() < 1e-15 && (re[2] - 0.75).abs() < 1e-15);
    }
}
