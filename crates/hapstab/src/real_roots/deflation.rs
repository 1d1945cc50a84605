//! Brackets of every positive root at once, where Descartes' bound is met: the coefficients'
//! sign variations V bound the number of positive roots from above (Descartes' rule of
//! signs), so V sign changes of p found between approximate roots prove that there are
//! exactly V, one between each pair of consecutive cuts. The approximate roots come from
//! Laguerre's method with forward deflation, smallest first (Press et al., *Numerical
//! Recipes*, 3rd ed., §9.5: Laguerre's step converges to a neighbouring root from any start
//! on a polynomial whose roots are all real, and forward deflation is stable when the roots
//! are removed in order of increasing magnitude; Wilkinson, *Rounding Errors in Algebraic
//! Processes*, 1963, ch. 2). Only the cuts come from the deflated polynomials; the roots
//! themselves are then refined on p ([`super::roots_between_ends`]). A polynomial with
//! fewer positive roots than V (a complex pair of positive real part) fails the count, and
//! the derivative cascade takes over.

use super::{laguerre_step, sure_sign};

/// Laguerre steps per approximate root at most.
const MAX_STEPS: usize = 40;

/// Relative step at which an approximate root is taken (the cuts need only separate the
/// roots; the refinement on p gives their digits).
const APPROX_DONE: f64 = 1e-8;

/// Laguerre's discriminant (n − 1)(n·H − G²)·v² below this fraction of n²·d² is negative
/// beyond rounding: a complex pair lies nearby, and the count will not be met.
const COMPLEX_DISC: f64 = 1e-9;

/// Cuts lo = x_0 < x_1 < … < x_V = hi with p's sign sure at each and changing across every
/// interval, V the sign variations of p's coefficients (module doc): each interval holds
/// exactly one root of p, and there are no other positive roots in (lo, hi). None where the
/// count is not met (the cascade decides then). `p` has nonzero constant and leading
/// coefficients and every positive root inside (lo, hi).
pub(super) fn descartes_cuts(p: &[f64], (lo, hi): (f64, f64)) -> Option<Vec<f64>> {
    let v = sign_variations_of(p);
    let mut roots = approximate_roots(p, v, (lo, hi))?;
    roots.sort_by(f64::total_cmp);
    let mut cuts = Vec::with_capacity(v + 1);
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

/// `count` approximate roots of p inside (lo, hi), by Laguerre's method from lo on p deflated
/// by each root found (those outside (lo, hi), e.g. negative ones, deflated and passed
/// over); None where an iteration meets a complex pair or does not settle.
fn approximate_roots(p: &[f64], count: usize, (lo, hi): (f64, f64)) -> Option<Vec<f64>> {
    let mut q = p.to_vec();
    let mut found: Vec<f64> = Vec::with_capacity(count);
    let mut x = lo;
    while found.len() < count && q.len() > 1 {
        let r = laguerre_root(&q, x)?;
        deflate(&mut q, r);
        if r > lo && r < hi {
            found.push(r);
            x = r;
        }
    }
    (found.len() == count).then_some(found)
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

/// Laguerre's iteration on q (ascending coefficients) from x to [`APPROX_DONE`]; None where
/// the discriminant shows a complex pair nearby ([`COMPLEX_DISC`]) or the iteration does not
/// settle within [`MAX_STEPS`].
fn laguerre_root(q: &[f64], mut x: f64) -> Option<f64> {
    let n = (q.len() - 1) as f64;
    for _ in 0..MAX_STEPS {
        let (mut v, mut d, mut s) = (0.0, 0.0, 0.0);
        for &c in q.iter().rev() {
            s = s * x + d;
            d = d * x + v;
            v = v * x + c;
        }
        if v == 0.0 {
            return Some(x);
        }
        let disc = (n - 1.0) * (n * (d * d - 2.0 * s * v) - d * d);
        if disc < -COMPLEX_DISC * n * n * d * d {
            return None;
        }
        let step = laguerre_step(v, d, s, n);
        if !step.is_finite() {
            return None;
        }
        x -= step;
        if step.abs() <= APPROX_DONE * x.abs() {
            return Some(x);
        }
    }
    None
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
    fn a_complex_pair_of_positive_real_part_leaves_it_to_the_cascade() {
        // (x − 1)(x − 4)(x² − 2x + 1.01): four sign variations, two positive roots
        let p = mul(&from_real_roots(&[1.0, 4.0]), &[1.01, -2.0, 1.0]);
        assert_eq!(sign_variations_of(&p), 4);
        assert!(descartes_cuts(&p, (0.01, 100.0)).is_none());
    }

    #[test]
    fn zero_coefficients_are_skipped_in_the_count() {
        assert_eq!(sign_variations_of(&[1.0, 0.0, 1.0]), 0);
        assert_eq!(sign_variations_of(&[-1.0, 0.0, 0.0, 1.0]), 1);
    }
}
