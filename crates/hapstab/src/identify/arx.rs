//! The starting point of the fit: a linear least-squares (equation-error, ARX-type) estimate
//! of the model's continuous transfer function through a state-variable filter (Young 1981;
//! Garnier, Mensler & Richard, Int. J. Control 76, 2003), mapped to the physical parameters.
//!
//! A discrete ARX fit at a fast sampling rate puts every pole near z = 1 where its
//! coefficients are ill-conditioned, and its mapping back to m, b, k is nonlinear; instead
//! the force and the position pass through the same filter λⁿ/(s + λ)ⁿ (n = D + 1), whose
//! states give their filtered derivatives, and den(s)·y = num(s)·u holds for the filtered
//! signals (the plant starts at rest, the filter too), so that
//!
//! ```text
//! y_f^(D) = −a_{D−1} y_f^(D−1) − … − a_0 y_f + b_N u_f^(N) + … + b_0 u_f + c·1_f
//! ```
//!
//! is linear in the monic transfer function's coefficients (c = a_0·y_0 absorbs the
//! position's offset). The steps:
//! 1. **filter** the held force (delayed as the loop delays it) and the position (averaged
//!    over each sample, which centres it on the held interval) exactly: the filter is
//!    sampled by [`crate::zoh::exp_and_integral`] in the time unit 1/λ, where its companion
//!    matrix has the binomial coefficients;
//! 2. **regress** y_f^(D) on the other columns (after the filter's transient), each column
//!    scaled to unit norm;
//! 3. **map** the coefficients to the model's parameters (the held ones keep their values,
//!    a negative estimate of a positive parameter is reflected);
//! 4. **rank** the starts of every λ in [`BANDWIDTHS`] by their output error: the
//!    refinement runs from each and keeps the best optimum (a start that explains the slow
//!    motion well may miss a resonance that another bandwidth catches).

use nalgebra::{DMatrix, DVector};

use super::data::Record;
use super::error::{IdResult, IdentifyError};
use super::model::{Domain, ModelKind, ModelSpec};
use super::response::SampledModel;
use crate::model::VelocityEstimator;
use crate::zoh::exp_and_integral;

/// The filter's bandwidths tried, as fractions of the sampling rate 1/T (in rad/s): from
/// slow plants (a soft arm at 1 Hz under a 1 kHz loop) to fast ones (a transmission mode at
/// a tenth of the rate).
pub const BANDWIDTHS: [f64; 6] = [0.002, 0.005, 0.01, 0.02, 0.05, 0.1];

/// Filter time constants 1/λ skipped at the start of the regression: the filter's transient
/// (its slowest mode, (λt)ⁿ e^{−λt}, is below 10⁻⁶ after 30 for n ≤ 13).
const TRANSIENT: f64 = 30.0;

/// A start: the full parameter vector and the position offset y_0.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    /// Every parameter of the model (held ones at their values).
    pub values: Vec<f64>,
    /// The position offset y_0 in m.
    pub offset: f64,
}

/// The continuous structure the regression fits: orders, and whether the plant integrates
/// (a_0 = 0: a free mass).
pub(crate) struct Structure {
    pub(crate) num: usize,
    pub(crate) den: usize,
    pub(crate) integrates: bool,
}

pub(crate) fn structure(spec: &ModelSpec) -> Structure {
    let held_zero = |name: &str| {
        let params = spec.kind.params();
        params
            .iter()
            .position(|p| p.name == name)
            .and_then(|i| spec.held(i))
            == Some(0.0)
    };
    match spec.kind {
        ModelKind::MassSpringDamper => Structure {
            num: 0,
            den: 2,
            integrates: held_zero("stiffness"),
        },
        ModelKind::HeldDevice => Structure {
            num: 0,
            den: 2,
            integrates: held_zero("arm-stiffness"),
        },
        ModelKind::TwoMass => Structure {
            num: 2,
            den: 4,
            integrates: true,
        },
        ModelKind::TransferFunction {
            num_order,
            den_order,
        } => Structure {
            num: num_order,
            den: den_order,
            integrates: held_zero("a0"),
        },
    }
}

