//! The analog Bessel (Thomson) low-pass prototype normalized as scipy's
//! `besselap(N, norm='phase')`: the roots of the reverse Bessel polynomial
//! θ_N(s) = Σ_k a_k s^k, a_k = (2N − k)!/(2^{N−k} k! (N − k)!) (Thomson 1949; scipy's
//! `_bessel_poly`), scaled by a_0^{−1/N} so that the product of the poles' moduli is 1 and the
//! high-frequency asymptote is the Butterworth one's, with gain 1.
//!
//! The poles come from the zeros x of the ordinary Bessel polynomial y_N(x) = x^N θ_N(1/x)
//! as scipy's `_bessel_zeros` finds them: Campos and Calderón's (2011) fitted starting points,
//! the Aberth–Ehrlich iteration, a Newton polish (here with y_N evaluated in double-double
//! arithmetic, so each zero is accurate to the rounding of its own value), the conjugates
//! averaged to an exactly symmetric set, then p = 1/x.

use num_complex::Complex64;

/// Aberth–Ehrlich sweeps before the polish (scipy's `maxiter`); the fitted starting points
/// converge in a handful for every order up to [`super::MAX_ORDER`].
const MAX_SWEEPS: usize = 50;

/// Newton steps of the polish; quadratic convergence from the Aberth result needs two.
const POLISH_STEPS: usize = 4;

/// The coefficients a_0 … a_N of θ_N in ascending powers (exact integers in f64 for N ≤ 8:
/// a_0 = (2N)!/(2^N N!) = 2027025 at N = 8).
pub(super) fn reverse_bessel(order: usize) -> Vec<f64> {
    let fact = |n: usize| (1..=n as u64).product::<u64>();
    (0..=order)
        .map(|k| {
            let num = fact(2 * order - k);
            let den = (1u64 << (order - k)) * fact(k) * fact(order - k);
            (num / den) as f64
        })
        .collect()
}

/// The phase-normalized prototype's N poles (gain 1).
pub(super) fn poles(order: usize) -> Vec<Complex64> {
    let theta = reverse_bessel(order);
    // y_N(x) = x^N θ_N(1/x): the same coefficients, ascending powers read in reverse.
    let y: Vec<f64> = theta.iter().rev().copied().collect();
    let mut x = aberth(&y, campos_zeros(order));
    for xi in &mut x {
        for _ in 0..POLISH_STEPS {
            let (_, dp) = crate::poly::eval_with_derivative(&y, *xi);
            let step = eval_dd(&y, *xi) / dp;
            *xi -= step;
        }
    }
    let symmetric: Vec<Complex64> = (0..order)
        .map(|i| (x[i] + x[order - 1 - i].conj()) * 0.5)
        .collect();
    let a_last = theta[0];
    let scale = 10f64.powf(-a_last.log10() / order as f64);
    symmetric.iter().map(|xi| xi.inv() * scale).collect()
}

/// Campos and Calderón's (2011) polynomial fit of the zeros of y_N, scipy's `_campos_zeros`:
/// x_k = a1·k + a2·k² + i(b0 + b1·k + b2·k² + b3·k³), k = 1 … N.
fn campos_zeros(order: usize) -> Vec<Complex64> {
    if order == 1 {
        return vec![Complex64::new(-1.0, 0.0)];
    }
    let n = order as f64;
    let s = 2.0 * n.powi(2) - 3.0 * n.powi(4) + n.powi(5);
    let b3 = (16.0 - 8.0 * n) / s;
    let b2 = (-24.0 - 12.0 * n + 12.0 * n * n) / s;
    let b1 = (8.0 + 24.0 * n - 12.0 * n * n - 2.0 * n.powi(3)) / s;
    let b0 = (-6.0 * n + 5.0 * n.powi(3) - n.powi(4)) / s;
    let r = 2.0 * n * n + n.powi(3);
    let (a1, a2) = ((-6.0 - 6.0 * n) / r, 6.0 / r);
    (1..=order)
        .map(|k| {
            let k = k as f64;
            Complex64::new(a1 * k + a2 * k * k, b0 + k * (b1 + k * (b2 + k * b3)))
        })
        .collect()
}

/// The Aberth–Ehrlich iteration on the polynomial with ascending coefficients `c` from the
/// starting points `x`, until every Newton correction is below 1e-15 (scipy's `_aberth`).
fn aberth(c: &[f64], mut x: Vec<Complex64>) -> Vec<Complex64> {
    for _ in 0..MAX_SWEEPS {
        let alpha: Vec<Complex64> = x
            .iter()
            .map(|&xi| {
                let (p, dp) = crate::poly::eval_with_derivative(c, xi);
                -p / dp
            })
            .collect();
        let beta: Vec<Complex64> = (0..x.len())
            .map(|k| {
                (0..x.len())
                    .filter(|&j| j != k)
                    .map(|j| (x[k] - x[j]).inv())
                    .sum()
            })
            .collect();
        for k in 0..x.len() {
            x[k] += alpha[k] / (1.0 + alpha[k] * beta[k]);
        }
        if alpha.iter().all(|a| a.norm() <= 1e-15) {
            break;
        }
    }
    x
}

/// A double-double number hi + lo, |lo| ≤ ulp(hi)/2 (Dekker 1971).
#[derive(Clone, Copy)]
struct Dd {
    hi: f64,
    lo: f64,
}

