//! K_max as every front end reports it: at a given damping, over a band of damping, and —
//! without either — the three numbers a designer reads first: the pure spring (B = 0), the
//! largest over the damping the device can *render*, and the largest over B ≥ 0 with the
//! damping it needs.
//!
//! **The renderable band.** The wall's damper multiplies the velocity estimate, and the
//! estimate of a quantized position is noisy: position steps of Δ give a white quantization
//! noise of variance Δ²/12 (Widrow & Kollár, *Quantization Noise*, 2008, ch. 4), which the
//! estimator V(z) amplifies by its H2 norm ‖V‖₂ (the root of the impulse response's energy,
//! Σ h[n]²). The damper's force noise is then B·‖V‖₂·Δ/√12, and keeping it below a force
//! noise F_n (RMS) allows 0 ≤ B ≤ B_r = F_n·√12/(Δ·‖V‖₂). The defaults
//! ([`DEFAULT_POSITION_RESOLUTION`], [`DEFAULT_FORCE_NOISE`]) are a desktop device's encoder
//! step at the handle and a force ripple small beside what a hand holding a stylus feels;
//! a low-pass velocity filter lowers ‖V‖₂ and widens the band while it shrinks the stable
//! region — the trade-off of Colgate & Brown's Z-width (1994).

use serde::Serialize;

use crate::boundary::Interval;
use crate::error::{Error, Result};
use crate::model::Loop;
use crate::param::Param;
use crate::region::ConfirmedMax;
use crate::system::System;

/// Default position resolution Δ at the handle, in m (10 µm: a desktop haptic device's
/// encoder step referred to the handle).
pub const DEFAULT_POSITION_RESOLUTION: f64 = 1e-5;

/// Default force noise F_n the damper may add, RMS in N (0.05 N: small beside the forces a
/// hand holding a stylus notices).
pub const DEFAULT_FORCE_NOISE: f64 = 0.05;

/// Longest impulse response summed for ‖V‖₂ (an estimator whose response has not decayed
/// by then has a pole on or too near the unit circle for a noise gain to mean anything).
const NOISE_GAIN_MAX_SAMPLES: usize = 20_000_000;

/// Relative energy left in the impulse response's tail when the sum stops: below the
/// rounding of the sum itself.
const NOISE_GAIN_TAIL: f64 = 1e-18;

/// What K_max is asked of: at one damping, over a band of damping, or the designer's three
/// numbers (B = 0, the renderable band, B ≥ 0). Dampings in Ns/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum KmaxQuery {
    /// K_max at the damping B.
    AtDamping(f64),
    /// K_max over lo ≤ B ≤ hi (hi may be +∞) and the B that reaches it, beside B = 0's.
    Band {
        /// Lower end in Ns/m (finite).
        lo: f64,
        /// Upper end in Ns/m (+∞ for no bound).
        hi: f64,
    },
    /// K_max at B = 0, over the renderable band of the given noise model, and over B ≥ 0.
    Design(NoiseModel),
}

/// The noise that bounds the damping a device renders: position steps and the force noise
/// allowed (see the module's doc).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NoiseModel {
    /// Position resolution Δ at the handle, m (> 0).
    pub position_resolution: f64,
    /// Largest force noise the damper may add, RMS in N (> 0).
    pub force_noise: f64,
}

impl Default for NoiseModel {
    fn default() -> Self {
        NoiseModel {
            position_resolution: DEFAULT_POSITION_RESOLUTION,
            force_noise: DEFAULT_FORCE_NOISE,
        }
    }
}

impl NoiseModel {
    /// A noise model with both values checked finite and positive.
    pub fn new(position_resolution: f64, force_noise: f64) -> Result<Self> {
        for (name, v) in [
            (Param::PositionResolution, position_resolution),
            (Param::ForceNoise, force_noise),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(Error::Invalid {
                    param: name,
                    reason: format!("must be a positive finite number (got {v})"),
                });
            }
        }
        Ok(NoiseModel {
            position_resolution,
            force_noise,
        })
    }
}

