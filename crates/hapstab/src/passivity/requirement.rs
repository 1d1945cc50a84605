//! The device damping a wall requires (Colgate–Schenkel's condition, eq. 28 generalized): the
//! wall's frequency structure, the requirement at one frequency, and its exact maximum over
//! frequency (see the [parent module](super) for the derivation).

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::extremum::{merge_grid, refine_max};
use crate::model::Loop;
use crate::params::Wall;

/// Grid samples per half-turn of phase (of the delay's e^{−jdθ} and of each filter
/// coefficient): oscillations are then resolved finely enough that a parabola through three
/// samples estimates each local maximum to about 1e-5 of the oscillation's amplitude.
const SAMPLES_PER_TURN: usize = 64;

/// Candidates whose parabolic estimate lies within this fraction of the function's scale
/// below the grid maximum are refined: far more than the parabola's error (about 1e-5).
const REFINE_WINDOW: f64 = 1e-3;

/// Extra grid samples around a filter pole at radius r < 1 (a resonance of width 1 − r):
/// offsets (1 − r)·2^{j/2} on both sides, j = −POLE_OFFSETS..=POLE_OFFSETS.
const POLE_OFFSETS: i32 = 16;

/// Poles of the velocity filter with |r| above this radius get the extra samples: below it
/// the resonance is wider than the uniform grid's resolution anyway.
const POLE_RADIUS: f64 = 0.5;

/// Width of the final bracket of a frequency maximum, relative to its angle. The function is flat at an
/// interior maximum, so the value there is exact to rounding long before: an error of 1e-9 rad
/// changes it by about f''·1e-18.
pub(crate) const THETA_TOL: f64 = 1e-9;

/// A local maximum whose parabola rises less than this fraction of the function's scale above
/// its grid sample is not refined: the grid value is then already exact to rounding (this
/// also keeps constant stretches, where every sample is a local maximum, cheap).
const FLAT: f64 = 1e-14;

/// The loop's wall as seen by the passivity condition: its frequency structure, independent of
/// the plant (the condition involves only the wall, the hold and the device's damper).
#[derive(Debug, Clone)]
pub struct SampledWall {
    period: f64,
    d: usize,
    lambda: f64,
    /// Velocity numerator (of T·V) in powers of z^{−1}.
    vn: Vec<f64>,
    /// Velocity denominator in powers of z^{−1}.
    vd: Vec<f64>,
    /// Lags m and coefficients c_m of (Vn·M)(e^{jθ})·conj Vd(e^{jθ}) = Σ c_m e^{−jmθ}.
    corr: Vec<(i64, f64)>,
    /// V(1) in 1/s: the estimator's DC gain (0 for every differentiator).
    dc_velocity: f64,
    /// The grid and the frequency basis on it.
    grid: Vec<f64>,
    basis: Vec<Basis>,
}

/// The pieces of the requirement at one θ that the wall (K, B) combines linearly.
#[derive(Debug, Clone, Copy)]
struct Basis {
    /// Re{(1 − e^{−jθ})z^{−d}M}/(1 − cos θ): the ratio of (C–S) per unit K.
    rk: f64,
    /// The same per unit B (with V(z)).
    rb: f64,
    /// Re V(e^{jθ}) in 1/s.
    re_v: f64,
    /// |V(e^{jθ})|² in 1/s².
    abs_v2: f64,
}

/// The device damping a wall requires, and where it binds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct DampingRequirement {
    /// b_required in Ns/m: the display is passive iff the device damping exceeds it (and the
    /// wall's static stiffness is >= 0).
    pub b_required: f64,
    /// θ = ωT in [0, π] of the maximum.
    pub theta: f64,
    /// The binding frequency θ/(2πT) in Hz.
    pub frequency_hz: f64,
}

impl SampledWall {
    /// The wall structure of a loop: its period, delay and velocity estimator. Fails when the
    /// estimator is not a stable filter (a pole on or outside the unit circle), for which the
    /// frequency-domain condition does not hold.
    pub fn new(lp: &Loop) -> Result<Self> {
        let (num, den) = lp.velocity.per_sample_filter(lp.period);
        check_filter_stable(&den)?;
        let len = num.len().max(den.len());
        let vn = reversed_padded(&num, len);
        let vd = reversed_padded(&den, len);
        let lambda = lp.delay.fraction;
        let vm = if lambda == 0.0 {
            vn.clone()
        } else {
            crate::poly::mul(&vn, &[1.0 - lambda, lambda])
        };
        let dc_velocity = vn.iter().sum::<f64>() / (lp.period * vd.iter().sum::<f64>());
        let mut wall = Self {
            period: lp.period,
            d: lp.delay.samples,
            lambda,
            corr: correlation(&vm, &vd),
            vn,
            vd,
            dc_velocity,
            grid: Vec::new(),
            basis: Vec::new(),
        };
        wall.grid = wall.make_grid(&den);
        wall.basis = wall.grid.iter().map(|&t| wall.basis_at(t)).collect();
        Ok(wall)
    }

