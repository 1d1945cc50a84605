//! The stable region of one (γ, δ, d) summarized from exact α-intervals on a β grid
//! (Section V, VIII, Figs. 8–10), and its sweep over γ up to the Nyquist frequency.

use rayon::prelude::*;
use serde::Serialize;

use super::search::{bisect_pred, golden_max};
use super::{Progress, no_progress, nyquist_gamma, unit_circle_pole};
use crate::boundary::{Interval, stable_stiffness_intervals};
use crate::error::{Error, Result, non_negative};
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::check_delay;

/// A bound B such that no (α, β) with |β| ≥ B is stable: |p(0)| = |n0 β| < 1 is necessary
/// (the product of the roots). Infinite when n0 = 0.
pub fn beta_bound(fam: &NormalizedFamily) -> f64 {
    let n0 = fam.numerator_constant().abs();
    if n0 > 0.0 { 1.0 / n0 } else { f64::INFINITY }
}

/// Summary of the stable region of one (γ, δ, d), from exact α-intervals on a β grid
/// (Section V/VIII, Figs. 8–10).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RegionSummary {
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Every p(z) has a root on the unit circle (δ = 0, γ = (jπ)²): the region is limit
    /// stable at best and strictly empty.
    pub degenerate: bool,
    /// No stable point found.
    pub empty: bool,
    /// Smallest β with a stable point (bisection-refined; NaN when empty).
    pub beta_min: f64,
    /// Largest β with a stable point (NaN when empty).
    pub beta_max: f64,
    /// Smallest stable α over the grid (NaN when empty).
    pub alpha_min: f64,
    /// Largest stable α (golden-section refined; NaN when empty).
    pub alpha_max: f64,
    /// β at which `alpha_max` is reached.
    pub beta_at_alpha_max: f64,
    /// Area by the trapezoidal rule over the β grid.
    pub area: f64,
}

fn union_extent(ivs: &[Interval]) -> Option<(f64, f64, f64)> {
    if ivs.is_empty() {
        return None;
    }
    let lo = ivs.iter().map(|i| i.lo).fold(f64::INFINITY, f64::min);
    let hi = ivs.iter().map(|i| i.hi).fold(f64::NEG_INFINITY, f64::max);
    let len = ivs.iter().map(|i| i.hi - i.lo).sum();
    Some((lo, hi, len))
}

/// The stable region of one (γ, δ, d) summarized from exact α-intervals at `beta_samples`
/// values of β spread uniformly over (−B, B), B from [`beta_bound`] (Section V, VIII).
/// α_max is refined by golden-section search between the neighbours of the best sample and
/// the β extent by bisection; the area is the trapezoidal rule on the grid.
pub fn region_summary(pp: PlantParams, d: usize, beta_samples: usize) -> Result<RegionSummary> {
    let pp = PlantParams::new(pp.gamma, pp.delta)?;
    let fam = NormalizedFamily::new(pp, d)?;
    let n = beta_samples.max(8);
    let mut out = RegionSummary {
        gamma: pp.gamma,
        delta: pp.delta,
        d,
        degenerate: unit_circle_pole(pp).is_some(),
        empty: true,
        beta_min: f64::NAN,
        beta_max: f64::NAN,
        alpha_min: f64::NAN,
        alpha_max: f64::NAN,
        beta_at_alpha_max: f64::NAN,
        area: 0.0,
    };
    if out.degenerate {
        return Ok(out);
    }
    let bb = beta_bound(&fam);
    if !bb.is_finite() {
        return Err(Error::Numerical(
            "no bound on beta (n0 = 0): region summary undefined".into(),
        ));
    }
    let h = 2.0 * bb / n as f64;
    let betas: Vec<f64> = (0..n).map(|i| -bb + (i as f64 + 0.5) * h).collect();
    let slices: Vec<Option<(f64, f64, f64)>> = betas
        .par_iter()
        .map(|&b| union_extent(&stable_stiffness_intervals(&fam, b)))
        .collect();
    let nonempty = |b: f64| !stable_stiffness_intervals(&fam, b).is_empty();
    let hi_at = |b: f64| {
        union_extent(&stable_stiffness_intervals(&fam, b)).map_or(f64::NEG_INFINITY, |s| s.1)
    };
    let idx: Vec<usize> = (0..n).filter(|&i| slices[i].is_some()).collect();
    let (Some(&first), Some(&last)) = (idx.first(), idx.last()) else {
        return Ok(out);
    };
    out.empty = false;
    // |β| = B itself is unstable (|p(0)| = 1), so the bound closes the grid on both sides.
    let below = if first == 0 { -bb } else { betas[first - 1] };
    let above = if last + 1 == n { bb } else { betas[last + 1] };
    out.beta_min = bisect_pred(below, betas[first], nonempty);
    out.beta_max = bisect_pred(above, betas[last], nonempty);
    out.alpha_min = idx
        .iter()
        .map(|&i| slices[i].map_or(f64::NAN, |s| s.0))
        .fold(f64::INFINITY, f64::min);
    (out.alpha_max, out.beta_at_alpha_max) = alpha_peak(&betas, &slices, &idx, hi_at);
    out.area = trapezoid_area(
        &betas,
        &slices,
        h,
        (first, last),
        (out.beta_min, out.beta_max),
    );
    Ok(out)
}

