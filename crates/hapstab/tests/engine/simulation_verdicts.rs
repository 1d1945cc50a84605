//! The steady-state verdicts of `simulate` against the exact analysis (Section V) and
//! against themselves: linear windows must agree with the spectral radius, settled verdicts
//! must not flip when the run is doubled, contact events are counted, limit cycles are
//! reported only once settled. Expected verdicts come from `hapstab::stability` (roots and
//! Schur–Cohn), never from the simulator.

use crate::common;
use common::SplitMix;
use hapstab::simulation::{
    Config, Contact, DEFAULT_MAX_SAMPLES, Effects, Friction, HumanForce, Initial, Model, Outcome,
    RunResult, exact_alpha_limit, simulate,
};
use hapstab::{Analysis, Normalized, PlantParams, Verdict};
use rayon::prelude::*;

/// The CLI's default run: 10 000 samples from x(0) = 1 mm at rest (`hapstab simulate`).
const DEFAULT_SAMPLES: usize = 10_000;
/// The explorer's shortest run: the first judgement comes after 300 samples.
const SHORT_SAMPLES: usize = 300;
const DEFAULT_X0: f64 = 1e-3;

/// One random linear setting: a model and how the wall touches the device.
#[derive(Debug, Clone)]
struct Setting {
    model: Model,
    unilateral: bool,
    push: f64,
    x0: f64,
    rho: f64,
    verdict: Verdict,
}

/// A random plant: physical (device and arm in SI units, T from 0.1 to 10 ms) or
/// normalized (m = 1, T = 1), with d from 0 to 10.
fn random_plant(rng: &mut SplitMix) -> (PlantParams, usize, f64, f64) {
    let d = (rng.next_f64() * 11.0) as usize;
    if rng.next_f64() < 0.5 {
        let (m, t) = (rng.log_range(0.05, 3.0), rng.log_range(1e-4, 1e-2));
        let (b, k) = (rng.range(0.0, 10.0), rng.range(0.0, 1000.0));
        let plant = PlantParams::new(k * t * t / m, b * t / m).unwrap();
        (plant, d, m, t)
    } else {
        let gamma = if rng.next_f64() < 0.5 {
            0.0
        } else {
            rng.log_range(1e-5, 0.3)
        };
        let plant = PlantParams::new(gamma, rng.log_range(1e-4, 1.0)).unwrap();
        (plant, d, 1.0, 1.0)
    }
}

/// A random wall scattered around the exact boundary along α at a random β, with
/// |ρ − 1| > 1e-3; unilateral settings are pushed so that a stable contact is never lost.
fn random_setting(rng: &mut SplitMix) -> Option<Setting> {
    let (plant, d, m, t) = random_plant(rng);
    let beta = rng.range(0.0, 1.5) / (1.0 + d as f64);
    let limit = exact_alpha_limit(plant, d, beta).ok()??;
    if !(limit.is_finite() && limit > 0.0) {
        return None;
    }
    let alpha = limit * rng.range(0.5, 1.5);
    let params = Normalized::new(alpha, beta, plant.gamma, plant.delta, d).ok()?;
    let an = Analysis::new(params).ok()?;
    if (an.spectral_radius - 1.0).abs() <= 1e-3 {
        return None;
    }
    let unilateral = rng.next_f64() < 0.5;
    // Push 1 N (or a normalized force of 1e-3 m); start 5 % beyond the equilibrium
    // penetration F/(K + k), so the deviation never exceeds the penetration while it decays.
    let push = if m == 1.0 && t == 1.0 { 1e-3 } else { 1.0 };
    let stiffness = (alpha + plant.gamma) * m / (t * t);
    Some(Setting {
        model: Model::new(params, m, t).unwrap(),
        unilateral,
        push: if unilateral { push } else { 0.0 },
        x0: if unilateral {
            1.05 * push / stiffness
        } else {
            DEFAULT_X0
        },
        rho: an.spectral_radius,
        verdict: an.verdict,
    })
}

fn run(s: &Setting, samples: usize) -> RunResult {
    let mut cfg = Config::new(s.model, samples);
    if s.unilateral {
        cfg.effects.contact = Contact::Unilateral;
    }
    cfg.human = HumanForce::Constant(s.push);
    cfg.initial = Initial {
        position: s.x0,
        velocity: 0.0,
    };
    simulate(&cfg).unwrap()
}

