//! What the fit is worth: the parameters' standard errors and 95 % intervals from the
//! Jacobian at the optimum, the fit's NRMSE, and the residual tests.
//!
//! **Covariance.** With white measurement noise, the output-error estimate is asymptotically
//! normal with covariance σ²(JᵀJ)⁻¹ in the optimiser's coordinates, σ² = Σe²/(N − p) (Ljung
//! 1999, §9.3, eq. 9.17–9.18), floored at the quantization's q²/12 when the position is
//! rounded to steps of q (the rounding error's variance, Widrow & Kollár, *Quantization
//! Noise*, 2008, ch. 4: the residuals of a model that is right cannot be smaller). A positive parameter's interval is e^{x ± z·se(x)}, positive
//! and skewed as its log-normal law; its standard error is the delta method's θ·se(x). A real
//! parameter's is θ ± z·se, z = [`Z_95`].
//!
//! **Residual tests** (Ljung 1999, §16.6): the residuals' autocorrelation at lags 1..M
//! (Ljung–Box, Q = N(N+2)Σ r_k²/(N − k) ~ χ²(M)) and their cross-correlation with the force
//! at lags 0..M (S = NΣ r_eu(τ)² ~ χ²(M+1)); each passes below the χ² 95 % quantile
//! (Wilson–Hilferty's approximation, within 0.5 % for M ≥ 10).

use nalgebra::DMatrix;
use serde::Serialize;

use super::error::{IdResult, IdentifyError};
use super::output_error::Coord;

/// The standard normal's 97.5 % quantile: a two-sided 95 % interval.
pub const Z_95: f64 = 1.959_963_984_540_054;

/// Lags M of the residual tests (Ljung 1999's default of 20 for a few thousand samples).
pub const TEST_LAGS: usize = 20;

/// Largest NRMSE reported as a fit: a model that leaves more than half of the position's
/// variation unexplained has not found the plant, and its parameters mean nothing.
pub const MAX_NRMSE: f64 = 0.5;

/// One parameter as identified.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Estimate {
    /// Its name.
    pub name: String,
    /// Its SI unit.
    pub unit: String,
    /// The estimate (or the held value).
    pub value: f64,
    /// True when it was held at a known value.
    pub fixed: bool,
    /// Standard error (None when held).
    pub standard_error: Option<f64>,
    /// 95 % confidence interval (None when held).
    pub ci95: Option<[f64; 2]>,
}

/// The fit's quality.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitQuality {
    /// ‖y − ŷ‖/‖y − ȳ‖.
    pub nrmse: f64,
    /// 100·(1 − NRMSE), as MATLAB's `compare` reports it.
    pub fit_percent: f64,
    /// RMS of the residuals in m.
    pub residual_rms: f64,
    /// Samples fitted.
    pub samples: usize,
}

/// A χ² test on correlations.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CorrelationTest {
    /// Lags M.
    pub lags: usize,
    /// The statistic.
    pub statistic: f64,
    /// Its 95 % quantile under the hypothesis of no correlation.
    pub threshold: f64,
    /// True when the statistic is below the threshold.
    pub passes: bool,
}

/// The covariance of the optimiser's coordinates, σ²(JᵀJ)⁻¹ with σ² = max(Σe²/(N − p),
/// `floor`) (module doc), computed on the Jacobian scaled to unit columns; refused when JᵀJ
/// is singular (the recording does not tell the parameters apart), naming the coordinate
/// with the least information.
pub fn covariance(
    jacobian: &[Vec<f64>],
    residual_ss: f64,
    floor: f64,
    names: &[String],
) -> IdResult<DMatrix<f64>> {
    let (n, p, norms, inv) = scaled_inverse(jacobian, names)?;
    let sigma2 = (residual_ss / (n - p) as f64).max(floor);
    Ok(DMatrix::from_fn(p, p, |a, b| {
        sigma2 * inv[(a, b)] / (norms[a] * norms[b])
    }))
}

/// The covariance of the optimiser's coordinates when the residuals come in `groups`
/// interleaved kinds of different noise (residual i of kind i mod `groups`: a frequency
/// response's log-magnitude and phase errors, Pintelon & Schoukens 2012, §9.4): each kind's
/// variance σ_g² = Σ_{i∈g} e_i²/(N_g − p·N_g/N), and the least-squares estimate's covariance
/// (JᵀJ)⁻¹ (Σ_i σ²_{g(i)} J_iᵀJ_i) (JᵀJ)⁻¹ (the sandwich, White 1980, *Econometrica* 48,
/// eq. 3; σ²(JᵀJ)⁻¹ when all kinds share one variance).
pub fn grouped_covariance(
    jacobian: &[Vec<f64>],
    residuals: &[f64],
    groups: usize,
    names: &[String],
) -> IdResult<DMatrix<f64>> {
    let (n, p, norms, inv) = scaled_inverse(jacobian, names)?;
    let variance: Vec<f64> = (0..groups)
        .map(|g| {
            let e: Vec<f64> = residuals.iter().skip(g).step_by(groups).copied().collect();
            let dof = e.len() as f64 * (1.0 - p as f64 / n as f64);
            e.iter().map(|x| x * x).sum::<f64>() / dof
        })
        .collect();
    let meat = DMatrix::from_fn(p, p, |a, b| {
        (0..n)
            .map(|i| variance[i % groups] * jacobian[a][i] * jacobian[b][i])
            .sum::<f64>()
            / (norms[a] * norms[b])
    });
    let sandwich = &inv * meat * &inv;
    Ok(DMatrix::from_fn(p, p, |a, b| {
        sandwich[(a, b)] / (norms[a] * norms[b])
    }))
}

