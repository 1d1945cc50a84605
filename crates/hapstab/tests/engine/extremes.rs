//! Property tests across extreme scales: random loops with parameters drawn log-uniformly
//! over the documented ranges (sampling periods 1e-7 … 1 s, masses, dampings and stiffnesses
//! over many decades, delays, every velocity estimator). For every point the answers of
//! independent routes must agree and be finite: the stable stiffness intervals at the
//! point's damping contain its stiffness iff the point test says stable (the Schur–Cohn test
//! where it is well-conditioned, the argument principle where it is not), and (on a subset)
//! the exact region contains it iff the point test says stable.
//!
//! A longer run: `HAPSTAB_EXTREME_CASES=1000000 cargo test -p hapstab --release --test engine extremes::`.

use hapstab::AffineFamily;
use hapstab::boundary::{WallPoint, stable_stiffness_intervals};
use hapstab::model::{Delay, Loop, MAX_PERIOD, MIN_PERIOD, Plant, VelocityEstimator};
use hapstab::paper::PlantParams;
use hapstab::params::Effective;
use hapstab::region::{DEFAULT_REL_TOL, StableRegion, stable_region, stable_region_with};
use hapstab::stability::Verdict;
use hapstab::verdict::decide;
use proptest::prelude::*;

/// The one verdict at a wall (the library's `decide`).
fn verdict_at(fam: &AffineFamily, a: f64, b: f64, c: &mut [f64]) -> Verdict {
    decide(fam, a, b, c).verdict
}

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
        period in log_uniform(1e-7, 1.0).prop_map(|t| t.clamp(MIN_PERIOD, MAX_PERIOD)),
        d in 0usize..12,
        frac in prop_oneof![3 => Just(0.0), 1 => 0.01f64..0.99],
        v in velocity(),
    ) -> Loop {
        let plant = Plant::mass_spring_damper(Effective::new(m, b, k).unwrap()).unwrap();
        let delay = Delay { samples: d, fraction: frac };
        Loop::new(plant, period, delay, v).unwrap()
    }
}

/// The family of the paper's plant (m, b, k) with a sampling period, delay and estimator.
fn msd_family(
    (m, b, k): (f64, f64, f64),
    period: f64,
    delay: Delay,
    v: VelocityEstimator,
) -> AffineFamily {
    let plant = Plant::mass_spring_damper(Effective::new(m, b, k).unwrap()).unwrap();
    AffineFamily::of_loop(&Loop::new(plant, period, delay, v).unwrap()).unwrap()
}

/// A wall the point test decides stable lies in the loop's region, or the region is refused.
fn stable_wall_in_region_or_refused(fam: &AffineFamily, w: WallPoint) {
    let mut c = fam.coefficients(w.a, w.b);
    assert_eq!(verdict_at(fam, w.a, w.b, &mut c), Verdict::Stable);
    if let Ok(r) = stable_region(fam) {
        assert!(r.contains(w), "{w:?} outside {} polygons", r.polygons.len());
    }
}

/// On an n × n grid over the box, the region contains exactly the walls the point test calls
/// stable, except within its chord tolerance of its edges.
fn region_agrees_on_a_grid(
    fam: &AffineFamily,
    r: &StableRegion,
    (a0, a1): (f64, f64),
    (b0, b1): (f64, f64),
    n: usize,
) {
    let band = DEFAULT_REL_TOL * r.size();
    let mut c = fam.coefficients(0.0, 0.0);
    for i in 0..n {
        for j in 0..n {
            let w = WallPoint {
                a: a0 + (a1 - a0) * (i as f64 + 0.37) / n as f64,
                b: b0 + (b1 - b0) * (j as f64 + 0.61) / n as f64,
            };
            let v = verdict_at(fam, w.a, w.b, &mut c);
            if v != Verdict::Marginal && r.contains(w) != (v == Verdict::Stable) {
                assert!(r.boundary_distance(w) <= band, "{v:?} at {w:?}");
            }
        }
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
    let ivs = stable_stiffness_intervals(fam, b);
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
            return Ok(()); // an honest refusal is allowed; its rate is held by `region_refusals_are_rare`
        };
        prop_assert!(r.area.is_finite());
        for p in &r.polygons {
            prop_assert!(p.vertices.iter().all(|v| v.a.is_finite() && v.b.is_finite()));
        }
        let verdict = verdict_at(&fam, a, b, &mut fam.coefficients(a, b));
        if verdict == Verdict::Marginal {
            return Ok(());
        }
        let stable = verdict == Verdict::Stable;
        let inside = r.contains(WallPoint { a, b });
        if stable != inside {
            // only allowed within the polygon's chord tolerance of its boundary
            let w = WallPoint { a, b };
            let (dist, tol) = (r.boundary_distance(w), DEFAULT_REL_TOL * r.size());
            prop_assert!(
                dist <= tol,
                "a = {a}, b = {b}: point test {stable}, region {inside}, {dist} from its edges (tolerance {tol})"
            );
        }
    }
}

