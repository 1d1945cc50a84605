//! Output-error refinement: the parameters θ that minimise Σ_k (y_k − ŷ_k(θ))² with ŷ the
//! exact sampled response of [`super::response`] (Ljung, *System Identification*, 2nd ed.,
//! 1999, §4.2 and §7.3), by Levenberg–Marquardt (Moré's MINPACK `lmder`, Lecture Notes in
//! Mathematics 630, 1978, as the `levenberg-marquardt` crate implements it — the algorithm
//! of scipy's `least_squares(method='lm')`).
//!
//! Several runs of the same plant are fitted together: one parameter vector, one position
//! offset per run, the residuals of every run in one least-squares problem.
//!
//! The optimiser moves a coordinate per free parameter: ln θ for a positive one (so every
//! step stays physical), θ/s for a real one (s its starting magnitude), and each run's
//! position offset y_0 in units of the positions' RMS. The Jacobian is the central difference of the
//! response in these coordinates with step [`DIFF_STEP`]; a trial parameter vector that no
//! loop accepts gets a residual far above any fit's, so the trust region shrinks away from it.

use levenberg_marquardt::{LeastSquaresProblem, LevenbergMarquardt};
use nalgebra_lm::{DMatrix, DVector, Dyn, Owned};
use rayon::prelude::*;

use super::arx::Start;
use super::data::Record;
use super::error::{IdResult, IdentifyError};
use super::model::{Domain, ModelSpec};
use super::response::SampledModel;
use crate::model::VelocityEstimator;

/// Central-difference step in the optimiser's coordinates: a relative change of 10⁻⁵ in a
/// parameter; the truncation error (step²) is 10⁻¹⁰ and the rounding error (ε/step) 10⁻¹¹,
/// both far below the parameters' statistical uncertainty.
pub const DIFF_STEP: f64 = 1e-5;

/// ∂f/∂x_j for every j by central differences with step [`DIFF_STEP`] in the fitted
/// coordinates, the columns in parallel; None where f fails at a trial point.
pub(crate) fn central_jacobian(
    x: &[f64],
    f: impl Fn(&[f64]) -> Option<Vec<f64>> + Sync,
) -> Option<Vec<Vec<f64>>> {
    (0..x.len())
        .into_par_iter()
        .map(|j| {
            let at = |h: f64| {
                let mut xp = x.to_vec();
                xp[j] += h;
                f(&xp)
            };
            let (plus, minus) = (at(DIFF_STEP)?, at(-DIFF_STEP)?);
            Some(
                plus.iter()
                    .zip(&minus)
                    .map(|(p, m)| (p - m) / (2.0 * DIFF_STEP))
                    .collect(),
            )
        })
        .collect()
}

/// Relative tolerance on the cost and on the coordinates at which the fit stops: ten times
/// below the agreement asked of an independent optimiser on the same cost (10⁻⁶ relative).
pub const TOLERANCE: f64 = 1e-12;

/// Weighted residual given to every sample of a trial vector no loop accepts.
const REJECTED: f64 = 1e6;

/// How the optimiser moves one coordinate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Coord {
    /// θ = e^x.
    Log,
    /// θ = s·x.
    Linear(f64),
}

impl Coord {
    /// The parameter at coordinate x.
    pub fn value(self, x: f64) -> f64 {
        match self {
            Coord::Log => x.exp(),
            Coord::Linear(s) => s * x,
        }
    }

    /// The coordinate of parameter θ.
    pub fn coordinate(self, v: f64) -> f64 {
        match self {
            Coord::Log => v.ln(),
            Coord::Linear(s) => v / s,
        }
    }

    /// dθ/dx at coordinate x.
    pub fn derivative(self, x: f64) -> f64 {
        match self {
            Coord::Log => x.exp(),
            Coord::Linear(s) => s,
        }
    }
}

