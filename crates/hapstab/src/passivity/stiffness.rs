//! The largest passive stiffness: over every wall damping, and at one damping.
//!
//! # Over every damping: a convex minimization in one variable
//!
//! b_required(K, B) is convex and positively homogeneous in (K, B) (the [parent module](super)),
//! so along the wall K = 1 N/m, B = β the requirement h(β) = b_required(1, β) is a convex
//! function of β, and the wall (K, β·K) is passive up to K = b/h(β). The largest passive
//! stiffness is therefore b / min_β h(β), reached at B = β*·K, where β* minimizes h (over the
//! β with W(1) = K·(1 + β·V(1)) ≥ 0). h is the maximum over θ of convex functions f_θ(β), so
//! the slope of the maximizing f_θ at β is a subgradient of h there (Danskin), and every
//! tangent of every f_θ lies below h. The minimum is bracketed by two samples whose slopes
//! have opposite signs; the two tangents meet at a β whose value is a certified lower bound
//! of min h, and the next sample is taken there (the cutting-plane step: at a kink where two
//! frequencies bind, the tangents of the two smooth branches converge on it in a few steps;
//! at a smooth minimum it is a secant step on the slope), with a halving of the bracket
//! whenever the tangent step does not halve it. The search stops when the best sample is
//! within a few ulps of the lower bound: the minimum is then certified to rounding.
//!
//! Inside the bracket the requirement binds near the frequencies where it binds at the
//! bracket's ends, so those samples screen only the grid cells around them (a lower bound of
//! h, its tangents still below h); the best one is then evaluated on the whole grid, and
//! should it bind elsewhere after all, the search inside the bracket is repeated on the whole
//! grid.

use std::ops::Range;

use super::requirement::SampledWall;
use crate::params::Wall;

/// The bracket search stops when the best sample exceeds the tangents' lower bound by at
/// most this fraction: min h is then known to rounding.
const GAP_REL: f64 = 1e-14;

/// Samples of the minimization at most (bracketing included); each costs one
/// [`SampledWall::required_damping`]. About 10–25 are taken.
const MAX_SAMPLES: usize = 200;

/// Grid cells on each side of a binding frequency that a sample inside the bracket screens.
const WINDOW: usize = 8;

/// Bisection steps for the largest passive K at a damping: from a bracket of any size down to
/// one ulp takes at most about 1100 halvings of the exponent range; 200 is plenty for the
/// brackets found by doubling.
const BISECTION_STEPS: usize = 200;

/// One sample of h(β) = b_required(1 N/m, β): its value and a subgradient.
#[derive(Debug, Clone, Copy)]
struct Sample {
    beta: f64,
    h: f64,
    slope: f64,
    /// The frequency θ = ωT where the requirement binds.
    theta: f64,
}

/// The largest passive stiffness for device damping b, and the damping where it is reached
/// (exact, without building the region's polygon; module doc). None when b <= 0 or the
/// requirement cannot be evaluated; K infinite when the region is unbounded in K.
pub fn passive_k_max(sw: &SampledWall, b: f64) -> Option<Wall> {
    if !(b > 0.0 && b.is_finite()) {
        return None;
    }
    match min_requirement(sw)? {
        Some(m) if m.h > 0.0 => {
            let k = b / m.h;
            Some(Wall {
                stiffness: k,
                damping: m.beta * k,
            })
        }
        _ => Some(Wall {
            stiffness: f64::INFINITY,
            damping: f64::NAN,
        }),
    }
}

/// h and its subgradient at β, screened on the whole grid or on some of its cells, with the
/// grid indices where the requirement peaks.
fn sample_in(sw: &SampledWall, beta: f64, cells: Option<&[Range<usize>]>) -> (Sample, Vec<usize>) {
    let wall = Wall {
        stiffness: 1.0,
        damping: beta,
    };
    let r = match cells {
        None => sw.required_damping_screened(wall),
        Some(c) => sw.required_damping_within(wall, c),
    };
    let s = Sample {
        beta,
        h: r.value,
        slope: sw.required_damping_slope_at(wall, r.theta),
        theta: r.theta,
    };
    (s, r.refined)
}

/// h and its subgradient at β on the whole grid.
fn sample(sw: &SampledWall, beta: f64) -> Sample {
    sample_in(sw, beta, None).0
}

