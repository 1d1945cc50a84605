//! A 50-point `sweep` (K_max over every damping B and the passive K_max at each point, as
//! `hapstab sweep` computes them, on two threads): the paper's loop (default device and arm,
//! T = 1 ms) over the delay 0–10 ms and, with a 100 Hz low-pass velocity filter, over the
//! filter's cut-off 20–500 Hz; and a general loop (two-mass device with the typical arm,
//! a 0.2 ms actuator lag, a 200 Hz low-pass velocity filter) over the delay 0–10 ms and over
//! the arm stiffness 0–2000 N/m at d = 10 (`common/general_loop.rs`). `benches/sweep_compare.sh`
//! runs the same files on an earlier commit in the same session.

use criterion::{Criterion, criterion_group, criterion_main};
use hapstab::loop_spec::default_plant;
use hapstab::model::{Delay, Loop, VelocityEstimator};
use hapstab::sweep::{KmaxAt, SweepRange, sweep_param};
use std::hint::black_box;

#[path = "common/general_loop.rs"]
mod common;
use common::general_loop;

fn general(delay: usize) -> Loop {
    general_loop(Delay::samples(delay).expect("valid"))
}

// `clone` of the range: the same file builds on earlier commits, where it is not `Copy`
#[allow(clippy::clone_on_copy)]
fn bench_sweep(c: &mut Criterion) {
    let mut g = c.benchmark_group("sweep");
    g.sample_size(20);
    let paper = Loop::new(
        default_plant().expect("valid"),
        1e-3,
        Delay::samples(0).expect("valid"),
        VelocityEstimator::Backward,
    )
    .expect("valid");
    let delays: SweepRange = "delay-time:0:0.01:50".parse().expect("valid");
    let arm: SweepRange = "arm-stiffness:0:2000:50".parse().expect("valid");
    let cutoffs: SweepRange = "cutoff:20:500:50".parse().expect("valid");
    let lowpass = Loop::new(
        paper.plant.clone(),
        1e-3,
        Delay::samples(0).expect("valid"),
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
    )
    .expect("valid");
    let cases = [
        ("paper_delay_time", paper, delays.clone()),
        ("paper_lowpass_cutoff", lowpass, cutoffs),
        ("general_delay_time", general(0), delays),
        ("general_arm_stiffness", general(10), arm),
    ];
    for (name, lp, range) in cases {
        g.bench_function(name, |b| {
            b.iter(|| {
                black_box(
                    sweep_param(black_box(&lp), &range, KmaxAt::Overall, &|_| {}).expect("sweep"),
                )
            })
        });
    }
    g.finish();
}

criterion_group!(benches, bench_sweep);
criterion_main!(benches);
