//! `/api/point`: the verdict, roots and spectral radius at one wall, the linear condition, its
//! margins and its passivity on any loop.

use std::time::Instant;

use hapstab::limits::point_cost;
use hapstab::paper::Normalized;
use hapstab::paper::linear::linear_check;
use hapstab::{Loop, Wall};
use serde::Serialize;

use super::wall_analyses::{wall_analyses, wall_of};
use super::within_budget;
use crate::limits::*;
use crate::query::{ApiError, Params, PlantSpec, lib_error};
use hapstab::margins::report::MarginsReport;
use hapstab::passivity::Passivity;

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
            -MAX_WALL * ph.k_per_alpha,
            MAX_WALL * ph.k_per_alpha,
            " N/m",
        )?;
        let b = p.num_in(
            "wall_damping",
            -MAX_WALL * ph.b_per_beta,
            MAX_WALL * ph.b_per_beta,
            " Ns/m",
        )?;
        return Ok((k / ph.k_per_alpha, b / ph.b_per_beta));
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

/// The physical wall of a point.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct WallOut {
    /// K in N/m.
    pub stiffness: f64,
    /// B in Ns/m.
    pub damping: f64,
}

/// The linear condition at a point.
#[derive(Debug, Clone, Copy, Serialize)]
pub(crate) struct PointLinear {
    pub alpha_lower: f64,
    pub alpha_upper: f64,
    pub satisfied: bool,
}

/// Answer of `/api/point`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct PointOut {
    /// (α, β, γ, δ, d); for a loop beyond the paper's the wall in wall units (a, b) with γ
    /// its static stiffness in wall units and δ = 0 (the loop is under `loop`).
    pub params: Normalized,
    #[serde(rename = "loop", skip_serializing_if = "Option::is_none")]
    pub lp: Option<Loop>,
    pub wall: Option<WallOut>,
    /// stable | marginal | unstable (Schur–Cohn with a 5e-11 marginal band).
    pub verdict: &'static str,
    pub stable: bool,
    /// Largest root modulus of p(z).
    pub spectral_radius: f64,
    /// Roots of p(z) as [re, im], largest modulus first.
    pub roots: Vec<[f64; 2]>,
    /// Linear condition (19), (23) of the paper's loop (null for other loops).
    pub linear: Option<PointLinear>,
    /// Passive for the device's own damping (Colgate–Schenkel: towards any passive operator);
    /// null where the condition does not apply (see `passivity`).
    pub passive: Option<bool>,
    /// Passive by eq. (28) with the arm's damping counted (towards this operator only); null
    /// without an arm.
    pub passive_with_arm: Option<bool>,
    /// Every margin of the wall, as `hapstab check --json` gives them (withheld with a note
    /// beside a verdict that is not stable).
    pub margins: MarginsReport,
    /// The passivity of the wall, as `hapstab passivity --json` gives it.
    pub passivity: Passivity,
    pub server_ms: f64,
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

/// The point's (α, β, γ, δ, d) (see [`PointOut::params`]).
pub(super) fn point_params(
    spec: &PlantSpec,
    alpha: f64,
    beta: f64,
) -> Result<Normalized, ApiError> {
    let v = spec.view();
    Normalized::new(alpha, beta, v.plant.gamma, v.plant.delta, v.d).map_err(lib_error)
}

/// Computes `/api/point`.
pub(crate) fn point(spec: &PlantSpec, at: WallAt) -> Result<PointOut, ApiError> {
    let t0 = Instant::now();
    let (alpha, beta) = at.units;
    let n = point_params(spec, alpha, beta)?;
    let a = spec.sys.analysis((alpha, beta)).map_err(lib_error)?;
    let linear = spec.paper.is_some().then(|| {
        let lc = linear_check(&n);
        PointLinear {
            alpha_lower: lc.alpha_lower,
            alpha_upper: lc.alpha_upper,
            satisfied: lc.satisfied,
        }
    });
    let (margins, passivity) = wall_analyses(spec, at.wall, a.stable())?;
    Ok(PointOut {
        passive: passivity.verdict.meets(),
        passive_with_arm: passivity.with_arm.and_then(|w| w.verdict.meets()),
        margins: MarginsReport::from(&margins),
        passivity,
        params: n,
        lp: spec.paper.is_none().then(|| spec.sys.lp().clone()),
        wall: spec.physical.map(|_| WallOut {
            stiffness: at.wall.stiffness,
            damping: at.wall.damping,
        }),
        verdict: a.verdict.as_str(),
        stable: a.stable(),
        spectral_radius: a.spectral_radius,
        roots: a.roots.iter().map(|z| [z.re, z.im]).collect(),
        linear,
        server_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}
