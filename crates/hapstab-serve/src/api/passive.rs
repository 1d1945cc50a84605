//! Colgate–Schenkel's passive region drawn by `/api/region` on any loop, from the library
//! ([`hapstab::passivity::passive_region`], eq. 28 generalized to any delay and velocity
//! estimator): for the device's own damping (passive towards any passive operator), and with
//! the arm's damping counted (eq. 28 read with eq. 1's b: towards this operator only). The
//! same walls `/api/point` calls passive.

use hapstab::passivity::{
    DeviceDamping, PassiveRegion, SampledWall, device_damping, passive_region,
};
use serde::Serialize;

use crate::query::{ApiError, PlantSpec, lib_error};

/// A passive region in the user's units.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct PassiveOut {
    pub equation: &'static str,
    /// The damping b the region is for, in Ns/m (in β units for a normalized loop).
    pub device_damping: f64,
    /// Counter-clockwise vertices as [K, B] in N/m and Ns/m ([α, β] for normalized input).
    pub vertices: Vec<[f64; 2]>,
    /// The vertices in the loop's wall units a, b (the plane the page and the export draw in).
    #[serde(skip)]
    pub drawn: Vec<[f64; 2]>,
}

/// The page's (α, β) of a wall in N/m and Ns/m (the inverse of
/// [`super::wall_analyses::wall_of`]).
fn units_of(spec: &PlantSpec, k: f64, b: f64) -> [f64; 2] {
    let (a, bb) = spec.sys.family().to_units(k, b);
    [a, bb]
}

fn region_out(spec: &PlantSpec, equation: &'static str, r: &PassiveRegion) -> PassiveOut {
    let drawn: Vec<[f64; 2]> = r
        .vertices
        .iter()
        .map(|w| units_of(spec, w.stiffness, w.damping))
        .collect();
    PassiveOut {
        equation,
        device_damping: r.device_damping,
        vertices: match spec.physical {
            Some(_) => r
                .vertices
                .iter()
                .map(|w| [w.stiffness, w.damping])
                .collect(),
            None => drawn.clone(),
        },
        drawn,
    }
}

/// The passive regions of a request's loop: the device's own damping, and eq. (28) with the
/// arm's damping counted when an arm with damping holds the device; none where the
/// condition does not apply (an actuator lag, a transfer function without an identified
/// damper, an unstable velocity filter).
pub(super) fn passive_regions(
    spec: &PlantSpec,
) -> Result<(Option<PassiveOut>, Option<PassiveOut>), ApiError> {
    let lp = spec.sys.lp();
    let (Ok(sw), DeviceDamping::Known { damping }) =
        (SampledWall::new(lp), device_damping(&lp.plant))
    else {
        return Ok((None, None));
    };
    let own = passive_region(&sw, damping).map_err(lib_error)?;
    let own = region_out(
        spec,
        "b_L > b_required(K, B): the device's own damping, passive towards any passive \
         operator (Colgate–Schenkel; eq. 28 at d = 0)",
        &own,
    );
    let with_arm = match lp.plant.effective_damping() {
        Some(b) if b > damping => Some(region_out(
            spec,
            "b_L + b_H > b_required(K, B): eq. (28) with the arm's damping counted, towards \
             this operator only",
            &passive_region(&sw, b).map_err(lib_error)?,
        )),
        _ => None,
    };
    Ok((Some(own), with_arm))
}
