//! `check` and `region`: the exact analyses of Section V for one loop, through the
//! library's `System` (the same methods the command line calls).

use hapstab::System;
use hapstab::answer::{PhysicalRegion, RegionPaperView, check_answer};
use hapstab::region::{EdgeKind, Polygon, StableRegion};
use num_complex::Complex64;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::dicts::dict_of;
use crate::errors::Context;
use crate::loops::PyLoop;
use crate::margins::{PyMargins, margins_object};
use crate::text::num;
use crate::wall::WallArgs;

/// The result of `check`.
#[pyclass(frozen, get_all, module = "hapstab", name = "Check")]
pub struct PyCheck {
    /// True iff every root of p(z) lies inside the unit circle (Section V).
    pub stable: bool,
    /// "stable", "marginal" (a root within 5e-11 of the circle) or "unstable".
    pub verdict: String,
    /// Largest root modulus of p(z).
    pub spectral_radius: f64,
    /// Roots of p(z), largest modulus first (complex128 array).
    pub roots: Py<PyArray1<Complex64>>,
    /// The wall's stiffness K in N/m.
    pub wall_stiffness: f64,
    /// The wall's damping B in Ns/m.
    pub wall_damping: f64,
    /// Stable K interval (lo, hi) in N/m at this B: the one containing K, else the one
    /// reaching furthest; None when no K is stable at this B.
    pub k_interval: Option<(f64, f64)>,
    /// The paper's loop: α = KT²/m (Table I), else None.
    pub alpha: Option<f64>,
    /// The paper's loop: β = BT/m, else None.
    pub beta: Option<f64>,
    /// The paper's loop: the stable α interval at this β (as k_interval), else None.
    pub alpha_interval: Option<(f64, f64)>,
    /// The paper's loop: linear condition (23), α < (β + δ)/(d + 1/2), else None.
    pub alpha_linear: Option<f64>,
    /// The paper's loop: linear condition (22), K < (b + B)/(t_d + T/2) in N/m, else None.
    pub k_linear: Option<f64>,
    /// The wall's margins beside the verdict (as `margins`; none for a wall that is not
    /// stable).
    pub margins: Py<PyMargins>,
}

#[pymethods]
impl PyCheck {
    fn __repr__(&self) -> String {
        format!(
            "Check(verdict='{}', spectral_radius={}, wall_stiffness={}, wall_damping={}, k_interval={})",
            self.verdict,
            num(self.spectral_radius),
            num(self.wall_stiffness),
            num(self.wall_damping),
            interval_text(self.k_interval)
        )
    }
}

pub(crate) fn interval_text(iv: Option<(f64, f64)>) -> String {
    iv.map_or("None".into(), |(lo, hi)| {
        format!("({}, {})", num(lo), num(hi))
    })
}

/// Is the virtual wall F = K·y + B·v on this loop stable? The closed loop's characteristic
/// polynomial p(z) = z^k·D(z)·Vd(z) + N(z)·(K·Vd(z) + B·Vn(z)) (eq. 9, generalized; for the
/// paper's loop p(z) = z^{d+1}D(z) + N(z)((α + β)z − β)) is tested by the Schur–Cohn
/// recursion for the verdict and its roots give the spectral radius (Section V).
///
/// The wall is K in N/m and B in Ns/m, or the paper's normalized α = KT²/m, β = BT/m
/// (a mass-spring-damper plant; on a Loop.normalized they are K and B).
#[pyfunction]
#[pyo3(signature = (r#loop, wall_stiffness = None, wall_damping = None, *, alpha = None,
                    beta = None))]