/// The refined fit.
#[derive(Debug, Clone)]
pub struct Fit {
    /// Every parameter of the model (held ones at their values).
    pub values: Vec<f64>,
    /// The position offset y_0 of each run in m.
    pub offsets: Vec<f64>,
    /// The model's response ŷ_k in m, offsets included, the runs one after the other.
    pub predicted: Vec<f64>,
    /// The optimiser's coordinates at the optimum, free parameters then the runs' offsets.
    pub x: Vec<f64>,
    /// Their kinds.
    pub coords: Vec<Coord>,
    /// ∂ŷ_k/∂x_j in m, one column per coordinate.
    pub jacobian: Vec<Vec<f64>>,
    /// Residual evaluations the optimiser made.
    pub evaluations: usize,
}

impl Fit {
    /// Σ_k (y_k − ŷ_k)² in m², the cost the fit minimises.
    pub fn cost(&self, measured: &[f64]) -> f64 {
        measured
            .iter()
            .zip(&self.predicted)
            .map(|(m, p)| (m - p).powi(2))
            .sum()
    }
}

/// The output-error problem for the optimiser.
struct Problem<'a> {
    records: &'a [Record],
    measured: Vec<f64>,
    spec: &'a ModelSpec,
    free: Vec<usize>,
    base: Vec<f64>,
    coords: Vec<Coord>,
    weight: f64,
    x: DVector<f64>,
    residuals: Option<Vec<f64>>,
}

impl Problem<'_> {
    /// ŷ(x) in m of every run, offsets included; None when no loop accepts the parameters.
    fn predict(&self, x: &[f64]) -> Option<Vec<f64>> {
        let mut v = self.base.clone();
        for (k, &i) in self.free.iter().enumerate() {
            v[i] = self.coords[k].value(x[k]);
        }
        let lp = self
            .spec
            .to_loop(&v, self.records[0].period, VelocityEstimator::Backward)
            .ok()?;
        let model = SampledModel::of_loop(&lp).ok()?;
        let mut y = Vec::with_capacity(self.measured.len());
        for (r, rec) in self.records.iter().enumerate() {
            let o = self.free.len() + r;
            let offset = self.coords[o].value(x[o]);
            y.extend(model.simulate(&rec.force).into_iter().map(|s| s + offset));
        }
        y.iter().all(|s| s.is_finite()).then_some(y)
    }

    /// ∂ŷ/∂x_j by central differences (module doc), in parallel over j.
    fn jacobian_columns(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        central_jacobian(x, |xp| self.predict(xp))
    }
}

impl LeastSquaresProblem<f64, Dyn, Dyn> for Problem<'_> {
    type ResidualStorage = Owned<f64, Dyn>;
    type JacobianStorage = Owned<f64, Dyn, Dyn>;
    type ParameterStorage = Owned<f64, Dyn>;

    fn set_params(&mut self, x: &DVector<f64>) {
        self.x.copy_from(x);
        self.residuals = self.predict(x.as_slice()).map(|y| {
            y.iter()
                .zip(&self.measured)
                .map(|(s, m)| (m - s) * self.weight)
                .collect()
        });
    }

    fn params(&self) -> DVector<f64> {
        self.x.clone()
    }

    fn residuals(&self) -> Option<DVector<f64>> {
        Some(match &self.residuals {
            Some(r) => DVector::from_column_slice(r),
            None => DVector::from_element(self.measured.len(), REJECTED),
        })
    }

    fn jacobian(&self) -> Option<DMatrix<f64>> {
        let cols = self.jacobian_columns(self.x.as_slice())?;
        let n = self.measured.len();
        Some(DMatrix::from_fn(n, cols.len(), |i, j| {
            -cols[j][i] * self.weight
        }))
    }
}

/// The coordinates of the free parameters (module doc) and of the `runs` offsets, scaled by
/// the positions' RMS `scale`.
fn coords(spec: &ModelSpec, free: &[usize], start: &Start, scale: f64, runs: usize) -> Vec<Coord> {
    let params = spec.params();
    let mut c: Vec<Coord> = free
        .iter()
        .map(|&i| match params[i].domain {
            Domain::Positive => Coord::Log,
            Domain::Real => Coord::Linear(if start.values[i] != 0.0 {
                start.values[i].abs()
            } else {
                1.0
            }),
        })
        .collect();
    c.extend(std::iter::repeat_n(Coord::Linear(scale), runs));
    c
}

