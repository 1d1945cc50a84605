//! `identify`: the plant from arrays of time, commanded force and measured position, as
//! `hapstab identify --json` gives it ([`hapstab::identify`]); bad data or a model that
//! cannot fit raise `ValueError` naming the keyword argument.

use hapstab::identify::frequency::FrequencyRecord;
use hapstab::identify::{
    Columns, Fixed, Identification, IdentifyError, ModelKind, ModelSpec, Record, StiffnessLimit,
    identify_frequency as identify_frequency_lib, identify_runs, stiffness_limit,
};
use hapstab::model::VelocityEstimator;
use num_complex::Complex64;
use numpy::{AllowTypeChange, PyArray1, PyArrayLike1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyTuple};

use crate::errors::{Context, bad, finite};
use crate::loops::PyLoop;
use crate::text::num;

/// The result of `identify`: every parameter (held ones marked), with standard errors and
/// 95 % intervals (NaN where held), the fit, the residual tests, and K_max at B = 0 with
/// its uncertainty.
#[pyclass(frozen, get_all, module = "hapstab", name = "Identification")]
pub struct PyIdentification {
    /// The model fitted.
    pub model: String,
    /// Parameter names, in the model's order.
    pub names: Vec<String>,
    /// Parameter units.
    pub units: Vec<String>,
    /// Estimates (or held values).
    pub values: Py<PyArray1<f64>>,
    /// Standard errors (NaN where held).
    pub standard_errors: Py<PyArray1<f64>>,
    /// Lower ends of the 95 % intervals (NaN where held).
    pub ci_low: Py<PyArray1<f64>>,
    /// Upper ends of the 95 % intervals (NaN where held).
    pub ci_high: Py<PyArray1<f64>>,
    /// True for the parameters held at a known value.
    pub fixed: Vec<bool>,
    /// The position the device rests at, in m.
    pub position_offset: f64,
    /// The sampling period T in s (the mean time step).
    pub period: f64,
    /// ‖y − ŷ‖/‖y − ȳ‖.
    pub nrmse: f64,
    /// 100·(1 − NRMSE).
    pub fit_percent: f64,
    /// RMS of the residuals in m.
    pub residual_rms: f64,
    /// True when the residuals pass the Ljung–Box whiteness test (20 lags, 95 %).
    pub whiteness_passes: bool,
    /// True when the residuals pass the cross-correlation test against the force.
    pub cross_correlation_passes: bool,
    /// The model's response ŷ_k in m.
    pub predicted: Py<PyArray1<f64>>,
    /// K_max at B = 0 of the identified loop, N/m.
    pub k_max: Option<f64>,
    /// 2.5 % and 97.5 % quantiles of K_max over loops drawn from the covariance, N/m.
    pub k_max_spread: Option<(f64, f64)>,
    /// Robust K_max over the parameters' 95 % box, N/m (None for a transfer function).
    pub k_max_robust: Option<f64>,
    /// The smallest and largest K_max over the parameters' 95 % box, N/m.
    pub k_max_box_range: Option<(f64, f64)>,
    /// K_max at B = 0's delta-method 95 % interval, N/m.
    pub k_max_interval: Option<(f64, f64)>,
    /// K_max at B = 0's delta-method standard error, N/m.
    pub k_max_standard_error: Option<f64>,
    /// The renderable band's upper end B_r, Ns/m (position resolution: `quantization`, or
    /// 10 µm without it; force noise 0.05 N).
    pub band_b_max: Option<f64>,
    /// K_max over the renderable band 0 ≤ B ≤ B_r, N/m.
    pub k_max_band: Option<f64>,
    /// Its delta-method 95 % interval, N/m.
    pub k_max_band_interval: Option<(f64, f64)>,
    /// The position offset of each run, m.
    pub position_offsets: Vec<f64>,
    /// The identified loop.
    pub fitted_loop: Py<PyLoop>,
}

