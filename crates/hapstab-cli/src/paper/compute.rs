//! The library computations behind `hapstab paper`: every stable region, validity point,
//! robust region and passivity check that a figure or a claim needs, run once each as
//! independent jobs in parallel (rayon).

use std::collections::HashMap;
use std::f64::consts::PI;

use anyhow::{Context, Result};
use hapstab::linear::{ValidityPoint, validity_points};
use hapstab::nyquist::{
    DEGENERATE_OFFSET, PassiveCheck, RobustOptions, RobustRegion, passive_inside_robust,
    robust_region, unit_circle_pole,
};
use hapstab::region::stable_region;
use hapstab::{PlantParams, PolyFamily};
use rayon::prelude::*;
use serde::Serialize;

/// Upper end of the human-arm stiffness range of eq. (15): γ < 1·10⁻³.
pub const GAMMA_ARM: f64 = 1e-3;
/// Upper end of the damping range of eq. (15): δ < 15·10⁻³.
pub const DELTA_ARM: f64 = 15e-3;
/// The δ values of Fig. 7.
pub const FIG7_DELTAS: [f64; 4] = [0.0, 0.005, 0.01, 0.015];
/// Error levels of Fig. 7: 2 % (circles) and 5 % (squares).
pub const LEVELS: [f64; 2] = [0.02, 0.05];
/// Fractions of the Nyquist frequency swept in the left panels of Figs. 8–10 (up to half).
pub const HALF_SWEEP: [(u32, u32); 5] = [(0, 1), (1, 8), (1, 4), (3, 8), (1, 2)];
/// Fractions of the Nyquist frequency swept in the right panels of Figs. 8–10 (up to full).
pub const FULL_SWEEP: [(u32, u32); 5] = [(0, 1), (1, 4), (1, 2), (3, 4), (1, 1)];
/// The δ of the lower panels of Figs. 9 and 10.
pub const DELTA_NYQUIST: f64 = 1.0;

/// Options of the robust regions drawn in Figs. 8–10: γ sampled at 41 points without the
/// golden-section refinement between samples (an outer approximation, within 1 % in area
/// of the library defaults, at a twentieth of the time). Claim C8 uses the refined check.
pub const ROBUST_DRAW: RobustOptions = RobustOptions {
    gamma_samples: 41,
    beta_samples: 61,
    refine_gamma: false,
    refine_beta_rounds: 2,
};

/// One plant and delay: (γ, δ, d).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Key {
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
}

impl Key {
    /// A key.
    pub const fn new(gamma: f64, delta: f64, d: usize) -> Self {
        Self { gamma, delta, d }
    }

    fn id(&self) -> (u64, u64, usize) {
        (self.gamma.to_bits(), self.delta.to_bits(), self.d)
    }

    /// The plant parameters.
    pub fn plant(&self) -> Result<PlantParams> {
        Ok(PlantParams::new(self.gamma, self.delta)?)
    }
}

/// γ at a fraction f = num/den of the Nyquist frequency, from eq. (26):
/// ω = √(γ − δ²/4)/T = fπ/T, i.e. γ = (fπ)² + δ²/4 (γ = 0 for f = 0). Where every (α, β) is
/// limit stable (δ = 0, γ = π²) the limit from inside, γ(1 − [`DEGENERATE_OFFSET`]), is used.
pub fn sweep_gamma(frac: (u32, u32), delta: f64) -> f64 {
    if frac.0 == 0 {
        return 0.0;
    }
    let f = frac.0 as f64 / frac.1 as f64;
    let g = (f * PI).powi(2) + delta * delta / 4.0;
    if unit_circle_pole(PlantParams { gamma: g, delta }).is_some() {
        g * (1.0 - DEGENERATE_OFFSET)
    } else {
        g
    }
}

/// How a region's outline was obtained.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// `hapstab::region::stable_region`: exact polygons.
    Exact,
    /// `stable_region` returned no polygon: outline through exact per-β α-intervals
    /// (`hapstab::nyquist::robust_region` over the single γ).
    Slices,
}

/// A stable region ready for drawing and tabulating.
#[derive(Debug, Clone, Serialize)]
pub struct Region {
    /// (γ, δ, d).
    pub key: Key,
    /// Closed outlines (first vertex not repeated), α horizontal, β vertical.
    #[serde(skip)]
    pub rings: Vec<Vec<(f64, f64)>>,
    /// Number of outline vertices.
    pub vertices: usize,
    /// Largest stable α.
    pub alpha_max: f64,
    /// β at α_max.
    pub beta_at_alpha_max: f64,
    /// Area in the (α, β)-plane.
    pub area: f64,
    /// Smallest α of the outline.
    pub alpha_min: f64,
    /// Smallest β of the outline.
    pub beta_min: f64,
    /// Largest β of the outline.
    pub beta_max: f64,
    /// Where the outline comes from.
    pub source: Source,
}

