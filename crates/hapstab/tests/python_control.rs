//! Independent check against python-control: the closed loops of
//! `tests/fixtures/control_loops.json` were formed by `benches/baseline/control_fixture.py`
//! with python-control alone (`sample_system(P, T, 'zoh')`, the delay as z^(−d), the velocity
//! estimator as a discrete tf, `feedback`, `poles`). hapstab builds the same loops from the
//! same numbers (plants in its serde form, estimators in the `--velocity` text form) through
//! its own engine (exact ZOH, affine family, roots) and must agree.

use hapstab::model::{Delay, Loop, Plant, PlantModel, VelocityEstimator};
use hapstab::params::Wall;
use hapstab::stability::Analysis;
use hapstab::{AffineFamily, Verdict};
use serde::Deserialize;

/// Spectral radii must agree to this relative difference: both sides compute every root of
/// well-separated closed loops to near machine precision, so 1e-9 leaves room only for the
/// conditioning of the roots, not for a modelling difference.
const RADIUS_REL_TOL: f64 = 1e-9;
/// Verdicts are compared only where python-control's radius is this far from 1: closer, the
/// two methods' rounding may fall on either side of the circle.
const VERDICT_BAND: f64 = 1e-9;

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
}

fn fixture() -> Fixture {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/fixtures/control_loops.json");
    let text = std::fs::read_to_string(path).expect("fixture control_loops.json");
    serde_json::from_str(&text).expect("fixture schema")
}

fn hapstab_loop(c: &Case) -> Loop {
    let velocity: VelocityEstimator = c.velocity.parse().expect("velocity spec");
    let plant = Plant::new(c.plant.clone(), c.force_lag).expect("plant");
    Loop::new(plant, c.period, Delay::samples(c.delay).unwrap(), velocity).expect("loop")
}

/// hapstab's (degree, spectral radius, verdict) for one case.
fn analyse(c: &Case) -> (usize, f64, Verdict) {
    let fam = AffineFamily::of_loop(&hapstab_loop(c)).expect("family");
    let (a, b) = fam.to_units(c.wall.stiffness, c.wall.damping);
    let poly = fam.coefficients(a, b);
    let an = Analysis::of_poly(&poly).expect("roots");
    (poly.len() - 1, an.spectral_radius, an.verdict)
}

/// A disagreement, described for the failure message.
fn check(c: &Case) -> Option<String> {
    let (degree, rho, verdict) = analyse(c);
    let rel = (rho - c.spectral_radius).abs() / c.spectral_radius;
    let what = format!(
        "case {} ({}, {} wall, d = {}, {}, lag {}): hapstab ρ = {rho:.17} ({}), python-control ρ = {:.17} ({}), relative difference {rel:.2e}",
        c.id,
        c.category,
        c.wall_kind,
        c.delay,
        c.velocity,
        c.force_lag,
        verdict.as_str(),
        c.spectral_radius,
        c.verdict
    );
    if degree != c.degree {
        return Some(format!("{what}; degree {degree} vs {}", c.degree));
    }
    if rel > RADIUS_REL_TOL {
        return Some(what);
    }
    let decidable = (c.spectral_radius - 1.0).abs() >= VERDICT_BAND;
    (decidable && verdict.as_str() != c.verdict).then_some(what)
}

#[test]
fn spectral_radius_and_verdict_match_python_control() {
    let fx = fixture();
    let loops: std::collections::BTreeSet<usize> = fx.cases.iter().map(|c| c.id).collect();
    assert!(loops.len() >= 200, "{} loops", loops.len());
    for kind in ["mass_spring_damper", "two_mass", "transfer_function"] {
        assert!(fx.cases.iter().any(|c| c.category == kind), "{kind}");
    }
    assert!(fx.cases.iter().any(|c| c.force_lag > 0.0));
    assert!(fx.cases.iter().any(|c| c.wall_kind == "near"));
    for v in ["backward", "lowpass:", "average:", "iir:"] {
        assert!(fx.cases.iter().any(|c| c.velocity.starts_with(v)), "{v}");
    }
    if let Ok(path) = std::env::var("HAPSTAB_CONTROL_DUMP") {
        // hapstab's radii for benches/baseline/control_mpmath.py --rust PATH
        let lines: Vec<String> = fx
            .cases
            .iter()
            .map(|c| format!("{} {} {:e}", c.id, c.wall_kind, analyse(c).1))
            .collect();
        std::fs::write(path, lines.join("\n") + "\n").unwrap();
    }
    let failures: Vec<String> = fx.cases.iter().filter_map(check).collect();
    assert!(
        failures.is_empty(),
        "{} of {} cases disagree:\n{}",
        failures.len(),
        fx.cases.len(),
        failures.join("\n")
    );
}
