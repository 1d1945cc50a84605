//! The linear condition of Section VI (`hapstab::paper::linear`, eq. 18–23): implied by the exact
//! boundary's conditions, Routh–Hurwitz of the normalized loop against the cubic's roots, the
//! validity points of Fig. 7, a loop's condition as its normalized view, fractional delays.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use crate::common::SplitMix;
use hapstab::model::{Delay, Loop, Plant, VelocityEstimator};
use hapstab::paper::NormalizedFamily;
use hapstab::paper::linear::{
    continuous_cubic_normalized, linear_alpha_limit, linear_condition, relative_error,
    routh_hurwitz, routh_hurwitz_normalized, validity_points,
};
use hapstab::params::{Effective, Physical, Sampling, Wall};
use hapstab::stability::{roots, schur_stable};
use hapstab::{AffineFamily, Error, Normalized, Param, PlantParams};

fn fam(gamma: f64, delta: f64, d: usize) -> NormalizedFamily {
    NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap()
}

fn stable(f: &NormalizedFamily, alpha: f64, beta: f64) -> bool {
    schur_stable(&f.coefficients(alpha, beta))
}

const FIG7_DELTAS: [f64; 4] = [0.0, 0.005, 0.01, 0.015];

fn family(lp: &Loop) -> AffineFamily {
    AffineFamily::of_loop(lp).unwrap()
}

/// Eq. (18) is implied by (19) and (22): over random physical plants and walls, every
/// sample that satisfies (19) and (22) satisfies (18). The sample is drawn wide enough that
/// (18) fails for some samples, and (22) is checked to be what (20) becomes without ε.
#[test]
fn eq18_implied_by_eq19_and_eq22() {
    let mut rng = SplitMix(7);
    let (mut both, mut fails18) = (0, 0);
    for _ in 0..200_000 {
        let m = rng.range(0.01, 5.0);
        let b = rng.range(0.0, 20.0);
        let k = rng.range(0.0, 2000.0);
        let t = rng.range(1e-4, 2e-3);
        let d = (rng.next_f64() * 4.0) as usize;
        let kw = rng.range(-3000.0, 3e4);
        let bw = rng.range(-40.0, 40.0);
        let p = Physical::new(
            Effective::new(m, b, k).unwrap(),
            Wall {
                stiffness: kw,
                damping: bw,
            },
            Sampling::new(t, d).unwrap(),
        )
        .unwrap();
        let rh = routh_hurwitz(&p);
        let tr = d as f64 * t + t / 2.0;
        let eq22 = kw < (b + bw) / tr;
        if !rh.eq18.holds {
            fails18 += 1;
        }
        if rh.eq19.holds && eq22 {
            both += 1;
            assert!(rh.eq18.holds, "(18) fails at {p:?}");
        }
    }
    assert!(both > 10_000 && fails18 > 10_000, "{both} {fails18}");
}

/// The normalized cubic (17) is Hurwitz exactly when (18)–(20) hold, and at ε → 0 (δ = 0,
/// γ = 0) the condition (20) is (23): α < β/(d + ½).
#[test]
fn routh_hurwitz_normalized_matches_cubic_roots() {
    let mut rng = SplitMix(11);
    for _ in 0..2000 {
        let n = Normalized::new(
            rng.range(-0.2, 1.0),
            rng.range(-0.5, 1.5),
            rng.range(0.0, 0.01),
            rng.range(0.0, 0.05),
            (rng.next_f64() * 3.0) as usize,
        )
        .unwrap();
        let c = continuous_cubic_normalized(&n);
        // Hurwitz via the roots of the cubic (companion matrix on s)
        let r = roots(&[c.a0, c.a1, c.a2, c.a3]).unwrap();
        let hurwitz = r.iter().all(|z| z.re < -1e-12);
        let rh = routh_hurwitz_normalized(&n);
        let margin = rh
            .eq18
            .margin
            .abs()
            .min(rh.eq19.margin.abs())
            .min(rh.eq20.margin.abs());
        if margin > 1e-9 {
            assert_eq!(hurwitz, rh.stable, "{n:?}");
        }
    }
    let n = Normalized::new(0.3, 0.2, 0.0, 0.0, 1).unwrap();
    let rh = routh_hurwitz_normalized(&n);
    // (20) with b = k = 0: m(B − K t_r) > 0
    assert!((rh.eq20.margin - (0.2 - 0.3 * 1.5)).abs() < 1e-15);
    assert_eq!(linear_alpha_limit(0.2, 0.0, 1), 0.2 / 1.5);
}

