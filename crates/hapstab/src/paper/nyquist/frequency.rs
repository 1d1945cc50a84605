//! The oscillation frequency of a mass-spring-damper (eq. 25, 26), the γ at which it reaches
//! the Nyquist frequency (eq. 27), and the physical stiffness that brings a device there
//! (Remark 4).

use serde::Serialize;

use crate::error::{Result, finite, non_negative, positive};
use crate::param::Param;

use std::f64::consts::PI;

/// Oscillation frequency of eq. (25) in rad/s, ω = √(k/m − b²/(4m²)), for k/m > b²/(4m²)
/// (under-damped); None otherwise.
pub fn oscillation_frequency(mass: f64, damping: f64, stiffness: f64) -> Option<f64> {
    let w2 = stiffness / mass - damping * damping / (4.0 * mass * mass);
    (w2 > 0.0 && w2.is_finite()).then(|| w2.sqrt())
}

/// Oscillation frequency of eq. (26) in rad/s from normalized parameters:
/// ω = √(γ − δ²/4)/T for γ > δ²/4; None otherwise.
pub fn normalized_frequency(gamma: f64, delta: f64, period: f64) -> Option<f64> {
    let w2 = gamma - delta * delta / 4.0;
    (w2 > 0.0 && w2.is_finite() && period > 0.0).then(|| w2.sqrt() / period)
}

/// The γ at which the plant oscillates at the Nyquist frequency π/T, eq. (27):
/// γ_N = π² + δ²/4.
pub fn nyquist_gamma(delta: f64) -> f64 {
    PI * PI + delta * delta / 4.0
}

/// Remark 4: the physical stiffness that brings a device to the Nyquist frequency.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct NyquistStiffness {
    /// Mass m in kg.
    pub mass: f64,
    /// Damping b in Ns/m.
    pub damping: f64,
    /// Sampling period T in s.
    pub period: f64,
    /// k = π² m/T² + b²/(4m) in N/m.
    pub stiffness: f64,
    /// δ = bT/m.
    pub delta: f64,
    /// γ_N = π² + δ²/4 (eq. 27).
    pub gamma: f64,
    /// The Nyquist frequency π/T in rad/s.
    pub nyquist_frequency: f64,
}

/// Remark 4: k = π² m/T² + b²/(4m), the stiffness at which a mass m with damping b sampled at
/// period T oscillates at the Nyquist frequency (≈ 987.0 kN/m for m = 0.1 kg, T = 1 ms,
/// b = 1.5 Ns/m).
pub fn nyquist_stiffness(mass: f64, damping: f64, period: f64) -> Result<NyquistStiffness> {
    positive(Param::Mass, mass)?;
    non_negative(Param::Damping, damping)?;
    positive(Param::Period, period)?;
    let stiffness = PI * PI * mass / (period * period) + damping * damping / (4.0 * mass);
    finite(Param::Stiffness, stiffness)?;
    let delta = damping * period / mass;
    Ok(NyquistStiffness {
        mass,
        damping,
        period,
        stiffness,
        delta,
        gamma: nyquist_gamma(delta),
        nyquist_frequency: PI / period,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn remark4_value() {
        let r = nyquist_stiffness(0.1, 1.5, 1e-3).unwrap();
        // π²·0.1/1e-6 + 1.5²/(4·0.1) = 986960.44 + 5.625
        assert!((r.stiffness - 986_966.065).abs() < 1e-2, "{}", r.stiffness);
        assert!((r.stiffness / 1e3 - 987.0).abs() < 0.05);
        let w = oscillation_frequency(0.1, 1.5, r.stiffness).unwrap();
        assert!((w - PI / 1e-3).abs() < 1e-9 * w);
        let wn = normalized_frequency(r.gamma, r.delta, 1e-3).unwrap();
        assert!((wn - PI / 1e-3).abs() < 1e-9 * wn);
        assert!(nyquist_stiffness(0.0, 1.0, 1e-3).is_err());
        assert!(nyquist_stiffness(0.1, -1.0, 1e-3).is_err());
    }
}
