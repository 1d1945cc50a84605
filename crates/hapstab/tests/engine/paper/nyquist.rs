//! Sections VII and VIII (`hapstab::paper::nyquist`): the Nyquist frequency's stiffness (Remark 4)
//! and regions, the pole at z = −1, the robust region and the passive region inside it, the γ
//! sweep of Fig. 8, and the robust K_max over the human operator's box.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use crate::common::SplitMix;
use hapstab::PlantParams;
use hapstab::boundary::stable_stiffness_intervals;
use hapstab::paper::NormalizedFamily;
use hapstab::paper::nyquist::{
    BoxOptions, GammaRange, PlantBox, RobustOptions, SweepInput, beta_bound, gamma_sweep,
    nyquist_gamma, nyquist_regions, nyquist_stiffness, passive_inside_robust, passive_region,
    region_summary, robust_kmax, robust_region,
};
use hapstab::stability::{Verdict, roots, schur_stable};
use hapstab::verdict::decide_coefficients;
use std::f64::consts::PI;

const PI2: f64 = PI * PI;

fn fam(gamma: f64, delta: f64, d: usize) -> NormalizedFamily {
    NormalizedFamily::new(PlantParams::new(gamma, delta).unwrap(), d).unwrap()
}

fn stable(f: &NormalizedFamily, alpha: f64, beta: f64) -> bool {
    schur_stable(&f.coefficients(alpha, beta))
}

/// The paper's plants γ ∈ [lo, hi] at δ and d.
fn range(delta: f64, d: usize, gamma_lo: f64, gamma_hi: f64) -> GammaRange {
    GammaRange {
        delta,
        d,
        gamma_lo,
        gamma_hi,
    }
}

/// Remark 4: k = π² m/T² + b²/(4m) ≈ 987.0 kN/m for m = 0.1 kg, T = 1 ms, b = 1.5 Ns/m.
#[test]
fn remark4_nyquist_stiffness() {
    let r = nyquist_stiffness(0.1, 1.5, 1e-3).unwrap();
    assert!((r.stiffness - (PI2 * 1e5 + 5.625)).abs() < 1e-6);
    assert_eq!(format!("{:.1}", r.stiffness / 1e3), "987.0");
    assert!((r.gamma - (PI2 + (1.5e-3 / 0.1f64).powi(2) / 4.0)).abs() < 1e-12);
    assert!((nyquist_gamma(1.0) - (PI2 + 0.25)).abs() < 1e-15);
}

/// δ = 0, d = 0, γ = π²/4 (half the Nyquist frequency): every stable point has α ≤ 0
/// (Fig. 8 left). Control: at 0.9·π²/4 some stable point still has α > 0.
#[test]
fn half_nyquist_region_in_left_half_plane_d0() {
    let s = region_summary(PlantParams::new(PI2 / 4.0, 0.0).unwrap(), 0, 401).unwrap();
    assert!(!s.empty && s.alpha_max <= 1e-12, "{s:?}");
    let f = fam(PI2 / 4.0, 0.0, 0);
    let bb = beta_bound(&f);
    for i in 0..=2000 {
        let b = -bb + 2.0 * bb * i as f64 / 2000.0;
        for iv in stable_stiffness_intervals(&f, b) {
            assert!(iv.hi <= 1e-12, "β={b}: {iv:?}");
        }
    }
    let c = region_summary(PlantParams::new(0.9 * PI2 / 4.0, 0.0).unwrap(), 0, 401).unwrap();
    assert!(c.alpha_max > 1e-3, "{c:?}");
}

/// δ = 0, d = 1, γ = (π/4)²: the region lies in α ≤ 0 (Fig. 10 top). Control at 0.9·γ.
#[test]
fn quarter_nyquist_region_in_left_half_plane_d1() {
    let g = (PI / 4.0).powi(2);
    let s = region_summary(PlantParams::new(g, 0.0).unwrap(), 1, 401).unwrap();
    assert!(!s.empty && s.alpha_max <= 1e-12, "{s:?}");
    let f = fam(g, 0.0, 1);
    let bb = beta_bound(&f);
    for i in 0..=2000 {
        let b = -bb + 2.0 * bb * i as f64 / 2000.0;
        for iv in stable_stiffness_intervals(&f, b) {
            assert!(iv.hi <= 1e-12, "β={b}: {iv:?}");
        }
    }
    let c = region_summary(PlantParams::new(0.9 * g, 0.0).unwrap(), 1, 401).unwrap();
    assert!(c.alpha_max > 1e-4, "{c:?}");
}

