//! Section VIII as one analysis: the stable regions of the γ sweep up to a fraction of γ_N
//! (eq. 27, Figs. 8–10), the robustly stable region over γ ∈ [0, γ_hi], and Colgate's
//! passive region (eq. 28) checked against it — what `hapstab nyquist --json` reports and
//! Python's `nyquist_regions` returns.

use serde::Serialize;

use super::{
    GammaRange, PassiveCheck, Progress, RegionSummary, RobustOptions, RobustRegion,
    gamma_sweep_with_progress, nyquist_gamma, passive_inside_robust_with_progress, passive_region,
    robust_region_with_progress,
};
use crate::boundary::WallPoint;
use crate::error::Result;
use crate::limits::{Cost, gamma_sweep_cost, passive_check_cost, robust_region_cost};

/// β samples of the passivity check (Section VIII-A).
pub const PASSIVE_SAMPLES: usize = 41;

/// Below this |α_max| a swept region has no stable point with α > 0: its α_max comes out of
/// the golden-section search at round-off level (about 1e-16·γ for γ up to γ_N ≈ 10), far
/// below this bound, and is reported as 0.
pub const ALPHA_ROUNDOFF: f64 = 1e-12;

/// The inputs of the analysis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SweepInput {
    /// δ of Table I.
    pub delta: f64,
    /// The delay d in samples.
    pub d: usize,
    /// The sweep reaches γ = gamma_fraction·γ_N.
    pub gamma_fraction: f64,
    /// Number of γ steps of the sweep (steps + 1 regions).
    pub steps: usize,
    /// β samples per stable region of the sweep.
    pub beta_samples: usize,
    /// γ samples of the robust region (at least 2 are used).
    pub gamma_samples: usize,
}

impl SweepInput {
    /// The steps of the three stages as progress counts them: the sweep's regions, the
    /// robust region's β slices, the passivity check's slices.
    pub fn stages(&self) -> [usize; 3] {
        [
            self.steps + 1,
            self.robust_options().beta_samples.max(8),
            PASSIVE_SAMPLES,
        ]
    }

    /// The estimated cost of the sweep, the robust region and the passivity check
    /// ([`crate::limits`]).
    pub fn cost(&self) -> Cost {
        let opts = self.robust_options();
        let sweep = gamma_sweep_cost(self.steps, self.beta_samples, self.d);
        let robust = robust_region_cost(
            opts.gamma_samples,
            opts.beta_samples,
            self.d,
            opts.refine_gamma,
            opts.refine_beta_rounds,
        );
        let passive = if self.delta > 0.0 {
            passive_check_cost(PASSIVE_SAMPLES, opts.gamma_samples, self.d)
        } else {
            Cost::ZERO
        };
        sweep.then(robust).then(passive)
    }

    /// The robust region's options: the given γ samples (at least 2), the rest default.
    pub fn robust_options(&self) -> RobustOptions {
        RobustOptions {
            gamma_samples: self.gamma_samples.max(2),
            ..Default::default()
        }
    }
}

/// One region of the γ sweep (α_max of 0 when every stable point has α ≤ 0, to round-off).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SweepRow {
    /// γ of the region.
    pub gamma: f64,
    /// A pole of the plant on the unit circle (no region).
    pub degenerate: bool,
    /// No stable wall.
    pub empty: bool,
    /// The region's β extent, low end.
    pub beta_min: f64,
    /// The region's β extent, high end.
    pub beta_max: f64,
    /// The lowest stable α.
    pub alpha_min: f64,
    /// The highest stable α (0 to round-off: [`ALPHA_ROUNDOFF`]).
    pub alpha_max: f64,
    /// Where α_max is reached; None when α_max is 0 to round-off (then reached along a
    /// boundary segment).
    pub beta_at_alpha_max: Option<f64>,
    /// The region's area in α·β.
    pub area: f64,
}

impl From<&RegionSummary> for SweepRow {
    fn from(s: &RegionSummary) -> Self {
        let roundoff = s.alpha_max.abs() <= ALPHA_ROUNDOFF;
        SweepRow {
            gamma: s.gamma,
            degenerate: s.degenerate,
            empty: s.empty,
            beta_min: s.beta_min,
            beta_max: s.beta_max,
            alpha_min: s.alpha_min,
            alpha_max: if roundoff { 0.0 } else { s.alpha_max },
            beta_at_alpha_max: (!roundoff).then_some(s.beta_at_alpha_max),
            area: s.area,
        }
    }
}

