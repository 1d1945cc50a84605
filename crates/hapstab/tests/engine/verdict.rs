//! The one verdict (`hapstab::verdict`): the same answer wherever a wall is decided, the exact
//! root at z = 1, the marginal band, and a radius that never contradicts the verdict.
//!
//! Expected values: closed forms (a free mass keeps its root at z = 1 exactly when no
//! stiffness is rendered), and the spectral radii of an independent state-space referee
//! (exact ZOH by the matrix exponential, eigenvalues; 40-digit mpmath) quoted to the digits
//! the audit that found these cases printed.

use hapstab::map::{Axis, AxisRange, MapKind, wall_map};
use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::params::Effective;
use hapstab::verdict::{Verdict, decide, verdict_of_radius};
use hapstab::{AffineFamily, Analysis};

fn tf_loop(num: &[f64], den: &[f64], lag: f64, period: f64, d: usize, fc: f64) -> AffineFamily {
    let model = PlantModel::TransferFunction {
        num: num.to_vec(),
        den: den.to_vec(),
    };
    let plant = Plant::new(model, lag).unwrap();
    let lp = Loop::new(
        plant,
        period,
        Delay::samples(d).unwrap(),
        VelocityEstimator::LowPass { cutoff_hz: fc },
    )
    .unwrap();
    AffineFamily::of_loop(&lp).unwrap()
}

/// The audit's first map loop: 1/(0.01s⁴ + 0.5s³ + 20s² + 100s + 1000), T = 0.1 ms, d = 3,
/// lowpass:50, lag 1 ms (descending coefficients as the CLI takes them).
fn crowded_loop() -> AffineFamily {
    tf_loop(
        &[1.0],
        &[0.01, 0.5, 20.0, 100.0, 1000.0],
        1e-3,
        1e-4,
        3,
        50.0,
    )
}

#[test]
fn free_mass_at_zero_stiffness_is_marginal_with_its_root_at_one() {
    // m = 0.1 kg, b = 1.5 Ns/m, no spring, T = 1 ms, iir:600,-500,-100/1,-0.4,0.05 (a
    // differentiator: its numerator sums to zero). K = 0: position is not fed back, so the
    // free mass's root at z = 1 stays exactly.
    let plant = Plant::new(
        PlantModel::MassSpringDamper(Effective {
            mass: 0.1,
            damping: 1.5,
            stiffness: 0.0,
        }),
        0.0,
    )
    .unwrap();
    let est = VelocityEstimator::Iir {
        b: vec![600.0, -500.0, -100.0],
        a: vec![1.0, -0.4, 0.05],
    };
    let lp = Loop::new(plant, 1e-3, Delay::samples(0).unwrap(), est).unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let (a, b) = fam.to_units(0.0, 10.0);
    let an = Analysis::of_family(&fam, a, b).expect("a finite wall always gets an answer");
    assert_eq!(an.verdict, Verdict::Marginal);
    assert_eq!(an.spectral_radius, 1.0);
    assert_eq!(
        decide(&fam, a, b, &mut fam.coefficients(a, b)).verdict,
        Verdict::Marginal
    );
    // a little stiffness moves the root inside: stable
    let (a1, _) = fam.to_units(100.0, 10.0);
    assert_eq!(
        Analysis::of_family(&fam, a1, b).unwrap().verdict,
        Verdict::Stable
    );
}

