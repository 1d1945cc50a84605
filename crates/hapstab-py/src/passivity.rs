//! `passivity`: the device damping a wall requires to be passive (Colgate–Schenkel; eq. 28
//! for the paper's loop, Section VIII), the verdict for the device and its passive region,
//! through the library calls of the command line's `hapstab passivity`.

use hapstab::answer::{PassiveRegionOut, PassivityAnswer, passivity_answer_for};
use hapstab::params::Wall;
use hapstab::passivity::{DeviceDamping, device_damping};
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;

use crate::errors::{Context, bad, finite};
use crate::loops::PyLoop;
use crate::text::num;
use crate::wall::WallArgs;

/// The passive region of the device: the walls (K, B) it renders passively.
#[pyclass(frozen, get_all, module = "hapstab", name = "PassiveRegion")]
pub struct PyPassiveRegion {
    /// The largest passive stiffness K in N/m (exact, on the boundary; inf when the region is
    /// unbounded in K).
    pub k_max: f64,
    /// The damping B in Ns/m at which k_max is reached.
    pub b_at_k_max: f64,
    /// Area in (N/m)·(Ns/m).
    pub area: f64,
    /// False when the region is unbounded (the polygon is then cut at ten times the size of
    /// its bounded part).
    pub bounded: bool,
    /// Counter-clockwise vertices as an (N, 2) float64 array of [K in N/m, B in Ns/m], first
    /// vertex not repeated; exact boundary points, chords within 1e-5 of the region's size.
    pub vertices: Py<PyArray2<f64>>,
}

#[pymethods]
impl PyPassiveRegion {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "PassiveRegion(k_max={}, b_at_k_max={}, area={}, bounded={}, vertices={})",
            num(self.k_max),
            num(self.b_at_k_max),
            num(self.area),
            if self.bounded { "True" } else { "False" },
            self.vertices.bind(py).shape()[0]
        )
    }
}

/// The result of `passivity`.
#[pyclass(frozen, get_all, module = "hapstab", name = "Passivity")]
pub struct PyPassivity {
    /// The wall's stiffness K in N/m.
    pub wall_stiffness: f64,
    /// The wall's damping B in Ns/m.
    pub wall_damping: f64,
    /// The device damping the wall requires, in Ns/m (δ on a Loop.normalized): the maximum
    /// over 0 ≤ ωT ≤ π of (T/2)·Re{(1 − e^{−jωT}) H(e^{jωT})}/(1 − cos ωT).
    pub b_required: f64,
    /// Where the requirement binds, in Hz (cycles per sample on a Loop.normalized).
    pub binding_frequency_hz: f64,
    /// The same as θ = ωT in [0, π] rad.
    pub binding_theta: f64,
    /// The wall's static stiffness K + B·V(1) in N/m (passivity needs it >= 0).
    pub dc_stiffness: f64,
    /// The device damping b in Ns/m the requirement is compared with: the device's own b_L,
    /// the arm's excluded (passivity towards any passive operator); None when the argument
    /// does not apply (see note).
    pub device_damping: Option<f64>,
    /// The paper's eq. (28) read with the effective damping b = b_L + b_H of eq. (1), the arm
    /// included: passivity towards this operator only. None unless the plant was built from
    /// a device and an arm (and no device_damping was given).
    pub effective_damping: Option<f64>,
    /// The verdict against effective_damping (as verdict), or None.
    pub effective_verdict: Option<String>,
    /// True when b > b_required and the static stiffness is >= 0; None when not applicable.
    pub meets: Option<bool>,
    /// "passive", "boundary" (b equals the requirement to 1e-12 relative), "not_passive" or
    /// "not_applicable".
    pub verdict: String,
    /// Why the verdict is "not_applicable", else None.
    pub note: Option<String>,
    /// The wall's stability verdict (Schur–Cohn, the same test as `check`), to read beside the
    /// passivity verdict: a stable wall need not be passive (common with delay).
    pub stable: bool,
    /// The passive region for the device damping; None when not applicable.
    pub passive_region: Option<Py<PyPassiveRegion>>,
}

#[pymethods]
impl PyPassivity {
    fn __repr__(&self) -> String {
        let dev = self.device_damping.map_or("None".into(), num);
        format!(
            "Passivity(verdict='{}', b_required={}, device_damping={dev}, binding_frequency_hz={}, stable={})",
            self.verdict,
            num(self.b_required),
            num(self.binding_frequency_hz),
            if self.stable { "True" } else { "False" }
        )
    }
}

