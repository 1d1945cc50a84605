//! Passivity of the sampled virtual wall (Section VIII, eq. 28, generalized to any loop):
//! the device damping b that Colgate and Schenkel's condition requires, the verdict for a
//! given device, and the passive region in the (K, B)-plane.
//!
//! # The condition (Colgate & Schenkel 1997)
//!
//! A device of mass m and viscous damping b renders, through a zero-order hold, the discrete
//! wall H(z) = z^{−d}·(K + B·V(z)) (V the velocity estimator, d whole samples of delay). The
//! human can impose any motion. Between two samples the force is constant, so the wall
//! absorbs F_k·(x_{k+1} − x_k), while the damper dissipates at least b·(x_{k+1} − x_k)²/T
//! (equality for a constant velocity within the sample). By Parseval the display is passive
//! iff, for every 0 < θ = ωT ≤ π,
//!
//! ```text
//! b ≥ (T/2) · Re{(1 − e^{−jθ}) H(e^{jθ})} / (1 − cos θ)                       (C–S)
//! ```
//!
//! For the paper's loop (backward difference, d = 0) the right side is KT/2 − B·cos θ, whose
//! maximum is KT/2 + |B|: eq. (28), δ > α/2 + |β| in normalized units. The frequency condition
//! weighs the energy exchanged by a motion; a wall whose static stiffness W(1) = K + B·V(1)
//! is negative also releases the energy ½|W(1)|x² stored at an offset, so passivity further
//! needs W(1) ≥ 0 (the paper states eq. 28 for α ≥ 0).
//!
//! # Evaluation without cancellation
//!
//! Numerator and denominator of (C–S) both vanish like θ² as θ → 0. With
//! 1 − e^{−jθ} = 2j·sin(θ/2)·e^{−jθ/2} and 1 − cos θ = 2 sin²(θ/2) the ratio is
//!
//! ```text
//! Re{(1 − e^{−jθ})H}/(1 − cos θ) = Re X·sin((d + ½)θ)/sin(θ/2) − Im X·cos((d + ½)θ)/sin(θ/2),
//! ```
//!
//! X = K + B·V the wall without its delay. The first factor is the Dirichlet kernel (2d + 1
//! at θ = 0); Im X/sin(θ/2) is formed from the filter's coefficient correlation
//! c_m (X = Σ c_m e^{−jmθ}/|den|²) as −Σ c_m·sin(mθ)/sin(θ/2), each quotient accurate to a few ulps
//! and equal to 2m at θ = 0. No difference of nearly equal numbers is formed for any θ, and
//! θ = 0 itself is evaluated exactly (the ratio's finite limit).
//!
//! # A fractional delay: derived, not refused
//!
//! With t_d = (d + λ)T the hold is moved by λT: over sample k the force is F_{k−d−1} on
//! [kT, kT + λT) and F_{k−d} on [kT + λT, (k + 1)T) (as in [`crate::zoh`]). The wall's energy
//! then depends on the position y_k at kT + λT too, which the human chooses freely. Repeating
//! the argument above with constant velocities on both parts of the sample (the damper then
//! dissipates b(y_k − x_k)²/(λT) + b(x_{k+1} − y_k)²/((1 − λ)T), its least for those
//! positions) and minimizing the energy over y at every frequency gives, exactly,
//!
//! ```text
//! b ≥ (T/2)·(q + √(q² + λ(1 − λ)·|X(e^{jθ})|²)),
//! q = ½·Re{(1 − e^{−jθ}) z^{−d} X M}/(1 − cos θ),  M = (1 − λ) + λ·e^{−jθ},
//! ```
//!
//! where M interpolates linearly between the delays d and d + 1 and the square root is the
//! energy the human can pump in by moving within the sample. At λ → 0 this is max(C–S, 0),
//! at λ → 1 the condition for d + 1 whole samples: continuous in the delay. (For λ > 0 every
//! wall needs b > 0; at λ = 0 a wall with negative stiffness may formally allow b < 0.)
//!
//! # The maximum over frequency
//!
//! The requirement is the maximum over 0 ≤ θ ≤ π, found exactly: the function is sampled on
//! a grid fine for its oscillations (64 samples per half-turn of the delay's and the filter's
//! phase, refined around the filter's poles near the unit circle), every local maximum whose
//! parabolic estimate can reach the grid maximum is refined by golden-section search, and the
//! ends θ = 0 (exact limit) and θ = π compete as well. The value is exact to rounding (the
//! function is flat at an interior maximum, so an error δθ in the frequency changes it by
//! O(δθ²)); the binding frequency is accurate to about 1e-8 relative.
//!
//! # The largest passive stiffness
//!
//! b_required is convex and positively homogeneous in (K, B), so the passive region is convex
//! and its largest K is b / min_β b_required(1, β), a convex minimization in one variable
//! that [`passive_k_max`] solves with a certified bound (about ten evaluations of the
//! requirement); at one damping, [`k_max_passive_at`] bisects on K.

mod device;
mod region;
mod requirement;
mod stiffness;

use serde::Serialize;

use crate::error::Result;
use crate::model::Loop;
use crate::params::Wall;

