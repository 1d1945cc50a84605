//! The one stability verdict of the crate (Section V: stable iff every root of p(z) lies
//! strictly inside the unit circle), used by `check`, maps in both modes, intervals,
//! regions, margins, the explorer and Python alike.
//!
//! A wall is
//! - **stable** when every root lies inside |z| < 1 − [`MARGINAL_BAND`],
//! - **unstable** when some root lies outside |z| > 1 + [`MARGINAL_BAND`],
//! - **marginal** otherwise: a root within the band of the circle (an undamped mode, a free
//!   mass's root at z = 1), or one that double precision cannot place on either side.
//!
//! The decision, step by step ([`decide`]):
//! 1. **Fast path**: one Schur–Cohn recursion ([`crate::schur_cohn`]) on the z-coefficients,
//!    accepted when every step's decision withstands rounding *and* the scaling of the
//!    coefficients to the band's radii 1 ∓ band (a relative perturbation of at most
//!    n·band): then the roots are inside 1 − band, or one is outside 1 + band.
//! 2. **The band's circles**: the recursion on c((1 − band)·z) and on c((1 + band)·z), each
//!    accepted when sure against rounding alone.
//! 3. **Argument principle** ([`crate::argument`]) on the circle that is still open, with
//!    the family's shifted form near z = 1 (exact there: its value at z = 1 comes from the
//!    plant's static stiffness, so a wall on the z = 1 line has its root at z = 1 exactly).
//! 4. Where even that cannot decide (a root within rounding of a band circle), the wall is
//!    **marginal**, and the answer says that it is undecided.

use serde::Serialize;

use crate::argument::{Coefficients, OnCircle, Wall, winding};
use crate::closed_loop::AffineFamily;
use crate::schur_cohn::{schur_cohn, schur_cohn_in_place};

/// Half-width of the marginal band in spectral radius: a wall is marginal when its spectral
/// radius lies in [1 − MARGINAL_BAND, 1 + MARGINAL_BAND]. 5e-11 is far above the rounding of
/// a well-conditioned root (1e-15) and far below any stability margin an engineer designs
/// with.
pub const MARGINAL_BAND: f64 = 5e-11;

/// Stability verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// All roots strictly inside the circle of radius 1 − [`MARGINAL_BAND`].
    Stable,
    /// Some root within [`MARGINAL_BAND`] of the unit circle and none beyond it, or a root
    /// that double precision cannot place (see [`Basis::Undecided`]).
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

/// What decided a verdict.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Basis {
    /// The Schur–Cohn recursion, every step sure over its rounding bound.
    SchurCohn,
    /// The argument principle on a band circle (the recursion was not sure).
    ArgumentPrinciple,
    /// Neither could decide: a root lies within rounding of a band circle, so the wall is
    /// reported marginal.
    Undecided,
}

/// A verdict with what decided it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Decision {
    /// Stable, marginal or unstable.
    pub verdict: Verdict,
    /// The method that decided it.
    pub basis: Basis,
}

/// The verdict that a spectral radius ρ gives with the marginal band of [`MARGINAL_BAND`].
pub fn verdict_of_radius(rho: f64) -> Verdict {
    if rho < 1.0 - MARGINAL_BAND {
        Verdict::Stable
    } else if rho <= 1.0 + MARGINAL_BAND {
        Verdict::Marginal
    } else {
        Verdict::Unstable
    }
}

