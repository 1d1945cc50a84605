//! Parameter ranges of real haptic systems (Section IV, eq. 11–15).
//!
//! The human-arm ratios of eq. (11), k_H/m_H < 710 s⁻² and b_H/m_H < 12.6 s⁻¹ (from the
//! values collected by Gil et al.), and the device ratio b_L/m_L < 0.625 s⁻¹ (Diolaiti et
//! al.) bound the normalized plant parameters through eq. (13):
//!
//! ```text
//! γ = T² k_H/(m_L + m_H) ≤ T² k_H/m_H               < 710 T²
//! δ = T (b_L + b_H)/(m_L + m_H) ≤ T (b_L/m_L + b_H/m_H) < 13.225 T        (eq. 14)
//! ```
//!
//! and, for T ≤ 1 ms with some margin for imprecise data, the extended range (15):
//! 0 ≤ γ < 1·10⁻³, 0 ≤ δ < 15·10⁻³.

use serde::Serialize;

use crate::error::{Error, Result, non_negative, positive};
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::{Arm, Device, Effective};

/// Upper bounds of the physical ratios that enter eq. (14).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct RatioLimits {
    /// Upper bound of k_H/m_H in s⁻² (eq. 11: 710).
    pub arm_stiffness_per_mass: f64,
    /// Upper bound of b_H/m_H in s⁻¹ (eq. 11: 12.6).
    pub arm_damping_per_mass: f64,
    /// Upper bound of b_L/m_L in s⁻¹ (Section IV, from [13]: 0.625).
    pub device_damping_per_mass: f64,
}

impl RatioLimits {
    /// The values of Section IV: eq. (11) for the arm and b_L/m_L < 0.625 s⁻¹ for the device.
    pub const PAPER: RatioLimits = RatioLimits {
        arm_stiffness_per_mass: 710.0,
        arm_damping_per_mass: 12.6,
        device_damping_per_mass: 0.625,
    };

    /// Validates custom limits (each finite and ≥ 0).
    pub fn new(
        arm_stiffness_per_mass: f64,
        arm_damping_per_mass: f64,
        device_damping_per_mass: f64,
    ) -> Result<Self> {
        Ok(Self {
            arm_stiffness_per_mass: non_negative(
                Param::ArmStiffnessPerMassLimit,
                arm_stiffness_per_mass,
            )?,
            arm_damping_per_mass: non_negative(
                Param::ArmDampingPerMassLimit,
                arm_damping_per_mass,
            )?,
            device_damping_per_mass: non_negative(
                Param::DeviceDampingPerMassLimit,
                device_damping_per_mass,
            )?,
        })
    }

    /// The damping coefficient of eq. (14): b_L/m_L + b_H/m_H bound (13.225 s⁻¹ for
    /// [`RatioLimits::PAPER`]).
    pub fn damping_per_mass(&self) -> f64 {
        self.arm_damping_per_mass + self.device_damping_per_mass
    }
}

/// The extended range of eq. (15), used by the paper for T ≤ 1 ms: γ < 1·10⁻³.
pub const EXTENDED_GAMMA_MAX: f64 = 1e-3;
/// The extended range of eq. (15): δ < 15·10⁻³.
pub const EXTENDED_DELTA_MAX: f64 = 15e-3;
/// The sampling period up to which eq. (15) covers eq. (14): T ≤ 1 ms (Section IV).
pub const EXTENDED_PERIOD_MAX: f64 = 1e-3;

/// The ranges of γ and δ for one sampling period (eq. 14) next to the extended range (15).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ranges {
    /// Sampling period T in s.
    pub period: f64,
    /// The ratio limits used.
    pub limits: RatioLimits,
    /// Upper bound of γ by eq. (14): T² · (k_H/m_H limit).
    pub gamma_max: f64,
    /// Upper bound of δ by eq. (14): T · (b_L/m_L + b_H/m_H limits).
    pub delta_max: f64,
    /// Upper bound of γ of the extended range (15).
    pub extended_gamma_max: f64,
    /// Upper bound of δ of the extended range (15).
    pub extended_delta_max: f64,
    /// True when the range (14) lies inside the extended range (15) (the case T ≤ 1 ms).
    pub within_extended: bool,
}

