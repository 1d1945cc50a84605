//! Independent check against python-control: the closed loops of
//! `tests/fixtures/control_loops.json` were formed by `benches/baseline/control_fixture.py`
//! with python-control alone (`sample_system(ss(P), T, 'zoh')`, the delay as z^(−d), the velocity
//! estimator as a discrete tf, `feedback`, `poles`) and refereed by
//! `benches/baseline/control_mpmath.py` (the same loops in mpmath at 60 digits:
//! `reference_radius`). hapstab builds the same loops from the same numbers (plants in its
//! serde form, estimators in the `--velocity` text form) through its own engine (exact ZOH,
//! affine family, roots) and must agree with both.
//!
//! Two kinds of loops are set apart, each for a stated reason:
//! - python-control itself misses the referee by more than 1e-9 on a few strongly unstable
//!   loops (ρ of 1.4 to 3.3, up to 5e-8): there hapstab is checked against the referee only.
//! - Where several roots of p(z) crowd near z = 1 (slow plant modes at fast sampling), the
//!   dominant root is ill-conditioned in the coefficients of p(z) in z: its condition number
//!   κ times the unit roundoff exceeds 1e-9, and no root finder working from those
//!   coefficients can reach 1e-9. hapstab polishes the roots near z = 1 in the shifted
//!   variable w = z − 1 (`Analysis::of_family`), where they are well-conditioned; those loops
//!   are checked in a test of their own.

use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::params::Wall;
use hapstab::stability::Analysis;
use hapstab::{AffineFamily, Verdict};
use serde::Deserialize;

/// Spectral radii must agree to this relative difference: both sides compute the roots of
/// well-conditioned closed loops to near machine precision, so 1e-9 leaves room only for
/// the conditioning of the roots, not for a modelling difference.
const RADIUS_REL_TOL: f64 = 1e-9;
/// Verdicts are compared only where the reference radius is this far from 1: closer, the
/// methods' rounding may fall on either side of the circle.
const VERDICT_BAND: f64 = 1e-9;
/// Largest condition number κ of the dominant root for which its modulus can be found to
/// [`RADIUS_REL_TOL`] from the z-coefficients of p(z): κ·ε <= 1e-9 (ε the unit roundoff).
const CONDITION_LIMIT: f64 = RADIUS_REL_TOL / f64::EPSILON;
/// Share of the fixture's cases that must be well-conditioned, so that setting the others
/// apart cannot hollow the test out (the seeded fixture has 96 %).
const MIN_WELL_CONDITIONED: f64 = 0.9;

#[derive(Deserialize)]
struct Fixture {
    cases: Vec<Case>,
}

#[derive(Deserialize)]
struct Case {
    id: usize,
    category: String,
    plant: PlantModel,
    force_lag: f64,
    period: f64,
    delay: usize,
    velocity: String,
    wall_kind: String,
    wall: Wall,
    degree: usize,
    spectral_radius: f64,
    verdict: String,
    reference_radius: f64,
}

fn fixture() -> Fixture {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/fixtures/control_loops.json"
    );
    let text = std::fs::read_to_string(path).expect("fixture control_loops.json");
    serde_json::from_str(&text).expect("fixture schema")
}

fn hapstab_loop(c: &Case) -> Loop {
    let velocity: VelocityEstimator = c.velocity.parse().expect("velocity spec");
    let plant = Plant::new(c.plant.clone(), c.force_lag).expect("plant");
    Loop::new(plant, c.period, Delay::samples(c.delay).unwrap(), velocity).expect("loop")
}

/// hapstab's answer for one case.
struct Answer {
    degree: usize,
    radius: f64,
    verdict: Verdict,
    /// Condition number of the dominant root's modulus under relative perturbations of the
    /// coefficients of p(z): Σ|c_i||z|^i / (|z|·|p'(z)|) at the dominant root z.
    condition: f64,
}

fn analyse(c: &Case) -> Answer {
    let fam = AffineFamily::of_loop(&hapstab_loop(c)).expect("family");
    let (a, b) = fam.to_units(c.wall.stiffness, c.wall.damping);
    let poly = fam.coefficients(a, b);
    let an = Analysis::of_family(&fam, a, b).expect("roots");
    let z = an.roots[0];
    let mut dp = num_complex::Complex64::new(0.0, 0.0);
    let mut size = 0.0;
    for (i, &ci) in poly.iter().enumerate() {
        size += ci.abs() * z.norm().powi(i as i32);
        if i > 0 {
            dp += z.powu(i as u32 - 1) * (ci * i as f64);
        }
    }
    Answer {
        degree: poly.len() - 1,
        radius: an.spectral_radius,
        verdict: an.verdict,
        condition: size / (z.norm() * dp.norm()),
    }
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b
}

