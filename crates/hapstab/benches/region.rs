//! Exact stable region (polygons to 1e-9 of the region's size) plus α_max:
//! - the paper's upper parameter limits γ = 0.001, δ = 0.015 and d = 0, 1, 2, 10, 100
//!   (target: under 1 ms for d ≤ 10);
//! - a general loop of order 5 (two-mass device with the typical arm and a 0.2 ms actuator
//!   lag, low-pass velocity at 200 Hz) with d = 0, 1, 10 and a fractional delay of 1.5
//!   samples (target: region and K_max under 2 ms for d ≤ 10).
//!
//! Run: `cargo bench -p hapstab --bench region`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::model::Delay;
use hapstab::paper::NormalizedFamily;
use hapstab::region::stable_region;
use hapstab::{AffineFamily, PlantParams};

#[path = "common/general_loop.rs"]
mod common;
use common::general_loop;

fn bench_region(c: &mut Criterion) {
    let mut g = c.benchmark_group("region");
    g.sample_size(20);
    for d in [0usize, 1, 2, 10, 100] {
        let fam = NormalizedFamily::new(PlantParams::new(0.001, 0.015).expect("valid"), d)
            .expect("valid");
        g.bench_with_input(
            BenchmarkId::new("boundary_and_alpha_max", d),
            &fam,
            |b, fam| {
                b.iter(|| {
                    let r = stable_region(black_box(fam)).expect("region");
                    black_box((r.a_max, r.b_at_a_max, r.polygons.len()))
                })
            },
        );
    }
    let delays = [
        ("0", Delay::samples(0)),
        ("1", Delay::samples(1)),
        ("10", Delay::samples(10)),
        ("1.5", Delay::from_time(1.5e-3, 1e-3)),
    ];
    for (label, delay) in delays {
        let lp = general_loop(delay.expect("valid delay"));
        g.bench_with_input(
            BenchmarkId::new("general_loop_order5", label),
            &lp,
            |b, lp| {
                b.iter(|| {
                    // discretization, family, region and K_max from scratch
                    let fam = AffineFamily::of_loop(black_box(lp)).expect("family");
                    let r = stable_region(&fam).expect("region");
                    black_box(fam.to_physical(r.a_max, r.b_at_a_max))
                })
            },
        );
    }
    g.finish();
}

criterion_group!(benches, bench_region);
criterion_main!(benches);
