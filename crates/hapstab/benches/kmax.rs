//! K_max without the polygon against the methods it replaces, on the general loop of the
//! region benchmark (a two-mass device held by the typical arm, a 0.2 ms actuator lag, a
//! 200 Hz low-pass velocity estimate; p of degree 7 + d) at d = 0, 1 and 10:
//! - at one damping (B = 5 Ns/m): the stable intervals from the Cayley crossing polynomial
//!   (`boundary::stable_stiffness_intervals`) against the θ scan they replace
//!   (`stable_between(scanned_line_crossings)`), from the loop's family;
//! - over the damping band B ≥ 0: `kmax_band::k_max_band` against the exact region's polygon
//!   and `region::alpha_max_within`;
//! - the whole `kmax` query at one damping and over the band from the loop (discretization
//!   included).
//!
//! Run single-threaded beside the numpy baseline: `bash benches/kmax_compare.sh`.

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use hapstab::AffineFamily;
use hapstab::boundary::{
    WallLine, scanned_line_crossings, stable_between, stable_stiffness_intervals,
};
use hapstab::kmax::{KmaxQuery, kmax};
use hapstab::kmax_band::k_max_band;
use hapstab::model::Delay;
use hapstab::region::{alpha_max_within, stable_region};

#[path = "common/general_loop.rs"]
mod common;
use common::general_loop;

fn bench_kmax(c: &mut Criterion) {
    let mut g = c.benchmark_group("kmax");
    g.sample_size(30);
    for d in [0usize, 1, 10] {
        let lp = general_loop(Delay::samples(d).expect("valid delay"));
        let fam = AffineFamily::of_loop(&lp).expect("family");
        let (_, b) = fam.to_units(0.0, 5.0);
        g.bench_with_input(BenchmarkId::new("at_damping", d), &fam, |bch, fam| {
            bch.iter(|| black_box(stable_stiffness_intervals(black_box(fam), b)))
        });
        g.bench_with_input(BenchmarkId::new("at_damping_scan", d), &fam, |bch, fam| {
            bch.iter(|| {
                let line = WallLine::stiffness_axis(b);
                let xs = scanned_line_crossings(black_box(fam), &line);
                black_box(stable_between(fam, &line, &xs))
            })
        });
        g.bench_with_input(BenchmarkId::new("band", d), &fam, |bch, fam| {
            bch.iter(|| black_box(k_max_band(black_box(fam), 0.0, f64::INFINITY)))
        });
        g.bench_with_input(BenchmarkId::new("band_region", d), &fam, |bch, fam| {
            bch.iter(|| {
                let r = stable_region(black_box(fam)).expect("region");
                black_box(alpha_max_within(fam, &r, 0.0, f64::INFINITY).expect("max"))
            })
        });
        g.bench_with_input(BenchmarkId::new("query_at_damping", d), &lp, |bch, lp| {
            bch.iter(|| {
                let sys = hapstab::System::of(black_box(lp)).expect("system");
                black_box(kmax(&sys, KmaxQuery::AtDamping(5.0)).expect("kmax"))
            })
        });
        g.bench_with_input(BenchmarkId::new("query_band", d), &lp, |bch, lp| {
            bch.iter(|| {
                let sys = hapstab::System::of(black_box(lp)).expect("system");
                let q = KmaxQuery::Band {
                    lo: 0.0,
                    hi: f64::INFINITY,
                };
                black_box(kmax(&sys, q).expect("kmax"))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_kmax);
criterion_main!(benches);
