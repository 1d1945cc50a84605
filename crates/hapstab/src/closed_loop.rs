//! The closed loop of Fig. 3: characteristic polynomial p(z) (eq. 7–9) and the transfer
//! function G_x(z) from force to position (eq. 7).
//!
//! With the plant N(z)/D(z) of [`crate::plant`] and the controller α + β(z − 1)/z delayed by
//! z^{−d}, the loop closes on
//!
//! ```text
//! p(z) = z^{d+1} D(z) + N(z) ((α + β) z − β),      degree d + 3, monic,
//! ```
//!
//! which is the paper's eq. (9) divided by its leading coefficient −2c1γ.

use num_complex::Complex64;
use serde::Serialize;

use crate::error::Result;
use crate::params::{Normalized, PlantParams, check_delay};
use crate::plant::DiscretePlant;

/// p(z) split by the wall parameters, p = P0 + α Pα + β Pβ (each ascending coefficients):
/// P0 = z^{d+1} D(z), Pα = z N(z), Pβ = (z − 1) N(z). The D-decomposition of
/// [`crate::boundary`] rests on this linearity in α and β.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PolyFamily {
    /// The plant.
    pub plant: DiscretePlant,
    /// Delay d in samples.
    pub d: usize,
}

impl PolyFamily {
    /// Builds the family for plant parameters (γ, δ) and delay d.
    pub fn new(pp: PlantParams, d: usize) -> Result<Self> {
        check_delay(d)?;
        Ok(Self {
            plant: DiscretePlant::from_params(pp),
            d,
        })
    }

    /// Degree d + 3 of p(z).
    pub fn degree(&self) -> usize {
        self.d + 3
    }

    /// Writes the ascending coefficients of p(z) for (α, β) into `out` (length d + 4).
    pub fn coefficients_into(&self, alpha: f64, beta: f64, out: &mut [f64]) {
        let n = self.degree();
        let pl = &self.plant;
        out[..=n].fill(0.0);
        // z^{d+1} (z² − a1 z + a0)
        out[n] = 1.0;
        out[n - 1] = -pl.a1;
        out[n - 2] = pl.a0;
        // (n1 z + n0)((α + β) z − β)
        let ab = alpha + beta;
        out[2] += pl.n1 * ab;
        out[1] += pl.n0 * ab - pl.n1 * beta;
        out[0] += -pl.n0 * beta;
    }

    /// The ascending coefficients of p(z) for (α, β) (eq. 9 up to a constant factor).
    pub fn coefficients(&self, alpha: f64, beta: f64) -> Vec<f64> {
        let mut c = vec![0.0; self.degree() + 1];
        self.coefficients_into(alpha, beta, &mut c);
        c
    }

    /// Evaluates (P0(z), Pα(z), Pβ(z)) at a complex point.
    pub fn parts_at(&self, z: Complex64) -> (Complex64, Complex64, Complex64) {
        let pl = &self.plant;
        let nz = pl.numerator(z);
        let p0 = z.powu(self.d as u32 + 1) * pl.denominator(z);
        (p0, z * nz, (z - 1.0) * nz)
    }

    /// p(z) at a complex point.
    pub fn eval(&self, alpha: f64, beta: f64, z: Complex64) -> Complex64 {
        let (p0, pa, pb) = self.parts_at(z);
        p0 + pa * alpha + pb * beta
    }

    /// p(1) = N(1)(α + γ) evaluated without cancellation (Section V: the left boundary
    /// α = −γ is a root at z = 1).
    pub fn value_at_one(&self, alpha: f64) -> f64 {
        self.plant.numerator_at_one() * (alpha + self.plant.gamma)
    }
}

/// The closed loop for one parameter set.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ClosedLoop {
    /// Parameters.
    pub params: Normalized,
    /// Family (plant and delay).
    pub family: PolyFamily,
    /// Ascending coefficients of the monic characteristic polynomial p(z), degree d + 3.
    pub poly: Vec<f64>,
}

impl ClosedLoop {
    /// Builds p(z) of eq. (9) for normalized parameters.
    pub fn new(params: Normalized) -> Result<Self> {
        let params = params.validated()?;
        let family = PolyFamily::new(params.plant(), params.d)?;
        let poly = family.coefficients(params.alpha, params.beta);
        Ok(Self {
            params,
            family,
            poly,
        })
    }

    /// G_x(z) of eq. (7) in normalized units: x/F = (T²/m) · z^{1+d} N(z) / p(z); this returns
    /// z^{1+d} N(z)/p(z).
    pub fn gx(&self, z: Complex64) -> Complex64 {
        let num = z.powu(self.params.d as u32 + 1) * self.family.plant.numerator(z);
        num / self.family.eval(self.params.alpha, self.params.beta, z)
    }
}
