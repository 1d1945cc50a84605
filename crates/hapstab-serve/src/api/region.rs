//! `/api/region`: the exact stable region (Section V) simplified for drawing, the linear
//! condition, the passive regions and on request the robust region (Section VIII), with
//! their estimated costs.

use std::time::Instant;

use hapstab::answer::{RegionAnswer, region_answer};
use hapstab::boundary::WallPoint;
use hapstab::kmax::{KmaxQuery, KmaxReport, NoiseModel, kmax};
use hapstab::limits::{Cost, region_cost, region_summary_cost, robust_region_cost};
use hapstab::paper::linear::linear_alpha_limit;
use hapstab::paper::nyquist::{
    GammaRange, RobustOptions, region_summary, robust_region, unit_circle_pole,
};
use hapstab::region::{Edge, Polygon, StableRegion};
use hapstab::{Loop, System};
use serde::Serialize;

use super::PlantOut;
use super::passive::{PassiveOut, passive_regions};
use super::region_request::RegionReq;
use super::robust_box::{RobustBoxOut, robust_box_out};
use crate::limits::*;
use crate::query::{ApiError, PaperPlant, PhysicalSpec, fmt, lib_error};
use crate::robust_box::RobustBoxAnswer;
use hapstab_plot::simplify::simplify_polygon;

/// β slices of the exact cross-check of an empty polygon result.
const EMPTY_CHECK_SLICES: usize = 64;

/// The exact stable region (Section V) as sent to the page: the library's region answer
/// ([`hapstab::answer::RegionAnswer`], the keys of `hapstab boundary --json`: K and B
/// for a physical loop, α and β for normalized input) of the polygons simplified for drawing,
/// with the simplification's figures.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct RegionJson {
    /// The region in the user's units, its polygons simplified for drawing.
    #[serde(flatten)]
    pub answer: RegionAnswer,
    /// The simplified rings in the loop's wall units a = K/k_per_unit, b = B/b_per_unit (the
    /// plane the page and the export draw in; (α, β) for the paper's loop).
    #[serde(skip)]
    pub drawn: Vec<Vec<[f64; 2]>>,
    /// The largest stable a and its b in wall units (NaN when empty).
    #[serde(skip)]
    pub max_drawn: [f64; 2],
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
pub(crate) struct LinearOut {
    pub equation: &'static str,
    /// dα/dβ along the line: 1/(d + 1/2).
    pub slope: f64,
    /// α of the line at β = 0: δ/(d + 1/2).
    pub alpha_at_beta0: f64,
    /// Lower bound of eq. (19): α > −γ.
    pub alpha_lower: f64,
}

/// The robustly stable region over a γ range (Section VIII), from
/// `hapstab::paper::nyquist::robust_region`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct RobustOut {
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
pub(crate) struct Timing {
    pub region: f64,
    pub robust: f64,
    /// The robust K_max over a box.
    pub robust_kmax: f64,
    pub total: f64,
}

/// Answer of `/api/region`.
#[derive(Debug, Clone, Serialize)]
pub(crate) struct RegionOut {
    /// The paper's (γ, δ, d) of a loop with its normalized view (Table I); null for a loop
    /// beyond the paper's, which is under `loop`.
    pub params: Option<PlantOut>,
    pub physical: Option<PhysicalSpec>,
    /// A loop beyond the paper's: plant, period, delay and velocity estimator (its region is
    /// sent in N/m and Ns/m like any physical loop's; the page draws it in the loop's wall
    /// units a = K/k_per_unit, b = B/b_per_unit).
    #[serde(rename = "loop", skip_serializing_if = "Option::is_none")]
    pub lp: Option<Loop>,
    pub region: RegionJson,
    /// The paper's linear condition (null for other loops).
    pub linear: Option<LinearOut>,
    pub passive: Option<PassiveOut>,
    /// Eq. (28) with the arm's damping counted (a device held by an arm): towards this
    /// operator only.
    pub passive_with_arm: Option<PassiveOut>,
    pub robust: Option<RobustOut>,
    /// Physical mode and loops beyond the paper's: K_max at B = 0, over the renderable band
    /// and over B ≥ 0 in N/m and Ns/m (the library's answer, as `hapstab kmax --json`).
    pub kmax: Option<KmaxReport>,
    /// With `box=…`: the robust K_max over the box at `wall_damping`, the keys of
    /// `hapstab kmax --robust --box … --json`.
    pub robust_kmax: Option<RobustBoxAnswer>,
    /// The command line's text of `robust_kmax`, a line per item, the last one saying what was
    /// checked.
    pub robust_kmax_text: Option<Vec<String>>,
    pub warnings: Vec<String>,
    pub server_ms: Timing,
}

