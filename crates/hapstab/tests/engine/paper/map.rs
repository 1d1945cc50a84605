//! The paper's grid maps over two of α, β, γ, δ (`hapstab::paper::map`, Section V) against an
//! independent method: the roots of p(z) = z^{d+1}D(z) + N(z)((α + β)z − β) (eq. 9) built from
//! the closed-form plant of eq. (5)–(6) (the tests' reference), point by point, on maps whose
//! plant is fixed, changes along one axis, or changes at every point.

use hapstab::map::{Axis, AxisRange, MapKind};
use hapstab::paper::map::{MapSpec, compute_map};
use hapstab::stability::roots_companion;
use hapstab::{Normalized, PlantParams};

use crate::common::discrete_plant::DiscretePlant;

/// The largest root modulus of eq. (9) from the closed-form plant.
fn closed_form_radius(p: &Normalized) -> f64 {
    let pl = DiscretePlant::from_params(PlantParams::new(p.gamma, p.delta).unwrap());
    let n = p.d + 3;
    let mut c = vec![0.0; n + 1];
    c[n] = 1.0;
    c[n - 1] = -pl.a1;
    c[n - 2] = pl.a0;
    let ab = p.alpha + p.beta;
    c[2] += pl.n1 * ab;
    c[1] += pl.n0 * ab - pl.n1 * p.beta;
    c[0] -= pl.n0 * p.beta;
    roots_companion(&c)
        .unwrap()
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
}

fn check(x: AxisRange, y: AxisRange, base: Normalized) {
    let spec = MapSpec::new(x, y, base).unwrap();
    let m = compute_map(&spec, MapKind::Stability, &|_| {}).unwrap();
    let (mut decided, mut stable) = (0, 0);
    for iy in 0..y.n {
        for ix in 0..x.n {
            let p = spec.point(ix, iy);
            let r = closed_form_radius(&p);
            if (r - 1.0).abs() < 1e-6 {
                continue;
            }
            decided += 1;
            stable += usize::from(r < 1.0);
            assert_eq!(m.is_stable(ix, iy), r < 1.0, "{p:?}: radius {r}");
        }
    }
    // Both verdicts occur, so the comparison can fail either way.
    assert!(decided > x.n * y.n * 9 / 10, "{decided} of {}", x.n * y.n);
    assert!(
        stable > 0 && stable < decided,
        "{stable} of {decided} stable"
    );
}

#[test]
fn map_with_a_fixed_plant_equals_the_closed_form_roots() {
    check(
        AxisRange::new(Axis::Alpha, -0.05, 0.8, 17).unwrap(),
        AxisRange::new(Axis::Beta, -0.05, 1.2, 15).unwrap(),
        Normalized::new(0.0, 0.0, 1e-3, 0.015, 1).unwrap(),
    );
}

#[test]
fn map_over_the_plant_along_one_axis_equals_the_closed_form_roots() {
    let base = Normalized::new(0.3, 0.4, 1e-3, 0.015, 2).unwrap();
    check(
        AxisRange::new(Axis::Alpha, 0.0, 0.6, 13).unwrap(),
        AxisRange::new(Axis::Gamma, 0.0, 0.2, 11).unwrap(),
        base,
    );
    check(
        AxisRange::new(Axis::Delta, 0.0, 3.0, 11).unwrap(),
        AxisRange::new(Axis::Beta, 0.0, 1.0, 13).unwrap(),
        base,
    );
}

#[test]
fn map_over_gamma_and_delta_equals_the_closed_form_roots() {
    check(
        AxisRange::new(Axis::Gamma, 0.0, 0.3, 14).unwrap(),
        AxisRange::new(Axis::Delta, 0.0, 2.0, 12).unwrap(),
        Normalized::new(0.25, 0.3, 0.0, 0.0, 1).unwrap(),
    );
}
