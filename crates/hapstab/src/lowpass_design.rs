//! The named digital low-pass filters of a velocity estimator — `butterworth:N:FC`,
//! `bessel:N:FC` and `critically-damped:N:FC` — designed on one path, that of scipy's
//! `iirfilter(N, f_c, btype='low', fs=1/T)` (for Butterworth also MATLAB's `butter`):
//!
//! 1. the family's analog prototype (no zeros, N poles p_k, gain k) for 1 rad/s;
//! 2. `lp2lp`: the cut-off pre-warped to ω_a = 2f_s·tan(π W_n/f_s) with scipy's
//!    normalization f_s = 2, W_n = 2f_c·T, poles ω_a·p_k and gain k·ω_a^N;
//! 3. `bilinear`: z = (2f_s + s)/(2f_s − s), poles (2f_s + p)/(2f_s − p), N zeros at −1,
//!    gain k·Re(1/Π(2f_s − p));
//! 4. `zpk2tf`: b = gain·Π(1 + z⁻¹), a = Π(1 − p_z z⁻¹),
//!
//! step for step, so that the coefficients agree with scipy's to rounding. The prototypes:
//!
//! - Butterworth (scipy's `buttap`): p_m = −e^{iπm/(2N)}, m = −N+1, −N+3, …, N−1, k = 1.
//! - Bessel (scipy's `besselap(N, norm='phase')`, the `bessel` submodule): the roots of the
//!   reverse Bessel polynomial scaled to unit product, k = 1.
//! - Critically damped: N equal real poles −α, α = 1/√(2^{1/N} − 1), k = α^N — the cascade of
//!   N first-order sections (1 + s/α)^{−N} whose |H(iω)|² = (1 + ω²/α²)^{−N} is 1/2 at ω = 1,
//!   so the cascade's −3 dB point is the cut-off (Robertson and Dowling, "Design and responses
//!   of Butterworth and critically damped digital filters", J. Electromyogr. Kinesiol. 13,
//!   2003, the correction factor C = √(2^{1/N} − 1) of N cascaded passes).
//!
//! The estimator filters the backward difference: V(z) = H(z)·(1 − z⁻¹)/T.

mod bessel;

use num_complex::Complex64;

use crate::error::{Error, Result};
use crate::model::VelocityEstimator;
use crate::param::Param;

/// Largest filter order of every family.
pub const MAX_ORDER: usize = 8;

/// A family of analog low-pass prototypes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Maximally flat magnitude (scipy's `butter`).
    Butterworth,
    /// Maximally flat group delay, phase-normalized (scipy's `bessel`, `norm='phase'`).
    Bessel,
    /// N equal real poles, −3 dB at the cut-off (no overshoot in the step response).
    CriticallyDamped,
}

impl Family {
    /// Every family, in the order the help texts list them.
    pub const ALL: [Family; 3] = [
        Family::Butterworth,
        Family::Bessel,
        Family::CriticallyDamped,
    ];

    /// The spec's keyword: `butterworth`, `bessel` or `critically-damped`.
    pub fn keyword(self) -> &'static str {
        match self {
            Family::Butterworth => "butterworth",
            Family::Bessel => "bessel",
            Family::CriticallyDamped => "critically-damped",
        }
    }

    /// The family of a spec keyword (ASCII case-insensitive), if it names one.
    pub fn from_keyword(word: &str) -> Option<Self> {
        Family::ALL
            .into_iter()
            .find(|f| f.keyword().eq_ignore_ascii_case(word))
    }

    fn order_param(self) -> Param {
        match self {
            Family::Butterworth => Param::ButterworthOrder,
            Family::Bessel => Param::BesselOrder,
            Family::CriticallyDamped => Param::CriticallyDampedOrder,
        }
    }

    fn cutoff_param(self) -> Param {
        match self {
            Family::Butterworth => Param::ButterworthCutoff,
            Family::Bessel => Param::BesselCutoff,
            Family::CriticallyDamped => Param::CriticallyDampedCutoff,
        }
    }

    /// The analog prototype for a cut-off of 1 rad/s: its N poles and gain k,
    /// H(s) = k/Π(s − p_k) (formulas in the module's documentation). 1 ≤ order ≤ [`MAX_ORDER`].
    pub fn prototype(self, order: usize) -> (Vec<Complex64>, f64) {
        use std::f64::consts::PI;
        let n = order as f64;
        match self {
            Family::Butterworth => {
                let poles = (0..order)
                    .map(|i| {
                        let m = -(n - 1.0) + 2.0 * i as f64;
                        -Complex64::from_polar(1.0, PI * m / (2.0 * n))
                    })
                    .collect();
                (poles, 1.0)
            }
            Family::Bessel => (bessel::poles(order), 1.0),
            Family::CriticallyDamped => {
                let alpha = 1.0 / (2f64.powf(1.0 / n) - 1.0).sqrt();
                (vec![Complex64::new(-alpha, 0.0); order], alpha.powf(n))
            }
        }
    }
}

