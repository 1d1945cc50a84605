//! The robustly stable region over a γ-interval at fixed δ and d (Section VIII, Figs. 8–10):
//! its slices, the polygon through their ends and its area. The method is in the
//! documentation of [`crate::paper::nyquist`].

use rayon::prelude::*;
use serde::Serialize;

use super::search::bisect_pred;
use super::slice::{Config, Slice, refined_slice, robust_at, unit_configs};
use super::{DEGENERATE_OFFSET, Progress, Ticker, beta_bound, no_progress, unit_circle_pole};
use crate::boundary::WallPoint;
use crate::error::{Error, Result, non_negative};
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::check_delay;

/// A slice of a robust region at one β: the robust α-interval (lo, hi).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RobustSlice {
    /// β.
    pub beta: f64,
    /// Lower end of the robust α-interval.
    pub lo: f64,
    /// Upper end of the robust α-interval.
    pub hi: f64,
    /// γ that sets the lower end.
    pub gamma_at_lo: f64,
    /// γ that sets the upper end.
    pub gamma_at_hi: f64,
}

/// Options of the robust-region computation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RobustOptions {
    /// Uniform γ samples over the interval, endpoints included (≥ 2).
    pub gamma_samples: usize,
    /// Initial uniform β samples over (−B, B) (≥ 8).
    pub beta_samples: usize,
    /// Refine the interval ends in γ by golden-section search around the worst sample.
    pub refine_gamma: bool,
    /// Rounds of adaptive β refinement of the polygon.
    pub refine_beta_rounds: usize,
}

impl Default for RobustOptions {
    fn default() -> Self {
        Self {
            gamma_samples: 41,
            beta_samples: 121,
            refine_gamma: true,
            refine_beta_rounds: 3,
        }
    }
}

/// The robustly stable region over γ ∈ [γ_lo, γ_hi] for fixed δ and d (Section VIII, Figs.
/// 8–10): the intersection of the stable regions of every γ in the interval.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobustRegion {
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Lower end of the γ interval.
    pub gamma_lo: f64,
    /// Upper end of the γ interval.
    pub gamma_hi: f64,
    /// γ samples at which every (α, β) is limit stable (δ = 0, γ = (jπ)²); there the stable
    /// region of the limit from inside the interval (γ·(1 ∓ [`DEGENERATE_OFFSET`])) is used.
    pub degenerate_gammas: Vec<f64>,
    /// Non-empty slices, ascending in β.
    pub slices: Vec<RobustSlice>,
    /// Some slice had more than one robust α-interval (only the union's hull is not
    /// reported; the slices keep the widest interval).
    pub multiple_intervals: bool,
    /// The polygon through the slice ends: upper ends ascending in β, then lower ends
    /// descending (counter-clockwise with α as abscissa). Empty when the region is empty.
    pub polygon: Vec<WallPoint>,
    /// Area of the polygon (shoelace).
    pub area: f64,
    /// Largest robust α over the slices (NaN when empty).
    pub alpha_max: f64,
    /// β at `alpha_max`.
    pub beta_at_alpha_max: f64,
    /// No robustly stable point found.
    pub empty: bool,
}

/// Shoelace area of a polygon (positive for counter-clockwise).
pub fn polygon_area(v: &[WallPoint]) -> f64 {
    let n = v.len();
    if n < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for i in 0..n {
        let (p, q) = (v[i], v[(i + 1) % n]);
        s += p.a * q.b - q.a * p.b;
    }
    0.5 * s
}

pub(super) fn gamma_samples(lo: f64, hi: f64, n: usize, delta: f64) -> (Vec<f64>, Vec<f64>) {
    let n = if hi > lo { n.max(2) } else { 1 };
    let mut degenerate = Vec::new();
    let mut gs = Vec::with_capacity(n);
    for i in 0..n {
        let mut g = crate::grid::evenly_spaced_at(lo, hi, n, i);
        let pp = PlantParams { gamma: g, delta };
        if unit_circle_pole(pp).is_some() {
            degenerate.push(g);
            // the limit from inside the interval
            g = if g > lo {
                g * (1.0 - DEGENERATE_OFFSET)
            } else {
                g * (1.0 + DEGENERATE_OFFSET)
            };
        }
        gs.push(g);
    }
    (gs, degenerate)
}

