//! System identification: from a recording of commanded force and measured position to the
//! plant of the loop, with its uncertainty, and to what that uncertainty means for the wall.
//!
//! The estimate is made on the **exact sampled model** every other analysis uses (zero-order
//! hold, whole and fractional delay, actuator lag: [`crate::zoh`]), in the steps
//! 1. **data** ([`data`]): the columns checked (finite, uniform increasing time, an exciting
//!    force, enough samples), the period taken from the time column;
//! 2. **start** ([`arx`]): a linear least-squares estimate of the continuous transfer function
//!    through a state-variable filter, mapped to the model's parameters;
//! 3. **refine** ([`output_error`]): output error by Levenberg–Marquardt, positive parameters
//!    as logarithms, the position offset estimated beside them, from each start in turn until
//!    one leaves residuals that pass the tests of step 4 (else the lowest cost is kept);
//! 4. **assess** ([`uncertainty`]): standard errors and 95 % intervals from the Jacobian, the
//!    NRMSE, the residuals' whiteness and their cross-correlation with the force;
//! 5. **consequence** ([`consequence`]): K_max at B = 0 of the identified loop, its spread
//!    over the parameters' covariance and the robust K_max over their 95 % box.

pub mod arx;
pub mod consequence;
pub mod data;
pub mod error;
pub mod excitation;
pub mod model;
pub mod output_error;
pub mod response;
pub mod uncertainty;

use serde::Serialize;

pub use consequence::{StiffnessLimit, stiffness_limit};
pub use data::{Columns, Record};
pub use error::{IdResult, IdentifyError};
pub use model::{Fixed, ModelKind, ModelSpec};
pub use uncertainty::{CorrelationTest, Estimate, FitQuality};

use crate::model::{Loop, VelocityEstimator};

/// An identified plant with what the recording says about it.
#[derive(Debug, Clone, Serialize)]
pub struct Identification {
    /// The model fitted (`mass-spring-damper`, `held-device`, `two-mass`, `tf:N/D`).
    pub model: String,
    /// Every parameter of the model, held ones marked.
    pub parameters: Vec<Estimate>,
    /// The position the device rests at, y_0 in m.
    pub position_offset: Estimate,
    /// The sampling period T in s (the recording's).
    pub period: f64,
    /// The delay t_d in s and the actuator lag τ in s the model was fitted with.
    pub delay_time: f64,
    /// The actuator lag τ in s.
    pub force_lag: f64,
    /// NRMSE, fit %, residual RMS.
    pub fit: FitQuality,
    /// Ljung–Box test of the residuals.
    pub whiteness: CorrelationTest,
    /// Cross-correlation test of the residuals against the force.
    pub cross_correlation: CorrelationTest,
    /// The linear least-squares start, every parameter.
    pub start: Vec<f64>,
    /// Residual evaluations of the output-error fit.
    pub evaluations: usize,
    /// The model's response ŷ_k in m.
    #[serde(skip)]
    pub predicted: Vec<f64>,
    /// The covariance of the optimiser's coordinates (free parameters, then the offset).
    #[serde(skip)]
    pub(crate) covariance: Vec<Vec<f64>>,
    /// The optimiser's coordinates at the optimum and their kinds.
    #[serde(skip)]
    pub(crate) optimum: output_error::Fit,
    /// The spec fitted.
    #[serde(skip)]
    pub(crate) spec: ModelSpec,
}

/// Identifies the plant of `spec` from a recording (module doc's steps 1–4).
pub fn identify(record: &Record, spec: &ModelSpec) -> IdResult<Identification> {
    let free = spec.free();
    if record.len() <= free.len() + 1 {
        return Err(IdentifyError::Data(format!(
            "{} samples: fewer than the {} parameters to fit",
            record.len(),
            free.len() + 1
        )));
    }
    let (start, fit) = best_refinement(record, spec)?;
    let quality = uncertainty::quality(&record.position, &fit.predicted);
    if quality.nrmse.is_nan() || quality.nrmse > uncertainty::MAX_NRMSE {
        return Err(IdentifyError::NoFit(format!(
            "{} explains only {:.1} % of the position (NRMSE {:.3} > {})",
            spec.kind.name(),
            quality.fit_percent.max(0.0),
            quality.nrmse,
            uncertainty::MAX_NRMSE
        )));
    }
    let residuals: Vec<f64> = record
        .position
        .iter()
        .zip(&fit.predicted)
        .map(|(m, p)| m - p)
        .collect();
    let ss: f64 = residuals.iter().map(|e| e * e).sum();
    let (estimates, offset, cov) = estimates(spec, &fit, ss)?;
    Ok(Identification {
        model: spec.kind.name(),
        parameters: estimates,
        position_offset: offset,
        period: record.period,
        delay_time: spec.delay_time,
        force_lag: spec.force_lag,
        fit: quality,
        whiteness: uncertainty::whiteness(&residuals, uncertainty::TEST_LAGS),
        cross_correlation: uncertainty::cross_correlation(
            &residuals,
            &record.force,
            uncertainty::TEST_LAGS,
        ),
        start: start.values,
        evaluations: fit.evaluations,
        predicted: fit.predicted.clone(),
        covariance: cov,
        optimum: fit,
        spec: spec.clone(),
    })
}

