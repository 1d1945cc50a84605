//! `frequency_response`: the open loop L(e^{jωT}) of a wall with its crossings, the data of
//! `hapstab bode` and `hapstab nyquist-plot` as numpy arrays
//! (`hapstab::freqresp::frequency_response`, the same call).

use hapstab::freqresp::{FrequencyResponse, frequency_response as response};
use hapstab::limits::{CIRCLE_EVAL_SECONDS, Cost, check_cost, core_degree};
use hapstab::margins::CrossingKind;
use num_complex::Complex64;
use numpy::PyArray1;
use numpy::prelude::*;
use pyo3::prelude::*;

use crate::budget::{check, check_loop, shape_of};
use crate::errors::{Context, bad};
use crate::loops::PyLoop;
use crate::margins::{PyMargins, margins_object};
use crate::wall::WallArgs;

/// One crossing as the Bode and Nyquist plots mark it.
#[pyclass(frozen, get_all, module = "hapstab", name = "Mark")]
pub struct PyMark {
    /// "gain" (|L| = 1) or "phase" (L real).
    pub kind: String,
    /// Angular frequency in rad/s.
    pub omega: f64,
    /// Frequency in Hz.
    pub frequency_hz: f64,
    /// The phase margin in degrees (gain crossover), the factor on (K, B) that puts a root on
    /// the unit circle (phase crossover).
    pub value: f64,
    /// 20·log10 |L| there, dB.
    pub magnitude_db: f64,
    /// The phase of L there in degrees, on the branch of the unwrapped curve.
    pub phase_deg: f64,
    /// L there.
    pub response: Complex64,
    /// True where the reported gain or phase margin is read.
    pub primary: bool,
}

#[pymethods]
impl PyMark {
    fn __repr__(&self) -> String {
        format!(
            "Mark(kind='{}', frequency_hz={}, value={}, primary={})",
            self.kind,
            self.frequency_hz,
            self.value,
            if self.primary { "True" } else { "False" }
        )
    }
}

/// The result of `frequency_response`.
#[pyclass(frozen, get_all, module = "hapstab", name = "FrequencyResponse")]
pub struct PyFrequencyResponse {
    /// Sampling period T in s.
    pub period: f64,
    /// The Nyquist frequency 1/(2T) in Hz.
    pub nyquist_hz: f64,
    /// Angular frequencies ω in rad/s.
    pub omega: Py<PyArray1<f64>>,
    /// ω/(2π) in Hz.
    pub frequency_hz: Py<PyArray1<f64>>,
    /// L(e^{jωT}), complex.
    pub response: Py<PyArray1<Complex64>>,
    /// 20·log10 |L|, dB.
    pub magnitude_db: Py<PyArray1<f64>>,
    /// arg L in degrees, unwrapped along the grid.
    pub phase_deg: Py<PyArray1<f64>>,
    /// Every gain and phase crossover, increasing in frequency (none when the wall is not
    /// stable: margins are defined for stable walls).
    pub marks: Vec<Py<PyMark>>,
    /// min |1 + L| and where: (distance, frequency in Hz, L there), or None.
    pub closest: Option<(f64, f64, Complex64)>,
    /// The wall's margins, as `margins` gives them.
    pub margins: Py<PyMargins>,
}

#[pymethods]
impl PyFrequencyResponse {
    fn __repr__(&self, py: Python<'_>) -> String {
        format!(
            "FrequencyResponse(points={}, marks={}, nyquist_hz={})",
            self.omega.bind(py).shape()[0],
            self.marks.len(),
            self.nyquist_hz
        )
    }
}

fn response_object(py: Python<'_>, fr: FrequencyResponse) -> PyResult<PyFrequencyResponse> {
    let values: Vec<Complex64> = fr
        .re
        .iter()
        .zip(&fr.im)
        .map(|(&re, &im)| Complex64::new(re, im))
        .collect();
    let marks = fr
        .marks
        .iter()
        .map(|m| {
            let mark = PyMark {
                kind: match m.kind {
                    CrossingKind::Gain => "gain",
                    CrossingKind::Phase => "phase",
                }
                .into(),
                omega: m.omega,
                frequency_hz: m.frequency_hz,
                value: m.value,
                magnitude_db: m.magnitude_db,
                phase_deg: m.phase_deg,
                response: Complex64::new(m.re, m.im),
                primary: m.primary,
            };
            Py::new(py, mark)
        })
        .collect::<PyResult<_>>()?;
    Ok(PyFrequencyResponse {
        period: fr.period,
        nyquist_hz: fr.nyquist_hz,
        omega: PyArray1::from_vec(py, fr.omega).unbind(),
        frequency_hz: PyArray1::from_vec(py, fr.frequency_hz).unbind(),
        response: PyArray1::from_vec(py, values).unbind(),
        magnitude_db: PyArray1::from_vec(py, fr.magnitude_db).unbind(),
        phase_deg: PyArray1::from_vec(py, fr.phase_deg).unbind(),
        marks,
        closest: fr
            .closest
            .map(|c| (c.distance, c.frequency_hz, Complex64::new(c.re, c.im))),
        margins: Py::new(py, margins_object(fr.margins.stable, (&fr.margins).into()))?,
    })
}

/// The open loop L(e^{jωT}) = (K·PK + B·PB)/P0 of the wall on the exact discrete loop (the
/// characteristic equation p(z) = 0 of eq. 9 is 1 + L = 0), the data of `hapstab bode` and
/// `hapstab nyquist-plot`: the same curve, crossings and margins.
///
/// omega: angular frequencies in rad/s (each finite and > 0), or None for the command line's
/// grid (log-spaced up to the Nyquist frequency π/T, joined with every lightly damped mode
/// and every crossing). The wall is K in N/m and B in Ns/m (or alpha/beta on the paper's
/// mass-spring-damper). Frequencies are physical: a loop built by Loop.normalized is refused.
/// The GIL is released during the computation.
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, omega = None, *,
                    alpha = None, beta = None))]
pub fn frequency_response(
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    omega: Option<&Bound<'_, PyAny>>,
    alpha: Option<f64>,
    beta: Option<f64>,
    py: Python<'_>,
) -> PyResult<PyFrequencyResponse> {
    if r#loop.normalized {
        return Err(bad(
            "loop",
            "the frequency response works in physical units (rad/s): build the loop from the plant in kg, Ns/m, N/m and a period, not Loop.normalized",
        ));
    }
    let lp = &r#loop.lp;
    let (sys, w) = WallArgs::system_and_wall(r#loop, wall_stiffness, wall_damping, alpha, beta)?;
    let fam = sys.family();
    let n = fam.degree();
    check_loop(
        check_cost(n, core_degree(fam), true),
        lp,
        fam,
        "the frequency response",
    )?;
    let omega: Option<Vec<f64>> = match omega {
        None => None,
        Some(x) => {
            let points: usize = shape_of(x)?.iter().product();
            let cost = Cost {
                seconds: CIRCLE_EVAL_SECONDS * (n + 1) as f64 * points as f64,
                memory: 56.0 * points as f64,
            };
            check(
                cost,
                "omega",
                "the frequency response",
                "give fewer frequencies",
            )?;
            Some(x.extract().map_err(|e| bad("omega", e))?)
        }
    };
    let fr = py.detach(|| response(lp, w, omega.as_deref())).py()?;
    response_object(py, fr)
}
