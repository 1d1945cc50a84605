//! The Z-width of a haptic device (Colgate & Brown 1994): the range of virtual walls it renders
//! stably, here exactly, in physical units, beside the walls it renders passively.
//!
//! For one loop (device, optional human arm, sampling, delay, velocity estimator) this
//! collects: the exact stable region of Section V ([`crate::region`]) converted to (K, B) in
//! N/m and Ns/m; the passive region of Colgate and Schenkel ([`crate::passivity`], eq. 28 for
//! the paper's loop, Section VIII); the linear condition (22) K < (b + B)/(t_d + T/2) as a
//! line; the largest stable stiffness and the damping that reaches it; and a table of the
//! largest stable, passive and linear-condition stiffness against the virtual damping.

use rayon::prelude::*;
use serde::Serialize;

use crate::boundary::WallPoint;
use crate::closed_loop::AffineFamily;
use crate::error::Result;
use crate::model::Loop;
use crate::params::Wall;
use crate::passivity::{
    DeviceDamping, PassiveRegion, SampledWall, device_damping, k_max_passive_at, passive_k_max,
    passive_region,
};
use crate::region::StableRegion;
use crate::system::System;

/// The linear stability condition (22): K < (b + B)/t_r with t_r = t_d + T/2.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearCondition {
    /// The plant's damping b in Ns/m: eq. (1)'s effective b, the arm's damping included.
    pub damping: f64,
    /// The effective delay t_r = t_d + T/2 in s (eq. 16).
    pub effective_delay: f64,
}

impl LinearCondition {
    /// The stiffness limit (b + B)/t_r in N/m at a virtual damping B.
    pub fn k_at(&self, damping: f64) -> f64 {
        (self.damping + damping) / self.effective_delay
    }
}

/// One row of the K_max-versus-damping table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ZWidthRow {
    /// Virtual damping B in Ns/m.
    pub damping: f64,
    /// Largest stable K in N/m at this B (the top of the exact stable interval; None when no K
    /// is stable).
    pub k_max: Option<f64>,
    /// Lower end of that stable interval in N/m (−k for the paper's plant).
    pub k_min: Option<f64>,
    /// Largest passive K in N/m at this B (None when none is, or passivity does not apply).
    pub k_max_passive: Option<f64>,
    /// The linear condition's limit (b + B)/t_r in N/m (None beyond the paper's loop, or
    /// without a device damping).
    pub k_linear: Option<f64>,
}

/// The Z-width of one loop (module doc). Polygons are counter-clockwise in (K, B).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ZWidth {
    /// Sampling period T in s.
    pub period: f64,
    /// Delay t_d in s.
    pub delay_time: f64,
    /// The device damping b that passivity and the linear condition use.
    pub device_damping: DeviceDamping,
    /// Stable components, (K in N/m, B in Ns/m).
    pub stable: Vec<Vec<Wall>>,
    /// Area of the stable region in N/m · Ns/m.
    pub stable_area: f64,
    /// The largest stable K in N/m and the B that reaches it (None when nothing is stable).
    pub k_max: Option<Wall>,
    /// The largest stable K with B >= 0 (a device that cannot render negative damping).
    pub k_max_nonnegative_damping: Option<Wall>,
    /// The passive region (None when passivity does not apply, see `device_damping`).
    pub passive: Option<PassiveRegion>,
    /// The largest passive K and its B by the paper's eq. (28) with the arm's damping counted
    /// (b = b_L + b_H of eq. 1): towards this operator only, not any passive operator; None
    /// when the plant names no operator or passivity does not apply.
    pub k_max_passive_with_arm: Option<Wall>,
    /// Whether every tested point strictly inside the passive region is stable (Section VIII:
    /// passive ⊂ stable where the argument applies); None without a passive region.
    pub passive_inside_stable: Option<bool>,
    /// The linear condition (22) (None beyond the paper's loop, or without a device damping).
    pub linear: Option<LinearCondition>,
    /// K_max against the virtual damping.
    pub table: Vec<ZWidthRow>,
}

/// Rows of the default table: the virtual damping from 0 toward the stable region's largest B.
pub const DEFAULT_TABLE_ROWS: usize = 11;

