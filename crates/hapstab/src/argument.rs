//! The argument principle: the number of roots of p(z) inside a circle |z| = r, exact where
//! the Schur–Cohn test on z-coefficients cannot be trusted (fast sampling and slow modes put
//! several roots within 10⁻⁵ of z = 1, where the z-coefficients have lost the digits that
//! place them).
//!
//! For real coefficients and no root on the circle, the phase of p(r·e^{iθ}) grows by π for
//! every root inside as θ runs from 0 to π. Near z = 1 a wall's family is evaluated in the
//! shifted variable w = r·e^{iθ} − 1 = (r − 1) − 2r·sin²(θ/2) + i·r·sin θ ([`AffineFamily`]'s
//! shifted form, formed from E = Φ − I, with the exact value at z = 1), elsewhere from the
//! z-coefficients with z^k = r^k·e^{ikθ}; both with a running bound on the rounding error.
//! The step in θ follows the phase (Δθ ≤ 0.3·|p|/|dp/dθ|, halved until the phase turns by
//! less than π/3), so no root is stepped over. Where |p| falls to its error bound on the way,
//! double precision cannot decide and the answer says so.

use num_complex::Complex64;
use serde::Serialize;

use crate::closed_loop::{AffineFamily, SHIFTED_THETA};
use crate::poly;

/// The answer of the argument-principle test on one circle.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Winding {
    /// Roots inside the circle (the phase advance over [0, π] divided by π).
    pub inside: usize,
    /// Degree of p.
    pub degree: usize,
    /// Smallest |p| met along the circle, relative to its rounding-error bound there (below
    /// [`DECIDABLE`] the count cannot be trusted: a root is within rounding of the circle).
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

/// A real polynomial that can be evaluated on a circle |z| = r with its θ-derivative and a
/// bound on the rounding error of the value.
pub trait OnCircle {
    /// Degree of p.
    fn degree(&self) -> usize;
    /// (p(r·e^{iθ}), dp/dθ, rounding bound of the value).
    fn on_circle(&self, r: f64, theta: f64) -> (Complex64, Complex64, f64);
}

/// A wall's p(z) = P0 + a·PK + b·PB of a loop's family.
#[derive(Debug, Clone, Copy)]
pub struct Wall<'a> {
    /// The family.
    pub fam: &'a AffineFamily,
    /// Stiffness in wall units.
    pub a: f64,
    /// Damping in wall units.
    pub b: f64,
}

/// Σ |c_j|·ρ^j: the scale of a polynomial's rounding error at |x| = ρ.
fn abs_at(c: &[f64], rho: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &q| acc * rho + q.abs())
}

impl OnCircle for Wall<'_> {
    fn degree(&self) -> usize {
        self.fam.degree()
    }

    fn on_circle(&self, r: f64, theta: f64) -> (Complex64, Complex64, f64) {
        let (fam, a, b) = (self.fam, self.a, self.b);
        let kf = fam.k as f64;
        let zk = crate::circle::polar(r.powi(fam.k as i32), theta * kf);
        let i = Complex64::i();
        let (x, dx_dtheta, core, pk, pb) = match &fam.shifted {
            Some(sh) if theta.abs() < SHIFTED_THETA => {
                let h = (0.5 * theta).sin();
                let w = Complex64::new((r - 1.0) - 2.0 * r * h * h, r * theta.sin());
                (w, i * (w + 1.0), &sh.p0_core, &sh.pk, &sh.pb)
            }
            _ => {
                let z = crate::circle::polar(r, theta);
                (z, i * z, &fam.p0_core, &fam.pk, &fam.pb)
            }
        };
        let (c, dc) = poly::eval_with_derivative(core, x);
        let (k, dk) = poly::eval_with_derivative(pk, x);
        let (bb, db) = poly::eval_with_derivative(pb, x);
        let value = zk * c + k * a + bb * b;
        let deriv = i * kf * zk * c + (zk * dc + dk * a + db * b) * dx_dtheta;
        let rho = x.norm();
        let n = (core.len() + pk.len()) as f64;
        let err = 4.0
            * n
            * f64::EPSILON
            * (abs_at(core, rho) * zk.norm()
                + a.abs() * abs_at(pk, rho)
                + b.abs() * abs_at(pb, rho));
        (value, deriv, err)
    }
}

/// Bare ascending coefficients (no shifted form): a polynomial that is not a wall's family.
#[derive(Debug, Clone, Copy)]
pub struct Coefficients<'a>(pub &'a [f64]);

impl OnCircle for Coefficients<'_> {
    fn degree(&self) -> usize {
        self.0.len().saturating_sub(1)
    }

    fn on_circle(&self, r: f64, theta: f64) -> (Complex64, Complex64, f64) {
        let z = crate::circle::polar(r, theta);
        let (p, dp) = poly::eval_with_derivative(self.0, z);
        let err = 4.0 * self.0.len() as f64 * f64::EPSILON * abs_at(self.0, r);
        (p, Complex64::i() * z * dp, err)
    }
}

