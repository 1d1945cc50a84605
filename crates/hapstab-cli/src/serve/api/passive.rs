//! Colgate's passive triangles of eq. (28) drawn by `/api/region` and tested by `/api/point`
//! (d = 0): the device's own damping, and the arm's damping counted.

use hapstab::nyquist::passive_region;
use serde::Serialize;

use super::region::ab;
use crate::serve::query::{ApiError, PlantSpec, lib_error};

/// Colgate's passive region, eq. (28), for d = 0: δ_L = b_L·T/m of the device's own damping
/// (passive towards any passive operator), or δ with the arm's damping counted.
#[derive(Debug, Clone, Serialize)]
pub struct PassiveOut {
    pub equation: &'static str,
    /// The δ of the triangle.
    pub delta: f64,
    /// Triangle (0, −δ), (2δ, 0), (0, δ) as [α, β].
    pub vertices: Vec<[f64; 2]>,
}

/// δ_L = b_L·T/m of the device's own damping in physical units; δ itself in normalized units
/// (the plant's damping is then all the device's).
pub(super) fn own_delta(spec: &PlantSpec) -> f64 {
    spec.physical.map_or(spec.plant.delta, |ph| {
        ph.device_damping * ph.period / ph.mass
    })
}

pub(super) fn has_arm_damping(spec: &PlantSpec) -> bool {
    spec.physical.is_some_and(|ph| ph.arm_damping > 0.0)
}

/// Colgate's passive triangles for d = 0: the device's own damping, and eq. (28) with the arm's
/// damping counted when an arm with damping holds the device.
pub(super) fn passive_triangles(
    spec: &PlantSpec,
) -> Result<(Option<PassiveOut>, Option<PassiveOut>), ApiError> {
    if spec.d != 0 {
        return Ok((None, None));
    }
    let triangle = |equation, delta: f64| -> Result<PassiveOut, ApiError> {
        let pr = passive_region(delta).map_err(lib_error)?;
        Ok(PassiveOut {
            equation,
            delta,
            vertices: pr.vertices.iter().map(ab).collect(),
        })
    };
    if spec.physical.is_none() {
        let eq = "δ > α/2 + |β|, α ≥ 0  (eq. 28, d = 0)";
        return Ok((Some(triangle(eq, spec.plant.delta)?), None));
    }
    let own = triangle(
        "δ_L > α/2 + |β|, α ≥ 0, δ_L = b_L·T/m: the device's own damping, passive towards any \
         passive operator (Colgate–Schenkel, d = 0)",
        own_delta(spec),
    )?;
    let with_arm = if has_arm_damping(spec) {
        Some(triangle(
            "δ > α/2 + |β|, δ = (b_L + b_H)·T/m: eq. (28) with the arm's damping counted, \
             towards this operator only",
            spec.plant.delta,
        )?)
    } else {
        None
    };
    Ok((Some(own), with_arm))
}
