//! The computations behind the JSON API, all synchronous and panic-free: request parameters
//! in, serializable answers out. The handlers at the crate root run them on the blocking pool.

//!
//! One endpoint per file: `/api/region` in `region` (its request in `region_request`, the
//! passive triangles it draws in `passive`, the robust K_max over a box in `robust_box`), `/api/point` in `point` (the clicked wall's margins and passivity in `wall_analyses`) and `/api/simulate` in
//! `simulation`. The budget check and the plant of an answer, which all share, are here.

use serde::Serialize;

use super::query::{ApiError, PlantSpec, clip};
use hapstab::limits::{Budget, Cost};

mod passive;
mod point;
mod region;
mod region_request;
mod robust_box;
mod simulation;
pub(crate) mod wall_analyses;

pub(crate) use point::{PointOut, point, point_budget, point_names, wall_point};
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

/// γ, δ, d of an answer.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct PlantOut {
    pub gamma: f64,
    pub delta: f64,
    pub d: usize,
}

impl From<&PlantSpec> for PlantOut {
    fn from(s: &PlantSpec) -> Self {
        Self {
            gamma: s.plant.gamma,
            delta: s.plant.delta,
            d: s.d,
        }
    }
}
