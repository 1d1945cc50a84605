//! Every margin of one wall (`hapstab::margins::margins`): the paper's loop (the default device
//! and arm) at d = 0 and 1 with the wall `check` uses by default, at d = 10 with K = 500 N/m,
//! B = 0.5 Ns/m.
//! Baseline: python-control's `stability_margins` on the same sampled loop
//! (`benches/baseline/margins_baseline.py`).

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::margins::margins;
use hapstab::model::Loop;
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
    g.finish();
}

criterion_group!(benches, bench_margins);
criterion_main!(benches);
