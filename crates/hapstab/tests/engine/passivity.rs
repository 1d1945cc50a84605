//! Passivity of the sampled wall (Colgate–Schenkel; the paper's eq. 28, Section VIII), for any
//! loop. Expected values come from closed forms, from a dense evaluation of the textbook
//! formula written here independently, from a time-domain energy balance, or from the
//! Schur–Cohn test — never from the passivity module itself.

use crate::common;
use common::SplitMix;
use hapstab::model::{Delay, Loop, Plant, PlantModel, TwoMass, VelocityEstimator};
use hapstab::params::{Arm, Effective, Wall};
use hapstab::passivity::{
    DeviceDamping, PassivityVerdict, SampledWall, k_max_passive_at, passive_region, passivity,
    passivity_of_device, passivity_with,
};
use hapstab::{AffineFamily, schur_stable};
use num_complex::Complex64;
use rayon::prelude::*;
use std::f64::consts::PI;

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
}

fn msd_loop(m: f64, b: f64, k: f64, t: f64, delay: Delay, v: VelocityEstimator) -> Loop {
    let plant = Plant::mass_spring_damper(Effective::new(m, b, k).unwrap()).unwrap();
    Loop::new(plant, t, delay, v).unwrap()
}

fn wall(k: f64, b: f64) -> Wall {
    Wall {
        stiffness: k,
        damping: b,
    }
}

fn required(lp: &Loop, k: f64, b: f64) -> f64 {
    SampledWall::new(lp)
        .unwrap()
        .required_damping(wall(k, b))
        .b_required
}

const PHANTOM_T: f64 = 1e-3;

/// Eq. (28) in physical units: backward difference, no delay, b_required = KT/2 + |B|.
#[test]
fn backward_difference_closed_form() {
    let mut rng = SplitMix(28);
    for _ in 0..200 {
        let t = 10f64.powf(rng.range(-5.0, -1.0));
        let k = 10f64.powf(rng.range(0.0, 6.0));
        let b = rng.range(-50.0, 50.0);
        let lp = msd_loop(0.1, 1.5, 0.0, t, Delay::NONE, VelocityEstimator::Backward);
        let want = k * t / 2.0 + b.abs();
        let got = required(&lp, k, b);
        assert!(rel(got, want) < 1e-12, "T={t} K={k} B={b}: {got} vs {want}");
    }
}

/// First-order low-pass of the backward difference, B >= 0: KT/2 + B(1 − a)/(1 + a).
#[test]
fn low_pass_closed_form() {
    let mut rng = SplitMix(1997);
    for _ in 0..200 {
        let t = 10f64.powf(rng.range(-4.0, -2.0));
        let fc = 10f64.powf(rng.range(0.0, 3.5));
        let k = 10f64.powf(rng.range(0.0, 5.0));
        let b = rng.range(0.0, 50.0);
        let lp = msd_loop(
            0.1,
            1.5,
            0.0,
            t,
            Delay::NONE,
            VelocityEstimator::LowPass { cutoff_hz: fc },
        );
        let a = (-2.0 * PI * fc * t).exp();
        let want = k * t / 2.0 + b * (1.0 - a) / (1.0 + a);
        let got = required(&lp, k, b);
        assert!(
            rel(got, want) < 1e-12,
            "T={t} fc={fc} K={k} B={b}: {got} vs {want}"
        );
    }
}

/// A spring alone behind d samples of delay: K(T/2 + dT), for every estimator.
#[test]
fn delayed_spring_closed_form() {
    for d in 0..=12 {
        for v in [
            VelocityEstimator::Backward,
            VelocityEstimator::LowPass { cutoff_hz: 50.0 },
            VelocityEstimator::Average { samples: 7 },
        ] {
            let lp = msd_loop(0.1, 1.5, 0.0, PHANTOM_T, Delay::samples(d).unwrap(), v);
            let k = 3e4;
            let want = k * (PHANTOM_T / 2.0 + d as f64 * PHANTOM_T);
            let req = SampledWall::new(&lp)
                .unwrap()
                .required_damping(wall(k, 0.0));
            assert!(
                rel(req.b_required, want) < 1e-12,
                "d={d}: {req:?} vs {want}"
            );
            assert_eq!(req.theta, 0.0, "the Dirichlet kernel peaks at θ = 0");
        }
    }
}

