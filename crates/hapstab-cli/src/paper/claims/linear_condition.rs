//! Claims C5–C6 (Sections VI–VII): the linear condition (22)/(23) and its error (24)
//! (Fig. 7).

use std::collections::BTreeMap;

use anyhow::Result;
use hapstab::paper::linear::{error_curve, linear_check, routh_hurwitz_normalized};
use hapstab::{Normalized, PlantParams};

use super::{Claim, Verdict, pct};
use crate::output::sig;
use crate::paper::compute::{FIG7_DELTAS, GAMMA_ARM, Key, Results};

/// (number of grid points satisfying (19) and (22), number of those violating (18)).
pub fn eq18_grid() -> Result<(usize, usize)> {
    let lin = hapstab::grid::evenly_spaced;
    let (mut sat, mut viol) = (0, 0);
    for &gamma in &[0.0, 1e-3, 0.05, 2.0] {
        for &delta in &[0.0, 0.015, 0.2, 1.0] {
            for d in 0..=2 {
                for &alpha in &lin(-2.5, 1.0, 36) {
                    for &beta in &lin(-1.5, 1.0, 26) {
                        let n = Normalized::new(alpha, beta, gamma, delta, d)?;
                        if linear_check(&n).satisfied {
                            sat += 1;
                            if !routh_hurwitz_normalized(&n).eq18.holds {
                                viol += 1;
                            }
                        }
                    }
                }
            }
        }
    }
    Ok((sat, viol))
}

pub(super) fn c5() -> Result<Claim> {
    let mut values = BTreeMap::new();
    let betas = [1e-6, 1e-4, 1e-3];
    let mut worst: f64 = 0.0;
    let mut worst_diff: f64 = 0.0;
    for d in 0..=1 {
        for delta in FIG7_DELTAS {
            let e1 = error_curve(PlantParams::new(GAMMA_ARM, delta)?, d, &betas)?;
            let e0 = error_curve(PlantParams::new(0.0, delta)?, d, &betas)?;
            for (a, b) in e1.iter().zip(&e0) {
                let (Some(x), Some(y)) = (a.error, b.error) else {
                    worst = f64::INFINITY;
                    continue;
                };
                worst = worst.max(x);
                worst_diff = worst_diff.max((x - y).abs());
            }
        }
    }
    let (sat, viol) = eq18_grid()?;
    values.insert("max_error_small_beta_gamma_0.001", worst);
    values.insert("max_error_difference_gamma", worst_diff);
    values.insert("grid_points_satisfying_19_22", sat as f64);
    values.insert("grid_points_violating_18", viol as f64);
    let ok = worst < 0.01 && viol == 0 && sat > 0;
    Ok(Claim {
        id: "C5",
        claim: "the linear condition (22)/(23) holds with arm stiffness; (18) is implied by (19) and (22)",
        figure: "eq. (18)–(24), Fig. 7: error (24) near β = 0 for γ = 0.001; (18) on a grid",
        measured: format!(
            "error (24) at β = 1e-6, 1e-4, 1e-3 with γ = 0.001 (δ ∈ {{0, 0.005, 0.01, 0.015}}, d = 0, 1): at most {} (differs from γ = 0 by at most {}); (18) fails at {viol} of {sat} grid points (α, β, γ, δ, d) that satisfy (19) and (23)",
            pct(worst),
            sig(worst_diff, 2)
        ),
        values,
        verdict: Verdict::from(ok),
        note: "reproduced when the error (24) of the linear condition stays below 1 % close to the origin with γ = 0.001 and no grid point satisfying (19) and (22)/(23) violates (18)".into(),
    })
}

pub(super) fn c6(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let mut worst = [0.0f64; 2];
    for (d, w) in worst.iter_mut().enumerate() {
        for delta in FIG7_DELTAS {
            let v0 = r.validity(Key::new(0.0, delta, d))?;
            let v1 = r.validity(Key::new(GAMMA_ARM, delta, d))?;
            for (a, b) in v0.iter().zip(v1) {
                *w = w.max((b.alpha - a.alpha).abs() / a.alpha);
            }
        }
    }
    let w = worst[0].max(worst[1]);
    values.insert("max_relative_difference_d0", worst[0]);
    values.insert("max_relative_difference_d1", worst[1]);
    values.insert("max_relative_difference", w);
    Ok(Claim {
        id: "C6",
        claim: "the α values where the linear condition's error reaches 2 % and 5 % differ by less than 0.2 % between γ = 0 and γ = 0.001 (Fig. 7)",
        figure: "Fig. 7: 2 % circles and 5 % squares, δ ∈ {0, 0.005, 0.01, 0.015}, d = 0, 1",
        measured: format!(
            "largest |α(γ = 0.001) − α(γ = 0)|/α(γ = 0) over δ and both levels: {} for d = 0, {} for d = 1",
            pct(worst[0]),
            pct(worst[1])
        ),
        values,
        verdict: Verdict::from(w < 0.002),
        note: "reproduced when the largest relative difference is below 0.2 %; it grows with d as the paper says".into(),
    })
}