/// Property: on 300 seeded random linear settings (physical and normalized, d <= 10,
/// bilateral and unilateral with a push) with |ρ − 1| > 1e-3, the default verdict (and the
/// verdict of a run that starts as short as the explorer's, 300 samples) equals
/// the analysis' verdict (stable ↔ decaying, unstable ↔ growing) with a linear judged window,
/// or is undecided (under 2 % of these, never for |ρ − 1| > 1e-2); the measured growth lies
/// on the same side of 1 as ρ, and a stable unilateral contact is never lost. An unstable
/// unilateral contact cannot keep contact (Remark 1 needs a device that stays on the wall):
/// those runs must lose contact and must never be called decaying; a cycle is a bouncing one.
#[test]
fn default_verdict_agrees_with_the_analysis_on_random_linear_settings() {
    let mut rng = SplitMix(0x0DEC_1DED_2008);
    let mut settings = Vec::new();
    while settings.len() < 300 {
        if let Some(s) = random_setting(&mut rng) {
            settings.push(s);
        }
    }
    let results: Vec<(RunResult, RunResult)> = settings
        .par_iter()
        .map(|s| (run(s, DEFAULT_SAMPLES), run(s, SHORT_SAMPLES)))
        .collect();
    let (mut premise, mut undecided) = (0, 0);
    let mut kinds = [0usize; 4]; // stable/unstable × bilateral/unilateral
    let runs = settings
        .iter()
        .zip(&results)
        .flat_map(|(s, (a, b))| [(s, a), (s, b)]);
    for (s, r) in runs {
        let v = &r.verdict;
        let tag = format!("{s:?}: {v:?}, {} samples", r.samples);
        let stable = s.verdict == Verdict::Stable;
        if r.requested_samples == DEFAULT_SAMPLES {
            kinds[usize::from(stable) * 2 + usize::from(s.unilateral)] += 1;
        }
        assert_eq!(v.spectral_radius, Some(s.rho), "{tag}");
        if s.unilateral && !stable {
            assert!(v.outcome != Outcome::Decaying, "{tag}");
            assert!(
                v.contact.separations > 0 || v.outcome == Outcome::Growing,
                "{tag}"
            );
            if v.outcome == Outcome::LimitCycle {
                assert!(v.limit_cycle.unwrap().bouncing, "{tag}");
            }
            continue;
        }
        premise += 1;
        if v.outcome == Outcome::Undecided {
            assert!(
                (s.rho - 1.0).abs() <= 1e-2,
                "undecided far from ρ = 1: {tag}"
            );
            undecided += 1;
            continue;
        }
        assert!(v.linear_window, "{tag}");
        let expect = if stable {
            Outcome::Decaying
        } else {
            Outcome::Growing
        };
        assert_eq!(v.outcome, expect, "{tag}");
        assert_eq!(v.contact.separations, 0, "{tag}");
        if let Some(g) = v.measured_growth_per_sample {
            assert_eq!(g < 1.0, stable, "measured growth {g}: {tag}");
        }
    }
    let far = settings
        .iter()
        .filter(|s| (s.rho - 1.0).abs() > 1e-2)
        .count();
    let samples: Vec<usize> = results.iter().map(|r| r.0.samples).collect();
    eprintln!(
        "{premise} runs in linear contact (two per setting), {undecided} undecided; coverage (unstable bil., unstable unil., stable bil., stable unil.) {kinds:?}; {far} with |ρ − 1| > 1e-2; samples {}..{}",
        samples.iter().min().unwrap_or(&0),
        samples.iter().max().unwrap_or(&0)
    );
    assert!(premise >= 400, "{premise} runs in linear contact");
    assert!(
        undecided * 50 < premise,
        "{undecided} undecided of {premise}"
    );
    assert!(kinds.iter().all(|&k| k >= 30), "coverage {kinds:?}");
}

/// The measured envelope growth is a measurement of the spectral radius: on linear
/// bilateral settings far from the boundary its log-rate is within 5 % of ln ρ.
#[test]
fn measured_growth_matches_the_spectral_radius() {
    let mut rng = SplitMix(0x6E0_7711);
    let mut checked = 0;
    while checked < 40 {
        let Some(mut s) = random_setting(&mut rng) else {
            continue;
        };
        if (s.rho - 1.0).abs() < 0.01 {
            continue;
        }
        s.unilateral = false;
        s.push = 0.0;
        s.x0 = DEFAULT_X0;
        let r = run(&s, DEFAULT_SAMPLES);
        let Some(g) = r.verdict.measured_growth_per_sample else {
            continue;
        };
        let (lg, lr) = (g.ln(), s.rho.ln());
        assert!(
            (lg - lr).abs() <= 0.05 * lr.abs(),
            "{s:?}: measured {g} vs ρ {}",
            s.rho
        );
        checked += 1;
    }
}

