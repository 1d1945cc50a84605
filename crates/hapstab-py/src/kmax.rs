//! `kmax`: the largest stable stiffness at a damping, over a band of damping, or — without
//! either — at B = 0, over the renderable band and over B ≥ 0, from the library's
//! [`hapstab::kmax::kmax`] (the answer of `hapstab kmax --json`, under the same keys).

use hapstab::answer::{KmaxAnswer, kmax_answer};
use hapstab::kmax::{KmaxQuery, NoiseModel, RenderableBand};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::analysis::interval_text;
use crate::dicts::dict_of;
use crate::errors::{Context, bad};
use crate::loops::PyLoop;
use crate::text::num;

/// The renderable damping band 0 ≤ B ≤ b_max and K_max over it.
#[pyclass(
    frozen,
    get_all,
    from_py_object,
    module = "hapstab",
    name = "RenderableBand"
)]
#[derive(Clone)]
pub struct PyRenderableBand {
    /// Position resolution Δ at the handle, m.
    pub position_resolution: f64,
    /// Largest force noise the damper may add, RMS in N.
    pub force_noise: f64,
    /// The velocity estimator's noise gain ‖V‖₂ in 1/s.
    pub velocity_noise_gain: f64,
    /// The band's upper end F_n·√12/(Δ·‖V‖₂), Ns/m.
    pub b_max: f64,
    /// K_max over the band in N/m; None when no stiffness is stable in it.
    pub k_max: Option<f64>,
    /// The damping that reaches it, Ns/m.
    pub b_at_k_max: Option<f64>,
    /// False where K_max over the band is a supremum (a corner of the region).
    pub k_max_attained: Option<bool>,
}

impl From<&RenderableBand> for PyRenderableBand {
    fn from(r: &RenderableBand) -> Self {
        PyRenderableBand {
            position_resolution: r.noise.position_resolution,
            force_noise: r.noise.force_noise,
            velocity_noise_gain: r.velocity_noise_gain,
            b_max: r.b_max,
            k_max: r.k_max,
            b_at_k_max: r.b_at_k_max,
            k_max_attained: r.k_max_attained,
        }
    }
}

#[pymethods]
impl PyRenderableBand {
    fn __repr__(&self) -> String {
        format!(
            "RenderableBand(b_max={}, k_max={}, b_at_k_max={})",
            num(self.b_max),
            self.k_max.map_or("None".into(), num),
            self.b_at_k_max.map_or("None".into(), num)
        )
    }
}

/// The result of `kmax`.
#[pyclass(frozen, get_all, module = "hapstab", name = "Kmax")]
pub struct PyKmax {
    /// Largest stable K in N/m; None when no K is stable.
    pub k_max: Option<f64>,
    /// The damping B in Ns/m where it holds: the given wall_damping, or where K_max over
    /// the band (damping_range, by default B ≥ 0) is reached.
    pub b_at_k_max: Option<f64>,
    /// With wall_damping: the stable K interval (lo, hi) in N/m that reaches K_max.
    pub k_interval: Option<(f64, f64)>,
    /// The paper's loop: linear condition (22), (b + B)/(t_d + T/2) in N/m at the same B.
    pub k_linear: Option<f64>,
    /// Without wall_damping: False where K_max is a supremum, a corner of the region that
    /// only the damping b_at_k_max touches (approached as B → b_at_k_max); None with a B.
    pub k_max_attained: Option<bool>,
    /// For a supremum: a damping in Ns/m beside b_at_k_max at which k_stable_near_k_max is
    /// stable.
    pub b_stable_near_k_max: Option<f64>,
    /// For a supremum: a stiffness in N/m within 1e-6 of K_max, stable at b_stable_near_k_max.
    pub k_stable_near_k_max: Option<f64>,
    /// Without wall_damping: K_max at B = 0 (no virtual damping), N/m.
    pub k_max_at_zero_damping: Option<f64>,
    /// Without wall_damping and damping_range: the renderable band and K_max over it.
    pub renderable: Option<PyRenderableBand>,
    /// The paper's loop: the same K_max in its normalized units (Table I), {"alpha_max",
    /// "beta", "gamma", "delta", "d"}, as `hapstab kmax --json` gives it; None beyond it.
    pub normalized: Option<Py<PyDict>>,
}

#[pymethods]
impl PyKmax {
    fn __repr__(&self) -> String {
        let opt = |x: Option<f64>| x.map_or("None".into(), num);
        format!(
            "Kmax(k_max={}, b_at_k_max={}, k_interval={}, k_max_at_zero_damping={}{})",
            opt(self.k_max),
            opt(self.b_at_k_max),
            interval_text(self.k_interval),
            opt(self.k_max_at_zero_damping),
            self.renderable
                .as_ref()
                .map_or(String::new(), |r| format!(", renderable={}", r.__repr__()))
        )
    }
}

