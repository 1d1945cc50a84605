//! `stability_probability`: P(stable) over a population of operators, at one wall or as a
//! curve against K, as `hapstab population --json` gives it ([`hapstab::population`]).

use hapstab::Param;
use hapstab::population::{Dist, Population, stability_probability as curve, wall_probability};
use hapstab::sweep::SweepParam;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::errors::{Context, bad, finite, swept};
use crate::loops::PyLoop;
use crate::text::num;

/// (level q, largest K with P ≥ q, its 95 % bracket lo, hi) in N/m (None: not reached).
type Level = (f64, Option<f64>, Option<f64>, Option<f64>);

/// P(stable) at one wall over the drawn operators.
#[pyclass(frozen, get_all, module = "hapstab", name = "WallProbability")]
pub struct PyWallProbability {
    /// The wall (K N/m, B Ns/m).
    pub wall_stiffness: f64,
    /// B in Ns/m.
    pub wall_damping: f64,
    /// Operators drawn.
    pub samples: usize,
    /// Operators for whom the wall is stable.
    pub stable: usize,
    /// stable/samples.
    pub probability: f64,
    /// Wilson's 95 % interval.
    pub interval: (f64, f64),
    /// The drawn parameters' names (columns of `draws`).
    pub param_names: Vec<String>,
    /// Each operator's parameters, (samples, len(param_names)).
    pub draws: Py<PyArray2<f64>>,
    /// Each operator's verdict at the wall.
    pub verdicts: Py<PyArray1<bool>>,
}

/// P(stable) against K at a damping, and the K of each level.
#[pyclass(frozen, get_all, module = "hapstab", name = "StabilityCurve")]
pub struct PyStabilityCurve {
    /// B in Ns/m.
    pub wall_damping: f64,
    /// Operators drawn.
    pub samples: usize,
    /// K in N/m.
    pub k: Py<PyArray1<f64>>,
    /// P(stable) at each K.
    pub probability: Py<PyArray1<f64>>,
    /// Wilson's 95 % interval at each K: lower ends.
    pub probability_lo: Py<PyArray1<f64>>,
    /// Upper ends.
    pub probability_hi: Py<PyArray1<f64>>,
    /// (level q, largest K with P ≥ q, its 95 % bracket lo, hi) per level (None: not reached).
    pub levels: Vec<Level>,
    /// The drawn parameters' names (columns of `draws`).
    pub param_names: Vec<String>,
    /// Each operator's parameters, (samples, len(param_names)).
    pub draws: Py<PyArray2<f64>>,
    /// Each operator's stable K interval at B, (samples, 2), N/m (NaN where none).
    pub intervals: Py<PyArray2<f64>>,
}

#[pymethods]
impl PyWallProbability {
    fn __repr__(&self) -> String {
        format!(
            "WallProbability(probability={}, stable={}, samples={})",
            num(self.probability),
            self.stable,
            self.samples
        )
    }
}

#[pymethods]
impl PyStabilityCurve {
    fn __repr__(&self) -> String {
        // each level as Python prints its tuple: (q, K, K_lo, K_hi), None where not reached
        let opt = |x: Option<f64>| x.map_or("None".into(), num);
        let levels: Vec<String> = self
            .levels
            .iter()
            .map(|&(q, k, lo, hi)| format!("({}, {}, {}, {})", num(q), opt(k), opt(lo), opt(hi)))
            .collect();
        format!(
            "StabilityCurve(samples={}, levels=[{}])",
            self.samples,
            levels.join(", ")
        )
    }
}

/// The population from {name: "uniform:LO:HI" | "normal:MEAN:SD" | "lognormal:MEDIAN:SIGMA"}.
fn population(distributions: Option<&Bound<'_, PyDict>>) -> PyResult<Population> {
    let Some(d) = distributions else {
        return Ok(Population::SectionIv);
    };
    let params = d
        .iter()
        .map(|(k, v)| -> PyResult<(SweepParam, Dist)> {
            let name: String = k
                .extract()
                .map_err(|_| bad("distributions", "keys must be str"))?;
            let text: String = v
                .extract()
                .map_err(|_| bad("distributions", format!("{name}: needs a text KIND:A:B")))?;
            let p: SweepParam = name
                .parse()
                .py_with(&[(Param::SweepParameter, "distributions")])?;
            let dist = Dist::parse(&text).py()?;
            Ok((p, dist))
        })
        .collect::<PyResult<_>>()?;
    Ok(Population::Independent { params })
}