/// The robustly stable region over γ ∈ [gamma_lo, gamma_hi].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustOut {
    /// Low end of the γ range (0).
    pub gamma_lo: f64,
    /// High end: gamma_fraction·γ_N.
    pub gamma_hi: f64,
    /// No wall is stable for every γ of the range.
    pub empty: bool,
    /// The highest robustly stable α.
    pub alpha_max: f64,
    /// Where it is reached.
    pub beta_at_alpha_max: f64,
    /// Area in α·β.
    pub area: f64,
    /// The sampled γ with a pole on the unit circle (their limit from inside is used).
    pub degenerate_gammas: Vec<f64>,
    /// Some slice had more than one stable interval.
    pub multiple_intervals: bool,
    /// Counter-clockwise vertices [alpha, beta].
    pub polygon: Vec<[f64; 2]>,
}

/// Colgate's passive region of eq. (28) and whether it lies in the robust region.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassiveOut {
    /// Vertices [alpha, beta].
    pub vertices: Vec<[f64; 2]>,
    /// Area in α·β.
    pub area: f64,
    /// Eq. (28) is Colgate's condition for d = 0.
    pub applies: bool,
    /// The check against the robust region.
    pub check: PassiveCheck,
}

/// Section VIII's answer for one (δ, d).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NyquistRegions {
    /// The inputs.
    pub input: SweepInput,
    /// γ_N = π² + δ²/4 (eq. 27).
    pub gamma_nyquist: f64,
    /// The regions of the γ sweep, in increasing γ.
    pub sweep: Vec<SweepRow>,
    /// The robust region over [0, gamma_fraction·γ_N].
    pub robust: RobustOut,
    /// The passive region at δ > 0 (None at δ = 0, where it is empty).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub passive: Option<PassiveOut>,
}

/// Vertices as [alpha, beta] pairs, as every command writes polygons.
fn pairs(v: &[WallPoint]) -> Vec<[f64; 2]> {
    v.iter().map(|p| [p.a, p.b]).collect()
}

/// Section VIII for the input (module doc): the sweep ([`gamma_sweep_with_progress`]), the
/// robust region ([`robust_region_with_progress`]) and at δ > 0 the passive region with its
/// check ([`passive_inside_robust_with_progress`]). `progress` counts the steps of the three
/// stages in a row ([`SweepInput::stages`]).
pub fn nyquist_regions(input: SweepInput, progress: Progress) -> Result<NyquistRegions> {
    let (delta, d) = (input.delta, input.d);
    let opts = input.robust_options();
    let [s0, s1, _] = input.stages();
    let gn = nyquist_gamma(delta);
    let g_hi = gn * input.gamma_fraction;
    let stage = |offset: usize| move |done: usize| progress(offset + done);
    let sweep = gamma_sweep_with_progress(
        delta,
        d,
        input.gamma_fraction,
        input.steps,
        input.beta_samples,
        &stage(0),
    )?;
    let range = GammaRange {
        delta,
        d,
        gamma_lo: 0.0,
        gamma_hi: g_hi,
    };
    let r = robust_region_with_progress(range, opts, &stage(s0))?;
    let passive = if delta > 0.0 {
        let p = passive_region(delta)?;
        let check =
            passive_inside_robust_with_progress(range, PASSIVE_SAMPLES, opts, &stage(s0 + s1))?;
        Some(PassiveOut {
            area: p.area(),
            vertices: pairs(&p.vertices),
            applies: d == 0,
            check,
        })
    } else {
        None
    };
    Ok(NyquistRegions {
        input,
        gamma_nyquist: gn,
        sweep: sweep.iter().map(SweepRow::from).collect(),
        robust: robust_out(r, g_hi),
        passive,
    })
}

/// The robust region over γ ∈ [0, g_hi] as it is reported.
fn robust_out(r: RobustRegion, g_hi: f64) -> RobustOut {
    RobustOut {
        gamma_lo: 0.0,
        gamma_hi: g_hi,
        empty: r.empty,
        alpha_max: r.alpha_max,
        beta_at_alpha_max: r.beta_at_alpha_max,
        area: r.area,
        degenerate_gammas: r.degenerate_gammas,
        multiple_intervals: r.multiple_intervals,
        polygon: pairs(&r.polygon),
    }
}
