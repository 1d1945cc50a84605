//! The paper's plant and sampling flags ([`PlantArgs`]): normalized (γ, δ) or physical
//! units, resolved to a [`PlantModel`].

use anyhow::{Result, bail};
use clap::Args;
use hapstab::params::{Arm, Device, Effective, Sampling};
use serde::Serialize;

use super::{DEFAULT_PERIOD, PHYSICAL_PLANT_FLAGS};

/// Plant and sampling: either normalized (γ, δ) or physical units. Without any flag: a
/// PHANToM-like device (m_L = 0.1 kg, b_L = 1.5 Ns/m) held by a typical arm (m_H = 1 kg,
/// b_H = 6 Ns/m, k_H = 350 N/m), T = 1 ms, d = 0.
#[derive(Args, Debug, Clone, Default)]
pub struct PlantArgs {
    /// Normalized physical stiffness γ = kT²/m (normalized mode: the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = PHYSICAL_PLANT_FLAGS)]
    pub gamma: Option<f64>,
    /// Normalized physical damping δ = bT/m (normalized mode: the paper's plant only).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = PHYSICAL_PLANT_FLAGS)]
    pub delta: Option<f64>,
    /// Effective mass m = m_L + m_H in kg (replaces the device and arm split).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["device_mass", "arm_mass"])]
    pub mass: Option<f64>,
    /// Effective damping b = b_L + b_H in Ns/m.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["device_damping", "arm_damping"])]
    pub damping: Option<f64>,
    /// Effective stiffness k = k_H in N/m.
    #[arg(long, allow_hyphen_values = true, conflicts_with = "arm_stiffness")]
    pub stiffness: Option<f64>,
    /// Device mass m_L in kg [default: 0.1].
    #[arg(long, allow_hyphen_values = true)]
    pub device_mass: Option<f64>,
    /// Device damping b_L in Ns/m [default: 1.5].
    #[arg(long, allow_hyphen_values = true)]
    pub device_damping: Option<f64>,
    /// Arm mass m_H in kg [default: 1.0].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_mass: Option<f64>,
    /// Arm damping b_H in Ns/m [default: 6].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_damping: Option<f64>,
    /// Arm stiffness k_H in N/m [default: 350].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_stiffness: Option<f64>,
    /// No human arm: the ungrabbed device (k_H = b_H = m_H = 0).
    #[arg(long, conflicts_with_all = ["arm_mass", "arm_damping", "arm_stiffness", "mass", "damping", "stiffness"])]
    pub no_arm: bool,
    /// Sampling period T in s, from 1e-7 to 1 [default: 0.001].
    #[arg(long, allow_hyphen_values = true)]
    pub period: Option<f64>,
    /// Delay d in whole samples [default: 0].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "delay_time")]
    pub delay: Option<f64>,
    /// Delay t_d = (d + λ)T in seconds; a fraction λ of a period is discretized exactly
    /// (modified z-transform) by the commands that accept the general loop.
    #[arg(long, allow_hyphen_values = true)]
    pub delay_time: Option<f64>,
    /// A loop saved as JSON: a report's "input" (e.g. `hapstab check --json > my.json`), its
    /// "loop" object, or a whole report. Flags given beside it change its parts: the arm,
    /// device or two-mass flags the matching parts of its plant, the other plant flags
    /// replace the plant; --period, --delay, --velocity, --force-lag and the wall flags
    /// their own part (a new --period keeps the file's delay in samples).
    #[arg(long = "loop", value_name = "FILE")]
    pub loop_file: Option<std::path::PathBuf>,
}

/// The resolved plant: normalized only, or physical with the normalization it implies.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct PlantModel {
    /// γ.
    pub gamma: f64,
    /// δ.
    pub delta: f64,
    /// d.
    pub d: usize,
    /// Physical plant and sampling, when given in physical units.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub physical: Option<(Effective, Sampling)>,
}

