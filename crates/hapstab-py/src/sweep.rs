//! `sweep`: K_max (stable and passive) against one parameter of a loop, as
//! `hapstab sweep --json` gives it ([`hapstab::sweep::kmax_sweep`]).

use hapstab::sweep::{KmaxAt, SweepParam, SweepPoint};
use numpy::{PyArray1, PyArrayLike1};
use pyo3::prelude::*;

use crate::errors::{Context, bad, finite};
use crate::loops::PyLoop;

/// K_max against a parameter (NaN where a value is missing; `notes` says why).
#[pyclass(frozen, get_all, module = "hapstab", name = "Sweep")]
pub struct PySweep {
    /// The parameter's name, as `--param` spells it ("delay-time", "arm-stiffness", …).
    pub param: String,
    /// The parameter's unit ("s", "Hz", "N/m", …).
    pub unit: String,
    /// The parameter's values.
    pub values: Py<PyArray1<f64>>,
    /// Largest stable K in N/m at each value.
    pub k_max: Py<PyArray1<f64>>,
    /// The B in Ns/m where it is reached.
    pub b_at_k_max: Py<PyArray1<f64>>,
    /// Largest passive K in N/m for the device's own damping, under the same constraint.
    pub k_max_passive: Py<PyArray1<f64>>,
    /// The same by eq. (28) with the arm's damping counted (this operator only).
    pub k_max_passive_with_arm: Py<PyArray1<f64>>,
    /// Why a value is missing, per point (None where nothing is).
    pub notes: Vec<Option<String>>,
    /// Why passivity does not apply, per point (then the passive K_max are NaN; None where it
    /// applies).
    pub passive_notes: Vec<Option<String>>,
}

#[pymethods]
impl PySweep {
    fn __repr__(&self) -> String {
        format!("Sweep(param='{}', points={})", self.param, self.notes.len())
    }
}

/// Where K_max is taken: at one damping, over a band, or overall.
fn k_max_at(wall_damping: Option<f64>, damping_range: Option<(f64, f64)>) -> PyResult<KmaxAt> {
    Ok(match (wall_damping, damping_range) {
        (Some(_), Some(_)) => {
            return Err(bad(
                "wall_damping, damping_range",
                "give one damping B or a damping range, not both",
            ));
        }
        (Some(b), None) => KmaxAt::Damping {
            damping: finite("wall_damping", b)?,
        },
        (None, Some((lo, hi))) => {
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return Err(bad(
                    "damping_range",
                    format!("must be (lo, hi) with lo <= hi (got ({lo}, {hi}))"),
                ));
            }
            KmaxAt::Band { lo, hi }
        }
        (None, None) => KmaxAt::Overall,
    })
}

/// K_max of the loop with one parameter set to each of `values` (in parallel, the GIL
/// released): `param` as `hapstab sweep --param` names it — delay-time, period (the delay
/// time kept), cutoff, window, force-lag, mass, damping, stiffness, motor-mass,
/// motor-damping, handle-mass, transmission-stiffness, transmission-damping, arm-mass,
/// arm-damping, arm-stiffness. K_max at `wall_damping` B (Ns/m), over `damping_range`
/// (lo, hi), or overall; beside it the passive K_max (device's own damping, and eq. (28)
/// with the arm). The numbers of `hapstab sweep --json`.
#[pyfunction]
#[pyo3(signature = (r#loop, param, values, *, wall_damping = None, damping_range = None))]
pub fn sweep(
    r#loop: &PyLoop,
    param: &str,
    values: PyArrayLike1<'_, f64>,
    wall_damping: Option<f64>,
    damping_range: Option<(f64, f64)>,
    py: Python<'_>,
) -> PyResult<PySweep> {
    let name: SweepParam = param.parse().py()?;
    let values: Vec<f64> = values.as_array().to_vec();
    if values.len() > hapstab::sweep::MAX_SWEEP_POINTS {
        return Err(bad(
            "values",
            format!(
                "at most {} values (got {})",
                hapstab::sweep::MAX_SWEEP_POINTS,
                values.len()
            ),
        ));
    }
    for &v in &values {
        finite("values", v)?;
    }
    let at = k_max_at(wall_damping, damping_range)?;
    let cost = hapstab::limits::sweep_cost(&r#loop.lp, name, &values, at);
    crate::budget::check(
        cost,
        "values",
        &format!("the sweep of {} values", values.len()),
        "sweep fewer values",
    )?;
    let base = &r#loop.lp;
    let points = py
        .detach(|| hapstab::sweep::kmax_sweep(&values, |v| name.apply(base, v), at, &|_| {}))
        .py_as("values")?;
    Ok(sweep_object(py, name, &values, &points))
}

fn sweep_object(py: Python<'_>, name: SweepParam, values: &[f64], p: &[SweepPoint]) -> PySweep {
    let col = |f: &dyn Fn(&SweepPoint) -> Option<f64>| {
        PyArray1::from_vec(py, p.iter().map(|x| f(x).unwrap_or(f64::NAN)).collect()).unbind()
    };
    PySweep {
        param: serde_json::to_value(name)
            .ok()
            .and_then(|v| v.as_str().map(str::to_string))
            .unwrap_or_default(),
        unit: name.unit().to_string(),
        values: PyArray1::from_vec(py, values.to_vec()).unbind(),
        k_max: col(&|x| x.k_max),
        b_at_k_max: col(&|x| x.b_at_k_max),
        k_max_passive: col(&|x| x.k_max_passive),
        k_max_passive_with_arm: col(&|x| x.k_max_passive_with_arm),
        notes: p.iter().map(|x| x.note.clone()).collect(),
        passive_notes: p.iter().map(|x| x.passive_note.clone()).collect(),
    }
}