/// Samples n, coordinates p, the Jacobian's column norms and (DᵀJᵀJD)⁻¹ with D the
/// columns' scaling to unit norm; refused as [`covariance`] says.
fn scaled_inverse(
    jacobian: &[Vec<f64>],
    names: &[String],
) -> IdResult<(usize, usize, Vec<f64>, DMatrix<f64>)> {
    let n = jacobian.first().map_or(0, Vec::len);
    let p = jacobian.len();
    if n <= p {
        return Err(IdentifyError::Data(format!(
            "{n} samples: fewer than the {p} parameters fitted and the offset"
        )));
    }
    let norms: Vec<f64> = jacobian
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .collect();
    if let Some(j) = norms.iter().position(|&s| s == 0.0 || !s.is_finite()) {
        return Err(IdentifyError::NoFit(format!(
            "the data carry no information on {}",
            names[j]
        )));
    }
    let jtj = DMatrix::from_fn(p, p, |a, b| {
        jacobian[a]
            .iter()
            .zip(&jacobian[b])
            .map(|(x, y)| x * y)
            .sum::<f64>()
            / (norms[a] * norms[b])
    });
    let inv = jtj.cholesky().map(|c| c.inverse()).ok_or_else(|| {
        IdentifyError::NoFit("the data do not tell the parameters apart (JᵀJ is singular)".into())
    })?;
    Ok((n, p, norms, inv))
}

/// A fitted parameter's estimate from its coordinate x and the coordinate's variance.
pub fn estimate(name: &str, unit: &str, coord: Coord, x: f64, var: f64) -> Estimate {
    let se = var.max(0.0).sqrt();
    let value = coord.value(x);
    let (standard_error, ci95) = match coord {
        Coord::Log => (value * se, [(x - Z_95 * se).exp(), (x + Z_95 * se).exp()]),
        Coord::Linear(s) => (
            s.abs() * se,
            [value - Z_95 * s.abs() * se, value + Z_95 * s.abs() * se],
        ),
    };
    Estimate {
        name: name.into(),
        unit: unit.into(),
        value,
        fixed: false,
        standard_error: Some(standard_error),
        ci95: Some(ci95),
    }
}

/// NRMSE, fit % and residual RMS of a response against the measurement.
pub fn quality(measured: &[f64], predicted: &[f64]) -> FitQuality {
    let n = measured.len() as f64;
    let mean = measured.iter().sum::<f64>() / n;
    let ss: f64 = measured
        .iter()
        .zip(predicted)
        .map(|(m, p)| (m - p).powi(2))
        .sum();
    let spread: f64 = measured.iter().map(|m| (m - mean).powi(2)).sum();
    let nrmse = if spread > 0.0 {
        (ss / spread).sqrt()
    } else {
        f64::INFINITY
    };
    FitQuality {
        nrmse,
        fit_percent: 100.0 * (1.0 - nrmse),
        residual_rms: (ss / n).sqrt(),
        samples: measured.len(),
    }
}

/// χ²(k)'s 95 % quantile by Wilson–Hilferty: k(1 − 2/(9k) + z√(2/(9k)))³, z = 1.6449.
pub fn chi2_95(k: usize) -> f64 {
    let k = k as f64;
    let z = 1.644_853_626_951_472;
    let c = 2.0 / (9.0 * k);
    k * (1.0 - c + z * c.sqrt()).powi(3)
}

/// Ljung–Box test of the residuals' whiteness (module doc).
pub fn whiteness(e: &[f64], lags: usize) -> CorrelationTest {
    let n = e.len();
    let lags = lags.min(n / 4).max(1);
    let r0: f64 = e.iter().map(|x| x * x).sum();
    let q: f64 = (1..=lags)
        .map(|k| {
            let rk: f64 = e[k..].iter().zip(e).map(|(a, b)| a * b).sum::<f64>() / r0;
            rk * rk / (n - k) as f64
        })
        .sum::<f64>()
        * (n * (n + 2)) as f64;
    test(lags, q, chi2_95(lags))
}

/// Cross-correlation test of the residuals e against the force u (module doc).
pub fn cross_correlation(e: &[f64], u: &[f64], lags: usize) -> CorrelationTest {
    let n = e.len();
    let lags = lags.min(n / 4);
    let mu = u.iter().sum::<f64>() / n as f64;
    let uc: Vec<f64> = u.iter().map(|x| x - mu).collect();
    let norm =
        (e.iter().map(|x| x * x).sum::<f64>() * uc.iter().map(|x| x * x).sum::<f64>()).sqrt();
    let s: f64 = (0..=lags)
        .map(|tau| {
            let r: f64 = e[tau..].iter().zip(&uc).map(|(a, b)| a * b).sum::<f64>() / norm;
            r * r
        })
        .sum::<f64>()
        * n as f64;
    test(lags, s, chi2_95(lags + 1))
}

fn test(lags: usize, statistic: f64, threshold: f64) -> CorrelationTest {
    CorrelationTest {
        lags,
        statistic,
        threshold,
        passes: statistic < threshold,
    }
}
