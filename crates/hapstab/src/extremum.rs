//! Extrema of a smooth function of one angle sampled on a grid: the peak gain, the stability
//! margin min |1 + L|, the passivity requirement's maximum over frequency.
//!
//! The three steps every such search shares:
//! 1. [`merge_grid`] sorts the angles and merges those that agree to rounding (grids built
//!    from several families — uniform, geometric, around poles — hold the same angle twice,
//!    one ulp apart, and two samples of the same point in rounding noise fake an extremum
//!    whose bracket misses the real one);
//! 2. a local extremum of the samples brackets a stationary point between its neighbours;
//! 3. [`refine_max`] refines it by Brent's method ([`brent_max`]: parabolic steps, golden
//!    section where they fail) and, when the search lands
//!    on an end of its bracket (no stationary point inside: the samples were in noise, or two
//!    extrema shared the cell), moves the bracket one cell that way and searches again, so the
//!    point returned is a stationary point or an end of the whole interval.

/// Golden-section iterations at most: the bracket shrinks by 0.618 each, from two grid cells
/// to 1e-13 of the angle in about 60.
const GOLDEN_ITERATIONS: usize = 80;

/// Brent's method's iterations at most (it needs about 10–20 for a smooth maximum; its
/// golden-section fallback halves the bracket's width every two).
const BRENT_ITERATIONS: usize = 100;

/// 1 − 1/φ: the golden-section step of Brent's method.
const GOLDEN_STEP: f64 = 0.381_966_011_250_105_1;

/// Angles closer than this (relative) are one point of the grid.
pub const MERGE_REL: f64 = 1e-12;

/// How many cells [`refine_max`] may move its bracket.
const MAX_SHIFTS: usize = 16;

/// Golden-section search for the maximum of f on [lo, hi] down to a bracket of width tol:
/// (argmax, max) (Kiefer 1953; Press et al., *Numerical Recipes* §10.2).
pub fn golden_max(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, tol: f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let mut x1 = hi - r * (hi - lo);
    let mut x2 = lo + r * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..GOLDEN_ITERATIONS {
        if hi - lo <= tol {
            break;
        }
        if f1 >= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - r * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + r * (hi - lo);
            f2 = f(x2);
        }
    }
    if f1 >= f2 { (x1, f1) } else { (x2, f2) }
}

/// Brent's method for the maximum of f on [lo, hi] down to a bracket of about width tol:
/// (argmax, max). Parabolic interpolation through the three best points, a golden-section
/// step where the parabola's vertex falls outside the bracket or the steps stop shrinking
/// (Brent 1973, *Algorithms for Minimization without Derivatives*, ch. 5, `localmin`; Press
/// et al., *Numerical Recipes* §10.3).
pub fn brent_max(f: impl Fn(f64) -> f64, lo: f64, hi: f64, tol: f64) -> (f64, f64) {
    let g = |x: f64| -f(x);
    let (mut a, mut b) = (lo, hi);
    let mut x = a + GOLDEN_STEP * (b - a);
    let (mut w, mut v) = (x, x);
    let mut fx = g(x);
    let (mut fw, mut fv) = (fx, fx);
    let (mut d, mut e) = (0.0_f64, 0.0_f64);
    for _ in 0..BRENT_ITERATIONS {
        let xm = 0.5 * (a + b);
        let tol1 = 0.25 * tol + f64::EPSILON * x.abs();
        let tol2 = 2.0 * tol1;
        if (x - xm).abs() <= tol2 - 0.5 * (b - a) {
            break;
        }
        let mut parabolic = false;
        if e.abs() > tol1 {
            let r = (x - w) * (fx - fv);
            let q0 = (x - v) * (fx - fw);
            let mut p = (x - v) * q0 - (x - w) * r;
            let mut q = 2.0 * (q0 - r);
            if q > 0.0 {
                p = -p;
            }
            q = q.abs();
            let e_old = e;
            e = d;
            if p.abs() < (0.5 * q * e_old).abs() && p > q * (a - x) && p < q * (b - x) {
                d = p / q;
                let u = x + d;
                if u - a < tol2 || b - u < tol2 {
                    d = tol1.copysign(xm - x);
                }
                parabolic = true;
            }
        }
        if !parabolic {
            e = if x >= xm { a - x } else { b - x };
            d = GOLDEN_STEP * e;
        }
        let u = if d.abs() >= tol1 {
            x + d
        } else {
            x + tol1.copysign(d)
        };
        let fu = g(u);
        if fu <= fx {
            if u >= x {
                a = x;
            } else {
                b = x;
            }
            (v, fv, w, fw, x, fx) = (w, fw, x, fx, u, fu);
        } else {
            if u < x {
                a = u;
            } else {
                b = u;
            }
            if fu <= fw || w == x {
                (v, fv, w, fw) = (w, fw, u, fu);
            } else if fu <= fv || v == x || v == w {
                (v, fv) = (u, fu);
            }
        }
    }
    (x, -fx)
}