    /// The sampling period T in s.
    pub fn period(&self) -> f64 {
        self.period
    }

    /// The wall's static stiffness W(1) = K + B·V(1) in N/m (K for every differentiator).
    pub fn dc_stiffness(&self, wall: Wall) -> f64 {
        wall.stiffness + wall.damping * self.dc_velocity
    }

    /// The estimator's DC gain V(1) in 1/s.
    pub fn dc_velocity(&self) -> f64 {
        self.dc_velocity
    }

    /// The damping required at one frequency θ = ωT ∈ [0, π] in Ns/m: the right side of
    /// (C–S) (with the fractional-delay form of the module doc when λ > 0). Its maximum over θ
    /// is [`SampledWall::required_damping`].
    pub fn required_damping_at(&self, wall: Wall, theta: f64) -> f64 {
        self.value(&self.basis_at(theta), wall)
    }

    /// The device damping the wall requires (Colgate–Schenkel; eq. 28 for the paper's loop):
    /// the maximum of [`SampledWall::required_damping_at`] over 0 ≤ θ ≤ π (see the module doc
    /// for how it is found exactly).
    pub fn required_damping(&self, wall: Wall) -> DampingRequirement {
        let (value, theta) = self.maximize(wall);
        DampingRequirement {
            b_required: value,
            theta,
            frequency_hz: theta / (2.0 * std::f64::consts::PI * self.period),
        }
    }

    fn value(&self, b: &Basis, wall: Wall) -> f64 {
        let (k, bb) = (wall.stiffness, wall.damping);
        let ratio = k * b.rk + bb * b.rb;
        let half_t = 0.5 * self.period;
        if self.lambda == 0.0 {
            return half_t * ratio;
        }
        let q = 0.5 * ratio;
        let w2 = (k * k + 2.0 * k * bb * b.re_v + bb * bb * b.abs_v2).max(0.0);
        half_t * plus_root(q, self.lambda * (1.0 - self.lambda) * w2)
    }

    /// The frequency basis at θ, free of cancellation (module doc).
    fn basis_at(&self, theta: f64) -> Basis {
        let (sh, ch) = (0.5 * theta).sin_cos();
        let d = self.d as f64;
        let (sphi, cphi) = ((d + 0.5) * theta).sin_cos();
        let dirichlet = if theta == 0.0 {
            2.0 * d + 1.0
        } else {
            sphi / sh
        };
        let lam = self.lambda;
        let rk = (1.0 - 2.0 * lam * sh * sh) * dirichlet + 2.0 * lam * ch * cphi;
        let (mut re_c, mut im_c_over) = (0.0, 0.0);
        for &(m, c) in &self.corr {
            let (s, co) = (m as f64 * theta).sin_cos();
            re_c += c * co;
            let s_over = if theta == 0.0 { 2.0 * m as f64 } else { s / sh };
            im_c_over -= c * s_over;
        }
        let z_inv = Complex64::from_polar(1.0, -theta);
        let vd = eval_inverse(&self.vd, z_inv);
        let vn = eval_inverse(&self.vn, z_inv);
        let vd2 = vd.norm_sqr();
        let t = self.period;
        let rb = (re_c * dirichlet - im_c_over * cphi) / (t * vd2);
        let v = vn / (vd * t);
        Basis {
            rk,
            rb,
            re_v: v.re,
            abs_v2: v.norm_sqr(),
        }
    }

    /// The uniform grid on [0, π] plus samples around the filter's poles near the circle.
    fn make_grid(&self, den_ascending: &[f64]) -> Vec<f64> {
        let pi = std::f64::consts::PI;
        let turns = self.d + self.vn.len() + 2;
        let n = SAMPLES_PER_TURN * turns;
        let mut g: Vec<f64> = (0..=n).map(|i| pi * i as f64 / n as f64).collect();
        for r in pole_roots(den_ascending) {
            let rad = r.norm();
            if !(POLE_RADIUS..1.0).contains(&rad) {
                continue;
            }
            let (center, width) = (r.arg().abs(), 1.0 - rad);
            for j in -POLE_OFFSETS..=POLE_OFFSETS {
                let off = width * 2f64.powf(j as f64 / 2.0);
                g.extend(
                    [center - off, center + off]
                        .into_iter()
                        .filter(|t| *t > 0.0 && *t < pi),
                );
            }
        }
        merge_grid(&mut g);
        g
    }

