//! The device damping b that the passivity condition compares with: the device's own damper.

use serde::Serialize;

use crate::model::{Plant, PlantModel, strip_leading_zeros};

/// The device damping b that the condition compares with, or why there is none.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DeviceDamping {
    /// The damper collocated with the actuator and the encoder, in Ns/m.
    Known {
        /// b in Ns/m.
        damping: f64,
    },
    /// The argument does not apply to this plant.
    NotApplicable {
        /// Why, in words.
        reason: String,
    },
}

/// The device damping of a plant for the passivity condition (Colgate–Schenkel: the device
/// and wall passive towards any passive operator): the device's own b_L = b − b_H for the
/// paper's plant when it names its operator (b itself when it does not), the motor-side damping b_m of a
/// two-mass device (the damper where the force acts and the position is measured; the
/// transmission, the handle and the arm are passive and only add to it), b of a transfer
/// function that is exactly c/(m s² + b s + k). Not applicable with an actuator lag (the force
/// is then not held constant over a sample, which the argument rests on) or for any other
/// transfer function (no identified damper).
pub fn device_damping(plant: &Plant) -> DeviceDamping {
    if plant.force_lag > 0.0 {
        return DeviceDamping::NotApplicable {
            reason: "the actuator lag filters the held force, so the sampled-data passivity \
                     argument (force constant over each sample) does not apply"
                .into(),
        };
    }
    match &plant.model {
        PlantModel::MassSpringDamper(e) => DeviceDamping::Known {
            damping: (e.damping - plant.operator.map_or(0.0, |a| a.damping)).max(0.0),
        },
        PlantModel::TwoMass(t) => DeviceDamping::Known {
            damping: t.motor_damping,
        },
        PlantModel::TransferFunction { num, den } => tf_damping(num, den),
    }
}

fn tf_damping(num: &[f64], den: &[f64]) -> DeviceDamping {
    let (num, den) = (strip_leading_zeros(num), strip_leading_zeros(den));
    if let ([c], [m, b, k]) = (num, den) {
        let (m, b, k) = (m / c, b / c, k / c);
        if m > 0.0 && b >= 0.0 && k >= 0.0 {
            return DeviceDamping::Known { damping: b };
        }
    }
    DeviceDamping::NotApplicable {
        reason: "the transfer-function plant is not a mass-spring-damper c/(ms² + bs + k), \
                 so no device damper can be identified"
            .into(),
    }
}
