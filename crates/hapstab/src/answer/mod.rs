//! The answers of the analyses with their inputs echoed, as every front end serializes them:
//! `hapstab kmax|sweep|zwidth|map|passivity --json` and the explorer's `/api/kmax`,
//! `/api/sweep`, `/api/zwidth`, `/api/map` and `/api/passivity` give the same objects under
//! the same keys, the explorer's `/api/point` is a [`WallAnswer`] and `hapstab simulate --json` and
//! `/api/simulate` a [`SimulationAnswer`] (the command line adds the files it wrote, the
//! explorer the map's grid or the run's trace).

mod check;
mod region;
mod simulation;
mod wall;

pub use check::{CheckAnswer, CheckPaperView, check_answer};
pub use region::{
    NormalizedRegion, PhysicalRegion, RegionAnswer, RegionEdge, RegionPaperView, WallUnitsOut,
    region_answer,
};
pub use simulation::{SimulationAnswer, SimulationInput};
pub use wall::{WallAnswer, wall_answer};

use std::time::Instant;

use serde::Serialize;

use crate::error::Result;
use crate::kmax::{KmaxQuery, KmaxReport, kmax};
use crate::loop_spec::LoopInput;
use crate::model::Loop;
use crate::params::Wall;
use crate::passivity::{
    DeviceDamping, PassiveRegion, Passivity, PassivityVerdict, SampledWall, passive_region,
    passivity_of_device, passivity_with,
};
use crate::stability::Verdict;
use crate::sweep::{KmaxAt, SweepParam, SweepPoint, SweepRange, sweep_param};
use crate::system::System;
use crate::zwidth::ZWidth;

/// The paper's normalized view of a K_max answer (Table I): α_max and its β beside the
/// plant's (γ, δ, d).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct KmaxPaperView {
    /// K_max in normalized units α = KT²/m.
    pub alpha_max: Option<f64>,
    /// Its damping in normalized units β = BT/m.
    pub beta: Option<f64>,
    /// The plant's normalized stiffness γ = kT²/m.
    pub gamma: f64,
    /// The plant's normalized damping δ = bT/m.
    pub delta: f64,
    /// The delay d in samples.
    pub d: usize,
}

/// The inputs of a K_max answer: the loop and the damping given, or the band searched.
#[derive(Debug, Clone, Serialize)]
pub struct KmaxInput {
    /// The loop (the form a loop file takes).
    #[serde(flatten)]
    pub lp: LoopInput,
    /// The given virtual damping B in Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_damping: Option<f64>,
    /// The damping band searched without a B, [lo, hi] in Ns/m (hi null: unbounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub damping_range: Option<[Option<f64>; 2]>,
}

/// K_max of a physical loop for a query, with the loop and the query echoed.
#[derive(Debug, Clone, Serialize)]
pub struct KmaxAnswer {
    /// The loop and the damping asked.
    pub input: KmaxInput,
    /// The answer, under the library's report keys.
    #[serde(flatten)]
    pub report: KmaxReport,
    /// The paper's loop: the same result in normalized units (Table I).
    #[serde(rename = "normalized", skip_serializing_if = "Option::is_none")]
    pub paper: Option<KmaxPaperView>,
}

/// K_max of a physical loop for a query ([`kmax`]), its inputs echoed: at a damping, over a
/// band of damping, or the design query (over B ≥ 0, beside B = 0 and the renderable band).
pub fn kmax_answer(sys: &System, query: KmaxQuery) -> Result<KmaxAnswer> {
    let lp = sys.lp();
    let report = kmax(sys, query)?;
    let (wall_damping, damping_range) = match query {
        KmaxQuery::AtDamping(b) => (Some(b), None),
        KmaxQuery::Band { lo, hi } => (None, Some([Some(lo), hi.is_finite().then_some(hi)])),
        KmaxQuery::Design(_) => (None, Some([Some(0.0), None])),
    };
    let paper = lp.paper_view().map(|pp| KmaxPaperView {
        alpha_max: report.k_max_units,
        beta: report.b_units,
        gamma: pp.gamma,
        delta: pp.delta,
        d: lp.delay.samples,
    });
    Ok(KmaxAnswer {
        input: KmaxInput {
            lp: LoopInput::new(lp, false, None),
            wall_damping,
            damping_range,
        },
        report,
        paper,
    })
}