/// The grid cells around the peaks of two samples and between their binding frequencies,
/// sorted and merged.
fn cells_near(sw: &SampledWall, ends: [&(Sample, Vec<usize>); 2]) -> Vec<Range<usize>> {
    let n = sw.grid_len();
    let around = |a: usize, b: usize| a.saturating_sub(WINDOW)..(b + WINDOW + 1).min(n);
    let mut cells: Vec<Range<usize>> = ends
        .iter()
        .flat_map(|(_, peaks)| peaks.iter().map(|&i| around(i, i)))
        .collect();
    // the binding frequency moves between the ends' as the damping does
    let (a, b) = (
        sw.grid_index(ends[0].0.theta),
        sw.grid_index(ends[1].0.theta),
    );
    cells.push(around(a.min(b), a.max(b)));
    cells.sort_by_key(|r| r.start);
    let mut merged: Vec<Range<usize>> = Vec::with_capacity(cells.len());
    for r in cells {
        match merged.last_mut() {
            Some(m) if r.start <= m.end => m.end = m.end.max(r.end),
            _ => merged.push(r),
        }
    }
    merged
}

/// The β range where W(1) = 1 + β·V(1) ≥ 0.
fn admissible(sw: &SampledWall) -> (f64, f64) {
    let v1 = sw.dc_velocity();
    if v1 > 0.0 {
        (-1.0 / v1, f64::INFINITY)
    } else if v1 < 0.0 {
        (f64::NEG_INFINITY, -1.0 / v1)
    } else {
        (f64::NEG_INFINITY, f64::INFINITY)
    }
}

/// The minimizing sample of h over the admissible β: Some(None) when h reaches 0 or below
/// (the region is unbounded in K); None when h is not a number.
fn min_requirement(sw: &SampledWall) -> Option<Option<Sample>> {
    let (start, peaks) = sample_in(sw, 0.0, None);
    if start.h.is_nan() || start.slope.is_nan() {
        return None;
    }
    if start.h <= 0.0 {
        return Some(None);
    }
    if start.slope == 0.0 {
        return Some(Some(start));
    }
    Some(match bracket(sw, (start, peaks)) {
        Bracket::Pair(lo, hi) => {
            let near = cutting_planes(sw, lo.clone(), hi.clone(), true)?;
            let whole = sample(sw, near.beta);
            if whole.h <= near.h * (1.0 + GAP_REL) {
                Some(whole)
            } else {
                cutting_planes(sw, lo, hi, false)
            }
        }
        Bracket::End(end) => Some(end),
        Bracket::Unbounded => None,
    })
}

/// The outcome of the search for a bracket of the minimum.
enum Bracket {
    /// Samples with slopes of opposite signs (negative, then positive), with their peaks.
    Pair((Sample, Vec<usize>), (Sample, Vec<usize>)),
    /// The minimum lies at the admissible range's end (or at a sample of zero slope).
    End(Sample),
    /// h reaches 0 (the region is unbounded in K).
    Unbounded,
}

/// Steps from the start downhill, doubling, until the slope turns (the step starts at the
/// period: B ~ K·T is the scale of the walls that bind).
fn bracket(sw: &SampledWall, first: (Sample, Vec<usize>)) -> Bracket {
    let start = first.0;
    let (lo_end, hi_end) = admissible(sw);
    let dir = if start.slope < 0.0 { 1.0 } else { -1.0 };
    let mut step = sw.period();
    let mut last = first;
    for _ in 0..MAX_SAMPLES {
        let beta = (start.beta + dir * step).clamp(lo_end, hi_end);
        let (s, peaks) = sample_in(sw, beta, None);
        if s.h.is_nan() || s.h <= 0.0 || !beta.is_finite() {
            return Bracket::Unbounded;
        }
        if s.slope == 0.0 {
            return Bracket::End(s);
        }
        if (s.slope > 0.0) == (dir > 0.0) {
            return if dir > 0.0 {
                Bracket::Pair(last, (s, peaks))
            } else {
                Bracket::Pair((s, peaks), last)
            };
        }
        if beta == lo_end || beta == hi_end {
            return Bracket::End(s);
        }
        last = (s, peaks);
        step *= 2.0;
    }
    // still descending after 2^200 periods: the supremum is approached at infinity; the
    // farthest sample is reported (a passive wall, the largest K found)
    Bracket::End(last.0)
}

