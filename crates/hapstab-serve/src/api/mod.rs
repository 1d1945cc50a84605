//! The computations behind the JSON API, all synchronous and panic-free: request parameters
//! in, serializable answers out. The handlers at the crate root run them on the blocking pool.

//!
//! One endpoint per file: `/api/region` in `region` (its request in `region_request`, the
//! passive triangles it draws in `passive`, the robust K_max over a box in `robust_box`),
//! `/api/point` in `point` (the library's `WallAnswer`; the page's wall in the loop's units in `wall_analyses`),
//! `/api/simulate` in `simulation`, and the analyses of `hapstab kmax`, `sweep`, `zwidth`,
//! `map` and `passivity` in `kmax`, `sweep`, `zwidth`, `map` and `passivity`. The budget
//! check, the physical loop of a request and the plant of an answer, which all share, are
//! here.

use serde::Serialize;

use super::query::{ApiError, PaperPlant, PlantSpec, clip};
use hapstab::System;
use hapstab::limits::{Budget, Cost};

mod kmax;
mod map;
mod passive;
mod passivity;
mod point;
mod region;
mod region_request;
mod robust_box;
mod simulation;
mod sweep;
pub(crate) mod wall_analyses;
mod zwidth;

pub(crate) use kmax::{kmax, kmax_names, parse_kmax};
pub(crate) use map::{map, map_names, parse_map};
pub(crate) use passivity::{parse_passivity, passivity, passivity_names};
pub(crate) use sweep::{parse_sweep, sweep, sweep_names};
pub(crate) use zwidth::{parse_zwidth, zwidth, zwidth_names};

#[cfg(test)]
pub(crate) use point::wall_point;
pub(crate) use point::{PointOut, WallAt, point, point_budget, point_names, wall_at};
pub(crate) use region::{RegionOut, region};
#[cfg(test)]
pub(crate) use region::{nominal_region_cost, robust_cost};
pub(crate) use region_request::{RegionReq, parse_region, region_names};
pub(crate) use simulation::{parse_simulate, simulate, simulate_names};

/// Refuses a computation whose estimated cost exceeds [`Budget::INTERACTIVE`], with a 400
/// naming the parameter that drives it.
pub(crate) fn within_budget(
    cost: Cost,
    what: &str,
    name: &str,
    value: &str,
) -> Result<(), ApiError> {
    Budget::INTERACTIVE.check(cost).map_err(|e| {
        ApiError::param(
            name,
            value,
            format!(
                "{what} {e}; reduce parameter '{name}' (got {}), see /api/limits",
                clip(value)
            ),
        )
    })
}

/// Refuses a computation on a request's loop beyond [`Budget::INTERACTIVE`], naming the
/// delay that sets the degree of its p(z).
pub(crate) fn loop_budget(spec: &PlantSpec, cost: Cost, what: &str) -> Result<(), ApiError> {
    let (name, value) = spec.delay_param();
    within_budget(cost, what, name, &value)
}

/// The physical loop of a request and its family; the normalized mode is refused for the
/// analyses in physical units (`what`: their name).
pub(crate) fn physical_loop<'a>(spec: &'a PlantSpec, what: &str) -> Result<&'a System, ApiError> {
    if spec.physical.is_none() {
        return Err(ApiError::param(
            "mode",
            "normalized",
            format!(
                "{what} works in physical units: give mode=physical and the device, not gamma/delta"
            ),
        ));
    }
    Ok(&spec.sys)
}

/// γ, δ, d of an answer.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct PlantOut {
    pub gamma: f64,
    pub delta: f64,
    pub d: usize,
}

impl From<PaperPlant> for PlantOut {
    fn from(p: PaperPlant) -> Self {
        Self {
            gamma: p.plant.gamma,
            delta: p.plant.delta,
            d: p.d,
        }
    }
}