/// Counts the roots of p inside |z| = r by the argument principle (see the module doc).
pub fn winding(p: &impl OnCircle, r: f64) -> Winding {
    let pi = std::f64::consts::PI;
    let degree = p.degree();
    let undecided = Winding {
        inside: 0,
        degree,
        margin: 0.0,
    };
    let (mut f, mut df, err) = p.on_circle(r, 0.0);
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
            let (g, dg, e) = p.on_circle(r, (theta + h).min(pi));
            let turn = (g / f).arg();
            // The linear model that chose the step must hold at its end and at its middle:
            // where the terms of dp/dθ cancel (roots of a cluster near z = 1 on both sides),
            // the phase can whirl a whole turn inside one step while arg(g/f) reads a small
            // angle and g even lies near the linear model's end.
            let linear = step_holds(p, r, theta, h, (f, df), g);
            if (turn.abs() < pi / 3.0 && linear) || h < 1e-300 {
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

/// A step of the winding from θ (value f, θ-derivative df) to θ + h (value g) is accepted
/// when the linear model holds at both ends of each half (within half of |f| at the end,
/// a quarter at the middle) and the two halves' turns, each below π/3, add up to the whole
/// step's: a whole turn hidden in the step shows at the middle.
fn step_holds(
    p: &impl OnCircle,
    r: f64,
    theta: f64,
    h: f64,
    (f, df): (Complex64, Complex64),
    g: Complex64,
) -> bool {
    let pi = std::f64::consts::PI;
    if (g - f - df * h).norm() > 0.5 * f.norm() {
        return false;
    }
    let (m, _, _) = p.on_circle(r, theta + 0.5 * h);
    let (first, second) = ((m / f).arg(), (g / m).arg());
    (m - f - df * (0.5 * h)).norm() <= 0.25 * f.norm()
        && first.abs() < pi / 3.0
        && second.abs() < pi / 3.0
        && (first + second - (g / f).arg()).abs() < 1e-6
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::PlantParams;
    use crate::paper::NormalizedFamily;

    #[test]
    fn counts_agree_with_the_schur_test_on_the_paper_loop() {
        let fam = NormalizedFamily::new(PlantParams::new(1e-3, 0.015).unwrap(), 2).unwrap();
        for &(a, b, stable) in &[(0.03, 0.3, true), (0.2, 0.3, false), (-0.01, 0.2, false)] {
            let w = winding(&Wall { fam: &fam, a, b }, 1.0);
            assert!(w.decided(), "{a} {b}: {w:?}");
            assert_eq!(w.stable(), stable, "{a} {b}: {w:?}");
            let c = fam.coefficients(a, b);
            assert_eq!(crate::schur_cohn::schur_stable(&c), stable);
            let wc = winding(&Coefficients(&c), 1.0);
            assert_eq!((wc.decided(), wc.inside), (true, w.inside));
        }
    }

    #[test]
    fn a_cluster_on_both_sides_of_z_one_is_not_stepped_over() {
        // a two-mass device at T = 1e-5: two pairs within 3e-5 and 4e-4 of the circle at
        // θ = 0.031 and 0.014, whose terms of dp/dθ cancel at θ = 0, and three fast roots
        let pair = |re: f64, im: f64| [re * re + im * im, -2.0 * re, 1.0];
        let c = [
            pair(0.999_486_871_753_8, 0.031_182_097_98),
            pair(0.999_543_100_543_4, 0.014_423_047_04),
            pair(-0.032_951_453_18, 0.050_663_724_52),
        ]
        .iter()
        .fold(vec![-0.066_473_263_86, 1.0], |acc, q| {
            crate::poly::mul(&acc, q)
        });
        for r in [1.0, 1.0 - 5e-11, 1.0 + 5e-11] {
            let w = winding(&Coefficients(&c), r);
            assert!(w.decided(), "{w:?}");
            assert_eq!(w.inside, 7, "r = {r}: {w:?}");
        }
    }

    #[test]
    fn counts_roots_inside_any_radius() {
        // (z − 0.5)(z + 0.9)(z² + 0.81): roots of modulus 0.5, 0.9, 0.9
        let c = crate::poly::mul(
            &crate::poly::mul(&[-0.5, 1.0], &[0.9, 1.0]),
            &[0.81, 0.0, 1.0],
        );
        let p = Coefficients(&c);
        assert_eq!(winding(&p, 0.95).inside, 4);
        assert_eq!(winding(&p, 0.7).inside, 1);
        assert_eq!(winding(&p, 0.3).inside, 0);
    }
}
