//! Passivity of the sampled virtual wall (Section VIII, eq. 28, generalized to any loop):
//! the device damping b that Colgate and Schenkel's condition requires, the verdict for a
//! given device, and the passive region in the (K, B)-plane.
//!
//! # The condition (Colgate & Schenkel 1997)
//!
//! A device of mass m and viscous damping b renders, through a zero-order hold, the discrete
//! wall H(z) = z^{−d}·(K + B·V(z)) (V the velocity estimator, d whole samples of delay). The
//! human can impose any motion. Between two samples the force is constant, so the wall
//! absorbs F_k·(x_{k+1} − x_k), while the damper dissipates at least b·(x_{k+1} − x_k)²/T
//! (equality for a constant velocity within the sample). By Parseval the display is passive
//! iff, for every 0 < θ = ωT ≤ π,
//!
//! ```text
//! b ≥ (T/2) · Re{(1 − e^{−jθ}) H(e^{jθ})} / (1 − cos θ)                       (C–S)
//! ```
//!
//! For the paper's loop (backward difference, d = 0) the right side is KT/2 − B·cos θ, whose
//! maximum is KT/2 + |B|: eq. (28), δ > α/2 + |β| in normalized units. The frequency condition
//! weighs the energy exchanged by a motion; a wall whose static stiffness W(1) = K + B·V(1)
//! is negative also releases the energy ½|W(1)|x² stored at an offset, so passivity further
//! needs W(1) ≥ 0 (the paper states eq. 28 for α ≥ 0).
//!
//! # Evaluation without cancellation
//!
//! Numerator and denominator of (C–S) both vanish like θ² as θ → 0. With
//! 1 − e^{−jθ} = 2j·sin(θ/2)·e^{−jθ/2} and 1 − cos θ = 2 sin²(θ/2) the ratio is
//!
//! ```text
//! Re{(1 − e^{−jθ})H}/(1 − cos θ) = Re X·sin((d + ½)θ)/sin(θ/2) − Im X·cos((d + ½)θ)/sin(θ/2),
//! ```
//!
//! X = K + B·V the wall without its delay. The first factor is the Dirichlet kernel (2d + 1
//! at θ = 0); Im X/sin(θ/2) is formed from the filter's coefficient correlation
//! c_m (X = Σ c_m e^{−jmθ}/|den|²) as −Σ c_m·sin(mθ)/sin(θ/2), each quotient accurate to an ulp
//! and equal to 2m at θ = 0. No difference of nearly equal numbers is formed for any θ, and
//! θ = 0 itself is evaluated exactly (the ratio's finite limit).
//!
//! # A fractional delay: derived, not refused
//!
//! With t_d = (d + λ)T the hold is moved by λT: over sample k the force is F_{k−d−1} on
//! [kT, kT + λT) and F_{k−d} on [kT + λT, (k + 1)T) (as in [`crate::zoh`]). The wall's energy
//! then depends on the position y_k at kT + λT too, which the human chooses freely. Repeating
//! the argument above with constant velocities on both parts of the sample (the damper then
//! dissipates b(y_k − x_k)²/(λT) + b(x_{k+1} − y_k)²/((1 − λ)T), its least for those
//! positions) and minimizing the energy over y at every frequency gives, exactly,
//!
//! ```text
//! b ≥ (T/2)·(q + √(q² + λ(1 − λ)·|X(e^{jθ})|²)),
//! q = ½·Re{(1 − e^{−jθ}) z^{−d} X M}/(1 − cos θ),  M = (1 − λ) + λ·e^{−jθ},
//! ```
//!
//! where M interpolates linearly between the delays d and d + 1 and the square root is the
//! energy the human can pump in by moving within the sample. At λ → 0 this is max(C–S, 0),
//! at λ → 1 the condition for d + 1 whole samples: continuous in the delay. (For λ > 0 every
//! wall needs b > 0; at λ = 0 a wall with negative stiffness may formally allow b < 0.)
//!
//! # The maximum over frequency
//!
//! The requirement is the maximum over 0 ≤ θ ≤ π, found exactly: the function is sampled on
//! a grid fine for its oscillations (64 samples per half-turn of the delay's and the filter's
//! phase, refined around the filter's poles near the unit circle), every local maximum whose
//! parabolic estimate can reach the grid maximum is refined by golden-section search, and the
//! ends θ = 0 (exact limit) and θ = π compete as well. The value is exact to rounding (the
//! function is flat at an interior maximum, so an error δθ in the frequency changes it by
//! O(δθ²)); the binding frequency is accurate to about 1e-8 relative.

