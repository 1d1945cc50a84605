//! Model arguments shared by the commands: normalized (α, β, γ, δ, d) or physical units.

use anyhow::{Result, bail};
use clap::Args;
use hapstab::params::{Arm, Device, Effective, Normalized, Physical, Sampling, Wall};
use serde::Serialize;

/// Default sampling period: 1 ms, the paper's upper limit (Section IV).
pub const DEFAULT_PERIOD: f64 = 1e-3;
/// Default virtual wall for `check`: K = 10 kN/m, B = 10 Ns/m.
pub const DEFAULT_WALL: Wall = Wall {
    stiffness: 10_000.0,
    damping: 10.0,
};

/// Plant and sampling: either normalized (γ, δ) or physical units. Without any flag: a
/// PHANToM-like device (m_L = 0.1 kg, b_L = 1.5 Ns/m) held by a typical arm (m_H = 1 kg,
/// b_H = 6 Ns/m, k_H = 350 N/m), T = 1 ms, d = 0.
#[derive(Args, Debug, Clone, Default)]
pub struct PlantArgs {
    /// Normalized physical stiffness γ = kT²/m (normalized mode).
    #[arg(long, allow_hyphen_values = true)]
    pub gamma: Option<f64>,
    /// Normalized physical damping δ = bT/m (normalized mode).
    #[arg(long, allow_hyphen_values = true)]
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
    /// Device mass m_L in kg [default 0.1].
    #[arg(long, allow_hyphen_values = true)]
    pub device_mass: Option<f64>,
    /// Device damping b_L in Ns/m [default 1.5].
    #[arg(long, allow_hyphen_values = true)]
    pub device_damping: Option<f64>,
    /// Arm mass m_H in kg [default 1.0].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_mass: Option<f64>,
    /// Arm damping b_H in Ns/m [default 6].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_damping: Option<f64>,
    /// Arm stiffness k_H in N/m [default 350].
    #[arg(long, allow_hyphen_values = true)]
    pub arm_stiffness: Option<f64>,
    /// No human arm: the ungrabbed device (k_H = b_H = m_H = 0).
    #[arg(long)]
    pub no_arm: bool,
    /// Sampling period T in s [default 0.001].
    #[arg(long, allow_hyphen_values = true)]
    pub period: Option<f64>,
    /// Delay d in whole samples [default 0].
    #[arg(long, allow_hyphen_values = true, conflicts_with = "delay_time")]
    pub delay: Option<f64>,
    /// Delay t_d in seconds; must be a whole number of periods.
    #[arg(long, allow_hyphen_values = true)]
    pub delay_time: Option<f64>,
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

fn delay_samples(v: f64) -> Result<usize> {
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
    fn normalized_mode(&self) -> bool {
        self.gamma.is_some() || self.delta.is_some()
    }

    fn any_physical(&self) -> bool {
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
        let base = if self.no_arm { Arm::NONE } else { Arm::TYPICAL };
        let arm = Arm {
            mass: self.arm_mass.unwrap_or(base.mass),
            damping: self.arm_damping.unwrap_or(base.damping),
            stiffness: self.arm_stiffness.unwrap_or(base.stiffness),
        };
        Ok(Effective::combine(device, arm)?)
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

/// A wall in either unit system.
#[derive(Args, Debug, Clone, Default)]
pub struct WallArgs {
    /// Normalized virtual stiffness α = KT²/m.
    #[arg(long, allow_hyphen_values = true)]
    pub alpha: Option<f64>,
    /// Normalized virtual damping β = BT/m.
    #[arg(long, allow_hyphen_values = true)]
    pub beta: Option<f64>,
    /// Virtual stiffness K in N/m [default 10000 in physical mode].
    #[arg(long, allow_hyphen_values = true)]
    pub wall_stiffness: Option<f64>,
    /// Virtual damping B in Ns/m [default 10 in physical mode].
    #[arg(long, allow_hyphen_values = true)]
    pub wall_damping: Option<f64>,
}

/// A fully resolved model for one parameter point.
#[derive(Debug, Clone, Copy)]
pub struct PointModel {
    /// Normalized parameters.
    pub normalized: Normalized,
    /// Physical description, when given in physical units.
    pub physical: Option<Physical>,
}

/// Resolves plant and wall arguments to one parameter point.
pub fn resolve_point(plant: &PlantArgs, wall: &WallArgs) -> Result<PointModel> {
    let normalized_wall = wall.alpha.is_some() || wall.beta.is_some();
    // --alpha/--beta without any physical flag: normalized mode with γ = δ = 0 by default.
    let pm = if normalized_wall && !plant.any_physical() {
        let mut p = plant.clone();
        p.gamma = Some(p.gamma.unwrap_or(0.0));
        p.resolve()?
    } else {
        plant.resolve()?
    };
    let physical_wall = wall.wall_stiffness.is_some() || wall.wall_damping.is_some();
    match pm.physical {
        None => {
            if physical_wall {
                bail!(
                    "--wall-stiffness/--wall-damping need a physical plant; use --alpha/--beta with --gamma/--delta"
                );
            }
            let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                bail!("normalized mode needs both --alpha and --beta");
            };
            Ok(PointModel {
                normalized: Normalized::new(alpha, beta, pm.gamma, pm.delta, pm.d)?,
                physical: None,
            })
        }
        Some((eff, s)) => {
            if normalized_wall {
                if physical_wall {
                    bail!(
                        "give the wall either as --alpha/--beta or as --wall-stiffness/--wall-damping"
                    );
                }
                let (Some(alpha), Some(beta)) = (wall.alpha, wall.beta) else {
                    bail!("give both --alpha and --beta");
                };
                let w = hapstab::params::wall_from_normalized(alpha, beta, eff.mass, s.period);
                let phys = Physical::new(eff, w, s)?;
                return Ok(PointModel {
                    normalized: phys.normalized()?,
                    physical: Some(phys),
                });
            }
            let w = Wall {
                stiffness: wall.wall_stiffness.unwrap_or(DEFAULT_WALL.stiffness),
                damping: wall.wall_damping.unwrap_or(DEFAULT_WALL.damping),
            };
            let phys = Physical::new(eff, w, s)?;
            Ok(PointModel {
                normalized: phys.normalized()?,
                physical: Some(phys),
            })
        }
    }
}