/// The textbook formula evaluated plainly: H(e^{jθ}) from the estimator's transfer function
/// (library-independent complex arithmetic on its coefficients), the ratio of (C–S) with the
/// fractional-delay form for λ > 0.
struct Plain {
    t: f64,
    d: usize,
    lambda: f64,
    num: Vec<f64>,
    den: Vec<f64>,
}

impl Plain {
    fn new(lp: &Loop) -> Self {
        let (num, den) = velocity_definition(&lp.velocity, lp.period);
        Self {
            t: lp.period,
            d: lp.delay.samples,
            lambda: lp.delay.fraction,
            num,
            den,
        }
    }

    /// V(e^{jθ}) in 1/s from its definition in powers of z^{-1} (Horner in z^{-1}).
    fn v(&self, theta: f64) -> Complex64 {
        let w = Complex64::from_polar(1.0, -theta);
        let ev = |c: &[f64]| {
            c.iter()
                .rev()
                .fold(Complex64::new(0.0, 0.0), |acc, &x| acc * w + x)
        };
        ev(&self.num) / ev(&self.den)
    }

    /// The plain ratio; only 1 − e^{−jθ} = 2sin²(θ/2) + j·sin θ and 1 − cos θ = 2sin²(θ/2)
    /// are written without cancellation (otherwise no sample below θ ≈ 1e-4 would be usable).
    fn at(&self, k: f64, b: f64, theta: f64) -> f64 {
        let x = k + b * self.v(theta);
        let e = Complex64::from_polar(1.0, -theta);
        let m = (1.0 - self.lambda) + self.lambda * e;
        let h = Complex64::from_polar(1.0, -(self.d as f64) * theta) * x * m;
        let one_minus_cos = 2.0 * (theta / 2.0).sin().powi(2);
        let one_minus_e = Complex64::new(one_minus_cos, theta.sin());
        let ratio = (one_minus_e * h).re / one_minus_cos;
        if self.lambda == 0.0 {
            return self.t / 2.0 * ratio;
        }
        let q = ratio / 2.0;
        let c = self.lambda * (1.0 - self.lambda) * x.norm_sqr();
        self.t / 2.0 * (q + (q * q + c).sqrt())
    }
}

/// Each estimator's definition as v = (Σ n_i z^{-i})/(Σ d_i z^{-i}) · y in m/s, written from
/// the estimators' documented formulas (not from the library's filter).
fn velocity_definition(v: &VelocityEstimator, t: f64) -> (Vec<f64>, Vec<f64>) {
    match v {
        VelocityEstimator::Backward => (vec![1.0 / t, -1.0 / t], vec![1.0]),
        VelocityEstimator::LowPass { cutoff_hz } => {
            let a = (-2.0 * PI * cutoff_hz * t).exp();
            (vec![(1.0 - a) / t, -(1.0 - a) / t], vec![1.0, -a])
        }
        VelocityEstimator::Average { samples } => {
            let n = *samples;
            let mut num = vec![0.0; n + 1];
            num[0] = 1.0 / (n as f64 * t);
            num[n] = -1.0 / (n as f64 * t);
            (num, vec![1.0])
        }
        VelocityEstimator::Iir { b, a } => (b.clone(), a.clone()),
        VelocityEstimator::Butterworth { .. }
        | VelocityEstimator::Bessel { .. }
        | VelocityEstimator::CriticallyDamped { .. } => {
            unreachable!("random_estimator draws no named low-pass (test_named_filters.py)")
        }
    }
}

fn random_estimator(rng: &mut SplitMix) -> VelocityEstimator {
    match rng.below(4) {
        0 => VelocityEstimator::Backward,
        1 => VelocityEstimator::LowPass {
            cutoff_hz: 10f64.powf(rng.range(1.0, 3.0)),
        },
        2 => VelocityEstimator::Average {
            samples: 1 + rng.below(15),
        },
        _ => {
            // A second-order Butterworth-like low-pass on the backward difference (stable
            // poles at radius r), in m/s: (1 − z^{-1})/T · g/(1 − 2r cos φ z^{-1} + r² z^{-2}).
            let r = rng.range(0.3, 0.95);
            let phi = rng.range(0.05, 1.0);
            let g = 1.0 - 2.0 * r * phi.cos() + r * r;
            let t = PHANTOM_T;
            VelocityEstimator::Iir {
                b: vec![g / t, -g / t],
                a: vec![1.0, -2.0 * r * phi.cos(), r * r],
            }
        }
    }
}