#[pymethods]
impl PyIdentification {
    fn __repr__(&self, py: Python<'_>) -> String {
        let values = self.values.bind(py).to_vec().unwrap_or_default();
        let pairs: Vec<String> = self
            .names
            .iter()
            .zip(values)
            .map(|(n, v)| format!("{n}={}", num(v)))
            .collect();
        format!(
            "Identification(model={:?}, {}, nrmse={}, k_max={})",
            self.model,
            pairs.join(", "),
            num(self.nrmse),
            self.k_max.map_or("None".into(), num)
        )
    }
}

/// The keyword an identification error is about, with its message.
fn to_py(e: IdentifyError) -> PyErr {
    let kw = match &e {
        IdentifyError::Column { column, .. } => column.clone(),
        IdentifyError::Parameter { name, .. } if name == "model" => "model".into(),
        IdentifyError::Parameter { .. } => "fixed".into(),
        IdentifyError::Data(_) => "t".into(),
        IdentifyError::NoFit(_) => "model".into(),
        IdentifyError::Loop(_) => "model".into(),
    };
    bad(&kw, e)
}

fn array(v: &Bound<'_, PyAny>, kw: &str) -> PyResult<Vec<f64>> {
    let a: PyArrayLike1<'_, f64, AllowTypeChange> = v
        .extract()
        .map_err(|_| bad(kw, "must be a 1-D array of numbers"))?;
    Ok(a.as_array().to_vec())
}

/// The recording from the three arrays, named `t`, `force`, `position` in its errors.
fn recording(
    t: &Bound<'_, PyAny>,
    force: &Bound<'_, PyAny>,
    position: &Bound<'_, PyAny>,
) -> PyResult<Record> {
    let columns = Columns {
        time: "t".into(),
        force: "force".into(),
        position: "position".into(),
    };
    Record::new(
        array(t, "t")?,
        array(force, "force")?,
        array(position, "position")?,
        &columns,
    )
    .map_err(to_py)
}

/// True when `v` is a list or tuple of arrays (several runs), not of numbers.
fn is_runs(v: &Bound<'_, PyAny>) -> bool {
    let Ok(items) = v.extract::<Vec<Bound<'_, PyAny>>>() else {
        return false;
    };
    (v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>())
        && items.first().is_some_and(|x| x.extract::<f64>().is_err())
}

/// The arrays of a list of runs, named `kw` in the error.
fn runs_of<'py>(v: &Bound<'py, PyAny>, kw: &str) -> PyResult<Vec<Bound<'py, PyAny>>> {
    v.extract()
        .map_err(|_| bad(kw, "must be a list of arrays, one per run, as t"))
}

/// The runs from `t`, `force`, `position`: three arrays (one run) or three lists of arrays
/// of one length (several runs of the same plant).
fn recordings(
    t: &Bound<'_, PyAny>,
    force: &Bound<'_, PyAny>,
    position: &Bound<'_, PyAny>,
) -> PyResult<Vec<Record>> {
    if !is_runs(t) {
        return Ok(vec![recording(t, force, position)?]);
    }
    let (ts, fs, xs) = (
        runs_of(t, "t")?,
        runs_of(force, "force")?,
        runs_of(position, "position")?,
    );
    for (kw, n) in [("force", fs.len()), ("position", xs.len())] {
        if n != ts.len() {
            return Err(bad(kw, format!("{n} runs, t has {}", ts.len())));
        }
    }
    ts.iter()
        .zip(&fs)
        .zip(&xs)
        .map(|((t, f), x)| recording(t, f, x))
        .collect()
}

/// The model spec from the keywords (errors naming them).
#[allow(clippy::too_many_arguments)]
fn model_spec(
    model: &str,
    fixed: Option<&Bound<'_, PyDict>>,
    delay: f64,
    force_lag: f64,
    fit_delay: bool,
    fit_force_lag: bool,
    quantization: f64,
) -> PyResult<ModelSpec> {
    let kind = ModelKind::parse(model).map_err(to_py)?;
    let spec = ModelSpec::new(
        kind,
        held(fixed)?,
        finite("delay", delay)?,
        finite("force_lag", force_lag)?,
    )
    .map_err(to_py)?
    .fitting_timing(fit_delay, fit_force_lag);
    spec.with_quantization(quantization)
        .map_err(|e| bad("quantization", e))
}

