//! Section VIII from Python: the stable regions of the γ sweep up to the Nyquist frequency,
//! the robustly stable region and Colgate's passive region checked against it
//! (`nyquist_regions`, the numbers of `hapstab nyquist --json`).

use hapstab::Param;
use hapstab::paper::nyquist::{
    NyquistRegions, SweepInput, SweepRow, no_progress, nyquist_regions as regions,
};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use crate::errors::{Context, bad, finite};
use crate::text::num;

/// The regions of Section VIII for one (δ, d) in normalized units (Table I); the sweep's
/// columns have one entry per swept γ.
#[pyclass(frozen, get_all, module = "hapstab", name = "NyquistRegions")]
pub struct PyNyquistRegions {
    /// δ of Table I.
    pub delta: f64,
    /// The delay d in samples.
    pub d: usize,
    /// γ_N = π² + δ²/4 (eq. 27).
    pub gamma_nyquist: f64,
    /// The swept γ, 0 … gamma_fraction·γ_N.
    pub sweep_gamma: Py<PyArray1<f64>>,
    /// The highest stable α of each swept region (0 when no stable α > 0).
    pub sweep_alpha_max: Py<PyArray1<f64>>,
    /// Where it is reached (NaN when α_max is 0: along a boundary segment).
    pub sweep_beta_at_alpha_max: Py<PyArray1<f64>>,
    /// The lowest stable α of each region.
    pub sweep_alpha_min: Py<PyArray1<f64>>,
    /// The β extent of each region, low end.
    pub sweep_beta_min: Py<PyArray1<f64>>,
    /// The β extent, high end.
    pub sweep_beta_max: Py<PyArray1<f64>>,
    /// The area of each region in α·β.
    pub sweep_area: Py<PyArray1<f64>>,
    /// Regions without a stable wall.
    pub sweep_empty: Vec<bool>,
    /// Swept γ with a pole on the unit circle.
    pub sweep_degenerate: Vec<bool>,
    /// The robust region over γ ∈ [0, gamma_fraction·γ_N]: vertices [α, β], counter-clockwise.
    pub robust_polygon: Py<PyArray2<f64>>,
    /// Its highest α.
    pub robust_alpha_max: f64,
    /// Where it is reached.
    pub robust_beta_at_alpha_max: f64,
    /// Its area in α·β.
    pub robust_area: f64,
    /// The upper end of its γ range.
    pub robust_gamma_hi: f64,
    /// Colgate's passive region (eq. 28) as vertices [α, β] (None at δ = 0).
    pub passive_polygon: Option<Py<PyArray2<f64>>>,
    /// Its area in α·β.
    pub passive_area: Option<f64>,
    /// Whether the passive region lies in the robust region (every checked slice).
    pub passive_inside_robust: Option<bool>,
    /// Eq. (28) is Colgate's condition for d = 0 only.
    pub passive_applies: Option<bool>,
}

#[pymethods]
impl PyNyquistRegions {
    fn __repr__(&self) -> String {
        format!(
            "NyquistRegions(delta={}, d={}, gamma_nyquist={}, robust_alpha_max={})",
            num(self.delta),
            self.d,
            num(self.gamma_nyquist),
            num(self.robust_alpha_max)
        )
    }
}

/// The stable regions of the paper's normalized loop as γ sweeps up to
/// gamma_fraction·γ_N in `steps` steps (eq. 27, Figs. 8–10), the robustly stable region over
/// that γ range, and at δ > 0 Colgate's passive region with whether it lies inside — the
/// numbers of `hapstab nyquist --delta δ --delay d --json`. The GIL is released.
#[pyfunction]
#[pyo3(signature = (delta = 0.0, d = 0, *, gamma_fraction = 1.0, steps = 4, beta_samples = 201, gamma_samples = 41))]
pub fn nyquist_regions(
    delta: f64,
    d: usize,
    gamma_fraction: f64,
    steps: usize,
    beta_samples: usize,
    gamma_samples: usize,
    py: Python<'_>,
) -> PyResult<PyNyquistRegions> {
    finite("delta", delta)?;
    hapstab::params::check_delay(d).py_with(&[(Param::Delay, "d")])?;
    if finite("gamma_fraction", gamma_fraction)? < 0.0 {
        return Err(bad(
            "gamma_fraction",
            format!("must be >= 0 (got {gamma_fraction})"),
        ));
    }
    if steps == 0 {
        return Err(bad("steps", "must be >= 1 (got 0)"));
    }
    let input = SweepInput {
        delta,
        d,
        gamma_fraction,
        steps,
        beta_samples,
        gamma_samples,
    };
    crate::budget::check(
        input.cost(),
        "beta_samples",
        "the sweep and the robust region",
        "use fewer steps, beta_samples or gamma_samples",
    )?;
    let r = py
        .detach(|| regions(input, &no_progress))
        .py_with(&[(Param::Delay, "d")])?;
    regions_object(py, &r)
}

/// [α, β] pairs as an (N, 2) array.
fn pairs_array(py: Python<'_>, v: &[[f64; 2]]) -> PyResult<Py<PyArray2<f64>>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat).reshape([v.len(), 2])?.unbind())
}

/// The Python object of [`NyquistRegions`].
fn regions_object(py: Python<'_>, r: &NyquistRegions) -> PyResult<PyNyquistRegions> {
    let column = |f: &dyn Fn(&SweepRow) -> f64| {
        PyArray1::from_vec(py, r.sweep.iter().map(f).collect()).unbind()
    };
    let passive = r.passive.as_ref();
    Ok(PyNyquistRegions {
        delta: r.input.delta,
        d: r.input.d,
        gamma_nyquist: r.gamma_nyquist,
        sweep_gamma: column(&|s| s.gamma),
        sweep_alpha_max: column(&|s| s.alpha_max),
        sweep_beta_at_alpha_max: column(&|s| s.beta_at_alpha_max.unwrap_or(f64::NAN)),
        sweep_alpha_min: column(&|s| s.alpha_min),
        sweep_beta_min: column(&|s| s.beta_min),
        sweep_beta_max: column(&|s| s.beta_max),
        sweep_area: column(&|s| s.area),
        sweep_empty: r.sweep.iter().map(|s| s.empty).collect(),
        sweep_degenerate: r.sweep.iter().map(|s| s.degenerate).collect(),
        robust_polygon: pairs_array(py, &r.robust.polygon)?,
        robust_alpha_max: r.robust.alpha_max,
        robust_beta_at_alpha_max: r.robust.beta_at_alpha_max,
        robust_area: r.robust.area,
        robust_gamma_hi: r.robust.gamma_hi,
        passive_polygon: passive.map(|p| pairs_array(py, &p.vertices)).transpose()?,
        passive_area: passive.map(|p| p.area),
        passive_inside_robust: passive.map(|p| p.check.inside),
        passive_applies: passive.map(|p| p.applies),
    })
}
