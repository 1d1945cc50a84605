//! The computations behind the JSON API, all synchronous and panic-free: request parameters
//! in, serializable answers out. The handlers in `mod.rs` run them on the blocking pool.

use std::time::Instant;

use hapstab::boundary::AlphaBeta;
use hapstab::linear::{linear_alpha_limit, linear_check};
use hapstab::loop_analysis;
use hapstab::nyquist::{
    RobustOptions, passive_region, region_summary, robust_region, unit_circle_pole,
};
use hapstab::params::{Effective, Normalized, PlantParams, Wall};
use hapstab::region::{EdgeKind, stable_region};
use hapstab::simulation::{Config, Contact, Effects, HumanForce, Initial, Model, RunResult};
use hapstab::simulation::{LoopModel, SimModel};
use hapstab::stability::Analysis;
use hapstab::{Loop, PolyFamily};
use serde::Serialize;

use super::limits::*;
use super::query::{
    ApiError, GeneralLoop, Params, PhysicalSpec, PlantSpec, clip, fmt, lib_error, plant_spec,
};
use super::simplify::simplify_polygon;
use hapstab::limits::{
    Budget, Cost, point_cost, region_cost, region_summary_cost, robust_region_cost, simulation_cost,
};

/// β slices of the exact cross-check of an empty polygon result.
const EMPTY_CHECK_SLICES: usize = 64;

/// Refuses a computation whose estimated cost exceeds [`Budget::INTERACTIVE`], with a 400
/// naming the parameter that drives it.
pub fn within_budget(cost: Cost, what: &str, name: &str, value: &str) -> Result<(), ApiError> {
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
pub struct PlantOut {
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

/// One edge of a drawn polygon.
#[derive(Debug, Clone, Serialize)]
pub struct EdgeOut {
    /// Index of the edge's first vertex in the polygon's vertex list.
    pub start: usize,
    /// z_plus_one (α = −γ), z_minus_one (α + 2β = c), complex (root pair e^{±iθ}) or window.
    pub kind: &'static str,
}

/// The exact stable region (Section V) as sent to the page.
#[derive(Debug, Clone, Serialize)]
pub struct RegionJson {
    /// Stable components: vertex rings of [α, β], counter-clockwise.
    pub polygons: Vec<Vec<[f64; 2]>>,
    /// Edges of each polygon.
    pub edges: Vec<Vec<EdgeOut>>,
    /// Largest stable α (the library's `StableRegion::alpha_max`; null when empty).
    pub alpha_max: f64,
    /// β at α_max.
    pub beta_at_alpha_max: f64,
    /// Area in the (α, β)-plane (of the exact polygons).
    pub area: f64,
    /// No stable point.
    pub empty: bool,
    /// Vertices of the exact polygons.
    pub vertices_exact: usize,
    /// Vertices sent after simplification.
    pub vertices_sent: usize,
    /// Simplification tolerance relative to the region's size.
    pub tol: f64,
}

/// The linear condition (23) of Section VII: α < (β + δ)/(d + 1/2), and α > −γ (19).
#[derive(Debug, Clone, Serialize)]
pub struct LinearOut {
    pub equation: &'static str,
    /// dα/dβ along the line: 1/(d + 1/2).
    pub slope: f64,
    /// α of the line at β = 0: δ/(d + 1/2).
    pub alpha_at_beta0: f64,
    /// Lower bound of eq. (19): α > −γ.
    pub alpha_lower: f64,
}

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

/// The robustly stable region over a γ range (Section VIII), from
/// `hapstab::nyquist::robust_region`.
#[derive(Debug, Clone, Serialize)]
pub struct RobustOut {
    pub gamma_lo: f64,
    pub gamma_hi: f64,
    /// Physical mode: the arm's stiffness range k_H ∈ [lo, hi] in N/m that gives the γ range
    /// (γ = k_H T²/m with m and b fixed); null when the range was given as γ.
    pub arm_stiffness_lo: Option<f64>,
    pub arm_stiffness_hi: Option<f64>,
    /// Uniform γ samples (ends included) and initial β slices.
    pub gamma_samples: usize,
    pub beta_samples: usize,
    /// Golden-section refinement of the slice ends in γ.
    pub refined: bool,
    pub method: &'static str,
    /// Polygon through the slice ends as [α, β], counter-clockwise.
    pub polygon: Vec<[f64; 2]>,
    pub alpha_max: f64,
    pub beta_at_alpha_max: f64,
    pub area: f64,
    pub empty: bool,
    /// Some slice had more than one robust α-interval.
    pub multiple_intervals: bool,
    /// γ samples at δ = 0, γ = (jπ)², replaced by the limit from inside the range.
    pub degenerate_gammas: Vec<f64>,
}

/// Server-side time in milliseconds.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Timing {
    pub region: f64,
    pub robust: f64,
    pub total: f64,
}

/// Answer of `/api/region`.
#[derive(Debug, Clone, Serialize)]
pub struct RegionOut {
    /// (γ, δ, d); for a loop beyond the paper's, γ is its static stiffness in wall units
    /// (the z = 1 line a = −γ) and δ = 0: the loop itself is under `loop`.
    pub params: PlantOut,
    pub physical: Option<PhysicalSpec>,
    /// A loop beyond the paper's: plant, period, delay and velocity estimator; the region
    /// is drawn in its wall units a = K/k_per_alpha, b = B/b_per_beta.
    #[serde(rename = "loop", skip_serializing_if = "Option::is_none")]
    pub lp: Option<Loop>,
    pub region: RegionJson,
    /// The paper's linear condition (null for other loops).
    pub linear: Option<LinearOut>,
    pub passive: Option<PassiveOut>,
    /// Eq. (28) with the arm's damping counted (physical units with an arm, d = 0): towards
    /// this operator only.
    pub passive_with_arm: Option<PassiveOut>,
    pub robust: Option<RobustOut>,
    pub warnings: Vec<String>,
    pub server_ms: Timing,
}

/// Query names of `/api/region`.
pub fn region_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = super::query::PLANT_PARAMS.to_vec();
    v.extend([
        "tol",
        "robust",
        "gamma_lo",
        "gamma_hi",
        "arm_stiffness_lo",
        "arm_stiffness_hi",
        "gamma_samples",
        "beta_samples",
        "refine",
    ]);
    v
}

