//! The region from exact slices of constant damping, where the arrangement of the curve
//! cannot be resolved (a curve that winds too often to sample, or branches that meet at the
//! wall-free point of a lossless plant).
//!
//! Each slice is the exact set of stable stiffnesses at one damping
//! ([`crate::boundary::stable_stiffness_intervals`]): its ends are points of the boundary, found
//! by the same crossings and point tests as `check` and `kmax --wall-damping`. Slices are
//! added by bisection in the damping until the interval ends of every slice are within the
//! chord tolerance of the chords between its neighbours, and until every change in the number
//! of intervals is located to 10⁻¹² of the scanned height. Consecutive slices with the same
//! number of intervals are joined end to end into polygons (left ends upward, right ends
//! downward); a change in the number closes them and opens new ones.

use super::*;
use crate::boundary::{Interval, stable_stiffness_intervals};

/// Uniform slices a scan starts from, before bisection.
const START_SLICES: usize = 256;

/// A change in the number of intervals is located to this fraction of the scanned height.
const TOPOLOGY_REL: f64 = 1e-12;

/// Most slices one scan may take (each is one exact line of crossings).
const MAX_SLICES: usize = 200_000;

/// One slice: its damping and its stable intervals with finite ends inside the box.
#[derive(Clone)]
struct Slice {
    b: f64,
    ivs: Vec<Interval>,
}

/// The stable region inside `bx` (a0, a1, b0, b1) from exact slices of constant damping, its
/// chords within `tol` (wall units) of the boundary; None when the scan would exceed
/// [`MAX_SLICES`]. K_max is left to the caller's confirmation.
pub(super) fn scanned_region(fam: &AffineFamily, bx: BoxF, tol: f64) -> Option<StableRegion> {
    let (a0, a1, b0, b1) = bx;
    let slice = |b: f64| Slice {
        b,
        ivs: stable_stiffness_intervals(fam, b)
            .into_iter()
            .filter(|iv| iv.lo.is_finite() && iv.hi.is_finite() && iv.hi > iv.lo)
            .filter(|iv| iv.hi > a0 && iv.lo < a1)
            .collect(),
    };
    let h = (b1 - b0) / START_SLICES as f64;
    let start: Vec<Slice> = (0..=START_SLICES)
        .into_par_iter()
        .map(|i| slice(b0 + h * i as f64))
        .collect();
    let min_gap = TOPOLOGY_REL * (b1 - b0);
    let mut slices = vec![start[0].clone()];
    for pair in start.windows(2) {
        refine_between(&slice, &pair[0], &pair[1], (tol, min_gap), &mut slices)?;
    }
    Some(StableRegion::unconfirmed(
        joined(&slices),
        scanned_max(fam, &slices),
    ))
}

