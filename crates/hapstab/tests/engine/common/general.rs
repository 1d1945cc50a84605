//! The general loops of the region and map tests: a two-mass device, an actuator lag, every
//! velocity estimator, fractional delays, a transfer function.

use hapstab::AffineFamily;
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Effective};

pub fn family(lp: &Loop) -> AffineFamily {
    AffineFamily::of_loop(lp).unwrap()
}

pub fn with(plant: Plant, delay: Delay, v: VelocityEstimator) -> Loop {
    Loop::new(plant, 1e-3, delay, v).unwrap()
}

/// Ten loops beyond the paper's: two-mass device, actuator lag, every velocity estimator,
/// fractional delays, a transfer function.
pub fn general_loops() -> Vec<(&'static str, Loop)> {
    let msd = || paper_plant();
    let two_mass = two_mass_plant;
    let frac = |x: f64| Delay::from_time(x * 1e-3, 1e-3).unwrap();
    let whole = |d: usize| Delay::samples(d).unwrap();
    let tf = fourth_order_plant();
    let iir = VelocityEstimator::Iir {
        // backward difference through a 2-tap moving average: (1 − z⁻²)/(2T)
        b: vec![500.0, 0.0, -500.0],
        a: vec![1.0],
    };
    vec![
        (
            "low-pass 100 Hz",
            with(
                msd(),
                whole(0),
                VelocityEstimator::LowPass { cutoff_hz: 100.0 },
            ),
        ),
        (
            "average 5",
            with(msd(), whole(1), VelocityEstimator::Average { samples: 5 }),
        ),
        ("iir", with(msd(), whole(0), iir)),
        (
            "delay 0.5T",
            with(msd(), frac(0.5), VelocityEstimator::Backward),
        ),
        (
            "delay 1.3T",
            with(msd(), frac(1.3), VelocityEstimator::Backward),
        ),
        (
            "force lag 0.2 ms",
            with(
                msd().with_force_lag(2e-4).unwrap(),
                whole(1),
                VelocityEstimator::Backward,
            ),
        ),
        (
            "two-mass",
            with(two_mass(), whole(1), VelocityEstimator::Backward),
        ),
        (
            "transfer function",
            with(tf, whole(0), VelocityEstimator::Backward),
        ),
        (
            "two-mass, low-pass, delay 0.7T",
            with(
                two_mass(),
                frac(0.7),
                VelocityEstimator::LowPass { cutoff_hz: 200.0 },
            ),
        ),
        (
            "device alone, average 15",
            with(
                Plant::mass_spring_damper(Effective::new(0.1, 1.5, 0.0).unwrap()).unwrap(),
                whole(0),
                VelocityEstimator::Average { samples: 15 },
            ),
        ),
    ]
}

pub fn paper_plant() -> Plant {
    Plant::mass_spring_damper(Effective::new(1.1, 7.5, 350.0).unwrap()).unwrap()
}

/// A two-mass device (50 g motor and handle, 20 kN/m transmission) held by the typical arm.
pub fn two_mass_plant() -> Plant {
    two_mass_held_by(Arm::TYPICAL, 0.0)
}

/// The same device held by `arm`, its force through a lag of time constant `lag` s.
pub fn two_mass_held_by(arm: Arm, lag: f64) -> Plant {
    Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: 0.05,
            motor_damping: 0.5,
            handle_mass: 0.05,
            transmission_stiffness: 2e4,
            transmission_damping: 2.0,
            arm,
        }),
        lag,
    )
    .unwrap()
}

/// The benchmarks' general loop (`benches/common/general_loop.rs`): the two-mass device held
/// by `arm` behind a 0.2 ms actuator lag and `delay`, a 200 Hz low-pass velocity estimate,
/// T = 1 ms.
pub fn bench_loop(arm: Arm, delay: Delay) -> Loop {
    with(
        two_mass_held_by(arm, 2e-4),
        delay,
        VelocityEstimator::LowPass { cutoff_hz: 200.0 },
    )
}

/// P(s) = (2s + 400)/(0.1s⁴ + 8s³ + 900s² + 4e4 s + 1e5).
pub fn fourth_order_plant() -> Plant {
    Plant::new(
        PlantModel::TransferFunction {
            num: vec![2.0, 400.0],
            den: vec![0.1, 8.0, 900.0, 4.0e4, 1.0e5],
        },
        0.0,
    )
    .unwrap()
}
