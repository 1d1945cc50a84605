//! The exact stable regions (`hapstab::region`) of the paper's loop and of general loops.
//! Expected values come from closed forms (pure mass), from the roots (spectral radius at
//! vertices) and from the independent grid method.

use crate::common::general::{family, general_loops};
use hapstab::boundary::{WallPoint, stable_stiffness_intervals};
use hapstab::map::{Axis, AxisRange, MapKind};
use hapstab::paper::NormalizedFamily;
use hapstab::paper::map::{MapSpec, compute_map};
use hapstab::region::{EdgeKind, StableRegion, stable_region};
use hapstab::schur_cohn::spectral_radius_schur;
use hapstab::stability::schur_stable;
use hapstab::{Normalized, PlantParams};

fn region(g: f64, dl: f64, d: usize) -> (NormalizedFamily, StableRegion) {
    let fam = NormalizedFamily::new(PlantParams::new(g, dl).unwrap(), d).unwrap();
    let r = stable_region(&fam).unwrap();
    (fam, r)
}

const CASES: &[(f64, f64, usize)] = &[
    (0.0, 0.0, 0),
    (0.001, 0.0, 0),
    (0.0, 0.015, 0),
    (0.001, 0.015, 0),
    (0.001, 0.015, 1),
    (0.0, 0.0, 2),
    (0.001, 0.015, 2),
    (0.001, 0.015, 10),
    (2.0, 1.0, 0),
    (1.0, 0.5, 1),
];

#[test]
fn vertices_lie_on_the_boundary() {
    for &(g, dl, d) in CASES {
        let (fam, r) = region(g, dl, d);
        assert!(!r.polygons.is_empty(), "γ={g} δ={dl} d={d}: empty");
        for poly in &r.polygons {
            assert!(poly.area() > 0.0);
            assert!(poly.edges.iter().all(|e| e.kind != EdgeKind::Window));
            let v = &poly.vertices;
            let n = v.len();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in v {
                lo = lo.min(p.a.min(p.b));
                hi = hi.max(p.a.max(p.b));
            }
            let size = hi - lo;
            let corners: Vec<WallPoint> = poly.corners().iter().map(|&i| v[i]).collect();
            let step = (n / 300).max(1);
            let mut c = vec![0.0; d + 4];
            let mut checked = 0;
            for &i in &poly.corners() {
                // Corners: p(e^{iθ}) = 0 at the vertex's θ. Where several roots meet on the
                // circle (e.g. the pure mass's double root at z = 1 at the origin) the
                // spectral radius is ill-conditioned (≈ ε^{1/2}), so check the residual.
                let p = v[i];
                let th = poly.thetas[i];
                let z = if th.is_nan() {
                    num_complex::Complex64::new(1.0, 0.0)
                } else {
                    num_complex::Complex64::from_polar(1.0, th)
                };
                let res = fam.eval(p.a, p.b, z).norm();
                assert!(res < 1e-12, "γ={g} δ={dl} d={d} corner {i}: |p| = {res}");
            }
            for i in (1..n).step_by(step) {
                let p = v[i];
                if poly.corners().contains(&i) {
                    continue;
                }
                // Within 1e-6 of the size of a corner where several roots meet on the circle,
                // the spectral radius from z-coefficients is ill-conditioned like the corner's
                // (ε^{1/2}): check the residual at the vertex's θ there, as at the corners.
                let at_corner = corners
                    .iter()
                    .any(|q| (q.a - p.a).hypot(q.b - p.b) < 1e-6 * size);
                if at_corner {
                    let z = num_complex::Complex64::from_polar(1.0, poly.thetas[i]);
                    let res = fam.eval(p.a, p.b, z).norm();
                    assert!(res < 1e-12, "γ={g} δ={dl} d={d} vertex {i}: |p| = {res}");
                    continue;
                }
                fam.coefficients_into(p.a, p.b, &mut c);
                let rho = spectral_radius_schur(&c);
                assert!(
                    (rho - 1.0).abs() < 1e-9,
                    "γ={g} δ={dl} d={d} vertex {i}: ρ = {rho}"
                );
                // inward/outward by 1e-6 of the size along the normal, away from corners
                let near_corner = corners
                    .iter()
                    .any(|q| (q.a - p.a).hypot(q.b - p.b) < 1e-4 * size);
                if near_corner {
                    continue;
                }
                let (a, b) = (v[(i + n - 1) % n], v[(i + 1) % n]);
                let (tx, ty) = (b.a - a.a, b.b - a.b);
                let l = tx.hypot(ty);
                let (nx, ny) = (-ty / l, tx / l); // left normal = inward for ccw
                let h = 1e-6 * size;
                fam.coefficients_into(p.a + h * nx, p.b + h * ny, &mut c);
                assert!(
                    schur_stable(&c),
                    "γ={g} δ={dl} d={d} vertex {i}: inward unstable"
                );
                fam.coefficients_into(p.a - h * nx, p.b - h * ny, &mut c);
                assert!(
                    !schur_stable(&c),
                    "γ={g} δ={dl} d={d} vertex {i}: outward stable"
                );
                checked += 1;
            }
            assert!(checked > 100, "{checked}");
        }
    }
}

