//! The Schur–Cohn recursion: Section V's algebraic stability test (every root of p(z)
//! strictly inside a circle), with the conditioning of each of its steps.
//!
//! For ascending coefficients c of degree n (c[n] ≠ 0), each step takes the reflection
//! coefficient k = c0/cn (|k| < 1 is necessary) and keeps (cn·c(z) − c0·c*(z))/z, one degree
//! lower; the roots all lie inside |z| < 1 iff every |k_j| < 1 (Schur 1917, Cohn 1922; see
//! e.g. Jury, *Theory and Application of the z-Transform Method*, 1964). Each step
//! b_j = a_{j+1} − k·a_{n−1−j} cancels when |k| is near 1, so rounding errors grow by
//! κ_j = Π_{i<j} (1 + |k_i|)/(1 − |k_i|): a step's decision 1 − |k_j| ≷ 0 is *sure* when the
//! gap exceeds [`STEP_SAFETY`] times its first-order error bound κ_j·(n·ε + η), η being any
//! further relative perturbation of the coefficients the decision must withstand.
//!
//! This is the only Schur–Cohn recursion of the crate: [`crate::verdict`] decides every wall
//! with it and falls back to the argument principle where it is not sure.

/// A step's decision is sure when its gap |1 − |k_j|| exceeds this many times its
/// first-order error bound κ_j·(n·ε + η) (the bound is first order; the factor covers the
/// neglected terms and the slack of the growth estimate).
pub const STEP_SAFETY: f64 = 64.0;

/// Degrees up to this run the recursion on stack buffers (maps call it once per point, where
/// a heap allocation would cost as much as the recursion itself).
const STACK_DEGREE: usize = 63;

/// Degrees up to this use the smaller stack buffers (the paper's loops and most devices).
const SMALL_DEGREE: usize = 15;

/// The outcome of one run of the recursion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SchurCohn {
    /// Every reflection coefficient had |k_j| < 1: all roots inside the circle tested.
    pub stable: bool,
    /// Every decision taken (each gap of the stable steps, and the failing step's excess)
    /// cleared [`STEP_SAFETY`] times its error bound.
    pub sure: bool,
    /// The growth factor κ of the rounding errors over the steps taken (infinite when a
    /// leading coefficient vanished or was not finite).
    pub kappa: f64,
}

/// Runs the recursion on c(r·z) (roots of c inside |z| < r iff `stable`), with the decisions
/// required to withstand a further relative perturbation `eta` of every coefficient.
pub fn schur_cohn(c: &[f64], r: f64, eta: f64) -> SchurCohn {
    let n = c.len();
    // two tiers of stack buffers: zeroing them is a measurable share of a low-degree test
    if n <= SMALL_DEGREE + 1 {
        let mut a = [0.0_f64; SMALL_DEGREE + 1];
        let mut b = [0.0_f64; SMALL_DEGREE + 1];
        recursion(c, r, eta, &mut a[..n], &mut b[..n])
    } else if n <= STACK_DEGREE + 1 {
        let mut a = [0.0_f64; STACK_DEGREE + 1];
        let mut b = [0.0_f64; STACK_DEGREE + 1];
        recursion(c, r, eta, &mut a[..n], &mut b[..n])
    } else {
        let mut a = vec![0.0; n];
        let mut b = vec![0.0; n];
        recursion(c, r, eta, &mut a, &mut b)
    }
}

/// True iff every root of c lies strictly inside the unit circle, by the plain recursion
/// (for polynomials that are not a wall's p(z), such as a filter's denominator).
pub fn schur_stable(c: &[f64]) -> bool {
    schur_cohn(c, 1.0, 0.0).stable
}