/// The γ and δ bounds of eq. (14) for sampling period T and given ratio limits, with the
/// extended range (15) (Section IV).
pub fn ranges_with(period: f64, limits: RatioLimits) -> Result<Ranges> {
    positive(Param::Period, period)?;
    let limits = RatioLimits::new(
        limits.arm_stiffness_per_mass,
        limits.arm_damping_per_mass,
        limits.device_damping_per_mass,
    )?;
    let gamma_max = period * period * limits.arm_stiffness_per_mass;
    let delta_max = period * limits.damping_per_mass();
    if !gamma_max.is_finite() || !delta_max.is_finite() {
        return Err(Error::OutOfRange {
            param: Param::Period,
            value: period,
            range: "a range where T²·(k_H/m_H) and T·(b/m) are finite",
        });
    }
    Ok(Ranges {
        period,
        limits,
        gamma_max,
        delta_max,
        extended_gamma_max: EXTENDED_GAMMA_MAX,
        extended_delta_max: EXTENDED_DELTA_MAX,
        within_extended: gamma_max <= EXTENDED_GAMMA_MAX && delta_max <= EXTENDED_DELTA_MAX,
    })
}

/// The γ and δ bounds of eq. (14) for the paper's ratio limits (eq. 11 and b_L/m_L < 0.625 s⁻¹):
/// γ < 710 T², δ < 13.225 T (Section IV).
pub fn ranges(period: f64) -> Result<Ranges> {
    ranges_with(period, RatioLimits::PAPER)
}

/// A concrete device and arm checked against eq. (12)–(13) (Section IV).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArmCheck {
    /// γ and δ of the combined plant by eq. (12).
    pub plant: PlantParams,
    /// The bound T² k_H/m_H of eq. (13) on γ (infinite when m_H = 0 < k_H, 0 when k_H = 0).
    pub gamma_bound: f64,
    /// The bound T (b_L/m_L + b_H/m_H) of eq. (13) on δ (terms with zero damping count 0).
    pub delta_bound: f64,
    /// k_H/m_H in s⁻² (0 when k_H = 0).
    pub arm_stiffness_per_mass: f64,
    /// b_H/m_H in s⁻¹ (0 when b_H = 0).
    pub arm_damping_per_mass: f64,
    /// b_L/m_L in s⁻¹ (0 when b_L = 0).
    pub device_damping_per_mass: f64,
    /// The arm's ratios satisfy eq. (11) and the device's b_L/m_L < 0.625 s⁻¹.
    pub within_paper_limits: bool,
}

fn ratio(num: f64, den: f64) -> f64 {
    if num == 0.0 {
        0.0
    } else if den == 0.0 {
        f64::INFINITY
    } else {
        num / den
    }
}

/// γ and δ of a device held by an arm (eq. 12) and the upper bounds of eq. (13), with a check
/// of the ratios against eq. (11) (Section IV).
pub fn check_arm(device: Device, arm: Arm, period: f64) -> Result<ArmCheck> {
    positive(Param::Period, period)?;
    let eff = Effective::combine(device, arm)?;
    let plant = PlantParams::from_physical(&eff, period)?;
    let ks = ratio(arm.stiffness, arm.mass);
    let bh = ratio(arm.damping, arm.mass);
    let bl = ratio(device.damping, device.mass);
    let l = RatioLimits::PAPER;
    Ok(ArmCheck {
        plant,
        gamma_bound: period * period * ks,
        delta_bound: period * (bl + bh),
        arm_stiffness_per_mass: ks,
        arm_damping_per_mass: bh,
        device_damping_per_mass: bl,
        within_paper_limits: ks < l.arm_stiffness_per_mass
            && bh < l.arm_damping_per_mass
            && bl < l.device_damping_per_mass,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_millisecond() {
        let r = ranges(1e-3).unwrap();
        assert!((r.gamma_max - 7.1e-4).abs() < 1e-18);
        assert!((r.delta_max - 13.225e-3).abs() < 1e-17);
        assert!(r.within_extended);
        assert!(!ranges(2e-3).unwrap().within_extended);
        assert!(ranges(0.0).is_err());
        assert!(ranges(f64::NAN).is_err());
    }

    #[test]
    fn eq13_bounds_hold_for_typical_arm() {
        let device = Device {
            mass: 0.1,
            damping: 0.05,
        };
        let c = check_arm(device, Arm::TYPICAL, 1e-3).unwrap();
        assert!(c.plant.gamma <= c.gamma_bound);
        assert!(c.plant.delta <= c.delta_bound);
        assert!(c.within_paper_limits);
        // Remark 4's PHANToM-like device has b_L/m_L = 15 s⁻¹, above the 0.625 s⁻¹ of [13].
        let ph = check_arm(Device::PHANTOM_LIKE, Arm::TYPICAL, 1e-3).unwrap();
        assert!(!ph.within_paper_limits);
        assert!(ph.plant.delta <= ph.delta_bound);
        let none = check_arm(Device::PHANTOM_LIKE, Arm::NONE, 1e-3).unwrap();
        assert_eq!(none.plant.gamma, 0.0);
        assert_eq!(none.gamma_bound, 0.0);
    }
}
