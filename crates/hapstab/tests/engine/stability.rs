//! The stability verdict (`hapstab::stability`, `hapstab::verdict`): the algebraic test
//! against the roots on 10⁵ points, the spectral radius two ways, the narrow marginal band,
//! delays up to 1000 samples, the analysis's roots and radius.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use hapstab::paper::NormalizedFamily;
use hapstab::schur_cohn::spectral_radius_schur;
use hapstab::stability::{Analysis, Verdict, roots, schur_stable};
use hapstab::verdict::decide_coefficients;
use hapstab::{Normalized, PlantParams};
use num_complex::Complex64;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

/// Pure mass, d = 0: p(z) = z³ + (s/2 − 2)z² + (1 + α/2)z − β/2 with s = α + β. Jury's
/// conditions are p(1) = α > 0, p(−1) = −4 < 0, |β| < 2 and 1 − β²/4 > |a0 a2 − a1|, whose
/// boundary is α = 2β(2 − β)/(2 + β) for 0 < β < 2 (largest at β = 2√2 − 2).
fn pure_mass_alpha(beta: f64) -> f64 {
    2.0 * beta * (2.0 - beta) / (2.0 + beta)
}

#[test]
fn algebraic_test_agrees_with_roots_on_100k_points() {
    use std::cell::Cell;
    let counted = Cell::new(0usize);
    let stable = Cell::new(0usize);
    let mut runner = TestRunner::new_with_rng(
        Config {
            cases: 110_000,
            max_global_rejects: 1_000_000,
            failure_persistence: None,
            ..Config::default()
        },
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let strat = (
        0usize..=20,
        0.0f64..1.0,
        0.0f64..1.0,
        0.0f64..1.0,
        0.0f64..1.0,
    );
    runner
        .run(&strat, |(d, ua, ub, ug, ud)| {
            // Scale α with the delay so that both verdicts are common.
            let t = d as f64 + 0.5;
            let alpha = -0.01 + ua * 0.4 / t;
            let beta = -0.05 + ub * 1.2 / t.sqrt();
            let gamma = if ug < 0.3 {
                0.0
            } else {
                10f64.powf(-6.0 + 6.0 * ug)
            };
            let delta = if ud < 0.3 {
                0.0
            } else {
                10f64.powf(-4.0 + 4.0 * ud)
            };
            let c = NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
                .unwrap()
                .coefficients(alpha, beta);
            let r = roots(&c).unwrap();
            let rho = r.iter().map(|z| z.norm()).fold(0.0, f64::max);
            if (rho - 1.0).abs() <= 1e-9 {
                return Ok(());
            }
            counted.set(counted.get() + 1);
            prop_assert_eq!(
                schur_stable(&c),
                rho < 1.0,
                "d={} α={} β={} γ={} δ={} ρ={}",
                d,
                alpha,
                beta,
                gamma,
                delta,
                rho
            );
            if rho < 1.0 {
                stable.set(stable.get() + 1);
            }
            Ok(())
        })
        .unwrap();
    let (n, s) = (counted.get(), stable.get());
    assert!(n >= 100_000, "only {n} points compared");
    assert!(
        s > n / 10 && s < n * 9 / 10,
        "unbalanced sample: {s} stable of {n}"
    );
}

#[test]
fn spectral_radius_two_ways() {
    let mut runner = TestRunner::new_with_rng(
        Config::with_cases(3000),
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let strat = (
        0usize..=10,
        -0.1f64..1.0,
        -0.3f64..2.0,
        0.0f64..0.01,
        0.0f64..0.1,
    );
    runner
        .run(&strat, |(d, alpha, beta, gamma, delta)| {
            let c = NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
                .unwrap()
                .coefficients(alpha, beta);
            let rho_roots = roots(&c)
                .unwrap()
                .iter()
                .map(|z| z.norm())
                .fold(0.0, f64::max);
            let rho_schur = spectral_radius_schur(&c);
            prop_assert!(
                (rho_roots - rho_schur).abs() < 1e-9 * rho_schur.max(1.0),
                "{} vs {}",
                rho_roots,
                rho_schur
            );
            Ok(())
        })
        .unwrap();
}

#[test]
fn marginal_band_is_narrow() {
    // Move a point across the pure-mass boundary until the spectral radius is 1 ± 1e-8:
    // it must get a definite verdict; exactly on the boundary it is marginal.
    let beta = 0.7;
    let fam = NormalizedFamily::new(PlantParams::new(0.0, 0.0).unwrap(), 0).unwrap();
    let a0 = pure_mass_alpha(beta);
    let rho = |a: f64| spectral_radius_schur(&fam.coefficients(a, beta));
    assert_eq!(
        decide_coefficients(&fam.coefficients(a0, beta)).verdict,
        Verdict::Marginal
    );
    for (target, want) in [
        (1.0 + 1e-8, Verdict::Unstable),
        (1.0 - 1e-8, Verdict::Stable),
    ] {
        // bisection on α for ρ(α) = target
        let (mut lo, mut hi) = if want == Verdict::Unstable {
            (a0, a0 * 1.1)
        } else {
            (a0 * 0.9, a0)
        };
        for _ in 0..80 {
            let mid = 0.5 * (lo + hi);
            if rho(mid) < target {
                lo = mid
            } else {
                hi = mid
            }
        }
        let c = fam.coefficients(0.5 * (lo + hi), beta);
        assert!((rho(0.5 * (lo + hi)) - target).abs() < 1e-12);
        assert_eq!(decide_coefficients(&c).verdict, want, "ρ = {target}");
    }
}

#[test]
fn large_delay_up_to_1000() {
    // δ = 0.01, β = 1e-4: half the linear-condition stiffness (β + δ)/(d + 1/2) is stable,
    // twice it is not; the Schur–Cohn verdicts are checked against the roots.
    for &d in &[100usize, 1000] {
        let fam = NormalizedFamily::new(PlantParams::new(0.0, 0.01).unwrap(), d).unwrap();
        let lin = (1e-4 + 0.01) / (d as f64 + 0.5);
        let c_in = fam.coefficients(0.5 * lin, 1e-4);
        let c_out = fam.coefficients(2.0 * lin, 1e-4);
        assert_eq!(c_in.len(), d + 4);
        assert!(schur_stable(&c_in), "d={d}");
        assert!(!schur_stable(&c_out), "d={d}");
        for (c, want_stable) in [(&c_in, true), (&c_out, false)] {
            if d == 1000 && want_stable {
                continue; // one 1003-degree root computation (about 3 s) is enough
            }
            let a = Analysis::of_poly(c).unwrap();
            assert_eq!(a.roots.len(), d + 3);
            assert_eq!(
                a.spectral_radius < 1.0,
                want_stable,
                "d={d} ρ={}",
                a.spectral_radius
            );
            assert!((a.spectral_radius - spectral_radius_schur(c)).abs() < 1e-9);
        }
    }
}

#[test]
fn analysis_reports_roots_and_radius() {
    let a = Analysis::new(Normalized::new(0.1, 0.5, 0.0, 0.0, 0).unwrap()).unwrap();
    assert_eq!(a.verdict, Verdict::Stable);
    assert_eq!(a.roots.len(), 3);
    // product of roots = −c0 = β/2 for the monic cubic
    let prod = a.roots.iter().fold(Complex64::new(1.0, 0.0), |p, z| p * z);
    assert!((prod.re - 0.25).abs() < 1e-14 && prod.im.abs() < 1e-14);
}