/// Sorts the angles and merges those within [`MERGE_REL`] (relative) of the previous one.
pub fn merge_grid(ts: &mut Vec<f64>) {
    ts.retain(|t| t.is_finite());
    ts.sort_by(f64::total_cmp);
    ts.dedup_by(|x, y| (*x - *y).abs() <= MERGE_REL * x.abs().max(y.abs()));
}

/// [`merge_grid`] of two grids that are already merged (sorted, finite, without near
/// duplicates), in one linear pass: the same grid.
pub fn merge_sorted_grids(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out: Vec<f64> = Vec::with_capacity(a.len() + b.len());
    let (mut i, mut j) = (0, 0);
    while i < a.len() || j < b.len() {
        let take_a = j == b.len() || (i < a.len() && a[i].total_cmp(&b[j]).is_le());
        let t = if take_a { a[i] } else { b[j] };
        if take_a {
            i += 1;
        } else {
            j += 1;
        }
        match out.last() {
            Some(&x) if (t - x).abs() <= MERGE_REL * x.abs().max(t.abs()) => {}
            _ => out.push(t),
        }
    }
    out
}

/// The indices of the local maxima of the samples: vs[i] ≥ both neighbours and strictly above
/// one of them (a plateau of equal samples is no extremum).
pub fn sample_maxima(vs: &[f64]) -> impl Iterator<Item = usize> + '_ {
    (1..vs.len().saturating_sub(1)).filter(move |&i| {
        let (l, c, r) = (vs[i - 1], vs[i], vs[i + 1]);
        c >= l && c >= r && (c > l || c > r)
    })
}

/// How much more than its estimate a local maximum may rise above its sample, in
/// [`may_exceed`].
const RISE_SAFETY: f64 = 4.0;

/// Whether the local maximum of the samples at i (ts[i − 1] < ts[i] < ts[i + 1]) may rise
/// above `best` between its neighbours: the parabola through the three samples estimates the
/// rise r of the maximum above vs[i], and the maximum is taken to be at most
/// vs[i] + [`RISE_SAFETY`]·(r + c) with c = vs[i] − min(vs[i − 1], vs[i + 1]), the
/// samples' contrast. A parabola's maximum lies within its bracket's nearer half, so it rises
/// at most c above the sample; a V-shaped peak (a root near the unit circle) at most 2r. A
/// maximum in rounding noise (r and c at an ulp) is thus never refined unless its sample
/// already ties `best`.
pub fn may_exceed(ts: &[f64], vs: &[f64], i: usize, best: f64) -> bool {
    if i == 0 || i + 1 >= vs.len() {
        return true;
    }
    let (t0, t1, t2) = (ts[i - 1], ts[i], ts[i + 1]);
    let (v0, v1, v2) = (vs[i - 1], vs[i], vs[i + 1]);
    // divided differences of the interpolating parabola v = v1 + s1·(t − t1) + s2·(t − t1)(t − t0)
    let d01 = (v1 - v0) / (t1 - t0);
    let d12 = (v2 - v1) / (t2 - t1);
    let curv = (d12 - d01) / (t2 - t0);
    let slope = d01 + curv * (t1 - t0);
    let rise = if curv < 0.0 {
        // vertex of the parabola: v1 − slope²/(4·curv)
        -slope * slope / (4.0 * curv)
    } else {
        f64::INFINITY
    };
    let contrast = v1 - v0.min(v2);
    v1 + RISE_SAFETY * (rise + contrast) >= best
}