/// The paper's plants of Section VIII: every normalized stiffness γ ∈ [γ_lo, γ_hi] at one
/// normalized damping δ and delay d (the arm's stiffness unknown within a range).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GammaRange {
    /// Normalized damping δ = bT/m.
    pub delta: f64,
    /// Delay in samples.
    pub d: usize,
    /// Lowest normalized stiffness γ = kT²/m.
    pub gamma_lo: f64,
    /// Highest normalized stiffness.
    pub gamma_hi: f64,
}

impl GammaRange {
    /// Checks δ ≥ 0, 0 ≤ γ_lo ≤ γ_hi and the delay.
    fn check(&self) -> Result<()> {
        non_negative(Param::Delta, self.delta)?;
        non_negative(Param::GammaLo, self.gamma_lo)?;
        non_negative(Param::GammaHi, self.gamma_hi)?;
        check_delay(self.d)?;
        if self.gamma_hi < self.gamma_lo {
            return Err(Error::OutOfRange {
                param: Param::GammaHi,
                value: self.gamma_hi,
                range: "[gamma_lo, inf)",
            });
        }
        Ok(())
    }
}

/// The robustly stable region over the range's γ ∈ [γ_lo, γ_hi] at its δ and d
/// (Section VIII). See the module documentation for the method.
pub fn robust_region(range: GammaRange, opts: RobustOptions) -> Result<RobustRegion> {
    robust_region_with_progress(range, opts, &no_progress)
}

/// [`robust_region`] reporting each finished slice of the initial β grid
/// (`opts.beta_samples`, at least 8, in all) to `progress`; the refinement rounds after it
/// take about as long again.
pub fn robust_region_with_progress(
    range: GammaRange,
    opts: RobustOptions,
    progress: Progress,
) -> Result<RobustRegion> {
    range.check()?;
    let (delta, d) = (range.delta, range.d);
    let (gamma_lo, gamma_hi) = (range.gamma_lo, range.gamma_hi);
    let (gs, degenerate_gammas) = gamma_samples(gamma_lo, gamma_hi, opts.gamma_samples, delta);
    let configs = unit_configs(&gs, delta, d)?;
    let bb = configs
        .iter()
        .map(|c| beta_bound(&c.fam))
        .fold(f64::INFINITY, f64::min);
    if !bb.is_finite() {
        return Err(Error::Numerical("no bound on beta (n0 = 0)".into()));
    }
    let ng = gs.len();
    let neighbours = |j: usize| {
        let a = if j > 0 { gs[j - 1] } else { gs[j] };
        let b = if j + 1 < ng { gs[j + 1] } else { gs[j] };
        (a, b)
    };
    let make = |_: usize, g: f64| {
        let pp = PlantParams {
            gamma: g.max(0.0),
            delta,
        };
        Config {
            scale: 1.0,
            table: None,
            fam: NormalizedFamily::new(pp, d).unwrap_or_else(|_| configs[0].fam.clone()),
        }
    };
    let slice = |b: f64| refined_slice(&configs, &gs, &neighbours, &make, b, opts.refine_gamma);
    let n = opts.beta_samples.max(8);
    let h = 2.0 * bb / n as f64;
    let mut betas: Vec<f64> = (0..n).map(|i| -bb + (i as f64 + 0.5) * h).collect();
    let ticker = Ticker::new(progress);
    let mut res: Vec<Option<Slice>> = betas
        .par_iter()
        .map(|&b| {
            let s = slice(b);
            ticker.tick();
            s
        })
        .collect();
    // extents by bisection between empty and non-empty neighbours
    let nonempty = |b: f64| robust_at(&configs, b).0.iter().any(|iv| iv.lo < iv.hi);
    let extra = extent_betas(&betas, &res, bb, nonempty);
    refine_bends(&mut betas, &mut res, opts.refine_beta_rounds, &slice);
    for b in extra {
        if let Some(s) = slice(b) {
            betas.push(b);
            res.push(Some(s));
        }
    }
    let multiple_intervals = res.iter().flatten().any(|s| s.several);
    let mut slices: Vec<RobustSlice> = betas
        .iter()
        .zip(&res)
        .filter_map(|(&beta, s)| {
            s.map(|s| RobustSlice {
                beta,
                lo: s.interval.lo,
                hi: s.interval.hi,
                gamma_at_lo: s.coord_lo,
                gamma_at_hi: s.coord_hi,
            })
        })
        .collect();
    slices.sort_by(|a, b| a.beta.total_cmp(&b.beta));
    Ok(region_of_slices(
        (delta, d, gamma_lo, gamma_hi),
        degenerate_gammas,
        slices,
        multiple_intervals,
    ))
}