/// A quantized or frictional setting (PHANToM-like device with an arm, T = 1 ms, d from 0
/// to 3, α from 0.2 to 1.2 of the linear limit, bilateral or pushed against a unilateral
/// wall).
fn nonlinear_setting(rng: &mut SplitMix) -> Option<Config> {
    let (m, t) = (rng.range(0.1, 1.5), 1e-3);
    let (b, k) = (rng.range(0.5, 8.0), rng.range(0.0, 400.0));
    let d = (rng.next_f64() * 4.0) as usize;
    let plant = PlantParams::new(k * t * t / m, b * t / m).ok()?;
    let beta = rng.range(0.02, 0.6) / (1.0 + d as f64);
    let limit = exact_alpha_limit(plant, d, beta).ok()??;
    if !limit.is_finite() {
        return None;
    }
    let alpha = limit * rng.range(0.2, 1.2);
    let params = Normalized::new(alpha, beta, plant.gamma, plant.delta, d).ok()?;
    let mut cfg = Config::new(Model::new(params, m, t).ok()?, 10_000);
    let kw = alpha * m / (t * t);
    cfg.effects = Effects {
        contact: if rng.next_f64() < 0.5 {
            Contact::Bilateral
        } else {
            Contact::Unilateral
        },
        ..Effects::LINEAR
    };
    if rng.next_f64() < 0.6 {
        cfg.effects.quantization = Some(rng.log_range(1e-6, 3e-5));
    }
    if cfg.effects.quantization.is_none() || rng.next_f64() < 0.3 {
        let fc = kw * rng.log_range(1e-6, 3e-5);
        cfg.effects.friction = Some(Friction {
            coulomb: fc,
            stiction: fc * rng.range(1.0, 2.0),
        });
    }
    cfg.human = HumanForce::Constant(rng.range(0.5, 3.0));
    cfg.initial.position = 1e-3;
    Some(cfg)
}

/// No verdict flips when the run is doubled: on 50 seeded settings with quantization or
/// friction whose default run settles, the run of twice the length settles to the same
/// outcome (and a limit cycle to the same bouncing kind).
#[test]
fn settled_verdicts_do_not_flip_when_the_run_is_doubled() {
    let mut rng = SplitMix(0xD0_0B1E);
    let mut configs = Vec::new();
    while configs.len() < 80 {
        if let Some(c) = nonlinear_setting(&mut rng) {
            configs.push(c);
        }
    }
    let pairs: Vec<(RunResult, RunResult)> = configs
        .par_iter()
        .map(|c| {
            let mut long = c.clone();
            long.samples *= 2;
            (simulate(c).unwrap(), simulate(&long).unwrap())
        })
        .collect();
    let mut settled = 0;
    let mut outcomes = std::collections::BTreeMap::new();
    for (c, (a, b)) in configs.iter().zip(&pairs) {
        if a.verdict.outcome == Outcome::Undecided {
            continue;
        }
        settled += 1;
        *outcomes.entry(a.verdict.outcome.as_str()).or_insert(0) += 1;
        let tag = format!(
            "{:?} {:?}: {:?} vs {:?}",
            c.model, c.effects, a.verdict, b.verdict
        );
        assert_eq!(a.verdict.outcome, b.verdict.outcome, "{tag}");
        let kind = |r: &RunResult| r.verdict.limit_cycle.map(|l| l.bouncing);
        assert_eq!(kind(a), kind(b), "{tag}");
        if settled == 50 {
            break;
        }
    }
    eprintln!("50 settled settings: {outcomes:?}");
    assert_eq!(settled, 50, "only {settled} settled: {outcomes:?}");
    assert!(outcomes.len() >= 2, "{outcomes:?}");
}

/// The default horizon is what the documentation says.
#[test]
fn default_horizon() {
    let p = Normalized::new(0.1, 0.5, 0.0, 0.0, 0).unwrap();
    let cfg = Config::new(Model::unit(p).unwrap(), 500);
    assert_eq!(cfg.max_samples, DEFAULT_MAX_SAMPLES);
    assert_eq!(DEFAULT_MAX_SAMPLES, 1_000_000);
}

/// The device of the reproductions: 0.2 kg, 2 Ns/m, held by the default arm (1 kg, 6 Ns/m,
/// 350 N/m), so m = 1.2 kg, b = 8 Ns/m, k = 350 N/m; T = 1 ms; wall K, B in N/m and Ns/m.
fn held_device(k_wall: f64, b_wall: f64, d: usize) -> Model {
    let (m, t) = (1.2, 1e-3);
    let p = Normalized::new(
        k_wall * t * t / m,
        b_wall * t / m,
        350.0 * t * t / m,
        8.0 * t / m,
        d,
    );
    Model::new(p.unwrap(), m, t).unwrap()
}

