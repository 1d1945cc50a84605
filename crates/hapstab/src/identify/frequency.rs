//! Identification from a measured frequency response: the model's exact sampled response
//! H(e^{jωT}) (zero-order hold, delay, lag; [`crate::zoh`]) fitted to measured complex
//! values at frequencies below the Nyquist frequency.
//!
//! The residual of frequency ω_i is the complex logarithm of the ratio,
//! ln(Ĥ(ω_i)/H_i) = Δln|H| + j·Δ∠H: its real part is the magnitude's error in nepers
//! (0.1 dB = 0.0115) and its imaginary part the phase's in radians (1° = 0.0175), so a
//! measurement with errors of a given size in dB and degrees weighs every frequency alike,
//! and the fit is least squares on both parts (Pintelon & Schoukens, *System Identification:
//! A Frequency Domain Approach*, 2nd ed., 2012, §9.4: the logarithmic least-squares
//! estimator). The steps mirror the time-domain fit:
//! 1. **data**: columns `frequency` (Hz) and `magnitude_db`, `phase_deg` or `real`, `imag`;
//! 2. **start**: Levy's complex linear least squares (IRE Trans. AC-4, 1959) on
//!    den(jω)·H = num(jω) for the monic continuous transfer function, the data first
//!    advanced by the hold's half sample and the delay, each equation divided by the size
//!    of den(jω)·H — first with (jω + ω_c)^D for den (ω_c the frequencies' geometric mean),
//!    then [`SK_ITERATIONS`] times with the last solution's den (Sanathanan & Koerner, IEEE
//!    Trans. AC-8, 1963), so that every equation weighs the response's relative error as
//!    the refinement's logarithm does (with (jω)^D for den the low frequencies weigh
//!    (a_0/ω^D)² too much, and a 0.5 dB response's start could be orders of magnitude off);
//! 3. **refine**: Levenberg–Marquardt on the logarithmic residuals, positive parameters as
//!    logarithms; standard errors and 95 % intervals from the Jacobian.
//!
//! H(e^{jωT}) is evaluated in the shifted variable w = z − 1 = −2sin²(ωT/2) + j·sin ωT, where
//! the plant's polynomials keep their digits at fast sampling ([`crate::zoh::DiscreteLoop`]).

use std::f64::consts::PI;

use levenberg_marquardt::LeastSquaresProblem;
use nalgebra_lm::{DMatrix, DVector, Dyn, Owned};
use num_complex::Complex64;

use super::arx::{Structure, structure, to_physical};
use super::data::CsvText;
use super::error::{IdResult, IdentifyError};
use super::model::{Domain, ModelSpec};
use super::output_error::{Coord, central_jacobian, minimized};
use crate::model::{Loop, VelocityEstimator};
use crate::poly;
use crate::zoh::DiscreteLoop;

/// A measured frequency response, checked: frequencies positive, increasing, below the
/// Nyquist frequency; values finite and non-zero.
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyRecord {
    /// Frequencies in Hz.
    pub frequency_hz: Vec<f64>,
    /// The response from force to position in m/N at each frequency.
    pub response: Vec<Complex64>,
    /// The sampling period T in s of the loop it was measured on.
    pub period: f64,
}

fn column(name: &str, reason: String) -> IdentifyError {
    IdentifyError::Column {
        column: name.into(),
        reason,
    }
}

impl FrequencyRecord {
    /// Checks a response measured at period T (module doc).
    pub fn new(frequency_hz: Vec<f64>, response: Vec<Complex64>, period: f64) -> IdResult<Self> {
        if !(period.is_finite() && period > 0.0) {
            return Err(IdentifyError::Parameter {
                name: "period".into(),
                reason: format!("= {period} must be a time > 0 in s"),
            });
        }
        let nyquist = 0.5 / period;
        for (i, f) in frequency_hz.iter().enumerate() {
            if !(f.is_finite() && *f > 0.0 && *f < nyquist) {
                return Err(column(
                    "frequency",
                    format!(
                        "row {}: {f} Hz is not in (0, {nyquist}) Hz (the Nyquist frequency of T = {period} s)",
                        i + 1
                    ),
                ));
            }
            if i > 0 && *f <= frequency_hz[i - 1] {
                return Err(column(
                    "frequency",
                    format!("row {}: not increasing", i + 1),
                ));
            }
        }
        if let Some(i) = response
            .iter()
            .position(|h| !(h.is_finite() && h.norm() > 0.0))
        {
            return Err(column(
                "response",
                format!(
                    "row {}: {} is not a finite non-zero response",
                    i + 1,
                    response[i]
                ),
            ));
        }
        Ok(FrequencyRecord {
            frequency_hz,
            response,
            period,
        })
    }