/// δ = 0, γ = π²: N(z) = (2/π²)(z + 1) and D(z) = (z + 1)², so p(z) = (z + 1)·q(z) for every
/// (α, β) and every d: a pole at z = −1, limit stable at best (Section VIII-B).
#[test]
fn pole_at_minus_one_at_nyquist() {
    let mut rng = SplitMix(3);
    for d in [0usize, 1, 2, 5] {
        let f = fam(PI2, 0.0, d);
        for _ in 0..50 {
            let (a, b) = (rng.range(-10.0, 10.0), rng.range(-5.0, 5.0));
            let c = f.coefficients(a, b);
            let r = roots(&c).unwrap();
            let near = r
                .iter()
                .map(|z| (z + 1.0).norm())
                .fold(f64::INFINITY, f64::min);
            assert!(near < 1e-9, "d={d} (α, β)=({a}, {b}): {r:?}");
            assert_ne!(decide_coefficients(&c).verdict, Verdict::Stable);
        }
    }
    let s = region_summary(PlantParams::new(PI2, 0.0).unwrap(), 0, 101).unwrap();
    assert!(s.degenerate && s.empty);
}

/// δ = 0, d = 0: as γ → π² the stable region tends to the triangle of the limit
/// p = (z + 1)(z² + (1 + c(α + β))z − cβ), c = 2/π²: −π² < α < −2β, β > −π²/2 (Fig. 8
/// right). At each β the interval is (−γ, hi) and hi → −2β; the deviation shrinks with
/// π² − γ.
#[test]
fn nyquist_triangle_limit_d0() {
    let mut prev = f64::INFINITY;
    for e in [1e-2, 1e-3, 1e-4, 1e-5] {
        let g = PI2 * (1.0 - e);
        let f = fam(g, 0.0, 0);
        let mut dev: f64 = 0.0;
        for i in 0..=100 {
            let b = 0.98 * PI2 / 2.0 * (2.0 * i as f64 / 100.0 - 1.0);
            let iv = stable_stiffness_intervals(&f, b);
            assert_eq!(iv.len(), 1, "γ={g} β={b}: {iv:?}");
            assert_eq!(iv[0].lo, -g);
            dev = dev.max((iv[0].hi + 2.0 * b).abs());
        }
        assert!(dev < prev, "e={e}: {dev} !< {prev}");
        prev = dev;
    }
    assert!(prev < 1e-3, "{prev}");
    // nothing beyond the triangle's β range
    let f = fam(PI2 * (1.0 - 1e-5), 0.0, 0);
    assert!(stable_stiffness_intervals(&f, -PI2 / 2.0 * 1.001).is_empty());
    assert!(stable_stiffness_intervals(&f, PI2 / 2.0 * 1.001).is_empty());
}

/// δ = 0, d = 0: the robustly stable region over γ ∈ [0, π²] is only the origin (Section
/// VIII-A): no slice of the intersection is non-empty, yet every region of the sweep comes
/// within 2·10⁻³ of the origin (the origin is in the closure of each).
#[test]
fn robust_region_only_origin_delta0() {
    let opts = RobustOptions {
        gamma_samples: 17,
        beta_samples: 81,
        ..Default::default()
    };
    let r = robust_region(range(0.0, 0, 0.0, PI2), opts).unwrap();
    assert!(r.empty, "{:?}", &r.slices[..r.slices.len().min(5)]);
    assert_eq!(r.degenerate_gammas, vec![PI2]);
    // Just below γ = π² (1 − 1e-4, not closer: at 1 − 1e-6 the walls near the origin keep a
    // root within 2.5e-12 of the circle, inside the marginal band, where every front end
    // reports them marginal).
    for i in 0..=16 {
        let g = PI2 * i as f64 / 16.0 * (1.0 - 1e-4);
        let f = fam(g, 0.0, 0);
        let near = [-1e-3, 1e-3].iter().any(|&b| {
            stable_stiffness_intervals(&f, b)
                .iter()
                .any(|iv| iv.lo < 1e-3 && iv.hi > -1e-3)
        });
        assert!(near, "γ={g}");
    }
}

