//! Exact stability boundaries by D-decomposition (Section V, Figs. 4–6).
//!
//! p(z) = P0(z) + α Pα(z) + β Pβ(z) is linear in α and β (see [`PolyFamily`]). A root on the
//! unit circle at z = e^{iθ} is two real linear equations in (α, β); with
//! R(z) = z^d D(z)/N(z) their solution is, for θ in (0, π),
//!
//! ```text
//! α(θ) = Im(R(z)(1 − z)) / sin θ,     β(θ) = −Im R(z) / sin θ.
//! ```
//!
//! z = 1 gives the line α = −γ (p(1) = N(1)(α + γ)); z = −1 gives the line
//! α + 2β = (−1)^{d+1} D(−1)/N(−1) (absent when N(−1) = 0, as for a pure mass).

use num_complex::Complex64;
use serde::Serialize;

use crate::closed_loop::PolyFamily;
use crate::stability::schur_stable;

/// A point of the (α, β)-plane.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AlphaBeta {
    /// Normalized virtual stiffness α.
    pub alpha: f64,
    /// Normalized virtual damping β.
    pub beta: f64,
}

/// The boundary point for a complex root pair at angle θ ∈ (0, π): the (α, β) for which
/// p(e^{iθ}) = 0 (D-decomposition, Section V). None where N(e^{iθ}) = 0.
pub fn curve_point(fam: &PolyFamily, theta: f64) -> Option<AlphaBeta> {
    let (s, c) = theta.sin_cos();
    curve_point_at(fam, Complex64::new(c, s))
}

/// As [`curve_point`] for z = e^{iθ} given directly (|z| = 1, Im z > 0), which lets callers
/// that step along the circle avoid a sine and cosine per point.
pub fn curve_point_at(fam: &PolyFamily, z: Complex64) -> Option<AlphaBeta> {
    let n = fam.plant.numerator(z);
    if n.norm_sqr() == 0.0 {
        return None;
    }
    // z^d by repeated squaring: O(log d) products, a few roundings
    let zd = z.powu(fam.d as u32);
    let r = zd * fam.plant.denominator(z) / n;
    let s = z.im;
    Some(AlphaBeta {
        alpha: (r * (1.0 - z)).im / s,
        beta: -r.im / s,
    })
}

/// The z = −1 line as (a, c) with α + a·β = c, i.e. α + 2β = (−1)^{d+1} D(−1)/N(−1);
/// None when N(−1) = 0.
pub fn minus_one_line(fam: &PolyFamily) -> Option<(f64, f64)> {
    let pl = &fam.plant;
    let n = pl.n0 - pl.n1;
    if n.abs() <= 1e-300 {
        return None;
    }
    let dm1 = 1.0 + pl.a1 + pl.a0;
    let sign = if (fam.d + 1).is_multiple_of(2) {
        1.0
    } else {
        -1.0
    };
    Some((2.0, sign * dm1 / n))
}

/// Q0(z) = P0(z) + β Pβ(z) and Pα(z) on the unit circle at angle θ, with z^{d+1} from its
/// polar form (O(1) for any d).
fn q0_palpha(fam: &PolyFamily, beta: f64, theta: f64) -> (Complex64, Complex64) {
    let z = Complex64::from_polar(1.0, theta);
    let zd1 = Complex64::from_polar(1.0, theta * (fam.d as f64 + 1.0));
    let n = fam.plant.numerator(z);
    (zd1 * fam.plant.denominator(z) + (z - 1.0) * n * beta, z * n)
}

