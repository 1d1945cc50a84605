//! The quantization condition K ≤ 2f_c/Δ of Abbott and Okamura (2005) against the energy
//! balance of the library's simulator (exact ZOH stepping, stick–slip Coulomb friction located
//! within each sample, the encoder's round(x/Δ)·Δ), on 20 seeded settings.
//!
//! **Within the published assumptions**: one mass m with viscous damping b and Coulomb friction
//! f_c (static = Coulomb), a bilateral pure spring (B = 0), no delay (d = 0), one encoder; the
//! settings put 2f_c/Δ at 5–30 % of 2b/T so that the quantization condition binds, and the
//! device's time constant m/b at 0.5 % of T.
//!
//! **The energy.** The human force F_H is held over each sample, so the energy the human puts
//! in over sample k is exactly F_H[k]·(x[k+1] − x[k]); E_H = Σ of it over the run. The device
//! with its wall is passive iff E_H ≥ −E(0) for every input: over a long run a negative E_H that
//! grows with the run is energy the wall generates and hands to the human.
//!
//! **The input.** The worst input of the energy argument: the device rests just below an
//! encoder edge e = (j + ½)Δ; on even samples the human pushes with the wall's lower level plus
//! (1 + ε)f_c, on odd samples with its upper level minus (1 + ε)f_c, so each stroke crosses the
//! edge while the held force is still at the level of the side it left. Per in-and-out cycle
//! of travel 2L the wall then hands out K·Δ·L and friction takes 2(1 + ε)f_c·L (viscous
//! damping carries the ε part), so E_H changes sign at K = (1 + ε)·2f_c/Δ: predicted within ε
//! = 2 % of K* = 2f_c/Δ. The test asserts the sign at 0.8K* (E_H > 0, dissipation) and 1.25K*
//! (E_H < 0 and beyond the initial storage, generation), bisects the K where it flips to within
//! 5 % of K*, and checks that random inputs at 0.8K* never take out more than the initial
//! storage.

use crate::common;
use common::SplitMix;
use hapstab::Loop;
use hapstab::params::{Effective, Wall};
use hapstab::passivity_quantized::{ConditionKind, QuantizedWall, quantized_passivity};
use hapstab::simulation::{
    Config, Contact, Effects, Friction, HumanForce, Initial, LoopModel, Simulator,
};

const SETTINGS: usize = 20;
const SAMPLES: usize = 8_000;
const EPS: f64 = 0.02;
/// The edge below which the device starts: j = 0, the edge Δ/2, where the quantized spring
/// stores nothing.
const LEVEL: f64 = 0.0;

#[derive(Debug, Clone, Copy)]
struct Setting {
    mass: f64,
    damping: f64,
    coulomb: f64,
    quantum: f64,
    period: f64,
}

impl Setting {
    fn draw(rng: &mut SplitMix) -> Self {
        let period = rng.log_range(2e-4, 2e-3);
        let damping = rng.range(2.0, 20.0);
        let coulomb = rng.log_range(0.05, 1.0);
        let share = rng.range(0.05, 0.3); // 2f_c/Δ as a share of 2b/T
        Setting {
            mass: 0.005 * period * damping,
            damping,
            coulomb,
            quantum: coulomb * period / (share * damping),
            period,
        }
    }

    fn k_star(&self) -> f64 {
        2.0 * self.coulomb / self.quantum
    }

    /// The stroke per sample of the worst input: ε f_c T / b.
    fn stroke(&self) -> f64 {
        EPS * self.coulomb * self.period / self.damping
    }

    fn start(&self) -> f64 {
        (LEVEL + 0.5) * self.quantum - 0.5 * self.stroke()
    }

    /// The energy stored at the start (at rest): the quantized spring's potential
    /// ∫₀^x K·round(s/Δ)Δ ds, exactly (level n over |s| ∈ [(n − ½)Δ, (n + ½)Δ)).
    fn storage(&self, k: f64) -> f64 {
        let (q, x) = (self.quantum, self.start().abs());
        let n = (x / q).round();
        // the full cells below level n, then level n from (n − ½)Δ to x
        let full: f64 = (1..n as usize).map(|j| j as f64 * q * q).sum();
        let part = if n >= 1.0 {
            n * q * (x - (n - 0.5) * q)
        } else {
            0.0
        };
        k * (full + part)
    }
}