/// The slices' exact (lowest α, highest α, total length) at each β sample, None where empty.
type Slices = [Option<(f64, f64, f64)>];

/// (α_max, β there) of the region: the best sample's highest α refined by golden-section
/// search between its neighbours (`hi_at`: the highest stable α at a β), kept only where it
/// improves on the sample; `idx` are the nonempty samples.
fn alpha_peak(
    betas: &[f64],
    slices: &Slices,
    idx: &[usize],
    hi_at: impl Fn(f64) -> f64,
) -> (f64, f64) {
    let n = betas.len();
    let hi = |i: usize| slices[i].map_or(f64::NEG_INFINITY, |s| s.1);
    let mut best = idx[0];
    for &i in idx {
        if hi(i) > hi(best) {
            best = i;
        }
    }
    let a = betas[best.saturating_sub(1)];
    let b = betas[(best + 1).min(n - 1)];
    let (bx, fx) = golden_max(a, b, hi_at);
    if fx >= hi(best) {
        (fx, bx)
    } else {
        (hi(best), betas[best])
    }
}

/// The region's area: the trapezoidal rule over the β grid of step h, with the ends closed
/// at the refined extent `(beta_min, beta_max)` (length 0 there) beyond the first and last
/// nonempty samples.
fn trapezoid_area(
    betas: &[f64],
    slices: &Slices,
    h: f64,
    (first, last): (usize, usize),
    (beta_min, beta_max): (f64, f64),
) -> f64 {
    let len = |i: usize| slices[i].map_or(0.0, |s| s.2);
    let mut area = 0.0;
    for i in 0..betas.len().saturating_sub(1) {
        area += 0.5 * (len(i) + len(i + 1)) * h;
    }
    area += 0.5 * len(first) * (betas[first] - beta_min).abs();
    area += 0.5 * len(last) * (beta_max - betas[last]).abs();
    area
}

/// The stable regions for γ = i/steps · F · γ_N, i = 0..=steps, with γ_N = π² + δ²/4
/// (Section VIII, Figs. 8–10).
pub fn gamma_sweep(
    delta: f64,
    d: usize,
    fraction: f64,
    steps: usize,
    beta_samples: usize,
) -> Result<Vec<RegionSummary>> {
    gamma_sweep_with_progress(delta, d, fraction, steps, beta_samples, &no_progress)
}

/// [`gamma_sweep`] reporting each finished region (steps + 1 in all) to `progress`.
pub fn gamma_sweep_with_progress(
    delta: f64,
    d: usize,
    fraction: f64,
    steps: usize,
    beta_samples: usize,
    progress: Progress,
) -> Result<Vec<RegionSummary>> {
    non_negative(Param::Delta, delta)?;
    non_negative(Param::GammaFraction, fraction)?;
    check_delay(d)?;
    if steps == 0 {
        return Err(Error::NotPositive {
            param: Param::Steps,
            value: 0.0,
        });
    }
    let gn = nyquist_gamma(delta) * fraction;
    (0..=steps)
        .map(|i| {
            let g = gn * i as f64 / steps as f64;
            let r = region_summary(PlantParams::new(g, delta)?, d, beta_samples);
            progress(i + 1);
            r
        })
        .collect()
}