/// The design K_max answer of a loop (`hapstab kmax` without a damping).
fn design_kmax(sys: &System) -> Result<KmaxReport, ApiError> {
    kmax(sys, KmaxQuery::Design(NoiseModel::default())).map_err(lib_error)
}

/// Estimated cost of the nominal part of `/api/region`: the exact polygons and, when they
/// come out empty, the cross-check by 64 exact α-interval slices.
pub(crate) fn nominal_region_cost(d: usize) -> Cost {
    region_cost(d).then(region_summary_cost(EMPTY_CHECK_SLICES, d))
}

/// Estimated cost of the robust region of `/api/region`.
pub(crate) fn robust_cost(
    d: usize,
    gamma_samples: usize,
    beta_samples: usize,
    refine: bool,
) -> Cost {
    robust_region_cost(
        gamma_samples,
        beta_samples,
        d,
        refine,
        ROBUST_REFINE_BETA_ROUNDS,
    )
}

pub(super) fn ab(p: &WallPoint) -> [f64; 2] {
    [p.a, p.b]
}

/// The exact region `r` of `sys` with its polygons simplified to `tol` relative to its size,
/// answered in the user's units (`normalized`: α and β).
fn region_json(sys: &System, normalized: bool, r: &StableRegion, tol: f64) -> RegionJson {
    let size = r.size();
    let abs_tol = if size.is_finite() { tol * size } else { 0.0 };
    let polygons: Vec<Polygon> = r
        .polygons
        .iter()
        .map(|poly| {
            let (vertices, starts) = simplify_polygon(poly, abs_tol);
            let edges = poly
                .edges
                .iter()
                .zip(starts)
                .map(|(e, start)| Edge { start, ..*e })
                .collect();
            // the drawn ring has no per-vertex angles: the answer does not carry them
            Polygon {
                vertices,
                edges,
                thetas: Vec::new(),
            }
        })
        .collect();
    let simplified = StableRegion {
        polygons,
        a_max: r.a_max,
        b_at_a_max: r.b_at_a_max,
        a_max_attained: r.a_max_attained,
        b_stable: r.b_stable,
        a_stable: r.a_stable,
        area: r.area,
    };
    RegionJson {
        answer: region_answer(sys, normalized, &simplified),
        drawn: simplified
            .polygons
            .iter()
            .map(|p| p.vertices.iter().map(ab).collect())
            .collect(),
        max_drawn: [r.a_max, r.b_at_a_max],
        empty: r.polygons.is_empty(),
        vertices_exact: r.polygons.iter().map(|p| p.vertices.len()).sum(),
        vertices_sent: simplified.polygons.iter().map(|p| p.vertices.len()).sum(),
        tol,
    }
}

/// The robustly stable region over the query's γ range (Section VIII).
fn robust_out(
    rr: super::region_request::RobustReq,
    delta: f64,
    d: usize,
) -> Result<RobustOut, ApiError> {
    let opts = RobustOptions {
        gamma_samples: rr.gamma_samples,
        beta_samples: rr.beta_samples,
        refine_gamma: rr.refine,
        refine_beta_rounds: ROBUST_REFINE_BETA_ROUNDS,
    };
    let range = GammaRange {
        delta,
        d,
        gamma_lo: rr.lo,
        gamma_hi: rr.hi,
    };
    let r = robust_region(range, opts).map_err(lib_error)?;
    Ok(RobustOut {
        gamma_lo: r.gamma_lo,
        gamma_hi: r.gamma_hi,
        arm_stiffness_lo: rr.arm_stiffness.map(|k| k[0]),
        arm_stiffness_hi: rr.arm_stiffness.map(|k| k[1]),
        gamma_samples: rr.gamma_samples,
        beta_samples: rr.beta_samples,
        refined: rr.refine,
        method: "hapstab::paper::nyquist::robust_region: intersection of exact per-β stable α-intervals over uniform γ samples",
        polygon: r.polygon.iter().map(ab).collect(),
        alpha_max: r.alpha_max,
        beta_at_alpha_max: r.beta_at_alpha_max,
        area: r.area,
        empty: r.empty,
        multiple_intervals: r.multiple_intervals,
        degenerate_gammas: r.degenerate_gammas,
    })
}

