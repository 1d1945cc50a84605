//! The paper's loop through the general engine reproduces the paper-only engine it replaced.
//!
//! The fixture holds, for 1000 seeded points (γ up to 1, δ up to 1, d ≤ 10), what hapstab
//! 9660ef8 computed with its closed-form paper plant: the spectral radius and the stable α
//! interval at β (`check`) and α_max (`boundary`); `benches/baseline/paper_regression.py`
//! made it. Agreement is required to 1e-12.

use hapstab::PlantParams;
use hapstab::boundary::stable_stiffness_intervals;
use hapstab::paper::NormalizedFamily;
use hapstab::region::stable_region;
use hapstab::stability::Analysis;
use serde::Deserialize;

#[derive(Deserialize)]
struct Point {
    gamma: f64,
    delta: f64,
    d: usize,
    alpha: f64,
    beta: f64,
    spectral_radius: f64,
    alpha_interval: Option<[f64; 2]>,
    alpha_max: f64,
    beta_at_alpha_max: f64,
}

#[derive(Deserialize)]
struct Fixture {
    points: Vec<Point>,
}

/// Relative agreement, with an absolute floor at the rounding level of p(z)'s coefficients
/// (O(1) in these units): a boundary at α = 3e-5 moves by ~1e-16 when a coefficient moves by
/// one ulp, which is 3e-12 of itself, below what either engine can resolve.
fn close(a: f64, b: f64, tol: f64) -> bool {
    a == b || (a - b).abs() <= tol * a.abs().max(b.abs()) + COEFFICIENT_ROUNDING
}

const COEFFICIENT_ROUNDING: f64 = 1e-15;

#[test]
fn general_engine_reproduces_the_paper_engine() {
    let text = include_str!("../../fixtures/paper_regression.json");
    let fx: Fixture = serde_json::from_str(text).expect("fixture");
    assert_eq!(fx.points.len(), 1000);
    let mut with_interval = 0;
    for (i, p) in fx.points.iter().enumerate() {
        let fam = NormalizedFamily::new(PlantParams::new(p.gamma, p.delta).unwrap(), p.d).unwrap();
        let a = Analysis::of_poly(&fam.coefficients(p.alpha, p.beta)).unwrap();
        assert!(
            close(a.spectral_radius, p.spectral_radius, 1e-12),
            "point {i}: ρ {} vs {}",
            a.spectral_radius,
            p.spectral_radius
        );
        let ivs = stable_stiffness_intervals(&fam, p.beta);
        let picked = ivs
            .iter()
            .find(|iv| iv.lo < p.alpha && p.alpha < iv.hi)
            .or_else(|| ivs.iter().max_by(|x, y| x.hi.total_cmp(&y.hi)))
            .map(|iv| [iv.lo, iv.hi]);
        match (picked, p.alpha_interval) {
            (Some(x), Some(y)) => {
                with_interval += 1;
                assert!(
                    close(x[0], y[0], 1e-12) && close(x[1], y[1], 1e-12),
                    "point {i}: interval {x:?} vs {y:?}"
                );
            }
            (None, None) => {}
            (x, y) => panic!("point {i}: interval {x:?} vs {y:?}"),
        }
        let r = stable_region(&fam).unwrap();
        assert!(
            close(r.a_max, p.alpha_max, 1e-12),
            "point {i} (γ={} δ={} d={}): α_max {} vs {}",
            p.gamma,
            p.delta,
            p.d,
            r.a_max,
            p.alpha_max
        );
        assert!(
            close(r.b_at_a_max, p.beta_at_alpha_max, 1e-6),
            "point {i}: β at α_max {} vs {}",
            r.b_at_a_max,
            p.beta_at_alpha_max
        );
    }
    assert!(with_interval > 900, "{with_interval}");
}
