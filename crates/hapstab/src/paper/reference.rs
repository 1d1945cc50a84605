//! The paper's closed forms evaluated literally, for comparison with the engine: eq. (10),
//! Remark 2, the discrete plant at k = 0 (Section III). The engine discretizes every loop
//! exactly through [`crate::zoh`]; `hapstab paper`'s claim C11 compares the two.

/// Remark 2, eq. (10), evaluated literally for k = 0 and δ > 0, normalized (T = m = 1):
/// H(z) = 1/(δ(z − 1)) − (1 − e^{−δ})/(δ²(z − e^{−δ})). Returned as (n1, n0, a1, a0) of the
/// combined fraction. Accurate only for δ not small (it divides by δ²); use
/// [`crate::zoh`] for computation and this for comparison with the paper.
pub fn eq10_coefficients(delta: f64) -> (f64, f64, f64, f64) {
    let e = (-delta).exp();
    let d2 = delta * delta;
    // [δ(z − e) − (1 − e)(z − 1)] / (δ² (z − 1)(z − e))
    let n1 = (delta - (1.0 - e)) / d2;
    let n0 = (-delta * e + (1.0 - e)) / d2;
    (n1, n0, 1.0 + e, e)
}
