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
pub mod bootstrap;
pub mod consequence;
pub mod data;
pub mod error;
pub mod excitation;
pub mod frequency;
pub mod model;
pub mod output_error;
pub mod propagate;
pub mod response;
pub mod uncertainty;

use serde::Serialize;

pub use consequence::{BandLimit, StiffnessLimit, stiffness_limit};
pub use data::{Columns, Record};
pub use error::{IdResult, IdentifyError};
pub use model::{Fixed, ModelKind, ModelSpec};
pub use propagate::Propagated;
pub use uncertainty::{CorrelationTest, Estimate, FitQuality};

use crate::model::{Loop, VelocityEstimator};

/// An identified plant with what the recording says about it.
#[derive(Debug, Clone, Serialize)]
pub struct Identification {
    /// The model fitted (`mass-spring-damper`, `held-device`, `two-mass`, `tf:N/D`).
    pub model: String,
    /// What was fitted: `time` (a recording; residuals in m) or `frequency` (a frequency
    /// response; residuals as ln(Ĥ/H), nepers and radians).
    pub source: &'static str,
    /// Every parameter of the model, held ones marked.
    pub parameters: Vec<Estimate>,
    /// The position the device rests at, y_0 in m (in the first run).
    pub position_offset: Estimate,
    /// The position offset of each run.
    pub position_offsets: Vec<Estimate>,
    /// The sampling period T in s (the recording's).
    pub period: f64,
    /// The delay t_d in s of the identified loop (the fitted one with `delay-time` among the
    /// parameters, else the given one; in JSON as the loop's).
    #[serde(skip)]
    pub delay_time: f64,
    /// The actuator lag τ in s of the identified loop (fitted or given, as the delay).
    #[serde(skip)]
    pub force_lag: f64,
    /// NRMSE, fit %, residual RMS over every run.
    pub fit: FitQuality,
    /// NRMSE, fit %, residual RMS of each run (none for a frequency response).
    pub runs: Vec<FitQuality>,
    /// Ljung–Box test of the residuals.
    pub whiteness: CorrelationTest,
    /// Cross-correlation test of the residuals against the force.
    /// Cross-correlation test of the residuals against the force (None for a frequency
    /// response).
    pub cross_correlation: Option<CorrelationTest>,
    /// The linear least-squares start, every parameter.
    pub start: Vec<f64>,
    /// Residual evaluations of the output-error fit.
    pub evaluations: usize,
    /// The model's response ŷ_k in m (time-domain data).
    #[serde(skip)]
    pub predicted: Vec<f64>,
    /// The model's response Ĥ(e^{jωT}) in m/N at the measured frequencies (frequency data).
    #[serde(skip)]
    pub predicted_response: Vec<num_complex::Complex64>,
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
    identify_runs(std::slice::from_ref(record), spec)
}

/// The runs of a fit laid end to end: positions and forces, and where each run starts.
struct Runs {
    position: Vec<f64>,
    force: Vec<f64>,
    bounds: Vec<std::ops::Range<usize>>,
}

impl Runs {
    /// The runs, refused when they are none or their periods differ (naming the run).
    fn new(records: &[Record], free: usize) -> IdResult<Self> {
        let Some(first) = records.first() else {
            return Err(IdentifyError::Data("no run to identify".into()));
        };
        let mut runs = Runs {
            position: Vec::new(),
            force: Vec::new(),
            bounds: Vec::new(),
        };
        for (i, r) in records.iter().enumerate() {
            if (r.period - first.period).abs() > data::UNIFORM_TOLERANCE * first.period {
                return Err(IdentifyError::Data(format!(
                    "run {}: sampled at T = {} s, run 1 at {} s",
                    i + 1,
                    r.period,
                    first.period
                )));
            }
            let at = runs.position.len();
            runs.position.extend(&r.position);
            runs.force.extend(&r.force);
            runs.bounds.push(at..runs.position.len());
        }
        if runs.position.len() <= free + records.len() {
            return Err(IdentifyError::Data(format!(
                "{} samples: fewer than the {} parameters to fit",
                runs.position.len(),
                free + records.len()
            )));
        }
        Ok(runs)
    }

    /// Each run's fit quality.
    fn qualities(&self, predicted: &[f64]) -> Vec<FitQuality> {
        self.bounds
            .iter()
            .map(|b| uncertainty::quality(&self.position[b.clone()], &predicted[b.clone()]))
            .collect()
    }
}

