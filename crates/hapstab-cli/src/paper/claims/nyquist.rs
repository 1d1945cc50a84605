//! Claims C7–C9 (Section VIII): the regions up to the Nyquist frequency, the robust and
//! passive regions (Figs. 8–10).

use std::collections::BTreeMap;
use std::f64::consts::PI;

use anyhow::Result;
use hapstab::PlantParams;
use hapstab::paper::NormalizedFamily;
use hapstab::paper::nyquist::{passive_region, unit_circle_pole};
use hapstab::stability::{Verdict as Stab, roots};

use super::{Claim, Verdict};
use crate::output::sig;
use crate::paper::compute::{
    DELTA_NYQUIST, Key, Region, Results, RobustKey, passive_gamma_hi, sweep_gamma,
};

/// Area of the polygon over the area of the triangle spanned by its rightmost vertex and the
/// top and bottom of its leftmost edge (1 for a triangle with a vertical left edge).
pub fn triangle_ratio(reg: &Region) -> f64 {
    let pts: Vec<(f64, f64)> = reg.rings.iter().flatten().copied().collect();
    if pts.len() < 3 {
        return f64::NAN;
    }
    let scale = (reg.alpha_max - reg.alpha_min).abs().max(1e-300);
    let right = pts
        .iter()
        .copied()
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .unwrap_or((0.0, 0.0));
    let left: Vec<(f64, f64)> = pts
        .iter()
        .copied()
        .filter(|p| p.0 <= reg.alpha_min + 1e-6 * scale)
        .collect();
    let top = left
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.0, 0.0));
    let bottom = left
        .iter()
        .copied()
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap_or((0.0, 0.0));
    let tri = 0.5
        * ((top.0 - bottom.0) * (right.1 - bottom.1) - (right.0 - bottom.0) * (top.1 - bottom.1))
            .abs();
    reg.area / tri
}

pub(super) fn c7(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let half = r.region(Key::new(sweep_gamma((1, 2), 0.0), 0.0, 0))?;
    let nyq = r.region(Key::new(sweep_gamma((1, 1), 0.0), 0.0, 0))?;
    let tri = triangle_ratio(nyq);
    let rob = r.robust(RobustKey {
        delta: 0.0,
        d: 0,
        full: true,
    })?;
    // The origin is limit stable for every γ (p(z) = z(z² − a1 z + 1) at α = β = 0 for δ = 0).
    let origin_marginal = [1e-3, 0.5, 2.0, 5.0, 9.0].iter().all(|&g| {
        NormalizedFamily::new(
            PlantParams {
                gamma: g,
                delta: 0.0,
            },
            0,
        )
        .map(|f| {
            hapstab::decide(&f, 0.0, 0.0, &mut f.coefficients(0.0, 0.0)).verdict == Stab::Marginal
        })
        .unwrap_or(false)
    });
    values.insert("alpha_max_half_nyquist", half.alpha_max);
    values.insert("triangle_area_ratio_nyquist", tri);
    values.insert("beta_at_alpha_max_nyquist", nyq.beta_at_alpha_max);
    values.insert("robust_area", rob.area);
    values.insert("robust_empty", rob.empty as u8 as f64);
    let ok = half.alpha_max <= 1e-9 && (tri - 1.0).abs() < 0.01 && rob.empty && origin_marginal;
    Ok(Claim {
        id: "C7",
        claim: "at half the Nyquist frequency (γ = π²/4, δ = 0, d = 0) the stable region lies in α ≤ 0; near γ = π² it is a triangle; the robust region is the origin (Fig. 8)",
        figure: "Fig. 8 (δ = 0, d = 0)",
        measured: format!(
            "α_max at γ = π²/4: {}; at γ → π² the region's area is {} of the triangle through its three corners (α_max = {} at β = {} < 0); robust region over 0 ≤ γ ≤ π²: {}; the origin is limit stable (root on |z| = 1) for every γ tested",
            sig(half.alpha_max, 3),
            sig(tri, 7),
            sig(nyq.alpha_max, 5),
            sig(nyq.beta_at_alpha_max, 5),
            if rob.empty {
                "no interior point".to_string()
            } else {
                format!("area {}", sig(rob.area, 3))
            }
        ),
        values,
        verdict: Verdict::from(ok),
        note: "reproduced when α_max ≤ 1e-9 at γ = π²/4, the area at γ = π²(1 − 1e-6) is within 1 % of the triangle through its corners, and the robust region has no interior point"
            .to_string(),
    })
}

