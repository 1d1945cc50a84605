//! The parameters' uncertainty carried to a positive quantity q(θ) of the identified loop
//! (K_max at B = 0, K_max over the renderable band) by the **delta method** (Casella &
//! Berger, *Statistical Inference*, 2nd ed., 2002, Theorem 5.5.24; JCGM 100:2008 *GUM*,
//! §5.1.2, eq. 10): with x̂ the optimiser's coordinates at the optimum and Σ their
//! covariance ([`super::uncertainty::covariance`]),
//!
//! ```text
//! var(ln q̂) ≈ gᵀ Σ g,   g_j = ∂ ln q / ∂x_j,
//! 95 % interval  q̂ · exp(±z·√(gᵀΣg)),  z = 1.96,   standard error q̂·√(gᵀΣg).
//! ```
//!
//! ln q rather than q: K_max grows in proportion to the damping (Section V), and the
//! positive parameters are fitted as logarithms, so ln K_max is close to linear in the
//! coordinates and its interval stays positive. Each g_j is a central difference of the
//! exact q over ±σ_j, the coordinate's own standard error: the slope over the range the
//! data leave open, not a derivative at a point (K_max over a band is the maximum of a
//! search whose last digits do not differentiate), so the interval is the linearisation of
//! q over the scale of its uncertainty.

use serde::Serialize;

use super::Identification;
use super::uncertainty::Z_95;
use crate::model::{Loop, VelocityEstimator};

/// A positive quantity of the identified loop with its delta-method uncertainty.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Propagated {
    /// q at the estimates.
    pub value: f64,
    /// Its standard error q̂·√(gᵀΣg) (module doc).
    pub standard_error: f64,
    /// Its 95 % interval q̂·exp(±1.96·√(gᵀΣg)).
    pub ci95: [f64; 2],
}

/// The loop at the optimiser's coordinates x̂ + dx (dx over the free parameters; the held
/// ones and the offsets as fitted); None when no loop accepts them.
pub(crate) fn loop_at(
    id: &Identification,
    velocity: &VelocityEstimator,
    dx: &[f64],
) -> Option<Loop> {
    let mut v: Vec<f64> = id.parameters.iter().map(|e| e.value).collect();
    for (k, &j) in id.spec.free().iter().enumerate() {
        v[j] = id.optimum.coords[k].value(id.optimum.x[k] + dx[k]);
    }
    id.spec.to_loop(&v, id.period, velocity.clone()).ok()
}

/// q(θ̂) with its delta-method standard error and 95 % interval (module doc); None when q
/// is not positive at the estimates or at a ±σ_j neighbour, or the covariance is missing.
pub fn delta_method(
    id: &Identification,
    velocity: &VelocityEstimator,
    q: impl Fn(&Loop) -> Option<f64>,
) -> Option<Propagated> {
    let p = id.spec.free().len();
    if id.covariance.len() < p {
        return None;
    }
    let positive = |dx: &[f64]| {
        let v = q(&loop_at(id, velocity, dx)?)?;
        (v > 0.0 && v.is_finite()).then_some(v)
    };
    let value = positive(&vec![0.0; p])?;
    let mut g = vec![0.0; p];
    for (j, gj) in g.iter_mut().enumerate() {
        let s = id.covariance[j][j].max(0.0).sqrt();
        if s == 0.0 {
            continue;
        }
        let mut dx = vec![0.0; p];
        dx[j] = s;
        let up = positive(&dx)?;
        dx[j] = -s;
        let down = positive(&dx)?;
        *gj = (up.ln() - down.ln()) / (2.0 * s);
    }
    let var: f64 = (0..p)
        .flat_map(|a| (0..p).map(move |b| (a, b)))
        .map(|(a, b)| g[a] * id.covariance[a][b] * g[b])
        .sum();
    let se = var.max(0.0).sqrt();
    Some(Propagated {
        value,
        standard_error: value * se,
        ci95: [value * (-Z_95 * se).exp(), value * (Z_95 * se).exp()],
    })
}
