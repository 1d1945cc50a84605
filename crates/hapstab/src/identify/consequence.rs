//! What the identified plant means for the wall: K_max at B = 0 (the pure spring, Section V)
//! of the identified loop, with two measures of how far the recording pins it down:
//! - the **spread**: the 2.5 % and 97.5 % quantiles of K_max over loops drawn from the
//!   parameters' normal law (the fit's covariance in the optimiser's coordinates, so a
//!   positive parameter is log-normal), a Monte-Carlo propagation of the uncertainty (JCGM
//!   101:2008, *Propagation of distributions using a Monte Carlo method*);
//! - the **robust** K_max over the parameters' 95 % confidence box ([`crate::robust`]): the
//!   stiffness stable for every plant whose parameters lie inside their intervals, for the
//!   models whose parameters are loop parameters (not a transfer function's coefficients);
//! - the **interval**: the delta method's 95 % interval of K_max ([`super::propagate`]):
//!   K̂·exp(±1.96·√(gᵀΣg)) with g the gradient of ln K_max in the optimiser's coordinates,
//!   the calibrated one (about 95 % of recordings hold the truth);
//! - K_max over the **renderable band** 0 ≤ B ≤ B_r ([`crate::kmax::renderable_band`], the
//!   position resolution Δ the recording's quantization step when one is given) with its
//!   delta-method interval the same way;
//! - the **range over the box**: the smallest and largest K_max of the loops at the box's
//!   corners (up to [`MAX_CORNER_PARAMS`] free parameters), the smallest lowered to the
//!   robust K_max. The box is a few standard errors wide, where K_max is close to linear in
//!   the parameters, so its extremes lie at corners; the range is at least as wide as the
//!   linearised 95 % interval of K_max (Σ|∂K/∂θ_i|·1.96σ_i ≥ 1.96·√(gᵀΣg), Cauchy–Schwarz
//!   with |ρ_ij| ≤ 1) and wider when several parameters move K_max or they are correlated:
//!   the conservative interval (it held the truth in every one of 200 recordings of each
//!   test case, BENCHMARKS.md).

use nalgebra::DMatrix;
use rayon::prelude::*;
use serde::Serialize;

use super::Identification;
use super::error::IdResult;
use super::propagate::{Propagated, delta_method, loop_at};
use crate::kmax::{KmaxQuery, NoiseModel, RenderableBand, kmax, renderable_band};
use crate::model::VelocityEstimator;
use crate::robust::{BoxSide, RobustKmax, RobustOptions, robust_kmax};
use crate::splitmix::SplitMix;
use crate::system::System;

/// Free parameters beyond which the range over the box is not formed (2^8 = 256 corners).
pub const MAX_CORNER_PARAMS: usize = 8;

/// Loops drawn for the spread by default: the 2.5 % quantile of 400 draws rests on 10 of
/// them, enough for two significant digits.
pub const DEFAULT_DRAWS: usize = 400;

/// K_max at B = 0 of an identified loop and its uncertainty (module doc).
#[derive(Debug, Clone, Serialize)]
pub struct StiffnessLimit {
    /// K_max at B = 0 of the identified loop in N/m (None: no stiffness is stable).
    pub k_max: Option<f64>,
    /// The 2.5 % and 97.5 % quantiles of K_max over the drawn loops, N/m (a draw with no
    /// stable stiffness counts as 0).
    pub spread: Option<[f64; 2]>,
    /// Loops drawn, and how many of them were valid loops.
    pub draws: usize,
    /// Valid draws.
    pub valid_draws: usize,
    /// The robust K_max over the parameters' 95 % box (None for a transfer function).
    pub robust: Option<RobustKmax>,
    /// The smallest and largest K_max over the 95 % box (module doc), N/m; None beyond
    /// [`MAX_CORNER_PARAMS`] free parameters or when a corner has no stable stiffness.
    pub box_range: Option<[f64; 2]>,
    /// K_max at B = 0 with its delta-method standard error and 95 % interval (module doc).
    pub interval: Option<Propagated>,
    /// K_max over the renderable band with its delta-method interval (module doc).
    pub renderable: Option<BandLimit>,
}

/// K_max over the renderable damping band of the identified loop, with its uncertainty.
#[derive(Debug, Clone, Serialize)]
pub struct BandLimit {
    /// The band and K_max over it at the estimates.
    #[serde(flatten)]
    pub band: RenderableBand,
    /// K_max over the band with its delta-method standard error and 95 % interval.
    pub interval: Option<Propagated>,
}

/// The noise model of the renderable band B ≤ B_r = F_n·√12/(Δ·‖V‖₂) ([`crate::kmax`]'s
/// module doc): the recording's quantization step as the position resolution Δ when one was
/// given, otherwise [`NoiseModel::default`].
pub fn band_noise(id: &Identification) -> NoiseModel {
    let mut noise = NoiseModel::default();
    if id.spec.quantization > 0.0 {
        noise.position_resolution = id.spec.quantization;
    }
    noise
}

/// K_max over the renderable band of one loop under `noise`.
fn band_of(lp: &crate::Loop, noise: NoiseModel) -> Option<RenderableBand> {
    let sys = System::of(lp).ok()?;
    renderable_band(&sys, noise).ok().flatten()
}

/// K_max over the renderable band of the identified loop with its delta-method interval.
fn band_limit(id: &Identification, velocity: &VelocityEstimator) -> IdResult<Option<BandLimit>> {
    let noise = band_noise(id);
    let lp = id.to_loop(velocity.clone())?;
    let Some(band) = renderable_band(&System::new(lp)?, noise)? else {
        return Ok(None);
    };
    let interval = delta_method(id, velocity, |lp| band_of(lp, noise)?.k_max);
    Ok(Some(BandLimit { band, interval }))
}