use num_complex::Complex64;
use serde::Serialize;

use crate::error::{Error, Result};
use crate::model::{Loop, Plant, PlantModel, strip_leading_zeros};
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

/// Golden-section iterations at most: the bracket shrinks by 0.618 each, from two grid
/// cells (at most π/32) to [`THETA_TOL`] in about 35.
const GOLDEN_ITERATIONS: usize = 64;

/// Width of the final bracket of a frequency maximum, in radians. The function is flat at an
/// interior maximum, so the value there is exact to rounding long before: an error of 1e-9 rad
/// changes it by about f''·1e-18.
pub(crate) const THETA_TOL: f64 = 1e-9;

/// A local maximum whose parabola rises less than this fraction of the function's scale above
/// its grid sample is not refined: the grid value is then already exact to rounding (this
/// also keeps constant stretches, where every sample is a local maximum, cheap).
const FLAT: f64 = 1e-14;

/// Relative width of the band |b − b_required| ≤ BOUNDARY_BAND·scale in which a device is
/// reported as on the passivity boundary rather than passive or not: the requirement is exact
/// to a few ulps, so 1e-12 only absorbs rounding.
pub const BOUNDARY_BAND: f64 = 1e-12;

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
        g.sort_by(f64::total_cmp);
        g.dedup();
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
            let (t, v) = self.golden(wall, self.grid[i - 1], self.grid[i + 1]);
            if v > best {
                best = v;
                best_t = t;
            }
        }
        (best, best_t)
    }

    /// Golden-section search for the maximum on [lo, hi].
    fn golden(&self, wall: Wall, lo: f64, hi: f64) -> (f64, f64) {
        golden_max(|t| self.required_damping_at(wall, t), lo, hi, THETA_TOL)
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

/// The device damping b that the condition compares with, or why there is none.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DeviceDamping {
    /// The damper collocated with the actuator and the encoder, in Ns/m.
    Known {
        /// b in Ns/m.
        damping: f64,
    },
    /// The argument does not apply to this plant.
    NotApplicable {
        /// Why, in words.
        reason: String,
    },
}

/// The device damping of a plant for the passivity condition: the effective b of eq. (1) for
/// the paper's plant (eq. 28 uses δ = bT/m, arm included), the motor-side damping b_m of a
/// two-mass device (the damper where the force acts and the position is measured; the
/// transmission, the handle and the arm are passive and only add to it), b of a transfer
/// function that is exactly c/(m s² + b s + k). Not applicable with an actuator lag (the force
/// is then not held constant over a sample, which the argument rests on) or for any other
/// transfer function (no identified damper).
pub fn device_damping(plant: &Plant) -> DeviceDamping {
    if plant.force_lag > 0.0 {
        return DeviceDamping::NotApplicable {
            reason: "the actuator lag filters the held force, so the sampled-data passivity \
                     argument (force constant over each sample) does not apply"
                .into(),
        };
    }
    match &plant.model {
        PlantModel::MassSpringDamper(e) => DeviceDamping::Known { damping: e.damping },
        PlantModel::TwoMass(t) => DeviceDamping::Known {
            damping: t.motor_damping,
        },
        PlantModel::TransferFunction { num, den } => tf_damping(num, den),
    }
}

fn tf_damping(num: &[f64], den: &[f64]) -> DeviceDamping {
    let (num, den) = (strip_leading_zeros(num), strip_leading_zeros(den));
    if let ([c], [m, b, k]) = (num, den) {
        let (m, b, k) = (m / c, b / c, k / c);
        if m > 0.0 && b >= 0.0 && k >= 0.0 {
            return DeviceDamping::Known { damping: b };
        }
    }
    DeviceDamping::NotApplicable {
        reason: "the transfer-function plant is not a mass-spring-damper c/(ms² + bs + k), \
                 so no device damper can be identified"
            .into(),
    }
}