pub fn check(
    r#loop: &PyLoop,
    wall_stiffness: Option<f64>,
    wall_damping: Option<f64>,
    alpha: Option<f64>,
    beta: Option<f64>,
    py: Python<'_>,
) -> PyResult<PyCheck> {
    let lp = &r#loop.lp;
    let (sys, w) = WallArgs::system_and_wall(r#loop, wall_stiffness, wall_damping, alpha, beta)?;
    let fam = sys.family();
    let units = sys.wall_units(w).py()?;
    let stable = sys.decide(units).verdict == hapstab::Verdict::Stable;
    let core = hapstab::limits::core_degree(fam);
    let cost = hapstab::limits::check_cost(fam.degree(), core, stable);
    crate::budget::check_loop(cost, lp, fam, "the verdict and the margins")?;
    let ans = py
        .detach(|| check_answer(&sys, r#loop.normalized, w))
        .py()?;
    let paper = ans.paper.as_ref();
    Ok(PyCheck {
        stable: ans.stable,
        verdict: ans.verdict.into(),
        spectral_radius: ans.spectral_radius,
        wall_stiffness: w.stiffness,
        wall_damping: w.damping,
        // a normalized loop has m = T = 1: K = α, its interval the α interval
        k_interval: match ans.k_interval {
            Some(k) => k,
            None => paper.and_then(|p| p.alpha_interval),
        }
        .map(|[lo, hi]| (lo, hi)),
        alpha: paper.map(|p| p.point.alpha),
        beta: paper.map(|p| p.point.beta),
        alpha_interval: paper
            .and_then(|p| p.alpha_interval)
            .map(|[lo, hi]| (lo, hi)),
        alpha_linear: paper.map(|p| p.alpha_linear),
        k_linear: paper.and_then(|p| p.k_linear),
        margins: Py::new(py, margins_object(ans.stable, ans.margins))?,
        roots: PyArray1::from_vec(py, ans.roots).unbind(),
    })
}

/// One edge of a region polygon.
#[pyclass(frozen, get_all, from_py_object, module = "hapstab", name = "Edge")]
#[derive(Clone)]
pub struct PyEdge {
    /// Index of the edge's first vertex.
    pub start: usize,
    /// Index of its last vertex (the next edge's first; 0 for the last edge).
    pub stop: usize,
    /// "z=1" (a real root at z = 1: α = −γ for the paper's loop), "z=-1" (a real root at
    /// z = −1), "complex" (a root pair e^{±iθ} on the unit circle) or "window" (a cut of the
    /// search window, never part of a correct region).
    pub kind: String,
    /// For "complex": θ in rad at the first vertex, else None.
    pub theta_start: Option<f64>,
    /// For "complex": θ in rad at the last vertex, else None.
    pub theta_end: Option<f64>,
}

#[pymethods]
impl PyEdge {
    fn __repr__(&self) -> String {
        let theta = match (self.theta_start, self.theta_end) {
            (Some(a), Some(b)) => format!(", theta_start={}, theta_end={}", num(a), num(b)),
            _ => String::new(),
        };
        format!(
            "Edge(start={}, stop={}, kind='{}'{theta})",
            self.start, self.stop, self.kind
        )
    }
}

fn edge_kind(k: &EdgeKind) -> (&'static str, Option<f64>, Option<f64>) {
    match k {
        EdgeKind::ZPlusOne => ("z=1", None, None),
        EdgeKind::ZMinusOne => ("z=-1", None, None),
        EdgeKind::Complex {
            theta_start,
            theta_end,
        } => ("complex", Some(*theta_start), Some(*theta_end)),
        EdgeKind::Window => ("window", None, None),
    }
}

fn edges(p: &Polygon) -> Vec<PyEdge> {
    let n = p.edges.len();
    p.edges
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let (kind, theta_start, theta_end) = edge_kind(&e.kind);
            PyEdge {
                start: e.start,
                stop: p.edges[(i + 1) % n].start,
                kind: kind.into(),
                theta_start,
                theta_end,
            }
        })
        .collect()
}

/// The result of `region`.
#[pyclass(frozen, get_all, module = "hapstab", name = "Region")]
pub struct PyRegion {
    /// Stable components as closed counter-clockwise polygons, each an (N, 2) float64 array
    /// of [K in N/m, B in Ns/m] (first vertex not repeated).
    pub polygons: Vec<Py<PyArray2<f64>>>,
    /// Per polygon, θ in rad of the root pair e^{±iθ} at each vertex on a complex-pair arc
    /// (NaN on the z = ±1 lines), float64 arrays of length N.
    pub thetas: Vec<Py<PyArray1<f64>>>,
    /// Per polygon, its edges in order.
    pub edges: Vec<Vec<PyEdge>>,
    /// Largest stable stiffness K_max in N/m, None when nothing is stable.
    pub k_max: Option<f64>,
    /// The damping B in Ns/m at which K_max is reached.
    pub b_at_k_max: Option<f64>,
    /// False where K_max is a supremum: a corner of the region that only the damping
    /// b_at_k_max touches (approached as B → b_at_k_max); None when nothing is stable.
    pub k_max_attained: Option<bool>,
    /// A damping in Ns/m at which k_stable_near_k_max is stable: b_at_k_max when K_max is
    /// attained, one beside it for a supremum.
    pub b_stable_near_k_max: Option<f64>,
    /// A stiffness in N/m within 1e-6 of K_max that the verdict confirms stable at
    /// b_stable_near_k_max.
    pub k_stable_near_k_max: Option<f64>,
    /// Total area in (N/m)·(Ns/m).
    pub area: f64,
    /// The N/m and Ns/m of one wall unit, {"stiffness", "damping"} (m/T² and m/T for the
    /// paper's plant), as `hapstab boundary --json` gives them.
    pub wall_units: Py<PyDict>,
    /// The paper's loop: its normalized view (Table I), {"gamma", "delta", "d",
    /// "alpha_max", "beta_at_alpha_max", "area"}, as `hapstab boundary --json` gives it;
    /// None for a loop beyond the paper's.
    pub normalized: Option<Py<PyDict>>,
}

#[pymethods]
impl PyRegion {
    fn __repr__(&self) -> String {
        let opt = |x: Option<f64>| x.map_or("None".into(), num);
        format!(
            "Region(polygons={}, k_max={}, b_at_k_max={}, area={})",
            self.polygons.len(),
            opt(self.k_max),
            opt(self.b_at_k_max),
            num(self.area)
        )
    }
}

/// An (N, 2) float64 array of [K, B] rows.
fn rows<'py>(py: Python<'py>, ring: &[[f64; 2]]) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = ring.iter().flatten().copied().collect();
    PyArray1::from_vec(py, flat).reshape([ring.len(), 2])
}

