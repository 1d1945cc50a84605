//! The robust α-set at one β (Section VIII): the intersection of the exact stable α-intervals
//! of a sampled set of plant configurations, with its ends refined by golden-section search
//! in the plant parameter that sets them.

use std::sync::OnceLock;

use super::search::{golden_max, golden_min};
use crate::boundary::{
    CircleTable, Interval, stable_stiffness_intervals, stable_stiffness_intervals_tabulated,
};
use crate::error::Result;
use crate::paper::NormalizedFamily;
use crate::paper::PlantParams;

/// Intersection of two sorted lists of disjoint open intervals.
fn intersect(a: &[Interval], b: &[Interval]) -> Vec<Interval> {
    let mut out = Vec::new();
    for x in a {
        for y in b {
            let lo = x.lo.max(y.lo);
            let hi = x.hi.min(y.hi);
            if lo < hi {
                out.push(Interval { lo, hi });
            }
        }
    }
    out.sort_by(|p, q| p.lo.total_cmp(&q.lo));
    out
}

/// One plant configuration of a robust problem: the family and its mass relative to the
/// reference mass in which α and β are measured (1 for a fixed mass).
#[derive(Debug, Clone)]
pub(super) struct Config {
    pub(super) scale: f64,
    pub(super) fam: NormalizedFamily,
    /// The family's crossing scan, computed on first use when the configuration is one of
    /// the samples that many β-slices cut (None for the single-use configurations of a
    /// golden-section refinement).
    pub(super) table: Option<OnceLock<CircleTable>>,
}

/// One unscaled configuration per γ sample, at damping δ and delay d.
pub(super) fn unit_configs(gammas: &[f64], delta: f64, d: usize) -> Result<Vec<Config>> {
    gammas
        .iter()
        .map(|&g| {
            Ok(Config {
                scale: 1.0,
                table: Some(OnceLock::new()),
                fam: NormalizedFamily::new(PlantParams::new(g, delta)?, d)?,
            })
        })
        .collect()
}

impl Config {
    /// Stable reference-α intervals at reference β: α_ref/s must lie in I(β_ref/s), so the
    /// set is s·I(β_ref/s).
    fn intervals(&self, beta_ref: f64) -> Vec<Interval> {
        let s = self.scale;
        let ivs = match &self.table {
            Some(t) => {
                let table = t.get_or_init(|| CircleTable::new(&self.fam));
                stable_stiffness_intervals_tabulated(&self.fam, table, beta_ref / s)
            }
            None => stable_stiffness_intervals(&self.fam, beta_ref / s),
        };
        ivs.into_iter()
            .map(|iv| Interval {
                lo: iv.lo * s,
                hi: iv.hi * s,
            })
            .collect()
    }
}

/// The robust α-set at one β for a sampled set of configurations, with the index of the
/// configuration that sets each end of a single-interval result.
pub(super) fn robust_at(configs: &[Config], beta: f64) -> (Vec<Interval>, Option<(usize, usize)>) {
    let mut acc: Option<Vec<Interval>> = None;
    let mut single = true;
    let (mut arg_lo, mut arg_hi) = (0usize, 0usize);
    let (mut best_lo, mut best_hi) = (f64::NEG_INFINITY, f64::INFINITY);
    for (j, c) in configs.iter().enumerate() {
        let ivs = c.intervals(beta);
        if ivs.len() != 1 {
            single = false;
        } else {
            if ivs[0].lo > best_lo {
                best_lo = ivs[0].lo;
                arg_lo = j;
            }
            if ivs[0].hi < best_hi {
                best_hi = ivs[0].hi;
                arg_hi = j;
            }
        }
        let next = match acc {
            None => ivs,
            Some(prev) => intersect(&prev, &ivs),
        };
        let empty = next.is_empty();
        acc = Some(next);
        if empty {
            return (Vec::new(), None);
        }
    }
    let res = acc.unwrap_or_default();
    let args = (single && res.len() == 1).then_some((arg_lo, arg_hi));
    (res, args)
}

/// A robust slice at one β: the robust α-interval (the widest, when the robust set has
/// several), the plant coordinates that set its ends, and the configurations that set them.
#[derive(Debug, Clone, Copy)]
pub(super) struct Slice {
    /// The robust α-interval.
    pub(super) interval: Interval,
    /// The coordinate of the plant that sets its lower end (NaN when not known).
    pub(super) coord_lo: f64,
    /// The coordinate of the plant that sets its upper end (NaN when not known).
    pub(super) coord_hi: f64,
    /// Whether the robust set had several intervals.
    pub(super) several: bool,
    /// The sampled configurations (indices) that set the two ends, for a single interval.
    pub(super) ends: Option<(usize, usize)>,
}

/// Robust slice at β with optional golden refinement in the plant parameter that
/// `make(t)` maps to a configuration (t ∈ [lo, hi] of the refined coordinate).
pub(super) fn refined_slice(
    configs: &[Config],
    coords: &[f64],
    neighbours: &(dyn Fn(usize) -> (f64, f64) + Sync),
    make: &(dyn Fn(usize, f64) -> Config + Sync),
    beta: f64,
    refine: bool,
) -> Option<Slice> {
    let (ivs, args) = robust_at(configs, beta);
    if ivs.is_empty() {
        return None;
    }
    let multiple = ivs.len() > 1;
    let widest = *ivs
        .iter()
        .max_by(|a, b| (a.hi - a.lo).total_cmp(&(b.hi - b.lo)))?;
    let Some((jl, jh)) = args.filter(|_| refine) else {
        let (tl, th) = args.map_or((f64::NAN, f64::NAN), |(l, h)| (coords[l], coords[h]));
        return Some(Slice {
            interval: widest,
            coord_lo: tl,
            coord_hi: th,
            several: multiple,
            ends: args,
        });
    };
    let mid = 0.5 * (widest.lo + widest.hi);
    let pick = |c: &Config| -> Option<Interval> {
        c.intervals(beta)
            .into_iter()
            .find(|iv| iv.lo <= mid && mid <= iv.hi)
    };
    let (a, b) = neighbours(jh);
    let (th, hi) = golden_min(a, b, |t| {
        pick(&make(jh, t)).map_or(f64::NEG_INFINITY, |iv| iv.hi)
    });
    let (a, b) = neighbours(jl);
    let (tl, lo) = golden_max(a, b, |t| {
        pick(&make(jl, t)).map_or(f64::INFINITY, |iv| iv.lo)
    });
    let lo = lo.max(widest.lo);
    let hi = hi.min(widest.hi);
    let tl = if lo > widest.lo { tl } else { coords[jl] };
    let th = if hi < widest.hi { th } else { coords[jh] };
    if lo >= hi {
        return None;
    }
    Some(Slice {
        interval: Interval { lo, hi },
        coord_lo: tl,
        coord_hi: th,
        several: multiple,
        ends: args,
    })
}
