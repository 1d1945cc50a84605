//! The general loop of the region and K_max benchmarks: a two-mass device held by the typical
//! arm, a 0.2 ms actuator lag, a 200 Hz low-pass velocity estimate, T = 1 ms (order 5 with the
//! lag state; p of degree 6 + d).

use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::Arm;

/// The general loop with the given delay.
pub fn general_loop(delay: Delay) -> Loop {
    let plant = Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: 0.05,
            motor_damping: 0.5,
            handle_mass: 0.05,
            transmission_stiffness: 2e4,
            transmission_damping: 2.0,
            arm: Arm::TYPICAL,
        }),
        2e-4,
    )
    .expect("valid plant");
    Loop::new(
        plant,
        1e-3,
        delay,
        VelocityEstimator::LowPass { cutoff_hz: 200.0 },
    )
    .expect("valid loop")
}
