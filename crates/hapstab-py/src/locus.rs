//! `root_locus`: the roots of p(z) as the virtual stiffness K sweeps at a fixed damping B,
//! the data of `hapstab locus` as numpy arrays (`hapstab::locus::root_locus`, the same call).

use hapstab::limits::{Cost, interval_cost, roots_cost};
use hapstab::locus::{DEFAULT_SAMPLES, RootLocus, root_locus as locus};
use num_complex::Complex64;
use numpy::prelude::*;
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::budget::{check, check_loop, shape_of};
use crate::errors::{Context, bad, finite};
use crate::loops::PyLoop;

/// The result of `root_locus`.
#[pyclass(frozen, get_all, module = "hapstab", name = "RootLocus")]
pub struct PyRootLocus {
    /// The virtual damping B in Ns/m.
    pub wall_damping: f64,
    /// K_max at B in N/m (the upper end of the stable K interval reaching furthest), or None
    /// when no K is stable at B.
    pub k_max: Option<f64>,
    /// That stable interval (lo, hi) of K in N/m, or None.
    pub k_interval: Option<(f64, f64)>,
    /// Index of the sample K = K_max in `wall_stiffness` (None without K_max, or for a given
    /// sweep that does not hold it).
    pub k_max_index: Option<usize>,
    /// The root of p(z) closest to the unit circle at K = K_max: where the locus crosses it.
    pub crossing: Option<Complex64>,
    /// The frequency of the oscillation at K_max in Hz (|arg z|/(2πT) of that root), or None.
    pub crossing_frequency_hz: Option<f64>,
    /// The stiffnesses K of the sweep in N/m.
    pub wall_stiffness: Py<PyArray1<f64>>,
    /// The roots of p(z), one row per K (complex, shape (len(K), degree)), branch-ordered.
    pub roots: Py<PyArray2<Complex64>>,
    /// max |z| at each K.
    pub spectral_radius: Py<PyArray1<f64>>,
}

#[pymethods]
impl PyRootLocus {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "RootLocus(wall_damping={}, k_max={}, samples={})",
            self.wall_damping,
            self.k_max.map_or("None".into(), |k| k.to_string()),
            self.wall_stiffness.bind(py).shape()[0]
        )
    }
}

fn locus_object(py: Python<'_>, rl: RootLocus) -> PyResult<PyRootLocus> {
    let rows = rl.roots.len();
    let cols = rl.roots.first().map_or(0, Vec::len);
    if rl.roots.iter().any(|r| r.len() != cols) {
        return Err(crate::errors::NumericalError::new_err(
            "root_locus: the roots of p(z) differ in number along the sweep",
        ));
    }
    let flat: Vec<Complex64> = rl.roots.into_iter().flatten().collect();
    Ok(PyRootLocus {
        wall_damping: rl.damping,
        k_max: rl.k_max,
        k_interval: rl.k_interval.map(|[lo, hi]| (lo, hi)),
        k_max_index: rl.k_max_index,
        crossing: rl.crossing,
        crossing_frequency_hz: rl.crossing_frequency_hz,
        wall_stiffness: PyArray1::from_vec(py, rl.stiffness).unbind(),
        roots: PyArray1::from_vec(py, flat).reshape([rows, cols])?.unbind(),
        spectral_radius: PyArray1::from_vec(py, rl.spectral_radius).unbind(),
    })
}

/// The root locus in the virtual stiffness K at the damping B (Ns/m): the roots of the
/// characteristic polynomial p(z) (eq. 9) at each K, with the unit circle as the stability
/// boundary (Section V); the data of `hapstab locus`.
///
/// wall_stiffness: the stiffnesses K in N/m (each finite), or None for the command line's
/// sweep (uniform from 0 to 1.5·K_max with the exact ends of the stable K interval inserted,
/// so that at K = K_max, `k_max_index`, a root lies on the unit circle). A loop built by
/// Loop.normalized is refused (K and B are physical here). The GIL is released during the
/// computation.
#[pyfunction]
#[pyo3(signature = (r#loop, wall_damping, wall_stiffness = None))]
pub fn root_locus(
    r#loop: &PyLoop,
    wall_damping: f64,
    wall_stiffness: Option<&Bound<'_, PyAny>>,
    py: Python<'_>,
) -> PyResult<PyRootLocus> {
    if r#loop.normalized {
        return Err(bad(
            "loop",
            "the root locus works in physical units (N/m, Ns/m): build the loop from the plant in kg, Ns/m, N/m and a period, not Loop.normalized",
        ));
    }
    let b = finite("wall_damping", wall_damping)?;
    let lp = &r#loop.lp;
    let sys = r#loop.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let samples = match wall_stiffness {
        Some(x) => shape_of(x)?.iter().product(),
        None => DEFAULT_SAMPLES + 3,
    };
    let per = roots_cost(n);
    let sweep = Cost {
        seconds: per.seconds * samples as f64,
        memory: per.memory + 16.0 * (n * samples) as f64,
    };
    let cost = interval_cost(n).then(sweep);
    match wall_stiffness {
        Some(_) => check(
            cost,
            "wall_stiffness",
            "the root locus",
            "give fewer stiffnesses",
        )?,
        None => check_loop(cost, lp, fam, "the root locus")?,
    }
    let ks: Option<Vec<f64>> = wall_stiffness
        .map(|x| x.extract().map_err(|e| bad("wall_stiffness", e)))
        .transpose()?;
    let rl = py.detach(|| locus(lp, b, ks.as_deref())).py()?;
    locus_object(py, rl)
}
