//! The unit circle as a real half-line: with the Cayley transform z = (1 + s)/(1 − s), the
//! point z = e^{iθ} is s = i·ω with ω = tan(θ/2), and a polynomial X(z) of degree ≤ N becomes
//! X̃(s) = (1 − s)^N·X((1 + s)/(1 − s)), of degree ≤ N (the bilinear map of Jury,
//! *Theory and Application of the z-Transform Method*, 1964, §3.6). Split into even and odd
//! parts, X̃(iω) = Xe(u) + i·ω·Xo(u) with u = ω², so for two parts of p
//!
//! ```text
//! Im(X(z)·conj Y(z)) = ω·[X, Y](u) / |1 − iω|^{2N},   [X, Y] = Xo·Ye − Xe·Yo,
//! Re(X(z)·conj Y(z)) = (Xe·Ye + u·Xo·Yo)(u) / |1 − iω|^{2N}.
//! ```
//!
//! The D-decomposition's equations on the circle (Section V; [`crate::boundary`]) are then
//! real polynomials in u ∈ (0, ∞) (θ ∈ (0, π)): at a damping b the stiffness axis meets the
//! boundary where [P0, PK] + b·[PB, PK] = 0, and the complex-pair curve is the rational curve
//! a(u) = [P0, PB]/[PB, PK], b(u) = −[P0, PK]/[PB, PK]. Their positive roots
//! ([`crate::real_roots`]) are every crossing, with no θ grid to miss a pair between samples.
//!
//! The transform is formed from the parts in the shifted variable w = z − 1 where the family
//! keeps them (z − 1 = 2s/(1 − s): the low powers of s, which carry the roots near z = 1 of
//! fast sampling, come free of cancellation), else from the z-coefficients. Its coefficients
//! grow like 2^N while its values on the axis grow like 2^{N/2}, so the brackets lose about
//! N bits near θ = π/2: they are used up to [`MAX_DEGREE`] to locate crossings, which are
//! then polished on the circle itself.

use crate::closed_loop::AffineFamily;
use crate::poly;

/// Largest degree of p for which the transformed polynomials are formed: the brackets lose
/// about 2^N of their relative precision near θ = π/2 (2^28 ≈ 3e8, leaving seven digits to
/// tell crossings apart before they are polished); longer loops are scanned on the circle.
pub const MAX_DEGREE: usize = 28;

/// The parts P0, PK, PB of p under the Cayley transform (ascending in s, degree ≤ N = deg p)
/// and the bracket polynomials in u = ω² of the module doc.
#[derive(Debug, Clone, PartialEq)]
pub struct CayleyFamily {
    /// [P0, PK](u).
    pub p0_pk: Vec<f64>,
    /// [PB, PK](u).
    pub pb_pk: Vec<f64>,
    /// [P0, PB](u).
    pub p0_pb: Vec<f64>,
    /// Even and odd parts (Xe, Xo) of P̃0, P̃K, P̃B in u.
    pub parts: [(Vec<f64>, Vec<f64>); 3],
}

impl CayleyFamily {
    /// The transform of a family's parts; None above [`MAX_DEGREE`].
    pub fn new(fam: &AffineFamily) -> Option<Self> {
        let n = fam.degree();
        if n > MAX_DEGREE {
            return None;
        }
        let [p0, pk, pb] = transformed_parts(fam, n);
        let parts = [even_odd(&p0), even_odd(&pk), even_odd(&pb)];
        let [x0, xk, xb] = &parts;
        Some(Self {
            p0_pk: bracket(x0, xk),
            pb_pk: bracket(xb, xk),
            p0_pb: bracket(x0, xb),
            parts,
        })
    }

    /// The crossing polynomial of the wall line from + t·dir: [Q, D] with Q = P0 + from·(PK,
    /// PB) and D = dir·(PK, PB), i.e. d_a·[P0, PK] + d_b·[P0, PB] + (f_b·d_a − f_a·d_b)·[PB, PK]
    /// (the brackets are bilinear and antisymmetric); its positive roots u = tan²(θ/2) are the
    /// angles at which a root of p crosses the circle along the line.
    pub fn line_polynomial(&self, line: &crate::boundary::WallLine) -> Vec<f64> {
        let (f, d) = (line.from, line.dir);
        let mixed = f.b * d.a - f.a * d.b;
        poly::weighted_sum_trimmed(&[(d.a, &self.p0_pk), (d.b, &self.p0_pb), (mixed, &self.pb_pk)])
    }

    /// The stiffness axis's crossing polynomial at damping b: [P0, PK] + b·[PB, PK], whose
    /// positive roots u = tan²(θ/2) are the angles at which a root of p crosses the circle.
    pub fn axis_polynomial(&self, b: f64) -> Vec<f64> {
        poly::weighted_sum_trimmed(&[(1.0, &self.p0_pk), (b, &self.pb_pk)])
    }
}