/// Whether the display is passive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PassivityVerdict {
    /// b > b_required and W(1) >= 0.
    Passive,
    /// b = b_required within [`BOUNDARY_BAND`].
    Boundary,
    /// b < b_required, or the wall's static stiffness is negative.
    NotPassive,
    /// The condition does not apply to this plant (see [`DeviceDamping`]).
    NotApplicable,
}

/// The passivity of one wall on one loop.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Passivity {
    /// The wall (K in N/m, B in Ns/m).
    pub wall: Wall,
    /// The required device damping and its binding frequency.
    pub requirement: DampingRequirement,
    /// The wall's static stiffness W(1) = K + B·V(1) in N/m (must be >= 0).
    pub dc_stiffness: f64,
    /// The device's damping.
    pub device: DeviceDamping,
    /// The verdict.
    pub verdict: PassivityVerdict,
}

/// Passivity of a wall on a loop (Colgate–Schenkel; eq. 28 for the paper's loop): the
/// required device damping, the device's damping and the verdict.
pub fn passivity(lp: &Loop, wall: Wall) -> Result<Passivity> {
    let sw = SampledWall::new(lp)?;
    Ok(passivity_with(&sw, lp, wall))
}

/// As [`passivity`] with the wall structure already built.
pub fn passivity_with(sw: &SampledWall, lp: &Loop, wall: Wall) -> Passivity {
    passivity_of_device(sw, wall, device_damping(&lp.plant))
}

/// Passivity of a wall for a given device damper (Colgate–Schenkel; eq. 28 for the paper's
/// loop): the requirement of the wall structure `sw` against `device`, e.g. a damping other
/// than the plant's own [`device_damping`] ("would a device with b = … render it passively?").
pub fn passivity_of_device(sw: &SampledWall, wall: Wall, device: DeviceDamping) -> Passivity {
    let requirement = sw.required_damping(wall);
    let dc_stiffness = sw.dc_stiffness(wall);
    let verdict = match &device {
        DeviceDamping::NotApplicable { .. } => PassivityVerdict::NotApplicable,
        DeviceDamping::Known { damping } => {
            verdict_for(*damping, requirement.b_required, dc_stiffness)
        }
    };
    Passivity {
        wall,
        requirement,
        dc_stiffness,
        device,
        verdict,
    }
}

fn verdict_for(b: f64, required: f64, dc_stiffness: f64) -> PassivityVerdict {
    if dc_stiffness < 0.0 {
        return PassivityVerdict::NotPassive;
    }
    let band = BOUNDARY_BAND * b.abs().max(required.abs());
    if (b - required).abs() <= band {
        PassivityVerdict::Boundary
    } else if b > required {
        PassivityVerdict::Passive
    } else {
        PassivityVerdict::NotPassive
    }
}

/// The passive region of a loop for a device damping b (Section VIII, Fig. 9, generalized):
/// {(K, B): W(1) ≥ 0, b_required(K, B) < b} as a counter-clockwise polygon in physical units.
///
/// b_required is convex and positively homogeneous in (K, B) (a maximum over θ of linear
/// functions, or of q + √(q² + c|X|²) which is a norm plus a linear function), so the region
/// is convex, has the origin as a corner on the line W(1) = 0, and scales linearly with b.
/// Its boundary point in each direction u is u·b/b_required(u); the polygon's vertices are
/// such exact boundary points, placed adaptively until every chord is within
/// [`PASSIVE_REL_TOL`] of the boundary.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PassiveRegion {
    /// The device damping b in Ns/m.
    pub device_damping: f64,
    /// Counter-clockwise vertices (K in N/m, B in Ns/m), the first not repeated; empty when
    /// b <= 0.
    pub vertices: Vec<Wall>,
    /// False when b_required <= 0 along some direction: the region is then unbounded and the
    /// polygon is cut at [`UNBOUNDED_CLIP`] times its bounded size.
    pub bounded: bool,
    /// The largest passive stiffness K in N/m (exact, not a vertex maximum; NaN when empty,
    /// infinite when unbounded in K).
    pub k_max: f64,
    /// The damping B in Ns/m at which it is reached.
    pub b_at_k_max: f64,
    /// Area in N/m · Ns/m.
    pub area: f64,
}

