//! The exact sampled response of a model to a recorded force: the loop's own discrete plant
//! ([`crate::zoh::DiscreteLoop`]: zero-order hold, whole and fractional delay, actuator lag),
//! run from rest,
//!
//! ```text
//! x_{k+1} = Φ x_k + Γ0 u_{k−d} + Γ1 u_{k−d−1},   ŷ_k = C x_k + y_0,   u = F/k_u,
//! ```
//!
//! with x_0 = 0, F_j = 0 before the recording starts, k_u the loop's wall unit and y_0 the
//! position the device rests at (the encoder's zero is arbitrary).

use crate::model::Loop;
use crate::zoh::DiscreteLoop;

/// The matrices of one sampled model, flattened for a fast simulation.
#[derive(Debug, Clone)]
pub struct SampledModel {
    n: usize,
    phi: Vec<f64>,
    g0: Vec<f64>,
    g1: Vec<f64>,
    c: Vec<f64>,
    delay: usize,
    input_scale: f64,
}

impl SampledModel {
    /// The sampled plant of a loop (module doc).
    pub fn of_loop(lp: &Loop) -> crate::Result<Self> {
        let dl = DiscreteLoop::new(lp)?;
        let phi: Vec<f64> = dl.phi().into_iter().flatten().collect();
        Ok(SampledModel {
            n: dl.order(),
            phi,
            g0: dl.gamma0.clone(),
            g1: dl.gamma1.clone(),
            c: dl.c.clone(),
            delay: dl.delay.samples,
            input_scale: 1.0 / dl.scale.stiffness,
        })
    }

    /// ŷ_k = C x_k for every sample of `force` (module doc, without the offset y_0), written
    /// into `out`.
    pub fn simulate_into(&self, force: &[f64], out: &mut [f64]) {
        let n = self.n;
        let mut x = vec![0.0; n];
        let mut next = vec![0.0; n];
        let u_at = |j: isize| {
            if j >= 0 {
                force[j as usize] * self.input_scale
            } else {
                0.0
            }
        };
        for (k, y) in out.iter_mut().enumerate() {
            *y = self.c.iter().zip(&x).map(|(c, x)| c * x).sum();
            let u0 = u_at(k as isize - self.delay as isize);
            let u1 = u_at(k as isize - self.delay as isize - 1);
            for (i, nx) in next.iter_mut().enumerate() {
                let row = &self.phi[i * n..(i + 1) * n];
                *nx = row.iter().zip(&x).map(|(a, x)| a * x).sum::<f64>()
                    + self.g0[i] * u0
                    + self.g1[i] * u1;
            }
            std::mem::swap(&mut x, &mut next);
        }
    }

    /// ŷ_k = C x_k for every sample of `force` (module doc, without the offset).
    pub fn simulate(&self, force: &[f64]) -> Vec<f64> {
        let mut out = vec![0.0; force.len()];
        self.simulate_into(force, &mut out);
        out
    }
}