/// The largest interval end of the slices, maximized between the neighbours of its slice by
/// golden-section search on the exact largest end (NaN, NaN when no slice is stable).
fn scanned_max(fam: &AffineFamily, slices: &[Slice]) -> (f64, f64) {
    let top = |s: &Slice| {
        s.ivs
            .iter()
            .map(|iv| iv.hi)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let Some(j) = (0..slices.len()).max_by(|&x, &y| top(&slices[x]).total_cmp(&top(&slices[y])))
    else {
        return (f64::NAN, f64::NAN);
    };
    let best = top(&slices[j]);
    if !best.is_finite() {
        return (f64::NAN, f64::NAN);
    }
    let f = |b: f64| {
        stable_stiffness_intervals(fam, b)
            .iter()
            .filter(|iv| iv.hi.is_finite() && iv.hi > iv.lo)
            .map(|iv| iv.hi)
            .fold(f64::NEG_INFINITY, f64::max)
    };
    let (mut lo, mut hi) = (
        slices[j.saturating_sub(1)].b,
        slices[(j + 1).min(slices.len() - 1)].b,
    );
    let g = 0.5 * (5f64.sqrt() - 1.0);
    let (mut x1, mut x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..GOLDEN_STEPS {
        if f1 >= f2 {
            hi = x2;
            (x2, f2) = (x1, f1);
            x1 = hi - g * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            (x1, f1) = (x2, f2);
            x2 = lo + g * (hi - lo);
            f2 = f(x2);
        }
    }
    [(best, slices[j].b), (f1, x1), (f2, x2)]
        .into_iter()
        .max_by(|x, y| x.0.total_cmp(&y.0))
        .unwrap_or((best, slices[j].b))
}

/// Golden-section steps: 0.618^80 ≈ 2·10⁻¹⁷ of the bracket.
const GOLDEN_STEPS: usize = 80;

/// Appends the slices strictly above `lo` up to and including `hi`, bisecting the gap until
/// the middle slice agrees with the chords of its neighbours (same count, ends within tol)
/// or the gap is below `min_gap`. None when the slices run past [`MAX_SLICES`].
fn refine_between(
    slice: &(impl Fn(f64) -> Slice + Sync),
    lo: &Slice,
    hi: &Slice,
    (tol, min_gap): (f64, f64),
    out: &mut Vec<Slice>,
) -> Option<()> {
    let mut stack = vec![hi.clone()];
    let mut below = lo.clone();
    while let Some(top) = stack.pop() {
        if out.len() + stack.len() > MAX_SLICES {
            return None;
        }
        let gap = top.b - below.b;
        if gap > min_gap {
            let mid = slice(below.b + 0.5 * gap);
            if !follows_chords(&below, &mid, &top, tol) {
                stack.push(top);
                stack.push(mid);
                continue;
            }
        }
        out.push(top.clone());
        below = top;
    }
    Some(())
}

/// True when the middle slice has as many intervals as both neighbours and each of its ends
/// lies within tol of the chord between the neighbours' ends.
fn follows_chords(lo: &Slice, mid: &Slice, hi: &Slice, tol: f64) -> bool {
    let n = mid.ivs.len();
    if lo.ivs.len() != n || hi.ivs.len() != n {
        return false;
    }
    let w = (mid.b - lo.b) / (hi.b - lo.b);
    let near = |x: f64, y0: f64, y1: f64| (x - (y0 + w * (y1 - y0))).abs() <= tol;
    (0..n).all(|i| {
        let (l, m, u) = (&lo.ivs[i], &mid.ivs[i], &hi.ivs[i]);
        near(m.lo, l.lo, u.lo) && near(m.hi, l.hi, u.hi)
    })
}

/// Polygons from runs of consecutive slices with the same number of intervals: interval i
/// of each slice of a run is joined to interval i of the next.
fn joined(slices: &[Slice]) -> Vec<Polygon> {
    let mut polygons = Vec::new();
    let mut run_start = 0;
    for i in 1..=slices.len() {
        let ends_run = i == slices.len() || slices[i].ivs.len() != slices[run_start].ivs.len();
        if ends_run {
            let run = &slices[run_start..i];
            for k in 0..run[0].ivs.len() {
                polygons.extend(strand_polygon(run, k));
            }
            run_start = i;
        }
    }
    polygons
}

/// The counter-clockwise polygon of interval k along a run of slices: left ends upward,
/// right ends downward. None for a single slice (no area).
fn strand_polygon(run: &[Slice], k: usize) -> Option<Polygon> {
    if run.len() < 2 {
        return None;
    }
    let at = |a: f64, b: f64| WallPoint { a, b };
    let right = run.iter().map(|s| at(s.ivs[k].hi, s.b));
    let left = run.iter().rev().map(|s| at(s.ivs[k].lo, s.b));
    let vertices: Vec<WallPoint> = right.chain(left).collect();
    let n = vertices.len();
    let arc = EdgeKind::Complex {
        theta_start: f64::NAN,
        theta_end: f64::NAN,
    };
    let edges = vec![
        Edge {
            start: 0,
            kind: arc,
        },
        Edge {
            start: run.len() - 1,
            kind: arc,
        },
        Edge {
            start: run.len(),
            kind: arc,
        },
        Edge {
            start: n - 1,
            kind: arc,
        },
    ];
    Some(Polygon {
        vertices,
        edges,
        thetas: vec![f64::NAN; n],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn slice(b: f64, ivs: &[(f64, f64)]) -> Slice {
        Slice {
            b,
            ivs: ivs.iter().map(|&(lo, hi)| Interval { lo, hi }).collect(),
        }
    }

    /// A stable band [0, 4] × [0, 6] with the hole (1, 3) × (2, 4): the polygons cover the
    /// band around the hole, not the hole, and their areas add up to the band's minus the hole's.
    #[test]
    fn a_hole_is_left_out_of_the_polygons() {
        let one = [(0.0, 4.0)];
        let two = [(0.0, 1.0), (3.0, 4.0)];
        let slices = vec![
            slice(0.0, &one),
            slice(1.0, &one),
            slice(2.0, &one),
            slice(2.0 + 1e-12, &two),
            slice(3.0, &two),
            slice(4.0, &two),
            slice(4.0 + 1e-12, &one),
            slice(5.0, &one),
            slice(6.0, &one),
        ];
        let polys = joined(&slices);
        assert_eq!(polys.len(), 4);
        let inside = |a: f64, b: f64| polys.iter().any(|p| p.contains(WallPoint { a, b }));
        assert!(!inside(2.0, 3.0), "the hole");
        assert!(inside(0.5, 3.0) && inside(3.5, 3.0) && inside(2.0, 1.0) && inside(2.0, 5.0));
        let area: f64 = polys.iter().map(Polygon::area).sum();
        assert!((area - (24.0 - 4.0)).abs() < 1e-9, "{area}");
        assert!(polys.iter().all(|p| p.area() > 0.0), "counter-clockwise");
    }

    /// Slices whose ends move along straight lines need no bisection; a change in the number
    /// of intervals is located to the topology tolerance.
    #[test]
    fn bisection_locates_a_split() {
        let at = |b: f64| {
            if b < 0.3 {
                slice(b, &[(0.0, 1.0 + b)])
            } else {
                slice(b, &[(0.0, 0.4), (0.6, 1.0 + b)])
            }
        };
        let mut out = vec![at(0.0)];
        refine_between(&at, &at(0.0), &at(1.0), (1e-9, 1e-12), &mut out).unwrap();
        let split = out
            .windows(2)
            .find(|w| w[0].ivs.len() != w[1].ivs.len())
            .unwrap();
        assert!(split[0].b < 0.3 && split[1].b >= 0.3 && split[1].b - split[0].b <= 1e-12);
        assert!(out.len() < 100, "{} slices", out.len());
    }
}