/// The initial estimates (module doc), one per filter bandwidth that gives a usable one,
/// best output error first; refused when none does.
pub fn initial_estimates(record: &Record, spec: &ModelSpec) -> IdResult<Vec<Start>> {
    let st = structure(spec);
    let mut starts: Vec<(f64, Start)> = Vec::new();
    for frac in BANDWIDTHS {
        let lambda = frac * 2.0 * std::f64::consts::PI / record.period;
        let Some((a, b)) = regress(record, spec, &st, lambda) else {
            continue;
        };
        let Some(mut values) = to_physical(spec, &a, &b) else {
            continue;
        };
        values.extend(spec.timing_start(record.period));
        let Some((cost, offset)) = output_error(record, spec, &values) else {
            continue;
        };
        starts.push((cost, Start { values, offset }));
    }
    if starts.is_empty() {
        return Err(IdentifyError::NoFit(format!(
            "no initial estimate of {} explains the data (the linear least-squares fit gave no physical plant at any filter bandwidth)",
            spec.kind.name()
        )));
    }
    starts.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(starts.into_iter().map(|(_, s)| s).collect())
}

/// The sum of squared output errors of a start and its best offset (the mean residual).
pub(crate) fn output_error(
    record: &Record,
    spec: &ModelSpec,
    values: &[f64],
) -> Option<(f64, f64)> {
    let lp = spec
        .to_loop(values, record.period, VelocityEstimator::Backward)
        .ok()?;
    let y = SampledModel::of_loop(&lp).ok()?.simulate(&record.force);
    let n = y.len() as f64;
    let offset = record
        .position
        .iter()
        .zip(&y)
        .map(|(m, s)| m - s)
        .sum::<f64>()
        / n;
    let cost: f64 = record
        .position
        .iter()
        .zip(&y)
        .map(|(m, s)| (m - s - offset).powi(2))
        .sum();
    cost.is_finite().then_some((cost, offset))
}

/// The filtered derivatives 0..=order of a held signal w through 1/(σ + 1)^(order+1), σ = s/λ,
/// in the time unit 1/λ, one column per derivative.
fn filtered(w: &[f64], order: usize, step: f64) -> Vec<Vec<f64>> {
    let n = order + 1;
    // (σ + 1)^n = Σ C(n, i) σ^i: companion matrix of the chain of integrators.
    let binom: Vec<f64> = (0..=n)
        .scan(1.0, |c, i| {
            let v = *c;
            *c = *c * (n - i) as f64 / (i + 1) as f64;
            Some(v)
        })
        .collect();
    let mut a = vec![vec![0.0; n]; n];
    for i in 0..n - 1 {
        a[i][i + 1] = 1.0;
    }
    for (i, c) in binom[..n].iter().enumerate() {
        a[n - 1][i] = -c;
    }
    let (e, psi) = exp_and_integral(&a, step);
    let gamma: Vec<f64> = psi.iter().map(|row| row[n - 1]).collect();
    let mut z = vec![0.0; n];
    let mut cols = vec![Vec::with_capacity(w.len()); n];
    for &wk in w {
        for (col, zi) in cols.iter_mut().zip(&z) {
            col.push(*zi);
        }
        let next: Vec<f64> = (0..n)
            .map(|i| z[i] + e[i].iter().zip(&z).map(|(a, z)| a * z).sum::<f64>() + gamma[i] * wk)
            .collect();
        z = next;
    }
    cols.truncate(order + 1);
    cols
}

/// The force in effect over each sample: F_{k−d} after the whole delay, mixed with
/// F_{k−d−1} over the fraction λ of the sample that it still holds.
fn held_force(record: &Record, spec: &ModelSpec) -> Vec<f64> {
    let samples = spec.delay_time / record.period;
    let d = samples.floor() as usize;
    let frac = samples - d as f64;
    let at = |j: isize| {
        if j >= 0 {
            record.force[j as usize]
        } else {
            0.0
        }
    };
    (0..record.len() as isize)
        .map(|k| (1.0 - frac) * at(k - d as isize) + frac * at(k - d as isize - 1))
        .collect()
}

