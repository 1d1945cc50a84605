//! Tests of the time-domain simulator. Expected values come from closed forms or
//! from the independent root finder / Schur–Cohn test of `hapstab::stability`, never from
//! the simulator itself.

use crate::common;
use common::SplitMix;
use hapstab::paper::NormalizedFamily;
use hapstab::simulation::{
    BoundarySearch, Config, Contact, Effects, Friction, HumanForce, Model, Outcome, StableWhen,
    empirical_boundary, exact_alpha_limit, linear_growth, simulate,
};
use hapstab::{Analysis, Error, Normalized, PlantParams};

const M: f64 = 0.1;
const T: f64 = 1e-3;

fn model(alpha: f64, beta: f64, gamma: f64, delta: f64, d: usize) -> Model {
    Model::new(Normalized::new(alpha, beta, gamma, delta, d).unwrap(), M, T).unwrap()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The growth per sample measured by subspace iteration through the simulator's own step
/// equals the spectral radius of p(z) from the roots (`Analysis`) to 1e-6 relative at 50
/// seeded points with |ρ − 1| > 1e-3, and the run's verdict agrees with the Schur–Cohn
/// stability test, its measured envelope growth lying on the same side of 1. Delays up to 6 make the state
/// (d + 3) larger than the iteration block (6), so complex dominant pairs and delay-line
/// modes are exercised, not only exact one-step Rayleigh–Ritz.
#[test]
fn linear_growth_equals_spectral_radius_at_random_points() {
    let mut rng = SplitMix(0x5EED_2008);
    let (mut tested, mut stable, mut complex_dominant, mut big_state) = (0, 0, 0, 0);
    while tested < 50 {
        let d = (rng.next_f64() * 7.0) as usize;
        let gamma = if rng.next_f64() < 0.7 {
            rng.next_f64() * 1e-3
        } else {
            rng.next_f64() * 0.5
        };
        let delta = if rng.next_f64() < 0.7 {
            rng.next_f64() * 0.015
        } else {
            rng.next_f64()
        };
        let beta = if rng.next_f64() < 0.9 {
            1.2 * rng.next_f64() / (1.0 + d as f64)
        } else {
            -0.1 * rng.next_f64()
        };
        // Scatter α around the exact boundary (used only to place the points).
        let scale = 0.3 + 1.4 * rng.next_f64();
        let alpha = match exact_alpha_limit(PlantParams::new(gamma, delta).unwrap(), d, beta) {
            Ok(Some(a)) if a.is_finite() => scale * a,
            _ => scale * (beta + delta).abs() / (0.5 + d as f64),
        };
        let p = Normalized::new(alpha, beta, gamma, delta, d).unwrap();
        let an = Analysis::new(p).unwrap();
        if (an.spectral_radius - 1.0).abs() <= 1e-3 {
            continue;
        }
        tested += 1;
        let g = linear_growth(&p).unwrap();
        assert!(g.converged, "{p:?}: {g:?}");
        assert!(
            rel(g.growth_per_sample, an.spectral_radius) < 1e-6,
            "{p:?}: growth {} vs spectral radius {}",
            g.growth_per_sample,
            an.spectral_radius
        );
        let mut cfg = Config::new(Model::new(p, M, T).unwrap(), 2000);
        cfg.initial.position = 1e-3;
        let r = simulate(&cfg).unwrap();
        let expect = if an.stable() {
            Outcome::Decaying
        } else {
            Outcome::Growing
        };
        let v = &r.verdict;
        assert_eq!(v.outcome, expect, "{p:?}, rho = {}", an.spectral_radius);
        let g = v.measured_growth_per_sample.unwrap();
        assert_eq!(g < 1.0, an.stable(), "{p:?}: measured {g}");
        stable += an.stable() as usize;
        complex_dominant += (an.roots[0].im.abs() > 1e-12) as usize;
        big_state += (d + 3 > 6) as usize;
    }
    // The sample must cover both verdicts, complex pairs and iterated (not exact) blocks.
    assert!((10..=40).contains(&stable), "stable points: {stable}");
    assert!(
        complex_dominant >= 10,
        "complex dominant pairs: {complex_dominant}"
    );
    assert!(big_state >= 5, "states larger than the block: {big_state}");
}

/// The run loop itself (ring-buffer delay line, wall law, ZOH step) reproduces eq. (9): by
/// Cayley–Hamilton every trajectory of the unforced linear loop satisfies the recurrence
/// Σ c_i x[k+i] = 0 with the coefficients c of p(z) (eq. 7–9).
#[test]
fn run_satisfies_the_characteristic_recurrence() {
    for &(alpha, beta, gamma, delta, d) in &[
        (0.1, 0.3, 0.0, 0.0, 0),
        (0.05, 0.1, 1e-3, 0.015, 1),
        (0.3, 0.2, 0.2, 0.5, 2),
        (0.9, 0.05, 1e-4, 0.0, 4),
    ] {
        let p = Normalized::new(alpha, beta, gamma, delta, d).unwrap();
        let c = NormalizedFamily::new(p.plant(), d)
            .unwrap()
            .coefficients(alpha, beta);
        let mut cfg = Config::new(Model::new(p, M, T).unwrap(), 300);
        cfg.initial.position = 1e-3;
        cfg.initial.velocity = -0.02;
        let x = traced(cfg).position;
        for k in 0..x.len() - c.len() {
            let (mut sum, mut scale) = (0.0, 0.0);
            for (i, ci) in c.iter().enumerate() {
                sum += ci * x[k + i];
                scale += (ci * x[k + i]).abs();
            }
            assert!(sum.abs() <= 1e-12 * scale, "{p:?} k={k}: {sum} vs {scale}");
        }
    }
}

/// A stable linear run pushed with F_H settles where K(x − x_w) + k x = F_H.
#[test]
fn stable_run_settles_at_the_static_equilibrium() {
    let (alpha, beta, gamma, delta, d) = (0.05, 0.2, 1e-3, 0.01, 1);
    let (kw, ka) = (alpha * M / (T * T), gamma * M / (T * T));
    let mut cfg = Config::new(model(alpha, beta, gamma, delta, d), 20_000);
    cfg.effects.wall_position = 0.01;
    cfg.human = HumanForce::Constant(2.0);
    let r = simulate(&cfg).unwrap();
    let expect = (2.0 + kw * 0.01) / (kw + ka);
    assert!(
        rel(r.final_position, expect) < 1e-9,
        "{} vs {expect}",
        r.final_position
    );
    assert_eq!(r.verdict.outcome, Outcome::Decaying);
}

/// The dominant mode's frequency from the simulator is |arg λ|/(2πT) of the dominant root.
#[test]
fn linear_frequency_is_the_dominant_root_angle() {
    let p = Normalized::new(0.3, 0.4, 0.0, 0.01, 1).unwrap();
    let an = Analysis::new(p).unwrap();
    let g = linear_growth(&p).unwrap();
    let expect = an.roots[0].arg().abs() / (2.0 * std::f64::consts::PI * T);
    assert!(
        rel(g.frequency_hz(T), expect) < 1e-6,
        "{} vs {expect}",
        g.frequency_hz(T)
    );
}

/// The exact pure-mass boundary for d = 0 (Section V with γ = δ = 0):
/// α_max = 2β(2 − β)/(2 + β).
#[test]
fn exact_alpha_limit_matches_pure_mass_closed_form() {
    for &b in &[0.05, 0.3, 1.0, 1.7] {
        let a = exact_alpha_limit(PlantParams::new(0.0, 0.0).unwrap(), 0, b)
            .unwrap()
            .unwrap();
        let expect = 2.0 * b * (2.0 - b) / (2.0 + b);
        assert!(rel(a, expect) < 1e-9, "beta {b}: {a} vs {expect}");
    }
    assert_eq!(
        exact_alpha_limit(PlantParams::new(0.0, 0.0).unwrap(), 0, -0.1).unwrap(),
        None
    );
}

/// Every sample of a run of exactly `cfg.samples` samples (not extended).
fn traced(mut cfg: Config) -> hapstab::simulation::Trace {
    cfg.max_samples = cfg.samples;
    cfg.trace_rows = cfg.samples + 1;
    let tr = simulate(&cfg).unwrap().trace.unwrap();
    assert_eq!(tr.time.len(), cfg.samples);
    tr
}

/// Acceptance (b), pure mass: K = B = 0 and no arm: the velocity is exactly constant and
/// the position grows linearly; with a constant push F the ZOH is exact,
/// x = x0 + v0 t + F t²/(2m).
#[test]
fn pure_mass_moves_at_constant_speed() {
    let mut cfg = Config::new(model(0.0, 0.0, 0.0, 0.0, 2), 5000);
    cfg.initial.position = 0.01;
    cfg.initial.velocity = 0.37;
    let tr = traced(cfg.clone());
    for k in 0..tr.time.len() {
        assert_eq!(tr.velocity[k], 0.37);
        let x = 0.01 + 0.37 * tr.time[k];
        assert!((tr.position[k] - x).abs() < 1e-13, "k={k}");
        assert_eq!(tr.wall_force[k], 0.0);
    }
    cfg.human = HumanForce::Constant(0.8);
    let tr = traced(cfg);
    for k in 0..tr.time.len() {
        let t = tr.time[k];
        let x = 0.01 + 0.37 * t + 0.8 * t * t / (2.0 * M);
        assert!((tr.position[k] - x).abs() <= 1e-13 * x, "k={k}");
        assert!(rel(tr.velocity[k], 0.37 + 0.8 * t / M) < 1e-13, "k={k}");
    }
}

fn energy(x: f64, v: f64, k: f64) -> f64 {
    0.5 * M * v * v + 0.5 * k * x * x
}

/// Acceptance (b), energy: with physical damping only the energy ½mv² (+ ½kx² with the
/// arm's spring) decays strictly at every sample; damping alone follows v = v0 e^{−δk};
/// the undamped arm spring conserves energy.
#[test]
fn physical_damping_dissipates_energy_monotonically() {
    // Damping only: closed form.
    let delta = 0.015;
    let mut cfg = Config::new(model(0.0, 0.0, 0.0, delta, 0), 3000);
    cfg.initial.velocity = 0.2;
    let tr = traced(cfg);
    for k in 1..tr.time.len() {
        let v = 0.2 * (-delta * k as f64).exp();
        assert!(rel(tr.velocity[k], v) < 1e-12, "k={k}");
        assert!(energy(0.0, tr.velocity[k], 0.0) < energy(0.0, tr.velocity[k - 1], 0.0));
    }
    // Arm spring and damper (γ, δ > 0): strictly decreasing energy.
    let (gamma, delta) = (1e-3, 0.01);
    let k_arm = gamma * M / (T * T);
    let mut cfg = Config::new(model(0.0, 0.0, gamma, delta, 1), 4000);
    cfg.initial.position = 0.02;
    cfg.initial.velocity = -0.1;
    let tr = traced(cfg);
    for k in 1..tr.time.len() {
        let (e0, e1) = (
            energy(tr.position[k - 1], tr.velocity[k - 1], k_arm),
            energy(tr.position[k], tr.velocity[k], k_arm),
        );
        assert!(e1 < e0, "k={k}: {e1} >= {e0}");
    }
    // Undamped arm spring: x = x0 cos ωt, energy conserved.
    let mut cfg = Config::new(model(0.0, 0.0, gamma, 0.0, 0), 4000);
    cfg.initial.position = 0.02;
    let tr = traced(cfg);
    let w = (k_arm / M).sqrt();
    let e0 = energy(0.02, 0.0, k_arm);
    for k in 0..tr.time.len() {
        assert!((tr.position[k] - 0.02 * (w * tr.time[k]).cos()).abs() < 1e-13);
        assert!(rel(energy(tr.position[k], tr.velocity[k], k_arm), e0) < 1e-11);
    }
}

/// The wall law: with d samples of delay the force is K·x[k−d] + B·(x[k−d] − x[k−d−1])/T,
/// and quantization makes the wall see round(x/q)·q.
#[test]
fn wall_force_uses_delayed_quantized_samples() {
    let (alpha, beta, d, q) = (0.02, 0.1, 2, 1e-5);
    let (kw, bw) = (alpha * M / (T * T), beta * M / T);
    let mut cfg = Config::new(model(alpha, beta, 0.0, 0.0, d), 300);
    cfg.initial.velocity = 0.01;
    cfg.effects.quantization = Some(q);
    cfg.effects.wall_position = -3e-4;
    let tr = traced(cfg);
    let sense = |x: f64| (x / q).round() * q;
    for k in d + 1..tr.time.len() {
        let yd = sense(tr.position[k - d]);
        let yd1 = sense(tr.position[k - d - 1]);
        let f = kw * (yd + 3e-4) + bw * (yd - yd1) / T;
        assert!(
            (tr.wall_force[k] - f).abs() < 1e-9 * f.abs().max(1.0),
            "k={k}"
        );
    }
    // Before the delay line fills, the wall sees the resting initial position.
    assert!((tr.wall_force[0] - kw * 3e-4).abs() < 1e-9);
}

/// Coulomb friction on a pure mass: constant deceleration F_c/m, stop at t* = m v0/F_c
/// inside a sample, at x* = m v0²/(2F_c), then stuck for good (located reversal, stick rule).
#[test]
fn coulomb_friction_stops_the_mass_at_the_closed_form_point() {
    let (v0, fc) = (0.1234, 0.3);
    let mut cfg = Config::new(model(0.0, 0.0, 0.0, 0.0, 0), 200);
    cfg.initial.velocity = v0;
    cfg.effects.friction = Some(Friction {
        coulomb: fc,
        stiction: 0.5,
    });
    let tr = traced(cfg);
    let t_stop = M * v0 / fc;
    let x_stop = M * v0 * v0 / (2.0 * fc);
    for k in 0..tr.time.len() {
        let t = tr.time[k];
        if t < t_stop {
            assert!((tr.velocity[k] - (v0 - fc / M * t)).abs() < 1e-12, "k={k}");
            assert!((tr.position[k] - (v0 * t - fc / M * t * t / 2.0)).abs() < 1e-13);
        } else {
            assert_eq!(tr.velocity[k], 0.0, "k={k}");
            assert!((tr.position[k] - x_stop).abs() < 1e-12, "k={k}");
        }
    }
}

/// Coulomb friction with viscous damping: v(t) = (v0 + F_c/b) e^{−bt/m} − F_c/b stops at
/// t* = (m/b) ln(1 + b v0/F_c); the fractional sub-steps must be exact ZOH steps.
#[test]
fn coulomb_with_damping_stops_at_the_closed_form_point() {
    let (v0, fc, delta) = (0.2, 0.05, 0.02);
    let b = delta * M / T;
    let mut cfg = Config::new(model(0.0, 0.0, 0.0, delta, 0), 400);
    cfg.initial.velocity = v0;
    cfg.effects.friction = Some(Friction {
        coulomb: fc,
        stiction: fc,
    });
    let tr = traced(cfg);
    let t_stop = M / b * (1.0 + b * v0 / fc).ln();
    let x_at = |t: f64| (M / b) * (v0 + fc / b) * (1.0 - (-b * t / M).exp()) - fc / b * t;
    let x_stop = x_at(t_stop);
    assert!(t_stop > 0.05 && t_stop < 0.3);
    for k in 0..tr.time.len() {
        let t = tr.time[k];
        if t < t_stop {
            assert!((tr.position[k] - x_at(t)).abs() < 1e-12, "k={k}");
        } else {
            assert_eq!(tr.velocity[k], 0.0);
            assert!((tr.position[k] - x_stop).abs() < 1e-12, "k={k}");
        }
    }
}

/// Static friction: a push below F_s never moves the device; above it the device slides
/// with acceleration (F − F_c)/m from the first sample.
#[test]
fn static_friction_holds_until_breakaway() {
    let mut cfg = Config::new(model(0.0, 0.0, 0.0, 0.0, 0), 100);
    cfg.effects.friction = Some(Friction {
        coulomb: 0.2,
        stiction: 0.5,
    });
    cfg.human = HumanForce::Constant(0.49);
    let r = simulate(&cfg).unwrap();
    assert_eq!((r.final_position, r.final_velocity), (0.0, 0.0));
    assert_eq!(r.verdict.outcome, Outcome::Decaying);
    assert_eq!(r.verdict.reason, "the device came to rest");
    cfg.human = HumanForce::Constant(-0.7);
    let tr = traced(cfg);
    for k in 0..tr.time.len() {
        let t = tr.time[k];
        assert!(
            (tr.position[k] + 0.5 * 0.5 / M * t * t).abs() < 1e-12,
            "k={k}"
        );
    }
}

/// Saturation bounds the wall force, and a saturated wall cannot hold a push above F_max.
#[test]
fn saturation_limits_the_wall_force() {
    let mut cfg = Config::new(model(0.05, 0.2, 0.0, 0.0, 1), 3000);
    cfg.effects.saturation = Some(2.0);
    cfg.effects.contact = Contact::UnilateralNoPull;
    cfg.human = HumanForce::Constant(3.0);
    let tr = traced(cfg);
    assert!(tr.wall_force.iter().all(|f| (0.0..=2.0).contains(f)));
    // Once saturated, the mass accelerates at (3 − 2)/m: the last velocity increments.
    let n = tr.time.len();
    assert_eq!(tr.wall_force[n - 1], 2.0);
    let dv = tr.velocity[n - 1] - tr.velocity[n - 2];
    assert!(rel(dv, 1.0 / M * T) < 1e-9, "{dv}");
}

/// Remark 1: a unilateral wall pushed hard enough that the device never leaves it behaves
/// exactly as the bilateral wall; its verdict is judged on a linear window, agrees with the
/// analysis and its measured growth matches the spectral radius; out of contact the wall
/// exerts no force.
#[test]
fn unilateral_wall_in_permanent_contact_is_bilateral() {
    let (alpha, beta, d) = (0.05, 0.1, 1);
    let k = alpha * M / (T * T);
    let mut cfg = Config::new(model(alpha, beta, 0.0, 0.0, d), 4000);
    cfg.human = HumanForce::Constant(10.0);
    cfg.initial.position = 1.5 * 10.0 / k;
    let bilateral = traced(cfg.clone());
    cfg.effects.contact = Contact::Unilateral;
    let unilateral = traced(cfg.clone());
    assert!(unilateral.position.iter().all(|&x| x > 0.0));
    assert_eq!(bilateral, unilateral);
    let rho = Analysis::new(Normalized::new(alpha, beta, 0.0, 0.0, d).unwrap())
        .unwrap()
        .spectral_radius;
    let v = simulate(&cfg).unwrap().verdict;
    let g = v.measured_growth_per_sample.unwrap();
    assert!(rel(g.ln(), rho.ln()) < 0.02, "measured {g} vs rho {rho}");
    assert_eq!(v.outcome, Outcome::Decaying);
    assert!(v.linear_window);
    assert_eq!((v.contact.contacts, v.contact.separations), (0, 0));
    // Moving away from the wall surface at x_w = 0: no force, constant speed.
    cfg.human = HumanForce::Constant(0.0);
    cfg.initial.position = -1e-3;
    cfg.initial.velocity = -0.1;
    let tr = traced(cfg);
    assert!(tr.wall_force.iter().all(|&f| f == 0.0));
    assert!(tr.velocity.iter().all(|&v| v == -0.1));
}

/// Human force profiles: a per-sample vector and a function of time reproduce the constant
/// push; the vector's last value is held after it ends.
#[test]
fn human_force_profiles_agree() {
    let mut cfg = Config::new(model(0.05, 0.1, 1e-4, 0.01, 1), 500);
    cfg.human = HumanForce::Constant(1.5);
    let constant = traced(cfg.clone());
    cfg.human = HumanForce::Samples(vec![1.5; 100]);
    assert_eq!(traced(cfg.clone()), constant);
    cfg.human = HumanForce::function(|_| 1.5);
    assert_eq!(traced(cfg.clone()), constant);
    cfg.human = HumanForce::function(|t| if t < 0.1 { 0.0 } else { 1.5 });
    let step = traced(cfg.clone());
    assert_eq!(step.human_force[99], 0.0);
    assert_eq!(step.human_force[100], 1.5);
}

/// Bad input is an error naming the parameter, never a panic.
#[test]
fn invalid_input_is_rejected() {
    let base = Config::new(model(0.05, 0.1, 0.0, 0.0, 0), 100);
    let check = |cfg: Config, needle: &str| {
        let e = simulate(&cfg).unwrap_err();
        assert!(e.to_string().contains(needle), "{e}");
    };
    let mut c = base.clone();
    c.samples = 1;
    check(c, "samples");
    let mut c = base.clone();
    c.effects.quantization = Some(0.0);
    check(c, "quantization");
    let mut c = base.clone();
    c.effects.saturation = Some(-1.0);
    check(c, "saturation");
    let mut c = base.clone();
    c.effects.friction = Some(Friction {
        coulomb: 1.0,
        stiction: 0.5,
    });
    check(c, "static friction");
    let mut c = base.clone();
    c.human = HumanForce::Samples(vec![0.0, f64::NAN]);
    check(c, "human force");
    let mut c = base.clone();
    c.human = HumanForce::function(|t| if t > 0.05 { f64::INFINITY } else { 0.0 });
    check(c, "human force");
    let mut c = base.clone();
    c.initial.velocity = f64::NAN;
    check(c, "initial velocity");
    let mut c = base.clone();
    c.effects.wall_position = f64::INFINITY;
    check(c, "wall position");
    assert!(matches!(
        Model::new(Normalized::new(0.1, 0.1, 0.0, 0.0, 0).unwrap(), 0.0, T),
        Err(Error::NotPositive { .. })
    ));
    assert!(hapstab::simulation::samples_for_duration(0.0, T).is_err());
    assert_eq!(
        hapstab::simulation::samples_for_duration(0.5, T).unwrap(),
        500
    );
}

/// A growing nonlinear run is caught before overflow and reported as growing.
#[test]
fn unstable_saturation_free_run_blows_up_as_growing() {
    let mut cfg = Config::new(model(1.5, 0.1, 0.0, 0.0, 0), 20_000);
    cfg.effects.quantization = Some(1e-9);
    cfg.initial.position = 1e-3;
    let r = simulate(&cfg).unwrap();
    assert_eq!(r.verdict.outcome, Outcome::Growing);
    assert!(r.blown_up && r.samples < 20_000);
    assert!(r.verdict.measured_growth_per_sample.unwrap() > 1.0);
}

/// With the linear bilateral wall the simulated boundary equals the closed-form
/// pure-mass boundary 2β(2 − β)/(2 + β) within the bisection tolerance; with a unilateral
/// wall and a steady push nothing above the linear boundary can decay (the equilibrium is
/// linearly unstable), so the simulated boundary is not above it.
#[test]
fn empirical_boundary_brackets_the_exact_one() {
    let betas = vec![0.1, 0.5, 1.0];
    let mut tpl = Config::new(model(0.1, 0.1, 0.0, 0.0, 0), 3000);
    tpl.initial.velocity = 0.05;
    let search = BoundarySearch {
        template: tpl.clone(),
        dampings: betas.clone(),
        a_max: Some(1.0),
        grid: 8,
        rel_tolerance: 1e-4,
        stable_when: StableWhen::Decaying,
    };
    for pt in empirical_boundary(&search).unwrap() {
        let b = pt.b;
        let expect = 2.0 * b * (2.0 - b) / (2.0 + b);
        let (lo, hi) = (pt.a_simulated.unwrap(), pt.a_unstable.unwrap());
        assert!(
            lo <= expect && expect <= hi,
            "beta {b}: [{lo}, {hi}] vs {expect}"
        );
        // The bisection ends at the first run that is not stable: unstable, or undecided
        // within the marginal band around the exact boundary (|ρ − 1| tiny).
        let end = pt.inconclusive.map_or(hi, |i| i.a.min(hi));
        assert!(end - lo <= 1e-4 * end, "{pt:?}");
        if let Some(i) = pt.inconclusive {
            assert_eq!(i.outcome, Outcome::Undecided, "{pt:?}");
            assert!(rel(i.a, expect) < 1e-3, "{pt:?}");
        }
    }
    let mut uni = search;
    uni.template.effects = Effects {
        contact: Contact::Unilateral,
        ..Effects::LINEAR
    };
    uni.template.human = HumanForce::Constant(1.0);
    uni.rel_tolerance = 1e-2;
    for pt in empirical_boundary(&uni).unwrap() {
        let lin = pt.a_linear.unwrap();
        let sim = pt.a_simulated.unwrap();
        assert!(sim <= lin * (1.0 + 1e-2), "beta {}: {sim} vs {lin}", pt.b);
        assert!(sim > 0.5 * lin, "beta {}: {sim} vs {lin}", pt.b);
    }
}

/// Acceptance (c), quantization (Diolaiti et al., ref. [13]): a PHANToM-like device
/// (m = 0.1 kg, T = 1 ms, b = 1.5 Ns/m so δ = 0.015, no arm) with a 30 µm encoder, for
/// d ∈ {0, 1}, β ∈ {0.05, 0.1, 0.2} and α ∈ {0.8, 0.9, 0.95}·α_lin(β): every setting is
/// linearly stable (Schur–Cohn, roots), yet every quantized run from a 1 mm penetration
/// sustains a limit cycle of peak-to-peak amplitude between q/2 and 20q at a frequency within 25 % of
/// the linear dominant mode's; Coulomb friction F_c = F_s = Kq/2 (Diolaiti's bound
/// K < 2F_c/q) removes every one of them (the device sticks).
#[test]
fn quantization_sustains_limit_cycles_inside_the_linear_region() {
    let (q, delta) = (3e-5, 0.015);
    let mut cycles = 0;
    for d in [0, 1] {
        for beta in [0.05, 0.1, 0.2] {
            let lin = exact_alpha_limit(PlantParams::new(0.0, delta).unwrap(), d, beta)
                .unwrap()
                .unwrap();
            for s in [0.8, 0.9, 0.95] {
                let alpha = s * lin;
                let p = Normalized::new(alpha, beta, 0.0, delta, d).unwrap();
                let an = Analysis::new(p).unwrap();
                assert!(an.stable() && an.spectral_radius < 1.0);
                let f_dom = an.roots[0].arg().abs() / (2.0 * std::f64::consts::PI * T);
                let mut cfg = Config::new(Model::new(p, M, T).unwrap(), 20_000);
                cfg.effects.quantization = Some(q);
                cfg.initial.position = 1e-3;
                let r = simulate(&cfg).unwrap();
                let tag = format!("d={d} beta={beta} s={s}: {r:?}");
                assert_eq!(r.verdict.outcome, Outcome::LimitCycle, "{tag}");
                let lc = r.verdict.limit_cycle.unwrap();
                let a = lc.peak_to_peak;
                assert!(a > 0.5 * q && a < 20.0 * q, "{tag}");
                assert_eq!(lc.counts, Some(a / q));
                assert!(!lc.bouncing);
                let f = lc.frequency_hz;
                assert!((f / f_dom - 1.0).abs() < 0.25, "{tag}, f_dom {f_dom}");
                cycles += 1;
                let fc = 0.5 * alpha * M / (T * T) * q;
                cfg.effects.friction = Some(Friction {
                    coulomb: fc,
                    stiction: fc,
                });
                let r = simulate(&cfg).unwrap();
                assert_eq!(
                    r.verdict.outcome,
                    Outcome::Decaying,
                    "with friction {fc} N: {r:?}"
                );
                assert_eq!(r.final_velocity, 0.0);
            }
        }
    }
    assert_eq!(cycles, 18);
    // The empirical boundary therefore depends on the criterion: requiring decay, even
    // α = α_lin/8 (the first grid point) is unstable; accepting limit cycles below 20q peak-to-peak puts
    // the boundary just inside the linear one.
    for d in [0, 1] {
        let mut tpl = Config::new(model(0.1, 0.1, 0.0, delta, d), 5000);
        tpl.effects.quantization = Some(q);
        tpl.initial.position = 1e-3;
        let mut search = BoundarySearch {
            template: tpl,
            dampings: vec![0.1],
            a_max: None,
            grid: 8,
            rel_tolerance: 1e-2,
            stable_when: StableWhen::Decaying,
        };
        let pt = empirical_boundary(&search).unwrap()[0];
        assert_eq!(pt.a_simulated, None, "{pt:?}");
        search.stable_when = StableWhen::AmplitudeBelow(20.0 * q);
        let pt = empirical_boundary(&search).unwrap()[0];
        let (sim, lin) = (pt.a_simulated.unwrap(), pt.a_linear.unwrap());
        assert!(sim > 0.8 * lin && sim <= lin * (1.0 + 1e-2), "{pt:?}");
    }
}

/// A trace of x(t) on t = k·dt, k = 0 … n − 1 (velocity and forces zero: unused here).
fn trace_of(x: impl Fn(f64) -> f64, dt: f64, n: usize) -> hapstab::simulation::Trace {
    let time: Vec<f64> = (0..n).map(|k| k as f64 * dt).collect();
    let position: Vec<f64> = time.iter().map(|&t| x(t)).collect();
    hapstab::simulation::Trace {
        velocity: vec![0.0; n],
        wall_force: vec![0.0; n],
        human_force: vec![0.0; n],
        time,
        position,
    }
}

#[test]
fn settling_time_of_an_exponential_is_ln_fifty() {
    // x = e^{-t} decays to 0: it leaves the 2 % band for good at t = ln 50 (closed form)
    let tr = trace_of(|t| (-t).exp(), 1e-3, 20_001);
    assert_eq!(tr.rest_position(), 0.0);
    let ts = tr.settling_time(hapstab::simulation::SETTLING_BAND);
    assert!((ts - 50f64.ln()).abs() <= 1e-3, "settling time {ts}");
    // a push held against the wall, x = 0.01(1 − e^{-t}): rest at the last position, the
    // distance from it 0.01·e^{-t}(1 − e^{t − 20}) leaves the band at ln 50 as well
    let held = trace_of(|t| 0.01 * (1.0 - (-t).exp()), 1e-3, 20_001);
    assert_eq!(held.rest_position(), *held.position.last().unwrap());
    let ts = held.settling_time(hapstab::simulation::SETTLING_BAND);
    assert!((ts - 50f64.ln()).abs() <= 2e-3, "held settling time {ts}");
    // a trace that never moves has settled from the start
    assert_eq!(trace_of(|_| 0.0, 1e-3, 10).settling_time(0.02), 0.0);
}
