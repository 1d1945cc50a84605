//! Acceptance tests of the foundation (issue 2): exact plant, p(z), stability test.
//! Expected values come from closed forms derived by hand or from the paper's own formula.

use hapstab::closed_loop::PolyFamily;
use hapstab::plant::{DiscretePlant, eq10_coefficients};
use hapstab::schur_cohn::spectral_radius_schur;
use hapstab::stability::{Analysis, Verdict, roots, schur_stable};
use hapstab::verdict::decide_coefficients;
use hapstab::{Normalized, PlantParams};
use num_complex::Complex64;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

fn verdict(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize) -> Verdict {
    let fam = PolyFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap();
    decide_coefficients(&fam.coefficients(alpha, beta)).verdict
}

/// Pure mass, d = 0: p(z) = z³ + (s/2 − 2)z² + (1 + α/2)z − β/2 with s = α + β. Jury's
/// conditions are p(1) = α > 0, p(−1) = −4 < 0, |β| < 2 and 1 − β²/4 > |a0 a2 − a1|, whose
/// boundary is α = 2β(2 − β)/(2 + β) for 0 < β < 2 (largest at β = 2√2 − 2).
fn pure_mass_alpha(beta: f64) -> f64 {
    2.0 * beta * (2.0 - beta) / (2.0 + beta)
}

#[test]
fn pure_mass_boundary_closed_form() {
    let beta_star = 2.0 * 2f64.sqrt() - 2.0;
    for &beta in &[0.05, 0.3, beta_star, 1.0, 1.5, 1.9] {
        let a = pure_mass_alpha(beta);
        assert_eq!(
            verdict(a * (1.0 - 1e-6), beta, 0.0, 0.0, 0),
            Verdict::Stable,
            "β={beta}"
        );
        assert_eq!(
            verdict(a * (1.0 + 1e-6), beta, 0.0, 0.0, 0),
            Verdict::Unstable,
            "β={beta}"
        );
        // the left boundary is α = 0 (= −γ)
        assert_eq!(verdict(1e-6 * a, beta, 0.0, 0.0, 0), Verdict::Stable);
        assert_eq!(verdict(-1e-6 * a, beta, 0.0, 0.0, 0), Verdict::Unstable);
    }
    // α is largest at β = 2√2 − 2: the closed form's derivative vanishes there
    let h = 1e-5;
    let slope = (pure_mass_alpha(beta_star + h) - pure_mass_alpha(beta_star - h)) / (2.0 * h);
    assert!(slope.abs() < 1e-9, "{slope}");
    assert!((pure_mass_alpha(beta_star) - (12.0 - 8.0 * 2f64.sqrt())).abs() < 1e-15);
}

