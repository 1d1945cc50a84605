//! `/api/kmax`: the largest stable stiffness K_max of a physical loop at one damping
//! (`wall_damping`), over a band of damping (`damping_lo`, optional `damping_hi`), or without
//! either the design answer (over B ≥ 0, beside B = 0 and the renderable band of
//! `position_resolution` and `force_noise`): the library's [`kmax_answer`], the object
//! `hapstab kmax --json` prints.

use hapstab::answer::{KmaxAnswer, kmax_answer};
use hapstab::kmax::{DEFAULT_FORCE_NOISE, DEFAULT_POSITION_RESOLUTION, KmaxQuery, NoiseModel};
use hapstab::limits::{core_degree, interval_cost, region_cost_of_degree};
use hapstab::sweep::KmaxAt;

use super::{loop_budget, physical_loop};
use crate::limits::MAX_PHYS_DAMPING;
use crate::query::{ApiError, Params, PlantSpec, lib_error};

/// The query names that say where K_max is taken.
pub(crate) const DAMPING_PARAMS: &[&str] = &["wall_damping", "damping_lo", "damping_hi"];

/// Query names of `/api/kmax`.
pub(crate) fn kmax_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.extend(DAMPING_PARAMS);
    v.extend(["position_resolution", "force_noise"]);
    v
}

/// Where K_max is taken: at `wall_damping` (Ns/m), over `damping_lo` ≤ B ≤ `damping_hi`
/// (no `damping_hi`: unbounded), or over every damping (None).
pub(crate) fn damping_of(p: &Params) -> Result<Option<KmaxAt>, ApiError> {
    let why = " Ns/m (virtual damping B)";
    let (lim_lo, lim_hi) = (-MAX_PHYS_DAMPING, MAX_PHYS_DAMPING);
    if p.has("wall_damping") {
        if let Some(name) = ["damping_lo", "damping_hi"].into_iter().find(|n| p.has(n)) {
            return Err(ApiError::param(
                name,
                p.raw(name).unwrap_or(""),
                format!(
                    "give either 'wall_damping' or the band 'damping_lo'/'damping_hi', not both (got '{name}' beside 'wall_damping')"
                ),
            ));
        }
        let damping = p.num_in("wall_damping", lim_lo, lim_hi, why)?;
        return Ok(Some(KmaxAt::Damping { damping }));
    }
    if !p.has("damping_lo") && !p.has("damping_hi") {
        return Ok(None);
    }
    let lo = p.num_in("damping_lo", lim_lo, lim_hi, why)?;
    let hi = p.num_or("damping_hi", f64::INFINITY, lim_lo, lim_hi, why)?;
    if lo > hi {
        return Err(ApiError::param(
            "damping_hi",
            p.raw("damping_hi").unwrap_or(""),
            format!("parameter 'damping_hi' must not be below 'damping_lo' (got {lo} and {hi})"),
        ));
    }
    Ok(Some(KmaxAt::Band { lo, hi }))
}

/// The K_max query of a request: at a damping, over a band, or the design query with its
/// noise model.
fn query_of(p: &Params) -> Result<KmaxQuery, ApiError> {
    Ok(match damping_of(p)? {
        Some(KmaxAt::Damping { damping }) => KmaxQuery::AtDamping(damping),
        Some(KmaxAt::Band { lo, hi }) => KmaxQuery::Band { lo, hi },
        Some(KmaxAt::Overall) | None => {
            let positive = |name: &str, default: f64| match p.opt_num(name)? {
                None => Ok(default),
                Some(x) if x > 0.0 => Ok(x),
                Some(x) => Err(ApiError::param(
                    name,
                    p.raw(name).unwrap_or(""),
                    format!("parameter '{name}' must be a positive number (got {x})"),
                )),
            };
            let dx = positive("position_resolution", DEFAULT_POSITION_RESOLUTION)?;
            let fn_ = positive("force_noise", DEFAULT_FORCE_NOISE)?;
            KmaxQuery::Design(NoiseModel::new(dx, fn_).map_err(lib_error)?)
        }
    })
}

/// A parsed `/api/kmax` request.
pub(crate) struct KmaxReq {
    spec: PlantSpec,
    query: KmaxQuery,
}

/// Reads the loop and the query of `/api/kmax`.
pub(crate) fn parse_kmax(p: &Params) -> Result<KmaxReq, ApiError> {
    if (p.has("position_resolution") || p.has("force_noise"))
        && let Some(name) = DAMPING_PARAMS.iter().find(|n| p.has(n))
    {
        return Err(ApiError::param(
            name,
            p.raw(name).unwrap_or(""),
            format!(
                "'position_resolution' and 'force_noise' set the renderable band of the answer over every damping: not with '{name}'"
            ),
        ));
    }
    Ok(KmaxReq {
        spec: crate::query::plant_spec(p)?,
        query: query_of(p)?,
    })
}

/// Computes `/api/kmax` within the interactive budget.
pub(crate) fn kmax(req: &KmaxReq) -> Result<KmaxAnswer, ApiError> {
    let sys = physical_loop(&req.spec, "K_max")?;
    let fam = sys.family();
    let n = fam.degree();
    let mut cost = interval_cost(n);
    if !matches!(req.query, KmaxQuery::AtDamping(_)) {
        cost = cost.then(region_cost_of_degree(n, core_degree(fam)));
    }
    loop_budget(&req.spec, cost, "K_max")?;
    kmax_answer(sys, req.query).map_err(lib_error)
}
