//! The stability boundary of Section V (`hapstab::boundary`): the pure mass's boundary in
//! closed form, and the stable stiffness interval shrinking as the plant's damping grows.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use hapstab::PlantParams;
use hapstab::boundary::stable_stiffness_intervals;
use hapstab::paper::NormalizedFamily;
use hapstab::stability::Verdict;
use hapstab::verdict::decide_coefficients;

fn verdict(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize) -> Verdict {
    let fam = NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap();
    decide_coefficients(&fam.coefficients(alpha, beta)).verdict
}

/// Pure mass, d = 0: p(z) = z³ + (s/2 − 2)z² + (1 + α/2)z − β/2 with s = α + β. Jury's
/// conditions are p(1) = α > 0, p(−1) = −4 < 0, |β| < 2 and 1 − β²/4 > |a0 a2 − a1|, whose
/// boundary is α = 2β(2 − β)/(2 + β) for 0 < β < 2 (largest at β = 2√2 − 2).
fn pure_mass_alpha(beta: f64) -> f64 {
    2.0 * beta * (2.0 - beta) / (2.0 + beta)
}

fn fam(gamma: f64, delta: f64, d: usize) -> NormalizedFamily {
    NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap()
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

/// In the human range of eq. (15) the stable interval grows with δ: at every sampled (γ, β),
/// hi is non-decreasing along δ ∈ [0, 0.015], so the worst damping of a box is its lower end.
#[test]
fn stable_interval_monotone_in_delta() {
    for d in [0usize, 1] {
        for gi in 0..=4 {
            let g = 1e-3 * gi as f64 / 4.0;
            for bi in 1..=12 {
                let b = 0.08 * bi as f64;
                let mut prev = f64::NEG_INFINITY;
                for di in 0..=15 {
                    let f = fam(g, 1e-3 * di as f64, d);
                    let hi = stable_stiffness_intervals(&f, b)
                        .iter()
                        .map(|iv| iv.hi)
                        .fold(f64::NEG_INFINITY, f64::max);
                    assert!(hi >= prev, "d={d} γ={g} β={b} δ={}", 1e-3 * di as f64);
                    prev = hi;
                }
            }
        }
    }
}
