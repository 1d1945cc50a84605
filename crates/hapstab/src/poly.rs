//! Real polynomials with ascending coefficients (c[k] multiplies z^k), and the characteristic
//! polynomial of a small dense matrix. These are the building blocks of the loop's
//! characteristic polynomial p(z) (eq. 7–9 and its generalization in [`crate::closed_loop`]).

use num_complex::Complex64;

/// Product of two polynomials (ascending coefficients).
pub fn mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    if a.is_empty() || b.is_empty() {
        return Vec::new();
    }
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, &x) in a.iter().enumerate() {
        if x == 0.0 {
            continue;
        }
        for (o, &y) in out[i..].iter_mut().zip(b) {
            *o += x * y;
        }
    }
    out
}

/// Ascending coefficients of the monic polynomial Π (x − r) with the given real roots.
pub fn from_real_roots(roots: &[f64]) -> Vec<f64> {
    roots.iter().fold(vec![1.0], |c, &r| mul(&c, &[-r, 1.0]))
}

/// a + s·b, padded to the longer length.
pub fn add_scaled(a: &[f64], s: f64, b: &[f64]) -> Vec<f64> {
    let n = a.len().max(b.len());
    (0..n)
        .map(|k| a.get(k).copied().unwrap_or(0.0) + s * b.get(k).copied().unwrap_or(0.0))
        .collect()
}

/// Σ w_i·p_i (ascending coefficients) with the leading coefficients that are rounding noise
/// removed: a coefficient whose magnitude is within `ROUNDING_ULPS`·ε of the sum of its
/// terms' magnitudes (Σ |w_i·p_i,j|, or the given `scale`) cannot be told from zero by this
/// computation (a cancelling leading term, as in the derivative bracket a1′a2 − a1a2′ of two
/// polynomials of one degree), and a root it would place near infinity is an artefact.
pub fn weighted_sum_trimmed(terms: &[(f64, &[f64])]) -> Vec<f64> {
    let n = terms.iter().map(|(_, p)| p.len()).max().unwrap_or(0);
    let mut sum = vec![0.0; n];
    let mut scale = vec![0.0; n];
    for (w, p) in terms {
        for (j, &c) in p.iter().enumerate() {
            sum[j] += w * c;
            scale[j] += (w * c).abs();
        }
    }
    trim_rounding_lead(&mut sum, &scale);
    sum
}

/// a·b − c·d (ascending coefficients) with the leading coefficients that are rounding noise
/// removed, as [`weighted_sum_trimmed`] does, the scale of each coefficient being
/// Σ |a_i·b_j| + |c_i·d_j| over its products.
pub fn mul_diff_trimmed(a: &[f64], b: &[f64], c: &[f64], d: &[f64]) -> Vec<f64> {
    let abs = |p: &[f64]| p.iter().map(|x| x.abs()).collect::<Vec<f64>>();
    let mut out = add_scaled(&mul(a, b), -1.0, &mul(c, d));
    let scale = add_scaled(&mul(&abs(a), &abs(b)), 1.0, &mul(&abs(c), &abs(d)));
    trim_rounding_lead(&mut out, &scale);
    out
}

/// Rounding errors of a few operations per coefficient, in units of ε (module doc of
/// [`weighted_sum_trimmed`]).
pub const ROUNDING_ULPS: f64 = 8.0;

/// Removes the leading coefficients of `c` that lie within [`ROUNDING_ULPS`]·ε of `scale`,
/// the sum of the magnitudes of the terms that formed them.
pub fn trim_rounding_lead(c: &mut Vec<f64>, scale: &[f64]) {
    while let Some(&last) = c.last() {
        let j = c.len() - 1;
        if last.abs() > ROUNDING_ULPS * f64::EPSILON * scale.get(j).copied().unwrap_or(0.0) {
            break;
        }
        c.pop();
    }
}

/// z^k · a(z).
pub fn shift_up(a: &[f64], k: usize) -> Vec<f64> {
    let mut out = vec![0.0; k];
    out.extend_from_slice(a);
    out
}