fn matrix(py: Python<'_>, rows: &[Vec<f64>], cols: usize) -> PyResult<Py<PyArray2<f64>>> {
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat)
        .reshape([rows.len(), cols])?
        .unbind())
}

/// P(stable) over a population of operators (seeded): with `wall_stiffness` K (N/m), at the
/// wall (K, `wall_damping`) by each operator's exact verdict, with Wilson's 95 % interval;
/// without it, the curve P(stable) against K at `wall_damping` from each operator's exact
/// stable interval and the largest K keeping each of `levels` of the population stable.
/// `distributions` = {name: "uniform:LO:HI" | "normal:MEAN:SD" | "lognormal:MEDIAN:SIGMA"}
/// with `hapstab sweep --param`'s names; None draws the paper's Section IV arm (m_H in
/// 0.5..2 kg, k_H/m_H in 0..710 s⁻², b_H/m_H in 0..12.6 s⁻¹). The numbers of
/// `hapstab population --json`.
#[pyfunction]
#[pyo3(signature = (r#loop, *, wall_stiffness = None, wall_damping = 0.0, samples = 10_000,
                    seed = 1, levels = vec![0.99, 0.999], distributions = None))]
#[allow(clippy::too_many_arguments)]
pub fn stability_probability(
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: f64,
    samples: usize,
    seed: u64,
    levels: Vec<f64>,
    distributions: Option<&Bound<'_, PyDict>>,
    py: Python<'_>,
) -> PyResult<Py<PyAny>> {
    let pop = population(distributions)?;
    let b = finite("wall_damping", wall_damping)?;
    let sys = r#loop.system()?;
    let fam = sys.family();
    let cost = hapstab::limits::population_cost(fam.degree(), samples);
    crate::budget::check_loop(cost, &r#loop.lp, fam, "the population")?;
    let lp = &r#loop.lp;
    // a drawn value that a loop refuses comes from the distributions
    let own = swept("distributions");
    if let Some(k) = wall_stiffness {
        let wall = hapstab::params::Wall {
            stiffness: finite("wall_stiffness", k)?,
            damping: b,
        };
        let r = py
            .detach(|| wall_probability(lp, &pop, wall, samples, seed))
            .py_with(&own)?;
        let cols = r.param_names.len();
        let out = PyWallProbability {
            wall_stiffness: r.wall_stiffness,
            wall_damping: r.wall_damping,
            samples: r.samples,
            stable: r.stable,
            probability: r.probability,
            interval: (r.interval[0], r.interval[1]),
            param_names: r.param_names.iter().map(|s| s.to_string()).collect(),
            draws: matrix(py, &r.draws, cols)?,
            verdicts: PyArray1::from_vec(py, r.verdicts).unbind(),
        };
        return Ok(Py::new(py, out)?.into_any());
    }
    let r = py
        .detach(|| curve(lp, &pop, b, samples, seed, &levels))
        .py_with(&own)?;
    let v = |x: &[f64]| PyArray1::from_vec(py, x.to_vec()).unbind();
    let intervals: Vec<Vec<f64>> = r.intervals.iter().map(|i| i.to_vec()).collect();
    let out = PyStabilityCurve {
        wall_damping: r.wall_damping,
        samples: r.samples,
        k: v(&r.k),
        probability: v(&r.probability),
        probability_lo: v(&r.probability_lo),
        probability_hi: v(&r.probability_hi),
        levels: r
            .levels
            .iter()
            .map(|l| (l.level, l.k, l.k_lo, l.k_hi))
            .collect(),
        param_names: r.param_names.iter().map(|s| s.to_string()).collect(),
        draws: matrix(py, &r.draws, r.param_names.len())?,
        intervals: matrix(py, &intervals, 2)?,
    };
    Ok(Py::new(py, out)?.into_any())
}