/// Upward crossings of the position through `level` per second over `from..` of a trace.
fn crossing_rate(tr: &hapstab::simulation::Trace, from: f64, level: f64) -> f64 {
    let idx: Vec<usize> = (1..tr.time.len())
        .filter(|&i| {
            tr.time[i - 1] >= from && tr.position[i - 1] < level && tr.position[i] >= level
        })
        .collect();
    let (a, b) = (idx[0], idx[idx.len() - 1]);
    (idx.len() - 1) as f64 / (tr.time[b] - tr.time[a])
}

/// An unstable unilateral contact (K = 20 kN/m, B = 5 Ns/m, d = 1: spectral radius 1.007)
/// pushed with 1 N from the surface at 10 mm/s, judged after 0.3 s: the oscillation grows in
/// contact until the device leaves the wall, then bounces. The verdict is a bouncing limit
/// cycle (contact lost and regained every cycle), never decaying, with no growth factor; its
/// frequency matches the position crossings of the trace.
#[test]
fn unstable_unilateral_contact_bounces() {
    let mut cfg = Config::new(held_device(20_000.0, 5.0, 1), 300);
    cfg.effects.contact = Contact::Unilateral;
    cfg.human = HumanForce::Constant(1.0);
    cfg.initial = Initial {
        position: 0.0,
        velocity: 0.01,
    };
    cfg.trace_rows = 100_000;
    let r = simulate(&cfg).unwrap();
    let v = &r.verdict;
    assert_eq!(v.outcome, Outcome::LimitCycle, "{v:?}");
    assert!(r.samples > 300, "extended until settled");
    assert!(v.spectral_radius.unwrap() > 1.0 && v.linear_verdict == Some(Verdict::Unstable));
    assert!(!v.linear_window && v.measured_growth_per_sample.is_none());
    let lc = v.limit_cycle.unwrap();
    assert!(
        lc.bouncing
            && v.reason
                .contains("contact is lost and regained every cycle")
    );
    // One separation per cycle in the judged window.
    assert!(
        (v.contact.judged_separations as f64 - lc.cycles).abs() <= 1.0,
        "{v:?}"
    );
    let tr = r.trace.unwrap();
    let from = v.judged_from_sample as f64 * 1e-3;
    let tail: Vec<f64> = (0..tr.time.len())
        .filter(|&i| tr.time[i] >= from)
        .map(|i| tr.position[i])
        .collect();
    let (lo, hi) = tail
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
    assert!((hi - lo - lc.peak_to_peak).abs() <= 1e-12, "{lc:?}");
    let f = crossing_rate(&tr, from, 0.5 * (lo + hi));
    assert!((f / lc.frequency_hz - 1.0).abs() < 0.05, "{f} Hz vs {lc:?}");
}

/// A stable quantized unilateral contact (K = 8 kN/m, B = 5 Ns/m, d = 1, q = 10 µm, pushed
/// with 2 N; spectral radius 0.9996) decays slowly into a quantization cycle. Judged after
/// 2 s it is not called a limit cycle before the cycle has settled: the run is extended and
/// reports the same cycle as a 20 s run (about 2.5 counts peak-to-peak). With the horizon at
/// 2 s it is undecided, with the reason.
#[test]
fn slow_quantized_transient_is_not_a_limit_cycle() {
    let run = |seconds: usize, horizon: Option<usize>| {
        let mut cfg = Config::new(held_device(8000.0, 5.0, 1), seconds * 1000);
        cfg.max_samples = horizon.unwrap_or(cfg.max_samples);
        cfg.effects.contact = Contact::Unilateral;
        cfg.effects.quantization = Some(1e-5);
        cfg.human = HumanForce::Constant(2.0);
        cfg.initial.position = 1e-3;
        simulate(&cfg).unwrap()
    };
    let (short, long) = (run(2, None), run(20, None));
    assert!(short.samples > 2000);
    for r in [&short, &long] {
        assert_eq!(r.verdict.outcome, Outcome::LimitCycle, "{:?}", r.verdict);
        assert!(r.verdict.spectral_radius.unwrap() < 1.0);
    }
    let (a, b) = (
        short.verdict.limit_cycle.unwrap(),
        long.verdict.limit_cycle.unwrap(),
    );
    assert!(
        (a.peak_to_peak / b.peak_to_peak - 1.0).abs() < 0.1,
        "{a:?} vs {b:?}"
    );
    assert!(
        (a.frequency_hz / b.frequency_hz - 1.0).abs() < 0.05,
        "{a:?} vs {b:?}"
    );
    assert!((2.0..4.0).contains(&b.counts.unwrap()), "{b:?}");
    assert_eq!(b.counts, Some(b.peak_to_peak / 1e-5));
    let capped = run(2, Some(2000));
    assert_eq!(capped.verdict.outcome, Outcome::Undecided);
    assert!(
        capped.verdict.reason.contains("horizon"),
        "{}",
        capped.verdict.reason
    );
    assert!(capped.verdict.limit_cycle.is_none());
}

