//! The steady-state verdicts of `simulate` against the exact analysis (Section V) and
//! against themselves: linear windows must agree with the spectral radius, settled verdicts
//! must not flip when the run is doubled, contact events are counted, limit cycles are
//! reported only once settled. Expected verdicts come from `hapstab::stability` (roots and
//! Schur–Cohn), never from the simulator.

use hapstab::simulation::{
    Config, Contact, DEFAULT_MAX_SAMPLES, Effects, Friction, HumanForce, Initial, Model, Outcome,
    RunResult, exact_alpha_limit, simulate,
};
use hapstab::{Analysis, Normalized, PlantParams, Verdict};
use rayon::prelude::*;

/// SplitMix64: a seeded generator, so the "random" settings are the same on every run.
struct SplitMix(u64);

impl SplitMix {
    fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next_f64()
    }

    fn log_range(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.next_f64()).exp()
    }
}

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
        let gamma = if rng.next_f64() < 0.5 { 0.0 } else { rng.log_range(1e-5, 0.3) };
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
    let runs = settings.iter().zip(&results).flat_map(|(s, (a, b))| [(s, a), (s, b)]);
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
            assert!(v.contact.separations > 0 || v.outcome == Outcome::Growing, "{tag}");
            if v.outcome == Outcome::LimitCycle {
                assert!(v.limit_cycle.unwrap().bouncing, "{tag}");
            }
            continue;
        }
        premise += 1;
        if v.outcome == Outcome::Undecided {
            assert!((s.rho - 1.0).abs() <= 1e-2, "undecided far from ρ = 1: {tag}");
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
    let far = settings.iter().filter(|s| (s.rho - 1.0).abs() > 1e-2).count();
    let samples: Vec<usize> = results.iter().map(|r| r.0.samples).collect();
    eprintln!(
        "{premise} runs in linear contact (two per setting), {undecided} undecided; coverage (unstable bil., unstable unil., stable bil., stable unil.) {kinds:?}; {far} with |ρ − 1| > 1e-2; samples {}..{}",
        samples.iter().min().unwrap_or(&0),
        samples.iter().max().unwrap_or(&0)
    );
    assert!(premise >= 400, "{premise} runs in linear contact");
    assert!(undecided * 50 < premise, "{undecided} undecided of {premise}");
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
        let tag = format!("{:?} {:?}: {:?} vs {:?}", c.model, c.effects, a.verdict, b.verdict);
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