#[test]
fn alpha_max_pure_mass_closed_form() {
    let (_, r) = region(0.0, 0.0, 0);
    let beta = 2.0 * 2f64.sqrt() - 2.0;
    let alpha = 2.0 * beta * (2.0 - beta) / (2.0 + beta);
    assert!(
        (r.a_max - alpha).abs() < 1e-12 * alpha,
        "{} vs {alpha}",
        r.a_max
    );
    assert!(
        (r.b_at_a_max - beta).abs() < 1e-12 * beta,
        "{} vs {beta}",
        r.b_at_a_max
    );
    // area: ∫₀² 2β(2 − β)/(2 + β) dβ = 12 − 16 ln 2
    let area = 12.0 - 16.0 * 2f64.ln();
    assert!((r.area - area).abs() < 1e-8 * area, "{} vs {area}", r.area);
}

#[test]
fn alpha_max_is_a_maximum_of_the_intervals() {
    // α_max agrees with the exact interval at its β, and no interval at nearby β exceeds it.
    for &(g, dl, d) in CASES {
        let (fam, r) = region(g, dl, d);
        let iv = stable_stiffness_intervals(&fam, r.b_at_a_max);
        let hi = iv.iter().map(|i| i.hi).fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (hi - r.a_max).abs() < 1e-10 * r.a_max.abs().max(1e-12),
            "γ={g} δ={dl} d={d}: {hi} vs {}",
            r.a_max
        );
        for k in 1..=20 {
            let db = r.b_at_a_max.abs().max(1e-3) * 0.02 * k as f64;
            for b in [r.b_at_a_max - db, r.b_at_a_max + db] {
                for i in stable_stiffness_intervals(&fam, b) {
                    assert!(
                        i.hi <= r.a_max * (1.0 + 1e-12) + 1e-300,
                        "β={b}: {} > {}",
                        i.hi,
                        r.a_max
                    );
                }
            }
        }
    }
}

#[test]
fn alpha_max_shrinks_with_delay_and_grows_with_damping() {
    for &g in &[0.0, 0.001] {
        for &dl in &[0.0, 0.005, 0.015, 0.1] {
            let am: Vec<f64> = (0..5).map(|d| region(g, dl, d).1.a_max).collect();
            assert!(am.windows(2).all(|w| w[1] < w[0]), "γ={g} δ={dl}: {am:?}");
        }
        for d in 0..4 {
            let am: Vec<f64> = [0.0, 0.005, 0.015, 0.1]
                .iter()
                .map(|&dl| region(g, dl, d).1.a_max)
                .collect();
            assert!(am.windows(2).all(|w| w[1] > w[0]), "γ={g} d={d}: {am:?}");
        }
    }
}