/// A named low-pass: family, order N and cut-off f_c in Hz.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NamedLowPass {
    /// The prototype family.
    pub family: Family,
    /// Order N, 1 ..= [`MAX_ORDER`].
    pub order: usize,
    /// Cut-off f_c in Hz, 0 < f_c < 1/(2T).
    pub cutoff_hz: f64,
}

impl NamedLowPass {
    /// The filter of this family, order and cut-off (unchecked: see [`Self::validated`]).
    pub const fn new(family: Family, order: usize, cutoff_hz: f64) -> Self {
        Self {
            family,
            order,
            cutoff_hz,
        }
    }

    /// Checks 1 ≤ N ≤ 8 and f_c > 0, naming the family's parameter.
    pub fn validated(self) -> Result<Self> {
        crate::error::positive(self.family.cutoff_param(), self.cutoff_hz)?;
        if !(1..=MAX_ORDER).contains(&self.order) {
            return Err(Error::OutOfRange {
                param: self.family.order_param(),
                value: self.order as f64,
                range: "1..=8",
            });
        }
        Ok(self)
    }

    /// Refuses a cut-off at or beyond the Nyquist frequency 1/(2T) of the period.
    pub fn within_nyquist(self, period: f64) -> Result<Self> {
        if self.cutoff_hz * 2.0 * period >= 1.0 {
            return Err(Error::Invalid {
                param: self.family.cutoff_param(),
                reason: format!(
                    "must be below the Nyquist frequency 1/(2T) = {} Hz (got {} Hz)",
                    0.5 / period,
                    self.cutoff_hz
                ),
            });
        }
        Ok(self)
    }

    /// The low-pass H(z) = b(z⁻¹)/a(z⁻¹) at sampling period `period` (scipy's
    /// `iirfilter(N, f_c, btype='low', ftype=…, fs=1/T)`, steps 1–4 of the module's
    /// documentation): (b, a) in powers of z⁻¹, a0 = 1. Needs a validated filter with
    /// 0 < f_c < 1/(2T).
    pub fn lowpass(&self, period: f64) -> (Vec<f64>, Vec<f64>) {
        use std::f64::consts::PI;
        let (prototype, k_proto) = self.family.prototype(self.order);
        // scipy normalizes to fs = 2: Wn = f_c/(f_s/2), warped = 2·fs·tan(π·Wn/fs)
        let fs = 2.0;
        let wn = self.cutoff_hz * 2.0 * period;
        let warped = 2.0 * fs * (PI * wn / fs).tan();
        // lp2lp_zpk
        let poles: Vec<Complex64> = prototype.iter().map(|p| p * warped).collect();
        let k_analog = k_proto * warped.powf(self.order as f64);
        // bilinear_zpk
        let fs2 = 2.0 * fs;
        let z_poles: Vec<Complex64> = poles.iter().map(|p| (fs2 + p) / (fs2 - p)).collect();
        let z_zeros = vec![Complex64::new(-1.0, 0.0); self.order];
        let denom = poles
            .iter()
            .fold(Complex64::new(1.0, 0.0), |acc, p| acc * (fs2 - p));
        let k = k_analog * (Complex64::new(1.0, 0.0) / denom).re;
        // zpk2tf
        let b = poly(&z_zeros).iter().map(|c| k * c.re).collect();
        let a = poly(&z_poles).iter().map(|c| c.re).collect();
        (b, a)
    }