fn held(fixed: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<Fixed>> {
    let Some(d) = fixed else {
        return Ok(Vec::new());
    };
    d.iter()
        .map(|(k, v)| {
            let name: String = k.extract().map_err(|_| bad("fixed", "keys must be str"))?;
            let value: f64 = v
                .extract()
                .map_err(|_| bad("fixed", format!("{name}: must be a number")))?;
            Ok(Fixed { name, value })
        })
        .collect()
}

/// Fits `model` ("mass-spring-damper", "held-device", "two-mass" or "tf:N/D") to a
/// recording by output error on the exact sampled model (Ljung 1999, §7.3): time `t` in s
/// (uniform), commanded `force` in N, measured `position` in m — or lists of such arrays,
/// one per run of the same plant, fitted together; `fixed` = {name: value} holds parameters
/// (e.g. {"device-mass": 0.1}); `delay` (s) and `force_lag` (s) are known parts of the loop,
/// or the starts of their fit with `fit_delay`, `fit_force_lag`; `quantization` (m) is the
/// position's rounding step (noise at least q²/12, the renderable band's resolution); K_max
/// at B = 0 and over the renderable band is for the wall's `velocity` estimator, with
/// delta-method intervals, its spread over `draws` loops drawn with `seed`. The numbers of
/// `hapstab identify --json`.
#[pyfunction]
#[pyo3(signature = (t, force, position, *, model = "mass-spring-damper", fixed = None,
                    delay = 0.0, force_lag = 0.0, fit_delay = false, fit_force_lag = false,
                    quantization = 0.0, velocity = "backward", draws = 400, seed = 1))]
#[allow(clippy::too_many_arguments)]
pub fn identify(
    py: Python<'_>,
    t: &Bound<'_, PyAny>,
    force: &Bound<'_, PyAny>,
    position: &Bound<'_, PyAny>,
    model: &str,
    fixed: Option<&Bound<'_, PyDict>>,
    delay: f64,
    force_lag: f64,
    fit_delay: bool,
    fit_force_lag: bool,
    quantization: f64,
    velocity: &str,
    draws: usize,
    seed: u64,
) -> PyResult<PyIdentification> {
    let records = recordings(t, force, position)?;
    let spec = model_spec(
        model,
        fixed,
        delay,
        force_lag,
        fit_delay,
        fit_force_lag,
        quantization,
    )?;
    fitted(py, velocity, (draws, seed), || {
        identify_runs(&records, &spec)
    })
}

/// The Python result of an identification and its K_max.
fn result(
    py: Python<'_>,
    id: &Identification,
    lim: &StiffnessLimit,
    velocity: VelocityEstimator,
) -> PyResult<PyIdentification> {
    let lp = id.to_loop(velocity).py()?;
    let col = |f: &dyn Fn(&hapstab::identify::Estimate) -> f64| {
        PyArray1::from_vec(py, id.parameters.iter().map(f).collect()).unbind()
    };
    Ok(PyIdentification {
        model: id.model.clone(),
        names: id.parameters.iter().map(|p| p.name.clone()).collect(),
        units: id.parameters.iter().map(|p| p.unit.clone()).collect(),
        values: col(&|p| p.value),
        standard_errors: col(&|p| p.standard_error.unwrap_or(f64::NAN)),
        ci_low: col(&|p| p.ci95.map_or(f64::NAN, |c| c[0])),
        ci_high: col(&|p| p.ci95.map_or(f64::NAN, |c| c[1])),
        fixed: id.parameters.iter().map(|p| p.fixed).collect(),
        position_offset: id.position_offset.value,
        period: id.period,
        nrmse: id.fit.nrmse,
        fit_percent: id.fit.fit_percent,
        residual_rms: id.fit.residual_rms,
        whiteness_passes: id.whiteness.passes,
        cross_correlation_passes: id.cross_correlation.as_ref().is_some_and(|t| t.passes),
        predicted: PyArray1::from_slice(py, &id.predicted).unbind(),
        k_max: lim.k_max,
        k_max_spread: lim.spread.map(|[a, b]| (a, b)),
        k_max_box_range: lim.box_range.map(|[a, b]| (a, b)),
        k_max_interval: lim.interval.map(|p| (p.ci95[0], p.ci95[1])),
        k_max_standard_error: lim.interval.map(|p| p.standard_error),
        band_b_max: lim.renderable.as_ref().map(|b| b.band.b_max),
        k_max_band: lim.renderable.as_ref().and_then(|b| b.band.k_max),
        k_max_band_interval: lim
            .renderable
            .as_ref()
            .and_then(|b| b.interval)
            .map(|p| (p.ci95[0], p.ci95[1])),
        position_offsets: id.position_offsets.iter().map(|o| o.value).collect(),
        k_max_robust: lim.robust.as_ref().and_then(|r| r.k_max),
        fitted_loop: Py::new(
            py,
            PyLoop {
                lp,
                normalized: false,
            },
        )?,
    })
}

