//! Library answers given to Python as dicts with the keys of the command line's JSON.

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::bad;

/// `v` serialized as the command line's JSON writes it, as a Python dict.
pub(crate) fn dict_of<'py>(py: Python<'py>, v: &impl serde::Serialize) -> PyResult<Py<PyDict>> {
    let json = serde_json::to_string(v).map_err(|e| bad("result", e))?;
    let loads = py.import("json")?.getattr("loads")?;
    Ok(loads.call1((json,))?.cast_into::<PyDict>()?.unbind())
}
