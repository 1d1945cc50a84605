//! Passivity of a sampled virtual spring with position quantization and Coulomb friction:
//! the closed forms of Abbott and Okamura (IEEE Trans. Robotics 21(5), 2005, "Effects of
//! position quantization and sampling rate on virtual-wall passivity") and, for a delay, of
//! Diolaiti, Niemeyer, Barbagli and Salisbury (IEEE Trans. Robotics 22(2), 2006, "Stability of
//! haptic rendering: discretization, quantization, time delay, and Coulomb effects").
//!
//! **Model (Abbott and Okamura's assumptions).** A single mass m with viscous damping b and
//! Coulomb friction f_c, pushed by the human and by the actuator; one sensor, an encoder of
//! resolution Δ; the wall a pure spring F = K·q(x_k) of the quantized sampled position,
//! held over each sample (zero-order hold), no virtual damping (B = 0) and no delay (d = 0).
//! Their main result, necessary and sufficient for passivity with no assumption on the
//! human, is
//!
//! ```text
//! K ≤ 2b/T        (sampling: the held force lags the motion; Colgate–Schenkel, eq. 28 with B = 0)
//! K ≤ 2f_c/Δ      (quantization: a stale quantized level across one encoder edge)
//! ```
//!
//! both at once, K ≤ min(2b/T, 2f_c/Δ). The energy argument: a stroke of length L across an
//! encoder edge while the force is still at the level on the other side creates at most K·Δ·L
//! (the levels differ by KΔ), and Coulomb friction dissipates f_c·L per stroke, 2f_c·L over an
//! in-and-out cycle; a long stroke within one sample creates K·L²/2, which viscous damping
//! dissipates as b·L²/T at the least.
//!
//! **Beyond them.** With d whole samples of delay the sampling condition becomes
//! K ≤ 2b/(T + 2dT) (Diolaiti et al.'s energy condition b > K(T/2 + t_d); hapstab's
//! [`crate::passivity`] evaluates the same for any estimator); with a virtual damper B it is
//! b > KT/2 + |B| for d = 0 (eq. 28). The quantization bound 2f_c/Δ is stated by Abbott and
//! Okamura for B = 0 and d = 0 only: for other walls it is reported, flagged as outside the
//! published assumptions.
//!
//! The equation numbers of the two papers could not be checked against their text here: the
//! conditions are cited by the papers' main results as stated above.

use serde::Serialize;

use crate::error::{Result, finite, non_negative, positive};
use crate::param::Param;

/// A sampled virtual wall on a device with friction and an encoder.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QuantizedWall {
    /// Wall stiffness K in N/m (>= 0).
    pub stiffness: f64,
    /// Wall damping B in Ns/m (the published closed forms assume 0).
    pub damping: f64,
    /// Sampling period T in s (> 0).
    pub period: f64,
    /// Whole samples of delay d of the wall force.
    pub delay: usize,
    /// The device's viscous damping b in Ns/m (>= 0).
    pub device_damping: f64,
    /// The device's Coulomb friction f_c in N (>= 0).
    pub coulomb: f64,
    /// The encoder resolution Δ in m (> 0).
    pub quantization: f64,
}

/// Which condition of [`quantized_passivity`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ConditionKind {
    /// The sampling condition b > K(T/2 + dT) + |B|, i.e. K ≤ 2(b − |B|)/(T + 2dT).
    Sampling,
    /// The quantization condition K ≤ 2f_c/Δ.
    Quantization,
}

/// One condition: its closed-form bound on K and whether the wall meets it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Condition {
    /// Which one.
    pub kind: ConditionKind,
    /// The largest passive K in N/m by this condition (−∞ when no K ≥ 0 meets it).
    pub k_bound: f64,
    /// K ≤ k_bound.
    pub met: bool,
    /// True when the wall lies within the published assumptions of this closed form.
    pub within_assumptions: bool,
    /// The source of the closed form, in words.
    pub source: &'static str,
}

/// The verdict of [`quantized_passivity`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum QuantizedVerdict {
    /// Every condition met, within the published assumptions.
    Passive,
    /// Some condition violated (for a condition within its assumptions: not passive).
    NotPassive,
    /// Every condition met, but a closed form was applied outside its assumptions.
    PassiveOutsideAssumptions,
}

/// Both conditions, the bound that binds, and the verdict.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct QuantizedPassivity {
    /// The sampling condition.
    pub sampling: Condition,
    /// The quantization condition.
    pub quantization: Condition,
    /// min of the two bounds: the largest passive K, N/m.
    pub k_max: f64,
    /// The condition whose bound is the smaller (the sampling one on a tie).
    pub binding: ConditionKind,
    /// The verdict.
    pub verdict: QuantizedVerdict,
}

/// Abbott and Okamura's sampling bound 2b/T generalized by Diolaiti et al. to a delay and by
/// eq. 28 to a damper: K ≤ 2(b − |B|)/(T + 2dT) (module doc).
pub fn sampling_bound(w: &QuantizedWall) -> f64 {
    let span = w.period * (1.0 + 2.0 * w.delay as f64);
    let spare = w.device_damping - w.damping.abs();
    if spare < 0.0 {
        f64::NEG_INFINITY
    } else {
        2.0 * spare / span
    }
}