/// The renderable damping band 0 ≤ B ≤ `b_max` of a loop under a noise model, and K_max
/// over it.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RenderableBand {
    /// The noise model that sets the band.
    #[serde(flatten)]
    pub noise: NoiseModel,
    /// The velocity estimator's noise gain ‖V‖₂ in 1/s (velocity noise RMS per metre of
    /// position noise RMS).
    pub velocity_noise_gain: f64,
    /// The band's upper end B_r = F_n·√12/(Δ·‖V‖₂), Ns/m.
    pub b_max: f64,
    /// K_max over the band, N/m (None when no stiffness is stable in it).
    pub k_max: Option<f64>,
    /// The damping that reaches it, Ns/m.
    pub b_at_k_max: Option<f64>,
    /// False where K_max over the band is a supremum (a corner of the region).
    pub k_max_attained: Option<bool>,
}

/// The answer of a K_max query, in N/m and Ns/m: the keys of `hapstab kmax --json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KmaxReport {
    /// Largest stable K (over the band, or at the given damping), N/m.
    pub k_max: Option<f64>,
    /// B at which K_max over the band is reached (absent with a given B), Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b_at_k_max: Option<f64>,
    /// False where K_max over the band is a supremum: a corner of the region that only the
    /// damping `b_at_k_max` touches, approached as B → `b_at_k_max` (absent with a given B).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_max_attained: Option<bool>,
    /// For a supremum, a damping beside `b_at_k_max` at which `k_stable_near_k_max` is
    /// stable, Ns/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub b_stable_near_k_max: Option<f64>,
    /// For a supremum, a stiffness within 1e-6 of K_max (1e-9 where the corner's wedge is
    /// wide enough) that the verdict confirms stable at `b_stable_near_k_max`, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_stable_near_k_max: Option<f64>,
    /// K_max with no virtual damping (B = 0: the plant's own damping only), N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_max_at_zero_damping: Option<f64>,
    /// Stable K interval at the given B, N/m.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_interval: Option<[f64; 2]>,
    /// Linear condition (22): (b + B)/(t_d + T/2) at the same B, N/m (the paper's loop).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub k_linear: Option<f64>,
    /// The renderable damping band and K_max over it (the design query only; absent where
    /// the estimator's noise gain is unbounded).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub renderable: Option<RenderableBand>,
    /// K_max in the family's wall units (α_max for the paper's loop).
    #[serde(skip)]
    pub k_max_units: Option<f64>,
    /// The damping of K_max in wall units (β for the paper's loop).
    #[serde(skip)]
    pub b_units: Option<f64>,
}

/// The velocity estimator's noise gain ‖V‖₂ = √(Σ h[n]²) in 1/s, h the impulse response of
/// the estimator V(z) from position (m) to velocity (m/s) ([`Loop`]'s per-sample filter
/// divided by T). √2/T for the backward difference. None when the response does not decay
/// (a pole on or outside the unit circle).
pub fn velocity_noise_gain(lp: &Loop) -> Option<f64> {
    let (num, den) = lp.velocity.per_sample_filter(lp.period);
    let n = den.len() - 1;
    // ascending powers of z, monic of degree n → powers of z⁻¹: b'[k] = num[n − k]
    let b: Vec<f64> = (0..=n)
        .map(|k| num.get(n - k).copied().unwrap_or(0.0))
        .collect();
    let a: Vec<f64> = (0..=n).map(|k| den[n - k]).collect();
    let mut h = vec![0.0; n + 1];
    let (mut energy, mut window) = (0.0, 0.0);
    let span = (n + 1).max(64);
    for k in 0..NOISE_GAIN_MAX_SAMPLES {
        let mut hk = if k <= n { b[k] } else { 0.0 };
        for j in 1..=n.min(k) {
            hk -= a[j] * h[(k - j) % (n + 1)];
        }
        h[k % (n + 1)] = hk;
        energy += hk * hk;
        window += hk * hk;
        if !energy.is_finite() {
            return None;
        }
        if (k + 1) % span == 0 {
            if k > n && window <= NOISE_GAIN_TAIL * energy {
                return Some(energy.sqrt() / lp.period);
            }
            window = 0.0;
        }
    }
    None
}