/// Removes trailing (highest-power) exact zeros, keeping at least one coefficient.
pub fn trim(mut a: Vec<f64>) -> Vec<f64> {
    while a.len() > 1 && a[a.len() - 1] == 0.0 {
        a.pop();
    }
    a
}

/// |z| as √(re² + im²) where the square is a normal number (no overflow, no underflow: to
/// an ulp, and several times faster than `hypot`), else by `hypot`.
#[inline]
pub fn modulus(z: Complex64) -> f64 {
    let s = z.norm_sqr();
    if s.is_normal() { s.sqrt() } else { z.norm() }
}

/// Value at a complex point by Horner's rule.
pub fn eval(c: &[f64], z: Complex64) -> Complex64 {
    c.iter()
        .rev()
        .fold(Complex64::new(0.0, 0.0), |acc, &ci| acc * z + ci)
}

/// Three polynomials (ascending coefficients) at one complex point by Horner's rule, in one
/// pass: the three recurrences are independent, so they run side by side. Each value is
/// bit for bit that of [`eval`] (a shorter polynomial's leading zeros stay exact zeros).
pub fn eval3(a: &[f64], b: &[f64], c: &[f64], z: Complex64) -> [Complex64; 3] {
    let n = a.len().max(b.len()).max(c.len());
    let (zr, zi) = (z.re, z.im);
    let (mut ar, mut ai, mut br, mut bi, mut cr, mut ci) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    let m = b.len();
    if a.len() == n && c.len() == m {
        // the family's shape (P0's core at least as long as the wall parts, which are equally
        // long): no test for missing coefficients in the loops
        for &x in a[m..].iter().rev() {
            (ar, ai) = (ar * zr - ai * zi + x, ar * zi + ai * zr);
        }
        for ((&x, &y), &w) in a[..m].iter().zip(b).zip(c).rev() {
            (ar, ai) = (ar * zr - ai * zi + x, ar * zi + ai * zr);
            (br, bi) = (br * zr - bi * zi + y, br * zi + bi * zr);
            (cr, ci) = (cr * zr - ci * zi + w, cr * zi + ci * zr);
        }
        return [
            Complex64::new(ar, ai),
            Complex64::new(br, bi),
            Complex64::new(cr, ci),
        ];
    }
    let at = |p: &[f64], i: usize| if i < p.len() { p[i] } else { 0.0 };
    for i in (0..n).rev() {
        (ar, ai) = (ar * zr - ai * zi + at(a, i), ar * zi + ai * zr);
        (br, bi) = (br * zr - bi * zi + at(b, i), br * zi + bi * zr);
        (cr, ci) = (cr * zr - ci * zi + at(c, i), cr * zi + ci * zr);
    }
    [
        Complex64::new(ar, ai),
        Complex64::new(br, bi),
        Complex64::new(cr, ci),
    ]
}

/// Value and first derivative at a complex point by Horner's rule.
pub fn eval_with_derivative(c: &[f64], z: Complex64) -> (Complex64, Complex64) {
    let zero = Complex64::new(0.0, 0.0);
    c.iter()
        .rev()
        .fold((zero, zero), |(p, dp), &ci| (p * z + ci, dp * z + p))
}

/// Value and first derivative at a real point.
pub fn eval_real(c: &[f64], x: f64) -> (f64, f64) {
    c.iter()
        .rev()
        .fold((0.0, 0.0), |(p, dp), &ci| (p * x + ci, dp * x + p))
}

/// The Taylor shift q(z) = p(z + s): the coefficients of p in powers of (z − s) read as a
/// polynomial in z. Used to convert the shifted (delta-like) form in w = z − 1 to z (s = −1).
pub fn taylor_shift(p: &[f64], s: f64) -> Vec<f64> {
    let mut c = p.to_vec();
    taylor_shift_in_place(&mut c, s);
    c
}

