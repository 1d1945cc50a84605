//! The library computations behind `hapstab paper`: every stable region, validity point,
//! robust region and passivity check that a figure or a claim needs, run once each as
//! independent jobs in parallel (rayon).
//!
//! Here the keys of the work and the results; [`region`] computes one stable region,
//! [`jobs`] lists the jobs and runs them.

mod jobs;
mod region;

use std::collections::HashMap;
use std::f64::consts::PI;

use anyhow::{Context, Result};
use hapstab::PlantParams;
use hapstab::paper::linear::ValidityPoint;
use hapstab::paper::nyquist::{
    DEGENERATE_OFFSET, PassiveCheck, RobustOptions, RobustRegion, unit_circle_pole,
};
use serde::Serialize;

pub use jobs::{jobs, passive_gamma_hi, run};
pub use region::Region;

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
