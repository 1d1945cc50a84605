//! `stability_map`: the grid method of Section V over the wall (K, B) of any loop, one
//! Schur–Cohn test per point, in parallel with the GIL released.

use hapstab::map::{MapKind, MapValues, wall_map_points, wall_map_values};
use numpy::{
    AllowTypeChange, IxDyn, PyArray1, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::errors::{Context, bad};
use crate::loops::PyLoop;

/// The result of `stability_map`.
#[pyclass(frozen, get_all, module = "hapstab", name = "StabilityMap")]
pub struct PyStabilityMap {
    /// True where every root of p(z) lies inside the unit circle (bool array).
    pub stable: Py<PyArrayDyn<bool>>,
    /// With spectral_radius=True: the largest root modulus (float64 array, same shape; the
    /// smallest r with every root inside |z| < r, by bisection on the Schur–Cohn test of
    /// p(rz), to about 1e-15 relative); else None.
    pub spectral_radius: Option<Py<PyArrayDyn<f64>>>,
}

#[pymethods]
impl PyStabilityMap {
    fn __repr__(&self, py: Python<'_>) -> String {
        let shape = self.stable.bind(py).shape().to_vec();
        format!(
            "StabilityMap(shape={shape:?}, spectral_radius={})",
            if self.spectral_radius.is_some() {
                "array"
            } else {
                "None"
            }
        )
    }
}

/// The values of an array divided by a unit, copied (the GIL is released afterwards, and
/// another Python thread may write to the caller's array meanwhile).
fn in_units(x: &PyArrayLikeDyn<'_, f64, AllowTypeChange>, unit: f64) -> Vec<f64> {
    x.as_array().iter().map(|v| v / unit).collect()
}

fn shaped<'py, T: numpy::Element>(
    py: Python<'py>,
    v: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
    PyArray1::from_vec(py, v).reshape(IxDyn(shape))
}

/// Stability of the wall over a grid (the paper's grid method, Section V): at each wall
/// (K, B) the Schur–Cohn test of p(z) = P0(z) + K·PK(z) + B·PB(z) (eq. 9, generalized), in
/// parallel on all cores with the GIL released.
///
/// wall_stiffness (K in N/m) and wall_damping (B in Ns/m) are either two 1-D arrays, the
/// grid's axes (the result has shape (len(wall_damping), len(wall_stiffness)): rows are B,
/// columns K, as numpy.meshgrid(wall_stiffness, wall_damping)), or two arrays of the same
/// shape, one wall per element (the result has that shape).
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness, wall_damping, *, spectral_radius = false))]
pub fn stability_map<'py>(
    py: Python<'py>,
    r#loop: &PyLoop,
    wall_stiffness: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    wall_damping: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    spectral_radius: bool,
) -> PyResult<PyStabilityMap> {
    let fam = r#loop.family()?;
    let kind = if spectral_radius {
        MapKind::SpectralRadius
    } else {
        MapKind::Stability
    };
    let (ks, bs) = (
        wall_stiffness.shape().to_vec(),
        wall_damping.shape().to_vec(),
    );
    let a = in_units(&wall_stiffness, fam.scale.stiffness);
    let b = in_units(&wall_damping, fam.scale.damping);
    let (values, shape): (hapstab::Result<MapValues>, Vec<usize>) = if ks.len() == 1
        && bs.len() == 1
    {
        (
            py.detach(|| wall_map_values(&fam, &a, &b, kind)),
            vec![bs[0], ks[0]],
        )
    } else if ks == bs {
        (py.detach(|| wall_map_points(&fam, &a, &b, kind)), ks)
    } else {
        return Err(bad(
            "wall_stiffness, wall_damping",
            format!(
                "must be two 1-D axes or two arrays of the same shape (got shapes {ks:?} and {bs:?})"
            ),
        ));
    };
    let values = values.py()?;
    Ok(PyStabilityMap {
        stable: shaped(py, values.stable, &shape)?.unbind(),
        spectral_radius: values
            .radius
            .map(|r| shaped(py, r, &shape).map(Bound::unbind))
            .transpose()?,
    })
}
