//! A 1000×1000 stability map over (α, β) by the Schur–Cohn test, in parallel, for d = 0 and
//! d = 10 (γ = 0.001, δ = 0.015). The numpy.roots baseline of the same map is in
//! benches/baseline/; `bash benches/compare.sh` measures both in one run.
//! Run: `cargo bench -p hapstab --bench map`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::Normalized;
use hapstab::map::{Axis, AxisRange, MapKind, MapSpec, compute_map};

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

fn bench_map(c: &mut Criterion) {
    let mut g = c.benchmark_group("map_1000x1000");
    g.sample_size(10);
    for d in [0usize, 10] {
        let s = spec(d);
        g.bench_with_input(BenchmarkId::new("schur", d), &s, |b, s| {
            b.iter(|| {
                let m = compute_map(black_box(s), MapKind::Stability, &|_| {});
                black_box(m.stable.iter().filter(|&&x| x).count())
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_map);
criterion_main!(benches);
