//! Property tests across extreme scales: random loops with parameters drawn log-uniformly
//! over the documented ranges (sampling periods 1e-7 … 1 s, masses, dampings and stiffnesses
//! over many decades, delays, every velocity estimator). For every point the answers of
//! independent routes must agree and be finite: the stable stiffness intervals at the
//! point's damping contain its stiffness iff the point test says stable (the Schur–Cohn test
//! where it is well-conditioned, the argument principle where it is not), and (on a subset)
//! the exact region contains it iff the point test says stable.
//!
//! A longer run: `HAPSTAB_EXTREME_CASES=1000000 cargo test -p hapstab --release --test extremes`.

use hapstab::AffineFamily;
use hapstab::argument::verdict_at;
use hapstab::boundary::{AlphaBeta, stable_alpha_intervals};
use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::params::Effective;
use hapstab::region::stable_region;
use hapstab::stability::Verdict;
use proptest::prelude::*;

fn log_uniform(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (lo.ln()..hi.ln()).prop_map(f64::exp)
}

fn maybe_zero(s: impl Strategy<Value = f64>) -> impl Strategy<Value = f64> {
    prop_oneof![1 => Just(0.0), 4 => s]
}

fn velocity() -> impl Strategy<Value = VelocityEstimator> {
    prop_oneof![
        3 => Just(VelocityEstimator::Backward),
        1 => log_uniform(1.0, 1e4).prop_map(|cutoff_hz| VelocityEstimator::LowPass { cutoff_hz }),
        1 => (1usize..20).prop_map(|samples| VelocityEstimator::Average { samples }),
    ]
}

prop_compose! {
    fn a_loop()(
        m in log_uniform(1e-3, 10.0),
        b in maybe_zero(log_uniform(1e-3, 1e3)),
        k in maybe_zero(log_uniform(1e-2, 1e6)),
        period in log_uniform(1e-7, 1.0),
        d in 0usize..12,
        frac in prop_oneof![3 => Just(0.0), 1 => 0.01f64..0.99],
        v in velocity(),
    ) -> Loop {
        let plant = Plant::mass_spring_damper(Effective::new(m, b, k).unwrap()).unwrap();
        let delay = Delay { samples: d, fraction: frac };
        Loop::new(plant, period, delay, v).unwrap()
    }
}

/// Relative distance below which a stiffness counts as on an interval's end.
const ON_BOUNDARY: f64 = 1e-9;

fn check_point(fam: &AffineFamily, a: f64, b: f64) -> Result<(), TestCaseError> {
    let mut c = fam.coefficients(a, b);
    prop_assert!(c.iter().all(|x| x.is_finite()), "coefficients not finite");
    let verdict = verdict_at(fam, a, b, &mut c);
    if verdict == Verdict::Marginal {
        return Ok(()); // a root within rounding of the circle: no side to agree on
    }
    let stable = verdict == Verdict::Stable;
    let ivs = stable_alpha_intervals(fam, b);
    for iv in &ivs {
        prop_assert!(!iv.lo.is_nan() && !iv.hi.is_nan());
    }
    let scale = a.abs().max(1e-300);
    let near_end = ivs.iter().any(|iv| {
        (iv.lo - a).abs() <= ON_BOUNDARY * scale || (iv.hi - a).abs() <= ON_BOUNDARY * scale
    });
    if !near_end {
        let inside = ivs.iter().any(|iv| iv.lo < a && a < iv.hi);
        prop_assert_eq!(inside, stable, "a = {}, b = {}, intervals {:?}", a, b, ivs);
    }
    Ok(())
}

/// A signed value log-uniform in magnitude over [lo, hi]: walls near the wall-free point,
/// where fast sampling puts every root near z = 1.
fn signed_log(lo: f64, hi: f64) -> impl Strategy<Value = f64> {
    (any::<bool>(), log_uniform(lo, hi)).prop_map(|(neg, x)| if neg { -x } else { x })
}