/// The region `r` of `sys` as Python's object: the library's answer in N/m and Ns/m
/// ([`PhysicalRegion`] and [`RegionPaperView`], the numbers of `hapstab boundary --json`) with None where it has NaN
/// (nothing stable), the vertices' angles and the edges.
fn region_object(py: Python<'_>, sys: &System, r: &StableRegion) -> PyResult<PyRegion> {
    let ph = PhysicalRegion::of(sys.family(), r);
    let found = !r.polygons.is_empty();
    let some = |x: f64| found.then_some(x);
    Ok(PyRegion {
        polygons: ph
            .polygons
            .iter()
            .map(|ring| Ok(rows(py, ring)?.unbind()))
            .collect::<PyResult<_>>()?,
        thetas: r
            .polygons
            .iter()
            .map(|p| PyArray1::from_slice(py, &p.thetas).unbind())
            .collect(),
        edges: r.polygons.iter().map(edges).collect(),
        k_max: some(ph.k_max),
        b_at_k_max: some(ph.b_at_k_max),
        k_max_attained: found.then_some(ph.k_max_attained),
        b_stable_near_k_max: some(ph.b_stable_near_k_max),
        k_stable_near_k_max: some(ph.k_stable_near_k_max),
        area: ph.area,
        wall_units: dict_of(py, &ph.wall_units)?,
        normalized: RegionPaperView::of(sys.lp(), r)
            .map(|n| dict_of(py, &n))
            .transpose()?,
    })
}

/// The exact stable region of the wall (K, B) by D-decomposition (Section V, Figs. 4–6):
/// closed polygons bounded by the z = 1 line (α = −γ for the paper's loop), the z = −1 line
/// and the complex-pair curve, where p(e^{iθ}) = 0 gives
/// α(θ) = Im(P0·conj PB)/Im(conj PK·PB), β(θ) = Im(PK·conj P0)/Im(conj PK·PB); each face is
/// classified by one Schur–Cohn test, arcs follow the curve to 1e-9 of the region's size, and
/// K_max (α_max) is solved on dα/dθ = 0. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (r#loop))]
pub fn region(r#loop: &PyLoop, py: Python<'_>) -> PyResult<PyRegion> {
    let sys = r#loop.system()?;
    let fam = sys.family();
    let lp = &r#loop.lp;
    let cost =
        hapstab::limits::region_cost_of_degree(fam.degree(), hapstab::limits::core_degree(fam));
    crate::budget::check_loop(cost, lp, fam, "the exact region")?;
    let r = py.detach(|| sys.region()).py()?;
    region_object(py, &sys, &r)
}
