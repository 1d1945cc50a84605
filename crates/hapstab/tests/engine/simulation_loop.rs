//! The simulator on general loops (every plant model, actuator lag, fractional delay, every
//! velocity estimator) against the analysis of the same loop, and on the paper's loop against
//! an independent stepping of its closed-form 2×2 plant. Expected values come from the roots
//! of p(z) (`hapstab::stability::roots` on `AffineFamily::coefficients`), from closed forms
//! or from independent linear algebra, never from the simulator itself.

use crate::common;
use crate::common::discrete_plant::DiscretePlant;
use common::SplitMix;
use hapstab::simulation::{
    Config, Contact, Friction, HumanForce, LoopModel, Model, Outcome, SimModel, Simulator, Trace,
    exact_alpha_limit, linear_growth_of, simulate,
};
use hapstab::zoh::{PlantPorts, StateSpace};
use hapstab::{
    Arm, Delay, Effective, Loop, Normalized, Plant, PlantModel, PlantParams, TwoMass,
    VelocityEstimator, Wall,
};
use rayon::prelude::*;

fn poly_mul(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// A device + arm of random size (SI units).
fn random_arm(rng: &mut SplitMix) -> Arm {
    Arm {
        mass: rng.range(0.1, 1.0),
        damping: rng.range(0.0, 8.0),
        stiffness: rng.range(0.0, 500.0),
    }
}

/// Plant kinds: 0 mass-spring-damper, 1 two-mass device, 2 transfer function of order 2..6
/// (the device's m s² + b s + k times real poles and resonances, sometimes with a zero).
fn random_plant_model(rng: &mut SplitMix, kind: usize) -> PlantModel {
    match kind {
        0 => PlantModel::MassSpringDamper(
            Effective::new(
                rng.log_range(0.05, 2.0),
                rng.range(0.0, 10.0),
                rng.range(0.0, 1000.0),
            )
            .unwrap(),
        ),
        1 => PlantModel::TwoMass(TwoMass {
            motor_mass: rng.log_range(0.02, 0.3),
            motor_damping: rng.range(0.0, 2.0),
            handle_mass: rng.range(0.0, 0.2),
            transmission_stiffness: rng.log_range(500.0, 2e4),
            transmission_damping: rng.range(0.0, 5.0),
            arm: random_arm(rng),
        }),
        _ => {
            let mut den = vec![rng.log_range(0.05, 2.0), rng.range(0.0, 10.0)];
            den.push(rng.range(0.0, 1000.0));
            for _ in 0..rng.below(3) {
                let factor = if rng.next_f64() < 0.5 || den.len() > 5 {
                    vec![rng.log_range(1e-4, 1e-2), 1.0]
                } else {
                    let w = rng.log_range(50.0, 2000.0);
                    let zeta = rng.range(0.02, 0.5);
                    vec![1.0 / (w * w), 2.0 * zeta / w, 1.0]
                };
                den = poly_mul(&den, &factor);
            }
            let num = if rng.next_f64() < 0.3 {
                vec![1.0 / rng.log_range(50.0, 3000.0), 1.0]
            } else {
                vec![1.0]
            };
            PlantModel::TransferFunction { num, den }
        }
    }
}

/// Estimator kinds: 0 backward, 1 low-pass, 2 average, 3 a two-pole IIR low-pass of the
/// backward difference.
fn random_velocity(rng: &mut SplitMix, kind: usize, period: f64) -> VelocityEstimator {
    match kind {
        0 => VelocityEstimator::Backward,
        1 => VelocityEstimator::LowPass {
            cutoff_hz: rng.log_range(30.0, 0.3 / period),
        },
        2 => VelocityEstimator::Average {
            samples: 1 + rng.below(6),
        },
        _ => {
            let (p1, p2) = (rng.range(0.3, 0.9), rng.range(0.3, 0.9));
            let c = (1.0 - p1) * (1.0 - p2) / period;
            VelocityEstimator::Iir {
                b: vec![c, -c],
                a: vec![1.0, -(p1 + p2), p1 * p2],
            }
        }
    }
}

/// A general loop with a wall scattered around its exact boundary along the stiffness.
#[derive(Debug, Clone)]
struct Setting {
    model: SimModel,
    coefficients: Vec<f64>,
    rho: f64,
    plant_kind: usize,
    velocity_kind: usize,
}

fn spectral_radius(c: &[f64]) -> f64 {
    hapstab::stability::roots(c)
        .unwrap()
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
}

fn random_setting(rng: &mut SplitMix, i: usize) -> Option<Setting> {
    let (plant_kind, velocity_kind) = (i % 3, (i / 3) % 4);
    let period = rng.log_range(2e-4, 2e-3);
    let lag = if rng.next_f64() < 0.4 {
        rng.range(0.05, 2.0) * period
    } else {
        0.0
    };
    let plant = Plant::new(random_plant_model(rng, plant_kind), lag).ok()?;
    let d = rng.below(4);
    let lambda = if rng.next_f64() < 0.6 {
        rng.range(0.05, 0.95)
    } else {
        0.0
    };
    let delay = Delay::from_time((d as f64 + lambda) * period, period).ok()?;
    let velocity = random_velocity(rng, velocity_kind, period);
    let lp = Loop::new(plant, period, delay, velocity).ok()?;
    let probe = SimModel::Loop(
        LoopModel::new(
            lp.clone(),
            Wall {
                stiffness: 0.0,
                damping: 0.0,
            },
        )
        .ok()?,
    );
    let b = rng.range(0.02, 1.0) / (1.0 + d as f64 + lambda);
    let limit = probe.exact_upper_a(b).ok()??;
    if !(limit.is_finite() && limit > 0.0) {
        return None;
    }
    let model = probe.with_wall_units(limit * rng.range(0.5, 1.5), b).ok()?;
    let (a, b) = model.wall_units();
    let coefficients = model.family().ok()?.coefficients(a, b);
    let rho = spectral_radius(&coefficients);
    ((rho - 1.0).abs() > 1e-3).then_some(Setting {
        model,
        coefficients,
        rho,
        plant_kind,
        velocity_kind,
    })
}

/// 60 settings: every plant model with every estimator (5 of each pair), a third with a
/// lag, most with a fractional delay.
fn settings() -> Vec<Setting> {
    let mut rng = SplitMix(0x5111_100F_2008);
    let mut out = Vec::new();
    let mut i = 0;
    while out.len() < 60 {
        if let Some(s) = random_setting(&mut rng, i) {
            out.push(s);
            i += 1;
        }
    }
    out
}

fn lp(s: &Setting) -> &Loop {
    match &s.model {
        SimModel::Loop(m) => &m.lp,
        SimModel::Paper(_) => unreachable!(),
    }
}

/// The settings cover what they claim to cover.
#[test]
fn settings_cover_every_model_estimator_lag_and_fraction() {
    let s = settings();
    let mut pairs = std::collections::BTreeSet::new();
    for x in &s {
        pairs.insert((x.plant_kind, x.velocity_kind));
    }
    assert_eq!(pairs.len(), 12);
    let lagged = s.iter().filter(|x| lp(x).plant.force_lag > 0.0).count();
    let fractional = s.iter().filter(|x| lp(x).delay.fraction > 0.0).count();
    let stable = s.iter().filter(|x| x.rho < 1.0).count();
    assert!(lagged >= 10 && fractional >= 20, "{lagged} {fractional}");
    assert!((15..=45).contains(&stable), "stable {stable}");
}

/// The growth per sample measured by block power iteration through the simulator's own
/// one-sample map equals the spectral radius of the loop's p(z) to 1e-6 on 60 general loops.
#[test]
fn linear_growth_equals_spectral_radius_on_general_loops() {
    let s = settings();
    let growth: Vec<_> = s
        .par_iter()
        .map(|x| linear_growth_of(&x.model).unwrap())
        .collect();
    for (x, g) in s.iter().zip(&growth) {
        let rel = (g.growth_per_sample - x.rho).abs() / x.rho;
        assert!(g.converged, "{x:?}: {g:?}");
        assert!(
            rel < 1e-6,
            "{x:?}: growth {} vs rho {}",
            g.growth_per_sample,
            x.rho
        );
    }
}

/// Every sample of a run of exactly `cfg.samples` samples (not extended).
fn traced(mut cfg: Config) -> Trace {
    cfg.max_samples = cfg.samples;
    cfg.trace_rows = cfg.samples + 1;
    let tr = simulate(&cfg).unwrap().trace.unwrap();
    assert_eq!(tr.time.len(), cfg.samples);
    tr
}

/// Samples after which the recurrence holds: a recursive estimator's past estimates are
/// state the simulator carries beyond the degree of p(z) (they flush after m samples).
fn settle(lp: &Loop) -> usize {
    match &lp.velocity {
        VelocityEstimator::LowPass { .. } => 1,
        VelocityEstimator::Iir { a, .. } => a.len() - 1,
        _ => 0,
    }
}

/// The simulator's run loop (delay line with the fractional split, estimator, wall law, exact
/// ZOH step) reproduces the loop's p(z): every trajectory of the unforced linear loop
/// satisfies Σ c_i y[k+i] = 0 with the coefficients of p(z) from the analysis (Cayley–
/// Hamilton), on 60 general loops.
#[test]
fn runs_satisfy_the_characteristic_recurrence_on_general_loops() {
    for x in settings() {
        let mut cfg = Config::new(x.model.clone(), 300);
        cfg.initial.position = 1e-3;
        cfg.initial.velocity = -0.02;
        let y = traced(cfg).position;
        let c = &x.coefficients;
        for k in settle(lp(&x))..y.len() - c.len() {
            let (mut sum, mut scale) = (0.0, 0.0);
            for (i, ci) in c.iter().enumerate() {
                sum += ci * y[k + i];
                scale += (ci * y[k + i]).abs();
            }
            assert!(sum.abs() <= 1e-12 * scale, "{x:?} k={k}: {sum} vs {scale}");
        }
    }
}

/// The default run (10 000 samples from 1 mm) and the explorer's shortest start (300
/// samples) agree with the analysis on 60 general loops, as on the paper's loop: decaying iff
/// stable, growing iff unstable, judged on a linear window, with the measured growth on the
/// same side of 1 as ρ; undecided only near |ρ − 1| ≤ 1e-2, for at most 2 % of the runs.
#[test]
fn verdicts_agree_with_the_analysis_on_general_loops() {
    let s = settings();
    let runs: Vec<_> = s
        .par_iter()
        .flat_map(|x| {
            [10_000, 300].map(|n| {
                let mut cfg = Config::new(x.model.clone(), n);
                cfg.initial.position = 1e-3;
                (x, simulate(&cfg).unwrap())
            })
        })
        .collect();
    let mut undecided = 0;
    for (x, r) in &runs {
        let v = &r.verdict;
        if v.outcome == Outcome::Undecided {
            assert!((x.rho - 1.0).abs() <= 1e-2, "{x:?}: {v:?}");
            undecided += 1;
            continue;
        }
        let expect = if x.rho < 1.0 {
            Outcome::Decaying
        } else {
            Outcome::Growing
        };
        assert_eq!(v.outcome, expect, "{x:?}: {v:?}");
        assert!(v.linear_window, "{x:?}: {v:?}");
        assert_eq!(
            v.spectral_radius,
            Some(x.model.analysis().unwrap().spectral_radius)
        );
        let g = v.measured_growth_per_sample.unwrap();
        assert_eq!(g < 1.0, x.rho < 1.0, "{x:?}: measured {g}");
    }
    assert!(undecided * 50 <= runs.len(), "{undecided} undecided");
}

/// The static equilibrium of a loop pushed by the human with F_H, solved independently from
/// the continuous state space: 0 = A x + B u_a + b_h u_h, u_a = −a·C x (the estimators
/// here read zero velocity at rest), in wall units.
fn equilibrium(lp: &Loop, a: f64, push: f64) -> f64 {
    let ss = StateSpace::of_plant(&lp.plant, lp.period).unwrap();
    let ports = PlantPorts::of_plant(&lp.plant, lp.period).unwrap();
    let n = ss.order();
    let m = nalgebra::DMatrix::from_fn(n, n, |i, j| ss.a[i][j] - a * ss.b[i] * ss.c[j]);
    let uh = push / lp.wall_scale().stiffness;
    let rhs = nalgebra::DVector::from_fn(n, |i, _| -ports.human[i] * uh);
    let x = m.lu().solve(&rhs).unwrap();
    (0..n).map(|i| ss.c[i] * x[i]).sum()
}

/// A stable general loop pushed by the human with 1 N settles at the equilibrium of its
/// continuous plant (the human pushes the handle of a two-mass device, not through the
/// actuator lag): the ZOH keeps the static gain exactly.
#[test]
fn pushed_stable_loops_settle_at_the_static_equilibrium() {
    let stable: Vec<Setting> = settings().into_iter().filter(|x| x.rho < 0.999).collect();
    assert!(stable.len() >= 15);
    let results: Vec<_> = stable
        .par_iter()
        .map(|x| {
            let mut cfg = Config::new(x.model.clone(), 20_000);
            cfg.human = HumanForce::Constant(1.0);
            simulate(&cfg).unwrap()
        })
        .collect();
    for (x, r) in stable.iter().zip(&results) {
        let expect = equilibrium(lp(x), x.model.wall_units().0, 1.0);
        if r.verdict.outcome != Outcome::Decaying {
            assert_eq!(
                r.verdict.outcome,
                Outcome::Undecided,
                "{x:?}: {:?}",
                r.verdict
            );
            continue;
        }
        let rel = (r.final_position - expect).abs() / expect.abs();
        assert!(rel < 1e-8, "{x:?}: {} vs {expect}", r.final_position);
    }
}

/// Friction acts on a mass; a transfer function names none, so a run with friction on one
/// is refused with an error naming friction.
#[test]
fn friction_on_a_transfer_function_is_refused() {
    let plant = Plant::new(
        PlantModel::TransferFunction {
            num: vec![1.0],
            den: vec![0.1, 1.0, 0.0],
        },
        0.0,
    )
    .unwrap();
    let lp = Loop::new(plant, 1e-3, Delay::NONE, VelocityEstimator::Backward).unwrap();
    let model = LoopModel::new(
        lp,
        Wall {
            stiffness: 1000.0,
            damping: 1.0,
        },
    )
    .unwrap();
    let mut cfg = Config::new(model, 100);
    cfg.effects.friction = Some(Friction {
        coulomb: 0.1,
        stiction: 0.1,
    });
    let e = simulate(&cfg).unwrap_err().to_string();
    assert!(
        e.contains("friction") && e.contains("transfer-function"),
        "{e}"
    );
}

/// The paper's loop as the simulator stepped it before the general engine: the closed-form
/// 2×2 ZOH plant of eq. (5–6) ([`DiscretePlant`]) in the state (x, T·ẋ), the wall law on
/// delayed (quantized) positions, and friction with reversals located by bisection on the
/// closed-form sub-step (the plant over τT is the ZOH plant with γτ², δτ).
struct PaperReference {
    plant: DiscretePlant,
    p: Normalized,
    scale: f64,
    quantum: Option<f64>,
    unilateral: bool,
    friction: Option<(f64, f64)>,
}

impl PaperReference {
    fn sense(&self, x: f64) -> f64 {
        self.quantum.map_or(x, |q| (x / q).round() * q)
    }

    fn step(&self, x: f64, w: f64, u: f64) -> (f64, f64) {
        let (f, g) = (self.plant.phi, self.plant.input);
        (
            f[0][0] * x + f[0][1] * w + g[0] * u,
            f[1][0] * x + f[1][1] * w + g[1] * u,
        )
    }

    fn sub_step(&self, x: f64, w: f64, u: f64, tau: f64) -> (f64, f64) {
        let (g, dl) = (self.p.gamma, self.p.delta);
        let p = DiscretePlant::from_params(PlantParams::new(g * tau * tau, dl * tau).unwrap());
        let (ws, us) = (tau * w, tau * tau * u);
        let x1 = p.phi[0][0] * x + p.phi[0][1] * ws + p.input[0] * us;
        let w1 = p.phi[1][0] * x + p.phi[1][1] * ws + p.input[1] * us;
        (x1, w1 / tau)
    }

    fn friction_step(&self, mut x: f64, mut w: f64, ua: f64, (uc, us): (f64, f64)) -> (f64, f64) {
        let mut remaining = 1.0_f64;
        for _ in 0..=16 {
            let sign = if w == 0.0 {
                let net = ua - self.p.gamma * x;
                if net.abs() <= us {
                    return (x, 0.0);
                }
                net.signum()
            } else {
                w.signum()
            };
            let u = ua - uc * sign;
            let (x1, w1) = if remaining == 1.0 {
                self.step(x, w, u)
            } else {
                self.sub_step(x, w, u, remaining)
            };
            if w1 * sign > 0.0 {
                return (x1, w1);
            }
            let (mut lo, mut hi) = (0.0_f64, remaining);
            while hi - lo > 1e-15 {
                let mid = 0.5 * (lo + hi);
                if self.sub_step(x, w, u, mid).1 * sign > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let tau = 0.5 * (lo + hi);
            x = self.sub_step(x, w, u, tau).0;
            w = 0.0;
            remaining -= tau;
            if remaining <= 1e-15 {
                return (x, 0.0);
            }
        }
        (x, w)
    }

    /// Positions (m), velocities (m/s) and wall forces (N) of every sample, and the number
    /// of samples before the first change of contact.
    fn run(&self, cfg: &Config, push: f64) -> ([Vec<f64>; 3], usize) {
        let (d, period) = (self.p.d, cfg.model.period());
        let (mut x, mut w) = (cfg.initial.position, cfg.initial.velocity * period);
        let mut hist = std::collections::VecDeque::from(vec![self.sense(x); d + 2]);
        let mut out = [vec![], vec![], vec![]];
        let (mut unchanged, mut first_contact) = (None, None);
        for k in 0..cfg.samples {
            hist.push_front(self.sense(x));
            hist.pop_back();
            let (yd, yd1) = (hist[d], hist[d + 1]);
            let law = self.p.alpha * yd + self.p.beta * (yd - yd1);
            let contact = !self.unilateral || yd > 0.0;
            if *first_contact.get_or_insert(contact) != contact && unchanged.is_none() {
                unchanged = Some(k);
            }
            let force = if contact { law } else { 0.0 };
            for (o, v) in out.iter_mut().zip([x, w / period, force / self.scale]) {
                o.push(v);
            }
            let ua = push * self.scale - force;
            (x, w) = match self.friction {
                Some(f) => self.friction_step(x, w, ua, f),
                None => self.step(x, w, ua),
            };
        }
        (out, unchanged.unwrap_or(cfg.samples))
    }
}

/// Agreement of the two steppings of the paper's loop, relative to a run's largest value:
/// both step exact ZOH matrices, which agree to a few ulps, over 1000 samples.
const PAPER_TOLERANCE: f64 = 1e-12;

/// The paper's loop through the general engine reproduces its closed-form 2×2 stepping to
/// 1e-12 (relative to each run's largest value) on 120 seeded settings of 1000 samples:
/// linear, unilateral with a push, quantized, with Coulomb/static friction, d up to 5. A
/// unilateral run is compared up to its first change of contact: where contact is lost
/// depends on the last bits of the position, so after a bounce two exact steppings part by
/// more than their ulps (up to 1e-9 after several bounces in these settings).
#[test]
fn paper_loop_matches_its_closed_form_stepping() {
    let mut rng = SplitMix(0x0BAD_5EED_2008);
    let (m, t) = (0.1, 1e-3);
    let (mut events, mut compared_total) = (0, 0);
    for i in 0..120 {
        let d = rng.below(6);
        let (gamma, delta) = (rng.log_range(1e-6, 0.1), rng.log_range(1e-4, 0.5));
        let beta = rng.range(0.0, 1.0) / (1.0 + d as f64);
        let limit = exact_alpha_limit(PlantParams::new(gamma, delta).unwrap(), d, beta)
            .unwrap()
            .filter(|a| a.is_finite())
            .unwrap_or(0.1);
        let p = Normalized::new(limit * rng.range(0.3, 1.2), beta, gamma, delta, d).unwrap();
        let mut cfg = Config::new(Model::new(p, m, t).unwrap(), 1000);
        cfg.max_samples = 1000;
        cfg.trace_rows = 1001;
        cfg.initial.position = 1e-3;
        cfg.initial.velocity = rng.range(-0.05, 0.05);
        let push = if i % 4 == 1 { 1.0 } else { 0.0 };
        cfg.human = HumanForce::Constant(push);
        let scale = t * t / m;
        let reference = PaperReference {
            plant: DiscretePlant::from_params(p.plant()),
            p,
            scale,
            quantum: (i % 4 == 2).then_some(1e-5),
            unilateral: i % 4 == 1,
            friction: (i % 4 == 3).then_some((0.2 * scale, 0.3 * scale)),
        };
        cfg.effects.quantization = reference.quantum;
        if reference.unilateral {
            cfg.effects.contact = Contact::Unilateral;
        }
        cfg.effects.friction = (i % 4 == 3).then_some(Friction {
            coulomb: 0.2,
            stiction: 0.3,
        });
        let mut sim = Simulator::new(&cfg).unwrap();
        sim.advance(1000).unwrap();
        events += sim.friction_events();
        let tr = sim.trace().unwrap().clone();
        let (want, compared) = reference.run(&cfg, push);
        compared_total += compared;
        let got = [&tr.position, &tr.velocity, &tr.wall_force];
        for (col, (g, w)) in got.iter().zip(&want).enumerate() {
            let peak = w.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
            for k in 0..compared {
                assert!(
                    (g[k] - w[k]).abs() <= PAPER_TOLERANCE * peak,
                    "setting {i} {p:?} column {col} k={k}: {} vs {}",
                    g[k],
                    w[k]
                );
            }
        }
    }
    assert!(events > 50, "friction reversals located: {events}");
    assert!(
        compared_total > 90_000,
        "samples compared: {compared_total}"
    );
}

/// A two-mass device without wall, released at rest from x0 with the arm spring pulling the
/// handle: static friction holds the motor exactly at x0 while the handle swings,
/// x_h = x_eq + A cos ωt with ω² = (k_t + k_H)/m_h, until the transmission's pull
/// k_t·A(1 − cos ωt) reaches F_s at t* = acos(1 − F_s/(k_t A))/ω (closed form); the motor
/// then slips, and its motion up to its first reversal matches an independent fine-step
/// (RK4, T/2000) integration of the two masses started at t*.
#[test]
fn two_mass_motor_sticks_then_breaks_away_at_the_closed_form_instant() {
    let (j, mh, kt, kh, x0, t) = (0.05, 0.2, 2000.0, 500.0, 0.01, 1e-3);
    let (fc, fs) = (4.0, 5.0);
    let plant = Plant::new(
        PlantModel::TwoMass(TwoMass {
            motor_mass: j,
            motor_damping: 0.0,
            handle_mass: mh,
            transmission_stiffness: kt,
            transmission_damping: 0.0,
            arm: Arm {
                mass: 0.0,
                damping: 0.0,
                stiffness: kh,
            },
        }),
        0.0,
    )
    .unwrap();
    let lp = Loop::new(plant, t, Delay::NONE, VelocityEstimator::Backward).unwrap();
    let wall = Wall {
        stiffness: 0.0,
        damping: 0.0,
    };
    let mut cfg = Config::new(LoopModel::new(lp, wall).unwrap(), 60);
    cfg.initial.position = x0;
    cfg.effects.friction = Some(Friction {
        coulomb: fc,
        stiction: fs,
    });
    let tr = traced(cfg);
    let w = ((kt + kh) / mh).sqrt();
    let x_eq = kt * x0 / (kt + kh);
    let amp = x0 - x_eq;
    let t_star = (1.0 - fs / (kt * amp)).acos() / w;
    let first = (t_star / t).ceil() as usize;
    assert!((10..50).contains(&first), "t* = {t_star}");
    for k in 0..first {
        assert_eq!((tr.position[k], tr.velocity[k]), (x0, 0.0), "k={k}");
    }
    // Independent integration from t*: motor slips toward the handle (negative), friction +F_c.
    let rhs = |s: [f64; 4]| {
        let pull = kt * (s[2] - s[0]);
        [s[1], (pull + fc) / j, s[3], (-pull - kh * s[2]) / mh]
    };
    let mut s = [
        x0,
        0.0,
        x_eq + amp * (w * t_star).cos(),
        -amp * w * (w * t_star).sin(),
    ];
    let mut now = t_star;
    for (k, (&x, &v)) in tr.position.iter().zip(&tr.velocity).enumerate().skip(first) {
        let target = k as f64 * t;
        let steps = ((target - now) / (t / 2000.0)).ceil().max(1.0) as usize;
        let h = (target - now) / steps as f64;
        for _ in 0..steps {
            let k1 = rhs(s);
            let k2 = rhs(std::array::from_fn(|i| s[i] + 0.5 * h * k1[i]));
            let k3 = rhs(std::array::from_fn(|i| s[i] + 0.5 * h * k2[i]));
            let k4 = rhs(std::array::from_fn(|i| s[i] + h * k3[i]));
            s = std::array::from_fn(|i| {
                s[i] + h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
            });
        }
        now = target;
        if s[1] >= 0.0 {
            assert!(k > first + 2, "the motor must slip for a few samples");
            break;
        }
        assert!((x - s[0]).abs() < 1e-9 * amp, "k={k}: {x} vs {}", s[0]);
        assert!((v - s[1]).abs() < 1e-7 * amp * w, "k={k}: {v} vs {}", s[1]);
    }
}
