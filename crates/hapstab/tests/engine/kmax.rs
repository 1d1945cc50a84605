//! K_max answers (`hapstab::kmax`): the velocity estimator's noise gain against its closed
//! forms, the renderable band against F_n·√12/(Δ‖V‖₂), K_max over it against the pure
//! mass's closed-form boundary α < 2β(2 − β)/(2 + β) (d = 0, backward difference), and the
//! design query's three numbers against the separate queries and the verdict.

use crate::common;
use common::SplitMix;
use common::loops::{random_loop, verdict};
use hapstab::Verdict;
use hapstab::kmax::{
    KmaxQuery, NoiseModel, RenderableBand, kmax, renderable_band, velocity_noise_gain,
};
use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::params::Effective;

fn device(m: f64, b: f64, period: f64, velocity: VelocityEstimator) -> Loop {
    let plant = Plant::mass_spring_damper(Effective::new(m, b, 0.0).unwrap()).unwrap();
    Loop::new(plant, period, Delay::samples(0).unwrap(), velocity).unwrap()
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * b.abs()
}

#[test]
fn noise_gain_closed_forms() {
    let t = 1e-3;
    // backward difference: h = [1, −1]/T
    let g = velocity_noise_gain(&device(0.1, 1.5, t, VelocityEstimator::Backward)).unwrap();
    assert!(close(g, 2f64.sqrt() / t, 1e-14), "{g}");
    // average over N: h = [1, 0, …, 0, −1]/(NT)
    let avg = VelocityEstimator::Average { samples: 15 };
    let g = velocity_noise_gain(&device(0.1, 1.5, t, avg)).unwrap();
    assert!(close(g, 2f64.sqrt() / (15.0 * t), 1e-14), "{g}");
    // first-order low-pass of the backward difference, a = exp(−2π f_c T):
    // Σ h² = (1 − a)²/T² · 2/(1 + a)
    for fc in [1.0, 30.0, 100.0, 400.0] {
        let a = (-2.0 * std::f64::consts::PI * fc * t).exp();
        let lp = device(0.1, 1.5, t, VelocityEstimator::LowPass { cutoff_hz: fc });
        let g = velocity_noise_gain(&lp).unwrap();
        let exact = (1.0 - a) / t * (2.0 / (1.0 + a)).sqrt();
        assert!(close(g, exact, 1e-12), "f_c {fc}: {g} vs {exact}");
    }
}

#[test]
fn noise_gain_of_an_unstable_filter_is_none() {
    // v = y/(1 − 1.01 z⁻¹): a pole outside the unit circle
    let iir = VelocityEstimator::Iir {
        b: vec![1.0, -1.0],
        a: vec![1.0, -1.01],
    };
    let lp = device(0.1, 1.5, 1e-3, iir);
    assert_eq!(velocity_noise_gain(&lp), None);
}

fn band_of(lp: &Loop, noise: NoiseModel) -> RenderableBand {
    let sys = hapstab::System::of(lp).unwrap();
    renderable_band(&sys, noise).unwrap().unwrap()
}

#[test]
fn renderable_band_of_the_pure_mass_is_closed_form() {
    // pure mass m, T, d = 0, backward difference: B_r = F_n·√12·T/(Δ·√2) and K_max over
    // 0 ≤ B ≤ B_r is the boundary α = 2β(2 − β)/(2 + β) at β_r = B_r·T/m (it rises with β
    // up to β = √8 − 2 ≈ 0.83).
    for (m, t, dx, fnoise) in [
        (0.1, 1e-3, 1e-5, 0.05),
        (1.0, 1e-3, 1e-6, 0.1),
        (0.5, 5e-4, 2e-5, 0.02),
    ] {
        let lp = device(m, 0.0, t, VelocityEstimator::Backward);
        let rb = band_of(&lp, NoiseModel::new(dx, fnoise).unwrap());
        let b_r = fnoise * 12f64.sqrt() * t / (dx * 2f64.sqrt());
        assert!(close(rb.b_max, b_r, 1e-14), "{} vs {b_r}", rb.b_max);
        let beta = b_r * t / m;
        assert!(beta < 8f64.sqrt() - 2.0);
        let k = 2.0 * beta * (2.0 - beta) / (2.0 + beta) * m / (t * t);
        assert!(close(rb.k_max.unwrap(), k, 1e-9), "{:?} vs {k}", rb.k_max);
        assert!(close(rb.b_at_k_max.unwrap(), b_r, 1e-12));
        assert_eq!(rb.k_max_attained, Some(true));
    }
}