/// The transformed parts P̃0, P̃K, P̃B (ascending in s) of degree ≤ n: each part
/// X = (1 + w)^k·c is c homogenized to degree n − k times (1 + s)^k (module doc).
fn transformed_parts(fam: &AffineFamily, n: usize) -> [Vec<f64>; 3] {
    let (core, pk, pb, variable) = match &fam.shifted {
        Some(sh) => (&sh.p0_core, &sh.pk, &sh.pb, Variable::Shifted),
        None => (&fam.p0_core, &fam.pk, &fam.pb, Variable::Z),
    };
    let mut p0 = homogenized(core, n - fam.k, variable);
    p0.resize(n + 1, 0.0);
    for _ in 0..fam.k {
        // × (1 + s)
        for r in (1..=n).rev() {
            p0[r] += p0[r - 1];
        }
    }
    [
        p0,
        homogenized(pk, n, variable),
        homogenized(pb, n, variable),
    ]
}

/// The variable a part's coefficients are in: w = z − 1 = 2s/(1 − s) or z = (1 + s)/(1 − s).
#[derive(Clone, Copy)]
enum Variable {
    Shifted,
    Z,
}

/// (1 − s)^m·c(x(s)) with x = 2s/(1 − s) (shifted) or (1 + s)/(1 − s) (z), ascending in s, by
/// Horner's rule on the homogeneous form: A_0 = c_m, A_{i+1} = X·A_i + c_{m−i−1}·(1 − s)^{i+1}
/// with X = 2s or 1 + s. Coefficients of c beyond degree m must be zero (they are not read).
fn homogenized(c: &[f64], m: usize, variable: Variable) -> Vec<f64> {
    let coef = |j: usize| c.get(j).copied().unwrap_or(0.0);
    let mut acc = vec![0.0; m + 1];
    acc[0] = coef(m);
    // (1 − s)^i, Pascal's rule with alternating signs
    let mut row = vec![0.0; m + 1];
    row[0] = 1.0;
    for i in 0..m {
        for r in (1..=i + 1).rev() {
            row[r] -= row[r - 1];
        }
        for r in (1..=i + 1).rev() {
            acc[r] = match variable {
                Variable::Shifted => 2.0 * acc[r - 1],
                Variable::Z => acc[r] + acc[r - 1],
            };
        }
        if let Variable::Shifted = variable {
            acc[0] = 0.0;
        }
        let cj = coef(m - i - 1);
        for r in 0..=i + 1 {
            acc[r] += cj * row[r];
        }
    }
    acc
}

/// (Xe, Xo) with X(iω) = Xe(ω²) + iω·Xo(ω²).
fn even_odd(x: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let sign = |m: usize| if m.is_multiple_of(2) { 1.0 } else { -1.0 };
    let even = x.iter().step_by(2).enumerate().map(|(m, c)| sign(m) * c);
    let odd = x
        .iter()
        .skip(1)
        .step_by(2)
        .enumerate()
        .map(|(m, c)| sign(m) * c);
    (even.collect(), odd.collect())
}

/// [X, Y] = Xo·Ye − Xe·Yo: Im(X conj Y) = ω·[X, Y] on the axis (module doc).
fn bracket((xe, xo): &(Vec<f64>, Vec<f64>), (ye, yo): &(Vec<f64>, Vec<f64>)) -> Vec<f64> {
    poly::mul_diff_trimmed(xo, ye, xe, yo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    #[test]
    fn brackets_are_the_imaginary_parts_on_the_circle() {
        for (g, dl, d) in [(1e-3, 0.015, 1), (0.5, 1.0, 3), (1e-6, 1e-4, 0)] {
            let pf =
                crate::paper::NormalizedFamily::new(crate::PlantParams::new(g, dl).unwrap(), d)
                    .unwrap();
            let cf = CayleyFamily::new(&pf).unwrap();
            let n = pf.degree() as i32;
            for theta in [1e-6, 0.01, 0.7, 1.5, 2.9, 3.1] {
                let (p0, pk, pb) = pf.parts_on_circle(theta);
                let w = (0.5 * theta).tan();
                let u = w * w;
                // |1 − iω|^{2N} = (1 + u)^N
                let scale = w / (1.0 + u).powi(n);
                let val = |c: &[f64]| poly::eval_real(c, u).0 * scale;
                let im = |x: Complex64, y: Complex64| (x * y.conj()).im;
                for (got, want) in [
                    (val(&cf.p0_pk), im(p0, pk)),
                    (val(&cf.pb_pk), im(pb, pk)),
                    (val(&cf.p0_pb), im(p0, pb)),
                ] {
                    let size = p0.norm().max(pb.norm()) * pk.norm().max(pb.norm());
                    assert!(
                        (got - want).abs() <= 1e-9 * size,
                        "θ = {theta}: {got} vs {want}"
                    );
                }
            }
        }
    }
}
