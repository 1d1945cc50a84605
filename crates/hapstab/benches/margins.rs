//! Every margin of one wall (`hapstab::margins::margins`): the paper's loop (the default device
//! and arm) at d = 0 and 1 with the wall `check` uses by default, at d = 10 with K = 500 N/m,
//! B = 0.5 Ns/m; and a general loop of order 6 at d = 10 with the same wall: the default
//! device and arm behind an 80 Hz transmission resonance (damping ratio 0.05) and two 0.5 ms
//! actuator lags, P(s) = ω²/((1.1 s² + 7.5 s + 350)(s² + 2ζω s + ω²)(τ s + 1)²).
//! Baseline: python-control's `stability_margins` on the same sampled loop
//! (`benches/baseline/margins_baseline.py`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::margins::margins;
use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::params::{Effective, Wall};
use std::hint::black_box;

fn bench_margins(c: &mut Criterion) {
    let mut g = c.benchmark_group("margins");
    g.sample_size(20);
    // the default wall at d = 0 and 1; at d = 10 it is unstable, so a softer one (stable)
    for (d, k, b) in [(0usize, 1e4, 10.0), (1, 1e4, 10.0), (10, 500.0, 0.5)] {
        let wall = Wall {
            stiffness: k,
            damping: b,
        };
        let lp =
            Loop::paper(Effective::new(1.1, 7.5, 350.0).expect("valid"), 1e-3, d).expect("valid");
        g.bench_with_input(BenchmarkId::new("paper_loop", d), &lp, |b, lp| {
            b.iter(|| black_box(margins(black_box(lp), wall).expect("margins")))
        });
    }
    let wall = Wall {
        stiffness: 500.0,
        damping: 0.5,
    };
    let lp = Loop::new(
        Plant::new(order_six(), 0.0).expect("valid"),
        1e-3,
        Delay::samples(10).expect("valid"),
        VelocityEstimator::Backward,
    )
    .expect("valid");
    g.bench_with_input(BenchmarkId::new("order_6_loop", 10), &lp, |b, lp| {
        b.iter(|| black_box(margins(black_box(lp), wall).expect("margins")))
    });
    g.finish();
}

/// The order-6 plant of the module doc (descending coefficients in s).
fn order_six() -> PlantModel {
    let mul = |a: &[f64], b: &[f64]| -> Vec<f64> {
        let mut c = vec![0.0; a.len() + b.len() - 1];
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                c[i + j] += x * y;
            }
        }
        c
    };
    let (w, zeta, tau) = (2.0 * std::f64::consts::PI * 80.0, 0.05, 5e-4);
    let den = mul(
        &mul(&[1.1, 7.5, 350.0], &[1.0, 2.0 * zeta * w, w * w]),
        &mul(&[tau, 1.0], &[tau, 1.0]),
    );
    PlantModel::TransferFunction {
        num: vec![w * w],
        den,
    }
}

criterion_group!(benches, bench_margins);
criterion_main!(benches);
