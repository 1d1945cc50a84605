//! Tests of the clipped trace of a growing run (`simulate_clipped`): the scale of a run's
//! start from its closed form, the cut at the first sample whose |x| exceeds 10³ times it
//! (checked against a whole run recorded at every sample), and no cut for runs that are not
//! growing.

use hapstab::Normalized;
use hapstab::simulation::{
    CLIP_FACTOR, Config, Contact, Effects, HumanForce, Initial, Model, Outcome, Simulator,
    simulate, simulate_clipped, start_scale,
};

const M: f64 = 0.1;
const T: f64 = 1e-3;

fn config(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize, samples: usize) -> Config {
    let p = Normalized::new(alpha, beta, gamma, delta, d).unwrap();
    Config::new(Model::new(p, M, T).unwrap(), samples)
}

/// The scale of the start is the largest of |x(0)|, |x_w|, |ẋ(0)|·T and |F_H|·T²/m.
#[test]
fn start_scale_is_the_largest_one_sample_displacement() {
    let mut c = config(0.1, 0.3, 0.001, 0.01, 0, 100);
    assert_eq!(start_scale(&c), 0.0, "at rest at the origin, no push");
    c.initial = Initial {
        position: -1e-3,
        velocity: 0.5,
    };
    c.human = HumanForce::Constant(2.0);
    // |x(0)| = 1 mm beats 0.5 m/s · 1 ms = 0.5 mm and 2 N · (1 ms)² / 0.1 kg = 20 µm
    assert_eq!(start_scale(&c), 1e-3);
    c.initial.position = 0.0;
    assert_eq!(start_scale(&c), 0.5 * T);
    c.initial.velocity = 0.0;
    c.human = HumanForce::Samples(vec![-30.0, 1.0]);
    assert!((start_scale(&c) - 30.0 * T * T / M).abs() < 1e-18);
    c.effects.wall_position = 0.02;
    assert_eq!(start_scale(&c), 0.02);
}

/// The first sample k of the whole run, recorded at every sample, with |x[k]| > threshold,
/// and that recording's positions.
fn first_beyond_at_every_sample(c: &Config, samples: usize, threshold: f64) -> (usize, Vec<f64>) {
    let mut every = c.clone();
    every.samples = samples;
    every.max_samples = samples;
    every.trace_rows = samples + 1;
    let mut sim = Simulator::new(&every).unwrap();
    sim.advance(samples).unwrap();
    assert_eq!(sim.trace_stride(), 1);
    let x = sim.take_trace().unwrap().position;
    let k = x
        .iter()
        .position(|v| !v.is_finite() || v.abs() > threshold)
        .unwrap();
    (k, x)
}

/// A bilateral wall beyond α_max (d = 1) from x(0) = 1 mm grows. Its trace, recorded
/// coarsely (50 rows), is cut before the first sample whose |x| exceeds 10³ · 1 mm = 1 m, found
/// in a recording of every sample; the kept rows are recorded again finely and equal that
/// recording's; the verdict is the whole run's.
#[test]
fn a_growing_run_is_cut_where_x_first_exceeds_the_threshold() {
    let mut c = config(0.5, 0.2, 0.001, 0.005, 1, 300);
    c.initial.position = 1e-3;
    c.trace_rows = 50;
    let whole = simulate(&c).unwrap();
    assert_eq!(whole.verdict.outcome, Outcome::Growing);
    assert!(whole.trace_stride > 1, "{}", whole.trace_stride);
    let (run, clip) = simulate_clipped(&c).unwrap();
    let clip = clip.expect("a growing run is cut");
    assert_eq!((clip.start_scale, clip.factor), (1e-3, CLIP_FACTOR));
    assert_eq!(clip.threshold, 1.0);
    assert_eq!(run.verdict.outcome, whole.verdict.outcome);
    assert_eq!(run.verdict.reason, whole.verdict.reason);
    assert_eq!(run.samples, whole.samples);

    let (k, every) = first_beyond_at_every_sample(&c, whole.samples, 1.0);
    assert_eq!(clip.sample, k);
    assert_eq!(clip.position, every[k]);
    assert!((clip.time - k as f64 * T).abs() < 1e-12);
    let tr = run.trace.unwrap();
    let s = run.trace_stride;
    assert!(s < whole.trace_stride, "recorded again more finely: {s}");
    assert_eq!(tr.position.len(), k.div_ceil(s), "rows before sample {k}");
    for (i, x) in tr.position.iter().enumerate() {
        assert_eq!(*x, every[i * s], "row {i}");
        assert!(x.abs() <= 1.0);
    }
    for col in [&tr.time, &tr.velocity, &tr.wall_force, &tr.human_force] {
        assert_eq!(col.len(), tr.position.len());
    }
}

/// Runs that are not growing keep their whole trace: a stable wall (decaying) and a
/// unilateral wall beyond α_max that bounces (limit cycle: the device of 0.2 kg, 2 Ns/m held
/// by a 1 kg, 6 Ns/m, 350 N/m arm, K = 20 kN/m, B = 5 Ns/m, d = 1, pushed with 1 N from rest at
/// the surface), whose motion exceeds 10³ times its start scale 1 N · T²/1.2 kg without growing.
#[test]
fn runs_that_do_not_grow_are_not_cut() {
    let mut stable = config(0.05, 0.3, 0.001, 0.015, 0, 400);
    stable.initial.position = 1e-3;
    stable.trace_rows = 2000;
    let m = 1.2;
    let p = Normalized::new(
        20e3 * T * T / m,
        5.0 * T / m,
        350.0 * T * T / m,
        8.0 * T / m,
        1,
    )
    .unwrap();
    let mut bounce = Config::new(Model::new(p, m, T).unwrap(), 300);
    bounce.effects = Effects {
        contact: Contact::Unilateral,
        ..Effects::LINEAR
    };
    bounce.human = HumanForce::Constant(1.0);
    bounce.trace_rows = 2000;
    assert_eq!(start_scale(&bounce), T * T / m);
    for (c, outcome) in [(stable, Outcome::Decaying), (bounce, Outcome::LimitCycle)] {
        let whole = simulate(&c).unwrap();
        assert_eq!(whole.verdict.outcome, outcome);
        let (run, clip) = simulate_clipped(&c).unwrap();
        assert_eq!(clip, None);
        assert_eq!(run.trace, whole.trace);
        assert_eq!(run.trace_stride, whole.trace_stride);
        if outcome == Outcome::LimitCycle {
            let peak = run
                .trace
                .unwrap()
                .position
                .iter()
                .fold(0.0f64, |a, x| a.max(x.abs()));
            assert!(peak > CLIP_FACTOR * start_scale(&c), "{peak}");
        }
    }
}
