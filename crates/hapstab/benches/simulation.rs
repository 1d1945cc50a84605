//! Throughput of the time-domain simulator (issue 6: at least 20 million simulated samples
//! per second per core in the linear case).
//!
//! Run with `cargo bench -p hapstab --bench simulation`; criterion reports the throughput
//! in elements (= samples) per second.

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use hapstab::Normalized;
use hapstab::simulation::{Config, Contact, HumanForce, Model, Simulator};

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
    group.finish();
}

criterion_group!(benches, bench_linear);
criterion_main!(benches);
