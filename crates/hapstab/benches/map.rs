//! A 1000×1000 stability map over (α, β) by the Schur–Cohn test, in parallel, for d = 0 and
//! d = 10 (γ = 0.001, δ = 0.015), and over (K, B) for a general loop of order 5 with d = 1. The numpy.roots baseline of the same map is in
//! benches/baseline/; `bash benches/compare.sh` measures both in one run.
//! Run: `cargo bench -p hapstab --bench map`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::map::{Axis, AxisRange, MapKind, wall_map};
use hapstab::model::Delay;
use hapstab::paper::map::{MapSpec, compute_map};
use hapstab::{AffineFamily, Normalized};

#[path = "common/general_loop.rs"]
mod common;
use common::general_loop;

/// The grid used by both this bench and the numpy baseline: α ∈ [−0.05, 1/(d+1/2)],
/// β ∈ [−0.05, 2/(d+1/2)^{1/2}], 1000 × 1000 points.
pub fn spec(d: usize) -> MapSpec {
    let t = d as f64 + 0.5;
    MapSpec::new(
        AxisRange::new(Axis::Alpha, -0.05, 1.0 / t, 1000).expect("valid"),
        AxisRange::new(Axis::Beta, -0.05, 2.0 / t.sqrt(), 1000).expect("valid"),
        Normalized::new(0.0, 0.0, 0.001, 0.015, d).expect("valid"),
    )
    .expect("valid")
}

/// The general loop of the region bench (order 5: two-mass device, arm, actuator lag,
/// low-pass velocity) with d = 1, over K ∈ [−2, 40] kN/m, B ∈ [−5, 40] Ns/m in wall units.
pub fn general_map(fam: &AffineFamily) -> (AxisRange, AxisRange) {
    let (a0, b0) = fam.to_units(-2e3, -5.0);
    let (a1, b1) = fam.to_units(40e3, 40.0);
    (
        AxisRange::new(Axis::Alpha, a0, a1, 1000).expect("valid"),
        AxisRange::new(Axis::Beta, b0, b1, 1000).expect("valid"),
    )
}

fn bench_map(c: &mut Criterion) {
    let mut g = c.benchmark_group("map_1000x1000");
    g.sample_size(10);
    for d in [0usize, 10] {
        let s = spec(d);
        g.bench_with_input(BenchmarkId::new("schur", d), &s, |b, s| {
            b.iter(|| {
                let m = compute_map(black_box(s), MapKind::Stability, &|_| {}).expect("map");
                black_box(m.stable.iter().filter(|&&x| x).count())
            })
        });
    }
    let lp = general_loop(Delay::samples(1).expect("valid"));
    let fam = AffineFamily::of_loop(&lp).expect("family");
    let (x, y) = general_map(&fam);
    g.bench_function("general_loop_order5_d1", |b| {
        b.iter(|| {
            let m = wall_map(black_box(&fam), x, y, MapKind::Stability, &|_| {}).expect("map");
            black_box(m.stable.iter().filter(|&&s| s).count())
        })
    });
    g.finish();
}

criterion_group!(benches, bench_map);
criterion_main!(benches);