/// A delay in whole samples from the --delay flag.
pub fn delay_samples(v: f64) -> Result<usize> {
    if !v.is_finite() {
        bail!("delay d must be a finite whole number of samples (got {v})");
    }
    if v < 0.0 {
        bail!("delay d must be >= 0 (got {v})");
    }
    if v.fract() != 0.0 {
        bail!("delay d must be a whole number of samples (got {v}); use --delay-time for seconds");
    }
    Ok(hapstab::params::check_delay(v as usize)?)
}

impl PlantArgs {
    /// True when the plant is given normalized (--gamma/--delta).
    pub fn normalized_mode(&self) -> bool {
        self.gamma.is_some() || self.delta.is_some()
    }

    /// True when a physical plant or sampling flag is given.
    pub fn any_physical(&self) -> bool {
        self.mass.is_some()
            || self.damping.is_some()
            || self.stiffness.is_some()
            || self.device_mass.is_some()
            || self.device_damping.is_some()
            || self.arm_mass.is_some()
            || self.arm_damping.is_some()
            || self.arm_stiffness.is_some()
            || self.no_arm
            || self.period.is_some()
            || self.delay_time.is_some()
    }

    /// The effective plant of eq. (1) from the physical flags and defaults.
    pub fn effective(&self) -> Result<Effective> {
        if self.mass.is_some() || self.damping.is_some() || self.stiffness.is_some() {
            let m = self.mass.unwrap_or(Device::PHANTOM_LIKE.mass);
            return Ok(Effective::new(
                m,
                self.damping.unwrap_or(Device::PHANTOM_LIKE.damping),
                self.stiffness.unwrap_or(0.0),
            )?);
        }
        let device = Device {
            mass: self.device_mass.unwrap_or(Device::PHANTOM_LIKE.mass),
            damping: self.device_damping.unwrap_or(Device::PHANTOM_LIKE.damping),
        };
        Ok(Effective::combine(device, self.arm())?)
    }

    /// The arm inside the effective plant of eq. (1), when the plant is given as a device and
    /// an arm (not as --mass/--damping/--stiffness, and not with --no-arm).
    pub fn operator(&self) -> Option<Arm> {
        let lumped = self.mass.is_some() || self.damping.is_some() || self.stiffness.is_some();
        let arm = self.arm();
        (!lumped && arm != Arm::NONE).then_some(arm)
    }

    /// The arm from the arm flags: the typical arm by default, none with --no-arm.
    pub fn arm(&self) -> Arm {
        let base = if self.no_arm { Arm::NONE } else { Arm::TYPICAL };
        Arm {
            mass: self.arm_mass.unwrap_or(base.mass),
            damping: self.arm_damping.unwrap_or(base.damping),
            stiffness: self.arm_stiffness.unwrap_or(base.stiffness),
        }
    }

    /// The sampling period and delay.
    pub fn sampling(&self) -> Result<Sampling> {
        let period = self.period.unwrap_or(DEFAULT_PERIOD);
        if let Some(t) = self.delay_time {
            return Ok(Sampling::from_delay_time(period, t)?);
        }
        Ok(Sampling::new(
            period,
            delay_samples(self.delay.unwrap_or(0.0))?,
        )?)
    }

    /// Resolves the plant in either mode.
    pub fn resolve(&self) -> Result<PlantModel> {
        if self.loop_file.is_some() {
            return crate::loop_file::paper_plant(self, "this analysis")?.resolve();
        }
        if self.normalized_mode() {
            if self.any_physical() {
                bail!("give either normalized (--gamma/--delta) or physical parameters, not both");
            }
            let pp =
                hapstab::PlantParams::new(self.gamma.unwrap_or(0.0), self.delta.unwrap_or(0.0))?;
            let d = delay_samples(self.delay.unwrap_or(0.0))?;
            return Ok(PlantModel {
                gamma: pp.gamma,
                delta: pp.delta,
                d,
                physical: None,
            });
        }
        let eff = self.effective()?;
        let s = self.sampling()?;
        let pp = hapstab::PlantParams::from_physical(&eff, s.period)?;
        Ok(PlantModel {
            gamma: pp.gamma,
            delta: pp.delta,
            d: s.delay,
            physical: Some((eff, s)),
        })
    }
}