/// The inputs of a sweep: the base loop, the swept parameter and where K_max is taken.
#[derive(Debug, Clone, Serialize)]
pub struct SweepInput {
    /// The base loop.
    #[serde(flatten)]
    pub lp: LoopInput,
    /// The swept parameter.
    pub param: SweepParam,
    /// The damping (or band) at which K_max is taken.
    pub k_max_at: KmaxAt,
}

/// K_max (stable and passive) against one parameter of a loop, its inputs echoed.
#[derive(Debug, Clone, Serialize)]
pub struct SweepAnswer {
    /// The base loop, the parameter and the damping.
    pub input: SweepInput,
    /// Unit of the swept values.
    pub unit: &'static str,
    /// K_max at every value.
    pub points: Vec<SweepPoint>,
    /// Wall-clock time of the analysis, s.
    pub seconds: f64,
}

/// The sweep of one parameter of a physical loop ([`sweep_param`]), timed, its inputs echoed;
/// `progress` is called with the number of points done.
pub fn sweep_answer(
    lp: &Loop,
    range: &SweepRange,
    at: KmaxAt,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<SweepAnswer> {
    let t = Instant::now();
    let points = sweep_param(lp, range, at, progress)?;
    Ok(SweepAnswer {
        input: SweepInput {
            lp: LoopInput::new(lp, false, None),
            param: range.param,
            k_max_at: at,
        },
        unit: range.param.unit(),
        points,
        seconds: t.elapsed().as_secs_f64(),
    })
}

/// The Z-width of one loop, labelled, its inputs echoed.
#[derive(Debug, Clone, Serialize)]
pub struct ZwidthLoop {
    /// The loop's label: its velocity estimator, or how it was given.
    pub label: String,
    /// The loop.
    pub input: LoopInput,
    /// Its Z-width.
    #[serde(flatten)]
    pub zwidth: ZWidth,
}

impl ZwidthLoop {
    /// The Z-width of a physical loop ([`crate::zwidth::zwidth`]) with the table's dampings
    /// in Ns/m (None: the default table).
    pub fn new(label: String, lp: &Loop, dampings: Option<&[f64]>) -> Result<Self> {
        Ok(ZwidthLoop {
            label,
            input: LoopInput::new(lp, false, None),
            zwidth: crate::zwidth::zwidth(lp, dampings)?,
        })
    }
}

/// The inputs of a Z-width comparison: the compared loops' specifications and the table's
/// dampings (each loop's own inputs are under `loops[i].input`).
#[derive(Debug, Clone, Serialize)]
pub struct ZwidthInput {
    /// The loops compared with the first, as given.
    pub compare: Vec<String>,
    /// The table's dampings in Ns/m; null: 11 from 0 to the largest stable B of each loop.
    pub table_damping: Option<Vec<f64>>,
}

/// The Z-width of one loop or of several compared.
#[derive(Debug, Clone, Serialize)]
pub struct ZwidthAnswer {
    /// The comparison's inputs.
    pub input: ZwidthInput,
    /// One Z-width per loop, the base loop first.
    pub loops: Vec<ZwidthLoop>,
}

/// The inputs of a stability map: the axes as given and the loop (or the fixed normalized
/// parameters).
#[derive(Debug, Clone, Serialize)]
pub struct MapInput {
    /// The horizontal axis, NAME:LO:HI:N.
    pub x: String,
    /// The vertical axis, NAME:LO:HI:N.
    pub y: String,
    /// The loop: physical for a (K, B) map, the paper's normalized plant with α and β for a
    /// map over α, β, γ, δ.
    #[serde(flatten)]
    pub lp: LoopInput,
    /// True when the spectral radius is computed at every point.
    pub radius: bool,
}

/// The summary of a stability map: how many of its points are stable.
#[derive(Debug, Clone, Serialize)]
pub struct MapSummary {
    /// The axes and the loop.
    pub input: MapInput,
    /// Number of grid points.
    pub points: usize,
    /// Number of stable grid points.
    pub stable_points: usize,
    /// Wall-clock time of the map, s.
    pub seconds: f64,
}

/// A passive region in a passivity answer: its largest stiffness and its polygon.
#[derive(Debug, Clone, Serialize)]
pub struct PassiveRegionOut {
    /// The largest passive stiffness K in N/m (α for a normalized plant).
    pub k_max: f64,
    /// The damping B at which it is reached, Ns/m (β for a normalized plant).
    pub b_at_k_max: f64,
    /// The region's area in N/m · Ns/m.
    pub area: f64,
    /// False when the region is unbounded (and its polygon cut).
    pub bounded: bool,
    /// Counter-clockwise vertices [K, B].
    pub vertices: Vec<[f64; 2]>,
}

impl From<&PassiveRegion> for PassiveRegionOut {
    fn from(r: &PassiveRegion) -> Self {
        PassiveRegionOut {
            k_max: r.k_max,
            b_at_k_max: r.b_at_k_max,
            area: r.area,
            bounded: r.bounded,
            vertices: r
                .vertices
                .iter()
                .map(|v| [v.stiffness, v.damping])
                .collect(),
        }
    }
}

/// The passivity of one wall (Colgate–Schenkel; eq. 28 for the paper's loop), beside its
/// stability and the passive region of the device.
#[derive(Debug, Clone, Serialize)]
pub struct PassivityAnswer {
    /// The loop and the wall.
    pub input: LoopInput,
    /// The device damping the wall requires, Ns/m (δ for a normalized plant).
    pub b_required: f64,
    /// Where the requirement binds, Hz (cycles per sample for a normalized plant).
    pub binding_frequency_hz: f64,
    /// The same as θ = ωT in [0, π].
    pub binding_theta: f64,
    /// The wall's static stiffness K + B·V(1), N/m (must be >= 0).
    pub dc_stiffness: f64,
    /// The device's own damping b_L, the arm's excluded (null when the argument does not
    /// apply): passivity towards any passive operator.
    pub device_damping: Option<f64>,
    /// The paper's eq. (28) read with the effective damping b = b_L + b_H of eq. (1), the arm
    /// included (null when the plant names no arm): passivity towards this operator only.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub effective_damping: Option<f64>,
    /// The verdict against the effective damping.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub effective_verdict: Option<PassivityVerdict>,
    /// True when b > b_required and the static stiffness is >= 0; null when not applicable.
    pub meets: Option<bool>,
    /// The verdict for the device's own damping.
    pub verdict: PassivityVerdict,
    /// Why the verdict is not applicable.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
    /// The wall's stability (Schur–Cohn), to read beside the passivity verdict.
    pub stable: bool,
    /// The passive region for the device's damping (null when not applicable).
    pub passive_region: Option<PassiveRegionOut>,
}

/// The passivity of the wall `w` (in the loop's units: N/m and Ns/m, α and β for a
/// normalized loop) on a loop, its stability and the device's passive region; `normalized`
/// says whether the loop is the paper's normalized one (m = T = 1). Also returns the library's
/// [`Passivity`] it is read from.
pub fn passivity_answer(
    sys: &System,
    normalized: bool,
    w: Wall,
) -> Result<(PassivityAnswer, Passivity)> {
    passivity_answer_for(sys, normalized, w, None)
}

/// [`passivity_answer`] for a given device damper in place of the plant's own
/// ([`passivity_of_device`]: "would a device with b = … render it passively?"); `None` is the
/// plant's own, with eq. (28)'s arm-counted verdict beside it ([`passivity_with`]).
pub fn passivity_answer_for(
    sys: &System,
    normalized: bool,
    w: Wall,
    device: Option<DeviceDamping>,
) -> Result<(PassivityAnswer, Passivity)> {
    let lp = sys.lp();
    let sw = SampledWall::new(lp)?;
    let p = match device {
        Some(d) => passivity_of_device(&sw, w, d),
        None => passivity_with(&sw, lp, w),
    };
    let stable = sys.decide(sys.wall_units(w)?).verdict == Verdict::Stable;
    let (device_damping, note, region) = match &p.device {
        DeviceDamping::Known { damping } => {
            let r = passive_region(&sw, *damping)?;
            (Some(*damping), None, Some(PassiveRegionOut::from(&r)))
        }
        DeviceDamping::NotApplicable { reason } => (None, Some(reason.clone()), None),
    };
    let answer = PassivityAnswer {
        input: LoopInput::new(lp, normalized, Some(p.wall)),
        b_required: p.requirement.b_required,
        binding_frequency_hz: p.requirement.frequency_hz,
        binding_theta: p.requirement.theta,
        dc_stiffness: p.dc_stiffness,
        device_damping,
        effective_damping: p.with_arm.map(|a| a.damping),
        effective_verdict: p.with_arm.map(|a| a.verdict),
        meets: p.verdict.meets(),
        verdict: p.verdict,
        note,
        stable,
        passive_region: region,
    };
    Ok((answer, p))
}
