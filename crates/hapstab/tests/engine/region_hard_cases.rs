//! Regions of loops that are hard to draw, right or refused: undamped two-mass devices (a
//! lossless resonance, the curve through the wall-free point twice), regions far thinner
//! than their curve's extent (fast sampling with a slow velocity filter), corners where K_max
//! is a supremum.
//!
//! Expected values come from methods independent of the polygons: the exact stable intervals
//! at fixed damping (1-D, matched to 1e-6 by the state-space referee on all 915 interval sets
//! of `fixtures/statespace_loops.json`) scanned densely over the damping, and the referee's
//! spectral radii of single walls quoted from its fixture.

use hapstab::AffineFamily;
use hapstab::boundary::{WallPoint, stable_stiffness_intervals};
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Effective};
use hapstab::region::{CONFIRM_REL, StableRegion, alpha_max_within, stable_region};

/// The undamped two-mass device (no motor, transmission or arm damping) of the audit.
fn undamped_two_mass(period: f64, lag: f64, delay: Delay, v: VelocityEstimator) -> AffineFamily {
    let plant = Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: 0.804655568232,
            motor_damping: 0.0,
            handle_mass: 0.417894852263,
            transmission_stiffness: 21962.7190042,
            transmission_damping: 0.0,
            arm: Arm {
                mass: 0.0,
                damping: 0.0,
                stiffness: 0.0,
            },
        }),
        lag,
    )
    .unwrap();
    AffineFamily::of_loop(&Loop::new(plant, period, delay, v).unwrap()).unwrap()
}

/// The audit's loop with a lag and a low-pass, T = 117 µs.
fn lagged(delay: Delay) -> AffineFamily {
    undamped_two_mass(
        0.000117311337797,
        0.000175330026909,
        delay,
        VelocityEstimator::LowPass {
            cutoff_hz: 176.784120008,
        },
    )
}

/// Highest finite end of the exact stable intervals at damping b (wall units).
fn top(fam: &AffineFamily, b: f64) -> Option<f64> {
    stable_stiffness_intervals(fam, b)
        .iter()
        .map(|iv| iv.hi)
        .filter(|h| h.is_finite())
        .reduce(f64::max)
}

/// The largest interval end over a dense scan of dampings in [lo, hi] (wall units).
fn scanned_max(fam: &AffineFamily, lo: f64, hi: f64, n: usize) -> f64 {
    (0..=n)
        .filter_map(|i| top(fam, lo + (hi - lo) * i as f64 / n as f64))
        .fold(f64::NEG_INFINITY, f64::max)
}

/// K_max of a region is confirmed: the interval at its damping reaches it, the wall just
/// inside is stable and just outside not; and no scanned damping does better.
fn assert_confirmed(fam: &AffineFamily, r: &StableRegion, scan: (f64, f64), what: &str) {
    let (a, b) = (r.a_max, r.b_at_a_max);
    assert!(a.is_finite() && b.is_finite(), "{what}: empty");
    let mut c = fam.coefficients(0.0, 0.0);
    let mut stable = |x: f64, y: f64| hapstab::verdict::inside_unit_circle(fam, x, y, &mut c);
    let d = CONFIRM_REL * a.abs();
    if r.a_max_attained {
        let t = top(fam, b).unwrap();
        assert!(
            (t - a).abs() <= 1e-9 * a.abs(),
            "{what}: interval top {t} vs K_max {a}"
        );
        assert_eq!(stable(a - d, b), Some(true), "{what}: inside");
    } else {
        assert_eq!(
            stable(r.a_stable, r.b_stable),
            Some(true),
            "{what}: supremum"
        );
        assert!(r.a_stable >= a - d, "{what}: {} far below {a}", r.a_stable);
    }
    assert_ne!(stable(a + d, b), Some(true), "{what}: outside");
    let best = scanned_max(fam, scan.0, scan.1, 400);
    assert!(
        best <= a * (1.0 + 1e-9),
        "{what}: a scanned damping reaches {best} > {a}"
    );
}

#[test]
fn undamped_two_mass_k_max_is_the_intervals_maximum() {
    let fam = lagged(Delay::samples(0).unwrap());
    let r = stable_region(&fam).unwrap();
    let (_, b_hi) = fam.to_units(0.0, 5000.0);
    assert_confirmed(&fam, &r, (0.0, b_hi), "no delay");
    let (k, b) = fam.to_physical(r.a_max, r.b_at_a_max);
    // the stable intervals at B = 1 kNs/m end at 8.8e5 N/m; K_max = 1.559e8 N/m at
    // B = 38 541 Ns/m was the wrong answer, where the referee finds ρ = 1.69625
    assert!(k > 8.8e5 && k < 1e6, "K_max = {k} at B = {b}");
    let (a, bb) = fam.to_units(1.558e8, 38541.1);
    assert!(!r.contains(WallPoint { a, b: bb }));
    // the referee: (−1.74e6 N/m, 746 Ns/m) is unstable, ρ = 1.1408
    let (a, bb) = fam.to_units(-1.74e6, 746.0);
    assert!(!r.contains(WallPoint { a, b: bb }));
    for p in &r.polygons {
        assert!(p.area() > 0.0);
    }
}