/// The local maximum of f bracketed by the samples ts[i − 1] < ts[i] < ts[i + 1], refined by
/// Brent's method ([`brent_max`]) to `rel` of the angle; the bracket moves by one cell (at most
/// [`MAX_SHIFTS`] times) while the search lands on one of its inner ends (module doc).
/// Returns (argmax, max), never below the sample f(ts[i]).
pub fn refine_max(f: impl Fn(f64) -> f64, ts: &[f64], i: usize, rel: f64) -> (f64, f64) {
    if ts.len() < 3 {
        return ts
            .iter()
            .map(|&t| (t, f(t)))
            .fold(
                (f64::NAN, f64::NEG_INFINITY),
                |b, x| if x.1 > b.1 { x } else { b },
            );
    }
    let last = ts.len() - 1;
    let mut i = i.clamp(1, last - 1);
    let mut best = (ts[i], f(ts[i]));
    for _ in 0..=MAX_SHIFTS {
        let (lo, hi) = (ts[i - 1], ts[i + 1]);
        let tol = rel * lo.abs().max(hi.abs()).max(f64::MIN_POSITIVE);
        let (t, v) = brent_max(&f, lo, hi, tol);
        if v >= best.1 {
            best = (t, v);
        }
        let near = 4.0 * tol;
        if t - lo <= near && i > 1 {
            i -= 1;
        } else if hi - t <= near && i + 1 < last {
            i += 1;
        } else {
            break;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merging_two_merged_grids_equals_merging_their_union() {
        // two grids with shared points, near duplicates (1e-13 apart) and interleaving
        let mut a: Vec<f64> = (0..200)
            .map(|i| (i as f64 * 0.37).sin().abs() * 3.0)
            .collect();
        let mut b: Vec<f64> = (0..150)
            .map(|i| (i as f64 * 0.11).cos().abs() * 3.0)
            .collect();
        b.extend(a.iter().take(20).map(|x| x * (1.0 + 1e-13)));
        b.extend(a.iter().skip(20).take(20).copied());
        merge_grid(&mut a);
        merge_grid(&mut b);
        let mut union = [a.clone(), b.clone()].concat();
        merge_grid(&mut union);
        assert_eq!(merge_sorted_grids(&a, &b), union);
        assert_eq!(merge_sorted_grids(&b, &a), union);
        assert_eq!(merge_sorted_grids(&a, &[]), a);
    }

    #[test]
    fn golden_finds_the_vertex_of_a_parabola() {
        let (t, v) = golden_max(|x| 2.0 - (x - 0.3).powi(2), 0.0, 1.0, 1e-13);
        assert!((t - 0.3).abs() < 1e-7, "{t}");
        assert!((v - 2.0).abs() < 1e-14, "{v}");
    }

    #[test]
    fn brent_finds_the_vertex_of_a_parabola_and_of_a_quartic() {
        let (t, v) = brent_max(|x| 2.0 - (x - 0.3).powi(2), 0.0, 1.0, 1e-13);
        assert!((t - 0.3).abs() < 1e-7, "{t}");
        assert!((v - 2.0).abs() < 1e-14, "{v}");
        // a flat (quartic) top and a maximum at the bracket's end
        let (t, v) = brent_max(|x| 1.0 - (x - 0.7).powi(4), 0.0, 1.0, 1e-13);
        assert!((t - 0.7).abs() < 1e-3 && (v - 1.0).abs() < 1e-12, "{t} {v}");
        let (t, _) = brent_max(|x| x, 0.0, 1.0, 1e-13);
        assert!(1.0 - t < 1e-12, "{t}");
    }

    #[test]
    fn a_maximum_that_cannot_reach_the_best_is_ruled_out() {
        // samples of 1 − (t − 0.33)²: the maximum 1 lies 1.1e-3 above the sample at 0.3
        let f = |t: f64| 1.0 - (t - 0.33).powi(2);
        let ts = [0.0, 0.1, 0.3, 0.5];
        let vs: Vec<f64> = ts.iter().map(|&t| f(t)).collect();
        assert!(may_exceed(&ts, &vs, 2, 1.0 - 1e-12));
        assert!(may_exceed(&ts, &vs, 2, 1.003));
        assert!(!may_exceed(&ts, &vs, 2, 1.25));
        // a V-shaped peak 1 − |t − 0.33|, its vertex midway to the far neighbour
        let g = |t: f64| 1.0 - (t - 0.33).abs();
        let ts = [0.3 - 1e-9, 0.3, 0.36];
        let vs: Vec<f64> = ts.iter().map(|&t| g(t)).collect();
        assert!(may_exceed(&ts, &vs, 1, 1.0));
        // samples in rounding noise cannot beat a better value found elsewhere
        let vs = [0.5, 0.5 + 1e-16, 0.5];
        assert!(!may_exceed(&[1.0, 2.0, 3.0], &vs, 1, 0.6));
        assert!(may_exceed(&[1.0, 2.0, 3.0], &vs, 1, 0.5));
    }

    #[test]
    fn merging_drops_an_angle_repeated_one_ulp_apart() {
        let a = std::f64::consts::PI / 7.0;
        let mut ts = vec![0.5, a, f64::from_bits(a.to_bits() + 1), 0.1, 0.5];
        merge_grid(&mut ts);
        assert_eq!(ts, vec![0.1, a, 0.5]);
    }

    #[test]
    fn a_bracket_that_misses_the_peak_moves_to_it() {
        // Samples in noise: the sample maximum at index 1 is bracketed by [0, 0.2], the peak of
        // f lies at 0.33 in the next cell.
        let f = |x: f64| -(x - 0.33).powi(2);
        let ts = [0.0, 0.1, 0.2, 0.4, 0.6];
        let (t, v) = refine_max(f, &ts, 1, 1e-13);
        assert!((t - 0.33).abs() < 1e-7, "{t}");
        assert!(v.abs() < 1e-14, "{v}");
    }

    #[test]
    fn a_grid_of_two_angles_gives_the_better_sample() {
        assert_eq!(refine_max(|x: f64| x, &[0.1, 0.2], 0, 1e-13), (0.2, 0.2));
    }

    #[test]
    fn a_peak_at_the_end_of_the_interval_is_returned_there() {
        let f = |x: f64| x;
        let ts = [0.0, 0.1, 0.2, 0.3];
        let (t, _) = refine_max(f, &ts, 1, 1e-13);
        assert!((t - 0.3).abs() < 1e-12, "{t}");
    }
}
