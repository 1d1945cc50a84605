//! Robust design across a range of human arms (beyond the paper): the largest virtual
//! stiffness stable for every plant of a box of masses, dampings and stiffnesses, and the
//! damping that reaches it.

use rayon::prelude::*;
use serde::Serialize;

use std::sync::OnceLock;

use super::search::golden_max;
use super::slice::{Config, refined_slice};
use super::{Progress, Ticker, beta_bound, no_progress};
use crate::boundary::WallPoint;
use crate::error::{Error, Result, finite, non_negative, positive};
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::check_delay;

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
        positive(Param::BoxMassMin, self.mass[0])?;
        positive(Param::BoxMassMax, self.mass[1])?;
        non_negative(Param::BoxDampingMin, self.damping[0])?;
        non_negative(Param::BoxDampingMax, self.damping[1])?;
        non_negative(Param::BoxStiffnessMin, self.stiffness[0])?;
        non_negative(Param::BoxStiffnessMax, self.stiffness[1])?;
        positive(Param::Period, self.period)?;
        check_delay(self.d)?;
        for (name, r) in [
            (Param::BoxMass, self.mass),
            (Param::BoxDamping, self.damping),
            (Param::BoxStiffness, self.stiffness),
        ] {
            if r[1] < r[0] {
                return Err(Error::OutOfRange {
                    param: name,
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
    pub normalized_at_min_mass: WallPoint,
    /// Number of plants sampled (before refinement).
    pub plants_sampled: usize,
}

fn linspace(r: [f64; 2], n: usize) -> Vec<f64> {
    if r[1] <= r[0] || n <= 1 {
        return vec![r[0]];
    }
    crate::grid::evenly_spaced(r[0], r[1], n)
}

/// The robust K-interval at virtual damping B over every plant sampled in the box, with the
/// end refined over the stiffness range at the worst (mass, damping) sample (robust design
/// beyond the paper). Returns (lo, hi, worst plant) or None when no K is stable for all.
pub fn robust_stiffness_interval(
    pb: &PlantBox,
    damping: f64,
    opts: BoxOptions,
) -> Result<Option<(f64, f64, [f64; 3])>> {
    finite(Param::WallDamping, damping)?;
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
                    fam: NormalizedFamily::new(pp, pb.d)?,
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
            fam: NormalizedFamily::new(pp, pb.d).unwrap_or_else(|_| configs[j].fam.clone()),
        }
    };
    let stiff: Vec<f64> = coords.iter().map(|c| c[2]).collect();
    let s = refined_slice(configs, &stiff, &neighbours, &make, beta_ref, refine)?;
    let iv = s.interval;
    // the worst plant: the sample whose interval hi is smallest, with the refined stiffness
    let mut worst = s.ends.map_or(coords[0], |(_, jh)| coords[jh]);
    if s.coord_hi.is_finite() {
        worst[2] = s.coord_hi;
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
        normalized_at_min_mass: WallPoint {
            a: hi * t * t / m_ref,
            b: b_opt * t / m_ref,
        },
        plants_sampled: configs.len(),
    })
}