/// [`taylor_shift`] in a stack buffer for polynomials of up to 32 coefficients, handed to
/// `f` (the same operations without an allocation).
pub fn with_taylor_shift<R>(p: &[f64], s: f64, f: impl FnOnce(&[f64]) -> R) -> R {
    const SMALL: usize = 32;
    if p.len() > SMALL {
        return f(&taylor_shift(p, s));
    }
    let mut buf = [0.0; SMALL];
    let c = &mut buf[..p.len()];
    c.copy_from_slice(p);
    taylor_shift_in_place(c, s);
    f(c)
}

/// [`taylor_shift`] of the coefficients in `c`, in place.
fn taylor_shift_in_place(c: &mut [f64], s: f64) {
    // Repeated synthetic division (Horner) by (z − s): exact for s = ±1 up to one rounding
    // per multiply-add.
    let n = c.len();
    for i in 0..n {
        for j in (i..n.saturating_sub(1)).rev() {
            c[j] += s * c[j + 1];
        }
    }
}

/// A dense row-major square matrix of small order (the plant's state dimension).
pub type Mat = Vec<Vec<f64>>;

/// The n×n identity.
pub fn identity(n: usize) -> Mat {
    (0..n)
        .map(|i| (0..n).map(|j| if i == j { 1.0 } else { 0.0 }).collect())
        .collect()
}

/// Matrix product.
pub fn mat_mul(a: &Mat, b: &Mat) -> Mat {
    let n = a.len();
    let m = b.first().map_or(0, Vec::len);
    let mut out = vec![vec![0.0; m]; n];
    for i in 0..n {
        for (k, bk) in b.iter().enumerate() {
            let aik = a[i][k];
            if aik == 0.0 {
                continue;
            }
            for j in 0..m {
                out[i][j] += aik * bk[j];
            }
        }
    }
    out
}

/// Matrix–vector product.
pub fn mat_vec(a: &Mat, x: &[f64]) -> Vec<f64> {
    rows_times(a.iter().map(Vec::as_slice), x)
}

/// The product of the matrix with the given rows and x (the rows of a [`Mat`] or of a
/// row-major work buffer; [`mat_vec`]).
pub fn rows_times<'a>(rows: impl Iterator<Item = &'a [f64]>, x: &[f64]) -> Vec<f64> {
    rows.map(|row| row.iter().zip(x).map(|(r, v)| r * v).sum())
        .collect()
}

/// Orders up to this one are formed in stack buffers where a hot path builds small matrices
/// (the matrix exponential, the numerator's determinant).
pub const SMALL_ORDER: usize = 6;

