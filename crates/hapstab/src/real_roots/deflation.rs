//! Brackets of every positive root at once, where Descartes' bound is met: the coefficients'
//! sign variations V bound the number of positive roots from above (Descartes' rule of
//! signs), so V sign changes of p found between approximate roots prove that there are
//! exactly V, one between each pair of consecutive cuts. The approximate roots come from
//! Laguerre's method with forward deflation, smallest first (Press et al., *Numerical
//! Recipes*, 3rd ed., §9.5: Laguerre's step converges to a neighbouring root from any start
//! on a polynomial whose roots are all real, and forward deflation is stable when the roots
//! are removed in order of increasing magnitude; Wilkinson, *Rounding Errors in Algebraic
//! Processes*, 1963, ch. 2). Only the cuts come from the deflated polynomials; the roots
//! themselves are then refined on p ([`super::roots_between_ends`]).
//!
//! A polynomial with fewer positive roots than V has complex pairs of positive real part;
//! Laguerre's iteration finds them in complex arithmetic, and a pair whose inclusion disc
//! (a disc about the approximation that holds a root of p, [`crate::polyroots::inclusion_radii`])
//! stays off the real axis is two non-real roots of p. With k sign changes found and C such
//! roots in disjoint discs, p has k positive roots (one per cut interval) once k + 2 + C
//! exceeds the degree: each interval holds an odd number, so a second root in one makes
//! k + 2. Where neither count is met, the derivative cascade takes over.

use num_complex::Complex64;

use super::{laguerre_step, sure_sign};

/// Laguerre steps per approximate root at most.
const MAX_STEPS: usize = 40;

/// Relative step at which an approximate root is taken (the cuts need only separate the
/// roots; the refinement on p gives their digits).
const APPROX_DONE: f64 = 1e-8;

/// Laguerre's discriminant (n − 1)(n·H − G²)·v² below this fraction of n²·d² is negative
/// beyond rounding: a complex pair lies nearby, and the count will not be met.
const COMPLEX_DISC: f64 = 1e-9;

/// Cuts lo = x_0 < x_1 < … < x_k = hi with p's sign sure at each and changing across every
/// interval, where k equals V, the sign variations of p's coefficients, or k + 2 plus the
/// certified non-real roots exceeds p's degree (module doc): each interval holds exactly one
/// root of p, and there are no other positive roots in (lo, hi); where V = 0, just lo and hi
/// (no root). None where neither count is met (the cascade decides then). `p` has nonzero
/// constant and leading coefficients and every positive root inside (lo, hi).
pub(super) fn descartes_cuts(p: &[f64], (lo, hi): (f64, f64)) -> Option<Vec<f64>> {
    let v = sign_variations_of(p);
    if v == 0 {
        // no positive root: one interval without a sign change
        return Some(vec![lo, hi]);
    }
    let mut roots = approximate_roots(p, v, (lo, hi))?;
    roots.sort_by(f64::total_cmp);
    let mut cuts = Vec::with_capacity(roots.len() + 1);
    cuts.push(lo);
    for w in roots.windows(2) {
        let m = (w[0] * w[1]).sqrt();
        (m > w[0] && m < w[1]).then_some(())?;
        cuts.push(m);
    }
    cuts.push(hi);
    let mut last = sure_sign(p, lo)?;
    for &x in &cuts[1..] {
        let s = sure_sign(p, x)?;
        (s != last).then_some(())?;
        last = s;
    }
    Some(cuts)
}

/// The sign variations of the coefficient sequence, zeros skipped: Descartes' bound on the
/// number of positive roots.
fn sign_variations_of(p: &[f64]) -> usize {
    let mut signs = p.iter().filter(|&&c| c != 0.0).map(|&c| c > 0.0);
    let Some(mut last) = signs.next() else {
        return 0;
    };
    let mut count = 0;
    for s in signs {
        count += usize::from(s != last);
        last = s;
    }
    count
}

/// The approximate positive roots of p inside (lo, hi), from Laguerre's method started at lo
/// on p deflated by each root found, smallest first (roots outside (lo, hi), e.g. negative
/// ones, deflated and passed over), until `count` (Descartes' bound) are found or the
/// certified non-real pairs leave no room for more (module doc); None where an iteration does
/// not settle or neither count is met.
fn approximate_roots(p: &[f64], count: usize, (lo, hi): (f64, f64)) -> Option<Vec<f64>> {
    let n = p.len() - 1;
    let mut q = p.to_vec();
    let mut found: Vec<f64> = Vec::with_capacity(count);
    let mut discs: Vec<(Complex64, f64)> = Vec::new();
    let mut x = lo;
    // the pairs' count settles it only where every root but one is positive or non-real: with
    // one certified pair at least, n − (count − 2) − 2 ≤ 1, so complex pairs are followed
    // only where count ≥ n − 1; roots deflated but neither counted nor certified and whether a
    // pair was met: with two such, the pairs' count cannot settle it, and after a pair
    // Descartes' rarely will
    let pairs_allowed = count + 1 >= n;
    let (mut spent, mut paired) = (0, false);
    while found.len() < count && q.len() > 1 {
        match next_root(&q, x, pairs_allowed)? {
            Root::Real(r) => {
                deflate(&mut q, r);
                if r > lo && r < hi {
                    found.push(r);
                    x = r;
                } else {
                    spent += 1;
                }
            }
            Root::Pair(z) => {
                deflate_pair(&mut q, z);
                paired = true;
                match certified_pair(p, z, &discs) {
                    Some(disc) => discs.push(disc),
                    None => spent += 2,
                }
            }
        }
        if paired && spent >= 2 {
            return None;
        }
    }
    let settled = found.len() == count
        || ((count - found.len()).is_multiple_of(2) && found.len() + 2 + 2 * discs.len() > n);
    settled.then_some(found)
}

