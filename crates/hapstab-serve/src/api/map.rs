//! `/api/map`: the paper's grid method (Section V) over the physical wall of any loop
//! (`x=K:LO:HI:N&y=B:LO:HI:N`, K in N/m, B in Ns/m) or over two of α, β, γ, δ of the paper's
//! normalized loop (`mode=normalized`, the others fixed by `alpha`, `beta`, `gamma`, `delta`),
//! optionally with the spectral radius (`radius=1`): the summary `hapstab map --json` prints
//! and the grid its `--out` file holds, row-major, x varying fastest.

use std::time::Instant;

use hapstab::Normalized;
use hapstab::answer::{MapInput, MapSummary};
use hapstab::limits::{map_cost_of_degree, plants_cost};
use hapstab::loop_spec::LoopInput;
use hapstab::map::{Axis, AxisRange, MapKind, wall_map_physical};
use hapstab::paper::map::{MapSpec, compute_map};
use serde::Serialize;

use super::{physical_loop, within_budget};
use crate::limits::{MAX_MAP_AXIS_POINTS, MAX_WALL};
use crate::query::{ApiError, Params, PlantSpec, clip, lib_error};

/// Query names of `/api/map`.
pub(crate) fn map_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.extend(["x", "y", "radius", "alpha", "beta"]);
    v
}

/// What an axis grids: a parameter of the paper's normalized loop, or the wall's K or B.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Name {
    Normalized(Axis),
    K,
    B,
}

/// One axis as given: its name, its text and n points from lo to hi.
#[derive(Debug, Clone)]
struct Grid {
    name: Name,
    text: String,
    range: AxisRange,
}

/// Reads the axis `flag` (x or y): NAME:LO:HI:N.
fn axis(p: &Params, flag: &str) -> Result<Grid, ApiError> {
    let raw = p
        .raw(flag)
        .ok_or_else(|| ApiError::param(flag, "", format!("missing parameter '{flag}'")))?;
    let bad = |why: String| ApiError::param(flag, raw, format!("parameter '{flag}': {why}"));
    let parts: Vec<&str> = raw.split(':').collect();
    let [name, lo, hi, n] = parts[..] else {
        return Err(bad(format!("must be NAME:LO:HI:N (got '{}')", clip(raw))));
    };
    let name = match name {
        "K" => Name::K,
        "B" => Name::B,
        other => Name::Normalized(other.parse().map_err(|_| {
            bad(format!(
                "unknown axis '{}' (alpha, beta, gamma, delta, K, B)",
                clip(other)
            ))
        })?),
    };
    let num = |t: &str, what: &str| match t.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x.abs() <= MAX_WALL * 1e6 => Ok(x),
        _ => Err(bad(format!("bad {what} '{}'", clip(t)))),
    };
    let (lo, hi) = (num(lo, "lower end")?, num(hi, "upper end")?);
    let n: usize = match n.trim().parse() {
        Ok(n) if (2..=MAX_MAP_AXIS_POINTS).contains(&n) => n,
        _ => {
            return Err(bad(format!(
                "the point count must be a whole number in [2, {MAX_MAP_AXIS_POINTS}] (got '{}')",
                clip(n)
            )));
        }
    };
    let ax = match name {
        Name::Normalized(a) => a,
        Name::K => Axis::Alpha,
        Name::B => Axis::Beta,
    };
    let range = AxisRange::new(ax, lo, hi, n).map_err(|e| bad(e.to_string()))?;
    Ok(Grid {
        name,
        text: raw.to_string(),
        range,
    })
}

/// A parsed `/api/map` request.
pub(crate) struct MapReq {
    spec: PlantSpec,
    x: Grid,
    y: Grid,
    kind: MapKind,
    /// The fixed α and β of a normalized map.
    alpha: f64,
    beta: f64,
}