/// The Z-width of a loop; `dampings` are the table's B values in Ns/m (None:
/// [`DEFAULT_TABLE_ROWS`] values from 0 in steps of 1/11 of the largest stable B).
pub fn zwidth(lp: &Loop, dampings: Option<&[f64]>) -> Result<ZWidth> {
    let sys = System::of(lp)?;
    let fam = sys.family();
    let region = sys.region()?;
    let stable: Vec<Vec<Wall>> = region
        .polygons
        .iter()
        .map(|p| p.vertices.iter().map(|v| physical(fam, *v)).collect())
        .collect();
    let device = device_damping(&lp.plant);
    let b_dev = match &device {
        DeviceDamping::Known { damping } => Some(*damping),
        DeviceDamping::NotApplicable { .. } => None,
    };
    let sw = SampledWall::new(lp)?;
    let passive = b_dev.map(|b| passive_region(&sw, b)).transpose()?;
    // the linear condition (22) is a stability condition: the arm's damping counts; it is
    // the paper's loop's (backward difference, whole delay, no lag, as
    // `System::linear_k`), not a filtered or lagged loop's
    let b_eff = b_dev.map(|b| lp.plant.effective_damping().unwrap_or(b));
    let linear = b_eff
        .filter(|_| lp.paper_view().is_some())
        .map(|b| LinearCondition {
            damping: b,
            effective_delay: lp.delay_time() + 0.5 * lp.period,
        });
    let rows = match dampings {
        Some(d) => d.to_vec(),
        None => default_dampings(&stable),
    };
    let table = rows
        .par_iter()
        .map(|&b| table_row(&sys, &sw, b_dev, linear, b))
        .collect::<Result<_>>()?;
    Ok(ZWidth {
        period: lp.period,
        delay_time: lp.delay_time(),
        device_damping: device,
        stable_area: region.area * fam.scale.stiffness * fam.scale.damping,
        k_max: k_max_of(fam, &region),
        k_max_nonnegative_damping: sys
            .k_max_within_region(&region, 0.0, f64::INFINITY)?
            .map(|p| physical(fam, WallPoint { a: p.a, b: p.b })),
        passive_inside_stable: passive.as_ref().map(|p| passive_inside(&sys, &sw, p)),
        k_max_passive_with_arm: b_dev
            .and(lp.plant.effective_damping())
            .and_then(|b| passive_k_max(&sw, b)),
        stable,
        passive,
        linear,
        table,
    })
}

fn physical(fam: &AffineFamily, p: WallPoint) -> Wall {
    let (k, b) = fam.to_physical(p.a, p.b);
    Wall {
        stiffness: k,
        damping: b,
    }
}

fn k_max_of(fam: &AffineFamily, region: &StableRegion) -> Option<Wall> {
    region.a_max.is_finite().then(|| {
        physical(
            fam,
            WallPoint {
                a: region.a_max,
                b: region.b_at_a_max,
            },
        )
    })
}

/// [`DEFAULT_TABLE_ROWS`] dampings in steps of 1/n of the largest B of the stable polygons,
/// from 0 (the region's tip at the largest B itself has no width).
fn default_dampings(stable: &[Vec<Wall>]) -> Vec<f64> {
    let top = stable
        .iter()
        .flatten()
        .map(|w| w.damping)
        .fold(0.0_f64, f64::max);
    let n = DEFAULT_TABLE_ROWS;
    (0..n).map(|i| top * i as f64 / n as f64).collect()
}

fn table_row(
    sys: &System,
    sw: &SampledWall,
    b_dev: Option<f64>,
    linear: Option<LinearCondition>,
    damping: f64,
) -> Result<ZWidthRow> {
    let scale = sys.family().scale;
    let top = sys
        .stable_intervals(sys.damping_units(damping)?)
        .into_iter()
        .filter(|iv| iv.hi.is_finite())
        .max_by(|x, y| x.hi.total_cmp(&y.hi));
    Ok(ZWidthRow {
        damping,
        k_max: top.map(|iv| iv.hi * scale.stiffness),
        k_min: top.map(|iv| iv.lo * scale.stiffness),
        k_max_passive: b_dev.and_then(|b| k_max_passive_at(sw, b, damping)),
        k_linear: linear.map(|l| l.k_at(damping)),
    })
}

/// Fraction of the way from the region's origin corner toward each test point: strictly
/// inside, clear of the polygon's chords (which lie within 1e-5 of the size inside the true
/// boundary) and of rounding.
const INSIDE_SCALES: [f64; 3] = [0.1, 0.5, 0.99];

/// Points whose static stiffness W(1) is below this fraction of the region's largest K lie on
/// the line W(1) = 0 (to rounding), where the plant's own static stiffness decides.
const ON_DC_LINE: f64 = 1e-9;

/// Every vertex ray and edge midpoint of the passive polygon, scaled strictly inside, tested
/// with Schur–Cohn (points on the line W(1) = 0 are skipped, see [`ON_DC_LINE`]).
fn passive_inside(sys: &System, sw: &SampledWall, p: &PassiveRegion) -> bool {
    let v = &p.vertices;
    let n = v.len();
    let floor = ON_DC_LINE * p.k_max.abs();
    (0..n).all(|i| {
        let (a, b) = (v[i], v[(i + 1) % n]);
        let mid = Wall {
            stiffness: 0.5 * (a.stiffness + b.stiffness),
            damping: 0.5 * (a.damping + b.damping),
        };
        [a, mid].into_iter().all(|w| {
            INSIDE_SCALES.iter().all(|&s| {
                let (k, bb) = (s * w.stiffness, s * w.damping);
                let dc = sw.dc_stiffness(Wall {
                    stiffness: k,
                    damping: bb,
                });
                if dc <= floor {
                    return true;
                }
                let w = Wall {
                    stiffness: k,
                    damping: bb,
                };
                sys.wall_units(w)
                    .is_ok_and(|u| sys.decide(u).verdict == crate::verdict::Verdict::Stable)
            })
        })
    })
}