    /// The velocity estimator's filter in powers of z⁻¹, as an `iir:` spec takes it: the
    /// low-pass applied to the backward difference, (b·(1 − z⁻¹)/T, a).
    pub fn velocity_filter(&self, period: f64) -> (Vec<f64>, Vec<f64>) {
        let (b, a) = self.lowpass(period);
        let mut num = vec![0.0; b.len() + 1];
        for (i, &bi) in b.iter().enumerate() {
            num[i] += bi / period;
            num[i + 1] -= bi / period;
        }
        (num, a)
    }

    /// The estimator as [`VelocityEstimator::per_sample_filter`] gives it: the
    /// [`Self::velocity_filter`] as an `iir:` filter, in ascending powers of z, scaled by T.
    pub fn per_sample_filter(&self, period: f64) -> (Vec<f64>, Vec<f64>) {
        let (b, a) = self.velocity_filter(period);
        VelocityEstimator::Iir { b, a }.per_sample_filter(period)
    }
}

impl From<NamedLowPass> for VelocityEstimator {
    fn from(f: NamedLowPass) -> Self {
        let (order, cutoff_hz) = (f.order, f.cutoff_hz);
        match f.family {
            Family::Butterworth => VelocityEstimator::Butterworth { order, cutoff_hz },
            Family::Bessel => VelocityEstimator::Bessel { order, cutoff_hz },
            Family::CriticallyDamped => VelocityEstimator::CriticallyDamped { order, cutoff_hz },
        }
    }
}