/// Chord tolerance of passive-region polygons, relative to the region's size in the
/// (KT/2, B)-plane: far below a plot's resolution; the largest passive stiffness is found
/// exactly on the boundary, not from the vertices.
pub const PASSIVE_REL_TOL: f64 = 1e-5;

/// Final bracket of the direction search for the largest passive stiffness, in radians: the
/// boundary's K is flat at its maximum, so 1e-10 rad leaves the value exact to rounding.
const DIRECTION_TOL: f64 = 1e-10;

/// An unbounded passive region is cut at this multiple of its bounded part's size.
pub const UNBOUNDED_CLIP: f64 = 10.0;

/// Initial directions of the adaptive boundary sampling (a half-turn of directions).
const INITIAL_DIRECTIONS: usize = 32;

/// Bisection depth limit of the boundary sampling: 2^-40 of a half-turn is far below any
/// tolerance; the limit only bounds the work at a corner.
const MAX_DEPTH: usize = 40;

impl PassiveRegion {
    /// True iff the wall lies inside the polygon (even-odd rule); the exact test is
    /// [`SampledWall::required_damping`] against b.
    pub fn contains(&self, wall: Wall) -> bool {
        let n = self.vertices.len();
        let mut inside = false;
        for i in 0..n {
            let (a, b) = (self.vertices[i], self.vertices[(i + 1) % n]);
            if (a.damping > wall.damping) != (b.damping > wall.damping) {
                let k = a.stiffness
                    + (wall.damping - a.damping) / (b.damping - a.damping)
                        * (b.stiffness - a.stiffness);
                if wall.stiffness < k {
                    inside = !inside;
                }
            }
        }
        inside
    }
}

/// A direction's boundary point in (κ, B) = (KT/2, B), Ns/m both; None when unbounded.
fn ray_point(sw: &SampledWall, b: f64, phi: f64) -> Option<(f64, f64)> {
    let (s, c) = phi.sin_cos();
    let wall = Wall {
        stiffness: 2.0 * c / sw.period,
        damping: s,
    };
    let need = sw.required_damping(wall).b_required;
    (need > 0.0).then(|| (c * b / need, s * b / need))
}

/// The passive region of a loop's wall for device damping b (see [`PassiveRegion`]).
pub fn passive_region(sw: &SampledWall, b: f64) -> Result<PassiveRegion> {
    crate::error::finite("device damping b", b)?;
    if b <= 0.0 {
        return Ok(PassiveRegion {
            device_damping: b,
            vertices: Vec::new(),
            bounded: true,
            k_max: f64::NAN,
            b_at_k_max: f64::NAN,
            area: 0.0,
        });
    }
    let half_t = 0.5 * sw.period;
    let (lo, hi) = direction_range(sw);
    let pts = boundary_points(sw, b, lo, hi);
    let bounded = pts.iter().all(|p| p.1.is_some());
    let size = pts
        .iter()
        .filter_map(|p| p.1)
        .fold(0.0_f64, |m, (x, y)| m.max(x.hypot(y)))
        .max(f64::MIN_POSITIVE);
    let clip = UNBOUNDED_CLIP * size;
    let to_wall = |(phi, p): &(f64, Option<(f64, f64)>)| {
        let (x, y) = p.unwrap_or((clip * phi.cos(), clip * phi.sin()));
        Wall {
            stiffness: x / half_t,
            damping: y,
        }
    };
    let mut vertices = vec![Wall {
        stiffness: 0.0,
        damping: 0.0,
    }];
    vertices.extend(pts.iter().map(to_wall));
    // The end directions lie on the line W(1) = 0 exactly (cos(±π/2) rounds to 6e-17).
    let v1 = sw.dc_velocity();
    for i in [1, vertices.len() - 1] {
        vertices[i].stiffness = -vertices[i].damping * v1;
    }
    let (k_max, b_at_k_max) = if bounded {
        largest_stiffness(sw, b, &pts)
    } else {
        (f64::INFINITY, f64::NAN)
    };
    let area = shoelace(&vertices);
    Ok(PassiveRegion {
        device_damping: b,
        vertices,
        bounded,
        k_max,
        b_at_k_max,
        area,
    })
}