/// Acceptance: the requirement against a dense evaluation of the plain formula at 10⁶
/// frequencies, to 1e-9, on 100 seeded loops with whole and fractional delays and every
/// estimator. The exact maximum must also never lie below a dense sample.
#[test]
fn dense_evaluation_on_100_loops() {
    let mut rng = SplitMix(0xC0_16A7E);
    let cases: Vec<(Loop, f64, f64)> = (0..100)
        .map(|i| {
            let d = rng.below(8);
            let lambda = if i % 2 == 0 {
                0.0
            } else {
                rng.range(0.01, 0.99)
            };
            let delay = Delay {
                samples: d,
                fraction: lambda,
            };
            let lp = msd_loop(0.1, 1.5, 0.0, PHANTOM_T, delay, random_estimator(&mut rng));
            let k = 10f64.powf(rng.range(2.0, 5.0));
            let b = rng.range(-20.0, 60.0);
            (lp, k, b)
        })
        .collect();
    const N: usize = 1_000_000;
    cases.par_iter().for_each(|(lp, k, b)| {
        let exact = required(lp, *k, *b);
        let plain = Plain::new(lp);
        let dense = (1..=N)
            .map(|i| plain.at(*k, *b, PI * i as f64 / N as f64))
            .fold(f64::NEG_INFINITY, f64::max);
        let scale = exact.abs().max(k * PHANTOM_T / 2.0);
        assert!(
            (exact - dense).abs() <= 1e-9 * scale,
            "{lp:?} K={k} B={b}: exact {exact} dense {dense}"
        );
        assert!(exact >= dense - 1e-12 * scale, "{exact} < {dense}");
    });
}

/// The fractional-delay form joins the whole-sample condition at both ends: λ → 0 gives
/// max(b_required(d), 0) and λ → 1 gives b_required(d + 1).
#[test]
fn fractional_delay_is_continuous() {
    let mut rng = SplitMix(77);
    for _ in 0..40 {
        let v = random_estimator(&mut rng);
        let d = rng.below(5);
        let (k, b) = (10f64.powf(rng.range(2.0, 5.0)), rng.range(-10.0, 40.0));
        let at = |samples: usize, fraction: f64| {
            let lp = msd_loop(
                0.1,
                1.5,
                0.0,
                PHANTOM_T,
                Delay { samples, fraction },
                v.clone(),
            );
            required(&lp, k, b)
        };
        let whole = at(d, 0.0);
        let next = at(d + 1, 0.0);
        let scale = whole.abs().max(next.abs()).max(k * PHANTOM_T);
        assert!((at(d, 1e-10) - whole.max(0.0)).abs() < 1e-7 * scale, "λ→0");
        assert!((at(d, 1.0 - 1e-10) - next).abs() < 1e-7 * scale, "λ→1");
    }
}