    /// The maximum over [0, π] and its θ (module doc: grid, parabolic screening, golden
    /// refinement, ends).
    fn maximize(&self, wall: Wall) -> (f64, f64) {
        let vals: Vec<f64> = self.basis.iter().map(|b| self.value(b, wall)).collect();
        let n = vals.len();
        let (mut best, mut best_t) = (vals[0], self.grid[0]);
        for (i, &v) in vals.iter().enumerate() {
            if v > best {
                best = v;
                best_t = self.grid[i];
            }
        }
        let scale = vals.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let floor = best - REFINE_WINDOW * scale;
        for i in 1..n - 1 {
            let (a, b, c) = (vals[i - 1], vals[i], vals[i + 1]);
            if b < a || b < c {
                continue;
            }
            let peak = parabola_peak(&self.grid[i - 1..=i + 1], a, b, c);
            if peak < floor || peak - b <= FLAT * scale {
                continue;
            }
            let (t, v) = refine_max(
                |t| self.required_damping_at(wall, t),
                &self.grid,
                i,
                THETA_TOL,
            );
            if v > best {
                best = v;
                best_t = t;
            }
        }
        (best, best_t)
    }
}

/// q + √(q² + c) for c ≥ 0 without cancellation when q < 0.
fn plus_root(q: f64, c: f64) -> f64 {
    let s = (q * q + c).sqrt();
    if q >= 0.0 {
        q + s
    } else if s - q > 0.0 {
        c / (s - q)
    } else {
        0.0
    }
}

/// The vertex value of the parabola through three samples (the middle one when degenerate).
fn parabola_peak(t: &[f64], a: f64, b: f64, c: f64) -> f64 {
    let (h1, h2) = (t[1] - t[0], t[2] - t[1]);
    // Divided differences of the quadratic through (t0, a), (t1, b), (t2, c).
    let d1 = (b - a) / h1;
    let d2 = (c - b) / h2;
    let curv = (d2 - d1) / (h1 + h2);
    if curv >= 0.0 {
        return b.max(a).max(c);
    }
    // Slope at t1: d1 + curv·h1; vertex at t1 − slope/(2 curv).
    let slope = d1 + curv * h1;
    b - slope * slope / (4.0 * curv)
}

/// Ascending coefficients in z (degree len − 1) as powers of z^{−1}, padded to `len`.
fn reversed_padded(asc: &[f64], len: usize) -> Vec<f64> {
    let mut out = vec![0.0; len];
    for (i, &c) in asc.iter().enumerate() {
        out[len - 1 - i] = c;
    }
    out
}

/// c_m = Σ_l a_{l+m}·b_l for every lag m with a nonzero coefficient.
fn correlation(a: &[f64], b: &[f64]) -> Vec<(i64, f64)> {
    let mut out: Vec<(i64, f64)> = Vec::new();
    let lo = -(b.len() as i64 - 1);
    let hi = a.len() as i64 - 1;
    for m in lo..=hi {
        let c: f64 = b
            .iter()
            .enumerate()
            .filter_map(|(l, &bl)| {
                let k = l as i64 + m;
                (k >= 0 && (k as usize) < a.len()).then(|| a[k as usize] * bl)
            })
            .sum();
        if c != 0.0 {
            out.push((m, c));
        }
    }
    out
}

/// Σ c_k·w^k with w = e^{−jθ} (coefficients in powers of z^{−1}).
fn eval_inverse(c: &[f64], w: Complex64) -> Complex64 {
    crate::poly::eval(c, w)
}

/// The roots of the estimator's denominator (ascending in z).
fn pole_roots(den: &[f64]) -> Vec<Complex64> {
    // Poles at z = 0 (the FIR estimators' z^N) are dropped: they shape nothing on the circle.
    let den = crate::poly::trim(den.to_vec());
    let zeros = den.iter().take_while(|&&x| x == 0.0).count();
    let den = &den[zeros..];
    if den.len() < 2 {
        return Vec::new();
    }
    crate::stability::roots(den).unwrap_or_default()
}

/// Refuses a velocity filter with a pole on or outside the unit circle.
fn check_filter_stable(den: &[f64]) -> Result<()> {
    let den = crate::poly::trim(den.to_vec());
    if den.len() < 2 || crate::stability::schur_stable(&den) {
        return Ok(());
    }
    let radius = pole_roots(&den)
        .iter()
        .map(|z| z.norm())
        .fold(0.0, f64::max);
    Err(Error::Invalid {
        name: "velocity filter",
        reason: format!(
            "has a pole at |z| = {radius} (on or outside the unit circle): the wall is not a \
             stable filter and the passivity condition does not apply"
        ),
    })
}