/// Reads the loop, the axes and the kind of `/api/map`.
pub(crate) fn parse_map(p: &Params) -> Result<MapReq, ApiError> {
    let spec = crate::query::plant_spec(p)?;
    let (x, y) = (axis(p, "x")?, axis(p, "y")?);
    let physical = spec.physical.is_some();
    match (x.name, y.name) {
        (Name::Normalized(_), Name::Normalized(_)) if physical => {
            return Err(ApiError::param(
                "x",
                &x.text,
                "maps over alpha, beta, gamma, delta are of the paper's normalized loop (mode=normalized); for a physical loop grid x=K:LO:HI:N and y=B:LO:HI:N".into(),
            ));
        }
        (Name::Normalized(_), Name::Normalized(_)) => {}
        (Name::K, Name::B) if !physical => {
            return Err(ApiError::param(
                "x",
                &x.text,
                "K and B axes map a physical loop (mode=physical); with mode=normalized grid alpha and beta".into(),
            ));
        }
        (Name::K, Name::B) => {
            if let Some(name) = ["alpha", "beta"].into_iter().find(|n| p.has(n)) {
                return Err(ApiError::param(
                    name,
                    p.raw(name).unwrap_or(""),
                    format!(
                        "parameter '{name}' fixes a normalized map's {name}; a K, B map grids the wall"
                    ),
                ));
            }
        }
        _ => {
            return Err(ApiError::param(
                "y",
                &y.text,
                "x and y must both be normalized (alpha, beta, gamma, delta), or x=K:… and y=B:…"
                    .into(),
            ));
        }
    }
    let why = " (the fixed parameter of a normalized map)";
    Ok(MapReq {
        kind: if p.flag("radius")? {
            MapKind::SpectralRadius
        } else {
            MapKind::Stability
        },
        alpha: p.num_or("alpha", 0.0, -MAX_WALL, MAX_WALL, why)?,
        beta: p.num_or("beta", 0.0, -MAX_WALL, MAX_WALL, why)?,
        spec,
        x,
        y,
    })
}

/// Answer of `/api/map`: the command line's summary and the grid.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct MapOut {
    #[serde(flatten)]
    pub summary: MapSummary,
    /// Stable flag per point, row-major (point (ix, iy) at iy·nx + ix).
    pub stable: Vec<bool>,
    /// Spectral radius per point (with `radius=1`; null where the roots cannot be found).
    pub spectral_radius: Option<Vec<f64>>,
}

/// Refuses a map beyond the interactive budget (every point counted stable, and the family of
/// each of `plants` plants, [`MapSpec::plants`]), naming the longer axis.
fn map_budget(req: &MapReq, degree: usize, plants: usize) -> Result<(), ApiError> {
    let points = req.x.range.n as f64 * req.y.range.n as f64;
    let radius = req.kind == MapKind::SpectralRadius;
    let g = if req.x.range.n >= req.y.range.n {
        ("x", &req.x.text)
    } else {
        ("y", &req.y.text)
    };
    within_budget(
        map_cost_of_degree(points, degree, radius, 1.0).then(plants_cost(plants as f64)),
        &format!("the map of {points} points"),
        g.0,
        g.1,
    )
}

/// Computes `/api/map` within the interactive budget.
pub(crate) fn map(req: &MapReq) -> Result<MapOut, ApiError> {
    let t = Instant::now();
    let (stable, radius, lp) = match req.x.name {
        Name::Normalized(_) => {
            let s = req.spec.view();
            let base = Normalized::new(req.alpha, req.beta, s.plant.gamma, s.plant.delta, s.d)
                .map_err(lib_error)?;
            let spec = MapSpec::new(req.x.range, req.y.range, base).map_err(lib_error)?;
            map_budget(req, s.d + 3, spec.plants())?;
            let m = compute_map(&spec, req.kind, &|_| {}).map_err(lib_error)?;
            let input = LoopInput::Normalized {
                gamma: base.gamma,
                delta: base.delta,
                d: base.d,
                alpha: Some(base.alpha),
                beta: Some(base.beta),
            };
            (m.stable, m.radius, input)
        }
        _ => {
            let sys = physical_loop(&req.spec, "the map over K and B")?;
            let (lp, fam) = (sys.lp(), sys.family());
            map_budget(req, fam.degree(), 1)?;
            let (x, y) = (&req.x.range, &req.y.range);
            let m = wall_map_physical(
                fam,
                ((x.lo, x.hi), x.n),
                ((y.lo, y.hi), y.n),
                req.kind,
                &|_| {},
            )
            .map_err(lib_error)?;
            (m.stable, m.radius, LoopInput::new(lp, false, None))
        }
    };
    Ok(MapOut {
        summary: MapSummary {
            input: MapInput {
                x: req.x.text.clone(),
                y: req.y.text.clone(),
                lp,
                radius: req.kind == MapKind::SpectralRadius,
            },
            points: stable.len(),
            stable_points: stable.iter().filter(|&&s| s).count(),
            seconds: t.elapsed().as_secs_f64(),
        },
        stable,
        spectral_radius: radius,
    })
}