    /// Reads CSV with a header naming `frequency` and either `magnitude_db` and `phase_deg`
    /// or `real` and `imag` (in m/N); lines starting with `#` are skipped.
    pub fn from_csv(text: &str, period: f64) -> IdResult<Self> {
        let table = CsvText::parse(text)?;
        let f = table
            .index("frequency")
            .ok_or_else(|| table.missing("frequency"))?;
        let (a, b, polar) = match (
            table.index("magnitude_db"),
            table.index("phase_deg"),
            table.index("real"),
            table.index("imag"),
        ) {
            (Some(m), Some(p), _, _) => (m, p, true),
            (_, _, Some(r), Some(i)) => (r, i, false),
            _ => {
                return Err(IdentifyError::Data(
                    "the header needs magnitude_db and phase_deg, or real and imag".into(),
                ));
            }
        };
        let cols = table.columns(&[f, a, b])?;
        let resp = cols[1]
            .iter()
            .zip(&cols[2])
            .map(|(&x, &y)| {
                if polar {
                    Complex64::from_polar(10f64.powf(x / 20.0), y.to_radians())
                } else {
                    Complex64::new(x, y)
                }
            })
            .collect();
        Self::new(cols[0].clone(), resp, period)
    }
}

/// H(e^{jωT}) in m/N of a loop's plant at each frequency in Hz (module doc).
pub fn sampled_response(lp: &Loop, frequency_hz: &[f64]) -> crate::Result<Vec<Complex64>> {
    let dl = DiscreteLoop::new(lp)?;
    let den = dl.denominator_shifted();
    let (num, k) = dl.numerator_shifted(&den);
    Ok(frequency_hz
        .iter()
        .map(|f| {
            let theta = 2.0 * PI * f * lp.period;
            let s = (theta / 2.0).sin();
            let w = Complex64::new(-2.0 * s * s, theta.sin());
            let z_k = Complex64::from_polar(1.0, -theta * k as f64);
            poly::eval(&num, w) / poly::eval(&den, w) * z_k / dl.scale.stiffness
        })
        .collect())
}

/// Sanathanan–Koerner iterations after Levy's fit (module doc step 2): enough for the
/// start to settle to a few digits (it moves by less than 10⁻⁶ after about five with
/// 0.1 dB errors), and the start needs no more than the optimiser's basin.
pub const SK_ITERATIONS: usize = 10;

/// Levy's start refined by Sanathanan–Koerner (module doc step 2): the model's parameters
/// from the monic continuous tf.
pub fn levy_start(rec: &FrequencyRecord, spec: &ModelSpec) -> IdResult<Vec<f64>> {
    let st = structure(spec);
    let first_a = usize::from(st.integrates);
    // the data advanced by the hold's half sample and the delay, at s = jω
    let points: Vec<(Complex64, Complex64)> = rec
        .frequency_hz
        .iter()
        .zip(&rec.response)
        .map(|(f, h)| {
            let w = 2.0 * PI * f;
            let advance = Complex64::from_polar(1.0, w * (spec.delay_time + rec.period / 2.0));
            (Complex64::new(0.0, w), h * advance)
        })
        .collect();
    // Levy's fit, each equation over |(jω + ω_c)^D·H| with ω_c the frequencies' geometric
    // mean: a denominator of the data's scale before any is known
    let ln_mean = points.iter().map(|(jw, _)| jw.im.ln()).sum::<f64>() / points.len() as f64;
    let wc = ln_mean.exp();
    let mut sol = levy_solve(&points, &st, first_a, |jw, h| {
        (jw + wc).powi(st.den as i32) * h
    })?;
    for _ in 0..SK_ITERATIONS {
        let a = denominator(&sol, &st, first_a);
        sol = levy_solve(&points, &st, first_a, |jw, h| poly::eval(&a, jw) * h)?;
    }
    let mut coef_a = vec![0.0; st.den];
    for (k, i) in (first_a..st.den).enumerate() {
        coef_a[i] = sol[k];
    }
    let na = st.den - first_a;
    let coef_b: Vec<f64> = (0..=st.num).map(|j| sol[na + j]).collect();
    let mut values = to_physical(spec, &coef_a, &coef_b).ok_or_else(|| {
        IdentifyError::NoFit("Levy's linear fit gives no physical plant to start from".into())
    })?;
    values.extend(spec.timing_start(rec.period));
    Ok(values)
}

/// The monic denominator a_0 … a_{D−1}, 1 (lowest power first) of a linear solution.
fn denominator(sol: &nalgebra::DVector<f64>, st: &Structure, first_a: usize) -> Vec<f64> {
    let mut a = vec![0.0; st.den + 1];
    for (k, i) in (first_a..st.den).enumerate() {
        a[i] = sol[k];
    }
    a[st.den] = 1.0;
    a
}

