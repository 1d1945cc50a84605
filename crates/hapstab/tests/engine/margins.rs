//! Stability margins of a wall on any loop. Each margin is checked against the Schur–Cohn test
//! on the perturbed loop (just inside and just beyond the margin) and against the roots, never
//! against the margins module itself.

use crate::common;
use common::SplitMix;
use hapstab::boundary::stable_stiffness_intervals;
use hapstab::margins::margins;
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Effective, Wall};
use hapstab::stability::roots;
use hapstab::{AffineFamily, schur_stable};
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

/// Schur–Cohn stability of a physical wall on a loop.
fn stable(lp: &Loop, k: f64, b: f64) -> bool {
    let fam = AffineFamily::of_loop(lp).unwrap();
    let (a, bb) = fam.to_units(k, b);
    schur_stable(&fam.coefficients(a, bb))
}

/// The root closest to the unit circle at a physical wall: (|z| − 1, arg z).
fn critical_root(lp: &Loop, k: f64, b: f64) -> (f64, f64) {
    let fam = AffineFamily::of_loop(lp).unwrap();
    let (a, bb) = fam.to_units(k, b);
    let z: Complex64 = roots(&fam.coefficients(a, bb))
        .unwrap()
        .into_iter()
        .min_by(|x, y| (x.norm() - 1.0).abs().total_cmp(&(y.norm() - 1.0).abs()))
        .unwrap();
    (z.norm() - 1.0, z.arg().abs())
}

fn random_loop(rng: &mut SplitMix, i: usize) -> Loop {
    let v = match rng.below(4) {
        0 => VelocityEstimator::Backward,
        1 => VelocityEstimator::LowPass {
            cutoff_hz: rng.range(30.0, 300.0),
        },
        2 => VelocityEstimator::Average {
            samples: 1 + rng.below(8),
        },
        _ => VelocityEstimator::Iir {
            b: vec![500.0, -500.0],
            a: vec![1.0, -0.5],
        },
    };
    let arm = Arm {
        mass: rng.range(0.0, 1.5),
        damping: rng.range(0.0, 6.0),
        stiffness: rng.range(0.0, 500.0),
    };
    let model = match i % 3 {
        0 => PlantModel::MassSpringDamper(
            Effective::new(0.1 + arm.mass, 1.5 + arm.damping, arm.stiffness).unwrap(),
        ),
        1 => PlantModel::TwoMass(TwoMass {
            motor_mass: rng.range(0.03, 0.2),
            motor_damping: rng.range(0.2, 3.0),
            handle_mass: rng.range(0.01, 0.1),
            transmission_stiffness: 10f64.powf(rng.range(4.0, 6.0)),
            transmission_damping: rng.range(0.0, 3.0),
            arm,
        }),
        _ => PlantModel::TransferFunction {
            num: vec![1.0],
            den: vec![0.3, 2.0, 100.0],
        },
    };
    let lag = if i % 4 == 3 {
        rng.range(1e-5, 3e-4)
    } else {
        0.0
    };
    let delay = Delay {
        samples: rng.below(3),
        fraction: if i % 2 == 1 { rng.range(0.0, 1.0) } else { 0.0 },
    };
    Loop::new(Plant::new(model, lag).unwrap(), 1e-3, delay, v).unwrap()
}

/// A stable wall inside the stable K interval at a random damping.
fn stable_wall(rng: &mut SplitMix, lp: &Loop) -> Option<Wall> {
    let fam = AffineFamily::of_loop(lp).unwrap();
    let b = rng.range(0.0, 20.0);
    let (_, beta) = fam.to_units(0.0, b);
    let iv = stable_stiffness_intervals(&fam, beta)
        .into_iter()
        .find(|iv| iv.hi.is_finite() && iv.hi > 0.0)?;
    let lo = iv.lo.max(0.0);
    let a = lo + (iv.hi - lo) * rng.range(0.2, 0.9);
    let (k, _) = fam.to_physical(a, beta);
    Some(Wall {
        stiffness: k,
        damping: b,
    })
}

fn cases(n: usize, seed: u64) -> Vec<(Loop, Wall)> {
    let mut rng = SplitMix(seed);
    let mut out = Vec::new();
    let mut i = 0;
    while out.len() < n {
        let lp = random_loop(&mut rng, i);
        i += 1;
        if let Some(w) = stable_wall(&mut rng, &lp) {
            out.push((lp, w));
        }
    }
    out
}

