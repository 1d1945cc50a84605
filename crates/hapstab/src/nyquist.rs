//! Nyquist frequency, robust stability and passivity (Section VIII, eq. 25–28, Figs. 8–10,
//! Remark 4), and a robust design across a range of human arms (beyond the paper).
//!
//! A mass-spring-damper oscillates at ω = √(k/m − b²/(4m²)) (eq. 25; the paper prints the
//! second term as b²/4m, which is not dimensionally consistent; eq. 26 is the consistent
//! form), i.e. ω = √(γ − δ²/4)/T (eq. 26), and reaches the Nyquist frequency π/T at
//! γ_N = π² + δ²/4 (eq. 27).
//!
//! # Robustly stable regions
//!
//! The robustly stable region over a γ-interval is the intersection of the stable regions
//! for every γ in it. It is computed slice by slice in β: at fixed β the stable α-set of each
//! γ is a union of intervals, exact by D-decomposition
//! ([`crate::boundary::stable_alpha_intervals`]); the robust α-set is their intersection. The
//! γ-interval is sampled uniformly (endpoints included) and, when the intersection is one
//! interval, its ends are refined by a golden-section search in γ between the neighbours of
//! the worst sample (the ends of the stable interval are smooth in γ between the points where
//! a different boundary piece takes over). The robust set is thus approached from outside; the
//! tests compare it with a four times denser γ grid. The region polygon is built from the
//! slice ends on a β grid that is refined where the ends bend (vertices are exact boundary
//! points, edges are chords) and whose extreme β are located by bisection. No polygon
//! boolean library is needed, and every number stays an exact per-β computation.
//!
//! # Degenerate plants
//!
//! For δ = 0 and γ = (jπ)², j = 1, 2, …, the plant's poles and a zero of N(z) meet on the unit
//! circle (at z = −1 for odd j, z = 1 for even j) and p(z) keeps that root for every (α, β):
//! every point is at best limit stable (Section VIII-B, last paragraph). There the strict
//! stable region is empty; [`region_summary`] reports `degenerate`, and the robust region
//! takes the limit from inside the γ-interval instead (reported in `degenerate_gammas`).

use rayon::prelude::*;
use serde::Serialize;

use crate::boundary::{
    AlphaBeta, CircleTable, Interval, stable_alpha_intervals, stable_alpha_intervals_tabulated,
};
use crate::closed_loop::PolyFamily;
use crate::error::{Error, Result, finite, non_negative, positive};
use crate::params::{PlantParams, check_delay};
use std::sync::OnceLock;

use std::f64::consts::PI;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A progress callback of a long analysis: called, possibly from worker threads, with the
/// number of its steps done so far (each function documents what a step is).
pub type Progress<'a> = &'a (dyn Fn(usize) + Sync);

/// A progress callback that does nothing.
pub fn no_progress(_: usize) {}

/// Counts finished steps across threads and reports each new count.
struct Ticker<'a> {
    done: AtomicUsize,
    progress: Progress<'a>,
}

impl<'a> Ticker<'a> {
    fn new(progress: Progress<'a>) -> Self {
        Self {
            done: AtomicUsize::new(0),
            progress,
        }
    }

    fn tick(&self) {
        (self.progress)(self.done.fetch_add(1, Ordering::Relaxed) + 1);
    }
}

/// Oscillation frequency of eq. (25) in rad/s, ω = √(k/m − b²/(4m²)), for k/m > b²/(4m²)
/// (under-damped); None otherwise.
pub fn oscillation_frequency(mass: f64, damping: f64, stiffness: f64) -> Option<f64> {
    let w2 = stiffness / mass - damping * damping / (4.0 * mass * mass);
    (w2 > 0.0 && w2.is_finite()).then(|| w2.sqrt())
}

/// Oscillation frequency of eq. (26) in rad/s from normalized parameters:
/// ω = √(γ − δ²/4)/T for γ > δ²/4; None otherwise.
pub fn normalized_frequency(gamma: f64, delta: f64, period: f64) -> Option<f64> {
    let w2 = gamma - delta * delta / 4.0;
    (w2 > 0.0 && w2.is_finite() && period > 0.0).then(|| w2.sqrt() / period)
}

/// The γ at which the plant oscillates at the Nyquist frequency π/T, eq. (27):
/// γ_N = π² + δ²/4.
pub fn nyquist_gamma(delta: f64) -> f64 {
    PI * PI + delta * delta / 4.0
}

/// Remark 4: the physical stiffness that brings a device to the Nyquist frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NyquistStiffness {
    /// Mass m in kg.
    pub mass: f64,
    /// Damping b in Ns/m.
    pub damping: f64,
    /// Sampling period T in s.
    pub period: f64,
    /// k = π² m/T² + b²/(4m) in N/m.
    pub stiffness: f64,
    /// δ = bT/m.
    pub delta: f64,
    /// γ_N = π² + δ²/4 (eq. 27).
    pub gamma: f64,
    /// The Nyquist frequency π/T in rad/s.
    pub nyquist_frequency: f64,
}