/// The linear least-squares solution (a_{first_a} … a_{D−1}, b_0 … b_N) of
/// den(jω)·H = num(jω), each equation divided by |size(jω, H)| (Levy 1959 with
/// Sanathanan & Koerner's weights, IEEE Trans. AC-8, 1963).
fn levy_solve(
    points: &[(Complex64, Complex64)],
    st: &Structure,
    first_a: usize,
    size: impl Fn(Complex64, Complex64) -> Complex64,
) -> IdResult<nalgebra::DVector<f64>> {
    let n_unknown = (st.den - first_a) + st.num + 1;
    let mut rows: Vec<[f64; 2]> = Vec::new();
    let mut m = Vec::new();
    for &(jw, h) in points {
        let lead = jw.powi(st.den as i32) * h;
        let scale = 1.0 / size(jw, h).norm();
        let mut cols: Vec<Complex64> = (first_a..st.den).map(|i| jw.powi(i as i32) * h).collect();
        cols.extend((0..=st.num).map(|j| -jw.powi(j as i32)));
        let target = -lead * scale;
        m.push(cols.iter().map(|c| c * scale).collect::<Vec<_>>());
        rows.push([target.re, target.im]);
    }
    let n = m.len();
    let a = nalgebra::DMatrix::from_fn(2 * n, n_unknown, |r, c| {
        let v = m[r / 2][c];
        if r % 2 == 0 { v.re } else { v.im }
    });
    let b = nalgebra::DVector::from_fn(2 * n, |r, _| rows[r / 2][r % 2]);
    let sol = a
        .svd(true, true)
        .solve(&b, 1e-14)
        .map_err(|e| IdentifyError::NoFit(format!("Levy's start: {e}")))?;
    if sol.iter().all(|v| v.is_finite()) {
        Ok(sol)
    } else {
        Err(IdentifyError::NoFit(
            "Levy's start: no finite solution".into(),
        ))
    }
}

/// The logarithmic least-squares problem for the optimiser.
pub(crate) struct FreqProblem<'a> {
    pub(crate) rec: &'a FrequencyRecord,
    pub(crate) spec: &'a ModelSpec,
    pub(crate) free: Vec<usize>,
    pub(crate) base: Vec<f64>,
    pub(crate) coords: Vec<Coord>,
    pub(crate) x: DVector<f64>,
    pub(crate) residuals: Option<Vec<f64>>,
}

impl FreqProblem<'_> {
    /// The full parameter vector at coordinates x.
    pub(crate) fn values(&self, x: &[f64]) -> Vec<f64> {
        let mut v = self.base.clone();
        for (k, &i) in self.free.iter().enumerate() {
            v[i] = self.coords[k].value(x[k]);
        }
        v
    }

    /// Ĥ at coordinates x; None when no loop accepts them.
    pub(crate) fn predict(&self, x: &[f64]) -> Option<Vec<Complex64>> {
        let lp = self
            .spec
            .to_loop(
                &self.values(x),
                self.rec.period,
                VelocityEstimator::Backward,
            )
            .ok()?;
        sampled_response(&lp, &self.rec.frequency_hz).ok()
    }

    /// [Re, Im] of ln(Ĥ/H) per frequency, interleaved.
    pub(crate) fn log_residuals(&self, x: &[f64]) -> Option<Vec<f64>> {
        let h = self.predict(x)?;
        let r: Vec<f64> = h
            .iter()
            .zip(&self.rec.response)
            .flat_map(|(p, m)| {
                let l = (p / m).ln();
                [l.re, l.im]
            })
            .collect();
        r.iter().all(|v| v.is_finite()).then_some(r)
    }

    /// ∂r/∂x_j by central differences.
    pub(crate) fn jacobian_columns(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        central_jacobian(x, |xp| self.log_residuals(xp))
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for FreqProblem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.x.copy_from(x);
        self.residuals = self.log_residuals(x.as_slice());
    }

    fn params(&self) -> DVector<f64> {
        self.x.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(match &self.residuals {
            Some(r) => DVector::from_column_slice(r),
            None => DVector::from_element(2 * self.rec.frequency_hz.len(), 1e6),
        })
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let cols = self.jacobian_columns(self.x.as_slice())?;
        let n = 2 * self.rec.frequency_hz.len();
        Some(DMatrix::from_fn(n, cols.len(), |i, j| cols[j][i]))
    }
}

/// Refines Levy's start by logarithmic least squares (module doc step 3): the problem at the
/// optimum and the optimiser's evaluations.
pub(crate) fn refine<'a>(
    rec: &'a FrequencyRecord,
    spec: &'a ModelSpec,
    start: &[f64],
) -> IdResult<(FreqProblem<'a>, usize)> {
    let free = spec.free();
    let params = spec.params();
    let coords: Vec<Coord> = free
        .iter()
        .map(|&i| match params[i].domain {
            Domain::Positive => Coord::Log,
            Domain::Real => Coord::Linear(if start[i] != 0.0 { start[i].abs() } else { 1.0 }),
        })
        .collect();
    let x0: Vec<f64> = free
        .iter()
        .zip(&coords)
        .map(|(&i, c)| c.coordinate(start[i]))
        .collect();
    let mut problem = FreqProblem {
        rec,
        spec,
        free,
        base: start.to_vec(),
        coords,
        x: DVector::from_vec(x0.clone()),
        residuals: None,
    };
    problem.set_params(&DVector::from_vec(x0));
    minimized(problem, "frequency-response")
}