/// The search of the module doc inside a bracket (lo.slope < 0 < hi.slope): secant steps on
/// the slope through the two latest samples where h is smooth, the tangents' meeting point
/// at a kink, a halving when two steps did not halve the gap between the best sample and
/// the lower bound; until that gap certifies the best sample. With `near`, each sample
/// screens only the grid cells around the peaks of the bracket's ends.
fn cutting_planes(
    sw: &SampledWall,
    mut lo: (Sample, Vec<usize>),
    mut hi: (Sample, Vec<usize>),
    near: bool,
) -> Option<Sample> {
    let mut best = if lo.0.h <= hi.0.h { lo.0 } else { hi.0 };
    let (mut prev, mut last) = (lo.0, hi.0);
    let mut gaps = [f64::INFINITY; 2];
    for _ in 0..MAX_SAMPLES {
        let (l, h) = (lo.0, hi.0);
        let (beta_x, lower) = tangents_meet(l, h);
        let gap = best.h - lower;
        if gap <= GAP_REL * best.h {
            break;
        }
        let stalled = gap > 0.5 * gaps[0];
        gaps = [gaps[1], gap];
        let step = if same_branch(sw, prev, last) {
            slope_secant(prev, last)
        } else {
            beta_x
        };
        let beta = if !stalled && step > l.beta && step < h.beta {
            step
        } else {
            0.5 * (l.beta + h.beta)
        };
        if beta <= l.beta || beta >= h.beta {
            break; // the bracket is down to adjacent numbers
        }
        let cells = near.then(|| cells_near(sw, [&lo, &hi]));
        let (s, peaks) = sample_in(sw, beta, cells.as_deref());
        if s.h.is_nan() || s.h <= 0.0 {
            return None;
        }
        if s.h < best.h {
            best = s;
        }
        if s.slope < 0.0 {
            lo = (s, peaks);
        } else if s.slope > 0.0 {
            hi = (s, peaks);
        } else {
            return Some(s);
        }
        (prev, last) = (last, s);
    }
    Some(best)
}

/// True when the requirement binds at nearby frequencies at lo and hi (within a few cells
/// of the grid the maximum is screened on): then h is smooth between them and the slope is
/// interpolated; at a kink, where two frequencies bind, the tangents are.
fn same_branch(sw: &SampledWall, lo: Sample, hi: Sample) -> bool {
    (lo.theta - hi.theta).abs() <= 4.0 * sw.grid_step()
}

/// The zero of the slope's linear interpolation through two samples (the secant step on
/// h'); NaN when their slopes are equal.
fn slope_secant(a: Sample, b: Sample) -> f64 {
    a.beta - a.slope * (b.beta - a.beta) / (b.slope - a.slope)
}

/// Where the tangents at lo and hi meet, and their common value there: a lower bound of
/// min h (both tangents lie below h everywhere).
fn tangents_meet(lo: Sample, hi: Sample) -> (f64, f64) {
    let beta = (hi.h - lo.h + lo.slope * lo.beta - hi.slope * hi.beta) / (lo.slope - hi.slope);
    (beta, lo.h + lo.slope * (beta - lo.beta))
}