/// The estimates of every parameter (held ones marked), the offset's, and the covariance
/// of the optimiser's coordinates (module doc step 4).
fn estimates(
    spec: &ModelSpec,
    fit: &output_error::Fit,
    residual_ss: f64,
) -> IdResult<(Vec<Estimate>, Estimate, Vec<Vec<f64>>)> {
    let free = spec.free();
    let params = spec.kind.params();
    let mut names: Vec<String> = free.iter().map(|&i| params[i].name.clone()).collect();
    names.push("position offset".into());
    let cov = uncertainty::covariance(fit, residual_ss, &names)?;
    let mut out: Vec<Estimate> = params
        .iter()
        .enumerate()
        .map(|(i, p)| Estimate {
            name: p.name.clone(),
            unit: p.unit.clone(),
            value: fit.values[i],
            fixed: true,
            standard_error: None,
            ci95: None,
        })
        .collect();
    for (k, &i) in free.iter().enumerate() {
        let p = &params[i];
        out[i] = uncertainty::estimate(&p.name, &p.unit, fit.coords[k], fit.x[k], cov[(k, k)]);
    }
    let o = free.len();
    let offset =
        uncertainty::estimate("position offset", "m", fit.coords[o], fit.x[o], cov[(o, o)]);
    let cov = (0..cov.nrows())
        .map(|a| (0..cov.ncols()).map(|b| cov[(a, b)]).collect())
        .collect();
    Ok((out, offset, cov))
}

/// The output-error optimum from the starts in their order (module doc step 3): the first
/// whose residuals pass both residual tests is taken at once (the model explains the data,
/// and another start would only find the same optimum); otherwise the one with the smallest
/// cost; the first refusal when none converges.
fn best_refinement(record: &Record, spec: &ModelSpec) -> IdResult<(arx::Start, output_error::Fit)> {
    let mut best: Option<(f64, arx::Start, output_error::Fit)> = None;
    let mut first_error = None;
    for start in arx::initial_estimates(record, spec)? {
        match output_error::refine(record, spec, &start) {
            Ok(fit) => {
                let cost = fit.cost(&record.position);
                let explains = residuals_pass(record, &fit);
                if best.as_ref().is_none_or(|(c, _, _)| cost < *c) {
                    best = Some((cost, start, fit));
                }
                if explains {
                    break;
                }
            }
            Err(e) => {
                first_error.get_or_insert(e);
            }
        }
    }
    match (best, first_error) {
        (Some((_, start, fit)), _) => Ok((start, fit)),
        (None, Some(e)) => Err(e),
        (None, None) => Err(IdentifyError::NoFit("no start to refine".into())),
    }
}

/// True when a fit's residuals pass the whiteness and the cross-correlation tests.
fn residuals_pass(record: &Record, fit: &output_error::Fit) -> bool {
    let e: Vec<f64> = record
        .position
        .iter()
        .zip(&fit.predicted)
        .map(|(m, p)| m - p)
        .collect();
    uncertainty::whiteness(&e, uncertainty::TEST_LAGS).passes
        && uncertainty::cross_correlation(&e, &record.force, uncertainty::TEST_LAGS).passes
}

impl Identification {
    /// The identified loop with the given velocity estimator: the plant at the estimates,
    /// the recording's period, the delay and lag fitted with.
    pub fn to_loop(&self, velocity: VelocityEstimator) -> crate::Result<Loop> {
        let v: Vec<f64> = self.parameters.iter().map(|p| p.value).collect();
        self.spec.to_loop(&v, self.period, velocity)
    }

    /// The estimate of a parameter by name.
    pub fn parameter(&self, name: &str) -> Option<&Estimate> {
        self.parameters.iter().find(|p| p.name == name)
    }
}