/// A parsed region request.
#[derive(Debug, Clone)]
pub struct RegionReq {
    pub spec: PlantSpec,
    pub tol: f64,
    pub robust: Option<RobustReq>,
}

/// A robust-region request over γ ∈ [lo, hi].
#[derive(Debug, Clone, Copy)]
pub struct RobustReq {
    pub lo: f64,
    pub hi: f64,
    /// The arm's stiffness range in N/m that gave [lo, hi] (physical mode).
    pub arm_stiffness: Option<[f64; 2]>,
    pub gamma_samples: usize,
    pub beta_samples: usize,
    pub refine: bool,
}

/// Validates a region request.
pub fn parse_region(p: &Params) -> Result<RegionReq, ApiError> {
    let spec = plant_spec(p)?;
    let tol = p.num_or(
        "tol",
        DEFAULT_TOL,
        MIN_TOL,
        MAX_TOL,
        " (drawing tolerance relative to the region's size)",
    )?;
    let robust = if p.flag("robust")? {
        if spec.general.is_some() {
            return Err(ApiError::param(
                "robust",
                p.raw("robust").unwrap_or(""),
                format!(
                    "parameter 'robust' (got '{}'): the robust region over a range of γ belongs to the paper's loop (device + arm, backward velocity, whole-sample delay, no actuator lag)",
                    clip(p.raw("robust").unwrap_or(""))
                ),
            ));
        }
        let (lo, hi, arm_stiffness) = robust_range(p, &spec)?;
        if spec.d > MAX_ROBUST_D {
            return Err(ApiError::param(
                "d",
                &spec.d.to_string(),
                format!(
                    "parameter 'd' must be at most {MAX_ROBUST_D} for the robust region (got {})",
                    spec.d
                ),
            ));
        }
        let gs = p
            .opt_count(
                "gamma_samples",
                MIN_ROBUST_GAMMA_SAMPLES,
                MAX_ROBUST_GAMMA_SAMPLES,
                "",
            )?
            .unwrap_or(DEFAULT_ROBUST_GAMMA_SAMPLES);
        let bs = p
            .opt_count(
                "beta_samples",
                MIN_ROBUST_BETA_SAMPLES,
                MAX_ROBUST_BETA_SAMPLES,
                "",
            )?
            .unwrap_or(DEFAULT_ROBUST_BETA_SAMPLES);
        let refine = p.flag("refine")?;
        let cost = robust_cost(spec.d, gs, bs, refine);
        let (name, value) = if gs * DEFAULT_ROBUST_BETA_SAMPLES >= bs * DEFAULT_ROBUST_GAMMA_SAMPLES
        {
            ("gamma_samples", gs)
        } else {
            ("beta_samples", bs)
        };
        within_budget(
            cost,
            &format!(
                "the robust region over gamma_samples × beta_samples = {gs} × {bs} at d = {}{}",
                spec.d,
                if refine { " with refinement" } else { "" }
            ),
            name,
            &value.to_string(),
        )?;
        Some(RobustReq {
            lo,
            hi,
            arm_stiffness,
            gamma_samples: gs,
            beta_samples: bs,
            refine,
        })
    } else {
        for name in [
            "gamma_lo",
            "gamma_hi",
            "arm_stiffness_lo",
            "arm_stiffness_hi",
            "gamma_samples",
            "beta_samples",
            "refine",
        ] {
            if let Some(v) = p.raw(name) {
                return Err(ApiError::param(
                    name,
                    v,
                    format!("parameter '{name}' (got '{}') needs robust=1", clip(v)),
                ));
            }
        }
        None
    };
    let nominal = nominal_region_cost(spec.cost_d());
    within_budget(nominal, "the exact region", "d", &spec.d.to_string())?;
    Ok(RegionReq { spec, tol, robust })
}

