//! `/api/sweep`: K_max (stable and passive) of a physical loop against one of its parameters
//! (`param` from `lo` to `hi` in `n` points, as `hapstab sweep --param NAME:LO:HI:N`), at a
//! damping, over a band or over every damping: the library's [`sweep_answer`], the object
//! `hapstab sweep --json` prints.

use hapstab::answer::{SweepAnswer, sweep_answer};
use hapstab::limits::sweep_cost;
use hapstab::sweep::{KmaxAt, SweepParam, SweepRange};

use super::kmax::{DAMPING_PARAMS, damping_of};
use super::{physical_loop, within_budget};
use crate::limits::MAX_SWEEP_POINTS;
use crate::query::{ApiError, Params, PlantSpec, clip, lib_error};

/// Query names of `/api/sweep`.
pub(crate) fn sweep_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.extend(["param", "lo", "hi", "n"]);
    v.extend(DAMPING_PARAMS);
    v
}

/// A parsed `/api/sweep` request.
pub(crate) struct SweepReq {
    spec: PlantSpec,
    range: SweepRange,
    at: KmaxAt,
}

/// Reads the loop, the swept range and the damping of `/api/sweep`.
pub(crate) fn parse_sweep(p: &Params) -> Result<SweepReq, ApiError> {
    let name = p
        .raw("param")
        .ok_or_else(|| ApiError::param("param", "", "missing parameter 'param'".into()))?;
    let param: SweepParam = name.trim().parse().map_err(|e: hapstab::Error| {
        ApiError::param("param", name, format!("parameter 'param': {e}"))
    })?;
    let lo = p.num("lo")?;
    let hi = p.num("hi")?;
    let n = p.count("n", 2, MAX_SWEEP_POINTS, " (points of the sweep)")?;
    let range = SweepRange::new(param, lo, hi, n).map_err(lib_error)?;
    Ok(SweepReq {
        spec: crate::query::plant_spec(p)?,
        range,
        at: damping_of(p)?.unwrap_or(KmaxAt::Overall),
    })
}

/// Computes `/api/sweep` within the interactive budget.
pub(crate) fn sweep(req: &SweepReq) -> Result<SweepAnswer, ApiError> {
    let sys = physical_loop(&req.spec, "the sweep")?;
    let lp = sys.lp();
    let r = &req.range;
    let cost = sweep_cost(lp, r.param, &r.values(), req.at);
    within_budget(
        cost,
        &format!("the sweep of {} points", r.n),
        "n",
        &r.n.to_string(),
    )?;
    sweep_answer(lp, r, req.at, &|_| {}).map_err(|e| {
        let name = r.param.name();
        ApiError::param(
            "param",
            name,
            format!("the sweep of {} from {} to {}: {e}", clip(name), r.lo, r.hi),
        )
    })
}