/// The β where the region's extent ends, by bisection between every empty and nonempty pair
/// of neighbouring samples, and at ±B beyond a nonempty end sample (|β| = B is unstable for
/// the plant that sets B).
fn extent_betas(
    betas: &[f64],
    res: &[Option<Slice>],
    bb: f64,
    nonempty: impl Fn(f64) -> bool,
) -> Vec<f64> {
    let n = betas.len();
    let mut extra: Vec<f64> = Vec::new();
    for i in 0..n.saturating_sub(1) {
        match (res[i].is_some(), res[i + 1].is_some()) {
            (false, true) => extra.push(bisect_pred(betas[i], betas[i + 1], &nonempty)),
            (true, false) => extra.push(bisect_pred(betas[i + 1], betas[i], &nonempty)),
            _ => {}
        }
    }
    if res[0].is_some() {
        extra.push(bisect_pred(-bb, betas[0], &nonempty));
    }
    if res[n - 1].is_some() {
        extra.push(bisect_pred(bb, betas[n - 1], &nonempty));
    }
    extra
}

/// Adaptive refinement where the slice ends bend: up to `rounds` times, a slice at the
/// midpoint of every pair of nonempty neighbours, stopping when no midpoint's ends leave the
/// chord by more than 1e-6 of the region's scale; `betas` and `res` stay sorted by β.
fn refine_bends(
    betas: &mut Vec<f64>,
    res: &mut Vec<Option<Slice>>,
    rounds: usize,
    slice: &(impl Fn(f64) -> Option<Slice> + Sync),
) {
    let scale = res
        .iter()
        .flatten()
        .map(|s| s.interval.hi.abs().max(s.interval.lo.abs()))
        .fold(1e-12_f64, f64::max);
    for _ in 0..rounds {
        let mut mids = Vec::new();
        for i in 0..betas.len().saturating_sub(1) {
            if let (Some(a), Some(b)) = (&res[i], &res[i + 1]) {
                let m = 0.5 * (betas[i] + betas[i + 1]);
                mids.push((m, a.interval, b.interval));
            }
        }
        let checks: Vec<(f64, Option<Slice>, bool)> = mids
            .par_iter()
            .map(|&(m, a, b)| {
                let s = slice(m);
                let bend = match &s {
                    Some(x) => {
                        (x.interval.hi - 0.5 * (a.hi + b.hi)).abs() > 1e-6 * scale
                            || (x.interval.lo - 0.5 * (a.lo + b.lo)).abs() > 1e-6 * scale
                    }
                    None => true,
                };
                (m, s, bend)
            })
            .collect();
        let mut any = false;
        for (m, s, bend) in checks {
            betas.push(m);
            res.push(s);
            any |= bend;
        }
        let mut order: Vec<usize> = (0..betas.len()).collect();
        order.sort_by(|&a, &b| betas[a].total_cmp(&betas[b]));
        *betas = order.iter().map(|&i| betas[i]).collect();
        *res = order.iter().map(|&i| res[i]).collect();
        if !any {
            break;
        }
    }
}

/// The robust region from its slices sorted by β: the polygon through their upper ends and
/// back through their lower ends, its area, and α_max with the β where it is reached.
fn region_of_slices(
    (delta, d, gamma_lo, gamma_hi): (f64, usize, f64, f64),
    degenerate_gammas: Vec<f64>,
    slices: Vec<RobustSlice>,
    multiple_intervals: bool,
) -> RobustRegion {
    let mut polygon: Vec<WallPoint> = slices
        .iter()
        .map(|s| WallPoint { a: s.hi, b: s.beta })
        .collect();
    polygon.extend(
        slices
            .iter()
            .rev()
            .map(|s| WallPoint { a: s.lo, b: s.beta }),
    );
    let area = if polygon.len() >= 3 {
        polygon_area(&polygon)
    } else {
        0.0
    };
    let best = slices.iter().max_by(|a, b| a.hi.total_cmp(&b.hi));
    RobustRegion {
        delta,
        d,
        gamma_lo,
        gamma_hi,
        degenerate_gammas,
        empty: slices.is_empty(),
        alpha_max: best.map_or(f64::NAN, |s| s.hi),
        beta_at_alpha_max: best.map_or(f64::NAN, |s| s.beta),
        slices,
        multiple_intervals,
        polygon,
        area,
    }
}