/// Fits `model` to a measured frequency response: `frequency_hz` (increasing, below the
/// Nyquist frequency of `period`) and the complex `response` in m/N, by the logarithmic
/// least squares of `hapstab identify --frequency-data` on the exact sampled response; the
/// other keywords as `identify`'s.
#[pyfunction]
#[pyo3(signature = (frequency_hz, response, *, period = 1e-3, model = "mass-spring-damper",
                    fixed = None, delay = 0.0, force_lag = 0.0, fit_delay = false,
                    fit_force_lag = false, velocity = "backward", draws = 400, seed = 1))]
#[allow(clippy::too_many_arguments)]
pub fn identify_frequency(
    py: Python<'_>,
    frequency_hz: &Bound<'_, PyAny>,
    response: &Bound<'_, PyAny>,
    period: f64,
    model: &str,
    fixed: Option<&Bound<'_, PyDict>>,
    delay: f64,
    force_lag: f64,
    fit_delay: bool,
    fit_force_lag: bool,
    velocity: &str,
    draws: usize,
    seed: u64,
) -> PyResult<PyIdentification> {
    let h: PyArrayLike1<'_, Complex64, AllowTypeChange> = response
        .extract()
        .map_err(|_| bad("response", "must be a 1-D array of complex numbers"))?;
    let rec = FrequencyRecord::new(
        array(frequency_hz, "frequency_hz")?,
        h.as_array().to_vec(),
        period,
    )
    .map_err(|e| match e {
        IdentifyError::Column { column, reason } if column == "frequency" => {
            bad("frequency_hz", reason)
        }
        other => to_py(other),
    })?;
    let spec = model_spec(
        model,
        fixed,
        delay,
        force_lag,
        fit_delay,
        fit_force_lag,
        0.0,
    )?;
    fitted(py, velocity, (draws, seed), || {
        identify_frequency_lib(&rec, &spec)
    })
}

/// The common end of `identify` and `identify_frequency`: the velocity estimate and the draw
/// count checked, then the fit and its K_max with the parameters' uncertainty (`draws`
/// bootstrap draws from `seed`) run without the GIL.
fn fitted(
    py: Python<'_>,
    velocity: &str,
    (draws, seed): (usize, u64),
    fit: impl FnOnce() -> Result<Identification, IdentifyError> + Send,
) -> PyResult<PyIdentification> {
    let velocity: VelocityEstimator = velocity
        .parse()
        .map_err(|e: hapstab::Error| bad("velocity", e))?;
    if draws == 0 {
        return Err(bad("draws", "must be at least 1"));
    }
    let (id, lim) = py
        .detach(|| {
            let id = fit()?;
            let lim = stiffness_limit(&id, &velocity, draws, seed)?;
            Ok::<_, IdentifyError>((id, lim))
        })
        .map_err(to_py)?;
    result(py, &id, &lim, velocity)
}