#[test]
fn grid_map_agrees_with_polygons() {
    for &(g, dl, d) in &[
        (0.001, 0.015, 0),
        (0.001, 0.015, 1),
        (0.0, 0.0, 2),
        (2.0, 1.0, 0),
    ] {
        let (_, r) = region(g, dl, d);
        let (mut a0, mut a1, mut b0, mut b1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in r.polygons.iter().flat_map(|p| &p.vertices) {
            a0 = a0.min(p.a);
            a1 = a1.max(p.a);
            b0 = b0.min(p.b);
            b1 = b1.max(p.b);
        }
        let (pa, pb) = (0.1 * (a1 - a0), 0.1 * (b1 - b0));
        let n = 200;
        let spec = MapSpec::new(
            AxisRange::new(Axis::Alpha, a0 - pa, a1 + pa, n).unwrap(),
            AxisRange::new(Axis::Beta, b0 - pb, b1 + pb, n).unwrap(),
            Normalized::new(0.0, 0.0, g, dl, d).unwrap(),
        )
        .unwrap();
        let m = compute_map(&spec, MapKind::Stability, &|_| {}).expect("map");
        // Polygon membership per grid row by scanline (even-odd rule on sorted crossings).
        let rows: Vec<Vec<f64>> = (0..n)
            .map(|iy| {
                let b = spec.y.value(iy);
                let mut xs = Vec::new();
                for poly in &r.polygons {
                    let v = &poly.vertices;
                    for k in 0..v.len() {
                        let (p, q) = (v[k], v[(k + 1) % v.len()]);
                        if (p.b > b) != (q.b > b) {
                            xs.push(p.a + (b - p.b) / (q.b - p.b) * (q.a - p.a));
                        }
                    }
                }
                xs.sort_by(f64::total_cmp);
                xs
            })
            .collect();
        let inside = |ix: i64, iy: i64| -> Option<bool> {
            if ix < 0 || iy < 0 || ix >= n as i64 || iy >= n as i64 {
                return None;
            }
            let a = spec.x.value(ix as usize);
            Some(rows[iy as usize].iter().filter(|&&x| x > a).count() % 2 == 1)
        };
        let mut compared = 0;
        for iy in 0..n as i64 {
            for ix in 0..n as i64 {
                let here = inside(ix, iy).unwrap_or(false);
                // skip cells within one cell of the boundary: any neighbour disagrees
                let near = (-1..=1).any(|dy| {
                    (-1..=1).any(|dx| inside(ix + dx, iy + dy).is_some_and(|o| o != here))
                });
                if near {
                    continue;
                }
                compared += 1;
                let p = WallPoint {
                    a: spec.x.value(ix as usize),
                    b: spec.y.value(iy as usize),
                };
                assert_eq!(
                    m.is_stable(ix as usize, iy as usize),
                    here,
                    "γ={g} δ={dl} d={d} at {p:?}"
                );
            }
        }
        assert!(compared > n * n * 8 / 10, "{compared}");
    }
}

#[test]
fn paper_range_and_large_delay() {
    for &g in &[0.0, 0.001] {
        for &dl in &[0.0, 0.015] {
            for d in 0..=2 {
                let (_, r) = region(g, dl, d);
                assert_eq!(r.polygons.len(), 1, "γ={g} δ={dl} d={d}");
                // the left boundary is the z = 1 line α = −γ
                let p = &r.polygons[0];
                assert!(p.edges.iter().any(|e| e.kind == EdgeKind::ZPlusOne));
                let amin = p.vertices.iter().map(|v| v.a).fold(f64::INFINITY, f64::min);
                assert!((amin + g).abs() < 1e-15, "{amin}");
            }
        }
    }
    let t = std::time::Instant::now();
    let (fam, r) = region(0.001, 0.015, 1000);
    let el = t.elapsed();
    assert!(el.as_secs_f64() < 2.0, "d = 1000 took {el:?}");
    assert!(r.a_max > 0.0 && r.a_max < 1e-3);
    let iv = stable_stiffness_intervals(&fam, r.b_at_a_max);
    assert!(iv.iter().any(|i| (i.hi - r.a_max).abs() < 1e-9 * r.a_max));
}

#[test]
fn chords_follow_the_curve_to_1e9_of_the_size() {
    // Between two consecutive vertices of a complex-pair arc, the curve point at the middle
    // angle lies within 1e-9 × (region size) of the chord.
    for &(g, dl, d) in CASES {
        let (fam, r) = region(g, dl, d);
        for poly in &r.polygons {
            let v = &poly.vertices;
            let ext = |f: fn(&WallPoint) -> f64| {
                let (lo, hi) = v
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                        (l.min(f(p)), h.max(f(p)))
                    });
                hi - lo
            };
            let size = ext(|p| p.a).max(ext(|p| p.b));
            let corners = poly.corners();
            let mut worst: f64 = 0.0;
            for i in 0..v.len() {
                let j = (i + 1) % v.len();
                let (ta, tb) = (poly.thetas[i], poly.thetas[j]);
                // both ends on the same arc (a line edge starts at a corner with a line kind)
                let on_line = poly
                    .edges
                    .iter()
                    .any(|e| e.start == i && !matches!(e.kind, EdgeKind::Complex { .. }));
                if on_line || !ta.is_finite() || !tb.is_finite() || (corners.contains(&j) && j == 0)
                {
                    continue;
                }
                let m = hapstab::boundary::curve_point(&fam, 0.5 * (ta + tb)).unwrap();
                let (a, b) = (v[i], v[j]);
                let (tx, ty) = (b.a - a.a, b.b - a.b);
                let l = tx.hypot(ty);
                if l == 0.0 {
                    continue;
                }
                let dev = ((m.a - a.a) * ty - (m.b - a.b) * tx).abs() / l;
                worst = worst.max(dev / size);
            }
            assert!(
                worst <= 1e-9,
                "γ={g} δ={dl} d={d}: chord deviation {worst:e} of the size"
            );
        }
    }
}

