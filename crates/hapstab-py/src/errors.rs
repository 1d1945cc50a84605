//! The library's errors as Python exceptions: a bad argument is a `ValueError` whose message
//! starts with the keyword argument that carries it ("period: sampling period T must be > 0
//! (got 0)", the keyword from the error's [`Param`]); a numerical routine that did not
//! converge on valid input is a `hapstab.NumericalError` (a `RuntimeError`).

use hapstab::sweep::SweepParam;
use hapstab::{Error, Param};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;

pyo3::create_exception!(
    hapstab,
    NumericalError,
    PyRuntimeError,
    "A numerical routine did not converge on valid input (the message says which and why)."
);

/// How a call names the keyword arguments behind the library's parameters.
enum Naming<'a> {
    /// Each parameter by its own keyword ([`Param::keyword`]), unless the call gives another
    /// one for it here (a call whose keyword differs from the package's usual one).
    Own(&'a [(Param, &'a str)]),
    /// Every parameter by one keyword: the call takes the parameters' values in it (a sweep's
    /// `values`).
    All(&'a str),
}

impl Naming<'_> {
    fn keyword(&self, p: Param) -> Option<&str> {
        match self {
            Naming::Own(own) => own
                .iter()
                .find(|(q, _)| *q == p)
                .map(|(_, kw)| *kw)
                .or(p.keyword()),
            Naming::All(kw) => Some(kw),
        }
    }
}

/// The Python exception for a library error, naming the keyword argument that carries its
/// parameter.
fn to_py(e: Error, naming: &Naming<'_>) -> PyErr {
    if let Error::Numerical(_) = e {
        return NumericalError::new_err(e.to_string());
    }
    match e.param().and_then(|p| naming.keyword(p)) {
        Some(kw) => PyValueError::new_err(format!("{kw}: {e}")),
        None => PyValueError::new_err(e.to_string()),
    }
}

/// Each parameter a sweep can set (a box's side, a population's distribution) renamed to
/// the keyword `kw` that takes their values, with the sweep's names themselves.
pub fn swept(kw: &str) -> Vec<(Param, &str)> {
    SweepParam::ALL
        .iter()
        .map(|p| (p.param(), kw))
        .chain([(Param::SweepParameter, kw)])
        .collect()
}

/// A `ValueError` for keyword argument `kw`.
pub fn bad(kw: &str, why: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(format!("{kw}: {why}"))
}

/// `?`-friendly conversion of library results.
pub trait Context<T> {
    /// Converts, naming each parameter by its keyword ([`Param::keyword`]).
    fn py(self) -> PyResult<T>;
    /// Converts with this call's own keywords for some parameters.
    fn py_with(self, own: &[(Param, &str)]) -> PyResult<T>;
    /// Converts, naming every parameter by the keyword `kw`.
    fn py_as(self, kw: &str) -> PyResult<T>;
}

impl<T> Context<T> for hapstab::Result<T> {
    fn py(self) -> PyResult<T> {
        self.map_err(|e| to_py(e, &Naming::Own(&[])))
    }

    fn py_with(self, own: &[(Param, &str)]) -> PyResult<T> {
        self.map_err(|e| to_py(e, &Naming::Own(own)))
    }

    fn py_as(self, kw: &str) -> PyResult<T> {
        self.map_err(|e| to_py(e, &Naming::All(kw)))
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

/// Each library parameter's key with the keyword argument(s) that carry it ("num, den",
/// "handle_mass + arm_mass"), None when no keyword does: the package's tests check that each
/// is a keyword of the API.
#[pyfunction]
pub fn _parameter_keywords() -> Vec<(&'static str, Option<&'static str>)> {
    Param::ALL.iter().map(|p| (p.key(), p.keyword())).collect()
}