#[test]
fn radius_map_agrees_with_check_where_roots_crowd_one() {
    let fam = crowded_loop();
    let s = fam.scale;
    let x = AxisRange::new(Axis::Alpha, 0.0, 2400.0 / s.stiffness, 25).unwrap();
    let y = AxisRange::new(Axis::Beta, 0.0, 0.001 / s.damping, 2).unwrap();
    let plain = wall_map(&fam, x, y, MapKind::Stability, &|_| {}).unwrap();
    let radius = wall_map(&fam, x, y, MapKind::SpectralRadius, &|_| {}).unwrap();
    assert_eq!(
        plain.stable, radius.stable,
        "the verdict must not depend on the radius"
    );
    // the referee: every wall of this map is stable (50 of 50)
    assert!(plain.stable.iter().all(|&s| s));
    let r = radius.radius.as_ref().unwrap();
    for (i, (&st, &rho)) in radius.stable.iter().zip(r).enumerate() {
        let (ix, iy) = (i % 25, i / 25);
        let an = Analysis::of_family(&fam, x.value(ix), y.value(iy)).unwrap();
        assert_eq!(
            rho, an.spectral_radius,
            "map radius is check's radius at {ix},{iy}"
        );
        assert_eq!(
            st,
            verdict_of_radius(rho) == Verdict::Stable,
            "{ix},{iy}: ρ = {rho}"
        );
    }
    // (2400 N/m, 0): the referee's ρ = 0.99999217 (stable); the z-coefficients' bisection gave
    // 1.0000091 (unstable)
    let rho = r[24];
    assert!((rho - 0.99999217).abs() < 5e-9, "{rho}");
}

#[test]
fn radius_map_keeps_the_stable_walls_of_a_slow_lag() {
    // The audit's second map loop: 22 of its 44 walls stable (the referee); the radius mode
    // gave 0.
    let fam = tf_loop(
        &[1265.00850577, 1165297.29408],
        &[
            4.88247269624,
            29.0294594768,
            233.513650414,
            853.157736134,
            667.545022956,
        ],
        0.0019798911845,
        0.00021027455696,
        5,
        11.9116389112,
    );
    let s = fam.scale;
    let x = AxisRange::new(Axis::Alpha, -0.0005 / s.stiffness, 0.0016 / s.stiffness, 22).unwrap();
    let y = AxisRange::new(Axis::Beta, 0.0, 0.001 / s.damping, 2).unwrap();
    let plain = wall_map(&fam, x, y, MapKind::Stability, &|_| {}).unwrap();
    let radius = wall_map(&fam, x, y, MapKind::SpectralRadius, &|_| {}).unwrap();
    assert_eq!(plain.stable, radius.stable);
    let stable = plain.stable.iter().filter(|&&s| s).count();
    assert_eq!(stable, 22, "the referee finds 22 stable walls");
}

/// A cluster of roots near z = 1 (T = 0.28 ms, slow fourth-order plant, 33.7 Hz low-pass,
/// 3.195 samples): the terms of dp/dθ cancel at θ = 0, so a step chosen by the linear model
/// alone jumped over a pair of roots 1.5e-5 inside the circle and the argument principle
/// counted 7 of 9 roots inside — the verdict said unstable beside a spectral radius of
/// 0.99998 and a stable K interval containing the wall. The referee: the roots of the loop's
/// shifted characteristic polynomial p(1 + w) (from `hapstab discretize`) in 50-digit mpmath,
/// largest modulus 0.999984954125547. Found by the margins property test.
#[test]
fn a_cluster_at_z_one_is_counted_inside() {
    let t = 0.0002813424803293956;
    let plant = Plant::new(
        PlantModel::TransferFunction {
            num: vec![2.0089263684950702],
            den: vec![
                1.0,
                1.6682042740111245,
                141.4257879463901,
                71.31772407762533,
                150.92641270820005,
            ],
        },
        0.0,
    )
    .unwrap();
    let delay = Delay {
        samples: 3,
        fraction: 0.19521967832596132,
    };
    let v = VelocityEstimator::LowPass {
        cutoff_hz: 33.703901899231724,
    };
    let lp = Loop::new(plant, t, delay, v).unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let (a, b) = fam.to_units(559.2596969510174 * 4.0, 3.052716531350584 * 4.0);
    let d = decide(&fam, a, b, &mut fam.coefficients(a, b));
    assert_eq!(d.verdict, Verdict::Stable, "{d:?}");
    let rho = Analysis::of_family(&fam, a, b).unwrap().spectral_radius;
    assert!((rho - 0.999984954125547).abs() < 1e-12, "{rho}");
}
