//! Throughput of the time-domain simulator: at least 20 million simulated samples per second
//! per core for the paper's linear loop; the same engine for a general loop (two-mass
//! device with actuator lag, low-pass velocity, fractional delay) and with friction.
//!
//! Run with `cargo bench -p hapstab --bench simulation`; criterion reports the throughput
//! in elements (= samples) per second.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use hapstab::simulation::{Config, Contact, Friction, HumanForce, LoopModel, Model, Simulator};
use hapstab::{Arm, Delay, Loop, Normalized, Plant, PlantModel, TwoMass, VelocityEstimator, Wall};

/// Samples per benchmark iteration.
const SAMPLES: usize = 1_000_000;

/// A PHANToM-like device (m = 0.1 kg, T = 1 ms, δ = 0.015) held by an arm (γ = 1e-4), a
/// stable wall (α = 0.05, β = 0.1), one sample of delay, pushed with 1 N: the state settles
/// on a non-zero equilibrium, so no denormal numbers slow the arithmetic.
fn config(samples: usize) -> Config {
    let params = Normalized::new(0.05, 0.1, 1e-4, 0.015, 1).expect("valid parameters");
    let model = Model::new(params, 0.1, 1e-3).expect("valid model");
    let mut cfg = Config::new(model, samples);
    cfg.human = HumanForce::Constant(1.0);
    cfg.initial.velocity = 0.05;
    cfg
}

fn bench_linear(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    group.throughput(Throughput::Elements(SAMPLES as u64));
    let cfg = config(SAMPLES);
    group.bench_function("linear_bilateral_d1", |b| {
        b.iter(|| {
            let mut sim = Simulator::new(black_box(&cfg)).expect("valid config");
            let n = sim.advance(SAMPLES).expect("no force function");
            black_box((n, sim.position()))
        })
    });
    let mut cfg_q = cfg.clone();
    cfg_q.effects.contact = Contact::Unilateral;
    cfg_q.effects.quantization = Some(3e-5);
    group.bench_function("unilateral_quantized_d1", |b| {
        b.iter(|| {
            let mut sim = Simulator::new(black_box(&cfg_q)).expect("valid config");
            let n = sim.advance(SAMPLES).expect("no force function");
            black_box((n, sim.position()))
        })
    });
    let mut cfg_f = cfg.clone();
    cfg_f.effects.friction = Some(Friction {
        coulomb: 0.05,
        stiction: 0.08,
    });
    cfg_f.human = HumanForce::function(|t| (40.0 * t).sin());
    group.bench_function("friction_stick_slip_d1", |b| {
        b.iter(|| {
            let mut sim = Simulator::new(black_box(&cfg_f)).expect("valid config");
            let n = sim.advance(SAMPLES).expect("finite force");
            black_box((n, sim.friction_events()))
        })
    });
    let cfg_g = general_config(SAMPLES);
    group.bench_function("general_two_mass_lag_lowpass_fractional", |b| {
        b.iter(|| {
            let mut sim = Simulator::new(black_box(&cfg_g)).expect("valid config");
            let n = sim.advance(SAMPLES).expect("no force function");
            black_box((n, sim.position()))
        })
    });
    group.finish();
}

/// A two-mass device (motor 0.05 kg, handle 0.05 kg, 2 kN/m transmission) held by an arm,
/// with a 0.2 ms actuator lag, a 100 Hz low-pass velocity and 1.4 samples of delay at 1 kHz;
/// a stable wall of 1 kN/m and 2 Ns/m, pushed with 1 N (order 5 with the lag).
fn general_config(samples: usize) -> Config {
    let plant = Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: 0.05,
            motor_damping: 0.5,
            handle_mass: 0.05,
            transmission_stiffness: 2000.0,
            transmission_damping: 1.0,
            arm: Arm {
                mass: 0.5,
                damping: 3.0,
                stiffness: 200.0,
            },
        }),
        2e-4,
    )
    .expect("valid plant");
    let period = 1e-3;
    let lp = Loop::new(
        plant,
        period,
        Delay::from_time(1.4 * period, period).expect("valid delay"),
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
    )
    .expect("valid loop");
    let wall = Wall {
        stiffness: 1000.0,
        damping: 2.0,
    };
    let mut cfg = Config::new(LoopModel::new(lp, wall).expect("finite wall"), samples);
    cfg.human = HumanForce::Constant(1.0);
    cfg.initial.velocity = 0.05;
    cfg
}

criterion_group!(benches, bench_linear);
criterion_main!(benches);