pub use device::{DeviceDamping, device_damping};
pub use region::{PASSIVE_REL_TOL, PassiveRegion, UNBOUNDED_CLIP, passive_region};
pub use requirement::{DampingRequirement, SampledWall};
pub use stiffness::{k_max_passive_at, passive_k_max};

/// Relative width of the band |b − b_required| ≤ BOUNDARY_BAND·scale in which a device is
/// reported as on the passivity boundary rather than passive or not: the requirement is exact
/// to a few ulps, so 1e-12 only absorbs rounding.
pub const BOUNDARY_BAND: f64 = 1e-12;

/// Whether the display is passive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PassivityVerdict {
    /// b > b_required and W(1) >= 0.
    Passive,
    /// b = b_required within [`BOUNDARY_BAND`].
    Boundary,
    /// b < b_required, or the wall's static stiffness is negative.
    NotPassive,
    /// The condition does not apply to this plant (see [`DeviceDamping`]).
    NotApplicable,
}

impl PassivityVerdict {
    /// The verdict's name in every report (its serde name).
    pub fn as_str(self) -> &'static str {
        match self {
            PassivityVerdict::Passive => "passive",
            PassivityVerdict::Boundary => "boundary",
            PassivityVerdict::NotPassive => "not_passive",
            PassivityVerdict::NotApplicable => "not_applicable",
        }
    }

    /// Whether the wall meets Colgate's condition (eq. 28) as every report states it: true
    /// when passive, false on the boundary or below it, None where it does not apply.
    pub fn meets(self) -> Option<bool> {
        match self {
            PassivityVerdict::NotApplicable => None,
            v => Some(v == PassivityVerdict::Passive),
        }
    }
}

/// The passivity of one wall on one loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Passivity {
    /// The wall (K in N/m, B in Ns/m).
    pub wall: Wall,
    /// The required device damping and its binding frequency.
    pub requirement: DampingRequirement,
    /// The wall's static stiffness W(1) = K + B·V(1) in N/m (must be >= 0).
    pub dc_stiffness: f64,
    /// The device's damping.
    pub device: DeviceDamping,
    /// The verdict.
    pub verdict: PassivityVerdict,
    /// The paper's eq. (28) read with the effective damping b = b_L + b_H of eq. (1), the arm
    /// included, when the plant names its operator: passivity towards this operator only, not
    /// towards any passive operator (the relation of the paper's robust region).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub with_arm: Option<ArmPassivity>,
}

/// Eq. (28) with the arm's damping counted (see [`Passivity::with_arm`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArmPassivity {
    /// The effective damping b = b_L + b_H in Ns/m.
    pub damping: f64,
    /// The verdict of the same requirement against b.
    pub verdict: PassivityVerdict,
}

/// Passivity of a wall on a loop (Colgate–Schenkel; eq. 28 for the paper's loop): the
/// required device damping, the device's damping and the verdict.
pub fn passivity(lp: &Loop, wall: Wall) -> Result<Passivity> {
    let sw = SampledWall::new(lp)?;
    Ok(passivity_with(&sw, lp, wall))
}

/// As [`passivity`] with the wall structure already built: the verdict for the device's own
/// damping, and eq. (28) with the arm's damping counted when the plant names its operator.
pub fn passivity_with(sw: &SampledWall, lp: &Loop, wall: Wall) -> Passivity {
    let mut p = passivity_of_device(sw, wall, device_damping(&lp.plant));
    if p.verdict == PassivityVerdict::NotApplicable {
        return p;
    }
    p.with_arm = lp.plant.effective_damping().map(|damping| ArmPassivity {
        damping,
        verdict: verdict_for(damping, p.requirement.b_required, p.dc_stiffness),
    });
    p
}

/// Passivity of a wall for a given device damper (Colgate–Schenkel; eq. 28 for the paper's
/// loop): the requirement of the wall structure `sw` against `device`, e.g. a damping other
/// than the plant's own [`device_damping`] ("would a device with b = … render it passively?").
pub fn passivity_of_device(sw: &SampledWall, wall: Wall, device: DeviceDamping) -> Passivity {
    let requirement = sw.required_damping(wall);
    let dc_stiffness = sw.dc_stiffness(wall);
    let verdict = match &device {
        DeviceDamping::NotApplicable { .. } => PassivityVerdict::NotApplicable,
        DeviceDamping::Known { damping } => {
            verdict_for(*damping, requirement.b_required, dc_stiffness)
        }
    };
    Passivity {
        wall,
        requirement,
        dc_stiffness,
        device,
        verdict,
        with_arm: None,
    }
}

fn verdict_for(b: f64, required: f64, dc_stiffness: f64) -> PassivityVerdict {
    if dc_stiffness < 0.0 {
        return PassivityVerdict::NotPassive;
    }
    let band = BOUNDARY_BAND * b.abs().max(required.abs());
    if (b - required).abs() <= band {
        PassivityVerdict::Boundary
    } else if b > required {
        PassivityVerdict::Passive
    } else {
        PassivityVerdict::NotPassive
    }
}