/// Remark 4: k = π² m/T² + b²/(4m), the stiffness at which a mass m with damping b sampled at
/// period T oscillates at the Nyquist frequency (≈ 987.0 kN/m for m = 0.1 kg, T = 1 ms,
/// b = 1.5 Ns/m).
pub fn nyquist_stiffness(mass: f64, damping: f64, period: f64) -> Result<NyquistStiffness> {
    positive("mass m", mass)?;
    non_negative("damping b", damping)?;
    positive("sampling period T", period)?;
    let stiffness = PI * PI * mass / (period * period) + damping * damping / (4.0 * mass);
    finite("stiffness k", stiffness)?;
    let delta = damping * period / mass;
    Ok(NyquistStiffness {
        mass,
        damping,
        period,
        stiffness,
        delta,
        gamma: nyquist_gamma(delta),
        nyquist_frequency: PI / period,
    })
}

/// Relative distance of √γ from jπ (δ = 0) within which a plant counts as degenerate. Closer
/// than this the pole and the zero at z = ±1 cancel to fewer than about half the digits and
/// the D-decomposition loses its accuracy (at 1e-8 the computed regions are visibly wrong,
/// at 1e-6 they still agree with the limit triangle to 1e-5).
pub const DEGENERATE_TOL: f64 = 1e-7;

/// Relative offset from a degenerate γ at which [`robust_region`] takes the limit region.
pub const DEGENERATE_OFFSET: f64 = 1e-6;

/// If every p(z) of the family has a root on the unit circle whatever (α, β) — δ = 0 and
/// √γ = jπ within [`DEGENERATE_TOL`] relative — the angle of that root (π for odd j, 0 for
/// even j)
/// (Section VIII-B: a pole at z = −1 for γ = π², δ = 0).
pub fn unit_circle_pole(pp: PlantParams) -> Option<f64> {
    if pp.delta != 0.0 || pp.gamma <= 0.0 {
        return None;
    }
    let w = pp.gamma.sqrt();
    let j = (w / PI).round();
    if j >= 1.0 && (w - j * PI).abs() <= DEGENERATE_TOL * w {
        Some(if j % 2.0 == 1.0 { PI } else { 0.0 })
    } else {
        None
    }
}

/// Colgate's passive region, eq. (28): δ > α/2 + |β| with α ≥ 0 (d = 0), a triangle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassiveRegion {
    /// Normalized physical damping δ.
    pub delta: f64,
    /// Vertices (0, −δ), (2δ, 0), (0, δ): counter-clockwise with α as abscissa, first vertex
    /// not repeated.
    pub vertices: Vec<AlphaBeta>,
}

impl PassiveRegion {
    /// True iff the point satisfies eq. (28): α ≥ 0 and δ > α/2 + |β|.
    pub fn contains(&self, p: AlphaBeta) -> bool {
        p.alpha >= 0.0 && self.delta > p.alpha / 2.0 + p.beta.abs()
    }

    /// Area 2δ² of the triangle.
    pub fn area(&self) -> f64 {
        2.0 * self.delta * self.delta
    }

    /// The largest passive α at β: 2(δ − |β|) for |β| < δ, None otherwise.
    pub fn alpha_max_at(&self, beta: f64) -> Option<f64> {
        (beta.abs() < self.delta).then(|| 2.0 * (self.delta - beta.abs()))
    }
}

/// Colgate's passive region of eq. (28) as a polygon (Section VIII-A, Fig. 9).
pub fn passive_region(delta: f64) -> Result<PassiveRegion> {
    non_negative("delta", delta)?;
    let p = |alpha, beta| AlphaBeta { alpha, beta };
    Ok(PassiveRegion {
        delta,
        vertices: vec![p(0.0, -delta), p(2.0 * delta, 0.0), p(0.0, delta)],
    })
}

/// A bound B such that no (α, β) with |β| ≥ B is stable: |p(0)| = |n0 β| < 1 is necessary
/// (the product of the roots). Infinite when n0 = 0.
pub fn beta_bound(fam: &PolyFamily) -> f64 {
    let n0 = fam.plant.n0.abs();
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

/// Golden-section maximum of f on [a, b] to 1e-12 of the angle: (argmax, max).
fn golden_max(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    crate::extremum::golden_max(f, a, b, 1e-12 * (a.abs() + b.abs()).max(1e-300))
}

/// Bisection between `a` (pred false) and `b` (pred true) to 1e-12 relative; returns the
/// point on the true side.
fn bisect_pred(mut a: f64, mut b: f64, pred: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if m == a || m == b || (b - a).abs() <= 1e-12 * (a.abs() + b.abs()).max(1e-300) {
            break;
        }
        if pred(m) {
            b = m;
        } else {
            a = m;
        }
    }
    b
}

