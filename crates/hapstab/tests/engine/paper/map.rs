//! The wall map (`hapstab::paper::map`) against the exact region.
//! Expected values come from closed forms derived by hand, the paper's own formulas and
//! statements, or published examples, never from program output.

use crate::common::general::{family, general_loops};

/// The grid method over a general loop's wall agrees with its exact region away from the
/// boundary.
#[test]
fn wall_map_agrees_with_the_region() {
    use hapstab::boundary::AlphaBeta;
    use hapstab::paper::map::{Axis, AxisRange, MapKind, wall_map};
    for (name, lp) in general_loops().into_iter().skip(6) {
        let fam = family(&lp);
        let r = hapstab::region::stable_region(&fam).unwrap();
        let x = AxisRange::new(Axis::Alpha, -0.2 * r.alpha_max, 1.2 * r.alpha_max, 120).unwrap();
        let b = r.beta_at_alpha_max.abs().max(0.05);
        let y = AxisRange::new(Axis::Beta, -2.0 * b, 3.0 * b, 100).unwrap();
        let map = wall_map(&fam, x, y, MapKind::Stability, &|_| {}).unwrap();
        let mut agree = 0;
        for iy in 0..y.n {
            for ix in 0..x.n {
                let p = AlphaBeta {
                    alpha: x.value(ix),
                    beta: y.value(iy),
                };
                agree += (map.is_stable(ix, iy) == r.contains(p)) as usize;
            }
        }
        // points exactly on a grid line of the boundary may differ: at most a thin band
        assert!(agree >= x.n * y.n - x.n - y.n, "{name}: {agree}");
    }
}
