//! `discretize`: the exact discrete loop as coefficient arrays in descending powers of z
//! (python-control's and MATLAB's convention).

use hapstab::AffineFamily;
use hapstab::zoh::DiscreteTf;
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::errors::Context;
use crate::loops::PyLoop;
use crate::wall::WallArgs;

/// The result of `discretize`; every coefficient array is float64 in descending powers of z.
#[pyclass(frozen, get_all, module = "hapstab", name = "Discretization")]
pub struct PyDiscretization {
    /// Sampling period T in s.
    pub period: f64,
    /// Numerator of the plant H(z) = z^(−plant_delay)·num(z)/den(z), force (N) to position
    /// (m) behind a zero-order hold (python-control's sample_system(P, T, 'zoh') with the
    /// input delay).
    pub plant_num: Py<PyArray1<f64>>,
    /// Denominator of H(z), monic.
    pub plant_den: Py<PyArray1<f64>>,
    /// The power k of H's pure delay z^(−k): d, or d + 1 with a fractional delay.
    pub plant_delay: usize,
    /// Numerator of the velocity estimator V(z), position (m) to velocity (m/s).
    pub velocity_num: Py<PyArray1<f64>>,
    /// Denominator of V(z), monic.
    pub velocity_den: Py<PyArray1<f64>>,
    /// P0 of p(z) = P0(z) + K·PK(z) + B·PB(z) (K in N/m, B in Ns/m): z^k·den·Vd.
    pub p0: Py<PyArray1<f64>>,
    /// PK: num·Vd per N/m.
    pub pk: Py<PyArray1<f64>>,
    /// PB: num·Vn per Ns/m.
    pub pb: Py<PyArray1<f64>>,
    /// The monic characteristic polynomial p(z) at the given wall, else None.
    pub characteristic: Option<Py<PyArray1<f64>>>,
    /// The wall's K in N/m, if given.
    pub wall_stiffness: Option<f64>,
    /// The wall's B in Ns/m, if given.
    pub wall_damping: Option<f64>,
}

#[pymethods]
impl PyDiscretization {
    fn __repr__(&self) -> String {
        format!(
            "Discretization(period={}, plant_delay={}, characteristic={})",
            crate::text::num(self.period),
            self.plant_delay,
            if self.characteristic.is_some() {
                "array"
            } else {
                "None"
            }
        )
    }
}

fn descending(py: Python<'_>, asc: &[f64]) -> Py<PyArray1<f64>> {
    let v: Vec<f64> = asc.iter().rev().copied().collect();
    PyArray1::from_vec(py, v).unbind()
}

/// (P0, PK, PB) ascending, padded to the degree, PK and PB per N/m and per Ns/m.
fn parts(fam: &AffineFamily) -> [Vec<f64>; 3] {
    let n = fam.degree() + 1;
    let mut p0 = vec![0.0; n];
    p0[fam.k..fam.k + fam.p0_core.len()].copy_from_slice(&fam.p0_core);
    let per = |c: &[f64], unit: f64| {
        let mut v: Vec<f64> = c.iter().map(|x| x / unit).collect();
        v.resize(n, 0.0);
        v
    };
    [
        p0,
        per(&fam.pk, fam.scale.stiffness),
        per(&fam.pb, fam.scale.damping),
    ]
}

/// The sampled open loop of a wall K, B (α, β on a normalized loop) in descending powers of
/// z: L(z) = (K·PK(z) + B·PB(z))/P0(z), formed as p(z) is (p = P0 + K·PK + B·PB, eq. 9), so
/// that 1 + L = 0 is the closed loop's characteristic equation.
pub(crate) fn open_loop(lp: &PyLoop, wall: &WallArgs) -> PyResult<(Vec<f64>, Vec<f64>)> {
    let dl = lp.lp.discretize().py()?;
    let fam = AffineFamily::new(&dl);
    let w = wall.resolve(lp, &fam)?;
    let (a, b) = fam.to_units(w.stiffness, w.damping);
    let n = fam.degree() + 1;
    let mut den = vec![0.0; n];
    den[fam.k..fam.k + fam.p0_core.len()].copy_from_slice(&fam.p0_core);
    let mut num = vec![0.0; n];
    for (i, x) in num.iter_mut().enumerate() {
        let at = |c: &[f64]| c.get(i).copied().unwrap_or(0.0);
        *x = a * at(&fam.pk) + b * at(&fam.pb);
    }
    let desc = |v: Vec<f64>| v.into_iter().rev().collect::<Vec<_>>();
    Ok((desc(num), desc(den)))
}

/// The exact discrete loop (Section III, eq. 2–9, generalized): the plant behind a
/// zero-order hold with its delay t_d = (d + λ)T (modified z-transform, no Padé or Thiran
/// approximation), the velocity estimator, and the closed loop's characteristic polynomial
/// p(z) = P0(z) + K·PK(z) + B·PB(z) — for a given wall, its coefficients. For the paper's
/// plant H(z) = (T²/m)·(n1 z + n0)/(z² − a1 z + a0) (eq. 5–6). Arrays are in descending
/// powers of z, as python-control's `tf(num, den, T)`.
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, *, alpha = None,
                    beta = None))]
pub fn discretize(
    py: Python<'_>,
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    alpha: Option<f64>,
    beta: Option<f64>,
) -> PyResult<PyDiscretization> {
    let dl = r#loop.lp.discretize().py()?;
    let fam = AffineFamily::new(&dl);
    let args = WallArgs {
        stiffness: wall_stiffness,
        damping: wall_damping,
        alpha,
        beta,
    };
    let given = [wall_stiffness, wall_damping, alpha, beta]
        .iter()
        .any(Option::is_some);
    let wall = given.then(|| args.resolve(r#loop, &fam)).transpose()?;
    let characteristic = wall.map(|w| {
        let (a, b) = fam.to_units(w.stiffness, w.damping);
        descending(py, &fam.coefficients(a, b))
    });
    let plant: DiscreteTf = dl.plant_tf_physical();
    let v = dl.velocity_tf_physical();
    let [p0, pk, pb] = parts(&fam);
    Ok(PyDiscretization {
        period: r#loop.lp.period,
        plant_num: descending(py, &plant.num),
        plant_den: descending(py, &plant.den),
        plant_delay: plant.delay,
        velocity_num: descending(py, &v.num),
        velocity_den: descending(py, &v.den),
        p0: descending(py, &p0),
        pk: descending(py, &pk),
        pb: descending(py, &pb),
        characteristic,
        wall_stiffness: wall.map(|w| w.stiffness),
        wall_damping: wall.map(|w| w.damping),
    })
}