/// Bisection for a sign change of `f` on [a, b] (f(a), f(b) of opposite signs).
pub(crate) fn bisect(mut a: f64, mut b: f64, f: impl Fn(f64) -> f64) -> f64 {
    let fa0 = f(a);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b {
            break;
        }
        if (f(m) > 0.0) == (fa0 > 0.0) {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}

/// Number of θ samples used to bracket sign changes for a delay d.
fn theta_samples(d: usize) -> usize {
    256 * (d + 4)
}

/// All α at which, for fixed β, p(z) has a root on the unit circle (D-decomposition along
/// α, Section V): α = −γ (z = 1), the z = −1 value, and α = −Q0/Pα where Im(Q0 conj Pα) = 0.
pub fn alpha_crossings(fam: &PolyFamily, beta: f64) -> Vec<f64> {
    let mut out = vec![-fam.plant.gamma];
    if let Some((a, c)) = minus_one_line(fam) {
        out.push(c - a * beta);
    }
    let f = |t: f64| {
        let (q, pa) = q0_palpha(fam, beta, t);
        (q * pa.conj()).im
    };
    let m = theta_samples(fam.d);
    let h = std::f64::consts::PI / m as f64;
    let mut prev_t = 1e-9 * h;
    let mut prev = f(prev_t);
    for i in 1..=m {
        let t = if i == m {
            std::f64::consts::PI * (1.0 - 1e-12)
        } else {
            i as f64 * h
        };
        let v = f(t);
        if v == 0.0 || (v > 0.0) != (prev > 0.0) {
            let tr = if v == 0.0 { t } else { bisect(prev_t, t, f) };
            let (q, pa) = q0_palpha(fam, beta, tr);
            if pa.norm() > 0.0 {
                let a = -(q * pa.conj()).re / pa.norm_sqr();
                if a.is_finite() {
                    out.push(a);
                }
            }
        }
        prev = v;
        prev_t = t;
    }
    out.sort_by(f64::total_cmp);
    out.dedup_by(|a, b| (*a - *b).abs() <= 1e-15 * a.abs().max(b.abs()));
    out
}

/// A stable interval lo < α < hi (either end may be infinite).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Interval {
    /// Lower end (exclusive).
    pub lo: f64,
    /// Upper end (exclusive).
    pub hi: f64,
}

/// The stable α-intervals for a given β (Section V): between consecutive boundary crossings
/// the number of unstable roots is constant, so one Schur–Cohn test per gap decides it.
pub fn stable_alpha_intervals(fam: &PolyFamily, beta: f64) -> Vec<Interval> {
    let xs = alpha_crossings(fam, beta);
    let scale = xs.iter().fold(1e-3_f64, |m, x| m.max(x.abs()));
    let mut coeffs = vec![0.0; fam.degree() + 1];
    let mut stable_at = |a: f64| {
        fam.coefficients_into(a, beta, &mut coeffs);
        schur_stable(&coeffs)
    };
    let mut out: Vec<Interval> = Vec::new();
    let push = |lo: f64, hi: f64, out: &mut Vec<Interval>| match out.last_mut() {
        Some(last) if last.hi == lo => last.hi = hi,
        _ => out.push(Interval { lo, hi }),
    };
    let first = xs[0];
    if stable_at(first - scale) {
        push(f64::NEG_INFINITY, first, &mut out);
    }
    for w in xs.windows(2) {
        if stable_at(0.5 * (w[0] + w[1])) {
            push(w[0], w[1], &mut out);
        }
    }
    let last = xs[xs.len() - 1];
    if stable_at(last + scale) {
        push(last, f64::INFINITY, &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlantParams;

    #[test]
    fn pure_mass_interval_is_closed_form() {
        let fam = PolyFamily::new(PlantParams::new(0.0, 0.0).unwrap(), 0).unwrap();
        for beta in [0.1, 0.7, 1.5] {
            let iv = stable_alpha_intervals(&fam, beta);
            let hi = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
            assert_eq!(iv.len(), 1, "{iv:?}");
            assert_eq!(iv[0].lo, 0.0);
            assert!((iv[0].hi - hi).abs() < 1e-14 * hi, "{} vs {hi}", iv[0].hi);
        }
        assert!(stable_alpha_intervals(&fam, -0.1).is_empty());
        assert!(stable_alpha_intervals(&fam, 2.1).is_empty());
    }

    #[test]
    fn curve_points_put_a_root_on_the_circle() {
        let fam = PolyFamily::new(PlantParams::new(1e-3, 0.015).unwrap(), 2).unwrap();
        for t in [0.01, 0.5, 1.0, 2.0, 3.0] {
            let p = curve_point(&fam, t).unwrap();
            let v = fam.eval(p.alpha, p.beta, Complex64::from_polar(1.0, t));
            assert!(
                v.norm() < 1e-14 * (1.0 + p.alpha.abs() + p.beta.abs()),
                "{v}"
            );
        }
    }
}
