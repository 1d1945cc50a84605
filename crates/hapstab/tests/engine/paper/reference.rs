//! The paper's plant sampled exactly (`hapstab::paper::reference`, eq. 2–10): the zero-order hold keeps
//! the DC gain, p(z) is continuous across the regimes of the plant's poles, and it is a
//! constant multiple of the paper's eq. (9).
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use crate::common::discrete_plant::DiscretePlant;
use hapstab::PlantParams;
use hapstab::paper::NormalizedFamily;
use hapstab::paper::reference::eq10_coefficients;
use hapstab::stability::roots;
use num_complex::Complex64;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
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
            let fam = NormalizedFamily::new(PlantParams::new(g, d).unwrap(), dd).unwrap();
            let c = fam.coefficients(-g, 0.37);
            let p1: f64 = c.iter().sum();
            assert!(p1.abs() < 1e-14, "p(1) = {p1}");
            let r = roots(&c).unwrap();
            let closest = r
                .iter()
                .map(|z| (z - 1.0).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(closest < 1e-9, "γ={g} δ={d} d={dd}: {closest}");
            assert_eq!(fam.value_at_one(-g, 0.37), 0.0);
        }
    }
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
            let ours = NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d)
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