pub(super) fn c8(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let p = r
        .passive
        .ok_or_else(|| anyhow::anyhow!("passive check was not computed"))?;
    let pr = passive_region(DELTA_NYQUIST)?;
    let rob = r.robust(RobustKey {
        delta: DELTA_NYQUIST,
        d: 0,
        full: true,
    })?;
    values.insert("inside", p.inside as u8 as f64);
    values.insert("min_right_margin", p.min_right_margin);
    values.insert("min_left_margin", p.min_left_margin);
    values.insert("passive_area", pr.area());
    values.insert("robust_area", rob.area);
    Ok(Claim {
        id: "C8",
        claim: "with δ = 1 the robust region contains Colgate's passive region (Fig. 9)",
        figure: "Fig. 9 (δ = 1, d = 0, 0 ≤ γ ≤ π² + 1/4)",
        measured: format!(
            "passive triangle (28) {} the robust region over 0 ≤ γ ≤ {}: smallest margin {} in α (at β = {}), {} checked slices; areas: passive {}, robust {}",
            if p.inside { "inside" } else { "NOT inside" },
            sig(passive_gamma_hi(), 6),
            sig(p.min_right_margin, 3),
            sig(p.beta_at_min_right_margin, 4),
            p.samples,
            sig(pr.area(), 4),
            sig(rob.area, 4)
        ),
        values,
        verdict: Verdict::from(p.inside),
        note: "reproduced when every checked β-slice of the passive triangle lies in the robust α-interval (γ refined between samples)".into(),
    })
}

pub(super) fn c9(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let q = r.region(Key::new(sweep_gamma((1, 4), 0.0), 0.0, 1))?;
    let q0 = r.region(Key::new(sweep_gamma((1, 4), 0.0), 0.0, 0))?;
    let g = PI * PI;
    let mut worst: f64 = 0.0;
    for d in [0usize, 1, 2, 5] {
        let fam = NormalizedFamily::new(
            PlantParams {
                gamma: g,
                delta: 0.0,
            },
            d,
        )?;
        for (a, b) in [(0.1, 0.3), (-0.5, 0.2), (1.0, -0.2)] {
            let rs = roots(&fam.coefficients(a, b))?;
            let m = rs
                .iter()
                .map(|z| (z + 1.0).norm())
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(m);
        }
    }
    let flagged = unit_circle_pole(PlantParams {
        gamma: g,
        delta: 0.0,
    }) == Some(PI);
    values.insert("alpha_max_d1_quarter", q.alpha_max);
    values.insert("alpha_max_d0_quarter", q0.alpha_max);
    values.insert("max_distance_root_to_minus_one", worst);
    let ok = q.alpha_max <= 1e-9 && worst < 1e-6 && flagged;
    Ok(Claim {
        id: "C9",
        claim: "with d = 1, δ = 0 the region lies in α ≤ 0 already at γ = (π/4)², and at γ = π², δ = 0 a pole sits at z = −1 for any d (Fig. 10)",
        figure: "Fig. 10 (d = 1); roots of p(z) at γ = π²",
        measured: format!(
            "α_max at γ = (π/4)²: {} for d = 1 (for comparison {} for d = 0); at γ = π², δ = 0 the root nearest z = −1 is {} away (d = 0, 1, 2, 5; three (α, β) each)",
            sig(q.alpha_max, 3),
            sig(q0.alpha_max, 4),
            sig(worst, 2)
        ),
        values,
        verdict: Verdict::from(ok),
        note: "reproduced when α_max ≤ 1e-9 and every root set contains z = −1 to 1e-6".into(),
    })
}