/// One sample interval's motion in the time domain: positions x_j at the samples and y_j at
/// jT + λT, constant velocity on each part. Returns the mean energy per sample the human puts
/// into damper and wall (negative: the display generates energy).
fn mean_energy(lp: &Loop, k: f64, bw: f64, damping: f64, x: &[f64], y: &[f64]) -> f64 {
    let t = lp.period;
    let (d, lam) = (lp.delay.samples, lp.delay.fraction);
    let (num, den) = velocity_definition(&lp.velocity, t);
    // v_k from its difference equation: Σ den_i v_{k−i} = Σ num_i x_{k−i}.
    let mut v = vec![0.0; x.len()];
    for j in 0..x.len() {
        let mut acc = 0.0;
        for (i, &n) in num.iter().enumerate() {
            if j >= i {
                acc += n * x[j - i];
            }
        }
        for (i, &a) in den.iter().enumerate().skip(1) {
            if j >= i {
                acc -= a * v[j - i];
            }
        }
        v[j] = acc / den[0];
    }
    let f: Vec<f64> = (0..x.len()).map(|j| k * x[j] + bw * v[j]).collect();
    let force = |j: isize| if j >= 0 { f[j as usize] } else { 0.0 };
    let warm = x.len() / 4;
    let mut e = 0.0;
    for j in warm..x.len() - 1 {
        let ji = j as isize - d as isize;
        if lam == 0.0 {
            let dx = x[j + 1] - x[j];
            e += damping * dx * dx / t + force(ji) * dx;
        } else {
            let (d1, d2) = (y[j] - x[j], x[j + 1] - y[j]);
            e += damping * (d1 * d1 / (lam * t) + d2 * d2 / ((1.0 - lam) * t));
            e += force(ji - 1) * d1 + force(ji) * d2;
        }
    }
    e / (x.len() - 1 - warm) as f64
}

/// The worst motion at frequency θ for device damping b: x_j = cos θj, and for λ > 0 the
/// position within the sample that extracts most energy (minimizing the energy over y).
fn worst_motion(lp: &Loop, k: f64, bw: f64, b: f64, theta: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
    let plain = Plain::new(lp);
    let t = lp.period;
    let lam = lp.delay.fraction;
    let z = Complex64::from_polar(1.0, theta);
    let g = z.powi(-(lp.delay.samples as i32)) * (k + bw * plain.v(theta));
    let u = if lam == 0.0 {
        Complex64::new(0.0, 0.0)
    } else {
        let c = (b / t) / (lam * (1.0 - lam));
        let r = -2.0 * (b / t) * (z - 1.0) / (1.0 - lam) + (1.0 / z - 1.0) * g;
        -r / (2.0 * c)
    };
    let x: Vec<f64> = (0..n).map(|j| (theta * j as f64).cos()).collect();
    let y: Vec<f64> = (0..n)
        .map(|j| x[j] + (u * Complex64::from_polar(1.0, theta * j as f64)).re)
        .collect();
    (x, y)
}

/// The requirement at a frequency is exactly where the time-domain energy of the worst motion
/// changes sign: 0.1 % less damping and the display generates energy, 0.1 % more and it
/// absorbs it — for whole and fractional delays and every estimator.
#[test]
fn time_domain_energy_changes_sign_at_the_requirement() {
    let mut rng = SplitMix(2024);
    for case in 0..24 {
        let v = random_estimator(&mut rng);
        let delay = Delay {
            samples: rng.below(4),
            fraction: if case % 3 == 0 {
                0.0
            } else {
                rng.range(0.05, 0.95)
            },
        };
        let lp = msd_loop(0.1, 1.5, 0.0, PHANTOM_T, delay, v);
        let sw = SampledWall::new(&lp).unwrap();
        let (k, bw) = (10f64.powf(rng.range(3.0, 4.5)), rng.range(0.0, 20.0));
        for theta in [0.4, 1.3, 2.2, 3.0] {
            let need = sw.required_damping_at(wall(k, bw), theta);
            if need <= 0.0 {
                continue; // the display absorbs energy at this frequency for any b >= 0
            }
            for (factor, sign) in [(0.999, -1.0), (1.001, 1.0)] {
                let b = need * factor;
                let (x, y) = worst_motion(&lp, k, bw, b, theta, 40_000);
                let e = mean_energy(&lp, k, bw, b, &x, &y);
                assert!(
                    e * sign > 0.0,
                    "{lp:?} K={k} B={bw} θ={theta}: b = {factor}·{need} gives energy {e}"
                );
            }
        }
    }
}

