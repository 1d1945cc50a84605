//! The paper's claims C1–C11, each measured through the library and judged.

use std::collections::BTreeMap;
use std::f64::consts::PI;

use anyhow::Result;
use hapstab::linear::{error_curve, linear_check, routh_hurwitz_normalized};
use hapstab::nyquist::{nyquist_stiffness, passive_region, unit_circle_pole};
use hapstab::params::{Arm, Device};
use hapstab::plant::{DiscretePlant, eq10_coefficients};
use hapstab::stability::{Verdict as Stab, roots};
use hapstab::{Normalized, PlantParams, PolyFamily};
use serde::Serialize;

use super::compute::{
    DELTA_ARM, DELTA_NYQUIST, FIG7_DELTAS, GAMMA_ARM, Key, Region, Results, RobustKey, Source,
    passive_gamma_hi, sweep_gamma,
};
use crate::output::sig;

/// Verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum Verdict {
    /// hapstab measures what the paper says.
    #[serde(rename = "reproduced")]
    Reproduced,
    /// Part of the claim holds; the note says which part does not.
    #[serde(rename = "partly reproduced")]
    Partly,
    /// hapstab measures something else.
    #[serde(rename = "differs")]
    Differs,
}

impl Verdict {
    /// The word used in the reports.
    pub fn as_str(&self) -> &'static str {
        match self {
            Verdict::Reproduced => "reproduced",
            Verdict::Partly => "partly reproduced",
            Verdict::Differs => "differs",
        }
    }

    fn from(ok: bool) -> Self {
        if ok {
            Verdict::Reproduced
        } else {
            Verdict::Differs
        }
    }
}

/// One claim of the paper with what hapstab measured.
#[derive(Debug, Clone, Serialize)]
pub struct Claim {
    /// C1 … C11.
    pub id: &'static str,
    /// The claim, as the paper states it.
    pub claim: &'static str,
    /// The figure or number that tests it.
    pub figure: &'static str,
    /// What hapstab measured (text).
    pub measured: String,
    /// The measured numbers.
    pub values: BTreeMap<&'static str, f64>,
    /// Verdict.
    pub verdict: Verdict,
    /// How the verdict was reached (criterion), and any difference.
    pub note: String,
}

/// Sampling period of the physical examples (C4, C10): 1 ms.
pub const PERIOD: f64 = 1e-3;

/// Window of the close-up Fig. 5: α range.
pub const FIG5_ALPHA: (f64, f64) = (-0.0015, 0.006);
/// Window of the close-up Fig. 5: β range.
pub const FIG5_BETA: (f64, f64) = (-0.02, 0.018);

/// A shift counts as visible from this fraction of an axis range on (0.5 %, about 4 px of an
/// 800 px panel): claims C2 and C3.
pub const VISIBLE: f64 = 0.005;

