//! Model parameters: the physical ones of Section II / eq. (1) — device, arm, effective
//! plant, wall, sampling — with their validation. The paper's dimensionless parameters of
//! Table I and the conversions to them are in [`crate::paper::normalized`].

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result, finite, non_negative, positive};
use crate::param::Param;

/// Largest supported delay in samples. A delay of 2000 samples is two seconds at 1 kHz, far
/// beyond any haptic loop; the bound keeps every analysis within memory and time.
pub const MAX_DELAY: usize = 2000;

/// The haptic device: a single mass `m_L` with viscous damping `b_L` (Section II).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Device {
    /// Device mass m_L in kg (>= 0).
    pub mass: f64,
    /// Device damping b_L in Ns/m (>= 0).
    pub damping: f64,
}

impl Device {
    /// A PHANToM-like device as in Remark 4: m_L = 0.1 kg, b_L = 1.5 Ns/m.
    pub const PHANTOM_LIKE: Device = Device {
        mass: 0.1,
        damping: 1.5,
    };
}

/// The human arm as a mass-spring-damper (Section II, Fig. 1).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Arm {
    /// Arm mass m_H in kg (>= 0).
    pub mass: f64,
    /// Arm damping b_H in Ns/m (>= 0).
    pub damping: f64,
    /// Arm stiffness k_H in N/m (>= 0).
    pub stiffness: f64,
}

impl Arm {
    /// A typical grasping arm inside the ranges of eq. (11): m_H = 1 kg, b_H = 6 Ns/m
    /// (b_H/m_H = 6 s⁻¹ < 12.6 s⁻¹), k_H = 350 N/m (k_H/m_H = 350 s⁻² < 710 s⁻²).
    pub const TYPICAL: Arm = Arm {
        mass: 1.0,
        damping: 6.0,
        stiffness: 350.0,
    };

    /// An ungrabbed device: k_H = b_H = m_H = 0 (Section IV permits this case).
    pub const NONE: Arm = Arm {
        mass: 0.0,
        damping: 0.0,
        stiffness: 0.0,
    };
}

/// The virtual wall: a discrete spring K and damper B (Section II, Fig. 3).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Wall {
    /// Virtual stiffness K in N/m (any finite value).
    pub stiffness: f64,
    /// Virtual damping B in Ns/m (any finite value).
    pub damping: f64,
}

/// The effective plant m, b, k of eq. (1): m = m_L + m_H, b = b_L + b_H, k = k_H.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Effective {
    /// Effective mass m in kg (> 0).
    pub mass: f64,
    /// Effective damping b in Ns/m (>= 0).
    pub damping: f64,
    /// Effective stiffness k in N/m (>= 0).
    pub stiffness: f64,
}

impl Effective {
    /// Builds and validates an effective plant directly (m > 0, b >= 0, k >= 0).
    pub fn new(mass: f64, damping: f64, stiffness: f64) -> Result<Self> {
        Ok(Self {
            mass: positive(Param::Mass, mass)?,
            damping: non_negative(Param::Damping, damping)?,
            stiffness: non_negative(Param::Stiffness, stiffness)?,
        })
    }

    /// Combines device and arm by eq. (1).
    pub fn combine(device: Device, arm: Arm) -> Result<Self> {
        non_negative(Param::DeviceMass, device.mass)?;
        non_negative(Param::DeviceDamping, device.damping)?;
        non_negative(Param::ArmMass, arm.mass)?;
        non_negative(Param::ArmDamping, arm.damping)?;
        non_negative(Param::ArmStiffness, arm.stiffness)?;
        Self::new(
            device.mass + arm.mass,
            device.damping + arm.damping,
            arm.stiffness,
        )
    }
}

/// Sampling: period T and a delay of d whole samples (t_d = d·T).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sampling {
    /// Sampling period T in s (> 0).
    pub period: f64,
    /// Delay d in whole samples.
    pub delay: usize,
}

impl Sampling {
    /// Validates T > 0 and d <= [`MAX_DELAY`].
    pub fn new(period: f64, delay: usize) -> Result<Self> {
        positive(Param::Period, period)?;
        check_delay(delay)?;
        Ok(Self { period, delay })
    }

    /// Builds the sampling from a delay time t_d in seconds, which must be a whole number of
    /// periods (Table I: d = t_d / T) by the one rule of [`crate::Delay::from_time`].
    pub fn from_delay_time(period: f64, delay_time: f64) -> Result<Self> {
        positive(Param::Period, period)?;
        let delay = crate::Delay::from_time(delay_time, period)?;
        if delay.fraction > 0.0 {
            return Err(Error::FractionalDelay {
                delay_time,
                period,
                ratio: delay.in_samples(),
            });
        }
        Self::new(period, delay.samples)
    }

    /// The delay time t_d = d·T in seconds.
    pub fn delay_time(&self) -> f64 {
        self.delay as f64 * self.period
    }
}

/// Checks a delay in samples against [`MAX_DELAY`].
pub fn check_delay(delay: usize) -> Result<usize> {
    if delay > MAX_DELAY {
        Err(Error::DelayTooLarge {
            value: delay as f64,
            max: MAX_DELAY,
        })
    } else {
        Ok(delay)
    }
}

/// A complete physical description: device, arm, wall and sampling.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Physical {
    /// The effective plant of eq. (1).
    pub plant: Effective,
    /// The virtual wall.
    pub wall: Wall,
    /// Sampling period and delay.
    pub sampling: Sampling,
}

impl Physical {
    /// Validates and bundles the parts.
    pub fn new(plant: Effective, wall: Wall, sampling: Sampling) -> Result<Self> {
        let plant = Effective::new(plant.mass, plant.damping, plant.stiffness)?;
        finite(Param::WallStiffness, wall.stiffness)?;
        finite(Param::WallDamping, wall.damping)?;
        let sampling = Sampling::new(sampling.period, sampling.delay)?;
        Ok(Self {
            plant,
            wall,
            sampling,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::paper::{Normalized, PlantParams};

    #[test]
    fn validation_errors_name_the_parameter() {
        let e = Effective::new(-1.0, 0.0, 0.0).unwrap_err();
        assert!(e.to_string().contains("mass m"), "{e}");
        assert!(e.to_string().contains("-1"), "{e}");
        assert!(Sampling::new(0.0, 0).is_err());
        assert!(Normalized::new(f64::NAN, 0.0, 0.0, 0.0, 0).is_err());
        assert!(Normalized::new(0.0, 0.0, -1.0, 0.0, 0).is_err());
        // a mass so small that δ = bT/m overflows blames the mass, not δ
        let tiny = Effective::new(1e-320, 7.5, 350.0).unwrap();
        let e = PlantParams::from_physical(&tiny, 1e-3).unwrap_err();
        assert!(e.to_string().starts_with("mass m = 1e-320"), "{e}");
        let huge_k = Effective::new(1.0, 0.0, f64::MAX).unwrap();
        let e = PlantParams::from_physical(&huge_k, 10.0).unwrap_err();
        assert!(e.to_string().starts_with("stiffness k"), "{e}");
        let e = Sampling::from_delay_time(1e-3, 1.5e-3).unwrap_err();
        assert!(matches!(e, Error::FractionalDelay { .. }), "{e}");
        assert_eq!(Sampling::from_delay_time(1e-3, 3e-3).unwrap().delay, 3);
    }
}
