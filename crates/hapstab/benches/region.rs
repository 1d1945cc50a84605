//! Exact stable region (polygons to 1e-9 of the region's size) plus α_max, for the paper's
//! upper parameter limits γ = 0.001, δ = 0.015 and d = 0, 1, 2, 10, 100 (issue 3 target:
//! under 1 ms for d ≤ 10). Run: `cargo bench -p hapstab --bench region`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::region::stable_region;
use hapstab::{PlantParams, PolyFamily};

fn bench_region(c: &mut Criterion) {
    let mut g = c.benchmark_group("region");
    g.sample_size(20);
    for d in [0usize, 1, 2, 10, 100] {
        let fam =
            PolyFamily::new(PlantParams::new(0.001, 0.015).expect("valid"), d).expect("valid");
        g.bench_with_input(
            BenchmarkId::new("boundary_and_alpha_max", d),
            &fam,
            |b, fam| {
                b.iter(|| {
                    let r = stable_region(black_box(fam)).expect("region");
                    black_box((r.alpha_max, r.beta_at_alpha_max, r.polygons.len()))
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench_region);
criterion_main!(benches);