/// The monic transfer function's (a_0..a_{D−1}, b_0..b_N) from the filtered regression at
/// bandwidth λ (rad/s); None when the regression is degenerate.
fn regress(
    record: &Record,
    spec: &ModelSpec,
    st: &Structure,
    lambda: f64,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let step = lambda * record.period;
    let n = record.len();
    let y_mid: Vec<f64> = (0..n)
        .map(|k| 0.5 * (record.position[k] + record.position[(k + 1).min(n - 1)]))
        .collect();
    let yf = filtered(&y_mid, st.den, step);
    let uf = filtered(&held_force(record, spec), st.num.max(st.den), step);
    let ones = filtered(&vec![1.0; n], 0, step);
    let skip = ((TRANSIENT / step).ceil() as usize).min(n / 2);
    let first_a = usize::from(st.integrates);
    let mut cols: Vec<Vec<f64>> = (first_a..st.den).map(|i| yf[i][skip..].to_vec()).collect();
    cols.extend((0..=st.num).map(|j| uf[j][skip..].to_vec()));
    if !st.integrates {
        cols.push(ones[0][skip..].to_vec());
    }
    let target = DVector::from_column_slice(&yf[st.den][skip..]);
    let coef = least_squares(&cols, &target)?;
    // back from the time unit 1/λ: a_i = α_i λ^{D−i}, b_j = β_j λ^{D−j}; α enters with −.
    let d = st.den as i32;
    let mut a = vec![0.0; st.den];
    for (k, i) in (first_a..st.den).enumerate() {
        a[i] = -coef[k] * lambda.powi(d - i as i32);
    }
    let na = st.den - first_a;
    let b = (0..=st.num)
        .map(|j| coef[na + j] * lambda.powi(d - j as i32))
        .collect();
    Some((a, b))
}

/// Least squares with every column scaled to unit norm (SVD); None when a column is zero or
/// the solution is not finite.
fn least_squares(cols: &[Vec<f64>], target: &DVector<f64>) -> Option<Vec<f64>> {
    let rows = target.len();
    let norms: Vec<f64> = cols
        .iter()
        .map(|c| c.iter().map(|x| x * x).sum::<f64>().sqrt())
        .collect();
    if norms.iter().any(|&s| s == 0.0 || !s.is_finite()) {
        return None;
    }
    let m = DMatrix::from_fn(rows, cols.len(), |i, j| cols[j][i] / norms[j]);
    let sol = m.svd(true, true).solve(target, 1e-12).ok()?;
    let coef: Vec<f64> = sol.iter().zip(&norms).map(|(c, s)| c / s).collect();
    coef.iter().all(|c| c.is_finite()).then_some(coef)
}

/// The model's parameters from the monic transfer function (a, b) (module doc step 3);
/// None when they are not finite.
pub(crate) fn to_physical(spec: &ModelSpec, a: &[f64], b: &[f64]) -> Option<Vec<f64>> {
    let raw = match spec.kind {
        ModelKind::MassSpringDamper => {
            let m = 1.0 / b[0];
            vec![m, a[1] * m, a[0] * m]
        }
        ModelKind::HeldDevice => {
            let m = 1.0 / b[0];
            let (ml, bl) = (spec.held(0).unwrap_or(0.0), spec.held(1).unwrap_or(0.0));
            // a light or weakly damped arm may come out below the device's part: take a
            // tenth of the total instead
            let part = |total: f64, device: f64| {
                if total - device > 0.0 {
                    total - device
                } else {
                    0.1 * total.abs()
                }
            };
            vec![ml, bl, part(m, ml), part(a[1] * m, bl), a[0] * m]
        }
        ModelKind::TwoMass => two_mass(a, b),
        ModelKind::TransferFunction { .. } => b.iter().chain(a).copied().collect(),
    };
    let params = spec.params();
    let values: Vec<f64> = raw
        .iter()
        .enumerate()
        .map(|(i, &v)| match (spec.held(i), params[i].domain) {
            (Some(h), _) => h,
            (None, Domain::Positive) => v.abs(),
            (None, Domain::Real) => v,
        })
        .collect();
    values
        .iter()
        .enumerate()
        .all(|(i, v)| v.is_finite() && (spec.held(i).is_some() || *v != 0.0))
        .then_some(values)
}

/// J, b_m, m_h, k_t, b_t of a free two-mass device from its monic transfer function
/// (n2 s² + n1 s + n0)/(s⁴ + d3 s³ + d2 s² + d1 s): n2 = 1/J, n1 = b_t/(J m_h),
/// n0 = k_t/(J m_h), d1 = b_m k_t/(J m_h), d2 = k_t/m_h + k_t/J + b_m b_t/(J m_h).
fn two_mass(a: &[f64], b: &[f64]) -> Vec<f64> {
    let (n0, n1, n2) = (b[0], b[1], b[2]);
    let (d1, d2) = (a[1], a[2]);
    let j = 1.0 / n2;
    let bm = d1 / n0;
    let mh = (d2 - n0 * j - bm * n1) / n0;
    vec![j, bm, mh, n0 * j * mh, n1 * j * mh]
}
