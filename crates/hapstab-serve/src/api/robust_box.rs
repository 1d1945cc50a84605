//! The robust K_max overlay of `/api/region` (`box=NAME:LO:HI,…`): the largest K stable at
//! one damping for every loop whose parameters lie in the box, for any physical loop, as
//! `hapstab kmax --robust --box … --json` gives it (the same keys, from
//! [`crate::robust_box::answer`]), with the command line's text beside it.

use hapstab::Loop;
use hapstab::robust::{BoxSide, RobustOptions};

use super::within_budget;
use crate::limits::{MAX_BOX_SAMPLES, MAX_BOX_VERIFY, MAX_PHYS_DAMPING};
use crate::query::{ApiError, Params, PlantSpec, clip};
use crate::robust_box::{RobustBoxAnswer, cost, parse_side, text_lines};

/// Query names of the robust K_max over a box (the command line's `--box`, `--wall-damping`,
/// `--samples`, `--verify`, `--seed`).
pub(super) const ROBUST_BOX_NAMES: [&str; 5] = ["box", "wall_damping", "samples", "verify", "seed"];

/// A parsed robust K_max request: the loop, the box, the damping B (Ns/m) and the search.
#[derive(Debug, Clone)]
pub(crate) struct RobustBoxReq {
    pub lp: Loop,
    pub sides: Vec<BoxSide>,
    pub wall_damping: f64,
    pub opts: RobustOptions,
}

/// The robust K_max answer of `/api/region`.
pub(super) struct RobustBoxOut {
    /// The keys of `hapstab kmax --robust --box … --json`.
    pub answer: RobustBoxAnswer,
    /// The command line's text of the same answer, a line per item.
    pub text: Vec<String>,
}

/// A 400 about the box, quoting what the client sent.
fn box_error(raw: &str, why: impl std::fmt::Display) -> ApiError {
    ApiError::param(
        "box",
        raw,
        format!("parameter 'box' (got '{}'): {why}", clip(raw)),
    )
}

/// The box's sides from `NAME:LO:HI,NAME:LO:HI,…` (`sweep --param`'s names, SI units).
fn sides(raw: &str) -> Result<Vec<BoxSide>, ApiError> {
    let parts: Vec<&str> = raw
        .split(',')
        .map(str::trim)
        .filter(|s| !s.is_empty())
        .collect();
    if parts.is_empty() {
        return Err(box_error(
            raw,
            "needs at least one NAME:LO:HI, e.g. arm-stiffness:0:2000",
        ));
    }
    parts
        .into_iter()
        .map(|s| parse_side(s).map_err(|e| box_error(raw, e)))
        .collect()
}

/// The search's settings: `samples`, `verify` and `seed`, the command line's defaults
/// without them.
fn options(p: &Params) -> Result<RobustOptions, ApiError> {
    let d = RobustOptions::default();
    let seed = match p.raw("seed") {
        None => d.seed,
        Some(s) => s.trim().parse::<u64>().map_err(|_| {
            ApiError::param(
                "seed",
                s,
                format!(
                    "parameter 'seed' must be a whole number in [0, {}] (got {})",
                    u64::MAX,
                    clip(s)
                ),
            )
        })?,
    };
    Ok(RobustOptions {
        samples: p
            .opt_count(
                "samples",
                0,
                MAX_BOX_SAMPLES,
                " (uniform samples of the box)",
            )?
            .unwrap_or(d.samples),
        verify: p
            .opt_count("verify", 0, MAX_BOX_VERIFY, " (random plants verified)")?
            .unwrap_or(d.verify),
        seed,
    })
}

/// Without `box`, none of its settings may be given.
fn refuse_without_box(p: &Params) -> Result<(), ApiError> {
    for name in &ROBUST_BOX_NAMES[1..] {
        if let Some(v) = p.raw(name) {
            return Err(ApiError::param(
                name,
                v,
                format!(
                    "parameter '{name}' (got '{}') needs box=NAME:LO:HI,…",
                    clip(v)
                ),
            ));
        }
    }
    Ok(())
}

/// The robust K_max part of a region request, validated and priced: None without `box`.
pub(super) fn parse_robust_box(
    p: &Params,
    spec: &PlantSpec,
) -> Result<Option<RobustBoxReq>, ApiError> {
    let Some(raw) = p.raw("box") else {
        refuse_without_box(p)?;
        return Ok(None);
    };
    if spec.physical.is_none() {
        return Err(box_error(
            raw,
            "the box's ranges are in SI units: use mode=physical",
        ));
    }
    let sides = sides(raw)?;
    let wall_damping = p.num_or(
        "wall_damping",
        0.0,
        -MAX_PHYS_DAMPING,
        MAX_PHYS_DAMPING,
        " Ns/m (the damping B of the robust K_max)",
    )?;
    let opts = options(p)?;
    let lp = spec.sys.lp().clone();
    let c = cost(&lp, &sides, &opts).map_err(|e| box_error(raw, e))?;
    within_budget_blaming(c, raw, &opts)?;
    Ok(Some(RobustBoxReq {
        lp,
        sides,
        wall_damping,
        opts,
    }))
}

/// Refuses a search beyond one request's budget, naming `verify` or `samples` where one of
/// them is above its default and drives the cost, else the box (its degree or its sides).
fn within_budget_blaming(
    c: hapstab::limits::Cost,
    raw: &str,
    opts: &RobustOptions,
) -> Result<(), ApiError> {
    let d = RobustOptions::default();
    let (fv, fs) = (
        opts.verify as f64 / d.verify as f64,
        opts.samples as f64 / d.samples as f64,
    );
    let (name, value) = if fv > 1.0 && fv >= fs {
        ("verify", opts.verify.to_string())
    } else if fs > 1.0 {
        ("samples", opts.samples.to_string())
    } else {
        ("box", raw.to_string())
    };
    within_budget(c, "the robust K_max over the box", name, &value)
}

/// Computes the robust K_max of a request with the command line's text.
pub(super) fn robust_box_out(req: &RobustBoxReq) -> Result<RobustBoxOut, ApiError> {
    let answer = crate::robust_box::answer(&req.lp, &req.sides, req.wall_damping, req.opts)
        .map_err(|e| {
            let raw: Vec<String> = req
                .sides
                .iter()
                .map(|s| format!("{}:{}:{}", s.param.name(), s.lo, s.hi))
                .collect();
            box_error(&raw.join(","), e)
        })?;
    let text = text_lines(&req.sides, &answer.report);
    Ok(RobustBoxOut { answer, text })
}
