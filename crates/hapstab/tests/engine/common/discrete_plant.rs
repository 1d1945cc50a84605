//! The tests' independent reference for the paper's plant: the exact discrete-time equivalent
//! of 1/(ms² + bs + k) behind a zero-order hold in closed form (Section III, eq. 2–6, and
//! eq. 10 for k = 0). The library discretizes every loop through `hapstab::zoh`; the tests
//! compare the two to rounding, and the simulation tests step this 2×2 plant as a second
//! simulator.
//!
//! In normalized time (unit = one sample T) the plant is 1/(s² + δs + γ) with gain T²/m, so
//!
//! ```text
//! H(z) = T²/m · (n1 z + n0) / (z² − a1 z + a0).
//! ```
//!
//! The paper writes the coefficients with c1 = √(δ² − 4γ) (eq. 6), which is imaginary in the
//! paper's whole parameter range, 0/0 at γ = 0 and cancels badly near δ² = 4γ. Here the
//! coefficients come from the exact matrix exponential instead: with A = [[0, 1], [−γ, −δ]]
//! = μI + M, μ = −δ/2, M² = qI, q = δ²/4 − γ,
//!
//! ```text
//! Φ = e^A = e^μ (C(q) I + S(q) M),   C(q) = cosh √q,  S(q) = sinh √q / √q,
//! Γ = ∫₀¹ e^{At} dt · [0, 1]ᵀ = [v, Φ12],
//! ```
//!
//! where C and S are entire functions of q (cos and sin(x)/x for q < 0), and
//! Ψ(h) = ∫₀ʰ e^{At} dt = u I + v M is summed as a short Taylor series at a small step
//! h = 2⁻ᵏ and doubled exactly, Ψ(2h) = (I + Φ(h)) Ψ(h). No step divides by γ, δ or c1,
//! so every regime (over-, critically and under-damped, γ = 0, δ = 0, pure mass) is accurate
//! to a few ulps, and the coefficients are continuous across the regime boundaries.

use hapstab::PlantParams;
use hapstab::Result;
use num_complex::Complex64;

/// The exact zero-order-hold equivalent of the normalized plant 1/(s² + δs + γ).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiscretePlant {
    /// Normalized stiffness γ.
    pub gamma: f64,
    /// Normalized damping δ.
    pub delta: f64,
    /// Numerator coefficient of z.
    pub n1: f64,
    /// Numerator constant.
    pub n0: f64,
    /// Denominator: z² − a1 z + a0, a1 = c2 + c3 = tr e^A (eq. 5).
    pub a1: f64,
    /// Denominator constant a0 = e^{−δ} = det e^A (eq. 5).
    pub a0: f64,
    /// The one-sample state transition matrix e^A of the state (x, ẋ·T).
    pub phi: [[f64; 2]; 2],
    /// The one-sample input vector ∫₀¹ e^{At} dt · [0, 1]ᵀ.
    pub input: [f64; 2],
}

/// C(q) = cosh √q and S(q) = sinh √q / √q, continued to q < 0 as cos √−q and sin √−q / √−q.
fn cosh_sinhc(q: f64) -> (f64, f64) {
    if q.abs() < 1e-6 {
        // Taylor series; the first omitted terms are below 1e-24 / 8!.
        let c = 1.0 + q / 2.0 * (1.0 + q / 12.0 * (1.0 + q / 30.0));
        let s = 1.0 + q / 6.0 * (1.0 + q / 20.0 * (1.0 + q / 42.0));
        (c, s)
    } else if q > 0.0 {
        let r = q.sqrt();
        (r.cosh(), r.sinh() / r)
    } else {
        let w = (-q).sqrt();
        (w.cos(), w.sin() / w)
    }
}

/// e^{Ah} = p I + s M as the pair (p, s), for μ = −δ/2, q = μ² − γ.
fn exp_pair(gamma: f64, mu: f64, q: f64, h: f64) -> (f64, f64) {
    let r = if q > 0.0 { q.sqrt() } else { 0.0 };
    if r * h >= 1.0 {
        // Real, well separated eigenvalues λ1 = −γ/(|μ| + r), λ2 = μ − r: no overflow of
        // cosh when δ is large, no cancellation in λ1 when γ ≪ δ².
        let l1 = -gamma / (-mu + r);
        let l2 = mu - r;
        let (e1, e2) = ((l1 * h).exp(), (l2 * h).exp());
        ((e1 + e2) / 2.0, (e1 - e2) / (2.0 * r))
    } else {
        let (c, s) = cosh_sinhc(q * h * h);
        let e = (mu * h).exp();
        (e * c, e * h * s)
    }
}

/// Ψ(h) = ∫₀ʰ e^{At} dt = u I + v M as (u, v), by its Taylor series; requires ‖Ah‖ ≤ 1/4.
fn psi_series(mu: f64, q: f64, h: f64) -> (f64, f64) {
    let (mh, qh) = (mu * h, q * h * h);
    // (Ah)^n = P_n I + Q_n (hM), P_{n+1} = μh P_n + q h² Q_n, Q_{n+1} = P_n + μh Q_n.
    let (mut pn, mut qn) = (1.0_f64, 0.0_f64);
    let (mut su, mut sv) = (0.0_f64, 0.0_f64);
    let mut fact = 1.0_f64; // (n+1)!
    for n in 0..40 {
        fact *= (n + 1) as f64;
        let (tu, tv) = (pn / fact, qn / fact);
        su += tu;
        sv += tv;
        if n > 2 && tu.abs() <= 1e-18 * su.abs() && tv.abs() <= 1e-18 * sv.abs() {
            break;
        }
        let next_p = mh * pn + qh * qn;
        qn = pn + mh * qn;
        pn = next_p;
    }
    (h * su, h * h * sv)
}