/// The renderable band 0 ≤ B ≤ F_n·√12/(Δ·‖V‖₂) of a loop (see the module's doc) and
/// K_max over it; None when the estimator's noise gain is unbounded.
pub fn renderable_band(sys: &System, noise: NoiseModel) -> Result<Option<RenderableBand>> {
    let fam = sys.family();
    let Some(gain) = velocity_noise_gain(sys.lp()) else {
        return Ok(None);
    };
    let b_max = noise.force_noise * 12f64.sqrt() / (noise.position_resolution * gain);
    let best = sys.k_max_within(0.0, sys.damping_units(b_max)?)?;
    let phys = best.map(|p| fam.to_physical(p.a, p.b));
    Ok(Some(RenderableBand {
        noise,
        velocity_noise_gain: gain,
        b_max,
        k_max: phys.map(|p| p.0),
        b_at_k_max: phys.map(|p| p.1),
        k_max_attained: best.map(|p| p.attained),
    }))
}

/// K_max of a loop for a query (Section V: the stable stiffness intervals at a damping, or
/// the stable region's largest stiffness within a damping band), with K_max at B = 0 beside
/// a band and the linear condition (22) beside both for the paper's loop.
pub fn kmax(sys: &System, query: KmaxQuery) -> Result<KmaxReport> {
    match query {
        KmaxQuery::AtDamping(b) => at_damping(sys, b),
        KmaxQuery::Band { lo, hi } => within(sys, lo, hi),
        KmaxQuery::Design(noise) => {
            let mut report = within(sys, 0.0, f64::INFINITY)?;
            report.renderable = renderable_band(sys, noise)?;
            Ok(report)
        }
    }
}

fn finite_damping(b: f64) -> Result<f64> {
    if b.is_finite() {
        Ok(b)
    } else {
        Err(Error::Invalid {
            param: Param::WallDamping,
            reason: format!("must be a finite number (got {b})"),
        })
    }
}

fn at_damping(sys: &System, b: f64) -> Result<KmaxReport> {
    let fam = sys.family();
    let bu = sys.damping_units(finite_damping(b)?)?;
    let best: Option<Interval> = sys.k_max_at_damping(bu);
    let k = |a: f64| fam.to_physical(a, 0.0).0;
    Ok(KmaxReport {
        k_max: best.map(|i| k(i.hi)),
        b_at_k_max: None,
        k_max_attained: None,
        b_stable_near_k_max: None,
        k_stable_near_k_max: None,
        k_max_at_zero_damping: None,
        k_interval: best.map(|i| [k(i.lo), k(i.hi)]),
        k_linear: sys.linear_k(b),
        renderable: None,
        k_max_units: best.map(|i| i.hi),
        b_units: best.map(|_| bu),
    })
}

fn within(sys: &System, lo: f64, hi: f64) -> Result<KmaxReport> {
    let fam = sys.family();
    let units = |b: f64| -> Result<f64> {
        if b.is_finite() {
            sys.damping_units(b)
        } else {
            Ok(b)
        }
    };
    let best: Option<ConfirmedMax> = sys.k_max_within(units(lo)?, units(hi)?)?;
    let phys = best.map(|p| fam.to_physical(p.a, p.b));
    let at_zero = sys.k_max_at_damping(0.0);
    let supremum = best.filter(|p| !p.attained);
    Ok(KmaxReport {
        k_max: phys.map(|p| p.0),
        b_at_k_max: phys.map(|p| p.1),
        k_max_attained: best.map(|p| p.attained),
        b_stable_near_k_max: supremum.map(|p| fam.to_physical(0.0, p.b_stable).1),
        k_stable_near_k_max: supremum.map(|p| fam.to_physical(p.a_stable, 0.0).0),
        k_max_at_zero_damping: at_zero.map(|i| fam.to_physical(i.hi, 0.0).0),
        k_interval: None,
        k_linear: phys.and_then(|p| sys.linear_k(p.1)),
        renderable: None,
        k_max_units: best.map(|p| p.a),
        b_units: best.map(|p| p.b),
    })
}
