//! `zwidth`: the Z-width of a loop, as `hapstab zwidth --json` gives it
//! ([`hapstab::zwidth::zwidth`]): the stable and passive regions, K_max and the K_max table
//! against the virtual damping.

use hapstab::Wall;
use hapstab::passivity::DeviceDamping;
use hapstab::zwidth::ZWidth;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;

use crate::errors::{Context, finite};
use crate::loops::PyLoop;
use crate::passivity::{PyPassiveRegion, region_object};
use crate::text::num;
use hapstab::answer::PassiveRegionOut;

/// The Z-width of a loop (the names of `hapstab zwidth --json`; K in N/m, B in Ns/m).
#[pyclass(frozen, get_all, module = "hapstab", name = "ZWidth")]
pub struct PyZWidth {
    /// The stable region's components as (N, 2) float64 arrays of [K, B], counter-clockwise.
    pub stable: Vec<Py<PyArray2<f64>>>,
    /// Area of the stable region in (N/m)·(Ns/m).
    pub stable_area: f64,
    /// The largest stable K and the B that reaches it (None when nothing is stable).
    pub k_max: Option<f64>,
    /// The B at k_max.
    pub b_at_k_max: Option<f64>,
    /// The largest stable K with B >= 0, and its B.
    pub k_max_nonnegative_damping: Option<(f64, f64)>,
    /// The device damping passivity and the linear condition use (None: not applicable).
    pub device_damping: Option<f64>,
    /// The passive region for the device's own damping (None when passivity does not apply).
    pub passive: Option<Py<PyPassiveRegion>>,
    /// The largest passive (K, B) by eq. (28) with the arm's damping counted (this operator
    /// only); None without an arm.
    pub k_max_passive_with_arm: Option<(f64, f64)>,
    /// Whether every tested wall strictly inside the passive region is stable.
    pub passive_inside_stable: Option<bool>,
    /// The linear condition (22) as (b, t_r): K < (b + B)/t_r.
    pub linear: Option<(f64, f64)>,
    /// The table's dampings B in Ns/m.
    pub table_damping: Py<PyArray1<f64>>,
    /// K_max at each B (NaN where no K is stable).
    pub table_k_max: Py<PyArray1<f64>>,
    /// The lower end of that stable interval (NaN where none).
    pub table_k_min: Py<PyArray1<f64>>,
    /// The largest passive K at each B (NaN where none or not applicable).
    pub table_k_max_passive: Py<PyArray1<f64>>,
    /// The linear condition's limit at each B (NaN without a device damping).
    pub table_k_linear: Py<PyArray1<f64>>,
}

#[pymethods]
impl PyZWidth {
    fn __repr__(&self) -> String {
        format!(
            "ZWidth(k_max={}, b_at_k_max={}, stable_area={}, components={})",
            self.k_max.map_or("None".into(), num),
            self.b_at_k_max.map_or("None".into(), num),
            num(self.stable_area),
            self.stable.len()
        )
    }
}

/// The Z-width of a loop (Colgate and Brown): the stable region in (K, B) with its K_max
/// (overall and with B >= 0), the passive region for the device's own damping
/// (Colgate–Schenkel), eq. (28) with the arm's damping, the linear condition (22), and K_max
/// (stable, passive, linear) at each damping of `table_damping` (Ns/m; default: 11 values
/// from 0 toward the region's largest B) — the numbers of `hapstab zwidth --json`.
#[pyfunction]
#[pyo3(signature = (r#loop, *, table_damping = None))]
pub fn zwidth(
    r#loop: &PyLoop,
    table_damping: Option<Vec<f64>>,
    py: Python<'_>,
) -> PyResult<PyZWidth> {
    if let Some(t) = &table_damping {
        for &b in t {
            finite("table_damping", b)?;
        }
    }
    let sys = r#loop.system()?;
    let fam = sys.family();
    let rows = table_damping.as_ref().map_or(8, Vec::len);
    crate::budget::check_loop(
        hapstab::limits::zwidth_cost(fam, rows),
        &r#loop.lp,
        fam,
        "the Z-width",
    )?;
    let lp = &r#loop.lp;
    let z = py
        .detach(|| hapstab::zwidth::zwidth(lp, table_damping.as_deref()))
        .py()?;
    zwidth_object(py, &z)
}

fn walls_array<'py>(py: Python<'py>, w: &[Wall]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = w.iter().flat_map(|v| [v.stiffness, v.damping]).collect();
    PyArray1::from_vec(py, flat).reshape([w.len(), 2])
}

fn column(
    py: Python<'_>,
    z: &ZWidth,
    f: impl Fn(&hapstab::zwidth::ZWidthRow) -> Option<f64>,
) -> Py<PyArray1<f64>> {
    let v: Vec<f64> = z.table.iter().map(|r| f(r).unwrap_or(f64::NAN)).collect();
    PyArray1::from_vec(py, v).unbind()
}

fn zwidth_object(py: Python<'_>, z: &ZWidth) -> PyResult<PyZWidth> {
    let pair = |w: Option<Wall>| w.map(|w| (w.stiffness, w.damping));
    Ok(PyZWidth {
        stable: z
            .stable
            .iter()
            .map(|p| walls_array(py, p).map(Bound::unbind))
            .collect::<PyResult<_>>()?,
        stable_area: z.stable_area,
        k_max: z.k_max.map(|w| w.stiffness),
        b_at_k_max: z.k_max.map(|w| w.damping),
        k_max_nonnegative_damping: pair(z.k_max_nonnegative_damping),
        device_damping: match &z.device_damping {
            DeviceDamping::Known { damping } => Some(*damping),
            DeviceDamping::NotApplicable { .. } => None,
        },
        passive: match &z.passive {
            Some(r) => Some(Py::new(py, region_object(py, &PassiveRegionOut::from(r))?)?),
            None => None,
        },
        k_max_passive_with_arm: pair(z.k_max_passive_with_arm),
        passive_inside_stable: z.passive_inside_stable,
        linear: z.linear.map(|l| (l.damping, l.effective_delay)),
        table_damping: column(py, z, |r| Some(r.damping)),
        table_k_max: column(py, z, |r| r.k_max),
        table_k_min: column(py, z, |r| r.k_min),
        table_k_max_passive: column(py, z, |r| r.k_max_passive),
        table_k_linear: column(py, z, |r| r.k_linear),
    })
}