type RayPoint = (f64, Option<(f64, f64)>);

/// Boundary points for directions lo..=hi, refined until chords are within tolerance.
fn boundary_points(sw: &SampledWall, b: f64, lo: f64, hi: f64) -> Vec<RayPoint> {
    let at = |phi: f64| (phi, ray_point(sw, b, phi));
    let init: Vec<RayPoint> = (0..=INITIAL_DIRECTIONS)
        .map(|i| at(lo + (hi - lo) * i as f64 / INITIAL_DIRECTIONS as f64))
        .collect();
    let size = init
        .iter()
        .filter_map(|p| p.1)
        .fold(0.0_f64, |m, (x, y)| m.max(x.hypot(y)));
    let tol = PASSIVE_REL_TOL * size;
    let mut out = vec![init[0]];
    for w in init.windows(2) {
        refine_chord(&at, w[0], w[1], tol, 0, &mut out);
        out.push(w[1]);
    }
    out
}

/// Inserts boundary points between a and b (exclusive) until the chord is within tol.
fn refine_chord(
    at: &impl Fn(f64) -> RayPoint,
    a: RayPoint,
    b: RayPoint,
    tol: f64,
    depth: usize,
    out: &mut Vec<RayPoint>,
) {
    if depth >= MAX_DEPTH {
        return;
    }
    let m = at(0.5 * (a.0 + b.0));
    let far = match (a.1, m.1, b.1) {
        (Some(pa), Some(pm), Some(pb)) => chord_distance(pa, pb, pm) > tol,
        (None, None, None) => false,
        _ => true, // where the region turns unbounded: resolve the transition
    };
    if far {
        refine_chord(at, a, m, tol, depth + 1, out);
        out.push(m);
        refine_chord(at, m, b, tol, depth + 1, out);
    }
}

/// Distance from p to the segment a–b.
fn chord_distance(a: (f64, f64), b: (f64, f64), p: (f64, f64)) -> f64 {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let len2 = dx * dx + dy * dy;
    if len2 == 0.0 {
        return (p.0 - a.0).hypot(p.1 - a.1);
    }
    let t = (((p.0 - a.0) * dx + (p.1 - a.1) * dy) / len2).clamp(0.0, 1.0);
    (p.0 - a.0 - t * dx).hypot(p.1 - a.1 - t * dy)
}

/// The largest passive stiffness for device damping b, and the damping where it is reached
/// (exact, without building the polygon): the best of [`INITIAL_DIRECTIONS`] boundary points,
/// refined by golden-section search over the direction. None when b <= 0; K infinite when
/// the region is unbounded.
pub fn passive_k_max(sw: &SampledWall, b: f64) -> Option<Wall> {
    if !(b > 0.0 && b.is_finite()) {
        return None;
    }
    let (lo, hi) = direction_range(sw);
    let pts: Vec<RayPoint> = (0..=INITIAL_DIRECTIONS)
        .map(|i| {
            let phi = lo + (hi - lo) * i as f64 / INITIAL_DIRECTIONS as f64;
            (phi, ray_point(sw, b, phi))
        })
        .collect();
    if pts.iter().any(|p| p.1.is_none()) {
        return Some(Wall {
            stiffness: f64::INFINITY,
            damping: f64::NAN,
        });
    }
    let (k, d) = largest_stiffness(sw, b, &pts);
    Some(Wall {
        stiffness: k,
        damping: d,
    })
}

/// The admissible directions (W(1) >= 0) in the (KT/2, B)-plane: a half-turn centred on the
/// normal of the line W(1) = 0.
fn direction_range(sw: &SampledWall) -> (f64, f64) {
    let center = sw.dc_velocity().atan2(2.0 / sw.period);
    (
        center - std::f64::consts::FRAC_PI_2,
        center + std::f64::consts::FRAC_PI_2,
    )
}