/// The passive region of the paper's loop is Colgate's triangle (0, ±b), (2b/T, 0) (Fig. 9),
/// the same as the normalized one of eq. (28).
#[test]
fn passive_region_of_the_paper_loop_is_the_triangle() {
    for (b, t) in [(1.5, 1e-3), (0.2, 5e-4), (7.0, 2e-3)] {
        let lp = msd_loop(0.1, b, 0.0, t, Delay::NONE, VelocityEstimator::Backward);
        let sw = SampledWall::new(&lp).unwrap();
        let r = passive_region(&sw, b).unwrap();
        assert!(r.bounded);
        assert!(
            rel(r.k_max, 2.0 * b / t) < 1e-12,
            "{} vs {}",
            r.k_max,
            2.0 * b / t
        );
        assert!(r.b_at_k_max.abs() < 1e-9 * b, "{}", r.b_at_k_max);
        let best = hapstab::passivity::passive_k_max(&sw, b).unwrap();
        assert!(rel(best.stiffness, 2.0 * b / t) < 1e-12 && best.damping.abs() < 1e-9 * b);
        assert!(
            rel(r.area, 2.0 * b * b / t) < 1e-6,
            "{} vs {}",
            r.area,
            2.0 * b * b / t
        );
        for v in &r.vertices {
            // every vertex on the triangle's closure: K >= 0, KT/2 + |B| <= b
            assert!(v.stiffness >= -1e-9 * b / t);
            assert!(v.stiffness * t / 2.0 + v.damping.abs() <= b * (1.0 + 1e-12));
        }
        for bw in [-0.9 * b, -0.3 * b, 0.0, 0.5 * b] {
            let k = k_max_passive_at(&sw, b, bw).unwrap();
            let want = 2.0 * (b - bw.abs()) / t;
            assert!(rel(k, want) < 1e-12, "B={bw}: {k} vs {want}");
        }
        assert!(k_max_passive_at(&sw, b, 1.01 * b).is_none());
    }
    // normalized: the triangle of hapstab::paper::nyquist::passive_region for δ
    let delta = 0.8;
    let lp = msd_loop(
        1.0,
        delta,
        0.0,
        1.0,
        Delay::NONE,
        VelocityEstimator::Backward,
    );
    let r = passive_region(&SampledWall::new(&lp).unwrap(), delta).unwrap();
    let tri = hapstab::paper::nyquist::passive_region(delta).unwrap();
    for v in &tri.vertices {
        let near = r
            .vertices
            .iter()
            .map(|w| (w.stiffness - v.a).hypot(w.damping - v.b))
            .fold(f64::INFINITY, f64::min);
        assert!(near < 1e-6 * delta, "corner {v:?} missing ({near})");
    }
}

/// Low-pass: the largest passive K at B >= 0 is 2(b − B(1 − a)/(1 + a))/T.
#[test]
fn low_pass_passive_stiffness() {
    let (b, t, fc) = (1.5, 1e-3, 100.0);
    let lp = msd_loop(
        0.1,
        b,
        0.0,
        t,
        Delay::NONE,
        VelocityEstimator::LowPass { cutoff_hz: fc },
    );
    let sw = SampledWall::new(&lp).unwrap();
    let a = (-2.0 * PI * fc * t).exp();
    for bw in [0.0, 0.5, 1.5, 4.0] {
        let want = 2.0 * (b - bw * (1.0 - a) / (1.0 + a)) / t;
        let got = k_max_passive_at(&sw, b, bw).unwrap();
        assert!(rel(got, want) < 1e-12, "B={bw}: {got} vs {want}");
    }
}

fn family_stable(fam: &AffineFamily, w: Wall) -> bool {
    let (a, b) = fam.to_units(w.stiffness, w.damping);
    schur_stable(&fam.coefficients(a, b))
}

/// Loops to which the paper's argument applies: a passive environment (arm) on a device
/// with a damper where the force acts, no actuator lag.
fn passive_environment_loops(rng: &mut SplitMix, n: usize) -> Vec<Loop> {
    (0..n)
        .map(|i| {
            let v = random_estimator(rng);
            let delay = Delay {
                samples: rng.below(4),
                fraction: if i % 2 == 0 { 0.0 } else { rng.range(0.0, 1.0) },
            };
            let arm = Arm {
                mass: rng.range(0.0, 2.0),
                damping: rng.range(0.0, 8.0),
                stiffness: rng.range(10.0, 800.0),
            };
            let plant = if i % 3 == 2 {
                Plant::new(
                    PlantModel::TwoMass(TwoMass {
                        motor_mass: rng.range(0.02, 0.2),
                        motor_damping: rng.range(0.5, 5.0),
                        handle_mass: rng.range(0.01, 0.1),
                        transmission_stiffness: 10f64.powf(rng.range(4.0, 6.0)),
                        transmission_damping: rng.range(0.0, 5.0),
                        arm,
                    }),
                    0.0,
                )
                .unwrap()
            } else {
                let e = Effective::new(
                    rng.range(0.05, 0.3) + arm.mass,
                    rng.range(0.5, 5.0) + arm.damping,
                    arm.stiffness,
                )
                .unwrap();
                Plant::mass_spring_damper(e).unwrap()
            };
            let t = 10f64.powf(rng.range(-3.5, -2.5));
            Loop::new(plant, t, delay, v).unwrap()
        })
        .collect()
}

