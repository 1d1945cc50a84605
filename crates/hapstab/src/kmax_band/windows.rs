//! The parts of the curve above a level (module doc of [`super`], step 4): on the curve
//! a(u) = a1(u)/a2(u) with a1 = [P0, PB], a2 = [PB, PK], so a(u) − a* = g(u)/a2(u) with
//! g = a1 − a*·a2, the crossing polynomial of the damping axis at a* (whose roots the
//! certificate has found). Between consecutive roots of g, a − a* changes sign only where a2
//! vanishes (a pole of the curve); a window between them where a2 has no root, certified by
//! Descartes' rule of signs on the window (Collins & Akritas 1976: the sign variations of
//! (1 + x)^n·a2((l + r·x)/(1 + x)) bound the number of a2's roots in (l, r)), and where
//! g/a2 < 0 at one point, lies below a* throughout: no stationary point or corner of the
//! curve inside it is a candidate above a*, and its roots are not sought.

use crate::cayley::CayleyFamily;
use crate::real_roots::{sign_variations, sure_sign};

/// The windows (l, r) of the positive u axis outside which the curve's stiffness a(u) stays
/// below `level` (module doc): between consecutive roots of g = a1 − level·a2 (`g_roots`,
/// increasing, the damping axis's crossing polynomial at `level`), every window that is not
/// certified below the level, adjacent ones merged.
pub(super) fn above_windows(cf: &CayleyFamily, level: f64, g_roots: &[f64]) -> Vec<(f64, f64)> {
    let g = crate::poly::weighted_sum_trimmed(&[(1.0, &cf.p0_pb), (-level, &cf.pb_pk)]);
    let mut cuts: Vec<f64> = vec![0.0];
    cuts.extend(
        g_roots
            .iter()
            .copied()
            .filter(|u| *u > 0.0 && u.is_finite()),
    );
    cuts.push(f64::INFINITY);
    let mut out: Vec<(f64, f64)> = Vec::new();
    for w in cuts.windows(2) {
        let (l, r) = (w[0], w[1]);
        if l >= r || (below_at(&g, &cf.pb_pk, middle(l, r)) && no_root_between(&cf.pb_pk, l, r)) {
            continue;
        }
        match out.last_mut() {
            Some(last) if last.1 == l => last.1 = r,
            _ => out.push((l, r)),
        }
    }
    out
}

/// A point inside (l, r): geometric where both ends are positive and finite.
fn middle(l: f64, r: f64) -> f64 {
    match (l > 0.0, r.is_finite()) {
        (true, true) => (l * r).sqrt(),
        (true, false) => 2.0 * l,
        (false, true) => 0.5 * r,
        (false, false) => 1.0,
    }
}

/// g(u)/a2(u) < 0 at u, both signs above their rounding bounds.
fn below_at(g: &[f64], a2: &[f64], u: f64) -> bool {
    match (sure_sign(g, u), sure_sign(a2, u)) {
        (Some(x), Some(y)) => x != y,
        _ => false,
    }
}

/// The polynomial c certainly has no root in the open interval (l, r): no sign variation
/// ([`sign_variations`]).
fn no_root_between(c: &[f64], l: f64, r: f64) -> bool {
    sign_variations(c, l, r) == Some(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descartes_window_test() {
        // (u − 1)(u − 3)(u² + 1): roots 1 and 3
        let c = crate::poly::mul(
            &crate::poly::mul(&[-1.0, 1.0], &[-3.0, 1.0]),
            &[1.0, 0.0, 1.0],
        );
        assert!(no_root_between(&c, 0.0, 0.9));
        assert!(no_root_between(&c, 1.1, 2.9));
        assert!(no_root_between(&c, 3.1, f64::INFINITY));
        assert!(!no_root_between(&c, 0.0, 1.1));
        assert!(!no_root_between(&c, 2.0, f64::INFINITY));
        assert!(!no_root_between(&c, 0.5, 3.5));
    }
}
