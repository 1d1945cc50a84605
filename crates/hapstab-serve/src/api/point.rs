//! `/api/point`: the verdict, roots and spectral radius at one wall, the linear condition, its
//! margins and its passivity on any loop.

use std::time::Instant;

use hapstab::Wall;
use hapstab::answer::{WallAnswer, wall_answer};
use hapstab::limits::point_cost;
use hapstab::paper::Normalized;
use serde::Serialize;

use super::wall_analyses::wall_of;
use super::within_budget;
use crate::limits::*;
use crate::query::{ApiError, Params, PlantSpec, lib_error};

/// α and β of a point; in physical mode optionally given as K (N/m) and B (Ns/m).
pub(crate) fn wall_point(p: &Params, spec: &PlantSpec) -> Result<(f64, f64), ApiError> {
    let phys_given = p.has("wall_stiffness") || p.has("wall_damping");
    let norm_given = p.has("alpha") || p.has("beta");
    if phys_given && norm_given {
        return Err(ApiError::bad(
            "give the point either as alpha/beta or as wall_stiffness/wall_damping, not both"
                .into(),
        ));
    }
    if phys_given {
        let Some(ph) = spec.physical else {
            return Err(ApiError::param(
                "wall_stiffness",
                p.raw("wall_stiffness").unwrap_or(""),
                "wall_stiffness/wall_damping need mode=physical".into(),
            ));
        };
        let k = p.num_in(
            "wall_stiffness",
            -MAX_WALL * ph.k_per_unit,
            MAX_WALL * ph.k_per_unit,
            " N/m",
        )?;
        let b = p.num_in(
            "wall_damping",
            -MAX_WALL * ph.b_per_unit,
            MAX_WALL * ph.b_per_unit,
            " Ns/m",
        )?;
        return Ok((k / ph.k_per_unit, b / ph.b_per_unit));
    }
    let alpha = p.num_in(
        "alpha",
        -MAX_WALL,
        MAX_WALL,
        " (normalized stiffness α = KT²/m)",
    )?;
    let beta = p.num_in(
        "beta",
        -MAX_WALL,
        MAX_WALL,
        " (normalized damping β = BT/m)",
    )?;
    Ok((alpha, beta))
}

/// The wall of a request: its (α, β) in the page's units and the wall in the loop's units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WallAt {
    /// (α, β), or a loop's wall units (a, b) beyond the paper's loop.
    pub units: (f64, f64),
    /// K in N/m and B in Ns/m (α and β for a normalized loop).
    pub wall: Wall,
}

impl WallAt {
    /// The wall at (α, β) in the page's units ([`wall_of`]).
    pub(crate) fn of_units(spec: &PlantSpec, alpha: f64, beta: f64) -> Self {
        WallAt {
            units: (alpha, beta),
            wall: wall_of(spec, alpha, beta),
        }
    }
}

/// The wall of a request ([`wall_point`]): given as K and B, they are kept as given and
/// converted to the page's units as the command line converts them
/// ([`hapstab::System::wall_units`]), so that every analysis of the wall is the
/// command line's; given as α and β, they are converted to K and B by [`wall_of`].
pub(crate) fn wall_at(p: &Params, spec: &PlantSpec) -> Result<WallAt, ApiError> {
    let units = wall_point(p, spec)?;
    if !p.has("wall_stiffness") && !p.has("wall_damping") {
        return Ok(WallAt::of_units(spec, units.0, units.1));
    }
    let wall = Wall {
        stiffness: p.num("wall_stiffness")?,
        damping: p.num("wall_damping")?,
    };
    let units = spec.sys.wall_units(wall).map_err(lib_error)?;
    Ok(WallAt { units, wall })
}

/// Query names of `/api/point`.
pub(crate) fn point_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.extend(["alpha", "beta", "wall_stiffness", "wall_damping"]);
    v
}

/// Answer of `/api/point`: the library's [`WallAnswer`] and the server's time.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct PointOut {
    #[serde(flatten)]
    pub answer: WallAnswer,
    pub server_ms: f64,
}

impl std::ops::Deref for PointOut {
    type Target = WallAnswer;
    fn deref(&self) -> &WallAnswer {
        &self.answer
    }
}

/// Refuses a point whose roots would cost more than one request may.
pub(crate) fn point_budget(spec: &PlantSpec) -> Result<(), ApiError> {
    let (name, value) = spec.delay_param();
    within_budget(
        point_cost(spec.cost_d()),
        "the roots at one point",
        name,
        &value,
    )
}

/// The point in Table I, (α, β, γ, δ, d), of a loop with the paper's view (None beyond it;
/// see `hapstab::answer::WallAnswer::params`).
pub(super) fn point_params(
    spec: &PlantSpec,
    alpha: f64,
    beta: f64,
) -> Result<Option<Normalized>, ApiError> {
    spec.paper
        .map(|p| Normalized::new(alpha, beta, p.plant.gamma, p.plant.delta, p.d))
        .transpose()
        .map_err(lib_error)
}

/// Computes `/api/point` ([`wall_answer`] on the request's loop).
pub(crate) fn point(spec: &PlantSpec, at: WallAt) -> Result<PointOut, ApiError> {
    let t0 = Instant::now();
    let (alpha, beta) = at.units;
    let params = point_params(spec, alpha, beta)?;
    let normalized = spec.physical.is_none();
    let answer =
        wall_answer(&spec.sys, params, normalized, at.units, at.wall).map_err(lib_error)?;
    Ok(PointOut {
        answer,
        server_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}
