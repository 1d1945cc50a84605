//! The human operator inside a plant: eq. (1) lumps the device (m_L, b_L) and the arm that
//! holds it (m_H, b_H, k_H) into one mass-spring-damper m = m_L + m_H, b = b_L + b_H,
//! k = k_H. Stability depends only on the sum; passivity (Colgate–Schenkel) asks whether the
//! device and wall are passive towards *any* passive operator, and then only the device's own
//! damping b_L = b − b_H counts. A [`Plant`] therefore remembers the arm it includes.

use crate::error::{Error, Result};
use crate::model::{Plant, PlantModel};
use crate::param::Param;
use crate::params::{Arm, Device, Effective};

impl Plant {
    /// The paper's plant of a device held by an arm (eq. 1): 1/(ms² + bs + k) with
    /// m = m_L + m_H, b = b_L + b_H, k = k_H, remembering the arm as its operator.
    pub fn held_device(device: Device, arm: Arm) -> Result<Self> {
        Plant::mass_spring_damper(Effective::combine(device, arm)?)?.with_operator(arm)
    }

    /// The same mass-spring-damper with `arm` named as the operator its m, b and k include
    /// (eq. 1); the arm must fit inside them (m_H ≤ m, b_H ≤ b, k_H ≤ k). Other plants hold
    /// their arm in their own model (a two-mass device's `arm`) and are refused.
    pub fn with_operator(self, arm: Arm) -> Result<Self> {
        Self {
            operator: Some(arm),
            ..self
        }
        .validated()
    }

    /// Checks the model, the lag τ >= 0 and that the operator fits inside the plant.
    pub fn validated(self) -> Result<Self> {
        let operator = self.operator;
        let plant = Plant::new(self.model, self.force_lag)?;
        if let Some(arm) = operator {
            check_operator(&plant.model, arm)?;
        }
        Ok(Self { operator, ..plant })
    }

    /// The effective damping b of eq. (1), device and arm together, when the plant is a
    /// mass-spring-damper that names its operator; None otherwise (then the plant's damping
    /// is all the device's own).
    pub fn effective_damping(&self) -> Option<f64> {
        match (&self.model, self.operator) {
            (PlantModel::MassSpringDamper(e), Some(_)) => Some(e.damping),
            _ => None,
        }
    }
}

fn check_operator(model: &PlantModel, arm: Arm) -> Result<()> {
    let PlantModel::MassSpringDamper(e) = model else {
        return Err(Error::Invalid {
            param: Param::Operator,
            reason: "only a mass-spring-damper (eq. 1) includes its operator; a two-mass \
                     device holds its arm in its own model"
                .into(),
        });
    };
    let parts = [
        (Param::ArmMass, arm.mass, "plant mass m", e.mass),
        (Param::ArmDamping, arm.damping, "plant damping b", e.damping),
        (
            Param::ArmStiffness,
            arm.stiffness,
            "plant stiffness k",
            e.stiffness,
        ),
    ];
    for (name, part, whole_name, whole) in parts {
        if !(0.0..=whole).contains(&part) {
            return Err(Error::Invalid {
                param: name,
                reason: format!(
                    "= {part} must be >= 0 and within the {whole_name} = {whole} it is part of"
                ),
            });
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn held_device_keeps_the_device_damping_apart() {
        let p = Plant::held_device(Device::PHANTOM_LIKE, Arm::TYPICAL).unwrap();
        assert_eq!(p.effective_damping(), Some(1.5 + 6.0));
        assert_eq!(p.operator, Some(Arm::TYPICAL));
        let lag = p.clone().with_force_lag(1e-3).unwrap();
        assert_eq!(lag.operator, Some(Arm::TYPICAL), "a lag keeps the operator");
    }

    #[test]
    fn an_arm_larger_than_the_plant_is_refused() {
        let e = Effective::new(1.1, 7.5, 350.0).unwrap();
        let plant = Plant::mass_spring_damper(e).unwrap();
        let arm = Arm {
            damping: 8.0,
            ..Arm::TYPICAL
        };
        let err = plant.with_operator(arm).unwrap_err().to_string();
        assert!(err.contains("arm damping b_H"), "{err}");
    }
}