/// δ = 1, d = 0: Colgate's passive triangle (28) lies inside the robust region over
/// γ ∈ [0, π² + 1/4] (Fig. 9). Controls: the passive vertex scaled by 1.3, (2.6, 0), is not
/// robustly stable, and at γ_N the region is the triangle of the closed form
/// p = (z + e^{−1/2})(z² + (e^{−1/2} + v(α + β))z − vβ), v = (1 + e^{−1/2})/(π² + 1/4):
/// α > −γ, α + 2β < γ tanh(1/4), β > −1/v.
#[test]
fn passive_inside_robust_delta1() {
    let opts = RobustOptions {
        gamma_samples: 33,
        ..Default::default()
    };
    let gn = PI2 + 0.25;
    let c = passive_inside_robust(range(1.0, 0, 0.0, gn), 41, opts).unwrap();
    assert!(c.inside && c.min_right_margin > 0.0, "{c:?}");
    let r = robust_region(
        range(1.0, 0, 0.0, gn),
        RobustOptions {
            gamma_samples: 33,
            beta_samples: 61,
            refine_beta_rounds: 1,
            ..Default::default()
        },
    )
    .unwrap();
    let p = passive_region(1.0).unwrap();
    assert!(r.area > p.area(), "{} vs {}", r.area, p.area());
    assert!(r.alpha_max > 2.0 && r.alpha_max < 2.6, "{}", r.alpha_max);
    let v = (1.0 + (-0.5f64).exp()) / gn;
    let f = fam(gn, 1.0, 0);
    for b in [-6.0, -3.0, -1.0, 0.0, 1.0, 3.0, 6.0] {
        let iv = stable_stiffness_intervals(&f, b);
        let hi = gn * 0.25f64.tanh() - 2.0 * b;
        assert_eq!(iv.len(), 1);
        assert!(
            (iv[0].lo + gn).abs() < 1e-12 && (iv[0].hi - hi).abs() < 1e-9,
            "{iv:?} {hi}"
        );
    }
    assert!(stable_stiffness_intervals(&f, -1.0 / v * 1.001).is_empty());
    assert!(!stable_stiffness_intervals(&f, -1.0 / v * 0.999).is_empty());
}

/// Stable regions along the γ sweep of Fig. 8: the area grows with γ and the lower α-bound
/// is −γ (Fig. 5).
#[test]
fn gamma_sweep_fig8() {
    let s = gamma_sweep(0.0, 0, 0.75, 3, 201).unwrap();
    assert_eq!(s.len(), 4);
    for w in s.windows(2) {
        assert!(w[1].area > w[0].area, "{:?}", w);
    }
    for r in &s {
        assert!((r.alpha_min + r.gamma).abs() < 1e-12, "{r:?}");
    }
    // pure mass: α_max = 12 − 8√2 at β = 2√2 − 2 (maximum of 2β(2 − β)/(2 + β))
    assert!((s[0].alpha_max - (12.0 - 8.0 * 2f64.sqrt())).abs() < 1e-9);
    assert!((s[0].beta_at_alpha_max - (2.0 * 2f64.sqrt() - 2.0)).abs() < 1e-5);
}

/// Section VIII as one analysis is the composition of its parts: the sweep, the robust
/// region and the passive region with its check equal the separate calls, and the progress
/// reaches the three stages' sum.
#[test]
fn nyquist_regions_compose_sweep_robust_and_passive() {
    let input = SweepInput {
        delta: 0.2,
        d: 1,
        gamma_fraction: 0.5,
        steps: 2,
        beta_samples: 24,
        gamma_samples: 3,
    };
    let most = std::sync::atomic::AtomicUsize::new(0);
    let progress = |n: usize| {
        most.fetch_max(n, std::sync::atomic::Ordering::Relaxed);
    };
    let r = nyquist_regions(input, &progress).unwrap();
    let sweep = gamma_sweep(0.2, 1, 0.5, 2, 24).unwrap();
    assert_eq!(r.sweep.len(), 3);
    for (row, s) in r.sweep.iter().zip(&sweep) {
        assert_eq!(
            (row.gamma, row.area, row.beta_min),
            (s.gamma, s.area, s.beta_min)
        );
    }
    let g_hi = nyquist_gamma(0.2) * 0.5;
    assert_eq!(r.gamma_nyquist, nyquist_gamma(0.2));
    let robust = robust_region(range(0.2, 1, 0.0, g_hi), input.robust_options()).unwrap();
    assert_eq!(
        (r.robust.alpha_max, r.robust.area),
        (robust.alpha_max, robust.area)
    );
    assert_eq!(r.robust.polygon.len(), robust.polygon.len());
    let passive = r.passive.as_ref().unwrap();
    assert_eq!(passive.area, passive_region(0.2).unwrap().area());
    assert!(
        !passive.applies,
        "eq. (28) is Colgate's condition for d = 0 only"
    );
    assert_eq!(
        most.load(std::sync::atomic::Ordering::Relaxed),
        input.stages().iter().sum::<usize>()
    );
}