/// The largest passive K and its B: the best vertex, refined by golden-section search over the
/// direction (on a convex region the boundary's K is unimodal in the direction).
fn largest_stiffness(sw: &SampledWall, b: f64, pts: &[RayPoint]) -> (f64, f64) {
    let kappa = |p: &RayPoint| p.1.map_or(f64::NEG_INFINITY, |(x, _)| x);
    let Some(i) = (0..pts.len()).max_by(|&i, &j| kappa(&pts[i]).total_cmp(&kappa(&pts[j]))) else {
        return (f64::NAN, f64::NAN);
    };
    let lo = pts[i.saturating_sub(1)].0;
    let hi = pts[(i + 1).min(pts.len() - 1)].0;
    let f = |phi: f64| ray_point(sw, b, phi).map_or(f64::NEG_INFINITY, |(x, _)| x);
    let (phi, _) = golden_max(f, lo, hi, DIRECTION_TOL);
    let best = [pts[i].0, phi]
        .into_iter()
        .max_by(|&x, &y| f(x).total_cmp(&f(y)))
        .unwrap_or(phi);
    let (x, y) = ray_point(sw, b, best).unwrap_or((f64::NAN, f64::NAN));
    (x / (0.5 * sw.period), y)
}

/// Golden-section search for the maximum of f on [lo, hi] down to a bracket of width tol:
/// (argmax, max).
pub(crate) fn golden_max(f: impl Fn(f64) -> f64, mut lo: f64, mut hi: f64, tol: f64) -> (f64, f64) {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let mut x1 = hi - r * (hi - lo);
    let mut x2 = lo + r * (hi - lo);
    let (mut f1, mut f2) = (f(x1), f(x2));
    for _ in 0..GOLDEN_ITERATIONS {
        if f1 >= f2 {
            hi = x2;
            x2 = x1;
            f2 = f1;
            x1 = hi - r * (hi - lo);
            f1 = f(x1);
        } else {
            lo = x1;
            x1 = x2;
            f1 = f2;
            x2 = lo + r * (hi - lo);
            f2 = f(x2);
        }
        if hi - lo <= tol {
            break;
        }
    }
    if f1 >= f2 { (x1, f1) } else { (x2, f2) }
}

/// Shoelace area of a polygon in physical units.
fn shoelace(v: &[Wall]) -> f64 {
    let n = v.len();
    (0..n)
        .map(|i| {
            let (a, b) = (v[i], v[(i + 1) % n]);
            a.stiffness * b.damping - b.stiffness * a.damping
        })
        .sum::<f64>()
        * 0.5
}

/// Bisection steps for the largest passive K at a damping: from a bracket of any size down to
/// one ulp takes at most about 1100 halvings of the exponent range; 200 is plenty for the
/// brackets found by doubling.
const BISECTION_STEPS: usize = 200;

/// The largest passive stiffness K in N/m at a given damping B (None when no K >= −B·V(1) is
/// passive there): b_required is convex in K, so it crosses b once; found by bisection to
/// full precision.
pub fn k_max_passive_at(sw: &SampledWall, b: f64, damping: f64) -> Option<f64> {
    let k_lo = -damping * sw.dc_velocity();
    let need = |k: f64| {
        sw.required_damping(Wall {
            stiffness: k,
            damping,
        })
        .b_required
    };
    let at_lo = need(k_lo);
    if at_lo.is_nan() || at_lo >= b {
        return None;
    }
    let mut step = 2.0 * b / sw.period;
    let mut k_hi = k_lo + step;
    let mut guard = 0;
    while need(k_hi) < b {
        step *= 2.0;
        k_hi = k_lo + step;
        guard += 1;
        if guard > 2000 || !k_hi.is_finite() {
            return Some(f64::INFINITY);
        }
    }
    let mut lo = k_lo;
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (lo + k_hi);
        if mid <= lo || mid >= k_hi {
            break;
        }
        if need(mid) < b {
            lo = mid;
        } else {
            k_hi = mid;
        }
    }
    Some(lo)
}
