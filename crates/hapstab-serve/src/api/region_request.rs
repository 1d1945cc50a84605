//! The request of `/api/region`: its query names, validation, and the γ range of a robust
//! region given as γ or as the arm's stiffness.

use hapstab::paper::PlantParams;
use hapstab::params::Effective;

use super::region::{nominal_region_cost, robust_cost};
use super::robust_box::{ROBUST_BOX_NAMES, RobustBoxReq, parse_robust_box};
use super::within_budget;
use crate::limits::*;
use crate::query::{ApiError, PaperPlant, Params, PlantSpec, clip, fmt, lib_error, plant_spec};

/// Query names of the robust region (robust=1 only).
const ROBUST_NAMES: [&str; 7] = [
    "gamma_lo",
    "gamma_hi",
    "arm_stiffness_lo",
    "arm_stiffness_hi",
    "gamma_samples",
    "beta_samples",
    "refine",
];

/// Query names of `/api/region`.
pub(crate) fn region_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.extend(["tol", "robust"]);
    v.extend(ROBUST_NAMES);
    v.extend(ROBUST_BOX_NAMES);
    v
}

/// A parsed region request.
#[derive(Debug, Clone)]
pub(crate) struct RegionReq {
    pub spec: PlantSpec,
    pub tol: f64,
    pub robust: Option<RobustReq>,
    /// The robust K_max over a box of the loop's parameters (`box=…`).
    pub robust_kmax: Option<RobustBoxReq>,
}

/// A robust-region request over γ ∈ [lo, hi].
#[derive(Debug, Clone, Copy)]
pub(crate) struct RobustReq {
    pub lo: f64,
    pub hi: f64,
    /// The arm's stiffness range in N/m that gave [lo, hi] (physical mode).
    pub arm_stiffness: Option<[f64; 2]>,
    pub gamma_samples: usize,
    pub beta_samples: usize,
    pub refine: bool,
}

/// Validates a region request.
pub(crate) fn parse_region(p: &Params) -> Result<RegionReq, ApiError> {
    let spec = plant_spec(p)?;
    let tol = p.num_or(
        "tol",
        DEFAULT_TOL,
        MIN_TOL,
        MAX_TOL,
        " (drawing tolerance relative to the region's size)",
    )?;
    let robust = if p.flag("robust")? {
        Some(parse_robust(p, &spec)?)
    } else {
        refuse_robust_names(p)?;
        None
    };
    let nominal = nominal_region_cost(spec.cost_d());
    let (name, value) = spec.delay_param();
    within_budget(nominal, "the exact region", name, &value)?;
    let robust_kmax = parse_robust_box(p, &spec)?;
    Ok(RegionReq {
        spec,
        tol,
        robust,
        robust_kmax,
    })
}

/// The robust part of a region request (robust=1): its γ range, grid and refinement.
fn parse_robust(p: &Params, spec: &PlantSpec) -> Result<RobustReq, ApiError> {
    let d = paper_for_robust(p, spec)?.d;
    let (lo, hi, arm_stiffness) = robust_range(p, spec)?;
    if d > MAX_ROBUST_D {
        return Err(ApiError::param(
            "d",
            &d.to_string(),
            format!("parameter 'd' must be at most {MAX_ROBUST_D} for the robust region (got {d})"),
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
    robust_within_budget(d, gs, bs, refine)?;
    Ok(RobustReq {
        lo,
        hi,
        arm_stiffness,
        gamma_samples: gs,
        beta_samples: bs,
        refine,
    })
}

/// The robust region over a range of γ belongs to the paper's loop only: its (γ, δ, d).
fn paper_for_robust(p: &Params, spec: &PlantSpec) -> Result<PaperPlant, ApiError> {
    let Some(pp) = spec.paper else {
        return Err(ApiError::param(
            "robust",
            p.raw("robust").unwrap_or(""),
            format!(
                "parameter 'robust' (got '{}'): the robust region over a range of γ belongs to the paper's loop (device + arm, backward velocity, whole-sample delay, no actuator lag)",
                clip(p.raw("robust").unwrap_or(""))
            ),
        ));
    };
    Ok(pp)
}

/// The robust grid's cost within one request's budget, naming the grid's larger side.
fn robust_within_budget(d: usize, gs: usize, bs: usize, refine: bool) -> Result<(), ApiError> {
    let cost = robust_cost(d, gs, bs, refine);
    let (name, value) = if gs * DEFAULT_ROBUST_BETA_SAMPLES >= bs * DEFAULT_ROBUST_GAMMA_SAMPLES {
        ("gamma_samples", gs)
    } else {
        ("beta_samples", bs)
    };
    within_budget(
        cost,
        &format!(
            "the robust region over gamma_samples × beta_samples = {gs} × {bs} at d = {d}{}",
            if refine { " with refinement" } else { "" }
        ),
        name,
        &value.to_string(),
    )
}

/// Without robust=1, none of the robust region's parameters may be given.
fn refuse_robust_names(p: &Params) -> Result<(), ApiError> {
    for name in ROBUST_NAMES {
        if let Some(v) = p.raw(name) {
            return Err(ApiError::param(
                name,
                v,
                format!("parameter '{name}' (got '{}') needs robust=1", clip(v)),
            ));
        }
    }
    Ok(())
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
