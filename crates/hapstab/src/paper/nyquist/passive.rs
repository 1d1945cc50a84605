//! Colgate's passive region of eq. (28) (Section VIII-A, Fig. 9) and the check that it lies
//! inside a robustly stable region.

use rayon::prelude::*;
use serde::Serialize;

use super::robust::gamma_samples;
use super::slice::{Config, refined_slice, unit_configs};
use super::{GammaRange, Progress, RobustOptions, Ticker, no_progress};
use crate::boundary::WallPoint;
use crate::error::{Result, non_negative, positive};
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;
use crate::param::Param;
use crate::params::check_delay;

/// Colgate's passive region, eq. (28): δ > α/2 + |β| with α ≥ 0 (d = 0), a triangle.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassiveRegion {
    /// Normalized physical damping δ.
    pub delta: f64,
    /// Vertices (0, −δ), (2δ, 0), (0, δ): counter-clockwise with α as abscissa, first vertex
    /// not repeated.
    pub vertices: Vec<WallPoint>,
}

impl PassiveRegion {
    /// True iff the point satisfies eq. (28): α ≥ 0 and δ > α/2 + |β|.
    pub fn contains(&self, p: WallPoint) -> bool {
        p.a >= 0.0 && self.delta > p.a / 2.0 + p.b.abs()
    }

    /// Area 2δ² of the triangle.
    pub fn area(&self) -> f64 {
        2.0 * self.delta * self.delta
    }

    /// The largest passive α at β: 2(δ − |β|) for |β| < δ, None otherwise.
    pub fn alpha_max_at(&self, beta: f64) -> Option<f64> {
        (beta.abs() < self.delta).then(|| 2.0 * (self.delta - beta.abs()))
    }
}

/// Colgate's passive region of eq. (28) as a polygon (Section VIII-A, Fig. 9).
pub fn passive_region(delta: f64) -> Result<PassiveRegion> {
    non_negative(Param::Delta, delta)?;
    let p = |alpha, beta| WallPoint { a: alpha, b: beta };
    Ok(PassiveRegion {
        delta,
        vertices: vec![p(0.0, -delta), p(2.0 * delta, 0.0), p(0.0, delta)],
    })
}

/// How Colgate's passive region (28) sits in a robust region.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct PassiveCheck {
    /// δ.
    pub delta: f64,
    /// Every checked slice of the closed passive triangle lies in the closure of the robust
    /// region (margins ≥ −1e-12).
    pub inside: bool,
    /// Smallest margin hi_robust − 2(δ − |β|) over the checked β.
    pub min_right_margin: f64,
    /// β of the smallest right margin.
    pub beta_at_min_right_margin: f64,
    /// Smallest margin 0 − lo_robust (0 when the robust region's left edge is α = 0, as for
    /// γ_lo = 0 where α = −γ = 0 is a boundary).
    pub min_left_margin: f64,
    /// Number of β checked.
    pub samples: usize,
}

/// Relative distance from the corners (0, ±δ) of the passive triangle at which
/// [`passive_inside_robust`] starts. At γ = 0 the corner (0, −δ) is limit stable (a double
/// root at z = 1 when α = 0 and β + δ = 0), and within 1e-6·δ of it the stable band, of
/// width about 2(β + δ), is thinner than what double precision resolves in the Schur–Cohn
/// test.
pub const PASSIVE_END_GAP: f64 = 1e-6;

/// Checks that the passive triangle of eq. (28) lies in the robust region over the range's
/// γ ∈ [γ_lo, γ_hi] at its δ and d: at `samples` values of β across (−δ, δ) (ends at
/// ±δ(1 − [`PASSIVE_END_GAP`])) the robust α-interval must contain [0, 2(δ − |β|)]
/// (Section VIII-A, Fig. 9).
pub fn passive_inside_robust(
    range: GammaRange,
    samples: usize,
    opts: RobustOptions,
) -> Result<PassiveCheck> {
    passive_inside_robust_with_progress(range, samples, opts, &no_progress)
}

/// [`passive_inside_robust`] reporting each checked β (`samples`, at least 3, in all) to
/// `progress`.
pub fn passive_inside_robust_with_progress(
    range: GammaRange,
    samples: usize,
    opts: RobustOptions,
    progress: Progress,
) -> Result<PassiveCheck> {
    let (delta, d) = (range.delta, range.d);
    let (gamma_lo, gamma_hi) = (range.gamma_lo, range.gamma_hi);
    positive(Param::Delta, delta)?;
    check_delay(d)?;
    let (gs, _) = gamma_samples(gamma_lo, gamma_hi, opts.gamma_samples, delta);
    let configs = unit_configs(&gs, delta, d)?;
    let ng = gs.len();
    let neighbours = |j: usize| {
        let a = if j > 0 { gs[j - 1] } else { gs[j] };
        let b = if j + 1 < ng { gs[j + 1] } else { gs[j] };
        (a, b)
    };
    let make = |_: usize, g: f64| Config {
        scale: 1.0,
        table: None,
        fam: NormalizedFamily::new(
            PlantParams {
                gamma: g.max(0.0),
                delta,
            },
            d,
        )
        .unwrap_or_else(|_| configs[0].fam.clone()),
    };
    let n = samples.max(3);
    let betas: Vec<f64> = (0..n)
        .map(|i| delta * (1.0 - PASSIVE_END_GAP) * (2.0 * i as f64 / (n - 1) as f64 - 1.0))
        .collect();
    let ticker = Ticker::new(progress);
    let margins: Vec<(f64, f64, f64)> = betas
        .par_iter()
        .map(|&b| {
            let need = 2.0 * (delta - b.abs());
            let m = match refined_slice(&configs, &gs, &neighbours, &make, b, opts.refine_gamma) {
                Some(s) => (b, s.interval.hi - need, -s.interval.lo),
                None => (b, f64::NEG_INFINITY, f64::NEG_INFINITY),
            };
            ticker.tick();
            m
        })
        .collect();
    let (mut mr, mut br, mut ml) = (f64::INFINITY, f64::NAN, f64::INFINITY);
    for (b, r, l) in margins {
        if r < mr {
            mr = r;
            br = b;
        }
        ml = ml.min(l);
    }
    Ok(PassiveCheck {
        delta,
        inside: mr >= -1e-12 && ml >= -1e-12,
        min_right_margin: mr,
        beta_at_min_right_margin: br,
        min_left_margin: ml,
        samples: n,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::paper::nyquist::polygon_area;

    #[test]
    fn passive_triangle() {
        let p = passive_region(1.0).unwrap();
        assert!((polygon_area(&p.vertices) - p.area()).abs() < 1e-15);
        assert!(p.contains(WallPoint { a: 0.5, b: 0.2 }));
        assert!(!p.contains(WallPoint { a: 1.7, b: 0.2 }));
        assert!(!p.contains(WallPoint { a: -0.1, b: 0.0 }));
    }
}
