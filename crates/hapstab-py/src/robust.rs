//! `robust_kmax`: robust K_max of any loop over a box of its parameters, as
//! `hapstab kmax --robust --box … --json` gives it ([`hapstab::robust::robust_kmax`]).

use hapstab::Param;
use hapstab::robust::{BoxSide, RobustKmax, RobustOptions};
use hapstab::sweep::SweepParam;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Context, bad, finite, swept};
use crate::loops::PyLoop;
use crate::text::num;

/// The result of `robust_kmax`.
#[pyclass(frozen, get_all, module = "hapstab", name = "RobustKmax")]
pub struct PyRobustKmax {
    /// The damping B in Ns/m.
    pub wall_damping: f64,
    /// The largest K (N/m) stable for every plant checked: the worst plant's K_max; None
    /// when no K is stable for every plant.
    pub k_max: Option<f64>,
    /// The smallest K (N/m) stable for every plant checked.
    pub k_min: Option<f64>,
    /// K_max of the loop as given, N/m.
    pub k_max_nominal: Option<f64>,
    /// The worst plant: {parameter name: value in its unit}.
    pub worst_plant: Vec<(String, f64)>,
    /// Plants whose exact stable interval was computed.
    pub plants_evaluated: usize,
    /// Random plants verified stable at K_max·(1 − 1e-6).
    pub plants_verified: usize,
    /// Verification plants found below K_max and folded into the search.
    pub verification_found: usize,
}

#[pymethods]
impl PyRobustKmax {
    fn __repr__(&self) -> String {
        format!(
            "RobustKmax(k_max={}, wall_damping={}, worst_plant={:?})",
            self.k_max.map_or("None".into(), num),
            num(self.wall_damping),
            self.worst_plant
        )
    }
}

impl From<RobustKmax> for PyRobustKmax {
    fn from(r: RobustKmax) -> Self {
        PyRobustKmax {
            wall_damping: r.wall_damping,
            k_max: r.k_max,
            k_min: r.k_min,
            k_max_nominal: r.k_max_nominal,
            worst_plant: r
                .worst_plant
                .into_iter()
                .map(|p| (p.param.to_string(), p.value))
                .collect(),
            plants_evaluated: r.plants_evaluated,
            plants_verified: r.plants_verified,
            verification_found: r.verification_found,
        }
    }
}

/// The box's sides from {name: (lo, hi)} with `hapstab sweep --param`'s names, in the
/// dict's order.
fn sides(bounds: &Bound<'_, PyDict>) -> PyResult<Vec<BoxSide>> {
    bounds
        .iter()
        .map(|(k, v)| {
            let name: String = k.extract().map_err(|_| bad("bounds", "keys must be str"))?;
            let (lo, hi): (f64, f64) = v
                .extract()
                .map_err(|_| bad("bounds", format!("{name}: needs a (lo, hi) pair")))?;
            let param: SweepParam = name.parse().py_with(&[(Param::SweepParameter, "bounds")])?;
            let (lo, hi) = (finite("bounds", lo)?, finite("bounds", hi)?);
            if lo > hi {
                return Err(bad(
                    "bounds",
                    format!("{name}: needs lo <= hi (got ({lo}, {hi}))"),
                ));
            }
            Ok(BoxSide { param, lo, hi })
        })
        .collect()
}

/// Robust K_max at `wall_damping` B (Ns/m) over a box of the loop's parameters, `bounds`
/// = {name: (lo, hi)} with `hapstab sweep --param`'s names (arm-stiffness, arm-mass,
/// arm-damping, mass, damping, stiffness, motor-mass, transmission-stiffness, cutoff,
/// delay-time, period, force-lag, …): the box's corners, centre and `samples` seeded
/// uniform plants solved exactly, a compass search from the worst, and `verify` random
/// plants checked by the verdict at K_max·(1 − 1e-6). The numbers of
/// `hapstab kmax --robust --box … --json`.
#[pyfunction]
#[pyo3(signature = (r#loop, bounds, *, wall_damping = 0.0, samples = 256, verify = 10_000, seed = 1))]
pub fn robust_kmax(
    r#loop: &PyLoop,
    bounds: &Bound<'_, PyDict>,
    wall_damping: f64,
    samples: usize,
    verify: usize,
    seed: u64,
    py: Python<'_>,
) -> PyResult<PyRobustKmax> {
    let sides = sides(bounds)?;
    let b = finite("wall_damping", wall_damping)?;
    let opts = RobustOptions {
        samples,
        verify,
        seed,
    };
    let sys = r#loop.system()?;
    let fam = sys.family();
    let lp = &r#loop.lp;
    let n = hapstab::robust::box_degree(lp, &sides).py_with(&swept("bounds"))?;
    let cost = hapstab::limits::robust_box_cost(n, sides.len(), &opts);
    crate::budget::check_loop(cost, lp, fam, "the robust K_max")?;
    let r = py
        .detach(|| hapstab::robust::robust_kmax(lp, &sides, b, &opts))
        .py_with(&swept("bounds"))?;
    Ok(PyRobustKmax::from(r))
}
