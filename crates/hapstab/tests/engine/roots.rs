//! The roots of p(z): the Aberth–Ehrlich finder against the companion matrix, closed forms
//! at the extremes, and the verdict of an `Analysis` against its own spectral radius.

use crate::common::discrete_plant::DiscretePlant;
use hapstab::paper::NormalizedFamily;
use hapstab::stability::{
    Analysis, MARGINAL_BAND, Verdict, roots, roots_companion, verdict_of_radius,
};
use hapstab::verdict::decide_coefficients;
use hapstab::{Normalized, PlantParams};
use num_complex::Complex64;
use std::time::Instant;

/// SplitMix64: a seeded generator, so the "random" points are the same on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn log_range(&mut self, lo_exp: f64, hi_exp: f64) -> f64 {
        10f64.powf(self.range(lo_exp, hi_exp))
    }
}

/// A random closed loop at delay d around the paper's region: γ, δ log-uniform over the
/// documented ranges, α and β scaled to the delay like the region's extent.
fn random_poly(rng: &mut Rng, d: usize) -> Vec<f64> {
    let pp = PlantParams::new(rng.log_range(-8.0, 0.0), rng.log_range(-8.0, 0.0)).unwrap();
    let t = d as f64 + 0.5;
    let alpha = rng.range(-0.5, 2.0) / t;
    let beta = rng.range(-0.5, 2.0) / t.sqrt();
    NormalizedFamily::new(pp, d)
        .unwrap()
        .coefficients(alpha, beta)
}

/// Matches every root of `a` to its nearest root of `b` and checks that this is an
/// assignment (a bijection): returns the largest matched distance.
fn assignment_distance(a: &[Complex64], b: &[Complex64]) -> f64 {
    assert_eq!(a.len(), b.len());
    let mut used = vec![false; b.len()];
    let mut worst: f64 = 0.0;
    for z in a {
        let (j, dist) = b
            .iter()
            .map(|w| (z - w).norm())
            .enumerate()
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap();
        assert!(!used[j], "two roots matched to {}: not an assignment", b[j]);
        used[j] = true;
        worst = worst.max(dist);
    }
    worst
}

/// Smallest distance between two roots, to make sure the matching is unambiguous.
fn separation(r: &[Complex64]) -> f64 {
    let mut s = f64::INFINITY;
    for (i, a) in r.iter().enumerate() {
        for b in &r[i + 1..] {
            s = s.min((a - b).norm());
        }
    }
    s
}

#[test]
fn aberth_matches_companion_matrix_at_d200() {
    let mut rng = Rng(200);
    for point in 0..6 {
        let c = random_poly(&mut rng, 200);
        let fast = roots(&c).unwrap();
        let slow = roots_companion(&c).unwrap();
        assert_eq!(fast.len(), 203);
        assert!(separation(&slow) > 1e-6, "point {point}: clustered roots");
        let dist = assignment_distance(&fast, &slow);
        assert!(dist < 1e-9, "point {point}: roots differ by {dist:e}");
    }
}

#[test]
fn aberth_matches_companion_matrix_at_low_delay() {
    let mut rng = Rng(3);
    for d in [0usize, 1, 2, 5, 10, 30] {
        for _ in 0..20 {
            let c = random_poly(&mut rng, d);
            let slow = roots_companion(&c).unwrap();
            if separation(&slow) < 1e-6 {
                continue;
            }
            let dist = assignment_distance(&roots(&c).unwrap(), &slow);
            assert!(dist < 1e-12, "d = {d}: roots differ by {dist:e}");
        }
    }
}

/// d = 2000: all 2003 roots in a fraction of a second, their sum equal to a1 (Vieta: the
/// sum of the roots of the monic p is −c[n−1] = a1) and the Schur–Cohn verdict agreeing.
#[test]
fn largest_delay_roots_are_fast_and_consistent() {
    let n = Normalized::new(0.009, 0.009, 3.2e-4, 6.8e-3, 2000).unwrap();
    let fam = NormalizedFamily::new(n.plant(), n.d).unwrap();
    let c = fam.coefficients(n.alpha, n.beta);
    let t = Instant::now();
    let an = Analysis::of_poly(&c).unwrap();
    let secs = t.elapsed().as_secs_f64();
    // The companion-matrix path took 88 s here; the bound only catches a return to O(n³).
    assert!(secs < 3.0, "{secs} s");
    assert_eq!(an.roots.len(), 2003);
    let sum: Complex64 = an.roots.iter().sum();
    assert!(
        (sum.re - DiscretePlant::from_params(n.plant()).a1).abs() < 1e-9 && sum.im.abs() < 1e-9,
        "{sum}"
    );
    assert_eq!(an.verdict, decide_coefficients(&c).verdict);
    assert_eq!(an.verdict, verdict_of_radius(an.spectral_radius));
}

/// γ = 1e10, δ = 1e4: the plant poles e^{−δ/2 ± i√(γ − δ²/4)} have modulus e^{−5000}, zero in
/// double precision, so at α = β = 0 (p = z D(z)) every root is 0 and the loop is stable.
/// The companion-matrix eigenvalues did not converge here.
#[test]
fn stiff_plant_has_its_roots_at_zero() {
    let an = Analysis::new(Normalized::new(0.0, 0.0, 1e10, 1e4, 0).unwrap()).unwrap();
    assert_eq!(an.verdict, Verdict::Stable);
    assert_eq!(an.spectral_radius, 0.0);
    assert_eq!(an.roots.len(), 3);
}

/// Over seeded points at every scale (d log-uniform up to 2000, γ and δ from 1e-12 to 1e3,
/// some zero), the verdict never contradicts the spectral radius reported with it: a
/// decided verdict is the radius's own and the Schur–Cohn test's; a marginal one has the
/// radius within its error of the marginal band.
#[test]
fn verdict_never_contradicts_the_spectral_radius() {
    let mut rng = Rng(12);
    for _ in 0..300 {
        let d = (rng.log_range(0.0, 3.3) as usize).clamp(1, 2001) - 1;
        let scale = |rng: &mut Rng| {
            if rng.next() < 0.1 {
                0.0
            } else {
                rng.log_range(-12.0, 3.0)
            }
        };
        let (g, de) = (scale(&mut rng), scale(&mut rng));
        let t = d as f64 + 0.5;
        let (a, b) = (rng.range(-0.5, 2.0) / t, rng.range(-0.5, 2.0) / t.sqrt());
        let an = Analysis::new(Normalized::new(a, b, g, de, d).unwrap()).unwrap();
        let (rho, err) = (an.spectral_radius, an.spectral_radius_error);
        let at = format!("(α, β, γ, δ, d) = ({a}, {b}, {g}, {de}, {d}): ρ = {rho} ± {err}");
        if an.verdict == Verdict::Marginal {
            assert!((rho - 1.0).abs() <= MARGINAL_BAND + err, "{at}");
        } else {
            assert_eq!(an.verdict, verdict_of_radius(rho), "{at}");
            assert_eq!(
                an.verdict,
                decide_coefficients(&an_poly(a, b, g, de, d)).verdict,
                "{at}"
            );
        }
    }
}

fn an_poly(a: f64, b: f64, g: f64, de: f64, d: usize) -> Vec<f64> {
    NormalizedFamily::new(PlantParams::new(g, de).unwrap(), d)
        .unwrap()
        .coefficients(a, b)
}