/// The 1-norm (largest absolute column sum).
pub fn norm1(a: &Mat) -> f64 {
    let n = a.first().map_or(0, Vec::len);
    (0..n)
        .map(|j| a.iter().map(|row| row[j].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// Reduces a square matrix to upper Hessenberg form by Householder reflections (an orthogonal
/// similarity, backward stable); returns the Hessenberg matrix. Matrices of order ≤ 2 are
/// already Hessenberg and are returned untouched, so the paper's plant is never perturbed.
fn hessenberg(mut a: Mat) -> Mat {
    let n = a.len();
    for k in 0..n.saturating_sub(2) {
        let alpha2: f64 = (k + 1..n).map(|i| a[i][k] * a[i][k]).sum();
        let tail2: f64 = (k + 2..n).map(|i| a[i][k] * a[i][k]).sum();
        if tail2 == 0.0 {
            continue;
        }
        let alpha = alpha2.sqrt().copysign(a[k + 1][k]);
        let mut v = vec![0.0; n];
        v[k + 1] = a[k + 1][k] + alpha;
        for i in k + 2..n {
            v[i] = a[i][k];
        }
        let vv: f64 = v.iter().map(|x| x * x).sum();
        // A ← H A H with H = I − 2 v vᵀ / vᵀv.
        let sums: Vec<f64> = (0..n)
            .map(|j| (k + 1..n).map(|i| v[i] * a[i][j]).sum::<f64>() * 2.0 / vv)
            .collect();
        for (i, row) in a.iter_mut().enumerate().skip(k + 1) {
            for (x, s) in row.iter_mut().zip(&sums) {
                *x -= s * v[i];
            }
        }
        for row in a.iter_mut() {
            let s: f64 = (k + 1..n).map(|j| row[j] * v[j]).sum::<f64>() * 2.0 / vv;
            for j in k + 1..n {
                row[j] -= s * v[j];
            }
        }
        for row in a.iter_mut().skip(k + 2) {
            row[k] = 0.0;
        }
    }
    a
}

/// The characteristic polynomial det(wI − A), monic, ascending coefficients: Householder
/// reduction to Hessenberg form, then the row recurrence of the leading principal minors
/// (Hyman's method). O(n³), backward stable for the small orders of haptic plants.
///
/// The rows may be any slices (a [`Mat`], or borrowed rows of a work buffer).
pub fn char_poly<R: AsRef<[f64]>>(a: &[R]) -> Vec<f64> {
    if a.len() > 2 {
        let owned: Mat = a.iter().map(|r| r.as_ref().to_vec()).collect();
        minors(&hessenberg(owned))
    } else {
        minors(a)
    }
}

/// det(wI − H) of an upper Hessenberg matrix by the row recurrence of its leading principal
/// minors (Hyman's method; [`char_poly`]).
fn minors<R: AsRef<[f64]>>(h: &[R]) -> Vec<f64> {
    let n = h.len();
    let h = |i: usize, j: usize| h[i].as_ref()[j];
    // Row j of q (stride n + 1) holds q_j(w) = det(wI − H[0..j, 0..j]), q_0 = 1.
    let stride = n + 1;
    let mut q = vec![0.0; stride * stride];
    q[0] = 1.0;
    for j in 0..n {
        // Expansion along column j: (w − h_jj) q_j − Σ_{i<j} h_ij (Π_{k=i+1..j} h_{k,k−1}) q_i.
        let (done, rest) = q.split_at_mut((j + 1) * stride);
        let next = &mut rest[..=j + 1];
        let qj = &done[j * stride..=j * stride + j];
        next[0] = -h(j, j) * qj[0];
        for m in 1..=j {
            next[m] = -h(j, j) * qj[m] + qj[m - 1];
        }
        next[j + 1] = qj[j];
        let mut prod = 1.0;
        for i in (0..j).rev() {
            prod *= h(i + 1, i);
            if prod == 0.0 {
                break;
            }
            let c = -h(i, j) * prod;
            for (x, qi) in next.iter_mut().zip(&done[i * stride..=i * stride + i]) {
                *x += c * qi;
            }
        }
    }
    q.drain(..n * stride);
    q
}

#[cfg(test)]
mod tests {
    use super::*;

    /// a1′a2 − a1a2′ of two cubics: the leading terms (3·a1₃)·a2₃ and a1₃·(3·a2₃) cancel in
    /// exact arithmetic, rounding leaves 1.1e-16 of them, and that is removed, so no root is
    /// placed near infinity; the other coefficients stay as they are.
    #[test]
    fn cancelled_leading_terms_are_trimmed() {
        let a1 = [-0.5, 0.9, 0.8, -0.9];
        let a2 = [-0.9, 0.1, 0.9, -0.2];
        let d = |c: &[f64]| -> Vec<f64> {
            c.iter()
                .enumerate()
                .skip(1)
                .map(|(j, &v)| v * j as f64)
                .collect()
        };
        let plain = add_scaled(&mul(&d(&a1), &a2), -1.0, &mul(&a1, &d(&a2)));
        let trimmed = mul_diff_trimmed(&d(&a1), &a2, &a1, &d(&a2));
        assert_eq!(plain.len(), 6);
        assert!(plain[5] != 0.0 && plain[5].abs() < 1e-15, "{plain:?}");
        assert_eq!(trimmed[..], plain[..5], "{trimmed:?}");
        // a small but genuine leading coefficient stays
        let kept = weighted_sum_trimmed(&[(1.0, &[1.0, 2.0, 1e-10]), (2.0, &[0.5, 0.0, 0.0])]);
        assert_eq!(kept, vec![2.0, 2.0, 1e-10]);
        // one that the sum cancels to rounding goes
        let gone = weighted_sum_trimmed(&[(1.0, &[1.0, 2.0, 0.1 + 0.2]), (-1.0, &[0.0, 0.0, 0.3])]);
        assert_eq!(gone, vec![1.0, 2.0]);
    }

    #[test]
    fn three_at_once_are_bit_for_bit_each_alone_at_every_shape() {
        let p: Vec<f64> = (0..10)
            .map(|i| (i as f64 * 1.7).sin() * 10f64.powi(i % 4))
            .collect();
        let z = Complex64::new(0.3, -0.95);
        // equal lengths, the family's shape (longer first, the two others equal), and others
        for (la, lb, lc) in [
            (9, 9, 9),
            (9, 7, 7),
            (8, 8, 2),
            (3, 9, 5),
            (1, 1, 1),
            (0, 4, 4),
        ] {
            let (a, b, c) = (&p[..la], &p[1..=lb], &p[..lc]);
            let [ea, eb, ec] = eval3(a, b, c, z);
            assert_eq!(
                (ea, eb, ec),
                (eval(a, z), eval(b, z), eval(c, z)),
                "{la} {lb} {lc}"
            );
        }
    }

    #[test]
    fn char_poly_of_companion_matrix() {
        // Companion matrix of (w − 1)(w − 2)(w + 3)(w − 0.5) = w⁴ − 0.5w³ − 7.5w² + 9.5w − 3.
        let c = [-3.0, 9.5, -7.5, -0.5, 1.0];
        let n = 4;
        let mut a = vec![vec![0.0; n]; n];
        for i in 1..n {
            a[i][i - 1] = 1.0;
        }
        for i in 0..n {
            a[i][n - 1] = -c[i];
        }
        // Scramble by a similarity with a non-orthogonal matrix so Householder has work to do.
        let s = vec![
            vec![1.0, 0.3, 0.0, 0.2],
            vec![0.0, 1.0, 0.5, 0.0],
            vec![0.1, 0.0, 1.0, 0.4],
            vec![0.0, 0.2, 0.0, 1.0],
        ];
        // inverse of s by Gauss–Jordan
        let mut aug: Vec<Vec<f64>> = s
            .iter()
            .enumerate()
            .map(|(i, r)| {
                let mut r = r.clone();
                r.extend((0..n).map(|j| if i == j { 1.0 } else { 0.0 }));
                r
            })
            .collect();
        for col in 0..n {
            let p = aug[col][col];
            for v in aug[col].iter_mut() {
                *v /= p;
            }
            for r in 0..n {
                if r != col {
                    let f = aug[r][col];
                    let pivot = aug[col].clone();
                    for (x, y) in aug[r].iter_mut().zip(pivot) {
                        *x -= f * y;
                    }
                }
            }
        }
        let sinv: Mat = aug.iter().map(|r| r[n..].to_vec()).collect();
        let b = mat_mul(&mat_mul(&s, &a), &sinv);
        let got = char_poly(&b);
        for (g, e) in got.iter().zip(c) {
            assert!((g - e).abs() < 1e-13, "{got:?}");
        }
    }

    #[test]
    fn taylor_shift_round_trip() {
        let p = [0.5, -2.0, 3.0, 1.0];
        let q = taylor_shift(&p, -1.0);
        // q(z) = p(z − 1): check at a few points
        for x in [-2.0, 0.3, 1.7] {
            let (a, _) = eval_real(&q, x);
            let (b, _) = eval_real(&p, x - 1.0);
            assert!((a - b).abs() < 1e-13);
        }
        let back = taylor_shift(&q, 1.0);
        for (a, b) in back.iter().zip(p) {
            assert!((a - b).abs() < 1e-14);
        }
    }
}
