//! The paper's normalized view (Hulin, Preusche, Hirzinger, IROS 2008): the loop of Fig. 3
//! with one mass-spring-damper for device and arm, the backward-difference velocity and an
//! integer delay of d samples, in the dimensionless units of Table I,
//!
//! ```text
//! α = K T²/m,   β = B T/m,   γ = k T²/m,   δ = b T/m.
//! ```
//!
//! It is a change of units on the one engine, not a second one: [`NormalizedFamily`] is the
//! [`AffineFamily`] of [`Loop::normalized`] (m = T = 1, so that its wall units are (α, β)),
//! labelled with (γ, δ, d). The analyses that exist only for this plant live here:
//!
//! | module | paper |
//! |---|---|
//! | [`normalized`] | Table I: α, β, γ, δ, d ([`Normalized`], [`PlantParams`]) and their conversions |
//! | [`reference`](mod@reference) | Remark 2, eq. (10) evaluated literally, for comparison with the engine's exact discretization |
//! | [`ranges`] | Section IV, eq. (11)–(15): parameter ranges of real systems |
//! | [`linear`] | Sections VI–VII, eq. (16)–(24): the linear condition and its validity |
//! | [`nyquist`] | Section VIII, eq. (25)–(28): Nyquist frequency, robust stability, passivity |
//! | [`map`] | Section V: grid maps over two of α, β, γ, δ |
//!
//! Every other analysis takes any loop ([`crate::System`]); the paper's loop in physical
//! units is [`Loop::paper`].

use serde::Serialize;

use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::model::{Loop, PlantModel, VelocityEstimator};
use crate::params::{Effective, check_delay};
use crate::stability::Analysis;
use crate::verdict::{Verdict, decide};

pub mod linear;
pub mod map;
pub mod normalized;
pub mod nyquist;
pub mod ranges;
pub mod reference;

pub use normalized::{Normalized, PlantParams, wall_from_normalized};

/// The paper's family in normalized units (Table I): the [`AffineFamily`] of the loop
/// [`Loop::normalized`], so that (a, b) = (α, β), with the plant's (γ, δ) and the delay d
/// it was built for. It dereferences to the [`AffineFamily`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NormalizedFamily {
    /// The normalized plant (γ, δ).
    pub params: PlantParams,
    /// Delay d in samples.
    pub d: usize,
    /// The family through the general engine.
    pub family: AffineFamily,
}

impl std::ops::Deref for NormalizedFamily {
    type Target = AffineFamily;
    fn deref(&self) -> &AffineFamily {
        &self.family
    }
}

impl NormalizedFamily {
    /// Builds the family for plant parameters (γ, δ) and delay d (eq. 9 through the general
    /// discretization of [`crate::zoh`]).
    pub fn new(pp: PlantParams, d: usize) -> Result<Self> {
        check_delay(d)?;
        let lp = Loop::normalized(pp, d)?;
        Ok(Self {
            params: pp,
            d,
            family: AffineFamily::of_loop(&lp)?,
        })
    }

    /// Normalized arm-and-device stiffness γ.
    pub fn gamma(&self) -> f64 {
        self.params.gamma
    }

    /// Normalized damping δ.
    pub fn delta(&self) -> f64 {
        self.params.delta
    }

    /// The constant n0 of the plant's numerator N(z) = n1·z + n0 (eq. 5), read from the
    /// stiffness part PK = N(z)·z of p(z) (eq. 9 divided by −2c1γ).
    pub fn numerator_constant(&self) -> f64 {
        self.family.pk.get(1).copied().unwrap_or(0.0)
    }
}

/// The paper's normalized view of a loop: the façade's two hooks on [`Loop`].
impl Loop {
    /// The paper's loop in normalized units (Table I): m = 1, T = 1, so that the wall's
    /// (K, B) are exactly (α, β) and the plant is 1/(s² + δs + γ).
    pub fn normalized(pp: PlantParams, d: usize) -> Result<Self> {
        let pp = PlantParams::new(pp.gamma, pp.delta)?;
        Self::paper(Effective::new(1.0, pp.delta, pp.gamma)?, 1.0, d)
    }

    /// The (γ, δ) of Table I when the plant is the paper's mass-spring-damper without lag and
    /// the velocity is the backward difference: the loops that have the paper's normalized
    /// view. None otherwise.
    pub fn paper_view(&self) -> Option<PlantParams> {
        match (&self.plant.model, &self.velocity) {
            (PlantModel::MassSpringDamper(e), VelocityEstimator::Backward)
                if self.plant.force_lag == 0.0 && self.delay.fraction == 0.0 =>
            {
                PlantParams::from_physical(e, self.period).ok()
            }
            _ => None,
        }
    }
}

impl Analysis {
    /// Runs the point test and the root finder on the paper's loop at the point `params` of
    /// Table I ([`Analysis::of_family`] on its [`NormalizedFamily`], Section V).
    pub fn new(params: Normalized) -> Result<Self> {
        let params = params.validated()?;
        let fam = NormalizedFamily::new(params.plant(), params.d)?;
        Self::of_family(&fam, params.alpha, params.beta)
    }
}

/// Stability of the paper's loop at one point of Table I by the one verdict
/// ([`crate::verdict::decide`]): true iff stable (a marginal wall is not).
pub fn is_stable(params: &Normalized) -> Result<bool> {
    let params = params.validated()?;
    let fam = NormalizedFamily::new(params.plant(), params.d)?;
    let mut c = fam.coefficients(params.alpha, params.beta);
    Ok(decide(&fam, params.alpha, params.beta, &mut c).verdict == Verdict::Stable)
}
