//! The library's errors as Python exceptions: a bad argument is a `ValueError` whose message
//! starts with the keyword argument that carries it ("period: sampling period T must be > 0
//! (got 0)"); a numerical routine that did not converge on valid input is a
//! `hapstab.NumericalError` (a `RuntimeError`).

use hapstab::Error;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    hapstab,
    NumericalError,
    PyRuntimeError,
    "A numerical routine did not converge on valid input (the message says which and why)."
);

/// The library's parameter names and the keyword arguments of the Python API that carry
/// them. A call may put its own pairs in front (see [`Context::py`]).
const KEYWORDS: &[(&str, &str)] = &[
    ("sampling period T", "period"),
    ("delay time t_d", "delay"),
    ("delay d", "delay"),
    ("delay fraction", "delay"),
    ("force lag tau", "force_lag"),
    ("mass m", "mass"),
    ("damping b", "damping"),
    ("stiffness k", "stiffness"),
    ("device mass m_L", "device_mass"),
    ("device damping b_L", "device_damping"),
    ("arm mass m_H", "arm_mass"),
    ("arm damping b_H", "arm_damping"),
    ("arm stiffness k_H", "arm_stiffness"),
    ("motor mass", "motor_mass"),
    ("motor damping", "motor_damping"),
    ("handle mass", "handle_mass"),
    ("handle mass + arm mass", "handle_mass + arm_mass"),
    ("transmission stiffness", "transmission_stiffness"),
    ("transmission damping", "transmission_damping"),
    ("plant numerator coefficient", "num"),
    ("plant denominator coefficient", "den"),
    ("plant numerator", "num"),
    ("plant denominator", "den"),
    ("plant transfer function", "num, den"),
    ("plant order", "den"),
    ("velocity estimator", "velocity"),
    ("velocity low-pass cut-off f_c", "velocity"),
    ("velocity average window N", "velocity"),
    ("velocity filter coefficient", "velocity"),
    ("velocity filter a0", "velocity"),
    ("velocity filter numerator", "velocity"),
    ("velocity filter numerator b", "velocity"),
    ("velocity filter denominator a", "velocity"),
    ("velocity filter length", "velocity"),
    ("gamma", "gamma"),
    ("delta", "delta"),
    ("alpha", "alpha"),
    ("beta", "beta"),
    ("wall stiffness K", "wall_stiffness"),
    ("wall damping B", "wall_damping"),
    ("wall stiffness", "wall_stiffness"),
    ("wall damping", "wall_damping"),
    ("map points", "wall_stiffness, wall_damping"),
    ("region tolerance", "rel_tol"),
    ("wall position x_w", "wall_position"),
    ("quantization q", "quantization"),
    ("saturation F_max", "saturation"),
    ("Coulomb friction F_c", "coulomb_friction"),
    ("static friction F_s", "static_friction"),
    ("friction", "coulomb_friction"),
    ("human force F_H", "human_force"),
    ("human force profile F_H[k]", "human_force"),
    ("initial position", "initial_position"),
    ("initial velocity", "initial_velocity"),
    ("samples", "samples"),
    ("max_samples (the horizon)", "max_samples"),
    ("trace rows", "trace_rows"),
    ("duration", "duration"),
    ("duration / T", "duration"),
];

/// The parameter an error names, in the library's words.
fn parameter(e: &Error) -> Option<&'static str> {
    match e {
        Error::NotFinite { name, .. }
        | Error::NotPositive { name, .. }
        | Error::Negative { name, .. }
        | Error::OutOfRange { name, .. }
        | Error::Invalid { name, .. }
        | Error::Unrepresentable { name, .. } => Some(name),
        Error::FractionalDelay { .. } => Some("delay time t_d"),
        Error::DelayTooLarge { .. } => Some("delay d"),
        Error::Numerical(_) => None,
    }
}

/// The Python exception for a library error, naming the keyword argument: `own` pairs of
/// (library name, keyword) first, then the package-wide table.
pub fn to_py(e: Error, own: &[(&str, &str)]) -> PyErr {
    if let Error::Numerical(_) = e {
        return NumericalError::new_err(e.to_string());
    }
    let keyword = parameter(&e).and_then(|name| {
        own.iter()
            .chain(KEYWORDS)
            .find(|(lib, _)| *lib == name)
            .map(|(_, kw)| *kw)
    });
    match keyword {
        Some(kw) => PyValueError::new_err(format!("{kw}: {e}")),
        None => PyValueError::new_err(e.to_string()),
    }
}

/// A `ValueError` for keyword argument `kw`.
pub fn bad(kw: &str, why: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{kw}: {why}"))
}

/// `?`-friendly conversion of library results.
pub trait Context<T> {
    /// Converts with the package-wide keyword table.
    fn py(self) -> PyResult<T>;
    /// Converts with pairs of (library name, keyword) that take precedence for this call.
    fn py_with(self, own: &[(&str, &str)]) -> PyResult<T>;
}

impl<T> Context<T> for hapstab::Result<T> {
    fn py(self) -> PyResult<T> {
        self.map_err(|e| to_py(e, &[]))
    }

    fn py_with(self, own: &[(&str, &str)]) -> PyResult<T> {
        self.map_err(|e| to_py(e, own))
    }
}

/// A finite float for keyword `kw`.
pub fn finite(kw: &str, x: f64) -> PyResult<f64> {
    if x.is_finite() {
        Ok(x)
    } else {
        Err(bad(kw, format!("must be a finite number (got {x})")))
    }
}