impl VelocityEstimator {
    /// The named low-pass of a `butterworth:`, `bessel:` or `critically-damped:` estimator.
    pub fn named_lowpass(&self) -> Option<NamedLowPass> {
        let (family, order, cutoff_hz) = match *self {
            VelocityEstimator::Butterworth { order, cutoff_hz } => {
                (Family::Butterworth, order, cutoff_hz)
            }
            VelocityEstimator::Bessel { order, cutoff_hz } => (Family::Bessel, order, cutoff_hz),
            VelocityEstimator::CriticallyDamped { order, cutoff_hz } => {
                (Family::CriticallyDamped, order, cutoff_hz)
            }
            _ => return None,
        };
        Some(NamedLowPass::new(family, order, cutoff_hz))
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    fn lowpass(family: Family, order: usize, fc: f64, t: f64) -> (Vec<f64>, Vec<f64>) {
        let f = NamedLowPass::new(family, order, fc);
        f.validated().unwrap().within_nyquist(t).unwrap().lowpass(t)
    }

    /// |H(e^{iωT})| from (b, a) in powers of z⁻¹.
    fn gain(b: &[f64], a: &[f64], hz: f64, t: f64) -> f64 {
        let z1 = Complex64::from_polar(1.0, -2.0 * std::f64::consts::PI * hz * t);
        let eval = |c: &[f64]| {
            c.iter()
                .rev()
                .fold(Complex64::new(0.0, 0.0), |s, &x| s * z1 + x)
        };
        (eval(b) / eval(a)).norm()
    }

    /// First order: the bilinear map of ω/(s + ω) with ω = α·ω_a in closed form,
    /// H(z) = g(1 + z⁻¹)/(1 + c z⁻¹), t = α·tan(π f_c T), g = t/(1 + t), c = (t − 1)/(t + 1);
    /// α = 1 for Butterworth and Bessel (both are 1/(s + 1) at N = 1) and
    /// α = 1/√(2 − 1) = 1 for the critically damped filter.
    #[test]
    fn first_order_is_the_closed_form() {
        let (fc, t) = (150.0, 1e-3);
        for family in Family::ALL {
            let (b, a) = lowpass(family, 1, fc, t);
            let w = (std::f64::consts::PI * fc * t).tan();
            let (g, c) = (w / (1.0 + w), (w - 1.0) / (w + 1.0));
            for (x, y) in b.iter().zip([g, g]) {
                assert!((x - y).abs() < 1e-15, "{family:?}: {b:?}");
            }
            assert!(
                (a[0] - 1.0).abs() < 1e-15 && (a[1] - c).abs() < 1e-15,
                "{family:?}: {a:?}"
            );
        }
    }

    /// Second-order critically damped filter in closed form: two poles at −α·ω_a,
    /// α = 1/√(√2 − 1), mapped by the bilinear transform with t = α·tan(π f_c T):
    /// H(z) = (t/(1 + t))²(1 + z⁻¹)²/(1 + c z⁻¹)², c = (t − 1)/(t + 1).
    #[test]
    fn second_order_critically_damped_is_the_closed_form() {
        let (fc, t) = (40.0, 5e-4);
        let (b, a) = lowpass(Family::CriticallyDamped, 2, fc, t);
        let alpha = 1.0 / (2f64.sqrt() - 1.0).sqrt();
        let w = alpha * (std::f64::consts::PI * fc * t).tan();
        let (g, c) = (w / (1.0 + w), (w - 1.0) / (w + 1.0));
        let (wb, wa) = ([g * g, 2.0 * g * g, g * g], [1.0, 2.0 * c, c * c]);
        for (x, y) in b.iter().zip(wb).chain(a.iter().zip(wa)) {
            assert!((x - y).abs() < 1e-14 * y.abs().max(1.0), "{b:?} {a:?}");
        }
    }

    /// Unit gain at DC for every family and order: Σb = Σa, to the rounding of sums whose
    /// terms (up to Σ|a|) cancel to a small total when the poles crowd z = 1.
    #[test]
    fn unit_dc_gain() {
        for family in Family::ALL {
            for order in 1..=MAX_ORDER {
                let (b, a) = lowpass(family, order, 80.0, 1e-3);
                let (sb, sa): (f64, f64) = (b.iter().sum(), a.iter().sum());
                let size: f64 = a.iter().map(|x| x.abs()).sum();
                assert!(sa > 0.0, "{family:?} order {order}");
                assert!(
                    (sb - sa).abs() < 1e-13 * size,
                    "{family:?} order {order}: {sb} vs {sa}"
                );
            }
        }
    }

    /// The pre-warping puts the analog −3 dB point exactly on f_c: Butterworth's and the
    /// critically damped cascade's |H| is 1/√2 there, for every order.
    #[test]
    fn half_power_at_the_cutoff() {
        let (fc, t) = (120.0, 1e-3);
        for order in 1..=MAX_ORDER {
            for family in [Family::Butterworth, Family::CriticallyDamped] {
                let (b, a) = lowpass(family, order, fc, t);
                let g = gain(&b, &a, fc, t);
                assert!((g - 0.5f64.sqrt()).abs() < 1e-12, "{family:?} {order}: {g}");
            }
        }
    }

    #[test]
    fn refusals_name_the_family_and_parameter() {
        let f = NamedLowPass::new;
        let e = f(Family::Bessel, 9, 50.0).validated().unwrap_err();
        assert!(e.to_string().contains("Bessel order N"), "{e}");
        let e = f(Family::CriticallyDamped, 0, 50.0)
            .validated()
            .unwrap_err();
        assert!(e.to_string().contains("critically damped order N"), "{e}");
        let e = f(Family::Bessel, 2, 500.0)
            .within_nyquist(1e-3)
            .unwrap_err();
        assert!(e.to_string().contains("Nyquist"), "{e}");
        assert_eq!(
            Family::from_keyword("Critically-Damped"),
            Some(Family::CriticallyDamped)
        );
        assert_eq!(Family::from_keyword("chebyshev"), None);
    }
}