/// Abbott and Okamura's quantization bound K ≤ 2f_c/Δ (module doc).
pub fn quantization_bound(w: &QuantizedWall) -> f64 {
    2.0 * w.coulomb / w.quantization
}

fn validated(w: &QuantizedWall) -> Result<QuantizedWall> {
    non_negative(Param::WallStiffness, w.stiffness)?;
    finite(Param::WallDamping, w.damping)?;
    positive(Param::Period, w.period)?;
    non_negative(Param::DeviceDamping, w.device_damping)?;
    non_negative(Param::CoulombFriction, w.coulomb)?;
    positive(Param::Quantization, w.quantization)?;
    Ok(*w)
}

/// The passivity of a quantized sampled spring on a device with viscous and Coulomb friction
/// by the closed forms of Abbott and Okamura (2005) (K ≤ min(2b/T, 2f_c/Δ), for B = 0, d = 0)
/// and Diolaiti et al. (2006) (the sampling bound with a delay, K ≤ 2b/(T + 2t_d)): each
/// condition with its bound, the one that binds, and the verdict (module doc). Errors name
/// a parameter out of range (K, b, f_c ≥ 0; T, Δ > 0; B finite).
pub fn quantized_passivity(wall: &QuantizedWall) -> Result<QuantizedPassivity> {
    let w = validated(wall)?;
    let abbott = w.damping == 0.0 && w.delay == 0;
    let sampling = Condition {
        kind: ConditionKind::Sampling,
        k_bound: sampling_bound(&w),
        met: w.stiffness <= sampling_bound(&w),
        within_assumptions: w.delay == 0 || w.damping == 0.0,
        source: if w.delay == 0 {
            "Abbott & Okamura 2005 (K ≤ 2b/T); with B: Colgate–Schenkel, b > KT/2 + |B|"
        } else {
            "Diolaiti et al. 2006, b > K(T/2 + t_d)"
        },
    };
    let quantization = Condition {
        kind: ConditionKind::Quantization,
        k_bound: quantization_bound(&w),
        met: w.stiffness <= quantization_bound(&w),
        within_assumptions: abbott,
        source: "Abbott & Okamura 2005 (K ≤ 2f_c/Δ, for B = 0 and d = 0)",
    };
    let binding = if quantization.k_bound < sampling.k_bound {
        ConditionKind::Quantization
    } else {
        ConditionKind::Sampling
    };
    let verdict = if !(sampling.met && quantization.met) {
        QuantizedVerdict::NotPassive
    } else if sampling.within_assumptions && quantization.within_assumptions {
        QuantizedVerdict::Passive
    } else {
        QuantizedVerdict::PassiveOutsideAssumptions
    };
    Ok(QuantizedPassivity {
        sampling,
        quantization,
        k_max: sampling.k_bound.min(quantization.k_bound),
        binding,
        verdict,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall(k: f64) -> QuantizedWall {
        QuantizedWall {
            stiffness: k,
            damping: 0.0,
            period: 1e-3,
            delay: 0,
            device_damping: 2.0,
            coulomb: 0.1,
            quantization: 1e-4,
        }
    }

    #[test]
    fn abbott_okamura_closed_forms() {
        // 2b/T = 4000 N/m, 2f_c/Δ = 2000 N/m: quantization binds
        let p = quantized_passivity(&wall(1999.0)).unwrap();
        assert_eq!(p.sampling.k_bound, 4000.0);
        assert_eq!(p.quantization.k_bound, 2000.0);
        assert_eq!(p.k_max, 2000.0);
        assert_eq!(p.binding, ConditionKind::Quantization);
        assert_eq!(p.verdict, QuantizedVerdict::Passive);
        let q = quantized_passivity(&wall(2001.0)).unwrap();
        assert_eq!(q.verdict, QuantizedVerdict::NotPassive);
        assert!(!q.quantization.met && q.sampling.met);
    }

    #[test]
    fn delay_and_damping_move_the_sampling_bound() {
        let mut w = wall(100.0);
        w.delay = 2;
        // 2b/(T + 2dT) = 4/(5e-3) = 800 N/m
        let p = quantized_passivity(&w).unwrap();
        assert!((p.sampling.k_bound - 800.0).abs() < 1e-9);
        assert_eq!(p.verdict, QuantizedVerdict::PassiveOutsideAssumptions);
        let mut w = wall(100.0);
        w.damping = 2.5;
        let p = quantized_passivity(&w).unwrap();
        assert_eq!(p.sampling.k_bound, f64::NEG_INFINITY);
        assert_eq!(p.verdict, QuantizedVerdict::NotPassive);
    }

    #[test]
    fn bad_values_are_errors() {
        let mut w = wall(1.0);
        w.quantization = 0.0;
        assert!(quantized_passivity(&w).is_err());
        let mut w = wall(1.0);
        w.coulomb = f64::NAN;
        assert!(quantized_passivity(&w).is_err());
        assert!(quantized_passivity(&wall(-1.0)).is_err());
    }
}
