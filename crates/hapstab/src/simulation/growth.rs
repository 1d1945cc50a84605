//! Growth of the homogeneous linear bilateral loop measured by stepping the simulator's own
//! one-sample map (Section V): block power iteration with Rayleigh–Ritz.

use nalgebra::{DMatrix, Schur};
use num_complex::Complex64;
use serde::Serialize;

use super::{Config, Effects, Model, SimModel, Simulator};
use crate::error::{Error, Result};
use crate::paper::Normalized;

/// Growth of the homogeneous linear bilateral loop, measured by stepping the simulator.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct LinearGrowth {
    /// Envelope factor per sample of the dominant mode: |λ| of the dominant Ritz value,
    /// which is the spectral radius of p(z) (eq. 9, Section V).
    pub growth_per_sample: f64,
    /// The dominant Ritz value λ (its argument is the oscillation angle per sample).
    pub dominant: Complex64,
    /// Relative residual ‖Av − λv‖/|λ| of the dominant Ritz pair.
    pub residual: f64,
    /// Block size of the power iteration.
    pub block: usize,
    /// Simulated steps per block vector.
    pub steps: usize,
    /// True when the residual fell below the target (1e-11).
    pub converged: bool,
}

impl LinearGrowth {
    /// Frequency of the dominant mode in Hz for period T: |arg λ| / (2πT).
    pub fn frequency_hz(&self, period: f64) -> f64 {
        self.dominant.arg().abs() / (2.0 * std::f64::consts::PI * period)
    }
}

/// Largest block of the power iteration.
const BLOCK: usize = 6;

/// The homogeneous linear bilateral loop's one-sample map: the simulator with the wall at
/// the origin, no human force and no nonlinear effect, stepped once from a given state.
struct HomogeneousMap {
    sim: Simulator,
}

impl HomogeneousMap {
    fn new(model: &SimModel) -> Result<Self> {
        let mut cfg = Config::new(model.clone(), 2);
        cfg.effects = Effects::LINEAR;
        Ok(Self {
            sim: Simulator::new(&cfg)?,
        })
    }

    fn len(&self) -> usize {
        self.sim.state_len()
    }

    fn apply(&mut self, src: &[f64], dst: &mut [f64]) -> Result<()> {
        self.sim.load_state(src);
        self.sim.advance(1)?;
        self.sim.store_state(dst);
        Ok(())
    }
}

/// Modified Gram–Schmidt on p columns of length n (column-major); returns false if the
/// block lost rank.
fn orthonormalize(q: &mut [f64], n: usize, p: usize) -> bool {
    for j in 0..p {
        for i in 0..j {
            let (a, b) = q.split_at_mut(j * n);
            let qi = &a[i * n..(i + 1) * n];
            let qj = &mut b[..n];
            let r: f64 = qi.iter().zip(qj.iter()).map(|(u, v)| u * v).sum();
            qj.iter_mut().zip(qi).for_each(|(v, u)| *v -= r * u);
        }
        let col = &mut q[j * n..(j + 1) * n];
        let norm = col.iter().map(|v| v * v).sum::<f64>().sqrt();
        if !(norm > 0.0 && norm.is_finite()) {
            return false;
        }
        col.iter_mut().for_each(|v| *v /= norm);
    }
    true
}

/// Solves the small complex system a·x = b in place by Gaussian elimination with partial
/// pivoting; zero pivots are replaced by a tiny value (inverse iteration).
fn complex_solve(a: &mut [Complex64], b: &mut [Complex64], p: usize) {
    let scale = a
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for c in 0..p {
        let piv = (c..p)
            .max_by(|&i, &j| a[i * p + c].norm().total_cmp(&a[j * p + c].norm()))
            .unwrap_or(c);
        if piv != c {
            for j in 0..p {
                a.swap(c * p + j, piv * p + j);
            }
            b.swap(c, piv);
        }
        if a[c * p + c].norm() < 1e-14 * scale {
            a[c * p + c] = Complex64::new(1e-14 * scale, 0.0);
        }
        for i in c + 1..p {
            let f = a[i * p + c] / a[c * p + c];
            for j in c..p {
                let v = a[c * p + j];
                a[i * p + j] -= f * v;
            }
            let v = b[c];
            b[i] -= f * v;
        }
    }
    for c in (0..p).rev() {
        let mut s = b[c];
        for j in c + 1..p {
            s -= a[c * p + j] * b[j];
        }
        b[c] = s / a[c * p + c];
    }
}