/// E_H over a run of the simulator with the human force profile `force(k, K)`.
fn human_energy(s: &Setting, k: f64, force: &[f64]) -> f64 {
    let plant = Effective::new(s.mass, s.damping, 0.0).unwrap();
    let lp = Loop::paper(plant, s.period, 0).unwrap();
    let model = LoopModel::new(
        lp,
        Wall {
            stiffness: k,
            damping: 0.0,
        },
    )
    .unwrap();
    let mut cfg = Config::new(model, SAMPLES);
    cfg.effects = Effects {
        contact: Contact::Bilateral,
        wall_position: 0.0,
        friction: Some(Friction {
            coulomb: s.coulomb,
            stiction: s.coulomb,
        }),
        quantization: Some(s.quantum),
        saturation: None,
    };
    cfg.human = HumanForce::Samples(force.to_vec());
    cfg.initial = Initial {
        position: s.start(),
        velocity: 0.0,
    };
    let mut sim = Simulator::new(&cfg).unwrap();
    let mut energy = 0.0;
    for f in force {
        let x0 = sim.position();
        assert_eq!(sim.advance(1).unwrap(), 1);
        energy += f * (sim.position() - x0);
    }
    energy
}

/// The worst input of the module doc at stiffness K.
fn worst_input(s: &Setting, k: f64) -> Vec<f64> {
    let (lo, hi) = (k * LEVEL * s.quantum, k * (LEVEL + 1.0) * s.quantum);
    let push = (1.0 + EPS) * s.coulomb;
    (0..SAMPLES)
        .map(|i| if i % 2 == 0 { lo + push } else { hi - push })
        .collect()
}

#[test]
fn closed_form_binds_as_drawn() {
    let mut rng = SplitMix(2005_0952);
    for _ in 0..SETTINGS {
        let s = Setting::draw(&mut rng);
        let w = QuantizedWall {
            stiffness: s.k_star(),
            damping: 0.0,
            period: s.period,
            delay: 0,
            device_damping: s.damping,
            coulomb: s.coulomb,
            quantization: s.quantum,
        };
        let p = quantized_passivity(&w).unwrap();
        assert_eq!(p.binding, ConditionKind::Quantization);
        assert!(p.quantization.within_assumptions && p.sampling.within_assumptions);
        assert!((p.k_max - 2.0 * s.coulomb / s.quantum).abs() <= 1e-12 * p.k_max);
        assert!(p.sampling.k_bound >= 3.0 * p.k_max);
    }
}

#[test]
fn energy_balance_changes_sign_at_the_quantization_bound() {
    let mut rng = SplitMix(2005_0952);
    let mut worst_flip: f64 = 0.0;
    for i in 0..SETTINGS {
        let s = Setting::draw(&mut rng);
        let ks = s.k_star();
        let below = human_energy(&s, 0.8 * ks, &worst_input(&s, 0.8 * ks));
        let above = human_energy(&s, 1.25 * ks, &worst_input(&s, 1.25 * ks));
        assert!(below > 0.0, "setting {i} {s:?}: E_H = {below} at 0.8 K*");
        assert!(
            above < -s.storage(1.25 * ks),
            "setting {i} {s:?}: E_H = {above} at 1.25 K*, storage {}",
            s.storage(1.25 * ks)
        );
        let (mut lo, mut hi) = (0.8 * ks, 1.25 * ks);
        for _ in 0..12 {
            let mid = 0.5 * (lo + hi);
            if human_energy(&s, mid, &worst_input(&s, mid)) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let flip = 0.5 * (lo + hi) / ks;
        worst_flip = worst_flip.max((flip - 1.0).abs());
        assert!(
            (flip - 1.0).abs() <= 0.05,
            "setting {i} {s:?}: flips at {flip} K*"
        );
        println!(
            "setting {i}: flips at {flip:.5} K* (predicted {:.5})",
            1.0 + EPS
        );
    }
    println!("largest |flip/K* − 1| = {worst_flip:.4}");
}

#[test]
fn random_inputs_below_the_bound_generate_nothing() {
    let mut rng = SplitMix(2006_0422);
    for i in 0..SETTINGS {
        let s = Setting::draw(&mut rng);
        let k = 0.8 * s.k_star();
        let mid = k * (LEVEL + 0.5) * s.quantum;
        // random pushes around the edge's force: up to 3 f_c either way, and the worst input
        // with a random excess
        let amp = s.coulomb * rng.range(1.0, 3.0);
        let noise: Vec<f64> = (0..SAMPLES)
            .map(|_| mid + amp * rng.range(-1.0, 1.0))
            .collect();
        let excess = rng.range(0.0, 0.5);
        let (lo, hi) = (k * LEVEL * s.quantum, k * (LEVEL + 1.0) * s.quantum);
        let push = (1.0 + excess) * s.coulomb;
        let alternating: Vec<f64> = (0..SAMPLES)
            .map(|j| if j % 2 == 0 { lo + push } else { hi - push })
            .collect();
        for (name, f) in [("noise", noise), ("alternating", alternating)] {
            let e = human_energy(&s, k, &f);
            assert!(
                e >= -s.storage(k),
                "setting {i} {s:?} {name}: E_H = {e} below −storage {}",
                s.storage(k)
            );
        }
    }
}