/// The device damper that replaces the plant's own: the given b unless the argument does not
/// hold for the loop at all (an actuator lag: the held force is filtered); None without one.
fn device_of(lp: &PyLoop, given: Option<f64>) -> PyResult<Option<DeviceDamping>> {
    let own = device_damping(&lp.lp.plant);
    let Some(b) = given else { return Ok(None) };
    let b = finite("device_damping", b)?;
    if b < 0.0 {
        return Err(bad(
            "device_damping",
            format!("the device damping b must be >= 0 Ns/m (got {b})"),
        ));
    }
    if lp.lp.plant.force_lag > 0.0 {
        return Ok(Some(own));
    }
    Ok(Some(DeviceDamping::Known { damping: b }))
}

pub(crate) fn region_object(py: Python<'_>, r: &PassiveRegionOut) -> PyResult<PyPassiveRegion> {
    let flat: Vec<f64> = r.vertices.iter().flatten().copied().collect();
    let vertices = PyArray1::from_vec(py, flat).reshape([r.vertices.len(), 2])?;
    Ok(PyPassiveRegion {
        k_max: r.k_max,
        b_at_k_max: r.b_at_k_max,
        area: r.area,
        bounded: r.bounded,
        vertices: vertices.unbind(),
    })
}

/// The Python object of the library's answer (the same keys as `hapstab passivity --json`).
fn passivity_object(py: Python<'_>, a: PassivityAnswer, wall: Wall) -> PyResult<PyPassivity> {
    let passive_region = match &a.passive_region {
        Some(r) => Some(Py::new(py, region_object(py, r)?)?),
        None => None,
    };
    Ok(PyPassivity {
        wall_stiffness: wall.stiffness,
        wall_damping: wall.damping,
        b_required: a.b_required,
        binding_frequency_hz: a.binding_frequency_hz,
        binding_theta: a.binding_theta,
        dc_stiffness: a.dc_stiffness,
        device_damping: a.device_damping,
        effective_damping: a.effective_damping,
        effective_verdict: a.effective_verdict.map(|v| v.as_str().into()),
        meets: a.meets,
        verdict: a.verdict.as_str().into(),
        note: a.note,
        stable: a.stable,
        passive_region,
    })
}

/// Is the sampled virtual wall passive on this device? Colgate and Schenkel's condition: a
/// device of damping b renders the discrete wall H(z) = z^{−d}·(K + B·V(z)) (V the velocity
/// estimator, d the delay in samples) through a zero-order hold passively iff
///
///     b > (T/2) · max over 0 ≤ ωT ≤ π of Re{(1 − e^{−jωT}) H(e^{jωT})} / (1 − cos ωT)
///
/// and the wall's static stiffness K + B·V(1) is >= 0. For the paper's loop (backward
/// difference, no delay) the right side is KT/2 + |B|: eq. (28), δ > α/2 + |β| in the
/// normalized units of Table I (Section VIII). With d samples of delay and B = 0 it is
/// K(T/2 + dT); a fractional delay is derived exactly (the human moving within a sample). The
/// maximum over frequency is found exactly (grid, then every candidate refined), evaluated
/// without cancellation at small ω.
///
/// The wall is K in N/m and B in Ns/m, or α = KT²/m, β = BT/m (as in `check`). The device
/// damping b is the device's own (b_L of MassSpringDamper.from_device_and_arm and Loop.paper,
/// the arm's b_H excluded: passive towards any passive operator; b of a MassSpringDamper
/// given as m, b, k; the motor-side damping of a TwoMass; b of a TransferFunction
/// c/(ms² + bs + k)); effective_damping and effective_verdict give the paper's eq. (28) with
/// b = b_L + b_H, towards this operator only. device_damping in Ns/m replaces b (not with an
/// actuator lag, where the condition does not apply). Also returns the wall's stability and
/// the passive region {(K, B): passive for b} as a polygon. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, *, alpha = None,
                    beta = None, device_damping = None))]
pub fn passivity(
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    alpha: Option<f64>,
    beta: Option<f64>,
    device_damping: Option<f64>,
    py: Python<'_>,
) -> PyResult<PyPassivity> {
    let sys = r#loop.system()?;
    let fam = sys.family();
    let n = fam.degree();
    let cost = hapstab::limits::passivity_cost(n, hapstab::limits::core_degree(fam))
        .then(hapstab::limits::roots_cost(n));
    crate::budget::check_loop(cost, &r#loop.lp, fam, "the passive region")?;
    let args = WallArgs {
        stiffness: wall_stiffness,
        damping: wall_damping,
        alpha,
        beta,
    };
    let w = args.resolve(r#loop, fam)?;
    let device = device_of(r#loop, device_damping)?;
    let (answer, p) = py
        .detach(|| passivity_answer_for(&sys, r#loop.normalized, w, device))
        .py()?;
    passivity_object(py, answer, p.wall)
}