/// Found by a long random run: an undamped plant far outside the paper's ranges (γ = 6.5e6,
/// δ = 0, d = 3: m = 22 g, k = 681 kN/m at T = 0.46 s) has stable walls at (α, β) ≈
/// (−0.19, −0.29), 0.14 from the region's edge in a region 1.8e8 across. The polygon may
/// leave them out at its default tolerance (1e-9 of the size, here 0.18) but must be within
/// that tolerance of them, and a tighter tolerance must include them.
#[test]
fn undamped_corner_at_extreme_gamma() {
    let fam = msd_family(
        (0.02224805533028814, 0.0, 680605.0573079706),
        0.4600570433599097,
        Delay::samples(3).unwrap(),
        VelocityEstimator::Backward,
    );
    let w = WallPoint {
        a: -0.18875524752594028,
        b: -0.2914861175691367,
    };
    assert_eq!(
        verdict_at(&fam, w.a, w.b, &mut fam.coefficients(w.a, w.b)),
        Verdict::Stable
    );
    // the exact boundary at this damping (stable intervals) is 0.11 away in α
    let ivs = stable_stiffness_intervals(&fam, w.b);
    assert!(ivs.iter().any(|iv| iv.lo < w.a && w.a < iv.hi));
    let r = stable_region(&fam).unwrap();
    if !r.contains(w) {
        assert!(r.boundary_distance(w) <= DEFAULT_REL_TOL * r.size());
    }
    let fine = stable_region_with(&fam, 1e-11).unwrap();
    assert!(fine.contains(w));
}

/// Found by a long random run: a loop sampled at 1 s with 11.01 samples of delay and a
/// 15-sample average (p of degree 29) whose boundary curve spans 10⁹ in β while the stable
/// region is 10⁷ tall. The region once came out as a few triangles inside the true one and
/// the verification grid, spread over the curve's extent, fell between them; the region's
/// own box is now checked too. The answer must contain the stable wall-free point or be an
/// honest refusal.
#[test]
fn region_far_smaller_than_its_curve_is_right_or_refused() {
    let delay = Delay {
        samples: 11,
        fraction: 0.01,
    };
    let fam = msd_family(
        (0.00765658591764391, 1.0, 4115.459237322136),
        1.0,
        delay,
        VelocityEstimator::Average { samples: 15 },
    );
    stable_wall_in_region_or_refused(&fam, WallPoint { a: 0.0, b: 0.0 });
}