/// Ritz values of the p×p matrix t (row-major) and the dominant one with its residual.
fn dominant_ritz(t: &[f64], p: usize, q: &[f64], aq: &[f64], n: usize) -> Option<(Complex64, f64)> {
    let m = DMatrix::from_row_slice(p, p, t);
    let schur = Schur::try_new(m, f64::EPSILON, 10_000)?;
    let eig = schur.complex_eigenvalues();
    let lam = eig
        .iter()
        .map(|z| Complex64::new(z.re, z.im))
        .max_by(|a, b| a.norm().total_cmp(&b.norm()))?;
    // Ritz vector by inverse iteration on t − λI.
    let mut y = vec![Complex64::new(1.0, 0.0); p];
    for (i, yi) in y.iter_mut().enumerate() {
        *yi = Complex64::new(1.0 + 0.1 * i as f64, 0.3 - 0.05 * i as f64);
    }
    for _ in 0..3 {
        let mut a: Vec<Complex64> = t.iter().map(|&v| Complex64::new(v, 0.0)).collect();
        for i in 0..p {
            a[i * p + i] -= lam;
        }
        complex_solve(&mut a, &mut y, p);
        let nrm = y.iter().map(|z| z.norm_sqr()).sum::<f64>().sqrt();
        if !(nrm > 0.0 && nrm.is_finite()) {
            return Some((lam, f64::INFINITY));
        }
        y.iter_mut().for_each(|z| *z /= nrm);
    }
    // Residual ‖(AQ) y − λ Q y‖ / |λ|, with ‖Q y‖ = 1.
    let mut res = 0.0;
    for r in 0..n {
        let mut s = Complex64::new(0.0, 0.0);
        for j in 0..p {
            s += y[j] * (aq[j * n + r]) - lam * y[j] * q[j * n + r];
        }
        res += s.norm_sqr();
    }
    Some((lam, res.sqrt() / lam.norm().max(f64::MIN_POSITIVE)))
}

/// Measures the growth per sample of the homogeneous linear bilateral loop of the paper
/// (eq. 9, Section V) in normalized units: [`linear_growth_of`] the loop of `params`.
pub fn linear_growth(params: &Normalized) -> Result<LinearGrowth> {
    linear_growth_of(&SimModel::Paper(Model::unit(*params)?))
}

/// Measures the growth per sample of any homogeneous linear bilateral loop (Section V) by
/// stepping the simulator's own one-sample map: block power iteration with a block of
/// min(state, 6) generic state vectors (plant state *and* the loop's memory: delay line,
/// estimator, previous force), re-orthonormalized every step, and Rayleigh–Ritz on the
/// block. The modulus of the dominant Ritz value is the envelope factor of the dominant mode,
/// so a complex dominant pair is tracked as the growth of a rotating plane rather than by the
/// oscillating norm of one trajectory. Stops when the dominant Ritz pair's relative residual
/// is below 1e-11 or after a work budget.
pub fn linear_growth_of(model: &SimModel) -> Result<LinearGrowth> {
    let mut map = HomogeneousMap::new(model)?;
    let n = map.len();
    let p = n.min(BLOCK);
    let mut seed = 0x9E37_79B9_7F4A_7C15_u64;
    let mut q: Vec<f64> = (0..n * p)
        .map(|_| {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        })
        .collect();
    if !orthonormalize(&mut q, n, p) {
        return Err(Error::Numerical("initial block is rank deficient".into()));
    }
    let mut aq = vec![0.0; n * p];
    let mut t = vec![0.0; p * p];
    let max_steps = (4e9 / (n * p * p) as f64).clamp(2_000.0, 1_000_000.0) as usize;
    let mut best: Option<(Complex64, f64)> = None;
    let mut steps = 0;
    let mut next_check = 1;
    loop {
        for j in 0..p {
            let (src, dst) = (&q[j * n..(j + 1) * n], &mut aq[j * n..(j + 1) * n]);
            map.apply(src, dst)?;
        }
        steps += 1;
        if steps >= next_check || steps >= max_steps {
            next_check = steps + if steps < 64 { 1 } else { 16 };
            for i in 0..p {
                for j in 0..p {
                    t[i * p + j] = (0..n).map(|r| q[i * n + r] * aq[j * n + r]).sum();
                }
            }
            if let Some((lam, res)) = dominant_ritz(&t, p, &q, &aq, n) {
                best = Some((lam, res));
                if res < 1e-11 || steps >= max_steps {
                    break;
                }
            } else if steps >= max_steps {
                break;
            }
        }
        std::mem::swap(&mut q, &mut aq);
        if !orthonormalize(&mut q, n, p) {
            // The map annihilated the block (all roots zero): nothing grows.
            return Ok(LinearGrowth {
                growth_per_sample: 0.0,
                dominant: Complex64::new(0.0, 0.0),
                residual: 0.0,
                block: p,
                steps,
                converged: true,
            });
        }
    }
    let (lam, res) = best.ok_or_else(|| Error::Numerical("Ritz values did not converge".into()))?;
    Ok(LinearGrowth {
        growth_per_sample: lam.norm(),
        dominant: lam,
        residual: res,
        block: p,
        steps,
        converged: res < 1e-11,
    })
}
