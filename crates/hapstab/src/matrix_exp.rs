//! The matrix exponential and its integral, E(h) = e^{Ah} − I and Ψ(h) = ∫₀ʰ e^{As} ds, by a
//! scaled Taylor series of Ψ and exact doubling (Van Loan, "Computing integrals involving the
//! matrix exponential", IEEE TAC 23(3), 1978, for the pair; Moler & Van Loan, "Nineteen
//! dubious ways to compute the exponential of a matrix, twenty-five years later", SIAM Review
//! 45(1), 2003, §3 for scaling and squaring):
//!
//! ```text
//! Ψ(s) = s Σ_j (As)^j/(j + 1)!   (‖As‖₁ ≤ 1/2),   E(s) = A·Ψ(s),
//! Ψ(2s) = (2I + E(s))·Ψ(s),      E(2s) = E(s)·(2I + E(s)).
//! ```
//!
//! E is formed without I, so that e^{Ah} − I keeps its digits when ‖Ah‖ is small (the ZOH's
//! Φ − I near z = 1). The work runs on row-major buffers reused through the doublings.

use crate::poly::{self, Mat, SMALL_ORDER};

/// Taylor terms are summed until they fall below this fraction of the sum: one ulp.
const TAYLOR_REL: f64 = 1e-17;
/// Scaling target of the Taylor series: ‖A h‖ ≤ 1/2 makes 20 terms exact to 1e-19.
const TAYLOR_NORM: f64 = 0.5;
/// Taylor terms at most (‖As‖ ≤ 1/2 needs about 20).
const TAYLOR_TERMS: usize = 40;

/// E(h) = e^{Ah} − I and Ψ(h) = ∫₀ʰ e^{As} ds of the square matrix `a` (module doc).
pub fn exp_and_integral(a: &Mat, h: f64) -> (Mat, Mat) {
    with_exp(a, h, |e, psi, n| (rows(e, n), rows(psi, n)))
}

/// E(h) = e^{Ah} − I and the input Ψ(h)·b of a force held over h (the zero-order hold's
/// Γ0 = Ψ(1 − λ)B of [`crate::zoh`], which generalizes the paper's eq. (2)), without forming
/// Ψ's rows: [`exp_and_integral`] followed by [`poly::mat_vec`], the same operations.
pub fn exp_and_input(a: &Mat, h: f64, b: &[f64]) -> (Mat, Vec<f64>) {
    with_exp(a, h, |e, psi, n| {
        (rows(e, n), poly::rows_times(psi.chunks(n.max(1)), b))
    })
}

/// Computes E(h) and Ψ(h) (module doc) into row-major work buffers and hands them, with the
/// order n, to `done`.
fn with_exp<R>(a: &Mat, h: f64, done: impl FnOnce(&[f64], &[f64], usize) -> R) -> R {
    let n = a.len();
    if h == 0.0 {
        let zero = vec![0.0; n * n];
        return done(&zero, &zero, n);
    }
    let norm = poly::norm1(a) * h;
    let mut k = 0;
    while norm * 0.5_f64.powi(k) > TAYLOR_NORM && k < 1100 {
        k += 1;
    }
    let s = h * 0.5_f64.powi(k);
    // Five n × n work buffers, on the stack for the plants' usual orders.
    let mut small = [0.0; 5 * SMALL_ORDER * SMALL_ORDER];
    let mut large = Vec::new();
    let buf: &mut [f64] = if n <= SMALL_ORDER {
        &mut small[..5 * n * n]
    } else {
        large.resize(5 * n * n, 0.0);
        &mut large
    };
    let (flat, rest) = buf.split_at_mut(n * n);
    let (mut psi, rest) = rest.split_at_mut(n * n);
    let (mut e, rest) = rest.split_at_mut(n * n);
    let (mut next, scaled) = rest.split_at_mut(n * n);
    for (x, row) in flat.chunks_mut(n).zip(a) {
        x.copy_from_slice(row);
    }
    scaled
        .iter_mut()
        .zip(flat.iter())
        .for_each(|(x, a)| *x = a * s);
    psi_series(scaled, n, s, psi, e, next);
    mul_into(e, flat, psi, n);
    let two_plus_e = scaled;
    for _ in 0..k {
        two_plus_e.copy_from_slice(e);
        add_diagonal(two_plus_e, n, 2.0);
        mul_into(next, two_plus_e, psi, n);
        std::mem::swap(&mut psi, &mut next);
        mul_into(next, e, two_plus_e, n);
        std::mem::swap(&mut e, &mut next);
    }
    done(e, psi, n)
}

