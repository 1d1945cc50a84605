//! All roots of p(z) at d = 10, 200 and 2000 (degree 13, 203, 2003) for γ = 0.001,
//! δ = 0.015, α = 0.5/(d + 1/2), β = 1/(d + 1/2)^{1/2}: the Aberth–Ehrlich finder behind
//! `stability::roots`, the companion-matrix cross-check (d ≤ 200; it takes about 90 s at
//! d = 2000) and the full `Analysis` (Schur–Cohn verdict reconciled with the radius).
//! The numpy.roots baseline of the same polynomials is benches/baseline/numpy_roots.py;
//! `bash benches/compare.sh` measures both in one run.
//! Run: `cargo bench -p hapstab --bench roots`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::PlantParams;
use hapstab::paper::NormalizedFamily;
use hapstab::stability::{Analysis, roots, roots_companion};

/// The polynomial shared with the numpy baseline.
pub fn poly(d: usize) -> Vec<f64> {
    let t = d as f64 + 0.5;
    NormalizedFamily::new(PlantParams::new(0.001, 0.015).expect("valid"), d)
        .expect("valid")
        .coefficients(0.5 / t, 1.0 / t.sqrt())
}

fn bench_roots(c: &mut Criterion) {
    let mut g = c.benchmark_group("roots");
    g.sample_size(10);
    for d in [10usize, 200, 2000] {
        let p = poly(d);
        g.bench_with_input(BenchmarkId::new("aberth", d), &p, |b, p| {
            b.iter(|| roots(black_box(p)).expect("converges").len())
        });
        g.bench_with_input(BenchmarkId::new("analysis", d), &p, |b, p| {
            b.iter(|| Analysis::of_poly(black_box(p)).expect("decides").verdict)
        });
        if d <= 200 {
            g.bench_with_input(BenchmarkId::new("companion", d), &p, |b, p| {
                b.iter(|| roots_companion(black_box(p)).expect("converges").len())
            });
        }
    }
    g.finish();
}

criterion_group!(benches, bench_roots);
criterion_main!(benches);