/// The γ range of a robust request: `gamma_lo`, `gamma_hi`, or in physical mode the arm's
/// stiffness range `arm_stiffness_lo`, `arm_stiffness_hi` in N/m (m and b fixed), converted
/// as the plant's γ = kT²/m is formed (Table I), so that the range means what `hapstab kmax
/// --robust --box-stiffness lo,hi` means.
fn robust_range(p: &Params, spec: &PlantSpec) -> Result<(f64, f64, Option<[f64; 2]>), ApiError> {
    let by_k = p.has("arm_stiffness_lo") || p.has("arm_stiffness_hi");
    let (lo, hi, k) = match spec.physical {
        Some(ph) if by_k => {
            refuse_gamma_range(p)?;
            let k_lo = p.num_in(
                "arm_stiffness_lo",
                0.0,
                MAX_PHYS_STIFFNESS,
                " N/m (robust range, lower arm stiffness k_H)",
            )?;
            let k_hi = p.num_in(
                "arm_stiffness_hi",
                0.0,
                MAX_PHYS_STIFFNESS,
                " N/m (robust range, upper arm stiffness k_H)",
            )?;
            let gamma = |name: &str, k: f64| -> Result<f64, ApiError> {
                let eff = Effective::new(ph.mass, ph.damping, k).map_err(lib_error)?;
                let g = PlantParams::from_physical(&eff, ph.period)
                    .map_err(lib_error)?
                    .gamma;
                if g > MAX_GAMMA {
                    return Err(ApiError::param(
                        name,
                        &fmt(k),
                        format!(
                            "parameter '{name}' = {} N/m gives γ = kT²/m = {} above the explorer's {}",
                            fmt(k),
                            fmt(g),
                            fmt(MAX_GAMMA)
                        ),
                    ));
                }
                Ok(g)
            };
            check_order("arm_stiffness", k_lo, k_hi)?;
            (
                gamma("arm_stiffness_lo", k_lo)?,
                gamma("arm_stiffness_hi", k_hi)?,
                Some([k_lo, k_hi]),
            )
        }
        None if by_k => {
            let name = if p.has("arm_stiffness_lo") {
                "arm_stiffness_lo"
            } else {
                "arm_stiffness_hi"
            };
            let v = p.raw(name).unwrap_or("");
            return Err(ApiError::param(
                name,
                v,
                format!(
                    "parameter '{name}' (got '{}') belongs to mode=physical; give gamma_lo, gamma_hi",
                    clip(v)
                ),
            ));
        }
        _ => {
            let lo = p.num_in("gamma_lo", 0.0, MAX_GAMMA, " (robust range, lower γ)")?;
            let hi = p.num_in("gamma_hi", 0.0, MAX_GAMMA, " (robust range, upper γ)")?;
            check_order("gamma", lo, hi)?;
            (lo, hi, None)
        }
    };
    Ok((lo, hi, k))
}