impl Dd {
    fn renormalized(hi: f64, lo: f64) -> Self {
        let s = hi + lo;
        Dd {
            hi: s,
            lo: lo - (s - hi),
        }
    }

    /// a + b, Knuth's two-sum on the leading parts.
    fn add(self, b: Dd) -> Dd {
        let s = self.hi + b.hi;
        let v = s - self.hi;
        let e = (self.hi - (s - v)) + (b.hi - v);
        Dd::renormalized(s, e + self.lo + b.lo)
    }

    /// a·b for a double b, the leading product exact by a fused multiply-add.
    fn mul(self, b: f64) -> Dd {
        let p = self.hi * b;
        let e = self.hi.mul_add(b, -p);
        Dd::renormalized(p, e + self.lo * b)
    }

    fn neg(self) -> Dd {
        Dd {
            hi: -self.hi,
            lo: -self.lo,
        }
    }
}

/// p(z) for ascending real coefficients `c` by Horner's rule in double-double complex
/// arithmetic (z exact as given), rounded to a double at the end.
fn eval_dd(c: &[f64], z: Complex64) -> Complex64 {
    let zero = Dd { hi: 0.0, lo: 0.0 };
    let (re, im) = c.iter().rev().fold((zero, zero), |(re, im), &ci| {
        let new_re = re.mul(z.re).add(im.mul(z.im).neg());
        let new_im = re.mul(z.im).add(im.mul(z.re));
        (new_re.add(Dd { hi: ci, lo: 0.0 }), new_im)
    });
    Complex64::new(re.hi + re.lo, im.hi + im.lo)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// θ_N's coefficients against the table of Bessel polynomials (OEIS A001498; scipy's
    /// `_bessel_poly` docstring): θ_4 = s⁴ + 10s³ + 45s² + 105s + 105, θ_5's constant 945.
    #[test]
    fn reverse_bessel_coefficients() {
        assert_eq!(reverse_bessel(1), vec![1.0, 1.0]);
        assert_eq!(reverse_bessel(3), vec![15.0, 15.0, 6.0, 1.0]);
        assert_eq!(reverse_bessel(4), vec![105.0, 105.0, 45.0, 10.0, 1.0]);
        assert_eq!(reverse_bessel(5)[0], 945.0);
        assert_eq!(reverse_bessel(8)[0], 2_027_025.0);
    }

    /// Delay-normalized poles (the roots of θ_N, before the phase scaling) against the
    /// published tables (Thomson 1949; Bond, "Bessel Filter Polynomials, Poles and Circuit
    /// Elements", 2003): N = 3: −2.3222, −1.8389 ± 1.7544i; N = 4: −2.8962 ± 0.8672i,
    /// −2.1038 ± 2.6574i; and N = 1, 2 in closed form: −1 and −√3/2 ± i/2 after scaling.
    #[test]
    fn poles_match_the_tables() {
        let unscale = |order: usize| {
            let a0 = reverse_bessel(order)[0];
            a0.powf(1.0 / order as f64)
        };
        let sorted = |order: usize| {
            let k = unscale(order);
            let mut p: Vec<Complex64> = poles(order).iter().map(|p| p * k).collect();
            p.sort_by(|a, b| a.im.total_cmp(&b.im));
            p
        };
        let want3 = [(-1.8389, -1.7544), (-2.3222, 0.0), (-1.8389, 1.7544)];
        let want4 = [
            (-2.1038, -2.6574),
            (-2.8962, -0.8672),
            (-2.8962, 0.8672),
            (-2.1038, 2.6574),
        ];
        for (order, want) in [(3, &want3[..]), (4, &want4[..])] {
            for (p, &(re, im)) in sorted(order).iter().zip(want) {
                assert!((p.re - re).abs() < 1e-4 && (p.im - im).abs() < 1e-4, "{p}");
            }
        }
        assert!((poles(1)[0] + 1.0).norm() < 1e-15);
        let h = 3f64.sqrt() / 2.0;
        for p in poles(2) {
            assert!(
                (p.re + h).abs() < 1e-15 && (p.im.abs() - 0.5).abs() < 1e-15,
                "{p}"
            );
        }
    }

    /// For every order the scaled-back poles are the roots of θ_N: Π(s − a_0^{1/N}p_k)
    /// reproduces its integer coefficients, and the scaled poles' product is 1 (gain 1 at DC).
    #[test]
    fn poles_are_the_roots_of_theta() {
        for order in 1..=super::super::MAX_ORDER {
            let theta = reverse_bessel(order);
            let k = theta[0].powf(1.0 / order as f64);
            let mut c = vec![Complex64::new(1.0, 0.0)];
            for p in poles(order) {
                let mut next = vec![Complex64::new(0.0, 0.0); c.len() + 1];
                for (i, &ci) in c.iter().enumerate() {
                    next[i] -= ci * p * k;
                    next[i + 1] += ci;
                }
                c = next;
            }
            for (got, want) in c.iter().zip(&theta) {
                assert!(
                    (got.re - want).abs() <= 1e-13 * want && got.im.abs() <= 1e-13 * want,
                    "order {order}: {c:?} vs {theta:?}"
                );
            }
            let prod: Complex64 = poles(order).iter().map(|p| -p).product();
            assert!((prod - 1.0).norm() < 1e-14, "order {order}: {prod}");
        }
    }
}