#[test]
fn undamped_two_mass_k_max_over_a_band() {
    let fam = lagged(Delay::samples(0).unwrap());
    let r = stable_region(&fam).unwrap();
    let (_, b100) = fam.to_units(0.0, 100.0);
    let m = alpha_max_within(&fam, &r, 0.0, b100).unwrap().unwrap();
    // the audit's 378 112 N/m at B = 93.04 was not stable; the exact intervals' maximum over
    // [0, 100] Ns/m is at the band's edge
    let best = scanned_max(&fam, 0.0, b100, 400);
    assert!((m.a - best).abs() <= 1e-9 * best, "{} vs {best}", m.a);
    assert!((m.b - b100).abs() <= 1e-12 * b100);
}

#[test]
fn undamped_two_mass_with_a_fractional_delay_is_not_empty() {
    let fam = lagged(Delay::from_time(0.000208330779878, 0.000117311337797).unwrap());
    let r = stable_region(&fam).unwrap();
    // the referee: (689.65 N/m, 0.67492 Ns/m) is stable, ρ = 0.999992306
    let (a, b) = fam.to_units(689.65, 0.67492);
    assert!(
        r.contains(WallPoint { a, b }),
        "{} polygons",
        r.polygons.len()
    );
    let (_, b_hi) = fam.to_units(0.0, 5000.0);
    assert_confirmed(&fam, &r, (0.0, b_hi), "fractional delay");
}

#[test]
fn undamped_two_mass_one_sample_delay_is_bounded() {
    // no lag, backward difference: the audit's region had B up to 1.6e16 Ns/m and an area of
    // −3e21
    let fam = undamped_two_mass(
        1e-4,
        0.0,
        Delay::samples(1).unwrap(),
        VelocityEstimator::Backward,
    );
    let r = stable_region(&fam).unwrap();
    assert!(r.area > 0.0 && r.area.is_finite());
    let (_, b_max) = fam.to_units(0.0, 1e6);
    for p in &r.polygons {
        assert!(p.area() > 0.0);
        assert!(
            p.vertices.iter().all(|v| v.b.abs() < b_max),
            "B beyond 1e6 Ns/m"
        );
    }
    let (_, b_hi) = fam.to_units(0.0, 2e4);
    assert_confirmed(&fam, &r, (0.0, b_hi), "one sample");
}

#[test]
fn two_branches_close_together_leave_no_false_hole() {
    // The audit's "hole" (B 605–607 Ns/m) was a lens drawn between two branches that never
    // cross; the walls there: (20 867 N/m, 605.9 Ns/m) stable, (20 866.99, 606.01) unstable.
    let plant = Plant::new(
        PlantModel::TransferFunction {
            num: vec![0.000551340607085, 0.00831936581947],
            den: vec![0.334778171044, 1.02955059894, 4.04532782511],
        },
        0.0,
    )
    .unwrap();
    let lp = Loop::new(
        plant,
        0.00011424717289,
        Delay::samples(6).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let r = stable_region(&fam).unwrap();
    for p in &r.polygons {
        assert!(p.area() > 0.0, "a clockwise polygon");
    }
    let inside = |k: f64, b: f64| {
        let (a, bb) = fam.to_units(k, b);
        r.contains(WallPoint { a, b: bb })
    };
    assert!(inside(20867.0, 605.9));
    assert!(!inside(20866.99, 606.01));
}

/// A 20 kHz servo with heavy velocity filtering and the audit's device: T = 20–100 µs,
/// cut-off 5–30 Hz, delays 0.2–1 ms (the audit's loop first). Every region resolves, and its
/// K_max is the exact intervals' maximum.
#[test]
fn thin_regions_at_fast_sampling_resolve() {
    let cases = [
        (5e-5, 10.0, 4e-4),
        (2e-5, 5.0, 2e-4),
        (2e-5, 30.0, 1e-3),
        (5e-5, 5.0, 1e-3),
        (5e-5, 30.0, 2e-4),
        (1e-4, 10.0, 6e-4),
        (1e-4, 5.0, 4e-4),
        (2e-5, 10.0, 5e-4),
        (5e-5, 20.0, 8e-4),
        (1e-4, 30.0, 1e-3),
        (3e-5, 15.0, 3e-4),
    ];
    for (t, fc, td) in cases {
        let plant = Plant::mass_spring_damper(Effective::new(1.25, 8.0, 350.0).unwrap()).unwrap();
        let lp = Loop::new(
            plant,
            t,
            Delay::from_time(td, t).unwrap(),
            VelocityEstimator::LowPass { cutoff_hz: fc },
        )
        .unwrap();
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let what = format!("T = {t}, fc = {fc}, td = {td}");
        let r = stable_region(&fam).unwrap_or_else(|e| panic!("{what}: {e}"));
        let (_, b_hi) = fam.to_units(0.0, 2e4);
        assert_confirmed(&fam, &r, (0.0, b_hi), &what);
    }
}