/// `{name}_hi` >= `{name}_lo`.
fn check_order(name: &str, lo: f64, hi: f64) -> Result<(), ApiError> {
    if hi < lo {
        return Err(ApiError::param(
            &format!("{name}_hi"),
            &fmt(hi),
            format!(
                "parameter '{name}_hi' must be >= {name}_lo = {} (got {})",
                fmt(lo),
                fmt(hi)
            ),
        ));
    }
    Ok(())
}

/// The robust range is given either as γ or as the arm's stiffness, not both.
fn refuse_gamma_range(p: &Params) -> Result<(), ApiError> {
    for name in ["gamma_lo", "gamma_hi"] {
        if let Some(v) = p.raw(name) {
            return Err(ApiError::param(
                name,
                v,
                format!(
                    "parameter '{name}' (got '{}'): give the robust range either as gamma_lo, gamma_hi or as arm_stiffness_lo, arm_stiffness_hi (N/m), not both",
                    clip(v)
                ),
            ));
        }
    }
    Ok(())
}

/// Estimated cost of the nominal part of `/api/region`: the exact polygons and, when they
/// come out empty, the cross-check by 64 exact α-interval slices.
pub fn nominal_region_cost(d: usize) -> Cost {
    region_cost(d).then(region_summary_cost(EMPTY_CHECK_SLICES, d))
}

/// Estimated cost of the robust region of `/api/region`.
pub fn robust_cost(d: usize, gamma_samples: usize, beta_samples: usize, refine: bool) -> Cost {
    robust_region_cost(
        gamma_samples,
        beta_samples,
        d,
        refine,
        ROBUST_REFINE_BETA_ROUNDS,
    )
}

fn edge_kind(k: &EdgeKind) -> &'static str {
    match k {
        EdgeKind::ZPlusOne => "z_plus_one",
        EdgeKind::ZMinusOne => "z_minus_one",
        EdgeKind::Complex { .. } => "complex",
        EdgeKind::Window => "window",
    }
}

fn ab(p: &AlphaBeta) -> [f64; 2] {
    [p.alpha, p.beta]
}