/// Cases per property: 4000 in CI; a longer run sets HAPSTAB_EXTREME_CASES (the region
/// property runs a tenth as many).
fn cases() -> u32 {
    std::env::var("HAPSTAB_EXTREME_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(4000)
}

/// The same cases on every CI run (a failure is then reproduced by rerunning); a longer run
/// (HAPSTAB_EXTREME_CASES) draws fresh ones, or those of PROPTEST_RNG_SEED.
fn config(cases: u32) -> ProptestConfig {
    let mut c = ProptestConfig::with_cases(cases);
    if std::env::var_os("HAPSTAB_EXTREME_CASES").is_none()
        && std::env::var_os("PROPTEST_RNG_SEED").is_none()
    {
        c.rng_seed = proptest::test_runner::RngSeed::Fixed(CI_SEED);
    }
    c
}

/// Seed of the CI cases.
const CI_SEED: u64 = 0x4841_5053;

proptest! {
    #![proptest_config(config(cases()))]

    #[test]
    fn intervals_agree_with_the_point_test_near_the_origin(
        lp in a_loop(), a in signed_log(1e-14, 1.0), b in signed_log(1e-12, 1.0)
    ) {
        let fam = AffineFamily::of_loop(&lp).unwrap();
        check_point(&fam, a, b)?;
    }

    #[test]
    fn intervals_agree_with_the_point_test(lp in a_loop(), a in -2.0f64..2.0, b in -1.0f64..3.0) {
        let fam = AffineFamily::of_loop(&lp).unwrap();
        // wall units scale like (α, β); spread the wall over the region's typical extent
        let d = lp.delay.in_samples() + 0.5;
        check_point(&fam, a / d, b / d.sqrt())?;
    }
}

proptest! {
    #![proptest_config(config(cases() / 10))]

    #[test]
    fn region_agrees_with_the_point_test(lp in a_loop(), a in -2.0f64..2.0, b in -1.0f64..3.0) {
        let fam = AffineFamily::of_loop(&lp).unwrap();
        let d = lp.delay.in_samples() + 0.5;
        let (a, b) = (a / d, b / d.sqrt());
        let Ok(r) = stable_region(&fam) else {
            return Ok(()); // an honest refusal is allowed; counted in the report test
        };
        prop_assert!(r.area.is_finite());
        for p in &r.polygons {
            prop_assert!(p.vertices.iter().all(|v| v.alpha.is_finite() && v.beta.is_finite()));
        }
        let verdict = verdict_at(&fam, a, b, &mut fam.coefficients(a, b));
        if verdict == Verdict::Marginal {
            return Ok(());
        }
        let stable = verdict == Verdict::Stable;
        let inside = r.contains(AlphaBeta { alpha: a, beta: b });
        if stable != inside {
            // only allowed within the polygon tolerance of the boundary: check by intervals
            let ivs = stable_alpha_intervals(&fam, b);
            let scale = r.alpha_max.abs().max(a.abs()).max(1e-300);
            let near = ivs.iter().any(|iv| (iv.lo - a).abs() < 1e-8 * scale || (iv.hi - a).abs() < 1e-8 * scale);
            prop_assert!(near, "a = {a}, b = {b}: point test {stable}, region {inside}, intervals {ivs:?}");
        }
    }
}

/// Known defect, found by a long random run: an undamped plant far outside the paper's ranges
/// (γ = 6.5e6, δ = 0, d = 3: m = 22 g, k = 681 kN/m at T = 0.46 s) has stable walls at
/// (α, β) ≈ (−0.19, −0.29), a distance of 1e-8 of the region's size from the wall-free
/// corner, that the drawn region leaves out (the stable intervals and the point test agree
/// that they are stable).
#[test]
#[ignore = "known defect: a region feature at 1e-8 of the region's size near an undamped corner"]
fn undamped_corner_at_extreme_gamma() {
    let plant = Plant::mass_spring_damper(
        Effective::new(0.02224805533028814, 0.0, 680605.0573079706).unwrap(),
    )
    .unwrap();
    let lp = Loop::new(
        plant,
        0.4600570433599097,
        Delay::samples(3).unwrap(),
        VelocityEstimator::Backward,
    )
    .unwrap();
    let fam = AffineFamily::of_loop(&lp).unwrap();
    let (a, b) = (-0.18875524752594028, -0.2914861175691367);
    assert_eq!(
        verdict_at(&fam, a, b, &mut fam.coefficients(a, b)),
        Verdict::Stable
    );
    let r = stable_region(&fam).unwrap();
    assert!(r.contains(AlphaBeta { alpha: a, beta: b }));
}