const EPS: f64 = 1e-6;

/// Asserts that the wall scaled by `factor` (±1e-6) lies on opposite sides of the boundary,
/// stable toward the wall itself.
fn crosses(lp: &Loop, (k, b): (f64, f64), factor: f64, scale_b: bool, what: &str) {
    let at = |f: f64| (k * f, if scale_b { b * f } else { b });
    let inside = if factor > 1.0 { 1.0 - EPS } else { 1.0 + EPS };
    let outside = if factor > 1.0 { 1.0 + EPS } else { 1.0 - EPS };
    let (ki, bi) = at(factor * inside);
    let (ko, bo) = at(factor * outside);
    assert!(
        stable(lp, ki, bi),
        "{what}: {lp:?} ({k}, {b}) ×{factor} inside"
    );
    assert!(
        !stable(lp, ko, bo),
        "{what}: {lp:?} ({k}, {b}) ×{factor} outside"
    );
}

/// Acceptance: every reported gain margin — on K alone and on (K, B) together, upward and
/// downward — multiplied by (1 ± 1e-6) lands on opposite sides of the boundary, and the
/// frequency of the upper stiffness margin is the angle of the root pair on the unit circle
/// there.
#[test]
fn gain_margins_cross_the_boundary() {
    cases(40, 0x6A1A).par_iter().for_each(|(lp, w)| {
        let m = margins(lp, *w).unwrap();
        assert!(m.stable, "{lp:?} {w:?}");
        let g = m
            .stiffness
            .unwrap_or_else(|| panic!("{lp:?} {w:?}: {:?}", m.notes));
        assert!(g.factor > 1.0);
        let (k, b) = (w.stiffness, w.damping);
        crosses(lp, (k, b), g.factor, false, "stiffness");
        let (off, angle) = critical_root(lp, k * g.factor, b);
        assert!(off.abs() < 1e-7, "{lp:?}: root off the circle by {off}");
        assert!((angle - g.theta).abs() < 1e-6, "{angle} vs {}", g.theta);
        let f = angle / (2.0 * PI * lp.period);
        assert!(
            (f - g.frequency_hz).abs() <= 1e-6 * (1.0 / lp.period),
            "{f} Hz vs {} Hz",
            g.frequency_hz
        );
        if let Some(lower) = m.stiffness_lower {
            assert!(lower.factor < 1.0 && lower.factor > 0.0, "{lower:?}");
            crosses(lp, (k, b), lower.factor, false, "stiffness lower");
        }
        for gk in [m.gain, m.gain_lower].into_iter().flatten() {
            crosses(lp, (k, b), gk.factor, true, "(K, B)");
        }
    });
}

/// Acceptance: adding the delay margin (±1e-6) as fractional delay crosses the boundary; the
/// root pair on the unit circle there has the reported frequency.
#[test]
fn delay_margin_crosses_the_boundary() {
    cases(30, 0xDE1A).par_iter().for_each(|(lp, w)| {
        let m = margins(lp, *w).unwrap();
        let dm = m
            .delay
            .unwrap_or_else(|| panic!("{lp:?} {w:?}: {:?}", m.notes));
        assert!(dm.seconds > 0.0);
        let at = |extra: f64| {
            let delay = Delay::from_time(lp.delay_time() + extra, lp.period).unwrap();
            lp.with_delay(delay).unwrap()
        };
        let (k, b) = (w.stiffness, w.damping);
        assert!(
            stable(&at(dm.seconds * (1.0 - EPS)), k, b),
            "{lp:?} {w:?} {dm:?}"
        );
        assert!(
            !stable(&at(dm.seconds * (1.0 + EPS)), k, b),
            "{lp:?} {w:?} {dm:?}"
        );
        let (off, angle) = critical_root(&at(dm.seconds), k, b);
        assert!(off.abs() < 1e-6, "{off}");
        assert!((angle - dm.theta).abs() < 1e-5, "{angle} vs {}", dm.theta);
    });
}