/// Section VIII: the passive region lies inside the stable region wherever the paper's
/// argument applies (a passive display coupled to a passive arm). Points along every vertex
/// ray and between vertices, strictly inside the passive polygon, are all Schur-stable.
#[test]
fn passive_region_lies_inside_the_stable_region() {
    let mut rng = SplitMix(0x9A55);
    let loops = passive_environment_loops(&mut rng, 60);
    let mut stable_not_passive = 0;
    for lp in &loops {
        let DeviceDamping::Known { damping } = hapstab::passivity::device_damping(&lp.plant) else {
            panic!("the argument applies to {lp:?}");
        };
        let sw = SampledWall::new(lp).unwrap();
        let fam = AffineFamily::of_loop(lp).unwrap();
        let r = passive_region(&sw, damping).unwrap();
        assert!(r.bounded && r.vertices.len() > 3, "{lp:?}");
        let n = r.vertices.len();
        for (i, v) in r.vertices.iter().enumerate().skip(1) {
            let next = r.vertices[(i + 1) % n];
            for s in [0.05, 0.5, 0.95, 0.999] {
                for p in [
                    wall(s * v.stiffness, s * v.damping),
                    wall(
                        s * 0.5 * (v.stiffness + next.stiffness),
                        s * 0.5 * (v.damping + next.damping),
                    ),
                ] {
                    if p.stiffness <= 0.0 {
                        continue; // on the line W(1) = 0 the plant's static stiffness decides
                    }
                    assert!(
                        family_stable(&fam, p),
                        "{lp:?}: passive {p:?} is not stable"
                    );
                    let pv = passivity_with(&sw, lp, p);
                    assert_eq!(pv.verdict, PassivityVerdict::Passive, "{p:?}");
                }
            }
        }
        // The stiffest stable wall at the device's own damping is usually far outside the
        // passive region.
        let (_, beta) = fam.to_units(0.0, damping);
        let top = hapstab::boundary::stable_stiffness_intervals(&fam, beta)
            .iter()
            .map(|iv| iv.hi)
            .fold(f64::NEG_INFINITY, f64::max);
        let (k, b) = fam.to_physical(0.999 * top, beta);
        if passivity_with(&sw, lp, wall(k, b)).verdict == PassivityVerdict::NotPassive {
            stable_not_passive += 1;
        }
    }
    assert!(stable_not_passive > 30, "{stable_not_passive}");
}

