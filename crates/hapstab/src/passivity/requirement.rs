//! The device damping a wall requires (Colgate–Schenkel's condition, eq. 28 generalized): the
//! wall's frequency structure, the requirement at one frequency, and its exact maximum over
//! frequency (see the [parent module](super) for the derivation).

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::extremum::{merge_grid, refine_max};
use crate::model::Loop;
use crate::param::Param;
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

/// Lags of the filter correlation whose e^{imθ} is a power of e^{iθ} in
/// [`SampledWall::basis_at`] (larger ones take their own sine and cosine).
const POWER_LAGS: usize = 8;

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
    /// The largest |m| of the correlation's lags.
    max_lag: usize,
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
        let corr = correlation(&vm, &vd);
        let max_lag = corr
            .iter()
            .map(|(m, _)| m.unsigned_abs() as usize)
            .max()
            .unwrap_or(0);
        let mut wall = Self {
            period: lp.period,
            d: lp.delay.samples,
            lambda,
            corr,
            max_lag,
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

    /// The uniform spacing of the grid the maximum over θ is screened on, in rad.
    pub fn grid_step(&self) -> f64 {
        std::f64::consts::PI / (SAMPLES_PER_TURN * self.turns()) as f64
    }

    /// Half-turns of phase the grid resolves: the delay's and each filter coefficient's.
    fn turns(&self) -> usize {
        self.d + self.vn.len() + 2
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

    /// ∂/∂B of [`SampledWall::required_damping_at`] at a fixed θ, in s: the slope of one of
    /// the convex functions of B whose maximum over θ is the requirement, so that at the
    /// maximizing θ it is a subgradient of [`SampledWall::required_damping`] in B (Danskin).
    /// Where the square root of the fractional-delay form vanishes, the middle of its
    /// subdifferential.
    pub fn required_damping_slope_at(&self, wall: Wall, theta: f64) -> f64 {
        let b = self.basis_at(theta);
        let (k, bb) = (wall.stiffness, wall.damping);
        let half_t = 0.5 * self.period;
        if self.lambda == 0.0 {
            return half_t * b.rb;
        }
        // d/dB of q + √(q² + c·|X|²): q = ratio/2, |X|² = K² + 2KB·Re V + B²|V|²
        let q = 0.5 * (k * b.rk + bb * b.rb);
        let dq = 0.5 * b.rb;
        let c = self.lambda * (1.0 - self.lambda);
        let w2 = (k * k + 2.0 * k * bb * b.re_v + bb * bb * b.abs_v2).max(0.0);
        let dw2 = 2.0 * k * b.re_v + 2.0 * bb * b.abs_v2;
        let root = (q * q + c * w2).sqrt();
        if root > 0.0 {
            half_t * (dq + (q * dq + 0.5 * c * dw2) / root)
        } else {
            half_t * dq
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

    /// The frequency basis at θ, free of cancellation (module doc). e^{imθ} for the
    /// correlation's lags |m| <= [`POWER_LAGS`] are powers of e^{iθ} (built from the half
    /// angle: cos θ = 1 − 2 sin²(θ/2), sin θ = 2 sin(θ/2) cos(θ/2)); for mθ < π/2 every product
    /// adds positive terms, so sin(mθ) keeps a relative error of a few ulps however small θ.
    fn basis_at(&self, theta: f64) -> Basis {
        let (sh, ch) = crate::circle::sin_cos(0.5 * theta);
        let d = self.d as f64;
        let (sphi, cphi) = crate::circle::sin_cos((d + 0.5) * theta);
        let dirichlet = if theta == 0.0 {
            2.0 * d + 1.0
        } else {
            sphi / sh
        };
        let lam = self.lambda;
        let rk = (1.0 - 2.0 * lam * sh * sh) * dirichlet + 2.0 * lam * ch * cphi;
        let z = Complex64::new(1.0 - 2.0 * sh * sh, 2.0 * sh * ch);
        let mut powers = [Complex64::new(1.0, 0.0); POWER_LAGS + 1];
        let top = self.max_lag.min(POWER_LAGS);
        for j in 1..=top {
            powers[j] = powers[j - 1] * z;
        }
        let powers = &powers[..=top];
        let (mut re_c, mut im_c_over) = (0.0, 0.0);
        for &(m, c) in &self.corr {
            let k = m.unsigned_abs() as usize;
            let (s, co) = match powers.get(k) {
                Some(p) => (p.im * m.signum() as f64, p.re),
                None => crate::circle::sin_cos(m as f64 * theta),
            };
            re_c += c * co;
            let s_over = if theta == 0.0 { 2.0 * m as f64 } else { s / sh };
            im_c_over -= c * s_over;
        }
        let z_inv = z.conj();
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
        let n = SAMPLES_PER_TURN * self.turns();
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
        let s = self.maximize_in(wall, std::slice::from_ref(&(0..self.grid.len())));
        (s.value, s.theta)
    }

    /// The requirement as [`SampledWall::required_damping`], with the grid indices of the
    /// maxima it refined (and of the best sample): where a nearby wall binds.
    pub(crate) fn required_damping_screened(&self, wall: Wall) -> Screened {
        self.maximize_in(wall, std::slice::from_ref(&(0..self.grid.len())))
    }

    /// The maximum over the grid cells of `windows` alone (sorted, disjoint index ranges):
    /// a lower bound of the requirement, equal to it when the wall binds inside them.
    pub(crate) fn required_damping_within(
        &self,
        wall: Wall,
        windows: &[std::ops::Range<usize>],
    ) -> Screened {
        self.maximize_in(wall, windows)
    }

    /// The number of grid samples.
    pub(crate) fn grid_len(&self) -> usize {
        self.grid.len()
    }

    /// The grid index nearest θ.
    pub(crate) fn grid_index(&self, theta: f64) -> usize {
        let i = self.grid.partition_point(|&t| t < theta);
        if i > 0 && (i == self.grid.len() || theta - self.grid[i - 1] < self.grid[i] - theta) {
            i - 1
        } else {
            i.min(self.grid.len() - 1)
        }
    }

    /// The module doc's screening on the samples of `windows`.
    fn maximize_in(&self, wall: Wall, windows: &[std::ops::Range<usize>]) -> Screened {
        let mut out = Screened {
            value: f64::NEG_INFINITY,
            theta: f64::NAN,
            refined: Vec::new(),
        };
        let mut vals: Vec<(usize, f64)> = Vec::new();
        let mut best_i = 0;
        for w in windows {
            for i in w.clone() {
                let v = self.value(&self.basis[i], wall);
                if v > out.value || out.theta.is_nan() {
                    (out.value, out.theta, best_i) = (v, self.grid[i], i);
                }
                vals.push((i, v));
            }
        }
        out.refined.push(best_i);
        let scale = vals.iter().fold(0.0_f64, |m, v| m.max(v.1.abs()));
        let floor = out.value - REFINE_WINDOW * scale;
        for k in 1..vals.len().saturating_sub(1) {
            let ((ia, a), (i, b), (ic, c)) = (vals[k - 1], vals[k], vals[k + 1]);
            if ia + 1 != i || i + 1 != ic || b < a || b < c {
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
            out.refined.push(i);
            if v > out.value {
                (out.value, out.theta) = (v, t);
            }
        }
        out
    }
}

/// A requirement found by screening part or all of the grid: the maximum, its θ and the grid
/// indices of the maxima refined (the best sample's first).
#[derive(Debug, Clone)]
pub(crate) struct Screened {
    /// The largest requirement found, in Ns/m.
    pub value: f64,
    /// Its θ.
    pub theta: f64,
    /// Grid indices where the requirement peaks.
    pub refined: Vec<usize>,
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
        param: Param::VelocityFilter,
        reason: format!(
            "has a pole at |z| = {radius} (on or outside the unit circle): the wall is not a \
             stable filter and the passivity condition does not apply"
        ),
    })
}
