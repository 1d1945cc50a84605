//! Grid maps over two of α, β, γ, δ — the paper's own method (Section V: "two parameters of
//! p(z) are gridded, and all the others are fixed") — computed in parallel with the
//! Schur–Cohn test, as a fast cross-check of the exact regions. The axes, the kinds of map and
//! the maps of any loop over its wall are [`crate::map`].

use serde::Serialize;

use crate::error::{Error, Result};
use crate::map::{Axis, AxisRange, MAX_POINTS, MapKind, grid, poly_point, wall_point};
use crate::paper::NormalizedFamily;
use crate::paper::{Normalized, PlantParams};
use crate::param::Param;

/// A map specification: two axes and the fixed values of the other parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapSpec {
    /// Horizontal axis.
    pub x: AxisRange,
    /// Vertical axis.
    pub y: AxisRange,
    /// Values of the parameters not gridded (the gridded ones are ignored).
    pub base: Normalized,
}

/// A computed map, row-major: value (ix, iy) at index iy·nx + ix.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Map {
    /// The specification.
    pub spec: MapSpec,
    /// Stable flag per point.
    pub stable: Vec<bool>,
    /// Spectral radius per point (only for `MapKind::SpectralRadius`).
    pub radius: Option<Vec<f64>>,
}

impl Map {
    /// Stable flag at grid indices.
    pub fn is_stable(&self, ix: usize, iy: usize) -> bool {
        self.stable[iy * self.spec.x.n + ix]
    }
}

impl MapSpec {
    /// Validates the specification (distinct axes, point count, base parameters).
    pub fn new(x: AxisRange, y: AxisRange, base: Normalized) -> Result<Self> {
        if x.axis == y.axis {
            return Err(Error::OutOfRange {
                param: Param::MapAxes,
                value: f64::NAN,
                range: "two different parameters",
            });
        }
        if x.n.saturating_mul(y.n) > MAX_POINTS {
            return Err(Error::OutOfRange {
                param: Param::MapPoints,
                value: (x.n as f64) * (y.n as f64),
                range: "[4, 1e8]",
            });
        }
        for r in [x, y] {
            if matches!(r.axis, Axis::Gamma | Axis::Delta) && r.lo < 0.0 {
                return Err(Error::Negative {
                    param: if r.axis == Axis::Gamma {
                        Param::Gamma
                    } else {
                        Param::Delta
                    },
                    value: r.lo,
                });
            }
        }
        let base = Normalized::new(base.alpha, base.beta, base.gamma, base.delta, base.d)?;
        Ok(Self { x, y, base })
    }

    fn point(&self, ix: usize, iy: usize) -> Normalized {
        let mut p = self.base;
        for (r, i) in [(self.x, ix), (self.y, iy)] {
            let v = r.value(i);
            match r.axis {
                Axis::Alpha => p.alpha = v,
                Axis::Beta => p.beta = v,
                Axis::Gamma => p.gamma = v,
                Axis::Delta => p.delta = v,
            }
        }
        p
    }

    fn plant_fixed(&self) -> bool {
        [self.x.axis, self.y.axis]
            .iter()
            .all(|a| matches!(a, Axis::Alpha | Axis::Beta))
    }
}

/// p(z) = z^{d+1} D(z) + N(z)((α + β) z − β) from the paper's closed-form plant (eq. 5, 9),
/// for maps whose axes change the plant at every point: the closed form costs a few
/// exponentials where the general discretization would cost a matrix exponential. The two
/// agree to rounding (tested in `crate::zoh`).
fn paper_coefficients(
    pl: &crate::paper::reference::DiscretePlant,
    d: usize,
    alpha: f64,
    beta: f64,
    out: &mut [f64],
) {
    let n = d + 3;
    out[..=n].fill(0.0);
    out[n] = 1.0;
    out[n - 1] = -pl.a1;
    out[n - 2] = pl.a0;
    let ab = alpha + beta;
    out[2] += pl.n1 * ab;
    out[1] += pl.n0 * ab - pl.n1 * beta;
    out[0] += -pl.n0 * beta;
}

/// Computes a map in parallel over rows (rayon). `progress` is called with the number of
/// rows finished so far (from any thread).
pub fn compute_map(spec: &MapSpec, kind: MapKind, progress: &(dyn Fn(usize) + Sync)) -> Map {
    let deg = spec.base.d + 3;
    let fixed = if spec.plant_fixed() {
        NormalizedFamily::new(spec.base.plant(), spec.base.d).ok()
    } else {
        None
    };
    let point = |ix: usize, iy: usize, c: &mut [f64]| {
        let p = spec.point(ix, iy);
        match &fixed {
            Some(fam) => wall_point(fam, p.alpha, p.beta, kind, c),
            None => {
                paper_coefficients(
                    &crate::paper::reference::DiscretePlant::from_params(PlantParams {
                        gamma: p.gamma,
                        delta: p.delta,
                    }),
                    p.d,
                    p.alpha,
                    p.beta,
                    c,
                );
                poly_point(c, kind)
            }
        }
    };
    let (stable, radius) = grid(spec.x.n, spec.y.n, deg, kind, progress, point);
    Map {
        spec: *spec,
        stable,
        radius,
    }
}
