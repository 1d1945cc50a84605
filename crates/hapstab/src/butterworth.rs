//! The digital Butterworth low-pass of a velocity estimator `butterworth:N:FC`: the analog
//! prototype of order N with poles −e^{iπm/(2N)}, m = −N+1, −N+3, …, N−1, scaled to the
//! pre-warped cut-off ω_a = 2f_s·tan(π f_c/f_s) and mapped by the bilinear transform
//! z = (2f_s + s)/(2f_s − s) — the design of MATLAB's and scipy's `butter(N, f_c, fs=1/T)`,
//! step for step (prototype, lp2lp, bilinear, zpk → tf), so that the coefficients agree with
//! theirs to rounding. The estimator filters the backward difference:
//! V(z) = H(z)·(1 − z⁻¹)/T.

use num_complex::Complex64;

/// Largest filter order.
pub const MAX_ORDER: usize = 8;

/// The polynomial with the given roots, highest power first (numpy's `poly`).
fn poly(roots: &[Complex64]) -> Vec<Complex64> {
    let mut c = vec![Complex64::new(1.0, 0.0)];
    for &r in roots {
        let mut next = c.clone();
        next.push(Complex64::new(0.0, 0.0));
        for (i, &ci) in c.iter().enumerate() {
            next[i + 1] -= r * ci;
        }
        c = next;
    }
    c
}

/// The low-pass H(z) = b(z⁻¹)/a(z⁻¹) of order `order` with cut-off `cutoff_hz` at sampling
/// period `period` (scipy's `butter(order, cutoff_hz, fs=1/period)`): (b, a) in powers of
/// z⁻¹, a0 = 1. Needs 1 ≤ order ≤ [`MAX_ORDER`] and 0 < f_c < 1/(2T).
pub fn lowpass(order: usize, cutoff_hz: f64, period: f64) -> (Vec<f64>, Vec<f64>) {
    use std::f64::consts::PI;
    let n = order as f64;
    // scipy normalizes to fs = 2: Wn = f_c/(f_s/2), warped = 2·fs·tan(π·Wn/fs)
    let fs = 2.0;
    let wn = cutoff_hz * 2.0 * period;
    let warped = 2.0 * fs * (PI * wn / fs).tan();
    let prototype: Vec<Complex64> = (0..order)
        .map(|i| {
            let m = -(n - 1.0) + 2.0 * i as f64;
            -Complex64::from_polar(1.0, PI * m / (2.0 * n))
        })
        .collect();
    let poles: Vec<Complex64> = prototype.iter().map(|p| p * warped).collect();
    let k_analog = warped.powi(order as i32);
    let fs2 = 2.0 * fs;
    let z_poles: Vec<Complex64> = poles.iter().map(|p| (fs2 + p) / (fs2 - p)).collect();
    let z_zeros = vec![Complex64::new(-1.0, 0.0); order];
    let denom = poles
        .iter()
        .fold(Complex64::new(1.0, 0.0), |acc, p| acc * (fs2 - p));
    let k = k_analog * (Complex64::new(1.0, 0.0) / denom).re;
    let b = poly(&z_zeros).iter().map(|c| k * c.re).collect();
    let a = poly(&z_poles).iter().map(|c| c.re).collect();
    (b, a)
}

/// The velocity estimator's filter in powers of z⁻¹, as an `iir:` spec takes it: the
/// low-pass applied to the backward difference, (b·(1 − z⁻¹)/T, a).
pub fn velocity_filter(order: usize, cutoff_hz: f64, period: f64) -> (Vec<f64>, Vec<f64>) {
    let (b, a) = lowpass(order, cutoff_hz, period);
    let mut num = vec![0.0; b.len() + 1];
    for (i, &bi) in b.iter().enumerate() {
        num[i] += bi / period;
        num[i + 1] -= bi / period;
    }
    (num, a)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// First order: the bilinear map of ω_a/(s + ω_a) in closed form,
    /// H(z) = g(1 + z⁻¹)/(1 + c z⁻¹) with t = tan(π f_c T), g = t/(1 + t), c = (t − 1)/(t + 1).
    #[test]
    fn first_order_is_the_closed_form() {
        let (fc, t) = (150.0, 1e-3);
        let (b, a) = lowpass(1, fc, t);
        let w = (std::f64::consts::PI * fc * t).tan();
        let (g, c) = (w / (1.0 + w), (w - 1.0) / (w + 1.0));
        for (x, y) in b.iter().zip([g, g]) {
            assert!((x - y).abs() < 1e-15, "{b:?}");
        }
        assert!(
            (a[0] - 1.0).abs() < 1e-15 && (a[1] - c).abs() < 1e-15,
            "{a:?}"
        );
    }

    /// Unit gain at DC for every order: Σb = Σa, to the rounding of sums whose terms (up to
    /// Σ|a|) cancel to a small total when the poles crowd z = 1.
    #[test]
    fn unit_dc_gain() {
        for order in 1..=MAX_ORDER {
            let (b, a) = lowpass(order, 80.0, 1e-3);
            let (sb, sa): (f64, f64) = (b.iter().sum(), a.iter().sum());
            let size: f64 = a.iter().map(|x| x.abs()).sum();
            assert!(sa > 0.0, "order {order}");
            assert!(
                (sb - sa).abs() < 1e-13 * size,
                "order {order}: {sb} vs {sa}"
            );
        }
    }
}