/// The 2 % and 5 % points of Fig. 7 for all 16 settings: each α is on the exact boundary
/// (stable just below, unstable just above by the Schur–Cohn test), β is located to 1e-9
/// relative (the error straddles the level within ±1e-9·β), and the level is not reached
/// earlier on a fine β grid. For γ = δ = d = 0 the points match the closed form of the
/// pure-mass boundary α = 2β(2 − β)/(2 + β): with α_lin = 2β the error is 2β/(2 − β), so
/// β = 2L/(2 + L). Finally the paper's claim: α differs by less than 0.2 % between γ = 0 and
/// γ = 0.001.
#[test]
fn fig7_validity_points() {
    use rayon::prelude::*;
    let levels = [0.02, 0.05];
    let settings: Vec<(usize, f64, f64)> = [0usize, 1]
        .iter()
        .flat_map(|&d| {
            FIG7_DELTAS
                .iter()
                .flat_map(move |&delta| [0.0, 0.001].map(|gamma| (d, delta, gamma)))
        })
        .collect();
    let table: Vec<_> = settings
        .par_iter()
        .map(|&(d, delta, gamma)| {
            let pts = validity_points(PlantParams::new(gamma, delta).unwrap(), d, &levels).unwrap();
            let f = fam(gamma, delta, d);
            for p in &pts {
                assert!(!p.at_start);
                assert!(stable(&f, p.alpha * (1.0 - 1e-9), p.beta), "{p:?}");
                assert!(!stable(&f, p.alpha * (1.0 + 1e-9), p.beta), "{p:?}");
                let below = relative_error(&f, p.beta * (1.0 - 1e-9)).unwrap();
                let above = relative_error(&f, p.beta * (1.0 + 1e-9)).unwrap();
                assert!(below < p.level && p.level < above, "{p:?} {below} {above}");
                for i in 1..100 {
                    let b = p.beta * i as f64 / 100.0;
                    assert!(relative_error(&f, b).unwrap() < p.level, "{p:?} at {b}");
                }
            }
            (d, delta, gamma, pts)
        })
        .collect();
    // closed form for γ = δ = d = 0
    let (_, _, _, pts) = &table[0];
    for p in pts {
        let beta = 2.0 * p.level / (2.0 + p.level);
        let alpha = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
        assert!(
            ((p.beta - beta) / beta).abs() < 1e-9,
            "{} vs {beta}",
            p.beta
        );
        assert!(
            ((p.alpha - alpha) / alpha).abs() < 1e-9,
            "{} vs {alpha}",
            p.alpha
        );
    }
    // γ = 0 versus γ = 0.001: "differ less than 0.2 %" (Section VII)
    for pair in table.chunks(2) {
        let (d, delta, _, a) = &pair[0];
        let (_, _, _, b) = &pair[1];
        for (p, q) in a.iter().zip(b) {
            let rel = ((p.alpha - q.alpha) / p.alpha).abs();
            assert!(rel < 2e-3, "d={d} δ={delta} level={}: {rel}", p.level);
        }
    }
}

/// The linear condition of a physical paper loop is its normalized view's: the validity
/// points of (γ, δ) of Table I, (23)'s slope 1/(d + 1/2) and intercept δ/(d + 1/2), (19)'s
/// −γ, and the wall's units m/T², m/T; a loop without the view is refused naming the loop.
#[test]
fn linear_condition_of_a_loop_is_its_normalized_view() {
    let (e, t, d) = (Effective::new(1.1, 7.5, 350.0).unwrap(), 1e-3, 2);
    let levels = [0.02, 0.1];
    let lc = linear_condition(&Loop::paper(e, t, d).unwrap(), &levels).unwrap();
    let pp = PlantParams::from_physical(&e, t).unwrap();
    assert_eq!((lc.gamma, lc.delta, lc.d), (pp.gamma, pp.delta, d));
    assert_eq!(lc.points, validity_points(pp, d, &levels).unwrap());
    assert_eq!((lc.slope, lc.intercept), (1.0 / 2.5, pp.delta / 2.5));
    assert_eq!(lc.alpha_lower, -pp.gamma);
    assert_eq!(
        (lc.units.stiffness, lc.units.damping),
        (1.1 / (t * t), 1.1 / t)
    );
    let lowpass = Loop::new(
        Plant::mass_spring_damper(e).unwrap(),
        t,
        Delay::samples(d).unwrap(),
        VelocityEstimator::LowPass { cutoff_hz: 100.0 },
    )
    .unwrap();
    match linear_condition(&lowpass, &levels) {
        Err(Error::Invalid {
            param: Param::Loop, ..
        }) => {}
        other => panic!("{other:?}"),
    }
}

/// With a fractional delay the linear condition of eq. (22) still holds in the limit:
/// K_max·(t_d + T/2)/(b + B) → 1 as (b + B)T/m → 0, for t_d ∈ {0.5, 1.3, 2.7}·T.
#[test]
fn fractional_delay_meets_the_linear_condition() {
    use hapstab::boundary::stable_stiffness_intervals;
    let (m, t) = (1.0, 1e-3);
    for td in [0.5, 1.3, 2.7] {
        let mut last_gap = f64::INFINITY;
        for damping in [1.0, 0.1, 0.01] {
            // (b + B)T/m = damping·1e-3 with b = 0 and B = damping
            let lp = Loop::new(
                Plant::mass_spring_damper(Effective::new(m, 0.0, 0.0).unwrap()).unwrap(),
                t,
                Delay::from_time(td * t, t).unwrap(),
                VelocityEstimator::Backward,
            )
            .unwrap();
            let fam = family(&lp);
            let (_, b) = fam.to_units(0.0, damping);
            let top = stable_stiffness_intervals(&fam, b)
                .iter()
                .map(|iv| iv.hi)
                .fold(f64::NEG_INFINITY, f64::max);
            let (k_max, _) = fam.to_physical(top, b);
            let ratio = k_max * (td * t + t / 2.0) / damping;
            let gap = (ratio - 1.0).abs();
            assert!(gap < last_gap, "t_d={td}T B={damping}: ratio {ratio}");
            last_gap = gap;
        }
        assert!(last_gap < 1e-2, "t_d={td}T: {last_gap}");
    }
}