/// Refines a start by output error over every run (module doc); `offsets` are the runs'
/// starting offsets. Refused when the optimiser fails or a parameter runs off to zero or
/// infinity.
pub fn refine(
    records: &[Record],
    spec: &ModelSpec,
    start: &Start,
    offsets: &[f64],
) -> IdResult<Fit> {
    let free = spec.free();
    let measured: Vec<f64> = records
        .iter()
        .flat_map(|r| r.position.iter().copied())
        .collect();
    let rms = (measured.iter().map(|y| y * y).sum::<f64>() / measured.len() as f64).sqrt();
    let scale = if rms > 0.0 { rms } else { 1.0 };
    let coords = coords(spec, &free, start, scale, records.len());
    let mut x0: Vec<f64> = free
        .iter()
        .zip(&coords)
        .map(|(&i, c)| c.coordinate(start.values[i]))
        .collect();
    x0.extend(offsets.iter().map(|o| o / scale));
    let mut problem = Problem {
        records,
        measured,
        spec,
        free: free.clone(),
        base: start.values.clone(),
        coords: coords.clone(),
        weight: 1.0 / scale,
        x: DVector::from_vec(x0.clone()),
        residuals: None,
    };
    // the optimiser asks for the residuals at the start without setting them first
    problem.set_params(&DVector::from_vec(x0));
    let (problem, evaluations) = minimized(problem, "output-error")?;
    finish(&problem, spec, evaluations)
}

/// The Levenberg–Marquardt minimum of a fit's residuals (Moré's MINPACK algorithm, the
/// `levenberg_marquardt` crate) to [`TOLERANCE`] in the residual and the step, with the
/// number of evaluations; an error naming the fit (`what`) where it stops without converging.
pub(crate) fn minimized<P>(problem: P, what: &str) -> IdResult<(P, usize)>
where
    P: LeastSquaresProblem<
            f64,
            Dyn,
            Dyn,
            ResidualStorage = Owned<f64, Dyn>,
            JacobianStorage = Owned<f64, Dyn, Dyn>,
            ParameterStorage = Owned<f64, Dyn>,
        >,
{
    let (problem, report) = LevenbergMarquardt::new()
        .with_ftol(TOLERANCE)
        .with_xtol(TOLERANCE)
        .with_gtol(0.0)
        .with_patience(200)
        .minimize(problem);
    if !report.termination.was_successful() {
        return Err(IdentifyError::NoFit(format!(
            "the {what} fit stopped without converging ({:?})",
            report.termination
        )));
    }
    Ok((problem, report.number_of_evaluations))
}

/// The fit at the optimiser's last point, checked to be a physical plant.
fn finish(p: &Problem, spec: &ModelSpec, evaluations: usize) -> IdResult<Fit> {
    let x = p.x.as_slice().to_vec();
    let params = spec.params();
    let mut values = p.base.clone();
    for (k, &i) in p.free.iter().enumerate() {
        values[i] = p.coords[k].value(x[k]);
        if !values[i].is_finite() || (params[i].domain == Domain::Positive && values[i] <= 0.0) {
            return Err(IdentifyError::NoFit(format!(
                "{} ran off to {:e}: the data do not determine it",
                params[i].name, values[i]
            )));
        }
    }
    let predicted = p
        .predict(&x)
        .ok_or_else(|| IdentifyError::NoFit("the fitted parameters make no valid loop".into()))?;
    let jacobian = p.jacobian_columns(&x).ok_or_else(|| {
        IdentifyError::NoFit("the fit sits at the edge of the valid loops".into())
    })?;
    Ok(Fit {
        offsets: (p.free.len()..x.len())
            .map(|o| p.coords[o].value(x[o]))
            .collect(),
        values,
        predicted,
        x,
        coords: p.coords.clone(),
        jacobian,
        evaluations,
    })
}
