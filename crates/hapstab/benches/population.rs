//! The human varies: P(stable) of one wall over 10⁵ operators of the paper's Section IV
//! population (`population::wall_probability`, each operator an exact verdict), the curve
//! P(stable) against K over 10⁴ operators (`stability_probability`, each an exact stable
//! interval), and the robust K_max over a box of the arm's mass, damping and stiffness
//! (`robust::robust_kmax`: 256 samples and the 8 corners solved, compass refinement, 10⁴
//! plants verified). The default device held by the arm, T = 1 ms, d = 0, B = 5 Ns/m.
//! Baseline: `benches/baseline/population_numpy.py` (numpy.roots per operator, and a
//! bisection on K with numpy.roots per plant), run beside it by
//! `bash benches/population_compare.sh`.

use criterion::{Criterion, criterion_group, criterion_main};
use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::params::{Arm, Device, Wall};
use hapstab::population::{Population, stability_probability, wall_probability};
use hapstab::robust::{BoxSide, RobustOptions, robust_kmax};
use hapstab::sweep::SweepParam;
use std::hint::black_box;

fn held() -> Loop {
    let plant = Plant::held_device(Device::PHANTOM_LIKE, Arm::TYPICAL).expect("valid");
    Loop::new(
        plant,
        1e-3,
        Delay::samples(0).expect("valid"),
        VelocityEstimator::Backward,
    )
    .expect("valid")
}

fn bench_population(c: &mut Criterion) {
    let mut g = c.benchmark_group("population");
    g.sample_size(10);
    let lp = held();
    let wall = Wall {
        stiffness: 2e4,
        damping: 5.0,
    };
    g.bench_function("wall_1e5", |b| {
        b.iter(|| {
            black_box(wall_probability(&lp, &Population::SectionIv, wall, 100_000, 1).expect("ok"))
        })
    });
    g.bench_function("curve_1e4", |b| {
        b.iter(|| {
            black_box(
                stability_probability(&lp, &Population::SectionIv, 5.0, 10_000, 1, &[0.99])
                    .expect("ok"),
            )
        })
    });
    let sides = [
        BoxSide {
            param: SweepParam::ArmStiffness,
            lo: 0.0,
            hi: 2000.0,
        },
        BoxSide {
            param: SweepParam::ArmMass,
            lo: 0.2,
            hi: 2.0,
        },
        BoxSide {
            param: SweepParam::ArmDamping,
            lo: 2.0,
            hi: 12.0,
        },
    ];
    g.bench_function("robust_box", |b| {
        b.iter(|| black_box(robust_kmax(&lp, &sides, 5.0, &RobustOptions::default()).expect("ok")))
    });
    g.finish();
}

criterion_group!(benches, bench_population);
criterion_main!(benches);