/// The exact region drawn with the tolerance relative to its size.
fn region_json(r: &hapstab::region::StableRegion, tol: f64) -> RegionJson {
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for v in r.polygons.iter().flat_map(|p| p.vertices.iter()) {
        x0 = x0.min(v.alpha);
        x1 = x1.max(v.alpha);
        y0 = y0.min(v.beta);
        y1 = y1.max(v.beta);
    }
    let size = (x1 - x0).max(y1 - y0);
    let abs_tol = if size.is_finite() { tol * size } else { 0.0 };
    let mut polygons = Vec::with_capacity(r.polygons.len());
    let mut edges = Vec::with_capacity(r.polygons.len());
    for poly in &r.polygons {
        let (verts, starts) = simplify_polygon(poly, abs_tol);
        polygons.push(verts.iter().map(ab).collect::<Vec<_>>());
        edges.push(
            poly.edges
                .iter()
                .zip(starts)
                .map(|(e, s)| EdgeOut {
                    start: s,
                    kind: edge_kind(&e.kind),
                })
                .collect::<Vec<_>>(),
        );
    }
    RegionJson {
        vertices_sent: polygons.iter().map(Vec::len).sum(),
        polygons,
        edges,
        alpha_max: r.alpha_max,
        beta_at_alpha_max: r.beta_at_alpha_max,
        area: r.area,
        empty: r.polygons.is_empty(),
        vertices_exact: r.polygons.iter().map(|p| p.vertices.len()).sum(),
        tol,
    }
}

/// `/api/region` for a loop beyond the paper's: the exact region of its family in wall
/// units; the paper's overlays (linear condition, passive region) do not apply.
fn general_region(req: &RegionReq, g: &GeneralLoop) -> Result<RegionOut, ApiError> {
    let t0 = Instant::now();
    let r = loop_analysis::region(&g.lp, &g.family).map_err(lib_error)?;
    let region = region_json(&r, req.tol);
    let ms = t0.elapsed().as_secs_f64() * 1e3;
    Ok(RegionOut {
        params: PlantOut::from(&req.spec),
        physical: req.spec.physical,
        lp: Some(g.lp.clone()),
        region,
        linear: None,
        passive: None,
        passive_with_arm: None,
        robust: None,
        warnings: Vec::new(),
        server_ms: Timing {
            region: ms,
            robust: 0.0,
            total: ms,
        },
    })
}

/// Computes the answer of `/api/region`.
pub fn region(req: &RegionReq) -> Result<RegionOut, ApiError> {
    if let Some(g) = &req.spec.general {
        return general_region(req, g);
    }
    let t0 = Instant::now();
    let spec = &req.spec;
    let fam = PolyFamily::new(spec.plant, spec.d).map_err(lib_error)?;
    let r = stable_region(&fam).map_err(lib_error)?;
    let t_region = t0.elapsed().as_secs_f64() * 1e3;
    let mut warnings = Vec::new();
    let region = region_json(&r, req.tol);
    if unit_circle_pole(spec.plant).is_some() {
        warnings.push(format!(
            "δ = 0 and γ = {} = (jπ)²: p(z) has a root on the unit circle for every (α, β) (Section VIII-B), so no point is strictly stable",
            fmt(spec.plant.gamma)
        ));
    } else if region.empty {
        // Cross-check an empty polygon result by exact per-β α-intervals.
        let summary = region_summary(spec.plant, spec.d, EMPTY_CHECK_SLICES).map_err(lib_error)?;
        if !summary.empty {
            warnings.push(format!(
                "the polygon construction (hapstab::region::stable_region) returned no region, but exact per-β α-intervals (hapstab::nyquist::region_summary) find stable points up to α = {} at β = {}",
                fmt(summary.alpha_max),
                fmt(summary.beta_at_alpha_max)
            ));
        }
    }
    let delta = spec.plant.delta;
    let linear = Some(LinearOut {
        equation: "α < (β + δ)/(d + 1/2)  (eq. 23),  α > −γ  (eq. 19)",
        slope: 1.0 / (spec.d as f64 + 0.5),
        alpha_at_beta0: linear_alpha_limit(0.0, delta, spec.d),
        alpha_lower: -spec.plant.gamma,
    });
    let (passive, passive_with_arm) = passive_triangles(spec)?;
    let t1 = Instant::now();
    let robust = match req.robust {
        Some(rr) => {
            let opts = RobustOptions {
                gamma_samples: rr.gamma_samples,
                beta_samples: rr.beta_samples,
                refine_gamma: rr.refine,
                refine_beta_rounds: ROBUST_REFINE_BETA_ROUNDS,
            };
            let r = robust_region(delta, spec.d, rr.lo, rr.hi, opts).map_err(lib_error)?;
            Some(RobustOut {
                gamma_lo: r.gamma_lo,
                gamma_hi: r.gamma_hi,
                arm_stiffness_lo: rr.arm_stiffness.map(|k| k[0]),
                arm_stiffness_hi: rr.arm_stiffness.map(|k| k[1]),
                gamma_samples: rr.gamma_samples,
                beta_samples: rr.beta_samples,
                refined: rr.refine,
                method: "hapstab::nyquist::robust_region: intersection of exact per-β stable α-intervals over uniform γ samples",
                polygon: r.polygon.iter().map(ab).collect(),
                alpha_max: r.alpha_max,
                beta_at_alpha_max: r.beta_at_alpha_max,
                area: r.area,
                empty: r.empty,
                multiple_intervals: r.multiple_intervals,
                degenerate_gammas: r.degenerate_gammas,
            })
        }
        None => None,
    };
    let t_robust = t1.elapsed().as_secs_f64() * 1e3;
    Ok(RegionOut {
        params: PlantOut::from(spec),
        physical: spec.physical,
        lp: None,
        region,
        linear,
        passive,
        passive_with_arm,
        robust,
        warnings,
        server_ms: Timing {
            region: t_region,
            robust: t_robust,
            total: t0.elapsed().as_secs_f64() * 1e3,
        },
    })
}