/// True when python-control itself misses the referee by more than the tolerance.
fn python_control_off(c: &Case) -> bool {
    rel(c.spectral_radius, c.reference_radius) > RADIUS_REL_TOL
}

/// A disagreement with python-control or the referee, described for the failure message.
fn check(c: &Case, h: &Answer) -> Option<String> {
    let what = format!(
        "case {} ({}, {} wall, d = {}, {}, lag {}): hapstab ρ = {:.17} ({}), python-control ρ = {:.17} ({}), reference ρ = {:.17}, condition {:.1e}",
        c.id,
        c.category,
        c.wall_kind,
        c.delay,
        c.velocity,
        c.force_lag,
        h.radius,
        h.verdict.as_str(),
        c.spectral_radius,
        c.verdict,
        c.reference_radius,
        h.condition
    );
    if h.degree != c.degree {
        return Some(format!("{what}; degree {} vs {}", h.degree, c.degree));
    }
    let off_python = !python_control_off(c) && rel(h.radius, c.spectral_radius) > RADIUS_REL_TOL;
    if off_python || rel(h.radius, c.reference_radius) > RADIUS_REL_TOL {
        return Some(what);
    }
    let decidable = (c.reference_radius - 1.0).abs() >= VERDICT_BAND;
    let want = if c.reference_radius < 1.0 {
        "stable"
    } else {
        "unstable"
    };
    let python_agrees = python_control_off(c) || c.verdict == want;
    (decidable && (h.verdict.as_str() != want || !python_agrees)).then_some(what)
}

/// Cases of the fixture with hapstab's answers.
type Answered = Vec<(Case, Answer)>;

/// The fixture's cases with hapstab's answers, split by the dominant root's conditioning:
/// (well-conditioned, ill-conditioned).
fn answers() -> (Answered, Answered) {
    fixture()
        .cases
        .into_iter()
        .map(|c| {
            let h = analyse(&c);
            (c, h)
        })
        .partition(|(_, h)| h.condition <= CONDITION_LIMIT)
}

fn disagreements(cases: &[(Case, Answer)]) -> Vec<String> {
    cases.iter().filter_map(|(c, h)| check(c, h)).collect()
}

#[test]
fn fixture_covers_every_kind_of_loop() {
    let fx = fixture();
    let loops: std::collections::BTreeSet<usize> = fx.cases.iter().map(|c| c.id).collect();
    assert!(loops.len() >= 200, "{} loops", loops.len());
    for kind in ["mass_spring_damper", "two_mass", "transfer_function"] {
        assert!(fx.cases.iter().any(|c| c.category == kind), "{kind}");
    }
    assert!(fx.cases.iter().any(|c| c.force_lag > 0.0));
    assert!(fx.cases.iter().any(|c| c.wall_kind == "near"));
    assert!((0..=10).all(|d| fx.cases.iter().any(|c| c.delay == d)));
    for v in ["backward", "lowpass:", "average:", "iir:"] {
        assert!(fx.cases.iter().any(|c| c.velocity.starts_with(v)), "{v}");
    }
    let plant_order = |c: &Case| match &c.plant {
        PlantModel::TransferFunction { den, .. } => den.len() - 1,
        PlantModel::TwoMass(_) => 4,
        PlantModel::MassSpringDamper(_) => 2,
    } + usize::from(c.force_lag > 0.0);
    assert_eq!(fx.cases.iter().map(plant_order).max(), Some(6));
}

#[test]
fn spectral_radius_and_verdict_match_python_control() {
    let (good, ill) = answers();
    let share = good.len() as f64 / (good.len() + ill.len()) as f64;
    assert!(share >= MIN_WELL_CONDITIONED, "{share}");
    if let Ok(path) = std::env::var("HAPSTAB_CONTROL_DUMP") {
        // hapstab's radii for benches/baseline/control_mpmath.py --rust PATH
        let lines: Vec<String> = good
            .iter()
            .chain(&ill)
            .map(|(c, h)| format!("{} {} {:e} {:e}", c.id, c.wall_kind, h.radius, h.condition))
            .collect();
        std::fs::write(path, lines.join("\n") + "\n").unwrap();
    }
    let failures = disagreements(&good);
    assert!(
        failures.is_empty(),
        "{} of {} well-conditioned cases disagree:\n{}",
        failures.len(),
        good.len(),
        failures.join("\n")
    );
}

#[test]
fn ill_conditioned_loops_match_the_reference() {
    let (_, ill) = answers();
    let failures = disagreements(&ill);
    assert!(
        failures.is_empty(),
        "{} of {} ill-conditioned cases disagree:\n{}",
        failures.len(),
        ill.len(),
        failures.join("\n")
    );
}
