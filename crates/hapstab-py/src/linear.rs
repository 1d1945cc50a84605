//! The linear condition (22)–(23) and where it stops holding (Sections VI–VII, Fig. 7):
//! Python's `linear_condition`, the numbers of `hapstab linear --json`.

use hapstab::paper::linear::{LinearCondition, linear_condition as condition};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::errors::Context;
use crate::loops::PyLoop;
use crate::text::num;

/// The linear condition of the paper's loop and its validity points (the names of
/// `hapstab linear --json`; one array entry per error level).
#[pyclass(frozen, get_all, module = "hapstab", name = "LinearCondition")]
pub struct PyLinearCondition {
    /// γ of Table I.
    pub gamma: f64,
    /// δ of Table I.
    pub delta: f64,
    /// The delay d in samples.
    pub d: usize,
    /// 1/(d + 1/2): (23) is α < linear_slope·β + linear_intercept.
    pub linear_slope: f64,
    /// δ/(d + 1/2).
    pub linear_intercept: f64,
    /// (19): α > alpha_lower = −γ.
    pub alpha_lower: f64,
    /// The error levels of eq. (24), as given.
    pub levels: Py<PyArray1<f64>>,
    /// The smallest β > 0 at which the error (24) reaches each level.
    pub beta: Py<PyArray1<f64>>,
    /// α on the exact upper boundary there.
    pub alpha: Py<PyArray1<f64>>,
    /// α_lin of (23) there.
    pub alpha_linear: Py<PyArray1<f64>>,
    /// The error (24) there (the level, to the tolerance).
    pub error: Py<PyArray1<f64>>,
    /// True where the level is reached already at β = 0⁺.
    pub at_start: Vec<bool>,
    /// α in N/m at each point (None for Loop.normalized).
    pub wall_stiffness: Option<Py<PyArray1<f64>>>,
    /// β in Ns/m at each point (None for Loop.normalized).
    pub wall_damping: Option<Py<PyArray1<f64>>>,
    /// K_lin of (23) in N/m at each point (None for Loop.normalized).
    pub k_linear: Option<Py<PyArray1<f64>>>,
    /// (23) in N/m and Ns/m: K < k_linear_slope·B + k_linear_intercept, slope
    /// 1/(T(d + 1/2)) in 1/s (None for Loop.normalized).
    pub k_linear_slope: Option<f64>,
    /// b/(T(d + 1/2)) in N/m (None for Loop.normalized).
    pub k_linear_intercept: Option<f64>,
    /// (19) in N/m: K > k_lower = −k (None for Loop.normalized).
    pub k_lower: Option<f64>,
}

#[pymethods]
impl PyLinearCondition {
    fn __repr__(&self) -> String {
        // a loop in physical units is described in N/m and Ns/m, a normalized one in Table I
        match (self.k_linear_slope, self.k_linear_intercept, self.k_lower) {
            (Some(slope), Some(intercept), Some(lower)) => format!(
                "LinearCondition(k_linear_slope={}, k_linear_intercept={}, k_lower={}, d={}, levels={})",
                num(slope),
                num(intercept),
                num(lower),
                self.d,
                self.at_start.len()
            ),
            _ => format!(
                "LinearCondition(gamma={}, delta={}, d={}, levels={})",
                num(self.gamma),
                num(self.delta),
                self.d,
                self.at_start.len()
            ),
        }
    }
}

/// The linear condition (22)–(23) of the paper's loop (a mass-spring-damper with the
/// backward difference and a whole-sample delay) and, for each error level of eq. (24), the
/// smallest β > 0 where the linear limit is that far from the exact boundary — the numbers of
/// `hapstab linear --json`. Other loops are refused (ValueError naming `loop`).
#[pyfunction]
#[pyo3(signature = (r#loop, *, levels = vec![0.02, 0.05]))]
pub fn linear_condition(
    r#loop: &PyLoop,
    levels: Vec<f64>,
    py: Python<'_>,
) -> PyResult<PyLinearCondition> {
    let lp = &r#loop.lp;
    let lc = py.detach(|| condition(lp, &levels)).py()?;
    Ok(condition_object(py, &lc, !r#loop.normalized))
}

/// The Python object of a [`LinearCondition`]; `physical` adds K and B in N/m and Ns/m.
fn condition_object(py: Python<'_>, lc: &LinearCondition, physical: bool) -> PyLinearCondition {
    let column = |f: &dyn Fn(&hapstab::paper::linear::ValidityPoint) -> f64| {
        PyArray1::from_vec(py, lc.points.iter().map(f).collect()).unbind()
    };
    let (ku, bu) = (lc.units.stiffness, lc.units.damping);
    let ph = physical.then(|| lc.physical());
    PyLinearCondition {
        gamma: lc.gamma,
        delta: lc.delta,
        d: lc.d,
        linear_slope: lc.slope,
        linear_intercept: lc.intercept,
        alpha_lower: lc.alpha_lower,
        levels: column(&|p| p.level),
        beta: column(&|p| p.beta),
        alpha: column(&|p| p.alpha),
        alpha_linear: column(&|p| p.alpha_linear),
        error: column(&|p| p.error),
        at_start: lc.points.iter().map(|p| p.at_start).collect(),
        wall_stiffness: physical.then(|| column(&|p| p.alpha * ku)),
        wall_damping: physical.then(|| column(&|p| p.beta * bu)),
        k_linear: physical.then(|| column(&|p| lc.k_linear(p))),
        k_linear_slope: ph.map(|h| h.k_linear_slope),
        k_linear_intercept: ph.map(|h| h.k_linear_intercept),
        k_lower: ph.map(|h| h.k_lower),
    }
}