/// The verdict against the device's damping, and where the argument does not apply.
#[test]
fn verdicts_and_device_damping() {
    let lp = msd_loop(
        0.1,
        1.5,
        0.0,
        1e-3,
        Delay::NONE,
        VelocityEstimator::Backward,
    );
    let p = passivity(&lp, wall(2000.0, 0.3)).unwrap(); // needs 1.3
    assert_eq!(p.verdict, PassivityVerdict::Passive);
    assert!(rel(p.requirement.b_required, 1.3) < 1e-14);
    let p = passivity(&lp, wall(2000.0, 0.6)).unwrap(); // needs 1.6
    assert_eq!(p.verdict, PassivityVerdict::NotPassive);
    assert!(
        rel(p.requirement.frequency_hz, 500.0) < 1e-12,
        "binds at the Nyquist frequency"
    );
    let p = passivity(&lp, wall(2400.0, 0.3)).unwrap(); // needs exactly 1.5
    assert_eq!(p.verdict, PassivityVerdict::Boundary);
    let p = passivity(&lp, wall(-100.0, 0.0)).unwrap(); // a negative spring
    assert_eq!(p.verdict, PassivityVerdict::NotPassive);
    // another device damper against the same wall: 1.6 needed, 1.7 given
    let sw = SampledWall::new(&lp).unwrap();
    let other = passivity_of_device(
        &sw,
        wall(2000.0, 0.6),
        DeviceDamping::Known { damping: 1.7 },
    );
    assert_eq!(other.verdict, PassivityVerdict::Passive);
    assert!(rel(other.requirement.b_required, 1.6) < 1e-14);
    let absent = DeviceDamping::NotApplicable {
        reason: "none".into(),
    };
    let p = passivity_of_device(&sw, wall(2000.0, 0.6), absent);
    assert_eq!(p.verdict, PassivityVerdict::NotApplicable);
    let lag = Loop::new(
        lp.plant.clone().with_force_lag(1e-4).unwrap(),
        1e-3,
        Delay::NONE,
        VelocityEstimator::Backward,
    )
    .unwrap();
    assert_eq!(
        passivity(&lag, wall(100.0, 0.0)).unwrap().verdict,
        PassivityVerdict::NotApplicable
    );
    let tf = |num: Vec<f64>, den: Vec<f64>| {
        Plant::new(PlantModel::TransferFunction { num, den }, 0.0).unwrap()
    };
    assert_eq!(
        hapstab::passivity::device_damping(&tf(vec![2.0], vec![0.2, 3.0, 10.0])),
        DeviceDamping::Known { damping: 1.5 }
    );
    assert!(matches!(
        hapstab::passivity::device_damping(&tf(vec![1.0], vec![1.0, 1.0, 1.0, 1.0])),
        DeviceDamping::NotApplicable { .. }
    ));
}

/// An unstable velocity filter is refused with a message naming it.
#[test]
fn unstable_filter_is_refused() {
    let lp = msd_loop(
        0.1,
        1.5,
        0.0,
        1e-3,
        Delay::NONE,
        VelocityEstimator::Iir {
            b: vec![1000.0, -1000.0],
            a: vec![1.0, -1.2],
        },
    );
    let e = SampledWall::new(&lp).unwrap_err().to_string();
    assert!(e.contains("velocity filter") && e.contains("1.2"), "{e}");
}

/// The passive region scales with the device damping (b_required is positively homogeneous in
/// (K, B)), so its largest K does: two independent searches at b and 2.5·b agree to 1e-9 on
/// delayed loops with every estimator (the sweep reads the device-and-arm figure this way).
#[test]
fn passive_stiffness_scales_with_the_device_damping() {
    let mut rng = SplitMix(77);
    let mut compared = 0;
    for i in 0..40 {
        let t = rng.log_range(1e-4, 1e-2);
        let delay = Delay::samples(i % 7).unwrap();
        let lp = msd_loop(0.1, 1.0, 0.0, t, delay, random_estimator(&mut rng));
        let sw = SampledWall::new(&lp).unwrap();
        let b = rng.range(0.1, 5.0);
        let (Some(one), Some(two)) = (
            hapstab::passivity::passive_k_max(&sw, b),
            hapstab::passivity::passive_k_max(&sw, 2.5 * b),
        ) else {
            continue;
        };
        if one.stiffness.is_finite() {
            compared += 1;
            assert!(
                rel(two.stiffness, 2.5 * one.stiffness) < 1e-9,
                "loop {i}: {} vs 2.5·{}",
                two.stiffness,
                one.stiffness
            );
        }
    }
    assert!(compared >= 30, "only {compared} loops compared");
}

#[test]
fn verdict_names_are_the_serialized_ones_and_meets_follows_the_verdict() {
    use hapstab::passivity::PassivityVerdict as V;
    for (v, meets) in [
        (V::Passive, Some(true)),
        (V::Boundary, Some(false)),
        (V::NotPassive, Some(false)),
        (V::NotApplicable, None),
    ] {
        let json = serde_json::to_string(&v).expect("serializes");
        assert_eq!(json, format!("\"{}\"", v.as_str()));
        assert_eq!(v.meets(), meets, "{v:?}");
    }
}