/// The phase margin is where |L| = 1 and a phase lag of that many degrees puts L on −1; and,
/// well below the Nyquist frequency where the hold acts as a pure delay, the delay margin is
/// close to the classical PM/ω_c (two independent methods: frequency response and the exact
/// sampled loop's roots).
#[test]
fn phase_margin_and_delay_margin_agree() {
    let mut checked = 0;
    for (lp, w) in cases(30, 0xFA5E) {
        let m = margins(&lp, w).unwrap();
        let (Some(pm), Some(dm)) = (m.phase, m.delay) else {
            continue;
        };
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let (a, b) = fam.to_units(w.stiffness, w.damping);
        let (p0, pk, pb) = fam.parts_at(Complex64::from_polar(1.0, pm.theta));
        let l = (pk * a + pb * b) / p0;
        assert!((l.norm() - 1.0).abs() < 1e-9, "|L| = {}", l.norm());
        let rotated = l * Complex64::from_polar(1.0, -pm.degrees.to_radians());
        assert!((rotated + 1.0).norm() < 1e-9, "{rotated}");
        if pm.theta < 0.3 && pm.degrees > 0.0 && (dm.theta - pm.theta).abs() < 0.05 * pm.theta {
            let classical = pm.degrees.to_radians() / pm.theta * lp.period;
            let r = dm.seconds / classical;
            assert!(
                (r - 1.0).abs() < 0.1,
                "{lp:?} {w:?}: {dm:?} vs PM/ω = {classical}"
            );
            checked += 1;
        }
    }
    assert!(checked >= 5, "{checked}");
}

/// A wall that is not stable has no margins, and says why.
#[test]
fn unstable_wall_has_no_margins() {
    let lp = Loop::paper(Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 0).unwrap();
    let m = margins(
        &lp,
        Wall {
            stiffness: 1e6,
            damping: 0.0,
        },
    )
    .unwrap();
    assert!(!m.stable);
    assert!(m.gain.is_none() && m.delay.is_none() && m.phase.is_none());
    assert!(m.notes[0].contains("not stable"));
}

/// The paper's pure mass without delay: the stable α interval at β is (0, 2β(2 − β)/(2 + β))
/// (closed form), so the gain margin on K is that end over α, with the root pair at the
/// angle where the curve meets it.
#[test]
fn pure_mass_gain_margin_closed_form() {
    let lp = Loop::paper(Effective::new(1.0, 0.0, 0.0).unwrap(), 1.0, 0).unwrap();
    for (alpha, beta) in [(0.1, 0.5), (0.3, 1.0), (0.01, 0.2)] {
        let m = margins(
            &lp,
            Wall {
                stiffness: alpha,
                damping: beta,
            },
        )
        .unwrap();
        let want = 2.0 * beta * (2.0 - beta) / (2.0 + beta) / alpha;
        let g = m.stiffness.unwrap();
        assert!(
            (g.factor - want).abs() < 1e-12 * want,
            "{} vs {want}",
            g.factor
        );
    }
}

/// A soft wall on a two-mass device with a low-pass velocity: its loop gain stays below 1 at
/// every frequency, so no added delay destabilizes it. The margins say so (a note, no
/// number) at once instead of scanning 2000 samples of delay, and the exact loop is indeed
/// stable at added delays of 1, 10, 100 and 1000 samples (fractional ones too).
#[test]
fn soft_wall_is_stable_for_every_added_delay() {
    let plant = Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: 0.05,
            motor_damping: 0.0,
            handle_mass: 0.05,
            transmission_stiffness: 5000.0,
            transmission_damping: 1.0,
            arm: Arm::TYPICAL,
        }),
        2e-4,
    )
    .unwrap();
    let v: VelocityEstimator = "lowpass:150".parse().unwrap();
    let lp = Loop::new(plant, 1e-3, Delay::from_time(1.4e-3, 1e-3).unwrap(), v).unwrap();
    let (k, b) = (100.0, 0.0);
    let t = std::time::Instant::now();
    let m = margins(
        &lp,
        Wall {
            stiffness: k,
            damping: b,
        },
    )
    .unwrap();
    assert!(t.elapsed().as_secs_f64() < 5.0, "{:?}", t.elapsed());
    assert!(
        m.stable && m.delay.is_none() && m.delay_at_least.is_none(),
        "{m:?}"
    );
    assert!(
        m.notes.iter().any(|n| n.contains("every added delay")),
        "{:?}",
        m.notes
    );
    for extra in [1.0, 10.37, 100.0, 1000.5] {
        let d = Delay::from_time(1.4e-3 + extra * 1e-3, 1e-3).unwrap();
        assert!(
            stable(&lp.with_delay(d).unwrap(), k, b),
            "unstable at +{extra} samples"
        );
    }
}