#[test]
fn near_nyquist_tends_to_the_triangle() {
    // δ = 0, d = 0, γ → π²: the region tends to the triangle α > −γ, α + 2β < 0, β > −γ/2
    // (Fig. 8, right), of area γ²: its vertices are (−γ, −γ/2), (−γ, γ/2), (γ, −γ/2).
    let pi2 = std::f64::consts::PI.powi(2);
    let mut last = f64::INFINITY;
    for eps in [1e-2, 1e-3, 1e-4, 1e-6] {
        let g = pi2 * (1.0 - eps);
        let (_, r) = region(g, 0.0, 0);
        assert_eq!(r.polygons.len(), 1, "ε={eps}");
        let gap = (r.area - g * g).abs() / (g * g);
        assert!(
            gap < last,
            "ε={eps}: relative area gap {gap} did not shrink"
        );
        last = gap;
    }
    assert!(last < 1e-3, "{last}");
}

/// Every vertex of a general loop's region lies on the boundary: ρ within 1e-9 of 1, and
/// 1e-6 of the region's size inward is stable, outward unstable (away from corners).
#[test]
fn general_region_vertices_lie_on_the_boundary() {
    use hapstab::stability::schur_stable;
    for (name, lp) in general_loops() {
        let fam = family(&lp);
        let r = hapstab::region::stable_region(&fam).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(!r.polygons.is_empty(), "{name}: empty");
        let mut c = vec![0.0; fam.degree() + 1];
        let mut checked = 0;
        for poly in &r.polygons {
            let v = &poly.vertices;
            let n = v.len();
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for p in v {
                lo = lo.min(p.a.min(p.b));
                hi = hi.max(p.a.max(p.b));
            }
            let size = hi - lo;
            let corners: Vec<usize> = poly.corners();
            for i in (0..n).step_by((n / 200).max(1)) {
                if corners.contains(&i) {
                    continue;
                }
                let p = v[i];
                // the radius as `check` computes it (roots near z = 1 polished in w = z − 1: a
                // vertex near θ = 0 has a pair of roots crowding z = 1, which the bisection on
                // the z-coefficients resolves only to about 1e-7)
                let rho = hapstab::stability::Analysis::of_family(&fam, p.a, p.b)
                    .unwrap()
                    .spectral_radius;
                assert!((rho - 1.0).abs() < 1e-9, "{name} vertex {i}: ρ = {rho}");
                let near_corner = corners
                    .iter()
                    .any(|&j| (v[j].a - p.a).hypot(v[j].b - p.b) < 1e-4 * size);
                if near_corner {
                    continue;
                }
                let (a, b) = (v[(i + n - 1) % n], v[(i + 1) % n]);
                let (tx, ty) = (b.a - a.a, b.b - a.b);
                let l = tx.hypot(ty);
                let (nx, ny) = (-ty / l, tx / l);
                let h = 1e-6 * size;
                fam.coefficients_into(p.a + h * nx, p.b + h * ny, &mut c);
                assert!(schur_stable(&c), "{name} vertex {i}: inward unstable");
                fam.coefficients_into(p.a - h * nx, p.b - h * ny, &mut c);
                assert!(!schur_stable(&c), "{name} vertex {i}: outward stable");
                checked += 1;
            }
        }
        assert!(checked > 50, "{name}: {checked}");
        // α_max is the top of the exact stable interval at its damping
        let iv = hapstab::boundary::stable_stiffness_intervals(&fam, r.b_at_a_max);
        let top = iv.iter().map(|i| i.hi).fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (top - r.a_max).abs() < 1e-9 * r.a_max.abs().max(1e-12),
            "{name}: α_max {} vs interval top {top}",
            r.a_max
        );
    }
}