#[test]
fn zero_order_hold_keeps_dc_gain() {
    for &(g, d) in &[
        (1e-3, 0.0),
        (1e-3, 0.015),
        (0.1, 0.5),
        (2.0, 1.0),
        (9.0, 0.0),
        (30.0, 4.0),
    ] {
        let p = DiscretePlant::new(g, d).unwrap();
        let n1 = p.n1 + p.n0;
        let d1 = 1.0 - p.a1 + p.a0;
        // D(1) from the coefficients loses ~|log10 γ| digits to cancellation.
        assert!(
            rel(n1 / d1, 1.0 / g) < 1e-15 / g.min(1.0) * 10.0,
            "γ={g} δ={d}"
        );
        assert!(rel(p.numerator_at_one(), n1) < 1e-14);
        // a root at z = 1 appears exactly at α = −γ
        for dd in [0usize, 1, 3] {
            let fam = PolyFamily::new(PlantParams::new(g, d).unwrap(), dd).unwrap();
            let c = fam.coefficients(-g, 0.37);
            let p1: f64 = c.iter().sum();
            assert!(p1.abs() < 1e-14, "p(1) = {p1}");
            let r = roots(&c).unwrap();
            let closest = r
                .iter()
                .map(|z| (z - 1.0).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(closest < 1e-9, "γ={g} δ={d} d={dd}: {closest}");
            assert_eq!(fam.value_at_one(-g), 0.0);
        }
    }
}

/// Critically damped (δ² = 4γ, μ = −δ/2 double eigenvalue):
/// g1 = (e^μ(μ − 1) + 1)/μ², Φ12 = e^μ, Φ22 = e^μ(1 + μ), a1 = 2e^μ.
fn critical(delta: f64) -> (f64, f64, f64) {
    let mu = -delta / 2.0;
    let e = mu.exp();
    let g1 = (e * (mu - 1.0) + 1.0) / (mu * mu);
    let n0 = e * e - e * (1.0 + mu) * g1;
    (g1, n0, 2.0 * e)
}

#[test]
fn continuity_at_regime_limits() {
    // γ → 0 (δ > 0): eq. (10)
    for &delta in &[0.5, 1.0, 3.0] {
        let (n1, n0, a1, a0) = eq10_coefficients(delta);
        let p = DiscretePlant::new(1e-14, delta).unwrap();
        for (x, y) in [(p.n1, n1), (p.n0, n0), (p.a1, a1), (p.a0, a0)] {
            assert!(rel(x, y) < 1e-12, "δ={delta}: {x} vs {y}");
        }
    }
    // γ → 0 with δ = 0: pure mass
    let p = DiscretePlant::new(1e-14, 0.0).unwrap();
    for (x, y) in [(p.n1, 0.5), (p.n0, 0.5), (p.a1, 2.0), (p.a0, 1.0)] {
        assert!(rel(x, y) < 1e-12, "{x} vs {y}");
    }
    // δ² = 4γ(1 ± 1e-12): critically damped closed form
    for &delta in &[0.5, 1.0, 2.0] {
        let (g1, n0, a1) = critical(delta);
        for s in [1.0 - 1e-12, 1.0, 1.0 + 1e-12] {
            let gamma = delta * delta / 4.0 * s;
            let p = DiscretePlant::new(gamma, delta).unwrap();
            for (x, y) in [(p.n1, g1), (p.n0, n0), (p.a1, a1)] {
                assert!(rel(x, y) < 1e-12, "δ={delta} s={s}: {x} vs {y}");
            }
        }
    }
    // δ → 0: undamped oscillator n1 = n0 = 2 sin²(ω/2)/ω², a1 = 2 cos ω
    for &gamma in &[1e-3, 0.5, 4.0, 9.8696] {
        let w: f64 = f64::sqrt(gamma);
        let nn = 2.0 * (w / 2.0).sin().powi(2) / gamma;
        let p = DiscretePlant::new(gamma, 1e-14).unwrap();
        for (x, y) in [(p.n1, nn), (p.n0, nn), (p.a1, 2.0 * w.cos()), (p.a0, 1.0)] {
            assert!(rel(x, y) < 1e-12, "γ={gamma}: {x} vs {y}");
        }
    }
}

/// The paper's eq. (9) evaluated literally in complex arithmetic (c1 imaginary when
/// δ² < 4γ), as ascending coefficients.
fn paper_eq9(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize) -> Vec<Complex64> {
    let c1 = Complex64::new(delta * delta - 4.0 * gamma, 0.0).sqrt();
    let c2 = (-(c1 + delta) / 2.0).exp();
    let c3 = (-(-c1 + delta) / 2.0).exp();
    let ed = (-delta).exp();
    let n = d + 3;
    let mut c = vec![Complex64::new(0.0, 0.0); n + 1];
    c[2] += ((c3 + c2 - 2.0) * c1 + (c3 - c2) * delta) * (alpha + beta);
    c[1] += ((c3 + c2 - 2.0 * ed) * c1 + (c2 - c3) * delta) * alpha
        + 2.0 * ((1.0 - ed) * c1 + (c2 - c3) * delta) * beta;
    // − 2(z² − z(c3 + c2) + e^{−δ}) c1 γ z^{1+d}
    c[n] += -2.0 * c1 * gamma;
    c[n - 1] += 2.0 * (c3 + c2) * c1 * gamma;
    c[n - 2] += -2.0 * ed * c1 * gamma;
    c[0] += ((2.0 * ed - c3 - c2) * c1 + (c3 - c2) * delta) * beta;
    c
}

#[test]
fn paper_polynomial_is_constant_multiple() {
    let mut runner = TestRunner::new_with_rng(
        Config::with_cases(2000),
        TestRng::deterministic_rng(RngAlgorithm::ChaCha),
    );
    let strat = (
        -1.0f64..2.0,
        -1.0f64..2.0,
        0.01f64..5.0,
        0.01f64..3.0,
        0usize..6,
    );
    runner
        .run(&strat, |(alpha, beta, gamma, delta, d)| {
            let disc = delta * delta - 4.0 * gamma;
            prop_assume!(disc.abs() > 0.1 * (delta * delta + 4.0 * gamma));
            let paper = paper_eq9(alpha, beta, gamma, delta, d);
            let ours = PolyFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
                .unwrap()
                .coefficients(alpha, beta);
            let k = paper[d + 3] / ours[d + 3];
            let scale = ours.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for (pc, oc) in paper.iter().zip(&ours) {
                let diff = (pc / k - oc).norm();
                prop_assert!(diff < 1e-10 * scale, "coef {pc} vs {oc} (k={k})");
            }
            Ok(())
        })
        .unwrap();
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
            let c = PolyFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
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
            let c = PolyFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
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
    let fam = PolyFamily::new(PlantParams::new(0.0, 0.0).unwrap(), 0).unwrap();
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
        let fam = PolyFamily::new(PlantParams::new(0.0, 0.01).unwrap(), d).unwrap();
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