/// E(s + t) = E(s) + E(t) + E(s)·E(t) of E(s) = e^{As} − I and E(t): the doubling of the
/// module doc for two different steps (e^{A(s+t)} = e^{As}·e^{At}), formed without I like it.
pub fn exp_joined(e_s: &Mat, e_t: &Mat) -> Mat {
    let n = e_s.len();
    let flat = |m: &Mat| -> Vec<f64> { m.iter().flatten().copied().collect() };
    let (x, y) = (flat(e_s), flat(e_t));
    let mut out = vec![0.0; n * n];
    mul_into(&mut out, &x, &y, n);
    for ((o, a), b) in out.iter_mut().zip(&x).zip(&y) {
        *o += a + b;
    }
    rows(&out, n)
}

/// Ψ(s) = s Σ_j (As)^j/(j + 1)! into `sum`, for ‖As‖ ≤ 1/2 given as `as_` (row-major, order
/// n; `term` and `next` are work buffers).
fn psi_series(as_: &[f64], n: usize, s: f64, sum: &mut [f64], term: &mut [f64], next: &mut [f64]) {
    // The plants' usual orders get loops the compiler unrolls (the same operations).
    match n {
        2 => psi_fixed::<2>(as_, s, sum, term, next),
        3 => psi_fixed::<3>(as_, s, sum, term, next),
        4 => psi_fixed::<4>(as_, s, sum, term, next),
        _ => psi_order(as_, n, s, sum, term, next),
    }
}

/// [`psi_series`] for the order N known at compile time.
fn psi_fixed<const N: usize>(
    as_: &[f64],
    s: f64,
    sum: &mut [f64],
    term: &mut [f64],
    next: &mut [f64],
) {
    psi_order(as_, N, s, sum, term, next);
}

/// [`psi_series`]'s loop for order n.
#[inline(always)]
fn psi_order(as_: &[f64], n: usize, s: f64, sum: &mut [f64], term: &mut [f64], next: &mut [f64]) {
    // term = (As)^j / (j+1)!
    let (mut term, mut next) = (term, next);
    term.fill(0.0);
    add_diagonal(term, n, 1.0);
    sum.copy_from_slice(term);
    for j in 1..TAYLOR_TERMS {
        mul_order(next, as_, term, n);
        std::mem::swap(&mut term, &mut next);
        let f = 1.0 / (j + 1) as f64;
        term.iter_mut().for_each(|x| *x *= f);
        let tn = norm1(term, n);
        sum.iter_mut().zip(term.iter()).for_each(|(x, t)| *x += t);
        if tn <= TAYLOR_REL * norm1(sum, n) {
            break;
        }
    }
    sum.iter_mut().for_each(|x| *x *= s);
}

/// out = x·y for row-major square matrices of order n (the summation order of
/// [`poly::mat_mul`], zero entries of x skipped).
fn mul_into(out: &mut [f64], x: &[f64], y: &[f64], n: usize) {
    // The plants' usual orders get loops the compiler unrolls (the same operations).
    match n {
        2 => mul_fixed::<2>(out, x, y),
        3 => mul_fixed::<3>(out, x, y),
        4 => mul_fixed::<4>(out, x, y),
        _ => mul_order(out, x, y, n),
    }
}

/// [`mul_into`] for the order N known at compile time.
fn mul_fixed<const N: usize>(out: &mut [f64], x: &[f64], y: &[f64]) {
    mul_order(out, x, y, N);
}

/// [`mul_into`]'s loops for order n.
#[inline(always)]
fn mul_order(out: &mut [f64], x: &[f64], y: &[f64], n: usize) {
    out.fill(0.0);
    for i in 0..n {
        let row = &mut out[i * n..(i + 1) * n];
        for k in 0..n {
            let xik = x[i * n + k];
            if xik == 0.0 {
                continue;
            }
            for (o, yk) in row.iter_mut().zip(&y[k * n..(k + 1) * n]) {
                *o += xik * yk;
            }
        }
    }
}

/// m += c·I.
#[inline(always)]
fn add_diagonal(m: &mut [f64], n: usize, c: f64) {
    for i in 0..n {
        m[i * n + i] += c;
    }
}

/// The largest absolute column sum.
#[inline(always)]
fn norm1(m: &[f64], n: usize) -> f64 {
    (0..n)
        .map(|j| (0..n).map(|i| m[i * n + j].abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The row-major buffer as rows.
fn rows(m: &[f64], n: usize) -> Mat {
    m.chunks(n.max(1)).map(<[f64]>::to_vec).collect()
}