/// K_max at B = 0 of one loop in N/m.
fn k_max_at_zero(lp: &crate::Loop) -> crate::Result<Option<f64>> {
    Ok(kmax(&System::of(lp)?, KmaxQuery::AtDamping(0.0))?.k_max)
}

/// K_max at B = 0 of the identified loop with the velocity estimator `velocity`, its spread
/// over `draws` loops drawn with `seed`, its delta-method interval, the robust K_max and the
/// range over the 95 % box, and K_max over the renderable band with its interval (module
/// doc).
pub fn stiffness_limit(
    id: &Identification,
    velocity: &VelocityEstimator,
    draws: usize,
    seed: u64,
) -> IdResult<StiffnessLimit> {
    let lp = id.to_loop(velocity.clone())?;
    let k_max = k_max_at_zero(&lp)?;
    let samples = drawn_k_max(id, velocity, draws, seed);
    let spread = quantiles(&samples);
    let sides: Vec<BoxSide> = id
        .parameters
        .iter()
        .filter(|p| !p.fixed)
        .filter_map(|p| {
            let param = id.spec.kind.sweep_param(&p.name)?;
            let [lo, hi] = p.ci95?;
            Some(BoxSide { param, lo, hi })
        })
        .collect();
    let free = id.parameters.iter().filter(|p| !p.fixed).count();
    let robust = if sides.is_empty() || sides.len() < free {
        None
    } else {
        let opts = RobustOptions {
            samples: 64,
            verify: 1000,
            seed,
        };
        Some(robust_kmax(&lp, &sides, 0.0, &opts)?)
    };
    let box_range = corner_range(id, velocity).map(|[lo, hi]| {
        let robust_lo = robust.as_ref().and_then(|r| r.k_max).unwrap_or(lo);
        [lo.min(robust_lo), hi]
    });
    Ok(StiffnessLimit {
        k_max,
        spread,
        draws,
        valid_draws: samples.len(),
        robust,
        box_range,
        interval: delta_method(id, velocity, |lp| k_max_at_zero(lp).ok().flatten()),
        renderable: band_limit(id, velocity)?,
    })
}

/// K_max at B = 0 of loops drawn from the fit's normal law: x = x̂ + L·z with LLᵀ the
/// covariance of the free parameters and z standard normal (Box–Muller on SplitMix streams).
fn drawn_k_max(
    id: &Identification,
    velocity: &VelocityEstimator,
    draws: usize,
    seed: u64,
) -> Vec<f64> {
    let p = id.spec.free().len(); // the offset, if any, comes last and does not move K_max
    let cov = DMatrix::from_fn(p, p, |a, b| id.covariance[a][b]);
    let Some(chol) = cov.cholesky() else {
        return Vec::new();
    };
    let l = chol.l();
    (0..draws)
        .into_par_iter()
        .filter_map(|i| {
            let mut rng = SplitMix::stream(seed, i);
            let z: Vec<f64> = (0..p).map(|_| normal(&mut rng)).collect();
            let dx: Vec<f64> = (0..p)
                .map(|k| (0..=k).map(|m| l[(k, m)] * z[m]).sum())
                .collect();
            let lp = loop_at(id, velocity, &dx)?;
            k_max_at_zero(&lp).ok().map(|k| k.unwrap_or(0.0).max(0.0))
        })
        .collect()
}

/// The smallest and largest K_max at B = 0 over the corners of the 95 % box.
fn corner_range(id: &Identification, velocity: &VelocityEstimator) -> Option<[f64; 2]> {
    let free = id.spec.free();
    if free.len() > MAX_CORNER_PARAMS {
        return None;
    }
    let base: Vec<f64> = id.parameters.iter().map(|e| e.value).collect();
    let ks: Vec<Option<f64>> = (0..1usize << free.len())
        .into_par_iter()
        .map(|mask| {
            let mut v = base.clone();
            for (bit, &i) in free.iter().enumerate() {
                let [lo, hi] = id.parameters[i].ci95?;
                v[i] = if mask >> bit & 1 == 1 { hi } else { lo };
            }
            let lp = id.spec.to_loop(&v, id.period, velocity.clone()).ok()?;
            k_max_at_zero(&lp).ok().flatten()
        })
        .collect();
    let ks: Option<Vec<f64>> = ks.into_iter().collect();
    let ks = ks?;
    let lo = ks.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = ks.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    Some([lo, hi])
}

/// A standard normal deviate (Box–Muller).
fn normal(rng: &mut SplitMix) -> f64 {
    let u1 = 1.0 - rng.next_f64(); // (0, 1]
    let u2 = rng.next_f64();
    (-2.0 * u1.ln()).sqrt() * (2.0 * std::f64::consts::PI * u2).cos()
}

/// The 2.5 % and 97.5 % quantiles (linear interpolation between order statistics, as
/// numpy's default); None without samples.
fn quantiles(samples: &[f64]) -> Option<[f64; 2]> {
    if samples.is_empty() {
        return None;
    }
    let mut s = samples.to_vec();
    s.sort_by(f64::total_cmp);
    let q = |p: f64| {
        let h = p * (s.len() - 1) as f64;
        let (i, f) = (h.floor() as usize, h.fract());
        let next = s[(i + 1).min(s.len() - 1)];
        s[i] + f * (next - s[i])
    };
    Some([q(0.025), q(0.975)])
}
