//! Seeded loops of every kind for the property tests: transfer functions up to order 6,
//! two-mass devices, mass-spring-dampers, every velocity estimator, force lags, whole and
//! fractional delays up to 600 samples, T from 1e-5 to 1e-1 s; a stable wall on each.

use super::SplitMix;
use hapstab::AffineFamily;
use hapstab::boundary::stable_stiffness_intervals;
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Effective};
use hapstab::verdict::{Verdict, decide};

/// Descending coefficients of a stable polynomial of the given order with modes between 0.3
/// and 300 rad/s (complex pairs of damping ratio 0.02–1, real poles).
pub fn stable_den(rng: &mut SplitMix, order: usize) -> Vec<f64> {
    let mut c = vec![1.0];
    let mut left = order;
    while left > 0 {
        let w = rng.log_range(0.3, 300.0);
        let f: Vec<f64> = if left >= 2 && rng.below(3) > 0 {
            left -= 2;
            vec![1.0, 2.0 * rng.log_range(0.02, 1.0) * w, w * w]
        } else {
            left -= 1;
            vec![1.0, w]
        };
        let mut n = vec![0.0; c.len() + f.len() - 1];
        for (i, a) in c.iter().enumerate() {
            for (j, b) in f.iter().enumerate() {
                n[i + j] += a * b;
            }
        }
        c = n;
    }
    c
}

pub fn estimator(rng: &mut SplitMix) -> VelocityEstimator {
    match rng.below(4) {
        0 => VelocityEstimator::Backward,
        1 => VelocityEstimator::LowPass {
            cutoff_hz: rng.log_range(5.0, 300.0),
        },
        2 => VelocityEstimator::Average {
            samples: 1 + rng.below(10),
        },
        _ => VelocityEstimator::Iir {
            b: vec![500.0, -500.0],
            a: vec![1.0, -0.5],
        },
    }
}

pub fn plant(rng: &mut SplitMix, i: usize) -> PlantModel {
    match i % 3 {
        0 => {
            let order = 2 + rng.below(5);
            let den = stable_den(rng, order);
            let gain = den[den.len() - 1] * rng.log_range(1e-3, 1.0);
            PlantModel::TransferFunction {
                num: vec![gain],
                den,
            }
        }
        1 => PlantModel::TwoMass(TwoMass {
            motor_mass: rng.range(0.03, 0.3),
            motor_damping: rng.range(0.0, 3.0),
            handle_mass: rng.range(0.01, 0.1),
            transmission_stiffness: rng.log_range(1e3, 1e6),
            transmission_damping: rng.range(0.0, 3.0),
            arm: Arm {
                mass: rng.range(0.0, 2.0),
                damping: rng.range(0.0, 6.0),
                stiffness: rng.range(0.0, 1500.0),
            },
        }),
        _ => PlantModel::MassSpringDamper(
            Effective::new(
                rng.range(0.1, 3.0),
                rng.range(0.0, 10.0),
                rng.range(0.0, 500.0),
            )
            .unwrap(),
        ),
    }
}

pub fn random_loop(rng: &mut SplitMix, i: usize) -> Option<Loop> {
    let period = rng.log_range(1e-5, 1e-1);
    let lag = if i % 4 == 3 {
        rng.log_range(0.1, 3.0) * period
    } else {
        0.0
    };
    let samples = match i % 20 {
        19 => 100 + rng.below(500),
        15..=18 => 5 + rng.below(60),
        _ => rng.below(4),
    };
    let delay = Delay {
        samples,
        fraction: if i % 2 == 1 { rng.range(0.0, 1.0) } else { 0.0 },
    };
    Loop::new(
        Plant::new(plant(rng, i), lag).ok()?,
        period,
        delay,
        estimator(rng),
    )
    .ok()
}

/// A wall inside the stable K interval at a random damping (None when none is stable).
pub fn stable_wall(rng: &mut SplitMix, fam: &AffineFamily) -> Option<(f64, f64)> {
    let (_, beta0) = fam.to_units(0.0, 1.0);
    let beta = beta0 * rng.range(0.0, 10.0) * if rng.below(4) == 0 { 0.0 } else { 1.0 };
    let iv = stable_stiffness_intervals(fam, beta)
        .into_iter()
        .find(|iv| iv.hi.is_finite() && iv.lo.is_finite() && iv.hi > iv.lo)?;
    Some((iv.lo + (iv.hi - iv.lo) * rng.range(0.05, 0.95), beta))
}

pub fn verdict(lp: &Loop, a: f64, b: f64) -> Verdict {
    let fam = AffineFamily::of_loop(lp).unwrap();
    decide(&fam, a, b, &mut fam.coefficients(a, b)).verdict
}