/// Identifies the plant of `spec` from several runs of it (module doc's steps 1–4): one
/// parameter vector, one position offset per run, every run's residuals in one fit.
pub fn identify_runs(records: &[Record], spec: &ModelSpec) -> IdResult<Identification> {
    let runs = Runs::new(records, spec.free().len())?;
    let (start, fit) = best_refinement(records, &runs, spec)?;
    let per_run = runs.qualities(&fit.predicted);
    if let Some((i, q)) = per_run
        .iter()
        .enumerate()
        .find(|(_, q)| q.nrmse.is_nan() || q.nrmse > uncertainty::MAX_NRMSE)
    {
        let run = if records.len() > 1 {
            format!(" of run {}", i + 1)
        } else {
            String::new()
        };
        return Err(IdentifyError::NoFit(format!(
            "{} explains only {:.1} % of the position{run} (NRMSE {:.3} > {})",
            spec.kind.name(),
            q.fit_percent.max(0.0),
            q.nrmse,
            uncertainty::MAX_NRMSE
        )));
    }
    let residuals: Vec<f64> = runs
        .position
        .iter()
        .zip(&fit.predicted)
        .map(|(m, p)| m - p)
        .collect();
    let ss: f64 = residuals.iter().map(|e| e * e).sum();
    let floor = spec.quantization * spec.quantization / 12.0;
    let noise = Noise::White {
        residual_ss: ss,
        floor,
    };
    let est = estimates(spec, &fit, noise, records.len())?;
    let (delay_time, force_lag) = timing(spec, &est.parameters);
    Ok(Identification {
        model: spec.kind.name(),
        source: "time",
        parameters: est.parameters,
        position_offset: est.offsets[0].clone(),
        position_offsets: est.offsets,
        period: records[0].period,
        delay_time,
        force_lag,
        fit: uncertainty::quality(&runs.position, &fit.predicted),
        runs: per_run,
        whiteness: uncertainty::whiteness(&residuals, uncertainty::TEST_LAGS),
        cross_correlation: Some(uncertainty::cross_correlation(
            &residuals,
            &runs.force,
            uncertainty::TEST_LAGS,
        )),
        start: start.values,
        evaluations: fit.evaluations,
        predicted: fit.predicted.clone(),
        predicted_response: Vec::new(),
        covariance: est.covariance,
        optimum: fit,
        spec: spec.clone(),
    })
}

/// The estimates of a fit and the covariance they come from.
struct Estimates {
    /// Every parameter, held ones marked.
    parameters: Vec<Estimate>,
    /// The position offset of each run (none for a frequency response).
    offsets: Vec<Estimate>,
    /// The covariance of the optimiser's coordinates.
    covariance: Vec<Vec<f64>>,
}

/// What the covariance takes the noise to be.
enum Noise<'a> {
    /// One white noise of variance max(Σe²/(N − p), floor) (a time recording).
    White { residual_ss: f64, floor: f64 },
    /// Interleaved kinds of residual, each with its own variance (a frequency response's
    /// log-magnitude and phase).
    Grouped { residuals: &'a [f64], groups: usize },
}

/// A held value as an estimate.
fn held(name: &str, unit: &str, value: f64) -> Estimate {
    Estimate {
        name: name.into(),
        unit: unit.into(),
        value,
        fixed: true,
        standard_error: None,
        ci95: None,
    }
}

/// The estimates of every parameter (held ones marked), the `offsets` runs' offsets (the
/// last coordinates), and the covariance of the optimiser's coordinates under `noise`
/// (module doc step 4).
fn estimates(
    spec: &ModelSpec,
    fit: &output_error::Fit,
    noise: Noise,
    offsets: usize,
) -> IdResult<Estimates> {
    let free = spec.free();
    let params = spec.params();
    let mut names: Vec<String> = free.iter().map(|&i| params[i].name.clone()).collect();
    names.extend((1..=offsets).map(|r| format!("position offset of run {r}")));
    let cov = match noise {
        Noise::White { residual_ss, floor } => {
            uncertainty::covariance(&fit.jacobian, residual_ss, floor, &names)?
        }
        Noise::Grouped { residuals, groups } => {
            uncertainty::grouped_covariance(&fit.jacobian, residuals, groups, &names)?
        }
    };
    let mut out: Vec<Estimate> = params
        .iter()
        .enumerate()
        .map(|(i, p)| held(&p.name, &p.unit, fit.values[i]))
        .collect();
    for (k, &i) in free.iter().enumerate() {
        let p = &params[i];
        out[i] = uncertainty::estimate(&p.name, &p.unit, fit.coords[k], fit.x[k], cov[(k, k)]);
    }
    let offsets = (free.len()..free.len() + offsets)
        .map(|o| {
            uncertainty::estimate("position offset", "m", fit.coords[o], fit.x[o], cov[(o, o)])
        })
        .collect();
    let cov = (0..cov.nrows())
        .map(|a| (0..cov.ncols()).map(|b| cov[(a, b)]).collect())
        .collect();
    Ok(Estimates {
        parameters: out,
        offsets,
        covariance: cov,
    })
}