impl PyKmax {
    /// The library's answer as Python's object; with a given damping B, `b_at_k_max` is B
    /// where a K is stable.
    fn of_answer(py: Python<'_>, a: KmaxAnswer, given_b: Option<f64>) -> PyResult<Self> {
        let r = a.report;
        Ok(PyKmax {
            k_max: r.k_max,
            b_at_k_max: r.b_at_k_max.or(given_b.filter(|_| r.k_max.is_some())),
            k_interval: r.k_interval.map(|[lo, hi]| (lo, hi)),
            k_linear: r.k_linear,
            k_max_attained: r.k_max_attained,
            b_stable_near_k_max: r.b_stable_near_k_max,
            k_stable_near_k_max: r.k_stable_near_k_max,
            k_max_at_zero_damping: r.k_max_at_zero_damping,
            renderable: r.renderable.as_ref().map(PyRenderableBand::from),
            normalized: a.paper.map(|p| dict_of(py, &p)).transpose()?,
        })
    }
}

/// The query of the keyword arguments: one damping, a band, or the design query.
fn query(
    wall_damping: Option<f64>,
    damping_range: Option<(f64, f64)>,
    position_resolution: Option<f64>,
    force_noise: Option<f64>,
) -> PyResult<KmaxQuery> {
    let noise_given = position_resolution.is_some() || force_noise.is_some();
    match (wall_damping, damping_range) {
        (Some(_), Some(_)) => Err(bad(
            "wall_damping, damping_range",
            "give one damping B or a damping range, not both",
        )),
        (Some(_), None) | (None, Some(_)) if noise_given => Err(bad(
            "position_resolution, force_noise",
            "set the renderable band, which is reported only without wall_damping and \
             damping_range",
        )),
        (Some(b), None) => Ok(KmaxQuery::AtDamping(crate::errors::finite(
            "wall_damping",
            b,
        )?)),
        (None, Some((lo, hi))) => {
            if lo.is_nan() || hi.is_nan() || lo > hi {
                return Err(bad(
                    "damping_range",
                    format!("must be (B_lo, B_hi) in Ns/m with B_lo <= B_hi (got ({lo}, {hi}))"),
                ));
            }
            Ok(KmaxQuery::Band { lo, hi })
        }
        (None, None) => {
            let d = NoiseModel::default();
            let dx = position_resolution.unwrap_or(d.position_resolution);
            let f = force_noise.unwrap_or(d.force_noise);
            Ok(KmaxQuery::Design(NoiseModel::new(dx, f).py()?))
        }
    }
}

/// The largest stable virtual stiffness K_max in N/m (Section V). With wall_damping B in
/// Ns/m: the upper end of the stable K interval reaching furthest at that B. With
/// damping_range (B_lo, B_hi) in Ns/m (B_hi may be inf): the largest stable K over that band
/// and the B that reaches it, beside K_max at B = 0. Without either (as `hapstab kmax`):
/// K_max over B ≥ 0 with its B, K_max at B = 0, and K_max over the renderable band
/// 0 ≤ B ≤ F_n·√12/(Δ·‖V‖₂) that position steps Δ (position_resolution, m) and the force
/// noise allowed F_n (force_noise, RMS in N) leave. Beside it, the paper's linear condition
/// (22) K < (b + B)/(t_d + T/2).
#[pyfunction]
#[pyo3(signature = (r#loop, *, wall_damping = None, damping_range = None,
                    position_resolution = None, force_noise = None))]
pub fn kmax(
    r#loop: &PyLoop,
    wall_damping: Option<f64>,
    damping_range: Option<(f64, f64)>,
    position_resolution: Option<f64>,
    force_noise: Option<f64>,
    py: Python<'_>,
) -> PyResult<PyKmax> {
    let q = query(
        wall_damping,
        damping_range,
        position_resolution,
        force_noise,
    )?;
    let sys = r#loop.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let cost = match q {
        KmaxQuery::AtDamping(_) => hapstab::limits::interval_cost(n),
        _ => hapstab::limits::region_cost_of_degree(n, hapstab::limits::core_degree(fam)),
    };
    crate::budget::check_loop(cost, &r#loop.lp, fam, "K_max")?;
    let answer = py.detach(|| kmax_answer(&sys, q)).py()?;
    let given_b = match q {
        KmaxQuery::AtDamping(b) => Some(b),
        _ => None,
    };
    PyKmax::of_answer(py, answer, given_b)
}