/// A root of a deflated polynomial.
enum Root {
    Real(f64),
    /// One of a complex pair (its conjugate is the other).
    Pair(Complex64),
}

/// The root that Laguerre's iteration reaches from x: in real arithmetic while the
/// discriminant allows, else (where `pairs` allows) in complex arithmetic (a pair, or a real
/// root reached from off the axis).
fn next_root(q: &[f64], x: f64, pairs: bool) -> Option<Root> {
    match laguerre_root(q, x) {
        Ok(r) => Some(Root::Real(r?)),
        Err(_) if !pairs => None,
        Err(at) => {
            let z = complex_laguerre(q, Complex64::new(at, 0.0))?;
            Some(if z.im.abs() <= APPROX_DONE * z.norm() {
                Root::Real(z.re)
            } else {
                Root::Pair(z)
            })
        }
    }
}

/// The disc about z (polished by Newton's steps on p) that holds a root of p, where it stays
/// off the real axis (a non-real root, whose conjugate is another) and off the discs already
/// certified; None else.
fn certified_pair(p: &[f64], z: Complex64, discs: &[(Complex64, f64)]) -> Option<(Complex64, f64)> {
    let z = polished(p, z);
    let radius = 2.0 * crate::polyroots::inclusion_radii(p, &[z]).ok()?.first()?;
    let apart = |&(c, r): &(Complex64, f64)| {
        (c - z).norm() > r + radius && (c.conj() - z).norm() > r + radius
    };
    (radius < z.im.abs() && discs.iter().all(apart)).then_some((z, radius))
}

/// Newton's steps on p from z (a root of a deflated polynomial, carrying the deflation's
/// rounding), a few at most.
fn polished(p: &[f64], mut z: Complex64) -> Complex64 {
    for _ in 0..POLISH_STEPS {
        let (v, d, _) = horner_complex(p, z);
        let step = v / d;
        if !(step.re.is_finite() && step.im.is_finite()) {
            break;
        }
        z -= step;
        if step.norm() <= 1e-15 * z.norm() {
            break;
        }
    }
    z
}

/// Newton's steps polishing a complex root on the original polynomial.
const POLISH_STEPS: usize = 4;

/// (q, q′, q″/2) at z by Horner's rule (ascending coefficients).
fn horner_complex(q: &[f64], z: Complex64) -> (Complex64, Complex64, Complex64) {
    let zero = Complex64::new(0.0, 0.0);
    let (mut v, mut d, mut s) = (zero, zero, zero);
    for &c in q.iter().rev() {
        s = s * z + d;
        d = d * z + v;
        v = v * z + c;
    }
    (v, d, s)
}

/// Laguerre's iteration in complex arithmetic (Press et al. §9.5) from z to [`APPROX_DONE`];
/// None where it does not settle within [`MAX_STEPS`].
fn complex_laguerre(q: &[f64], mut z: Complex64) -> Option<Complex64> {
    let n = (q.len() - 1) as f64;
    for _ in 0..MAX_STEPS {
        let (v, d, s) = horner_complex(q, z);
        if v.norm() == 0.0 {
            return Some(z);
        }
        let g = d / v;
        let h = g * g - 2.0 * s / v;
        let root = ((n - 1.0) * (n * h - g * g)).sqrt();
        let (plus, minus) = (g + root, g - root);
        let den = if plus.norm() >= minus.norm() {
            plus
        } else {
            minus
        };
        let step = n / den;
        if !(step.re.is_finite() && step.im.is_finite()) {
            return None;
        }
        z -= step;
        if step.norm() <= APPROX_DONE * z.norm() {
            return Some(z);
        }
    }
    None
}

/// q ← q/(x² − 2·Re z·x + |z|²) (ascending coefficients), the remainder dropped: forward
/// deflation by the pair z, z̄.
fn deflate_pair(q: &mut Vec<f64>, z: Complex64) {
    let (a1, a0) = (2.0 * z.re, z.norm_sqr());
    let n = q.len() - 1;
    if n < 2 {
        q.truncate(1);
        return;
    }
    // b_{k−2} = q_k + a1·b_{k−1} − a0·b_k, from b_{n−2} = q_n
    let mut b = vec![0.0; n - 1];
    for k in (2..=n).rev() {
        let above = |j: usize| if j < n - 1 { b[j] } else { 0.0 };
        b[k - 2] = q[k] + a1 * above(k - 1) - a0 * above(k);
    }
    *q = b;
}