/// α and β of a point; in physical mode optionally given as K (N/m) and B (Ns/m).
pub fn wall_point(p: &Params, spec: &PlantSpec) -> Result<(f64, f64), ApiError> {
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

/// Query names of `/api/point`.
pub fn point_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = super::query::PLANT_PARAMS.to_vec();
    v.extend(["alpha", "beta", "wall_stiffness", "wall_damping"]);
    v
}

/// The physical wall of a point.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct WallOut {
    /// K in N/m.
    pub stiffness: f64,
    /// B in Ns/m.
    pub damping: f64,
}

/// The linear condition at a point.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PointLinear {
    pub alpha_lower: f64,
    pub alpha_upper: f64,
    pub satisfied: bool,
}

/// Answer of `/api/point`.
#[derive(Debug, Clone, Serialize)]
pub struct PointOut {
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
    /// Inside Colgate's passive region for the device's own damping (d = 0 only).
    pub passive: Option<bool>,
    /// Inside eq. (28) with the arm's damping counted (physical units with an arm, d = 0).
    pub passive_with_arm: Option<bool>,
    pub server_ms: f64,
}

/// Refuses a point whose roots would cost more than one request may.
pub fn point_budget(spec: &PlantSpec) -> Result<(), ApiError> {
    within_budget(
        point_cost(spec.cost_d()),
        "the roots at one point",
        "d",
        &spec.d.to_string(),
    )
}

/// The wall of a point in physical units, if the request is physical.
fn wall_out(spec: &PlantSpec, alpha: f64, beta: f64) -> Option<WallOut> {
    spec.physical.map(|ph| WallOut {
        stiffness: alpha * ph.k_per_alpha,
        damping: beta * ph.b_per_beta,
    })
}

/// The point's (α, β, γ, δ, d) (see [`PointOut::params`]).
fn point_params(spec: &PlantSpec, alpha: f64, beta: f64) -> Result<Normalized, ApiError> {
    Normalized::new(alpha, beta, spec.plant.gamma, spec.plant.delta, spec.d).map_err(lib_error)
}