/// Refusals of the region stay rare over the random loops of the property above (the same
/// strategy, a fixed seed): under 0.5 % of 400 (at most one). Regions far thinner than the
/// window (fast sampling with a low-pass velocity filter of a few hertz: 10⁶ times taller
/// than wide) are computed in a stretched plane, and regions the curve's arrangement cannot
/// resolve are built from exact slices; 18 of these 400 were refused before either.
#[test]
fn region_refusals_are_rare() {
    use proptest::strategy::ValueTree;
    use proptest::test_runner::{Config, TestRng, TestRunner};
    let rng = TestRng::from_seed(proptest::test_runner::RngAlgorithm::ChaCha, &[7; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let n = 400;
    let refused = (0..n)
        .filter(|_| {
            let lp = a_loop().new_tree(&mut runner).unwrap().current();
            let e = stable_region(&AffineFamily::of_loop(&lp).unwrap()).err();
            if let Some(e) = &e {
                eprintln!("{lp:?}: {e}");
            }
            e.is_some()
        })
        .count();
    eprintln!("{refused} of {n} regions refused");
    assert!(refused * 200 < n, "{refused} of {n} regions refused");
}

/// The paper's loop over the explorer's ranges (γ ≤ 1000, δ ≤ 100): every region resolves
/// and agrees with the point test on a grid over its box, to its chord tolerance. Found
/// refused in 25 of these 270 settings: grid points on the diagonal of the window ran along
/// a z = −1 line, a face was classified by a point just inside a chord (beyond the curve it
/// approximates), rounding-wide gaps between stable intervals counted as gaps, and several
/// branches crossing within 1e-4 of the window (δ = 10, where the plant's poles are all but
/// gone) were left coarser than their crossings.
#[test]
fn paper_regions_resolve_over_the_explorer_ranges() {
    for g in [0.01, 1.0, 10.0, 50.0, 100.0, 200.0, 400.0, 700.0, 1000.0] {
        for dl in [0.0, 0.1, 1.0, 2.4, 10.0] {
            for d in [0usize, 1, 2, 3, 5, 8] {
                let lp = Loop::normalized(PlantParams::new(g, dl).unwrap(), d).unwrap();
                let fam = AffineFamily::of_loop(&lp).unwrap();
                let r = stable_region(&fam)
                    .unwrap_or_else(|e| panic!("γ = {g}, δ = {dl}, d = {d}: {e}"));
                let a = (-g - 1.0, r.a_max + 1.0);
                let b = (-3.0 * g - 10.0, 3.0 * g + 10.0);
                region_agrees_on_a_grid(&fam, &r, a, b, 12);
            }
        }
    }
}

/// Found by a long random run: sampled at 1.2 µs with a 1 Hz low-pass velocity filter, the
/// stable region is 1.8 wide and 10⁶ tall in (α, β); it was answered as empty while the
/// stiffness axis has stable walls. It must now be a region that holds them, or a refusal.
#[test]
fn thin_region_is_not_called_empty() {
    let fam = msd_family(
        (0.0024941309540034142, 38.07596165071776, 0.0),
        1.222811141433756e-6,
        Delay::samples(5).unwrap(),
        VelocityEstimator::LowPass { cutoff_hz: 1.0 },
    );
    let w = WallPoint {
        a: 0.0027542652682587252,
        b: 0.0,
    };
    stable_wall_in_region_or_refused(&fam, w);
}

/// Found by a long random run: sampled at 0.76 s with 5.1 samples of delay and an
/// 18-sample average (γ = 2024, δ = 22), the region came out as a piece 2000 away from the
/// stable wall-free point. The verification now tests that point too.
#[test]
fn region_holds_the_stable_wall_free_point() {
    let delay = Delay {
        samples: 5,
        fraction: 0.09765039015745926,
    };
    let fam = msd_family(
        (0.0454953215252378, 1.339569676351949, 158.69861020164703),
        0.7618021233319427,
        delay,
        VelocityEstimator::Average { samples: 18 },
    );
    stable_wall_in_region_or_refused(&fam, WallPoint { a: 0.0, b: 0.0 });
}

/// Undamped plants whose poles sit at e^{±iπ/4}…e^{±iπ/2} (γ = π²/16, π²/4): the boundary
/// curve passes through the same wall at two angles that are knots of the coarse sampling.
/// A change of the circle's evaluation by one rounding unit once split that point into a
/// sliver and broke the arrangement (the paper's Nyquist figures use these loops). Each
/// region resolves and agrees with the point test on a grid.
#[test]
fn undamped_regions_whose_curve_touches_itself_at_a_knot() {
    let pi2 = std::f64::consts::PI * std::f64::consts::PI;
    for g in [pi2 / 16.0, pi2 / 4.0] {
        for d in 0..4 {
            let fam = AffineFamily::of_loop(
                &Loop::normalized(PlantParams::new(g, 0.0).unwrap(), d).unwrap(),
            )
            .unwrap();
            let r = stable_region(&fam).unwrap_or_else(|e| panic!("γ = {g}, d = {d}: {e}"));
            region_agrees_on_a_grid(&fam, &r, (-g, 2.0), (-g, 1.0), 20);
        }
    }
}
