//! The dimensionless parameters of Table I: the plant's γ = kT²/m (eq. 4) and δ = bT/m, the
//! wall's α = KT²/m and β = BT/m, and the delay d = t_d/T, with their validation and the
//! conversions from and to the physical parameters of Section II ([`Physical`]).

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result, finite, non_negative, positive};
use crate::param::Param;
use crate::params::{Effective, Physical, Sampling, Wall, check_delay};

impl Physical {
    /// The dimensionless parameters of Table I. Values that overflow are refused naming the
    /// physical parameter to blame.
    pub fn normalized(&self) -> Result<Normalized> {
        let (m, t) = (self.plant.mass, self.sampling.period);
        let plant = PlantParams::from_physical(&self.plant, t)?;
        let alpha = per_mass(
            "α = KT²/m",
            [
                (Param::WallStiffness, self.wall.stiffness.abs()),
                (Param::Period, t),
            ],
            2,
            m,
        )?;
        let beta = per_mass(
            "β = BT/m",
            [
                (Param::WallDamping, self.wall.damping.abs()),
                (Param::Period, t),
            ],
            1,
            m,
        )?;
        Normalized::new(
            alpha.copysign(self.wall.stiffness),
            beta.copysign(self.wall.damping),
            plant.gamma,
            plant.delta,
            self.sampling.delay,
        )
    }
}

/// x·Tᵖ/m for a physical quantity x ≥ 0 (Table I), refused when it is not finite: the blame
/// goes to x or T when x·Tᵖ alone overflows, else to the mass m.
fn per_mass(
    derived: &'static str,
    [(x_name, x), (t_name, t)]: [(Param, f64); 2],
    power: i32,
    mass: f64,
) -> Result<f64> {
    let num = x * t.powi(power);
    let result = num / mass;
    if result.is_finite() {
        return Ok(result);
    }
    let (name, value) = if num.is_finite() {
        (Param::Mass, mass)
    } else if x >= t {
        (x_name, x)
    } else {
        (t_name, t)
    };
    Err(Error::Unrepresentable {
        param: name,
        value,
        derived,
        result,
    })
}

/// The plant part of the normalized parameters: γ = kT²/m (eq. 4) and δ = bT/m (Table I).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PlantParams {
    /// Normalized physical stiffness γ = kT²/m (>= 0).
    pub gamma: f64,
    /// Normalized physical damping δ = bT/m (>= 0).
    pub delta: f64,
}

impl PlantParams {
    /// Validates γ >= 0 and δ >= 0, both finite.
    pub fn new(gamma: f64, delta: f64) -> Result<Self> {
        Ok(Self {
            gamma: non_negative(Param::Gamma, gamma)?,
            delta: non_negative(Param::Delta, delta)?,
        })
    }

    /// γ and δ of an effective plant sampled with period T (Table I, eq. 4). A plant whose
    /// γ or δ overflows is refused naming the physical parameter (e.g. a mass so small that
    /// bT/m is infinite).
    pub fn from_physical(plant: &Effective, period: f64) -> Result<Self> {
        positive(Param::Period, period)?;
        let gamma = per_mass(
            "γ = kT²/m",
            [(Param::Stiffness, plant.stiffness), (Param::Period, period)],
            2,
            plant.mass,
        )?;
        let delta = per_mass(
            "δ = bT/m",
            [(Param::Damping, plant.damping), (Param::Period, period)],
            1,
            plant.mass,
        )?;
        Self::new(gamma, delta)
    }
}

/// The five dimensionless parameters of Table I: α = KT²/m, β = BT/m, γ = kT²/m, δ = bT/m,
/// d = t_d/T.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Normalized {
    /// Normalized virtual stiffness α = KT²/m (any finite value).
    pub alpha: f64,
    /// Normalized virtual damping β = BT/m (any finite value).
    pub beta: f64,
    /// Normalized physical stiffness γ = kT²/m (>= 0).
    pub gamma: f64,
    /// Normalized physical damping δ = bT/m (>= 0).
    pub delta: f64,
    /// Delay in samples d = t_d/T.
    pub d: usize,
}

impl Normalized {
    /// Validates: α, β finite; γ, δ finite and >= 0; d <= [`MAX_DELAY`](crate::params::MAX_DELAY).
    pub fn new(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize) -> Result<Self> {
        finite(Param::Alpha, alpha)?;
        finite(Param::Beta, beta)?;
        let plant = PlantParams::new(gamma, delta)?;
        check_delay(d)?;
        Ok(Self {
            alpha,
            beta,
            gamma: plant.gamma,
            delta: plant.delta,
            d,
        })
    }

    /// Re-checks a value built field by field (public fields): the same rules as
    /// [`Normalized::new`].
    pub fn validated(self) -> Result<Self> {
        Self::new(self.alpha, self.beta, self.gamma, self.delta, self.d)
    }

    /// The plant part (γ, δ).
    pub fn plant(&self) -> PlantParams {
        PlantParams {
            gamma: self.gamma,
            delta: self.delta,
        }
    }

    /// Converts back to physical units for a given effective mass m and period T (Table I
    /// inverted): K = αm/T², B = βm/T, k = γm/T², b = δm/T, t_d = dT.
    pub fn to_physical(&self, mass: f64, period: f64) -> Result<Physical> {
        positive(Param::Mass, mass)?;
        positive(Param::Period, period)?;
        let t2 = period * period;
        Physical::new(
            Effective::new(mass, self.delta * mass / period, self.gamma * mass / t2)?,
            Wall {
                stiffness: self.alpha * mass / t2,
                damping: self.beta * mass / period,
            },
            Sampling::new(period, self.d)?,
        )
    }
}

/// Converts a normalized (α, β) pair to a physical wall (K, B) for mass m and period T.
pub fn wall_from_normalized(alpha: f64, beta: f64, mass: f64, period: f64) -> Wall {
    Wall {
        stiffness: alpha * mass / (period * period),
        damping: beta * mass / period,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{Arm, Device};

    #[test]
    fn round_trip_physical_normalized() {
        let p = Physical::new(
            Effective::combine(
                Device {
                    mass: 0.1,
                    damping: 1.5,
                },
                Arm {
                    mass: 0.9,
                    damping: 5.0,
                    stiffness: 300.0,
                },
            )
            .unwrap(),
            Wall {
                stiffness: 2000.0,
                damping: 3.0,
            },
            Sampling::new(1e-3, 2).unwrap(),
        )
        .unwrap();
        let n = p.normalized().unwrap();
        assert!((n.alpha - 2000.0 * 1e-6 / 1.0).abs() < 1e-18);
        assert!((n.delta - 6.5e-3).abs() < 1e-18);
        let back = n.to_physical(1.0, 1e-3).unwrap();
        assert!((back.wall.stiffness - 2000.0).abs() < 1e-9);
        assert!((back.plant.stiffness - 300.0).abs() < 1e-9);
        assert_eq!(back.sampling.delay, 2);
    }
}