/// Computes `/api/point`.
pub fn point(spec: &PlantSpec, alpha: f64, beta: f64) -> Result<PointOut, ApiError> {
    let t0 = Instant::now();
    let n = point_params(spec, alpha, beta)?;
    let a = match &spec.general {
        Some(g) => loop_analysis::analysis(&g.lp, &g.family, (alpha, beta)),
        None => Analysis::new(n),
    }
    .map_err(lib_error)?;
    let paper = spec.general.is_none();
    let linear = paper.then(|| {
        let lc = linear_check(&n);
        PointLinear {
            alpha_lower: lc.alpha_lower,
            alpha_upper: lc.alpha_upper,
            satisfied: lc.satisfied,
        }
    });
    let inside = |delta: f64| alpha >= 0.0 && delta > alpha / 2.0 + beta.abs();
    let passive = (paper && spec.d == 0).then(|| inside(own_delta(spec)));
    let passive_with_arm = (paper && spec.d == 0 && has_arm_damping(spec)).then(|| inside(n.delta));
    Ok(PointOut {
        params: n,
        lp: spec.general.as_ref().map(|g| g.lp.clone()),
        wall: wall_out(spec, alpha, beta),
        verdict: a.verdict.as_str(),
        stable: a.stable(),
        spectral_radius: a.spectral_radius,
        roots: a.roots.iter().map(|z| [z.re, z.im]).collect(),
        linear,
        passive,
        passive_with_arm,
        server_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}

/// Query names of `/api/simulate`.
pub fn simulate_names() -> Vec<&'static str> {
    let mut v = point_names();
    v.extend(["samples", "push", "velocity", "contact"]);
    v
}

/// A parsed simulation request.
#[derive(Debug, Clone)]
pub struct SimReq {
    pub spec: PlantSpec,
    pub alpha: f64,
    pub beta: f64,
    pub samples: usize,
    pub push: f64,
    pub velocity: f64,
    pub contact: Contact,
}

/// Validates a simulation request.
pub fn parse_simulate(p: &Params) -> Result<SimReq, ApiError> {
    let spec = plant_spec(p)?;
    let (alpha, beta) = wall_point(p, &spec)?;
    let samples = match p.opt_count(
        "samples",
        MIN_SIM_SAMPLES,
        MAX_SIM_SAMPLES,
        " (simulated samples)",
    )? {
        Some(n) => n,
        None => {
            // about six periods of the wall's oscillation, ω ≈ √(α + γ) per sample
            let w = (alpha + spec.plant.gamma).max(1e-8).sqrt();
            ((6.0 * 2.0 * std::f64::consts::PI / w).ceil() as usize).clamp(300, 4000)
        }
    };
    // a run may be extended up to the horizon until its verdict settles: budget for that
    within_budget(
        simulation_cost(
            samples.max(SIM_HORIZON) as f64,
            spec.cost_d(),
            samples.min(MAX_TRACE_POINTS) as f64,
        )
        .then(point_cost(spec.cost_d())),
        "the simulation (extended up to its horizon)",
        "d",
        &spec.d.to_string(),
    )?;
    let push = p.num_or(
        "push",
        1.0,
        -MAX_PUSH,
        MAX_PUSH,
        " N (human push into the wall)",
    )?;
    let velocity = p.num_or(
        "velocity",
        0.01,
        -MAX_VELOCITY,
        MAX_VELOCITY,
        " m/s (approach velocity at the wall surface)",
    )?;
    let contact = match p.choice(
        "contact",
        &["unilateral", "unilateral_no_pull", "bilateral"],
        "unilateral",
    )? {
        "bilateral" => Contact::Bilateral,
        "unilateral_no_pull" => Contact::UnilateralNoPull,
        _ => Contact::Unilateral,
    };
    Ok(SimReq {
        spec,
        alpha,
        beta,
        samples,
        push,
        velocity,
        contact,
    })
}

/// A recorded trace, decimated.
#[derive(Debug, Clone, Serialize)]
pub struct TraceOut {
    /// Time in s.
    pub time: Vec<f64>,
    /// Position in m (positive into the wall).
    pub position: Vec<f64>,
    /// Wall force in N (positive pushes out).
    pub wall_force: Vec<f64>,
}

/// Answer of `/api/simulate`: the library's run result (the same verdict as `hapstab
/// simulate` for the same setting) with a decimated trace of the whole run.
#[derive(Debug, Clone, Serialize)]
pub struct SimOut {
    /// As [`PointOut::params`].
    pub params: Normalized,
    #[serde(rename = "loop", skip_serializing_if = "Option::is_none")]
    pub lp: Option<Loop>,
    /// Mass m in kg and period T in s used for units.
    pub mass: f64,
    pub period: f64,
    pub units_note: &'static str,
    /// unilateral | unilateral_no_pull | bilateral.
    pub contact_mode: Contact,
    pub push: f64,
    pub velocity: f64,
    /// outcome, reason, judged window, measured growth beside the spectral radius, limit
    /// cycle, contact events, samples simulated (see `hapstab::simulation::RunResult`).
    #[serde(flatten)]
    pub run: RunResult,
    pub trace: TraceOut,
    pub server_ms: f64,
}

/// Runs `/api/simulate`: the device starts at the wall surface x = 0 moving in with
/// `velocity`, the operator pushes with a constant `push`; unilateral wall by default. The
/// run is `samples` long, extended like `hapstab simulate` until its verdict settles.
pub fn simulate(req: &SimReq) -> Result<SimOut, ApiError> {
    let t0 = Instant::now();
    let spec = &req.spec;
    let n = point_params(spec, req.alpha, req.beta)?;
    let (mass, period, units_note) = match spec.physical {
        Some(ph) => (ph.mass, ph.period, "physical units of the request"),
        None => (
            1.0,
            1e-3,
            "normalized mode: shown for m = 1 kg and T = 1 ms (only the shape depends on α, β, γ, δ, d)",
        ),
    };
    let model = match (&spec.general, wall_out(spec, req.alpha, req.beta)) {
        (Some(g), Some(w)) => {
            let wall = Wall {
                stiffness: w.stiffness,
                damping: w.damping,
            };
            SimModel::Loop(LoopModel::new(g.lp.clone(), wall).map_err(lib_error)?)
        }
        _ => SimModel::Paper(Model::new(n, mass, period).map_err(lib_error)?),
    };
    let mut cfg = Config::new(model, req.samples);
    cfg.effects = Effects {
        contact: req.contact,
        ..Effects::LINEAR
    };
    cfg.human = HumanForce::Constant(req.push);
    cfg.initial = Initial {
        position: 0.0,
        velocity: req.velocity,
    };
    cfg.trace_rows = MAX_TRACE_POINTS;
    let mut run = hapstab::simulation::simulate(&cfg).map_err(lib_error)?;
    let trace = run.trace.take().unwrap_or_default();
    Ok(SimOut {
        params: n,
        lp: spec.general.as_ref().map(|g| g.lp.clone()),
        mass,
        period,
        units_note,
        contact_mode: req.contact,
        push: req.push,
        velocity: req.velocity,
        run,
        trace: TraceOut {
            time: trace.time,
            position: trace.position,
            wall_force: trace.wall_force,
        },
        server_ms: t0.elapsed().as_secs_f64() * 1e3,
    })
}

/// δ_L = b_L·T/m of the device's own damping in physical units; δ itself in normalized units
/// (the plant's damping is then all the device's).
fn own_delta(spec: &PlantSpec) -> f64 {
    spec.physical.map_or(spec.plant.delta, |ph| {
        ph.device_damping * ph.period / ph.mass
    })
}

fn has_arm_damping(spec: &PlantSpec) -> bool {
    spec.physical.is_some_and(|ph| ph.arm_damping > 0.0)
}

/// Colgate's passive triangles for d = 0: the device's own damping, and eq. (28) with the arm's
/// damping counted when an arm with damping holds the device.
fn passive_triangles(
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