/// The C4 plants: the PHANToM-like device alone, with each element of the typical arm added
/// on its own, and with the whole arm: (name, m, b, k) in SI units.
pub fn c4_plants() -> [(&'static str, f64, f64, f64); 5] {
    let (dv, arm) = (Device::PHANTOM_LIKE, Arm::TYPICAL);
    [
        ("device alone", dv.mass, dv.damping, 0.0),
        ("+ arm mass", dv.mass + arm.mass, dv.damping, 0.0),
        ("+ arm damping", dv.mass, dv.damping + arm.damping, 0.0),
        ("+ arm stiffness", dv.mass, dv.damping, arm.stiffness),
        (
            "+ whole arm",
            dv.mass + arm.mass,
            dv.damping + arm.damping,
            arm.stiffness,
        ),
    ]
}

fn c4_key(m: f64, b: f64, k: f64) -> Key {
    Key::new(k * PERIOD * PERIOD / m, b * PERIOD / m, 0)
}

/// Region keys the claims need beyond the figures.
pub fn extra_keys() -> Vec<Key> {
    c4_plants()
        .iter()
        .map(|&(_, m, b, k)| c4_key(m, b, k))
        .collect()
}

fn pct(x: f64) -> String {
    format!("{} %", sig(100.0 * x, 3))
}

/// Measures every claim.
pub fn claims(r: &Results) -> Result<Vec<Claim>> {
    Ok(vec![
        c1(r)?,
        c2(r)?,
        c3(r)?,
        c4(r)?,
        c5()?,
        c6(r)?,
        c7(r)?,
        c8(r)?,
        c9(r)?,
        c10()?,
        c11()?,
    ])
}

fn c1(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let mut ok = true;
    let mut parts = Vec::new();
    for (g, name, aname) in [
        (0.0, "area_ratio_gamma_0", "alpha_max_ratio_gamma_0"),
        (
            GAMMA_ARM,
            "area_ratio_gamma_0.001",
            "alpha_max_ratio_gamma_0.001",
        ),
    ] {
        let a0 = r.region(Key::new(g, 0.0, 0))?;
        let a1 = r.region(Key::new(g, DELTA_ARM, 0))?;
        let ratio = a1.area / a0.area;
        let aratio = a1.alpha_max / a0.alpha_max;
        ok &= ratio > 1.0;
        values.insert(name, ratio);
        values.insert(aname, aratio);
        parts.push(format!(
            "γ = {}: area {} → {} (×{}), α_max {} → {}",
            sig(g, 3),
            sig(a0.area, 5),
            sig(a1.area, 5),
            sig(ratio, 5),
            sig(a0.alpha_max, 5),
            sig(a1.alpha_max, 5)
        ));
    }
    Ok(Claim {
        id: "C1",
        claim: "physical damping δ enlarges the stable region (Fig. 4)",
        figure: "Fig. 4 (d = 0): area and α_max for δ = 0 and δ = 0.015",
        measured: parts.join("; "),
        values,
        verdict: Verdict::from(ok),
        note: "reproduced when the area with δ = 0.015 exceeds the area with δ = 0 for both γ"
            .into(),
    })
}

/// Largest |Δα| of the exact upper (bottom-right) boundary between γ = 0 and γ = 0.001 at
/// equal β over the part of Fig. 5's window where both exist.
fn bottom_shift(delta: f64) -> Result<f64> {
    let f0 = PolyFamily::new(PlantParams::new(0.0, delta)?, 0)?;
    let f1 = PolyFamily::new(PlantParams::new(GAMMA_ARM, delta)?, 0)?;
    let mut worst: f64 = 0.0;
    let n = 200;
    for i in 0..=n {
        let b = FIG5_BETA.0 + (FIG5_BETA.1 - FIG5_BETA.0) * i as f64 / n as f64;
        if let (Some(a0), Some(a1)) = (
            hapstab::linear::exact_upper_alpha(&f0, b),
            hapstab::linear::exact_upper_alpha(&f1, b),
        ) && a0.max(a1) > FIG5_ALPHA.0
            && a0.min(a1) < FIG5_ALPHA.1
        {
            worst = worst.max((a1 - a0).abs());
        }
    }
    Ok(worst)
}

fn c2(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let mut left_ok = true;
    let mut parts = Vec::new();
    let width = FIG5_ALPHA.1 - FIG5_ALPHA.0;
    let mut worst_rel: f64 = 0.0;
    for (delta, lname, bname) in [
        (0.0, "min_alpha_delta_0", "bottom_shift_delta_0"),
        (
            DELTA_ARM,
            "min_alpha_delta_0.015",
            "bottom_shift_delta_0.015",
        ),
    ] {
        let reg = r.region(Key::new(GAMMA_ARM, delta, 0))?;
        left_ok &= (reg.alpha_min + GAMMA_ARM).abs() <= 1e-9 * GAMMA_ARM;
        let shift = bottom_shift(delta)?;
        worst_rel = worst_rel.max(shift / width);
        values.insert(lname, reg.alpha_min);
        values.insert(bname, shift);
        parts.push(format!(
            "δ = {}: min α = {} (−γ = −0.001); bottom boundary moves ≤ {} in α ({} of the close-up's α-range)",
            sig(delta, 3),
            sig(reg.alpha_min, 10),
            sig(shift, 3),
            pct(shift / width)
        ));
    }
    let low = r.region(Key::new(GAMMA_ARM, DELTA_ARM, 0))?.beta_min;
    values.insert("bottom_corner_beta_gamma_0.001_delta_0.015", low);
    parts.push(format!(
        "the lowest corner moves from β = −δ to β = {} (= −δ − γ/2, where the boundary meets α = −γ)",
        sig(low, 6)
    ));
    values.insert("bottom_shift_relative", worst_rel);
    let ok = left_ok && worst_rel < VISIBLE;
    Ok(Claim {
        id: "C2",
        claim: "physical stiffness γ moves the left boundary to α = −γ and leaves the bottom boundary visibly unchanged (Fig. 5)",
        figure: "Fig. 5 (close-up, d = 0, γ = 0 and 0.001)",
        measured: parts.join("; "),
        values,
        verdict: Verdict::from(ok),
        note: format!(
            "reproduced when min α = −γ (to 1e-9 relative) and the bottom boundary moves by less than {} of the close-up's α-range",
            pct(VISIBLE)
        ),
    })
}

/// The largest displacement of the boundary (left edge, tip α_max, lowest corner) between
/// γ = 0 and γ = 0.001, relative to the region's extent.
pub fn visibility(r0: &Region, r1: &Region) -> f64 {
    let wa = r0.alpha_max - r0.alpha_min;
    let wb = r0.beta_max - r0.beta_min;
    let left = (r1.alpha_min - r0.alpha_min).abs() / wa;
    let tip = (r1.alpha_max - r0.alpha_max).abs() / wa;
    let bottom = (r1.beta_min - r0.beta_min).abs() / wb;
    left.max(tip).max(bottom)
}

fn c3(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let mut parts = Vec::new();
    let mut vis = [0.0f64; 3];
    let mut vis_min = [f64::INFINITY; 3];
    for d in 0..=2 {
        for delta in [0.0, DELTA_ARM] {
            let r0 = r.region(Key::new(0.0, delta, d))?;
            let r1 = r.region(Key::new(GAMMA_ARM, delta, d))?;
            let v = visibility(r0, r1);
            vis[d] = vis[d].max(v);
            vis_min[d] = vis_min[d].min(v);
            if delta == 0.0 {
                parts.push(format!(
                    "d = {d} (δ = 0): largest shift {} of the region's extent, area {}, α_max {}",
                    pct(v),
                    format_args!("{:+.2} %", 100.0 * (r1.area / r0.area - 1.0)),
                    format_args!("{:+.2} %", 100.0 * (r1.alpha_max / r0.alpha_max - 1.0)),
                ));
                values.insert(
                    ["area_change_d0", "area_change_d1", "area_change_d2"][d],
                    r1.area / r0.area - 1.0,
                );
            }
        }
    }
    values.insert("shift_d0_max", vis[0]);
    values.insert("shift_d1_min", vis_min[1]);
    values.insert("shift_d2_min", vis_min[2]);
    let ok = vis[0] < VISIBLE && vis_min[1] >= VISIBLE && vis_min[2] >= VISIBLE;
    Ok(Claim {
        id: "C3",
        claim: "for d = 1, 2 the influence of γ becomes visible in the whole region (Fig. 6)",
        figure: "Fig. 6 (d = 1, 2) against Fig. 4 (d = 0)",
        measured: parts.join("; "),
        values,
        verdict: Verdict::from(ok),
        note: format!(
            "shift = largest move of the left edge, the tip α_max or the lowest corner, relative to the region's α- or β-extent; reproduced when it is below {} for d = 0 and at least {} for d = 1 and 2 (both δ)",
            pct(VISIBLE),
            pct(VISIBLE)
        ),
    })
}

fn c4(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let plants = c4_plants();
    let phys = |m: f64, reg: &Region| {
        (
            reg.alpha_max * m / (PERIOD * PERIOD),
            reg.area * m * m / (PERIOD * PERIOD * PERIOD),
        )
    };
    let (m0, b0, k0) = (plants[0].1, plants[0].2, plants[0].3);
    let (kmax0, area0) = phys(m0, r.region(c4_key(m0, b0, k0))?);
    let mut parts = vec![format!(
        "device alone (m = {} kg, b = {} Ns/m): K_max = {} N/m, area {} N²·s/m²",
        sig(m0, 3),
        sig(b0, 3),
        sig(kmax0, 6),
        sig(area0, 4)
    )];
    let mut all_area = true;
    let mut all_kmax = true;
    let names = [
        ("", ""),
        ("area_ratio_mass", "kmax_ratio_mass"),
        ("area_ratio_damping", "kmax_ratio_damping"),
        ("area_ratio_stiffness", "kmax_ratio_stiffness"),
        ("area_ratio_arm", "kmax_ratio_arm"),
    ];
    for (i, &(name, m, b, k)) in plants.iter().enumerate().skip(1) {
        let (kmax, area) = phys(m, r.region(c4_key(m, b, k))?);
        all_area &= area > area0;
        all_kmax &= kmax >= kmax0;
        values.insert(names[i].0, area / area0);
        values.insert(names[i].1, kmax / kmax0);
        parts.push(format!(
            "{name}: area ×{}, K_max ×{}",
            sig(area / area0, 4),
            sig(kmax / kmax0, 5)
        ));
    }
    let verdict = match (all_area, all_kmax) {
        (true, true) => Verdict::Reproduced,
        (true, false) => Verdict::Partly,
        _ => Verdict::Differs,
    };
    let note = match verdict {
        Verdict::Partly => "each element of the arm enlarges the area of the stable region in the physical (K, B)-plane, \
             but the region does not grow in every direction: arm stiffness adds area at K < 0 (left edge K = −k) \
             and lowers K_max slightly, so the stiffer region does not contain the original one"
            .to_string(),
        _ => "reproduced when adding each element of the arm enlarges the area of the stable region in the \
              physical (K, B)-plane and does not lower K_max"
            .to_string(),
    };
    Ok(Claim {
        id: "C4",
        claim: "mass, stiffness and damping of the arm all enlarge the stable region (Section V conclusion)",
        figure: "numbers: PHANToM-like device (0.1 kg, 1.5 Ns/m) with a typical arm (1 kg, 6 Ns/m, 350 N/m), T = 1 ms, d = 0",
        measured: parts.join("; "),
        values,
        verdict,
        note,
    })
}

/// (number of grid points satisfying (19) and (22), number of those violating (18)).
pub fn eq18_grid() -> Result<(usize, usize)> {
    let lin = |lo: f64, hi: f64, n: usize| -> Vec<f64> {
        (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect()
    };
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

fn c5() -> Result<Claim> {
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

fn c6(r: &Results) -> Result<Claim> {
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

fn c7(r: &Results) -> Result<Claim> {
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
        PolyFamily::new(
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
        note: format!(
            "reproduced when α_max ≤ 1e-9 at γ = π²/4, the area at γ = π²(1 − 1e-6) is within 1 % of the triangle through its corners, and the robust region has no interior point{}",
            if nyq.source == Source::Slices {
                "; the region at γ = π²(1 − 1e-6) is outlined from exact per-β intervals because stable_region returned no polygon"
            } else {
                ""
            }
        ),
    })
}

fn c8(r: &Results) -> Result<Claim> {
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

fn c9(r: &Results) -> Result<Claim> {
    let mut values = BTreeMap::new();
    let q = r.region(Key::new(sweep_gamma((1, 4), 0.0), 0.0, 1))?;
    let q0 = r.region(Key::new(sweep_gamma((1, 4), 0.0), 0.0, 0))?;
    let g = PI * PI;
    let mut worst: f64 = 0.0;
    for d in [0usize, 1, 2, 5] {
        let fam = PolyFamily::new(
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

fn c10() -> Result<Claim> {
    let dv = Device::PHANTOM_LIKE;
    let n = nyquist_stiffness(dv.mass, dv.damping, PERIOD)?;
    let kn = n.stiffness / 1e3;
    let mut values = BTreeMap::new();
    values.insert("stiffness_kN_per_m", kn);
    Ok(Claim {
        id: "C10",
        claim: "Remark 4: about 987.0 kN/m brings a PHANToM-like device to the Nyquist frequency",
        figure: "Remark 4: m = 0.1 kg, T = 1 ms, b = 1.5 Ns/m",
        measured: format!(
            "k = π²m/T² + b²/(4m) = {} kN/m (γ_N = {})",
            sig(kn, 7),
            sig(n.gamma, 7)
        ),
        values,
        verdict: Verdict::from((kn - 987.0).abs() < 0.05),
        note: "reproduced when k rounds to 987.0 kN/m; b²/(4m) is used (the paper prints b²/4m, read as b²/(4m))".into(),
    })
}

fn c11() -> Result<Claim> {
    let mut worst: f64 = 0.0;
    for &delta in &[0.015, 0.1, 1.0, 5.0] {
        let p = DiscretePlant::new(0.0, delta)?;
        let (n1, n0, a1, a0) = eq10_coefficients(delta);
        for (x, y) in [(p.n1, n1), (p.n0, n0), (p.a1, a1), (p.a0, a0)] {
            worst = worst.max((x - y).abs() / y.abs());
        }
    }
    let mut values = BTreeMap::new();
    values.insert("max_relative_difference", worst);
    Ok(Claim {
        id: "C11",
        claim: "Remark 2: with k = 0 the discrete plant reduces to eq. (10)",
        figure: "Remark 2, eq. (10): plant coefficients at γ = 0, δ ∈ {0.015, 0.1, 1, 5}",
        measured: format!(
            "largest relative difference between the exact ZOH plant at γ = 0 and eq. (10): {}",
            sig(worst, 2)
        ),
        values,
        verdict: Verdict::from(worst < 1e-9),
        note: "reproduced when numerator and denominator coefficients agree to 1e-9 relative"
            .into(),
    })
}