fn extent(rings: &[Vec<(f64, f64)>]) -> (f64, f64, f64) {
    let pts = || rings.iter().flatten();
    (
        pts().map(|p| p.0).fold(f64::INFINITY, f64::min),
        pts().map(|p| p.1).fold(f64::INFINITY, f64::min),
        pts().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
    )
}

/// The stable region of one key: exact polygons, or the β-slice outline when
/// `stable_region` finds none (see [`Source::Slices`]).
pub fn region(key: Key) -> Result<Region> {
    let fam = PolyFamily::new(key.plant()?, key.d)?;
    let r = stable_region(&fam)?;
    if !r.polygons.is_empty() {
        let rings: Vec<Vec<(f64, f64)>> = r
            .polygons
            .iter()
            .map(|p| p.vertices.iter().map(|v| (v.alpha, v.beta)).collect())
            .collect();
        let (alpha_min, beta_min, beta_max) = extent(&rings);
        return Ok(Region {
            key,
            vertices: rings.iter().map(Vec::len).sum(),
            rings,
            alpha_max: r.alpha_max,
            beta_at_alpha_max: r.beta_at_alpha_max,
            area: r.area,
            alpha_min,
            beta_min,
            beta_max,
            source: Source::Exact,
        });
    }
    let opts = RobustOptions {
        gamma_samples: 2,
        beta_samples: 121,
        refine_gamma: false,
        refine_beta_rounds: 3,
    };
    let s = robust_region(key.delta, key.d, key.gamma, key.gamma, opts)
        .with_context(|| format!("stable region of {key:?} by slices"))?;
    let ring: Vec<(f64, f64)> = s.polygon.iter().map(|v| (v.alpha, v.beta)).collect();
    let rings = if ring.len() >= 3 { vec![ring] } else { vec![] };
    let (alpha_min, beta_min, beta_max) = extent(&rings);
    Ok(Region {
        key,
        vertices: rings.iter().map(Vec::len).sum(),
        rings,
        alpha_max: s.alpha_max,
        beta_at_alpha_max: s.beta_at_alpha_max,
        area: s.area,
        alpha_min,
        beta_min,
        beta_max,
        source: Source::Slices,
    })
}

/// Which robust region: δ, d and whether γ runs to the full (or half) Nyquist frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RobustKey {
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// γ up to the full Nyquist frequency (else half).
    pub full: bool,
}

impl RobustKey {
    /// Upper end of the γ interval: the last γ of the panel's sweep (eq. 26–27).
    pub fn gamma_hi(&self) -> f64 {
        let frac = if self.full { (1, 1) } else { (1, 2) };
        let f = frac.0 as f64 / frac.1 as f64;
        (f * PI).powi(2) + self.delta * self.delta / 4.0
    }

    fn id(&self) -> (u64, usize, bool) {
        (self.delta.to_bits(), self.d, self.full)
    }
}

/// One unit of work.
#[derive(Debug, Clone, Copy)]
pub enum Job {
    /// A stable region.
    Region(Key),
    /// The 2 % and 5 % points of Fig. 7.
    Validity(Key),
    /// A robust region of Figs. 8–10.
    Robust(RobustKey),
    /// Claim C8: passive triangle inside the robust region (δ = 1, d = 0, full range).
    Passive,
}

impl Job {
    /// Rough cost rank (higher first) so the slow jobs start first.
    fn cost(&self) -> u32 {
        match self {
            Job::Passive => 4,
            Job::Robust(r) if r.delta > 0.0 => 3,
            Job::Validity(_) => 2,
            Job::Robust(_) => 1,
            Job::Region(_) => 0,
        }
    }
}

enum Out {
    Region(Region),
    Validity(Key, Vec<ValidityPoint>),
    Robust(RobustKey, Box<RobustRegion>),
    Passive(PassiveCheck),
}

/// Everything computed.
#[derive(Default)]
pub struct Results {
    regions: HashMap<(u64, u64, usize), Region>,
    validity: HashMap<(u64, u64, usize), Vec<ValidityPoint>>,
    robust: HashMap<(u64, usize, bool), RobustRegion>,
    /// Claim C8.
    pub passive: Option<PassiveCheck>,
}