/// A device without arm, not pushed, started 1 mm inside a stable unilateral wall: the wall
/// pushes it out and it drifts away for good. That is `separated` (one bounce), never
/// decaying; the linear analysis of the contact is reported beside it.
#[test]
fn device_that_leaves_the_wall_is_separated() {
    let p = Normalized::new(0.02, 0.2, 0.0, 0.01, 1).unwrap();
    let mut cfg = Config::new(Model::new(p, 0.1, 1e-3).unwrap(), 10_000);
    cfg.effects.contact = Contact::Unilateral;
    cfg.initial.position = 1e-3;
    let r = simulate(&cfg).unwrap();
    let v = &r.verdict;
    assert_eq!(v.outcome, Outcome::Separated, "{v:?}");
    assert_eq!((v.contact.separations, v.contact.contacts), (1, 0));
    assert!(!v.contact.in_contact_at_end && v.contact.judged_contact_fraction == 0.0);
    assert_eq!(
        v.reason,
        "left the wall after 1 bounce and stayed out of contact over the whole judged window"
    );
    assert!(r.final_velocity < 0.0 && r.final_position < 0.0);
    assert_eq!(v.linear_verdict, Some(Verdict::Stable));
    // The same setting pushed with 1 N stays in contact and decays as the analysis says.
    cfg.human = HumanForce::Constant(1.0);
    let v = simulate(&cfg).unwrap().verdict;
    assert_eq!(v.outcome, Outcome::Decaying, "{v:?}");
    assert!(v.linear_window);
}

/// A push toward the wall brings a device that left it back: while it is on its way the
/// run is not called separated.
#[test]
fn device_coming_back_is_not_separated() {
    // No arm, no damping, tiny push: after leaving at about 0.2 m/s the device needs
    // 2 m v / F = 40 s to come back, far beyond the first check at 1 s.
    let p = Normalized::new(0.02, 0.2, 0.0, 0.0, 0).unwrap();
    let mut cfg = Config::new(Model::new(p, 0.1, 1e-3).unwrap(), 1000);
    cfg.effects.contact = Contact::Unilateral;
    cfg.human = HumanForce::Constant(0.001);
    cfg.initial.position = 1e-3;
    let r = simulate(&cfg).unwrap();
    let v = &r.verdict;
    assert_ne!(v.outcome, Outcome::Separated, "{v:?}");
    assert!(v.contact.contacts >= 1, "{v:?}");
}

/// The trace of an extended run keeps at most `trace_rows` rows, evenly spaced over the
/// whole run (the stride doubles when it fills up). The run: the undamped arm alone
/// (K = B = 0, δ = 0), a marginal loop whose oscillation never decays, so the run goes to its
/// horizon and is undecided, saying it is marginal.
#[test]
fn trace_of_an_extended_run_is_bounded() {
    let p = Normalized::new(0.0, 0.0, 0.01, 0.0, 0).unwrap();
    let mut cfg = Config::new(Model::unit(p).unwrap(), 1000);
    cfg.initial.position = 1e-3;
    cfg.max_samples = 200_000;
    cfg.trace_rows = 1000;
    let r = simulate(&cfg).unwrap();
    assert_eq!(r.samples, 200_000);
    assert_eq!(r.verdict.outcome, Outcome::Undecided);
    assert!(
        r.verdict.reason.contains("marginal"),
        "{}",
        r.verdict.reason
    );
    let tr = r.trace.unwrap();
    assert!(
        tr.time.len() <= 1000 && tr.time.len() >= 500,
        "{}",
        tr.time.len()
    );
    for (i, t) in tr.time.iter().enumerate() {
        assert_eq!(*t, (i * r.trace_stride) as f64);
    }
    assert!(tr.time.last().unwrap() + r.trace_stride as f64 >= r.samples as f64);
}
