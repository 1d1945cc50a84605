//! `stability_map`: the grid method of Section V over the wall (K, B) of any loop, one
//! Schur–Cohn test per point, in parallel with the GIL released.

use hapstab::map::{MapKind, wall_map_points, wall_map_values};
use numpy::{
    AllowTypeChange, IntoPyArray, IxDyn, PyArray1, PyArrayDyn, PyArrayLikeDyn, PyArrayMethods,
    PyUntypedArrayMethods,
};
use pyo3::prelude::*;

use crate::budget::shape_of;
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
    /// The wall stiffnesses asked for, N/m (float64 copy): the grid's K axis, or one K per
    /// wall (`grid`).
    pub wall_stiffness: Py<PyArrayDyn<f64>>,
    /// The wall dampings asked for, Ns/m (float64 copy): the grid's B axis, or one B per wall.
    pub wall_damping: Py<PyArrayDyn<f64>>,
    /// True when wall_stiffness and wall_damping are the grid's axes (rows B, columns K),
    /// False when they hold one wall per element.
    pub grid: bool,
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
/// wall_stiffness (K in N/m) and wall_damping (B in Ns/m) are either the grid's two 1-D axes
/// (grid=True: the result has shape (len(wall_damping), len(wall_stiffness)), rows are B and
/// columns K, as numpy.meshgrid(wall_stiffness, wall_damping)), or two arrays of the same
/// shape, one wall per element (grid=False: the result has that shape). By default
/// (grid=None) two 1-D arrays are axes and arrays of any other same shape are walls; pass
/// grid=False for an elementwise map of two 1-D arrays.
///
/// The cost is estimated from the arrays' shapes before they are copied, and a map beyond
/// the command line's budget is refused naming wall_stiffness, wall_damping.
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness, wall_damping, *, spectral_radius = false,
                    grid = None))]
pub fn stability_map<'py>(
    py: Python<'py>,
    r#loop: &PyLoop,
    wall_stiffness: &Bound<'py, PyAny>,
    wall_damping: &Bound<'py, PyAny>,
    spectral_radius: bool,
    grid: Option<bool>,
) -> PyResult<PyStabilityMap> {
    let sys = r#loop.system()?;
    let fam = sys.family();
    let kind = if spectral_radius {
        MapKind::SpectralRadius
    } else {
        MapKind::Stability
    };
    let (ks, bs) = (shape_of(wall_stiffness)?, shape_of(wall_damping)?);
    let as_grid = layout(&ks, &bs, grid)?;
    let shape = if as_grid {
        vec![bs[0], ks[0]]
    } else {
        ks.clone()
    };
    // the copies of the inputs in wall units
    let inputs = if as_grid {
        8.0 * (ks[0] + bs[0]) as f64
    } else {
        16.0 * shape.iter().map(|&n| n as f64).product::<f64>()
    };
    check_budget(&r#loop.lp, fam, &shape, spectral_radius, inputs)?;
    let extract = |x: &Bound<'py, PyAny>, kw: &str| {
        x.extract::<PyArrayLikeDyn<'py, f64, AllowTypeChange>>()
            .map_err(|e| pyo3::exceptions::PyTypeError::new_err(format!("{kw}: {e}")))
    };
    let k = extract(wall_stiffness, "wall_stiffness")?;
    let b_in = extract(wall_damping, "wall_damping")?;
    let a = in_units(&k, fam.scale.stiffness);
    let b = in_units(&b_in, fam.scale.damping);
    let values = if as_grid {
        py.detach(|| wall_map_values(fam, &a, &b, kind))
    } else {
        py.detach(|| wall_map_points(fam, &a, &b, kind))
    };
    let values = values.py()?;
    let copy = |x: &PyArrayLikeDyn<'py, f64, AllowTypeChange>| {
        x.as_array().to_owned().into_pyarray(py).unbind()
    };
    Ok(PyStabilityMap {
        wall_stiffness: copy(&k),
        wall_damping: copy(&b_in),
        grid: as_grid,
        stable: shaped(py, values.stable, &shape)?.unbind(),
        spectral_radius: values
            .radius
            .map(|r| shaped(py, r, &shape).map(Bound::unbind))
            .transpose()?,
    })
}

/// Whether the two shapes are a grid's axes (true) or elementwise walls (false), as `grid`
/// asks or by default (two 1-D arrays are axes).
fn layout(ks: &[usize], bs: &[usize], grid: Option<bool>) -> PyResult<bool> {
    let axes = ks.len() == 1 && bs.len() == 1;
    match grid {
        Some(true) if axes => Ok(true),
        Some(true) => Err(bad(
            "wall_stiffness, wall_damping",
            format!("must be two 1-D axes with grid=True (got shapes {ks:?} and {bs:?})"),
        )),
        Some(false) if ks == bs => Ok(false),
        None if axes => Ok(true),
        None if ks == bs => Ok(false),
        _ => Err(bad(
            "wall_stiffness, wall_damping",
            format!(
                "must be two 1-D axes or two arrays of the same shape (got shapes {ks:?} and {bs:?})"
            ),
        )),
    }
}

/// Refuses a map beyond the budget or beyond [`hapstab::limits::MAX_MAP_POINTS`] from its
/// shape alone: every point a Schur–Cohn test (or a spectral radius) of p(z), and the input
/// copies (`inputs` bytes) and the results in memory.
fn check_budget(
    lp: &hapstab::model::Loop,
    fam: &hapstab::AffineFamily,
    shape: &[usize],
    radius: bool,
    inputs: f64,
) -> PyResult<()> {
    let points = shape.iter().map(|&n| n as f64).product::<f64>();
    if points > hapstab::limits::MAX_MAP_POINTS as f64 {
        return Err(bad(
            "wall_stiffness, wall_damping",
            format!(
                "map points: {points:e} walls, at most {:e} are allowed",
                hapstab::limits::MAX_MAP_POINTS as f64
            ),
        ));
    }
    let mut cost = hapstab::limits::map_cost_of_degree(points, fam.degree(), radius, 1.0);
    cost.memory += inputs;
    let why = format!("use fewer walls; {}", crate::budget::degree_reason(lp, fam));
    crate::budget::check(
        cost,
        "wall_stiffness, wall_damping",
        &format!("the map of {points:e} walls"),
        &why,
    )
}