/// The output-error optimum from the starts in their order (module doc step 3; the starts
/// from the first run, every run's offset from its own mean residual): the first whose
/// residuals pass both residual tests is taken at once (the model explains the data, and
/// another start would only find the same optimum); otherwise the one with the smallest
/// cost; the first refusal when none converges.
fn best_refinement(
    records: &[Record],
    runs: &Runs,
    spec: &ModelSpec,
) -> IdResult<(arx::Start, output_error::Fit)> {
    let mut best: Option<(f64, arx::Start, output_error::Fit)> = None;
    let mut first_error = None;
    for start in arx::initial_estimates(&records[0], spec)? {
        let offsets: Vec<f64> = records
            .iter()
            .map(|r| arx::output_error(r, spec, &start.values).map_or(0.0, |(_, o)| o))
            .collect();
        match output_error::refine(records, spec, &start, &offsets) {
            Ok(fit) => {
                let cost = fit.cost(&runs.position);
                let explains = residuals_pass(runs, &fit);
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
fn residuals_pass(runs: &Runs, fit: &output_error::Fit) -> bool {
    let e: Vec<f64> = runs
        .position
        .iter()
        .zip(&fit.predicted)
        .map(|(m, p)| m - p)
        .collect();
    uncertainty::whiteness(&e, uncertainty::TEST_LAGS).passes
        && uncertainty::cross_correlation(&e, &runs.force, uncertainty::TEST_LAGS).passes
}

/// Identifies the plant of `spec` from a measured frequency response ([`frequency`]'s
/// steps): Levy's start, logarithmic least squares on the exact sampled response, the
/// estimates with their intervals (the magnitude's and the phase's errors each with its own
/// variance, [`uncertainty::grouped_covariance`]), the fit (NRMSE ‖Ĥ − H‖/‖H‖, the residual RMS in nepers
/// and radians) and the whiteness of the residuals over frequency.
pub fn identify_frequency(
    rec: &frequency::FrequencyRecord,
    spec: &ModelSpec,
) -> IdResult<Identification> {
    let free = spec.free();
    if 2 * rec.frequency_hz.len() <= free.len() {
        return Err(IdentifyError::Data(format!(
            "{} frequencies: fewer than the {} parameters to fit",
            rec.frequency_hz.len(),
            free.len()
        )));
    }
    let start = frequency::levy_start(rec, spec)?;
    let (problem, evaluations) = frequency::refine(rec, spec, &start)?;
    let x = problem.x.as_slice().to_vec();
    let no_fit = || IdentifyError::NoFit("the fitted parameters make no valid loop".into());
    let response = problem.predict(&x).ok_or_else(no_fit)?;
    let residuals = problem.log_residuals(&x).ok_or_else(no_fit)?;
    let fit = output_error::Fit {
        values: problem.values(&x),
        offsets: Vec::new(),
        predicted: Vec::new(),
        jacobian: problem.jacobian_columns(&x).ok_or_else(no_fit)?,
        x,
        coords: problem.coords.clone(),
        evaluations,
    };
    let ss: f64 = residuals.iter().map(|e| e * e).sum();
    let noise = Noise::Grouped {
        residuals: &residuals,
        groups: 2,
    };
    let est = estimates(spec, &fit, noise, 0)?;
    let (delay_time, force_lag) = timing(spec, &est.parameters);
    let err: f64 = response
        .iter()
        .zip(&rec.response)
        .map(|(p, m)| (p - m).norm_sqr())
        .sum();
    let size: f64 = rec.response.iter().map(|m| m.norm_sqr()).sum();
    let nrmse = (err / size).sqrt();
    let magnitude: Vec<f64> = residuals.iter().step_by(2).copied().collect();
    Ok(Identification {
        model: spec.kind.name(),
        source: "frequency",
        parameters: est.parameters,
        position_offset: held("position offset", "m", 0.0),
        position_offsets: Vec::new(),
        period: rec.period,
        delay_time,
        force_lag,
        fit: FitQuality {
            nrmse,
            fit_percent: 100.0 * (1.0 - nrmse),
            residual_rms: (ss / residuals.len() as f64).sqrt(),
            samples: rec.frequency_hz.len(),
        },
        runs: Vec::new(),
        whiteness: uncertainty::whiteness(&magnitude, uncertainty::TEST_LAGS),
        cross_correlation: None,
        start,
        evaluations,
        predicted: Vec::new(),
        predicted_response: response,
        covariance: est.covariance,
        optimum: fit,
        spec: spec.clone(),
    })
}

/// The delay and the lag a fit ends with: the fitted values when they were fitted, the
/// given ones otherwise.
fn timing(spec: &ModelSpec, parameters: &[Estimate]) -> (f64, f64) {
    let fitted = |name: &str, given: f64| {
        parameters
            .iter()
            .find(|p| p.name == name)
            .map_or(given, |p| p.value)
    };
    (
        fitted("delay-time", spec.delay_time),
        fitted("force-lag", spec.force_lag),
    )
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