/// The polygons agree with a direct grid of Schur–Cohn tests away from the boundary.
#[test]
fn general_region_agrees_with_a_grid() {
    use hapstab::boundary::WallPoint;
    use hapstab::stability::schur_stable;
    for (name, lp) in general_loops() {
        let fam = family(&lp);
        let r = hapstab::region::stable_region(&fam).unwrap();
        let pts = r.polygons.iter().flat_map(|p| p.vertices.iter());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in pts {
            x0 = x0.min(p.a);
            x1 = x1.max(p.a);
            y0 = y0.min(p.b);
            y1 = y1.max(p.b);
        }
        let (w, h) = (x1 - x0, y1 - y0);
        let n = 80;
        let mut c = vec![0.0; fam.degree() + 1];
        let mut stable_seen = 0;
        for i in 0..n {
            for j in 0..n {
                let a = x0 - 0.1 * w + 1.2 * w * (i as f64 + 0.37) / n as f64;
                let b = y0 - 0.1 * h + 1.2 * h * (j as f64 + 0.61) / n as f64;
                fam.coefficients_into(a, b, &mut c);
                let s = schur_stable(&c);
                stable_seen += s as usize;
                let inside = r.contains(WallPoint { a, b });
                assert_eq!(s, inside, "{name} at ({a}, {b})");
            }
        }
        // thin regions (long velocity windows) fill only a few per cent of their box
        assert!(stable_seen > n * n / 40, "{name}: {stable_seen}");
    }
}

/// The largest stable K within a damping band: the region's maximum when it lies inside,
/// otherwise the best of a dense scan of exact stable intervals over the band.
#[test]
fn stiffness_maximum_within_a_damping_band() {
    use hapstab::boundary::stable_stiffness_intervals;
    use hapstab::region::{alpha_max_within, stable_region};
    for (name, lp) in general_loops().into_iter().take(6) {
        let fam = family(&lp);
        let r = stable_region(&fam).unwrap();
        // a band around the maximum returns it
        let b = r.b_at_a_max;
        let p = alpha_max_within(&fam, &r, b - 0.01, b + 0.01)
            .unwrap()
            .unwrap();
        assert_eq!((p.a, p.b), (r.a_max, b), "{name}");
        // a band below the maximum: compare with a scan of exact intervals
        let (lo, hi) = (b - 0.5 * b.abs().max(0.05), b - 0.1 * b.abs().max(0.05));
        let Some(p) = alpha_max_within(&fam, &r, lo, hi).unwrap() else {
            continue;
        };
        assert!(p.b >= lo && p.b <= hi, "{name}: {p:?}");
        let scan = (0..=400)
            .map(|i| lo + (hi - lo) * i as f64 / 400.0)
            .flat_map(|bb| {
                stable_stiffness_intervals(&fam, bb)
                    .into_iter()
                    .map(|iv| iv.hi)
            })
            .filter(|h| h.is_finite())
            .fold(f64::NEG_INFINITY, f64::max);
        let tol = 1e-9 * r.a_max.abs();
        assert!(p.a >= scan - tol, "{name}: {} < scan {scan}", p.a);
        // and it is attained: the exact interval at its damping reaches it
        let top = stable_stiffness_intervals(&fam, p.b)
            .iter()
            .map(|iv| iv.hi)
            .fold(f64::NEG_INFINITY, f64::max);
        assert!(
            (top - p.a).abs() <= 1e-7 * r.a_max.abs(),
            "{name}: {top} vs {}",
            p.a
        );
    }
}