/// Robust K_max over the box (15), d = 0: it equals α_max of the worst corner (γ = 10⁻³,
/// δ = 0), and (α_max(1 − 10⁻⁶), β*) is stable on a dense 21 × 21 grid of the box while
/// α_max(1 + 10⁻⁶) is not.
#[test]
fn robust_kmax_human_box() {
    let pb = PlantBox::normalized([0.0, 1e-3], [0.0, 0.015], 0).unwrap();
    let opts = BoxOptions {
        stiffness_samples: 9,
        beta_samples: 49,
        ..Default::default()
    };
    let r = robust_kmax(&pb, opts).unwrap();
    let corner = region_summary(PlantParams::new(1e-3, 0.0).unwrap(), 0, 401).unwrap();
    assert!(
        ((r.stiffness_max - corner.alpha_max) / corner.alpha_max).abs() < 1e-8,
        "{r:?} vs {corner:?}"
    );
    let (a, b) = (r.stiffness_max, r.damping_at_max);
    let mut all = true;
    let mut any_unstable_above = false;
    for gi in 0..=20 {
        for di in 0..=20 {
            let f = fam(1e-3 * gi as f64 / 20.0, 0.015 * di as f64 / 20.0, 0);
            all &= stable(&f, a * (1.0 - 1e-6), b);
            any_unstable_above |= !stable(&f, a * (1.0 + 1e-6), b);
        }
    }
    assert!(all && any_unstable_above);
}

/// Corners are not enough: for δ = 0.5, d = 1, γ ∈ [0, 2.5] the stable interval's upper end
/// at fixed β is smallest at an interior γ. The box search (fine γ samples + refinement)
/// matches a dense γ grid, and is well below what the two corners alone give.
#[test]
fn robust_kmax_interior_worst_gamma() {
    let pb = PlantBox::normalized([0.0, 2.5], [0.5, 0.5], 1).unwrap();
    let opts = BoxOptions {
        stiffness_samples: 17,
        beta_samples: 41,
        ..Default::default()
    };
    let r = robust_kmax(&pb, opts).unwrap();
    assert!(r.worst_plant[2] > 0.05 && r.worst_plant[2] < 2.45, "{r:?}");
    // dense γ grid at the optimum β
    let dense = (0..=400)
        .map(|i| {
            let f = fam(2.5 * i as f64 / 400.0, 0.5, 1);
            stable_stiffness_intervals(&f, r.damping_at_max)
                .iter()
                .map(|iv| iv.hi)
                .fold(f64::NEG_INFINITY, f64::max)
        })
        .fold(f64::INFINITY, f64::min);
    assert!(
        r.stiffness_max <= dense + 1e-12,
        "{} vs {dense}",
        r.stiffness_max
    );
    assert!(
        dense - r.stiffness_max < 1e-4 * dense,
        "{} vs {dense}",
        r.stiffness_max
    );
    // the corners alone: max over β of min(hi(γ = 0), hi(γ = 2.5)) is larger
    let corners = (0..=200)
        .map(|i| {
            let b = 1.2 * i as f64 / 200.0;
            [0.0, 2.5]
                .iter()
                .map(|&g| {
                    stable_stiffness_intervals(&fam(g, 0.5, 1), b)
                        .iter()
                        .map(|iv| iv.hi)
                        .fold(f64::NEG_INFINITY, f64::max)
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(f64::NEG_INFINITY, f64::max);
    assert!(
        corners > r.stiffness_max * 1.01,
        "{corners} vs {}",
        r.stiffness_max
    );
}