/// q ← q/(x − r) (ascending coefficients), the remainder dropped: synthetic division from the
/// leading coefficient down (forward deflation).
fn deflate(q: &mut Vec<f64>, r: f64) {
    let n = q.len() - 1;
    let mut b = q[n];
    for k in (0..n).rev() {
        let c = q[k];
        q[k] = b;
        b = c + r * b;
    }
    q.pop();
}

/// Laguerre's iteration on q (ascending coefficients) from x to [`APPROX_DONE`] in real
/// arithmetic: Ok(None) where it does not settle within [`MAX_STEPS`]; Err(x) where the
/// discriminant at x shows a complex pair nearby ([`COMPLEX_DISC`]).
fn laguerre_root(q: &[f64], mut x: f64) -> Result<Option<f64>, f64> {
    let n = (q.len() - 1) as f64;
    for _ in 0..MAX_STEPS {
        let (mut v, mut d, mut s) = (0.0, 0.0, 0.0);
        for &c in q.iter().rev() {
            s = s * x + d;
            d = d * x + v;
            v = v * x + c;
        }
        if v == 0.0 {
            return Ok(Some(x));
        }
        let disc = (n - 1.0) * (n * (d * d - 2.0 * s * v) - d * d);
        if disc < -COMPLEX_DISC * n * n * d * d {
            return Err(x);
        }
        let step = laguerre_step(v, d, s, n);
        if !step.is_finite() {
            return Ok(None);
        }
        x -= step;
        if step.abs() <= APPROX_DONE * x.abs() {
            return Ok(Some(x));
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::poly::{from_real_roots, mul};

    #[test]
    fn cuts_separate_every_positive_root_of_a_real_rooted_polynomial() {
        let rs = [1e-6, 0.02, 0.5, 0.9, 1.1, 3.0, 40.0, 5e4];
        // and two negative roots, which are not counted
        let p = mul(&from_real_roots(&rs), &from_real_roots(&[-2.0, -0.1]));
        let cuts = descartes_cuts(&p, (1e-8, 1e6)).expect("the bound is met");
        assert_eq!(cuts.len(), rs.len() + 1);
        for (r, w) in rs.iter().zip(cuts.windows(2)) {
            assert!(w[0] < *r && *r < w[1], "{r} not in {w:?}");
        }
    }

    #[test]
    fn a_certified_complex_pair_settles_the_count() {
        // (x − 1)(x − 4)(x² − 2x + 1.01)(x + 3): four sign variations, two positive roots and
        // the pair 1 ± 0.1i, which leaves no room (2 + 2 + 2 > 5)
        let p = mul(&from_real_roots(&[1.0, 4.0, -3.0]), &[1.01, -2.0, 1.0]);
        assert_eq!(sign_variations_of(&p), 4);
        let cuts = descartes_cuts(&p, (0.01, 100.0)).expect("the pair is certified");
        assert_eq!(cuts.len(), 3);
        assert!(cuts[1] > 1.0 && cuts[1] < 4.0, "{cuts:?}");
    }

    #[test]
    fn room_for_another_pair_leaves_it_to_the_cascade() {
        // the same with two negative roots more: 2 + 2 + 2 ≤ 7, a second positive pair could
        // hide where the first is
        let p = mul(
            &from_real_roots(&[1.0, 4.0, -3.0, -5.0, -7.0]),
            &[1.01, -2.0, 1.0],
        );
        assert!(descartes_cuts(&p, (0.01, 100.0)).is_none());
        // and the cascade still finds both
        let got = super::super::positive_roots(&p);
        assert_eq!(got.len(), 2, "{got:?}");
    }

    #[test]
    fn pair_deflation_divides_exactly() {
        // (x² − 2x + 5)(x³ + 2x − 1)
        let z = Complex64::new(1.0, 2.0);
        let mut q = mul(&[5.0, -2.0, 1.0], &[-1.0, 2.0, 0.0, 1.0]);
        deflate_pair(&mut q, z);
        assert_eq!(q, vec![-1.0, 2.0, 0.0, 1.0]);
    }

    #[test]
    fn no_sign_variation_is_no_positive_root() {
        // (x + 1)(x + 2)(x² + x + 1): every coefficient positive
        let p = mul(&from_real_roots(&[-1.0, -2.0]), &[1.0, 1.0, 1.0]);
        assert_eq!(descartes_cuts(&p, (0.01, 100.0)), Some(vec![0.01, 100.0]));
        assert!(super::super::positive_roots(&p).is_empty());
    }

    #[test]
    fn zero_coefficients_are_skipped_in_the_count() {
        assert_eq!(sign_variations_of(&[1.0, 0.0, 1.0]), 0);
        assert_eq!(sign_variations_of(&[-1.0, 0.0, 0.0, 1.0]), 1);
    }
}
