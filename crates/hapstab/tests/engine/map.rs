//! The grid maps of any loop over its wall (`hapstab::map`): against the exact region, and
//! the maps by value and by point against the uniform grid.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use crate::common::general::{family, general_loops, two_mass_held_by, with};
use hapstab::map::{Axis, AxisRange, MapKind, wall_map, wall_map_points, wall_map_values};
use hapstab::params::Arm;
use hapstab::{AffineFamily, Delay, VelocityEstimator};

/// The two-mass device held by the typical arm, with lag, a low-pass velocity and a
/// fractional delay.
fn two_mass_family() -> AffineFamily {
    let lp = with(
        two_mass_held_by(Arm::TYPICAL, 2e-4),
        Delay::from_time(1.5e-3, 1e-3).unwrap(),
        VelocityEstimator::LowPass { cutoff_hz: 200.0 },
    );
    family(&lp)
}

/// The grid method over a general loop's wall agrees with its exact region away from the
/// boundary.
#[test]
fn wall_map_agrees_with_the_region() {
    use hapstab::boundary::WallPoint;
    for (name, lp) in general_loops().into_iter().skip(6) {
        let fam = family(&lp);
        let r = hapstab::region::stable_region(&fam).unwrap();
        let x = AxisRange::new(Axis::Alpha, -0.2 * r.a_max, 1.2 * r.a_max, 120).unwrap();
        let b = r.b_at_a_max.abs().max(0.05);
        let y = AxisRange::new(Axis::Beta, -2.0 * b, 3.0 * b, 100).unwrap();
        let map = wall_map(&fam, x, y, MapKind::Stability, &|_| {}).unwrap();
        let mut agree = 0;
        for iy in 0..y.n {
            for ix in 0..x.n {
                let p = WallPoint {
                    a: x.value(ix),
                    b: y.value(iy),
                };
                agree += (map.is_stable(ix, iy) == r.contains(p)) as usize;
            }
        }
        // points exactly on a grid line of the boundary may differ: at most a thin band
        assert!(agree >= x.n * y.n - x.n - y.n, "{name}: {agree}");
    }
}

/// A map by axis values and a map by (K, B) points give the uniform map's verdicts and radii,
/// bit for bit, in any number of parallel tasks.
#[test]
fn maps_by_value_equal_the_uniform_map() {
    let fam = two_mass_family();
    let (a0, b0) = fam.to_units(-2e3, -5.0);
    let (a1, b1) = fam.to_units(4e4, 40.0);
    let x = AxisRange::new(Axis::Alpha, a0, a1, 37).unwrap();
    let y = AxisRange::new(Axis::Beta, b0, b1, 23).unwrap();
    let m = wall_map(&fam, x, y, MapKind::SpectralRadius, &|_| {}).unwrap();
    let a: Vec<f64> = (0..x.n).map(|i| x.value(i)).collect();
    let b: Vec<f64> = (0..y.n).map(|i| y.value(i)).collect();
    let v = wall_map_values(&fam, &a, &b, MapKind::SpectralRadius).unwrap();
    assert_eq!((&v.stable, &v.radius), (&m.stable, &m.radius));
    assert!(m.stable.iter().any(|&s| s) && m.stable.iter().any(|&s| !s));
    // the same walls one by one (rows of b, columns of a), in more than one parallel task
    let (pa, pb): (Vec<f64>, Vec<f64>) =
        (0..3000).map(|k| (a[k % x.n], b[(k / x.n) % y.n])).unzip();
    let p = wall_map_points(&fam, &pa, &pb, MapKind::SpectralRadius).unwrap();
    let r = m.radius.as_ref().unwrap();
    for k in 0..3000 {
        let i = (k / x.n) % y.n * x.n + k % x.n;
        assert_eq!(
            (p.stable[k], p.radius.as_ref().unwrap()[k]),
            (m.stable[i], r[i])
        );
    }
    let s = wall_map_points(&fam, &pa, &pb, MapKind::Stability).unwrap();
    assert_eq!(s.stable, p.stable);
    assert!(s.radius.is_none());
}

/// Values that are not finite, or point lists of different lengths, are refused naming the
/// parameter.
#[test]
fn maps_by_value_refuse_bad_values() {
    let fam = two_mass_family();
    let e = wall_map_values(&fam, &[0.0, f64::NAN], &[0.0], MapKind::Stability);
    assert!(e.unwrap_err().to_string().contains("wall stiffness"));
    let e = wall_map_points(&fam, &[0.0], &[0.0, 1.0], MapKind::Stability);
    assert!(e.unwrap_err().to_string().contains("wall damping"));
    let e = wall_map_points(&fam, &[0.0], &[f64::INFINITY], MapKind::Stability);
    assert!(e.unwrap_err().to_string().contains("wall damping"));
}