/// The stable region of one (γ, δ, d) summarized from exact α-intervals at `beta_samples`
/// values of β spread uniformly over (−B, B), B from [`beta_bound`] (Section V, VIII).
/// α_max is refined by golden-section search between the neighbours of the best sample and
/// the β extent by bisection; the area is the trapezoidal rule on the grid.
pub fn region_summary(pp: PlantParams, d: usize, beta_samples: usize) -> Result<RegionSummary> {
    let pp = PlantParams::new(pp.gamma, pp.delta)?;
    let fam = PolyFamily::new(pp, d)?;
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
        .map(|&b| union_extent(&stable_alpha_intervals(&fam, b)))
        .collect();
    let nonempty = |b: f64| !stable_alpha_intervals(&fam, b).is_empty();
    let hi_at =
        |b: f64| union_extent(&stable_alpha_intervals(&fam, b)).map_or(f64::NEG_INFINITY, |s| s.1);
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
    let mut best = first;
    let mut amin = f64::INFINITY;
    for &i in &idx {
        let (lo, hi, _) = slices[i].unwrap_or((f64::NAN, f64::NAN, 0.0));
        amin = amin.min(lo);
        if hi > slices[best].map_or(f64::NEG_INFINITY, |s| s.1) {
            best = i;
        }
    }
    let a = if best > 0 {
        betas[best - 1]
    } else {
        betas[best]
    };
    let b = if best + 1 < n {
        betas[best + 1]
    } else {
        betas[best]
    };
    let (bx, fx) = golden_max(a, b, hi_at);
    let sample_hi = slices[best].map_or(f64::NEG_INFINITY, |s| s.1);
    if fx >= sample_hi {
        out.alpha_max = fx;
        out.beta_at_alpha_max = bx;
    } else {
        out.alpha_max = sample_hi;
        out.beta_at_alpha_max = betas[best];
    }
    out.alpha_min = amin;
    // trapezoid over the grid, with the ends closed at the refined extent (length 0 there)
    let len = |i: usize| slices[i].map_or(0.0, |s| s.2);
    let mut area = 0.0;
    for w in betas.windows(2).enumerate() {
        let (i, _) = w;
        area += 0.5 * (len(i) + len(i + 1)) * h;
    }
    area += 0.5 * len(first) * (betas[first] - out.beta_min).abs();
    area += 0.5 * len(last) * (out.beta_max - betas[last]).abs();
    out.area = area;
    Ok(out)
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
    non_negative("delta", delta)?;
    non_negative("gamma fraction", fraction)?;
    check_delay(d)?;
    if steps == 0 {
        return Err(Error::NotPositive {
            name: "steps",
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

/// Intersection of two sorted lists of disjoint open intervals.
fn intersect(a: &[Interval], b: &[Interval]) -> Vec<Interval> {
    let mut out = Vec::new();
    for x in a {
        for y in b {
            let lo = x.lo.max(y.lo);
            let hi = x.hi.min(y.hi);
            if lo < hi {
                out.push(Interval { lo, hi });
            }
        }
    }
    out.sort_by(|p, q| p.lo.total_cmp(&q.lo));
    out
}

/// One plant configuration of a robust problem: the family and its mass relative to the
/// reference mass in which α and β are measured (1 for a fixed mass).
#[derive(Debug, Clone)]
struct Config {
    scale: f64,
    fam: PolyFamily,
    /// The family's crossing scan, computed on first use when the configuration is one of
    /// the samples that many β-slices cut (None for the single-use configurations of a
    /// golden-section refinement).
    table: Option<OnceLock<CircleTable>>,
}

/// One unscaled configuration per γ sample, at damping δ and delay d.
fn unit_configs(gammas: &[f64], delta: f64, d: usize) -> Result<Vec<Config>> {
    gammas
        .iter()
        .map(|&g| {
            Ok(Config {
                scale: 1.0,
                table: Some(OnceLock::new()),
                fam: PolyFamily::new(PlantParams::new(g, delta)?, d)?,
            })
        })
        .collect()
}

impl Config {
    /// Stable reference-α intervals at reference β: α_ref/s must lie in I(β_ref/s), so the
    /// set is s·I(β_ref/s).
    fn intervals(&self, beta_ref: f64) -> Vec<Interval> {
        let s = self.scale;
        let ivs = match &self.table {
            Some(t) => {
                let table = t.get_or_init(|| CircleTable::new(&self.fam));
                stable_alpha_intervals_tabulated(&self.fam, table, beta_ref / s)
            }
            None => stable_alpha_intervals(&self.fam, beta_ref / s),
        };
        ivs.into_iter()
            .map(|iv| Interval {
                lo: iv.lo * s,
                hi: iv.hi * s,
            })
            .collect()
    }
}

/// The robust α-set at one β for a sampled set of configurations, with the index of the
/// configuration that sets each end of a single-interval result.
fn robust_at(configs: &[Config], beta: f64) -> (Vec<Interval>, Option<(usize, usize)>) {
    let mut acc: Option<Vec<Interval>> = None;
    let mut single = true;
    let (mut arg_lo, mut arg_hi) = (0usize, 0usize);
    let (mut best_lo, mut best_hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for (j, c) in configs.iter().enumerate() {
        let ivs = c.intervals(beta);
        if ivs.len() != 1 {
            single = false;
        } else {
            if ivs[0].lo > best_lo {
                best_lo = ivs[0].lo;
                arg_lo = j;
            }
            if ivs[0].hi < best_hi {
                best_hi = ivs[0].hi;
                arg_hi = j;
            }
        }
        let next = match acc {
            None => ivs,
            Some(prev) => intersect(&prev, &ivs),
        };
        let empty = next.is_empty();
        acc = Some(next);
        if empty {
            return (Vec::new(), None);
        }
    }
    let res = acc.unwrap_or_default();
    let args = (single && res.len() == 1).then_some((arg_lo, arg_hi));
    (res, args)
}

/// Golden-section minimization of `f` on [a, b].
fn golden_min(a: f64, b: f64, f: impl Fn(f64) -> f64) -> (f64, f64) {
    let (x, v) = golden_max(a, b, |t| -f(t));
    (x, -v)
}

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
    pub polygon: Vec<AlphaBeta>,
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
pub fn polygon_area(v: &[AlphaBeta]) -> f64 {
    let n = v.len();
    if n < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for i in 0..n {
        let (p, q) = (v[i], v[(i + 1) % n]);
        s += p.alpha * q.beta - q.alpha * p.beta;
    }
    0.5 * s
}

fn gamma_samples(lo: f64, hi: f64, n: usize, delta: f64) -> (Vec<f64>, Vec<f64>) {
    let n = if hi > lo { n.max(2) } else { 1 };
    let mut degenerate = Vec::new();
    let mut gs = Vec::with_capacity(n);
    for i in 0..n {
        let mut g = if n == 1 {
            lo
        } else {
            lo + (hi - lo) * i as f64 / (n - 1) as f64
        };
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

/// Robust slice at β with optional golden refinement in the plant parameter that
/// `make(t)` maps to a configuration (t ∈ [lo, hi] of the refined coordinate).
fn refined_slice(
    configs: &[Config],
    coords: &[f64],
    neighbours: &(dyn Fn(usize) -> (f64, f64) + Sync),
    make: &(dyn Fn(usize, f64) -> Config + Sync),
    beta: f64,
    refine: bool,
) -> Option<Slice> {
    refined_slice_args(configs, coords, neighbours, make, beta, refine)
        .map(|(iv, tl, th, m, _)| (iv, tl, th, m))
}

/// A robust slice: the interval, the coordinates that set its ends, and whether the robust
/// set had several intervals.
type Slice = (Interval, f64, f64, bool);
type SliceArgs = (Interval, f64, f64, bool, Option<(usize, usize)>);

fn refined_slice_args(
    configs: &[Config],
    coords: &[f64],
    neighbours: &(dyn Fn(usize) -> (f64, f64) + Sync),
    make: &(dyn Fn(usize, f64) -> Config + Sync),
    beta: f64,
    refine: bool,
) -> Option<SliceArgs> {
    let (ivs, args) = robust_at(configs, beta);
    if ivs.is_empty() {
        return None;
    }
    let multiple = ivs.len() > 1;
    let widest = *ivs
        .iter()
        .max_by(|a, b| (a.hi - a.lo).total_cmp(&(b.hi - b.lo)))?;
    let Some((jl, jh)) = args.filter(|_| refine) else {
        let (tl, th) = args.map_or((f64::NAN, f64::NAN), |(l, h)| (coords[l], coords[h]));
        return Some((widest, tl, th, multiple, args));
    };
    let mid = 0.5 * (widest.lo + widest.hi);
    let pick = |c: &Config| -> Option<Interval> {
        c.intervals(beta)
            .into_iter()
            .find(|iv| iv.lo <= mid && mid <= iv.hi)
    };
    let (a, b) = neighbours(jh);
    let (th, hi) = golden_min(a, b, |t| {
        pick(&make(jh, t)).map_or(f64::NEG_INFINITY, |iv| iv.hi)
    });
    let (a, b) = neighbours(jl);
    let (tl, lo) = golden_max(a, b, |t| {
        pick(&make(jl, t)).map_or(f64::INFINITY, |iv| iv.lo)
    });
    let lo = lo.max(widest.lo);
    let hi = hi.min(widest.hi);
    let tl = if lo > widest.lo { tl } else { coords[jl] };
    let th = if hi < widest.hi { th } else { coords[jh] };
    if lo >= hi {
        return None;
    }
    Some((Interval { lo, hi }, tl, th, multiple, args))
}

/// The robustly stable region over γ ∈ [γ_lo, γ_hi] at fixed δ and d (Section VIII).
/// See the module documentation for the method.
pub fn robust_region(
    delta: f64,
    d: usize,
    gamma_lo: f64,
    gamma_hi: f64,
    opts: RobustOptions,
) -> Result<RobustRegion> {
    robust_region_with_progress(delta, d, gamma_lo, gamma_hi, opts, &no_progress)
}

/// [`robust_region`] reporting each finished slice of the initial β grid
/// (`opts.beta_samples`, at least 8, in all) to `progress`; the refinement rounds after it
/// take about as long again.
pub fn robust_region_with_progress(
    delta: f64,
    d: usize,
    gamma_lo: f64,
    gamma_hi: f64,
    opts: RobustOptions,
    progress: Progress,
) -> Result<RobustRegion> {
    non_negative("delta", delta)?;
    non_negative("gamma_lo", gamma_lo)?;
    non_negative("gamma_hi", gamma_hi)?;
    check_delay(d)?;
    if gamma_hi < gamma_lo {
        return Err(Error::OutOfRange {
            name: "gamma_hi",
            value: gamma_hi,
            range: "[gamma_lo, inf)",
        });
    }
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
            fam: PolyFamily::new(pp, d).unwrap_or_else(|_| configs[0].fam.clone()),
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
    let mut extra: Vec<f64> = Vec::new();
    for i in 0..betas.len().saturating_sub(1) {
        match (res[i].is_some(), res[i + 1].is_some()) {
            (false, true) => extra.push(bisect_pred(betas[i], betas[i + 1], nonempty)),
            (true, false) => extra.push(bisect_pred(betas[i + 1], betas[i], nonempty)),
            _ => {}
        }
    }
    // |β| = B is unstable for the plant that sets B: close the grid at ±B
    if res[0].is_some() {
        extra.push(bisect_pred(-bb, betas[0], nonempty));
    }
    if res[n - 1].is_some() {
        extra.push(bisect_pred(bb, betas[n - 1], nonempty));
    }
    // adaptive refinement where the slice ends bend
    let scale = res
        .iter()
        .flatten()
        .map(|s| s.0.hi.abs().max(s.0.lo.abs()))
        .fold(1e-12_f64, f64::max);
    for _ in 0..opts.refine_beta_rounds {
        let mut mids = Vec::new();
        for i in 0..betas.len().saturating_sub(1) {
            if let (Some(a), Some(b)) = (&res[i], &res[i + 1]) {
                let m = 0.5 * (betas[i] + betas[i + 1]);
                mids.push((m, a.0, b.0));
            }
        }
        let checks: Vec<(f64, Option<Slice>, bool)> = mids
            .par_iter()
            .map(|&(m, a, b)| {
                let s = slice(m);
                let bend = match &s {
                    Some(x) => {
                        (x.0.hi - 0.5 * (a.hi + b.hi)).abs() > 1e-6 * scale
                            || (x.0.lo - 0.5 * (a.lo + b.lo)).abs() > 1e-6 * scale
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
        betas = order.iter().map(|&i| betas[i]).collect();
        res = order.iter().map(|&i| res[i]).collect();
        if !any {
            break;
        }
    }
    for b in extra {
        if let Some(s) = slice(b) {
            betas.push(b);
            res.push(Some(s));
        }
    }
    let mut slices: Vec<RobustSlice> = betas
        .iter()
        .zip(&res)
        .filter_map(|(&beta, s)| {
            s.map(|(iv, tl, th, _)| RobustSlice {
                beta,
                lo: iv.lo,
                hi: iv.hi,
                gamma_at_lo: tl,
                gamma_at_hi: th,
            })
        })
        .collect();
    slices.sort_by(|a, b| a.beta.total_cmp(&b.beta));
    let multiple_intervals = res.iter().flatten().any(|s| s.3);
    let mut polygon: Vec<AlphaBeta> = slices
        .iter()
        .map(|s| AlphaBeta {
            alpha: s.hi,
            beta: s.beta,
        })
        .collect();
    polygon.extend(slices.iter().rev().map(|s| AlphaBeta {
        alpha: s.lo,
        beta: s.beta,
    }));
    let area = if polygon.len() >= 3 {
        polygon_area(&polygon)
    } else {
        0.0
    };
    let best = slices.iter().max_by(|a, b| a.hi.total_cmp(&b.hi));
    Ok(RobustRegion {
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
    })
}

/// How Colgate's passive region (28) sits in a robust region.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PassiveCheck {
    /// δ.
    pub delta: f64,
    /// Every checked slice of the closed passive triangle lies in the closure of the robust
    /// region (margins ≥ −1e-12).
    pub inside: bool,
    /// Smallest margin hi_robust − 2(δ − |β|) over the checked β.
    pub min_right_margin: f64,
    /// β of the smallest right margin.
    pub beta_at_min_right_margin: f64,
    /// Smallest margin 0 − lo_robust (0 when the robust region's left edge is α = 0, as for
    /// γ_lo = 0 where α = −γ = 0 is a boundary).
    pub min_left_margin: f64,
    /// Number of β checked.
    pub samples: usize,
}

/// Relative distance from the corners (0, ±δ) of the passive triangle at which
/// [`passive_inside_robust`] starts. At γ = 0 the corner (0, −δ) is limit stable (a double
/// root at z = 1 when α = 0 and β + δ = 0), and within 1e-6·δ of it the stable band, of
/// width about 2(β + δ), is thinner than what double precision resolves in the Schur–Cohn
/// test.
pub const PASSIVE_END_GAP: f64 = 1e-6;

/// Checks that the passive triangle of eq. (28) lies in the robust region over
/// [γ_lo, γ_hi] at d = `d`: at `samples` values of β across (−δ, δ) (ends at
/// ±δ(1 − [`PASSIVE_END_GAP`])) the robust α-interval must contain [0, 2(δ − |β|)]
/// (Section VIII-A, Fig. 9).
pub fn passive_inside_robust(
    delta: f64,
    d: usize,
    gamma_lo: f64,
    gamma_hi: f64,
    samples: usize,
    opts: RobustOptions,
) -> Result<PassiveCheck> {
    passive_inside_robust_with_progress(delta, d, gamma_lo, gamma_hi, samples, opts, &no_progress)
}

/// [`passive_inside_robust`] reporting each checked β (`samples`, at least 3, in all) to
/// `progress`.
pub fn passive_inside_robust_with_progress(
    delta: f64,
    d: usize,
    gamma_lo: f64,
    gamma_hi: f64,
    samples: usize,
    opts: RobustOptions,
    progress: Progress,
) -> Result<PassiveCheck> {
    positive("delta", delta)?;
    check_delay(d)?;
    let (gs, _) = gamma_samples(gamma_lo, gamma_hi, opts.gamma_samples, delta);
    let configs = unit_configs(&gs, delta, d)?;
    let ng = gs.len();
    let neighbours = |j: usize| {
        let a = if j > 0 { gs[j - 1] } else { gs[j] };
        let b = if j + 1 < ng { gs[j + 1] } else { gs[j] };
        (a, b)
    };
    let make = |_: usize, g: f64| Config {
        scale: 1.0,
        table: None,
        fam: PolyFamily::new(
            PlantParams {
                gamma: g.max(0.0),
                delta,
            },
            d,
        )
        .unwrap_or_else(|_| configs[0].fam.clone()),
    };
    let n = samples.max(3);
    let betas: Vec<f64> = (0..n)
        .map(|i| delta * (1.0 - PASSIVE_END_GAP) * (2.0 * i as f64 / (n - 1) as f64 - 1.0))
        .collect();
    let ticker = Ticker::new(progress);
    let margins: Vec<(f64, f64, f64)> = betas
        .par_iter()
        .map(|&b| {
            let need = 2.0 * (delta - b.abs());
            let m = match refined_slice(&configs, &gs, &neighbours, &make, b, opts.refine_gamma) {
                Some((iv, _, _, _)) => (b, iv.hi - need, -iv.lo),
                None => (b, f64::NEG_INFINITY, f64::NEG_INFINITY),
            };
            ticker.tick();
            m
        })
        .collect();
    let (mut mr, mut br, mut ml) = (f64::INFINITY, f64::NAN, f64::INFINITY);
    for (b, r, l) in margins {
        if r < mr {
            mr = r;
            br = b;
        }
        ml = ml.min(l);
    }
    Ok(PassiveCheck {
        delta,
        inside: mr >= -1e-12 && ml >= -1e-12,
        min_right_margin: mr,
        beta_at_min_right_margin: br,
        min_left_margin: ml,
        samples: n,
    })
}

/// A box of plants in physical units for robust design (beyond the paper): every mass,
/// damping and stiffness in the given closed ranges, sampled at period T with delay d.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PlantBox {
    /// [m_min, m_max] in kg (m_min > 0).
    pub mass: [f64; 2],
    /// [b_min, b_max] in Ns/m.
    pub damping: [f64; 2],
    /// [k_min, k_max] in N/m.
    pub stiffness: [f64; 2],
    /// Sampling period T in s.
    pub period: f64,
    /// Delay d in samples.
    pub d: usize,
}

impl PlantBox {
    /// A box in normalized parameters: γ ∈ [γ_lo, γ_hi], δ ∈ [δ_lo, δ_hi] (m = T = 1, so
    /// K = α and B = β).
    pub fn normalized(gamma: [f64; 2], delta: [f64; 2], d: usize) -> Result<Self> {
        Self {
            mass: [1.0, 1.0],
            damping: delta,
            stiffness: gamma,
            period: 1.0,
            d,
        }
        .validated()
    }

    /// From an ungrabbed device (m_L, b_L, k = 0) to a device held by an arm with up to
    /// (m_H, b_H, k_H): mass ∈ [m_L, m_L + m_H], damping ∈ [b_L, b_L + b_H], stiffness ∈
    /// [0, k_H]. The box also holds combinations no single arm produces (e.g. k_H on the bare
    /// device mass), which makes the result conservative.
    pub fn ungrabbed_to_grabbed(
        device: crate::params::Device,
        arm: crate::params::Arm,
        period: f64,
        d: usize,
    ) -> Result<Self> {
        Self {
            mass: [device.mass, device.mass + arm.mass],
            damping: [device.damping, device.damping + arm.damping],
            stiffness: [0.0, arm.stiffness],
            period,
            d,
        }
        .validated()
    }

    /// Validates the ranges: finite, lo ≤ hi, masses > 0, damping and stiffness ≥ 0, T > 0.
    pub fn validated(self) -> Result<Self> {
        positive("minimum mass", self.mass[0])?;
        positive("maximum mass", self.mass[1])?;
        non_negative("minimum damping", self.damping[0])?;
        non_negative("maximum damping", self.damping[1])?;
        non_negative("minimum stiffness", self.stiffness[0])?;
        non_negative("maximum stiffness", self.stiffness[1])?;
        positive("sampling period T", self.period)?;
        check_delay(self.d)?;
        for (name, r) in [
            ("mass range", self.mass),
            ("damping range", self.damping),
            ("stiffness range", self.stiffness),
        ] {
            if r[1] < r[0] {
                return Err(Error::OutOfRange {
                    name,
                    value: r[1],
                    range: "an upper end >= the lower end",
                });
            }
        }
        Ok(self)
    }
}

/// Options of the robust K_max search.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BoxOptions {
    /// Samples of the mass range (ends included).
    pub mass_samples: usize,
    /// Samples of the damping range (ends included).
    pub damping_samples: usize,
    /// Samples of the stiffness range (ends included); refined by golden section.
    pub stiffness_samples: usize,
    /// Uniform β samples before the golden-section refinement of the optimum.
    pub beta_samples: usize,
}

impl Default for BoxOptions {
    fn default() -> Self {
        Self {
            mass_samples: 5,
            damping_samples: 3,
            stiffness_samples: 33,
            beta_samples: 97,
        }
    }
}

/// The largest virtual stiffness stable for every plant of a box, and the damping that
/// reaches it (robust design beyond the paper).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RobustKmax {
    /// The box.
    pub plant_box: PlantBox,
    /// Largest K (N/m; α for a normalized box) stable for every plant sampled in the box.
    pub stiffness_max: f64,
    /// The virtual damping B (Ns/m; β for a normalized box) at which it is reached.
    pub damping_at_max: f64,
    /// Lower end of the robust K interval at that B (−k_min-like bound).
    pub stiffness_min: f64,
    /// The plant (m, b, k) that limits K at the optimum.
    pub worst_plant: [f64; 3],
    /// α_max and β there measured in the minimum mass of the box: K T²/m_min, B T/m_min.
    pub normalized_at_min_mass: AlphaBeta,
    /// Number of plants sampled (before refinement).
    pub plants_sampled: usize,
}

fn linspace(r: [f64; 2], n: usize) -> Vec<f64> {
    if r[1] <= r[0] || n <= 1 {
        return vec![r[0]];
    }
    (0..n)
        .map(|i| r[0] + (r[1] - r[0]) * i as f64 / (n - 1) as f64)
        .collect()
}

/// The robust K-interval at virtual damping B over every plant sampled in the box, with the
/// end refined over the stiffness range at the worst (mass, damping) sample (robust design
/// beyond the paper). Returns (lo, hi, worst plant) or None when no K is stable for all.
pub fn robust_stiffness_interval(
    pb: &PlantBox,
    damping: f64,
    opts: BoxOptions,
) -> Result<Option<(f64, f64, [f64; 3])>> {
    finite("virtual damping B", damping)?;
    let pb = pb.validated()?;
    let (configs, coords) = box_configs(&pb, opts)?;
    Ok(box_slice(&pb, &configs, &coords, opts, damping, true))
}

type BoxCoords = Vec<[f64; 3]>;

fn box_configs(pb: &PlantBox, opts: BoxOptions) -> Result<(Vec<Config>, BoxCoords)> {
    let t = pb.period;
    let m_ref = pb.mass[0];
    let mut configs = Vec::new();
    let mut coords = Vec::new();
    for &m in &linspace(pb.mass, opts.mass_samples) {
        for &b in &linspace(pb.damping, opts.damping_samples) {
            for &k in &linspace(pb.stiffness, opts.stiffness_samples) {
                let pp = PlantParams::new(k * t * t / m, b * t / m)?;
                configs.push(Config {
                    scale: m / m_ref,
                    table: Some(OnceLock::new()),
                    fam: PolyFamily::new(pp, pb.d)?,
                });
                coords.push([m, b, k]);
            }
        }
    }
    Ok((configs, coords))
}

/// Robust K interval (N/m) at physical B for the sampled configurations, refined in k.
fn box_slice(
    pb: &PlantBox,
    configs: &[Config],
    coords: &[[f64; 3]],
    opts: BoxOptions,
    damping: f64,
    refine: bool,
) -> Option<(f64, f64, [f64; 3])> {
    let t = pb.period;
    let m_ref = pb.mass[0];
    let k_per_alpha = m_ref / (t * t);
    let beta_ref = damping * t / m_ref;
    let nk = linspace(pb.stiffness, opts.stiffness_samples).len();
    let ks = linspace(pb.stiffness, opts.stiffness_samples);
    let neighbours = |j: usize| {
        let i = j % nk;
        let a = if i > 0 { ks[i - 1] } else { ks[i] };
        let b = if i + 1 < nk { ks[i + 1] } else { ks[i] };
        (a, b)
    };
    let make = |j: usize, k: f64| {
        let [m, b, _] = coords[j];
        let pp = PlantParams {
            gamma: k.max(0.0) * t * t / m,
            delta: b * t / m,
        };
        Config {
            scale: m / m_ref,
            table: None,
            fam: PolyFamily::new(pp, pb.d).unwrap_or_else(|_| configs[j].fam.clone()),
        }
    };
    let stiff: Vec<f64> = coords.iter().map(|c| c[2]).collect();
    let (iv, _tl, th, _, args) =
        refined_slice_args(configs, &stiff, &neighbours, &make, beta_ref, refine)?;
    // the worst plant: the sample whose interval hi is smallest, with the refined stiffness
    let mut worst = args.map_or(coords[0], |(_, jh)| coords[jh]);
    if th.is_finite() {
        worst[2] = th;
    }
    Some((iv.lo * k_per_alpha, iv.hi * k_per_alpha, worst))
}

/// The largest virtual stiffness K stable for every plant of the box and the B that reaches
/// it (robust design beyond the paper). The box is sampled on a grid (mass × damping ×
/// stiffness) and the limiting end is refined over stiffness by golden-section search; the
/// optimum over B is a uniform scan over (−B_max, B_max) on the samples alone, B_max from
/// |n0 β| < 1 for every sample, then a golden-section refinement (with the stiffness
/// refinement) between the neighbours of the best sample. Damping could be sampled at its lower end only where the stable interval grows
/// with damping (checked in the tests); the grid keeps all damping samples anyway.
pub fn robust_kmax(pb: &PlantBox, opts: BoxOptions) -> Result<RobustKmax> {
    robust_kmax_with_progress(pb, opts, &no_progress)
}

/// [`robust_kmax`] reporting each scanned damping (`opts.beta_samples`, at least 8, in
/// all) to `progress`; the golden-section refinement after the scan takes about
/// 100/`beta_samples` of the scan's time.
pub fn robust_kmax_with_progress(
    pb: &PlantBox,
    opts: BoxOptions,
    progress: Progress,
) -> Result<RobustKmax> {
    let pb = pb.validated()?;
    let (configs, coords) = box_configs(&pb, opts)?;
    let t = pb.period;
    let m_ref = pb.mass[0];
    // |β| < 1/|n0| for every plant: use the smallest bound, in physical B
    let b_max = configs
        .iter()
        .map(|c| beta_bound(&c.fam) * c.scale * m_ref / t)
        .fold(f64::INFINITY, f64::min);
    if !b_max.is_finite() {
        return Err(Error::Numerical("no bound on B (n0 = 0)".into()));
    }
    let n = opts.beta_samples.max(8);
    let h = 2.0 * b_max / n as f64;
    let bs: Vec<f64> = (0..n).map(|i| -b_max + (i as f64 + 0.5) * h).collect();
    let ticker = Ticker::new(progress);
    let his: Vec<f64> = bs
        .par_iter()
        .map(|&b| {
            let hi = box_slice(&pb, &configs, &coords, opts, b, false)
                .map_or(f64::NEG_INFINITY, |s| s.1);
            ticker.tick();
            hi
        })
        .collect();
    let (ib, &hb) = his
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .ok_or_else(|| Error::Numerical("no samples".into()))?;
    if hb == f64::NEG_INFINITY {
        return Err(Error::Numerical(
            "no virtual stiffness is stable for every plant of the box".into(),
        ));
    }
    let a = if ib > 0 { bs[ib - 1] } else { bs[ib] };
    let b = if ib + 1 < n { bs[ib + 1] } else { bs[ib] };
    let f = |x: f64| {
        box_slice(&pb, &configs, &coords, opts, x, true).map_or(f64::NEG_INFINITY, |s| s.1)
    };
    let (bx, fx) = golden_max(a, b, f);
    // the coarse scan is unrefined (an upper estimate), so compare refined values only
    let b_opt = if fx >= f(bs[ib]) { bx } else { bs[ib] };
    let (lo, hi, worst) = box_slice(&pb, &configs, &coords, opts, b_opt, true)
        .ok_or_else(|| Error::Numerical("robust interval vanished at the optimum".into()))?;
    Ok(RobustKmax {
        plant_box: pb,
        stiffness_max: hi,
        damping_at_max: b_opt,
        stiffness_min: lo,
        worst_plant: worst,
        normalized_at_min_mass: AlphaBeta {
            alpha: hi * t * t / m_ref,
            beta: b_opt * t / m_ref,
        },
        plants_sampled: configs.len(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remark4_value() {
        let r = nyquist_stiffness(0.1, 1.5, 1e-3).unwrap();
        // π²·0.1/1e-6 + 1.5²/(4·0.1) = 986960.44 + 5.625
        assert!((r.stiffness - 986_966.065).abs() < 1e-2, "{}", r.stiffness);
        assert!((r.stiffness / 1e3 - 987.0).abs() < 0.05);
        let w = oscillation_frequency(0.1, 1.5, r.stiffness).unwrap();
        assert!((w - PI / 1e-3).abs() < 1e-9 * w);
        let wn = normalized_frequency(r.gamma, r.delta, 1e-3).unwrap();
        assert!((wn - PI / 1e-3).abs() < 1e-9 * wn);
        assert!(nyquist_stiffness(0.0, 1.0, 1e-3).is_err());
        assert!(nyquist_stiffness(0.1, -1.0, 1e-3).is_err());
    }

    #[test]
    fn passive_triangle() {
        let p = passive_region(1.0).unwrap();
        assert!((polygon_area(&p.vertices) - p.area()).abs() < 1e-15);
        assert!(p.contains(AlphaBeta {
            alpha: 0.5,
            beta: 0.2
        }));
        assert!(!p.contains(AlphaBeta {
            alpha: 1.7,
            beta: 0.2
        }));
        assert!(!p.contains(AlphaBeta {
            alpha: -0.1,
            beta: 0.0
        }));
    }

    #[test]
    fn degenerate_detection() {
        let g = PI * PI;
        assert_eq!(
            unit_circle_pole(PlantParams::new(g, 0.0).unwrap()),
            Some(PI)
        );
        assert_eq!(
            unit_circle_pole(PlantParams::new(4.0 * g, 0.0).unwrap()),
            Some(0.0)
        );
        assert_eq!(unit_circle_pole(PlantParams::new(g, 1e-3).unwrap()), None);
        assert_eq!(
            unit_circle_pole(PlantParams::new(0.9 * g, 0.0).unwrap()),
            None
        );
    }
}