/// The verdict of the wall (a, b) of a loop's family (see the module doc). `coeffs` is a
/// scratch buffer of length degree + 1 (overwritten: the recursion runs in it, so it does not
/// hold p's coefficients afterwards).
pub fn decide(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> Decision {
    let fast = fast_path(fam, a, b, coeffs);
    if fast.sure {
        return sure_verdict(fast.stable);
    }
    // the recursion overwrote the coefficients: the band's circles need them again
    fam.coefficients_into(a, b, coeffs);
    decide_near_circle(coeffs, &Wall { fam, a, b }, fast.stable)
}

/// Steps 1–2 of the module doc alone: [`decide`]'s verdict where a Schur–Cohn recursion
/// (on the z-coefficients, then on the band's circles) is sure, None where [`decide`] would
/// need the argument principle. For a caller free to pick among several walls to test, the
/// ones decided without it (a hundred times cheaper).
pub fn decide_fast(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> Option<Verdict> {
    let fast = fast_path(fam, a, b, coeffs);
    if fast.sure {
        return Some(sure_verdict(fast.stable).verdict);
    }
    fam.coefficients_into(a, b, coeffs);
    let sure_at = |r: f64| {
        let s = schur_cohn(coeffs, r, 0.0);
        s.sure.then_some(s.stable)
    };
    match (sure_at(1.0 - MARGINAL_BAND), sure_at(1.0 + MARGINAL_BAND)) {
        (Some(true), _) => Some(Verdict::Stable),
        (_, Some(false)) => Some(Verdict::Unstable),
        (Some(false), Some(true)) => Some(Verdict::Marginal),
        _ => None,
    }
}

/// The fast path's recursion on the wall's z-coefficients (written into `coeffs`).
fn fast_path(
    fam: &AffineFamily,
    a: f64,
    b: f64,
    coeffs: &mut [f64],
) -> crate::schur_cohn::SchurCohn {
    fam.coefficients_into(a, b, coeffs);
    let n = coeffs.len().saturating_sub(1) as f64;
    schur_cohn_in_place(coeffs, n * MARGINAL_BAND)
}

/// True iff [`decide`] says stable (a marginal wall is not).
pub fn stable(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> bool {
    decide(fam, a, b, coeffs).verdict == Verdict::Stable
}

/// The verdict of a bare polynomial (ascending coefficients, leading ≠ 0) by the same steps
/// as [`decide`], with the argument principle on its z-coefficients.
pub fn decide_coefficients(c: &[f64]) -> Decision {
    let n = c.len().saturating_sub(1) as f64;
    let fast = schur_cohn(c, 1.0, n * MARGINAL_BAND);
    if fast.sure {
        return sure_verdict(fast.stable);
    }
    decide_near_circle(c, &Coefficients(c), fast.stable)
}

/// Whether every root of the wall's p(z) lies strictly inside the unit circle, without the
/// marginal band: the test that classifies a whole cell of the D-decomposition (a gap between
/// crossings on a line, a face of the region), where the number of roots inside is constant
/// and the band only matters for walls reported one by one. The Schur–Cohn recursion where
/// it is sure, else the argument principle; None when neither can decide (a root within
/// rounding of the circle).
pub fn inside_unit_circle(fam: &AffineFamily, a: f64, b: f64, coeffs: &mut [f64]) -> Option<bool> {
    fam.coefficients_into(a, b, coeffs);
    inside_all(coeffs, &Wall { fam, a, b }, 1.0).map(|(inside, _)| inside)
}

/// Step 1 of the module doc where it is sure: the recursion's verdict.
fn sure_verdict(stable: bool) -> Decision {
    schur(if stable {
        Verdict::Stable
    } else {
        Verdict::Unstable
    })
}

/// Steps 2–4 of the module doc on coefficients `c` of the polynomial `p`, where the
/// recursion at r = 1 was not sure over the band (it leaned to `stable`).
fn decide_near_circle(c: &[f64], p: &impl OnCircle, stable: bool) -> Decision {
    // Not sure over the band: the circles 1 ∓ band decide, the one the recursion leaned to
    // first (an unstable-looking wall is mostly settled by the outer circle alone).
    let (inner, outer) = (1.0 - MARGINAL_BAND, 1.0 + MARGINAL_BAND);
    let decision = |verdict: Verdict, basis: Basis| Decision { verdict, basis };
    if stable {
        match inside_all(c, p, inner) {
            Some((true, basis)) => return decision(Verdict::Stable, basis),
            Some((false, _)) => {}
            None => return undecided(),
        }
        return match inside_all(c, p, outer) {
            Some((true, basis)) => decision(Verdict::Marginal, basis),
            Some((false, basis)) => decision(Verdict::Unstable, basis),
            None => undecided(),
        };
    }
    match inside_all(c, p, outer) {
        Some((false, basis)) => return decision(Verdict::Unstable, basis),
        Some((true, _)) => {}
        None => return undecided(),
    }
    match inside_all(c, p, inner) {
        Some((true, basis)) => decision(Verdict::Stable, basis),
        Some((false, basis)) => decision(Verdict::Marginal, basis),
        None => undecided(),
    }
}

fn inside_all(c: &[f64], p: &impl OnCircle, r: f64) -> Option<(bool, Basis)> {
    let s = schur_cohn(c, r, 0.0);
    if s.sure {
        return Some((s.stable, Basis::SchurCohn));
    }
    let w = winding(p, r);
    w.decided()
        .then_some((w.inside == w.degree, Basis::ArgumentPrinciple))
}

fn schur(verdict: Verdict) -> Decision {
    Decision {
        verdict,
        basis: Basis::SchurCohn,
    }
}

fn undecided() -> Decision {
    Decision {
        verdict: Verdict::Marginal,
        basis: Basis::Undecided,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_band_decides_roots_near_the_circle() {
        let v = |rs: &[f64]| decide_coefficients(&crate::poly::from_real_roots(rs)).verdict;
        assert_eq!(v(&[0.5, -0.9, 0.99]), Verdict::Stable);
        assert_eq!(v(&[0.5, -1.01, 0.2]), Verdict::Unstable);
        assert_eq!(v(&[0.5, 1.0]), Verdict::Marginal);
        assert_eq!(v(&[0.5, 1.0 - 1e-12]), Verdict::Marginal);
        assert_eq!(v(&[0.5, 1.0 + 1e-12]), Verdict::Marginal);
        assert_eq!(v(&[0.5, 1.0 - 1e-8]), Verdict::Stable);
        assert_eq!(v(&[0.5, 1.0 + 1e-8]), Verdict::Unstable);
        assert_eq!(v(&[0.5, -1.0 + 1e-9, 1.0 - 1e-12]), Verdict::Marginal);
        assert_eq!(v(&[0.5, -1.0 - 1e-9, 1.0 - 1e-12]), Verdict::Unstable);
    }
}