impl Results {
    /// The region of a key (computed beforehand).
    pub fn region(&self, k: Key) -> Result<&Region> {
        self.regions
            .get(&k.id())
            .with_context(|| format!("region {k:?} was not computed"))
    }

    /// The validity points of a key.
    pub fn validity(&self, k: Key) -> Result<&[ValidityPoint]> {
        self.validity
            .get(&k.id())
            .map(Vec::as_slice)
            .with_context(|| format!("validity points {k:?} were not computed"))
    }

    /// A robust region.
    pub fn robust(&self, k: RobustKey) -> Result<&RobustRegion> {
        self.robust
            .get(&k.id())
            .with_context(|| format!("robust region {k:?} was not computed"))
    }
}

/// The jobs of every figure plus `extra` region keys (claims), deduplicated.
pub fn jobs(extra: &[Key]) -> Vec<Job> {
    let mut keys: Vec<Key> = Vec::new();
    // Figs. 4–6: the corners of the range (15) for d = 0, 1, 2.
    for d in 0..=2 {
        for gamma in [0.0, GAMMA_ARM] {
            for delta in [0.0, DELTA_ARM] {
                keys.push(Key::new(gamma, delta, d));
            }
        }
    }
    // Fig. 7.
    let mut validity = Vec::new();
    for d in 0..=1 {
        for gamma in [0.0, GAMMA_ARM] {
            for delta in FIG7_DELTAS {
                keys.push(Key::new(gamma, delta, d));
                validity.push(Key::new(gamma, delta, d));
            }
        }
    }
    // Figs. 8–10.
    let mut robust = Vec::new();
    for (delta, d) in [(0.0, 0), (DELTA_NYQUIST, 0), (0.0, 1), (DELTA_NYQUIST, 1)] {
        for f in HALF_SWEEP.iter().chain(FULL_SWEEP.iter()) {
            keys.push(Key::new(sweep_gamma(*f, delta), delta, d));
        }
        for full in [false, true] {
            robust.push(RobustKey { delta, d, full });
        }
    }
    keys.extend_from_slice(extra);
    let mut seen = std::collections::HashSet::new();
    keys.retain(|k| seen.insert(k.id()));
    let mut jobs: Vec<Job> = keys.into_iter().map(Job::Region).collect();
    jobs.extend(validity.into_iter().map(Job::Validity));
    jobs.extend(robust.into_iter().map(Job::Robust));
    jobs.push(Job::Passive);
    jobs.sort_by_key(|j| std::cmp::Reverse(j.cost()));
    jobs
}

/// Options of the passivity check of claim C8 (the library defaults: refined in γ).
pub fn passive_options() -> RobustOptions {
    RobustOptions::default()
}

/// The γ range of claim C8: up to the Nyquist frequency for δ = 1.
pub fn passive_gamma_hi() -> f64 {
    RobustKey {
        delta: DELTA_NYQUIST,
        d: 0,
        full: true,
    }
    .gamma_hi()
}

fn run_job(j: Job) -> Result<Out> {
    Ok(match j {
        Job::Region(k) => Out::Region(region(k)?),
        Job::Validity(k) => Out::Validity(
            k,
            validity_points(k.plant()?, k.d, &LEVELS)
                .with_context(|| format!("validity points of {k:?}"))?,
        ),
        Job::Robust(r) => Out::Robust(
            r,
            Box::new(robust_region(r.delta, r.d, 0.0, r.gamma_hi(), ROBUST_DRAW)?),
        ),
        Job::Passive => Out::Passive(passive_inside_robust(
            DELTA_NYQUIST,
            0,
            0.0,
            passive_gamma_hi(),
            41,
            passive_options(),
        )?),
    })
}

/// Runs every job in parallel; `tick` is called after each.
pub fn run(jobs: &[Job], tick: &(dyn Fn() + Sync)) -> Result<Results> {
    let outs: Vec<Out> = jobs
        .par_iter()
        .with_max_len(1)
        .map(|&j| {
            let o = run_job(j);
            tick();
            o
        })
        .collect::<Result<_>>()?;
    let mut res = Results::default();
    for o in outs {
        match o {
            Out::Region(r) => {
                res.regions.insert(r.key.id(), r);
            }
            Out::Validity(k, v) => {
                res.validity.insert(k.id(), v);
            }
            Out::Robust(k, r) => {
                res.robust.insert(k.id(), *r);
            }
            Out::Passive(p) => res.passive = Some(p),
        }
    }
    Ok(res)
}
