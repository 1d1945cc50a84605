//! Unit tests of [`super`]: every fraction's loop against its direct discretization, the
//! bounds over a fine fraction grid, the unit numerators against the determinant form.
use super::*;
use crate::margins::frequency::loop_value;
use crate::model::{Plant, PlantModel, TwoMass, VelocityEstimator};
use crate::params::{Arm, Effective};

/// A two-mass device (order 4) with an actuator lag and a low-pass velocity filter, and
/// the paper's loop.
fn loops() -> Vec<(Loop, f64, f64)> {
    let two_mass = PlantModel::TwoMass(TwoMass {
        motor_mass: 0.1,
        motor_damping: 0.5,
        handle_mass: 0.05,
        transmission_stiffness: 4e4,
        transmission_damping: 1.0,
        arm: Arm {
            mass: 0.5,
            damping: 2.0,
            stiffness: 300.0,
        },
    });
    let paper = PlantModel::MassSpringDamper(Effective::new(1.1, 7.5, 350.0).unwrap());
    [
        (
            two_mass,
            2e-4,
            VelocityEstimator::LowPass { cutoff_hz: 80.0 },
        ),
        (paper, 1e-3, VelocityEstimator::Backward),
    ]
    .into_iter()
    .map(|(p, lag, v)| {
        let lp = Loop::new(Plant::new(p, lag).unwrap(), 1e-3, Delay::NONE, v).unwrap();
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let (a, b) = fam.to_units(2000.0, 3.0);
        (lp, a, b)
    })
    .collect()
}

#[test]
fn every_fraction_is_the_loop_discretized_at_that_fraction() {
    for (lp, a, b) in loops() {
        let fl = FractionLoop::new(&lp, &lp.discretize().unwrap(), a, b, &[0.1, 1.0]).unwrap();
        for lambda in [0.0, 0.125, 0.37, 0.5, 0.93] {
            // the direct discretization at the fraction (split hold, its own numerator)
            let direct = AffineFamily::of_loop(
                &lp.with_delay(Delay {
                    samples: 0,
                    fraction: lambda,
                })
                .unwrap(),
            )
            .unwrap();
            let hold = fl.hold(lambda);
            for theta in [1e-4, 0.01, 0.3, 1.0, 2.5, 3.1] {
                let want = loop_value(&direct, a, b, theta);
                let got = fl.parts(theta).view().loop_at(&hold.g);
                assert!(
                    (got - want).norm() <= 1e-11 * want.norm(),
                    "λ = {lambda}, θ = {theta}: {got} vs {want}"
                );
            }
        }
    }
}

#[test]
fn the_unit_numerators_match_the_determinant_form() {
    // the loops above and a stiff two-mass device sampled at 10 µs (roots crowding z = 1)
    let stiff = PlantModel::TwoMass(TwoMass {
        motor_mass: 0.195,
        motor_damping: 0.475,
        handle_mass: 0.0705,
        transmission_stiffness: 2.09e5,
        transmission_damping: 2.2,
        arm: Arm {
            mass: 0.028,
            damping: 5.39,
            stiffness: 530.0,
        },
    });
    let fast = Loop::new(
        Plant::new(stiff, 3e-4).unwrap(),
        1.09e-5,
        Delay::NONE,
        VelocityEstimator::Average { samples: 2 },
    )
    .unwrap();
    let mut worst = 0.0_f64;
    for lp in loops().into_iter().map(|l| l.0).chain([fast]) {
        let dl = lp.discretize().unwrap();
        let den = dl.denominator_shifted();
        let units = unit_numerators(&dl.phi_minus_identity, &dl.c, &den);
        for (j, u) in units.iter().enumerate() {
            let mut e = vec![0.0; u.len()];
            e[j] = 1.0;
            let want = dl.numerator_shifted_for(&e, &den);
            let scale = want.iter().map(|x| x.abs()).fold(0.0, f64::max);
            for (k, w) in want.iter().enumerate() {
                let got = u.get(k).copied().unwrap_or(0.0);
                // each coefficient to 1e-10 of itself, above the determinant form's
                // rounding (1e-13 of the largest coefficient)
                worst = worst.max((got - w).abs() / (1e-10 * w.abs() + 1e-12 * scale));
            }
        }
    }
    assert!(worst < 1.0, "worst difference {worst} of its tolerance");
}

#[test]
fn the_bounds_hold_over_a_fine_fraction_grid() {
    for (lp, a, b) in loops() {
        let fl = FractionLoop::new(&lp, &lp.discretize().unwrap(), a, b, &[0.1, 1.0]).unwrap();
        let delta = fl.deviation_bound(fl.holds());
        let holds: Vec<HoldInput> = (0..=1000).map(|i| fl.hold(i as f64 / 1000.0)).collect();
        for theta in [1e-3, 0.05, 0.4, 1.3, 2.2, 3.0] {
            let parts = fl.parts(theta);
            let (lo, hi) = fl.gain_bounds(parts.view(), &delta);
            for h in &holds {
                let g = parts.view().loop_at(&h.g).norm();
                assert!(
                    lo <= g * (1.0 + 1e-12) && g <= hi * (1.0 + 1e-12),
                    "θ = {theta}: {lo} ≤ {g} ≤ {hi}"
                );
            }
        }
    }
}