/// The robust K_max over the request's box, if any, and its time in ms.
fn robust_kmax(req: &RegionReq) -> Result<(Option<RobustBoxOut>, f64), ApiError> {
    let t = Instant::now();
    let out = req.robust_kmax.as_ref().map(robust_box_out).transpose()?;
    Ok((out, t.elapsed().as_secs_f64() * 1e3))
}

/// Computes the answer of `/api/region`: the exact region of the loop's family in its wall
/// units ((α, β) for the paper's loop), its passive regions and the design K_max in physical
/// mode; for the paper's loop also the linear condition and on request the robust region.
pub(crate) fn region(req: &RegionReq) -> Result<RegionOut, ApiError> {
    let t0 = Instant::now();
    let spec = &req.spec;
    let r = spec.sys.region().map_err(lib_error)?;
    let t_region = t0.elapsed().as_secs_f64() * 1e3;
    let region = region_json(&spec.sys, spec.physical.is_none(), &r, req.tol);
    let warnings = match spec.paper {
        Some(pp) => paper_warnings(pp, region.empty)?,
        None => Vec::new(),
    };
    let linear = spec.paper.map(|pp| LinearOut {
        equation: "α < (β + δ)/(d + 1/2)  (eq. 23),  α > −γ  (eq. 19)",
        slope: 1.0 / (pp.d as f64 + 0.5),
        alpha_at_beta0: linear_alpha_limit(0.0, pp.plant.delta, pp.d),
        alpha_lower: -pp.plant.gamma,
    });
    let (passive, passive_with_arm) = passive_regions(spec)?;
    let t1 = Instant::now();
    let robust = match (req.robust, spec.paper) {
        (Some(rr), Some(pp)) => Some(robust_out(rr, pp.plant.delta, pp.d)?),
        _ => None,
    };
    let t_robust = t1.elapsed().as_secs_f64() * 1e3;
    let kmax = spec.physical.map(|_| design_kmax(&spec.sys)).transpose()?;
    let (rk, t_rk) = robust_kmax(req)?;
    Ok(RegionOut {
        params: spec.paper.map(PlantOut::from),
        physical: spec.physical,
        lp: spec.paper.is_none().then(|| spec.sys.lp().clone()),
        region,
        linear,
        passive,
        passive_with_arm,
        robust,
        kmax,
        robust_kmax_text: rk.as_ref().map(|r| r.text.clone()),
        robust_kmax: rk.map(|r| r.answer),
        warnings,
        server_ms: Timing {
            region: t_region,
            robust: t_robust,
            robust_kmax: t_rk,
            total: t0.elapsed().as_secs_f64() * 1e3,
        },
    })
}

/// The paper's loop: a pole on the unit circle for every wall (Section VIII-B), or an empty
/// polygon that the exact per-β α-intervals contradict.
fn paper_warnings(pp: PaperPlant, empty: bool) -> Result<Vec<String>, ApiError> {
    let mut warnings = Vec::new();
    if unit_circle_pole(pp.plant).is_some() {
        warnings.push(format!(
            "δ = 0 and γ = {} = (jπ)²: p(z) has a root on the unit circle for every (α, β) (Section VIII-B), so no point is strictly stable",
            fmt(pp.plant.gamma)
        ));
    } else if empty {
        // Cross-check an empty polygon result by exact per-β α-intervals.
        let summary = region_summary(pp.plant, pp.d, EMPTY_CHECK_SLICES).map_err(lib_error)?;
        if !summary.empty {
            warnings.push(format!(
                "the polygon construction (hapstab::region::stable_region) returned no region, but exact per-β α-intervals (hapstab::paper::nyquist::region_summary) find stable points up to α = {} at β = {}",
                fmt(summary.alpha_max),
                fmt(summary.beta_at_alpha_max)
            ));
        }
    }
    Ok(warnings)
}