impl DiscretePlant {
    /// Computes the exact ZOH equivalent for normalized stiffness γ and damping δ
    /// (eq. 5–6 in a form valid in every regime; eq. 10 when γ = 0).
    pub fn new(gamma: f64, delta: f64) -> Result<Self> {
        let pp = PlantParams::new(gamma, delta)?;
        Ok(Self::from_params(pp))
    }

    /// As [`DiscretePlant::new`] for already validated parameters.
    pub fn from_params(pp: PlantParams) -> Self {
        let (gamma, delta) = (pp.gamma, pp.delta);
        let mu = -delta / 2.0;
        let q = mu * mu - gamma;
        let norm = -mu + q.abs().sqrt();
        // Smallest k with ‖A‖·2⁻ᵏ ≤ 1/4.
        let mut k: i32 = 0;
        while norm * 0.5_f64.powi(k) > 0.25 && k < 1100 {
            k += 1;
        }
        let mut h = 0.5_f64.powi(k);
        let (mut u, mut v) = psi_series(mu, q, h);
        for _ in 0..k {
            let (p, s) = exp_pair(gamma, mu, q, h);
            let nu = (1.0 + p) * u + q * s * v;
            let nv = (1.0 + p) * v + s * u;
            u = nu;
            v = nv;
            h *= 2.0;
        }
        let (p1, s1) = exp_pair(gamma, mu, q, 1.0);
        let half = delta / 2.0;
        let phi = [[p1 + half * s1, s1], [-gamma * s1, p1 - half * s1]];
        let input = [v, s1];
        let n1 = v;
        let n0 = s1 * s1 - phi[1][1] * v;
        Self {
            gamma,
            delta,
            n1,
            n0,
            a1: 2.0 * p1,
            a0: (-delta).exp(),
            phi,
            input,
        }
    }

    /// N(1) = n1 + n0 evaluated without cancellation as γ g1² + δ g1 g2 + g2²; equals
    /// γ·D(1), i.e. the zero-order hold keeps the DC gain 1/γ (Section III).
    pub fn numerator_at_one(&self) -> f64 {
        let (g1, g2) = (self.input[0], self.input[1]);
        self.gamma * g1 * g1 + self.delta * g1 * g2 + g2 * g2
    }

    /// D(1) = 1 − a1 + a0 computed as γ·N(1) (exact identity, no cancellation).
    pub fn denominator_at_one(&self) -> f64 {
        self.gamma * self.numerator_at_one()
    }

    /// Numerator N(z) = n1 z + n0.
    pub fn numerator(&self, z: Complex64) -> Complex64 {
        z * self.n1 + self.n0
    }

    /// Denominator D(z) = z² − a1 z + a0.
    pub fn denominator(&self, z: Complex64) -> Complex64 {
        z * z - z * self.a1 + self.a0
    }

    /// The normalized transfer function N(z)/D(z) (multiply by T²/m for metres per newton).
    pub fn transfer(&self, z: Complex64) -> Complex64 {
        self.numerator(z) / self.denominator(z)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hapstab::paper::reference::eq10_coefficients;

    fn rel(a: f64, b: f64) -> f64 {
        (a - b).abs() / b.abs().max(f64::MIN_POSITIVE)
    }

    #[test]
    fn pure_mass_is_exact() {
        let p = DiscretePlant::new(0.0, 0.0).unwrap();
        assert_eq!((p.n1, p.n0, p.a1, p.a0), (0.5, 0.5, 2.0, 1.0));
    }

    #[test]
    fn undamped_oscillator_closed_form() {
        // δ = 0: n1 = n0 = (1 − cos ω)/ω² = 2 sin²(ω/2)/ω², a1 = 2 cos ω, a0 = 1.
        for &g in &[1e-8_f64, 1e-3, 0.3, 2.0, 9.0, 30.0] {
            let w: f64 = g.sqrt();
            let expect = 2.0 * (w / 2.0).sin().powi(2) / g;
            let p = DiscretePlant::new(g, 0.0).unwrap();
            assert!(rel(p.n1, expect) < 1e-14, "g={g} n1 {} vs {}", p.n1, expect);
            assert!(rel(p.n0, expect) < 1e-13, "g={g} n0 {} vs {}", p.n0, expect);
            assert!(rel(p.a1, 2.0 * w.cos()) < 1e-14);
        }
    }

    #[test]
    fn gamma_zero_matches_eq10() {
        for &d in &[0.3, 1.0, 2.5, 7.0, 40.0] {
            let p = DiscretePlant::new(0.0, d).unwrap();
            let (n1, n0, a1, a0) = eq10_coefficients(d);
            assert!(rel(p.n1, n1) < 1e-13, "d={d}: {} vs {}", p.n1, n1);
            assert!(rel(p.n0, n0) < 1e-13, "d={d}: {} vs {}", p.n0, n0);
            assert!(rel(p.a1, a1) < 1e-14);
            assert!(rel(p.a0, a0) < 1e-15);
        }
    }
}