/// Spectral radius by bisection on the recursion of c(r·z), with no root finding: the
/// smallest r for which every root lies inside |z| < r, to about 1e-15 relative *in the
/// z-coefficients*. Where roots crowd z = 1 those coefficients no longer place the roots, and
/// the radius of [`crate::stability::Analysis`] (roots polished in w = z − 1) is the one to
/// report; this is an independent check for well-conditioned polynomials.
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
        if schur_cohn(c, mid, 0.0).stable {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// As [`schur_cohn`] at r = 1 on coefficients the caller no longer needs: the recursion runs
/// in `c` itself (overwritten), saving the copy on the hot path of a map.
pub fn schur_cohn_in_place(c: &mut [f64], eta: f64) -> SchurCohn {
    let n = c.len();
    if n <= SMALL_DEGREE + 1 {
        let mut b = [0.0_f64; SMALL_DEGREE + 1];
        run(c, &mut b[..n], eta)
    } else if n <= STACK_DEGREE + 1 {
        let mut b = [0.0_f64; STACK_DEGREE + 1];
        run(c, &mut b[..n], eta)
    } else {
        let mut b = vec![0.0; n];
        run(c, &mut b, eta)
    }
}

/// The recursion on two buffers of c's length (both overwritten).
fn recursion<'a>(c: &[f64], r: f64, eta: f64, a: &'a mut [f64], b: &'a mut [f64]) -> SchurCohn {
    if r == 1.0 {
        a.copy_from_slice(c);
    } else {
        let mut scale = 1.0;
        for (ai, ci) in a.iter_mut().zip(c) {
            *ai = ci * scale;
            scale *= r;
        }
    }
    run(a, b, eta)
}

/// The steps of the recursion on `a` (the polynomial, overwritten) with scratch `b`.
fn run<'a>(a: &'a mut [f64], b: &'a mut [f64], eta: f64) -> SchurCohn {
    let (mut a, mut b) = (a, b);
    let mut n = a.len() - 1;
    let per_step = n as f64 * f64::EPSILON + eta;
    let mut kappa = 1.0_f64;
    let mut sure = true;
    while n > 0 {
        let an = a[n];
        let k = a[0] / an;
        if !an.is_finite() || an == 0.0 || k.is_nan() {
            return SchurCohn {
                stable: false,
                sure: false,
                kappa: f64::INFINITY,
            };
        }
        let gap = 1.0 - k.abs();
        let bound = STEP_SAFETY * kappa * per_step;
        if gap <= 0.0 {
            return SchurCohn {
                stable: false,
                sure: sure && -gap > bound,
                kappa,
            };
        }
        sure &= gap > bound;
        kappa *= (1.0 + k.abs()) / gap;
        for j in 0..n {
            b[j] = a[j + 1] - k * a[n - 1 - j];
        }
        std::mem::swap(&mut a, &mut b);
        n -= 1;
    }
    SchurCohn {
        stable: true,
        sure,
        kappa,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_roots_are_decided_surely() {
        let s = schur_cohn(&crate::poly::from_real_roots(&[0.5, -0.9, 0.99]), 1.0, 0.0);
        assert!(s.stable && s.sure, "{s:?}");
        let u = schur_cohn(&crate::poly::from_real_roots(&[0.5, -1.01, 0.2]), 1.0, 0.0);
        assert!(!u.stable && u.sure, "{u:?}");
        // scaled: roots inside 0.98 but not inside 0.95
        let c = crate::poly::from_real_roots(&[0.3, -0.97]);
        assert!(schur_cohn(&c, 0.98, 0.0).stable);
        assert!(!schur_cohn(&c, 0.95, 0.0).stable);
    }

    #[test]
    fn a_root_on_the_circle_is_never_sure() {
        let c = crate::poly::from_real_roots(&[0.5, 1.0, 0.2]);
        assert!(!schur_cohn(&c, 1.0, 0.0).sure);
        // a root 1e-12 inside is decided by rounding alone, not against a 1e-10 perturbation
        let c = crate::poly::from_real_roots(&[0.5, 1.0 - 1e-12]);
        assert!(!schur_cohn(&c, 1.0, 1e-10).sure);
    }
}
