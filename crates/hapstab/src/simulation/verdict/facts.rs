//! What the classifier is told: the loop (which nonlinear effects are configured, the
//! linear analysis as a reference) and each sample.

use serde::Serialize;

use crate::stability::Verdict as LinearVerdict;

/// The analysis of the loop while the wall acts linearly (Section V), as a reference for
/// linear windows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearReference {
    /// Spectral radius of the closed loop.
    pub spectral_radius: f64,
    /// Stable, marginal or unstable.
    pub verdict: LinearVerdict,
}

/// What the classifier needs to know about the loop, independent of its plant model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LoopFacts {
    /// The wall acts only in contact (unilateral): contact may be lost.
    pub contact_can_be_lost: bool,
    /// The wall force is limited (saturation).
    pub force_limited: bool,
    /// Friction or quantization is configured: the loop is never linear.
    pub static_nonlinearity: bool,
    /// Encoder step q in m, to give amplitudes in counts.
    pub quantum: Option<f64>,
    /// Sampling period T in s, for frequencies.
    pub period: f64,
    /// The analysis of the loop in linear contact, if available.
    pub linear: Option<LinearReference>,
}

/// One sample as the classifier sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleFacts {
    /// Position in m (positive into the wall).
    pub position: f64,
    /// Velocity in any fixed unit (only ratios and signs are used).
    pub velocity: f64,
    /// The wall acts on this sample (always true for a bilateral wall).
    pub in_contact: bool,
    /// The wall force equals the linear bilateral law on this sample (in contact, not clamped,
    /// not saturated).
    pub linear: bool,
}