/// The largest passive stiffness K in N/m at a given damping B (None when no K >= −B·V(1) is
/// passive there): b_required is convex in K, so it crosses b once; found by bisection to
/// full precision.
pub fn k_max_passive_at(sw: &SampledWall, b: f64, damping: f64) -> Option<f64> {
    let k_lo = -damping * sw.dc_velocity();
    let need = |k: f64| {
        sw.required_damping(Wall {
            stiffness: k,
            damping,
        })
        .b_required
    };
    let at_lo = need(k_lo);
    if at_lo.is_nan() || at_lo >= b {
        return None;
    }
    let mut step = 2.0 * b / sw.period();
    let mut k_hi = k_lo + step;
    let mut guard = 0;
    while need(k_hi) < b {
        step *= 2.0;
        k_hi = k_lo + step;
        guard += 1;
        if guard > 2000 || !k_hi.is_finite() {
            return Some(f64::INFINITY);
        }
    }
    let mut lo = k_lo;
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + k_hi);
        if mid <= lo || mid >= k_hi {
            break;
        }
        if need(mid) < b {
            lo = mid;
        } else {
            k_hi = mid;
        }
    }
    Some(lo)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::{Delay, Loop, VelocityEstimator};
    use crate::params::{Arm, Device, Effective};

    fn wall_loop(period: f64, delay_time: f64, velocity: VelocityEstimator) -> SampledWall {
        let e = Effective::combine(Device::PHANTOM_LIKE, Arm::TYPICAL).expect("valid");
        let lp = Loop::paper(e, period, 0).expect("valid");
        let delay = Delay::from_time(delay_time, period).expect("valid");
        let lp = Loop::new(lp.plant.clone(), period, delay, velocity).expect("valid");
        SampledWall::new(&lp).expect("stable filter")
    }

    fn need(sw: &SampledWall, k: f64, b: f64) -> f64 {
        sw.required_damping(Wall {
            stiffness: k,
            damping: b,
        })
        .b_required
    }

    #[test]
    fn colgate_and_schenkel_closed_form_without_delay() {
        // backward difference, no delay: b > KT/2 + |B| (eq. 28), so K_max = 2b/T at B = 0
        for (t, b) in [(1e-3, 2.0), (1e-4, 0.3), (5e-3, 7.5)] {
            let sw = wall_loop(t, 0.0, VelocityEstimator::Backward);
            let w = passive_k_max(&sw, b).expect("bounded");
            let exact = 2.0 * b / t;
            assert!(
                (w.stiffness - exact).abs() <= 1e-14 * exact,
                "{} vs {exact}",
                w.stiffness
            );
            assert!(w.damping.abs() <= 1e-12 * b, "{}", w.damping);
        }
    }

    #[test]
    fn backward_difference_behind_whole_samples_of_delay_closed_form() {
        // backward difference behind d samples: K_max = (2b/T)·tan(π/(4(d + 1))) (d = 0 is
        // eq. 28's 2b/T; d = 1, 2 give (√2 − 1) and (2 − √3) times it). Independently, the
        // linear program max K s.t. (C–S) on 4·10⁵ frequencies (scipy's HiGHS, T = 1 ms,
        // b = 1.5 Ns/m) gives 1242.6406878 and 803.8475774 N/m for d = 1, 2 (1e-9 from the
        // closed form, the grid's error)
        for (t, b) in [(1e-3, 1.5), (2e-4, 4.0)] {
            for d in 1..=8 {
                let sw = wall_loop(t, d as f64 * t, VelocityEstimator::Backward);
                let k = passive_k_max(&sw, b).expect("bounded").stiffness;
                let exact = 2.0 * b / t * (std::f64::consts::PI / (4.0 * (d as f64 + 1.0))).tan();
                assert!(
                    (k - exact).abs() <= 1e-13 * exact,
                    "d = {d}: {k} vs {exact}"
                );
            }
        }
    }

    #[test]
    fn the_largest_stiffness_is_on_the_boundary_and_no_direction_beats_it() {
        let cases = [
            (1e-3, 0.0020408, VelocityEstimator::Backward),
            (1e-3, 0.0091837, VelocityEstimator::Backward),
            (
                1e-4,
                0.00033,
                VelocityEstimator::LowPass { cutoff_hz: 100.0 },
            ),
            (5e-3, 0.0131, VelocityEstimator::LowPass { cutoff_hz: 30.0 }),
            (1e-3, 0.0047, VelocityEstimator::Average { samples: 5 }),
        ];
        let b = 2.0;
        for (t, td, v) in cases {
            let sw = wall_loop(t, td, v);
            let w = passive_k_max(&sw, b).expect("bounded");
            let (k, bb) = (w.stiffness, w.damping);
            // on the boundary: passive just inside, not just outside (along the ray)
            assert!(
                need(&sw, k * (1.0 - 1e-9), bb * (1.0 - 1e-9)) < b,
                "{td}: inside"
            );
            assert!(
                need(&sw, k * (1.0 + 1e-9), bb * (1.0 + 1e-9)) > b,
                "{td}: outside"
            );
            // no wall damping gives more: b/h(β) over a dense β grid around the optimum and far
            let beta = bb / k;
            for i in -2000..=2000 {
                let x = beta + (i as f64) * 1e-3 * t + (i as f64).powi(3) * 1e-9 * t;
                let kk = b / need(&sw, 1.0, x);
                assert!(kk <= k * (1.0 + 1e-12), "{td}: β = {x} gives {kk} > {k}");
            }
        }
    }

    #[test]
    fn the_region_polygon_lies_within_the_largest_stiffness() {
        let sw = wall_loop(
            1e-3,
            0.0047,
            VelocityEstimator::LowPass { cutoff_hz: 100.0 },
        );
        let w = passive_k_max(&sw, 2.0).expect("bounded");
        let region = super::super::passive_region(&sw, 2.0).expect("region");
        let top = region
            .vertices
            .iter()
            .map(|v| v.stiffness)
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            top <= w.stiffness * (1.0 + 1e-12),
            "{top} > {}",
            w.stiffness
        );
        assert!(
            top >= w.stiffness * (1.0 - 1e-4),
            "{top} far below {}",
            w.stiffness
        );
        assert_eq!(region.k_max, w.stiffness);
    }

    #[test]
    fn no_device_damping_has_no_passive_stiffness() {
        let sw = wall_loop(1e-3, 0.0, VelocityEstimator::Backward);
        assert_eq!(passive_k_max(&sw, 0.0), None);
        assert_eq!(passive_k_max(&sw, f64::NAN), None);
    }
}
