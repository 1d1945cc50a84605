//! Degenerate plants (Section VIII-B): δ = 0 and γ = (jπ)², where every p(z) keeps a root
//! on the unit circle whatever (α, β).

use crate::paper::PlantParams;

use std::f64::consts::PI;

/// Relative distance of √γ from jπ (δ = 0) within which a plant counts as degenerate. Closer
/// than this the pole and the zero at z = ±1 cancel to fewer than about half the digits and
/// the D-decomposition loses its accuracy (at 1e-8 the computed regions are visibly wrong,
/// at 1e-6 they still agree with the limit triangle to 1e-5).
pub const DEGENERATE_TOL: f64 = 1e-7;

/// Relative offset from a degenerate γ at which [`robust_region`](super::robust_region) takes
/// the limit region.
pub const DEGENERATE_OFFSET: f64 = 1e-6;

/// If every p(z) of the family has a root on the unit circle whatever (α, β) — δ = 0 and
/// √γ = jπ within [`DEGENERATE_TOL`] relative — the angle of that root (π for odd j, 0 for
/// even j)
/// (Section VIII-B: a pole at z = −1 for γ = π², δ = 0).
pub fn unit_circle_pole(pp: PlantParams) -> Option<f64> {
    if pp.delta != 0.0 || pp.gamma <= 0.0 {
        return None;
    }
    let w = pp.gamma.sqrt();
    let j = (w / PI).round();
    if j >= 1.0 && (w - j * PI).abs() <= DEGENERATE_TOL * w {
        Some(if j % 2.0 == 1.0 { PI } else { 0.0 })
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_detection() {
        let g = PI * PI;
        assert_eq!(
            unit_circle_pole(PlantParams::new(g, 0.0).unwrap()),
            Some(PI)
        );
        assert_eq!(
            unit_circle_pole(PlantParams::new(4.0 * g, 0.0).unwrap()),
            Some(0.0)
        );
        assert_eq!(unit_circle_pole(PlantParams::new(g, 1e-3).unwrap()), None);
        assert_eq!(
            unit_circle_pole(PlantParams::new(0.9 * g, 0.0).unwrap()),
            None
        );
    }
}
