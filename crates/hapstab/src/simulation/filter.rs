//! The loop's velocity estimator as the difference equation the simulator runs on the
//! sensed positions: T·V(z) = num(z)/den(z) of [`crate::VelocityEstimator::per_sample_filter`]
//! (den monic of degree m), so that
//!
//! ```text
//! v_j = Σ_i num_i · y_{j−(m−i)} − Σ_{i<m} den_i · v_{j−(m−i)}      (T·velocity, m/sample)
//! ```
//!
//! Only the nonzero taps are kept: `average:N` reads two positions whatever N, and the
//! paper's backward difference v_j = y_j − y_{j−1} is computed exactly as that difference.

/// The nonzero taps of the estimator's difference equation.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct VelocityFilter {
    /// (lag, coefficient) of the positions, oldest first.
    positions: Vec<(usize, f64)>,
    /// (lag ≥ 1, coefficient) of the past estimates, oldest first.
    estimates: Vec<(usize, f64)>,
    /// The degree m of den: the oldest sample the filter reads is m back.
    order: usize,
    /// The common difference form (backward, average): two position taps and no recursion,
    /// summed in the same order as the general form.
    two_taps: Option<[(usize, f64); 2]>,
}

impl VelocityFilter {
    /// The filter of T·V(z) = num/den (ascending powers of z, den monic).
    pub(super) fn new(num: &[f64], den: &[f64]) -> Self {
        let order = den.len().saturating_sub(1);
        let taps = |c: &[f64], upto: usize| -> Vec<(usize, f64)> {
            c.iter()
                .take(upto)
                .enumerate()
                .filter(|(_, x)| **x != 0.0)
                .map(|(i, &x)| (order - i, x))
                .collect()
        };
        let positions = taps(num, order + 1);
        let estimates = taps(den, order);
        let two_taps = match (positions.as_slice(), estimates.is_empty()) {
            (&[a, b], true) => Some([a, b]),
            _ => None,
        };
        Self {
            positions,
            estimates,
            order,
            two_taps,
        }
    }

    /// The degree m of the estimator's denominator.
    pub(super) fn order(&self) -> usize {
        self.order
    }

    /// True when the estimate depends on past estimates (an IIR filter).
    pub(super) fn recursive(&self) -> bool {
        !self.estimates.is_empty()
    }

    /// The estimate v_j from the positions `y(lag)` = y_{j−lag} and past estimates
    /// `v(lag)` = v_{j−lag}.
    #[inline(always)]
    pub(super) fn output(&self, y: impl Fn(usize) -> f64, v: impl Fn(usize) -> f64) -> f64 {
        if let Some([(l0, c0), (l1, c1)]) = self.two_taps {
            return 0.0 + c0 * y(l0) + c1 * y(l1);
        }
        let mut acc = 0.0;
        for &(lag, c) in &self.positions {
            acc += c * y(lag);
        }
        for &(lag, c) in &self.estimates {
            acc -= c * v(lag);
        }
        acc
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::VelocityEstimator;

    fn filter(v: &VelocityEstimator) -> VelocityFilter {
        let (n, d) = v.per_sample_filter(1e-3);
        VelocityFilter::new(&n, &d)
    }

    #[test]
    fn backward_difference_is_exact() {
        let f = filter(&VelocityEstimator::Backward);
        let ys = [0.1_f64, 0.30000000000000004];
        let v = f.output(|lag| ys[1 - lag], |_| f64::NAN);
        assert_eq!(v, ys[1] - ys[0]);
        assert!(!f.recursive());
        assert_eq!(f.order(), 1);
    }

    #[test]
    fn average_reads_two_positions() {
        let f = filter(&VelocityEstimator::Average { samples: 7 });
        assert_eq!(f.positions.len(), 2);
        let v = f.output(|lag| lag as f64 * -0.5, |_| f64::NAN);
        assert!((v - 0.5).abs() < 1e-15, "{v}");
    }

    #[test]
    fn lowpass_recursion() {
        let fc = 50.0;
        let f = filter(&VelocityEstimator::LowPass { cutoff_hz: fc });
        let a = (-2.0 * std::f64::consts::PI * fc * 1e-3).exp();
        let v = f.output(|lag| if lag == 0 { 2.0 } else { 1.0 }, |_| 0.25);
        assert!((v - (a * 0.25 + (1.0 - a) * 1.0)).abs() < 1e-15, "{v}");
        assert!(f.recursive());
    }
}