#[test]
fn a_low_pass_widens_the_band() {
    let t = 1e-3;
    let noise = NoiseModel::default();
    let back = band_of(&device(0.1, 1.5, t, VelocityEstimator::Backward), noise);
    let low = device(0.1, 1.5, t, VelocityEstimator::LowPass { cutoff_hz: 100.0 });
    let low = band_of(&low, noise);
    assert!(
        low.b_max > 2.0 * back.b_max,
        "{} vs {}",
        low.b_max,
        back.b_max
    );
}

#[test]
fn design_query_is_the_three_separate_answers() {
    let mut rng = SplitMix(0x6b6d_6178);
    let (mut checked, mut marginal) = (0, 0);
    for i in 0..400 {
        let Some(lp) = random_loop(&mut rng, i) else {
            continue;
        };
        if lp.delay.samples > 20 {
            continue;
        }
        let sys = hapstab::System::of(&lp).unwrap();
        let fam = sys.family();
        let design = kmax(&sys, KmaxQuery::Design(NoiseModel::default())).unwrap();
        let all = kmax(
            &sys,
            KmaxQuery::Band {
                lo: 0.0,
                hi: f64::INFINITY,
            },
        )
        .unwrap();
        assert_eq!(design.k_max, all.k_max);
        assert_eq!(design.b_at_k_max, all.b_at_k_max);
        let zero = kmax(&sys, KmaxQuery::AtDamping(0.0)).unwrap();
        assert_eq!(design.k_max_at_zero_damping, zero.k_max);
        let Some(rb) = design.renderable else {
            continue;
        };
        // the band's K_max lies between B = 0's and the overall one, and is a boundary
        // point by the verdict where it is attained
        if let (Some(k), Some(b), Some(true)) = (rb.k_max, rb.b_at_k_max, rb.k_max_attained) {
            assert!(k >= zero.k_max.unwrap_or(f64::NEG_INFINITY) * (1.0 - 1e-9));
            assert!(k <= all.k_max.unwrap() * (1.0 + 1e-9));
            // the verdict: never unstable inside nor stable outside; marginal (ρ within the
            // rounding band of 1) only where 1e-6 in K moves ρ less than that band
            let (a_in, bu) = fam.to_units(k - 1e-6 * k.abs(), b);
            let (a_out, _) = fam.to_units(k + 1e-6 * k.abs(), b);
            let (inside, outside) = (verdict(&lp, a_in, bu), verdict(&lp, a_out, bu));
            assert_ne!(inside, Verdict::Unstable, "loop {i}: {lp:?} {rb:?}");
            assert_ne!(outside, Verdict::Stable, "loop {i}: {lp:?} {rb:?}");
            marginal += usize::from(inside == Verdict::Marginal || outside == Verdict::Marginal);
            // at the band's edge it is the top of the exact stable interval there
            if b == rb.b_max {
                let at = kmax(&sys, KmaxQuery::AtDamping(b)).unwrap();
                assert!(close(k, at.k_max.unwrap(), 1e-9), "loop {i}: {k} vs {at:?}");
            }
            checked += 1;
        }
    }
    assert!(checked > 100, "only {checked} loops checked");
    // K_max over the band is attained where the exact stable interval at its damping reaches
    // it; at fast sampling 1e-6 in K moves ρ by less than the verdict's rounding band there
    // (about one loop in ten of these)
    assert!(marginal * 8 < checked, "{marginal} of {checked} marginal");
}

#[test]
fn noise_model_refuses_non_positive_values() {
    for (dx, f) in [
        (0.0, 0.05),
        (-1e-5, 0.05),
        (1e-5, 0.0),
        (f64::NAN, 0.05),
        (1e-5, f64::INFINITY),
    ] {
        let e = NoiseModel::new(dx, f).unwrap_err().to_string();
        assert!(e.contains("must be a positive finite number"), "{e}");
    }
}
