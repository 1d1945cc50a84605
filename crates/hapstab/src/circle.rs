//! Points on the unit circle, e^{iθ}, and (sin x, cos x) from one call: every frequency
//! response, boundary scan and passivity grid evaluates them at hundreds of angles.
//!
//! `libm`'s `sincos` (a port of musl's, itself FreeBSD's msun: error below one ulp) computes
//! both in one argument reduction without the rounding-mode switch that the system `sincos`
//! makes on every call; measured 11–12 ns against 16–21 ns (`BENCHMARKS.md`).

use num_complex::Complex64;

/// (sin x, cos x), each within one ulp.
#[inline]
pub fn sin_cos(x: f64) -> (f64, f64) {
    libm::sincos(x)
}

/// e^{iθ} = cos θ + i sin θ.
#[inline]
pub fn unit(theta: f64) -> Complex64 {
    let (s, c) = libm::sincos(theta);
    Complex64::new(c, s)
}

/// r·e^{iθ}.
#[inline]
pub fn polar(r: f64, theta: f64) -> Complex64 {
    unit(theta) * r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_closed_forms_at_exact_angles() {
        // sin(π/6) = 1/2 and cos(π/3) = 1/2 to an ulp; e^{iπ/2} = i to rounding
        let (s, c) = sin_cos(std::f64::consts::FRAC_PI_6);
        assert!((s - 0.5).abs() <= f64::EPSILON, "{s}");
        assert!((c - 0.75_f64.sqrt()).abs() <= f64::EPSILON, "{c}");
        let z = unit(std::f64::consts::FRAC_PI_2);
        assert!(
            z.re.abs() < 1e-16 && (z.im - 1.0).abs() <= f64::EPSILON,
            "{z}"
        );
        let w = polar(2.0, std::f64::consts::PI);
        assert!(
            (w.re + 2.0).abs() <= 2.0 * f64::EPSILON && w.im.abs() < 1e-15,
            "{w}"
        );
    }

    #[test]
    fn agrees_with_the_system_library_to_an_ulp_over_many_turns() {
        for i in 0..20_000 {
            let x = -300.0 + 0.03 * i as f64;
            let (s, c) = sin_cos(x);
            assert!((s - x.sin()).abs() <= 2.0 * f64::EPSILON, "sin {x}");
            assert!((c - x.cos()).abs() <= 2.0 * f64::EPSILON, "cos {x}");
        }
    }
}
