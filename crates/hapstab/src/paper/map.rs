//! Grid maps over two of α, β, γ, δ — the paper's own method (Section V: "two parameters of
//! p(z) are gridded, and all the others are fixed") — computed in parallel with the
//! Schur–Cohn test, as a fast cross-check of the exact regions. The axes, the kinds of map and
//! the maps of any loop over its wall are [`crate::map`].

use serde::Serialize;

use crate::error::{Error, Result};
use rayon::prelude::*;

use crate::map::{Axis, AxisRange, MAX_POINTS, MapKind, grid, wall_point};
use crate::paper::Normalized;
use crate::paper::NormalizedFamily;
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

    /// The number of plants the map forms a family for: 1 when both axes are α and β, the
    /// points of the γ or δ axis when one is, every point when both are.
    pub fn plants(&self) -> usize {
        let plant_axis = |r: AxisRange| matches!(r.axis, Axis::Gamma | Axis::Delta);
        match (plant_axis(self.x), plant_axis(self.y)) {
            (false, false) => 1,
            (true, false) => self.x.n,
            (false, true) => self.y.n,
            (true, true) => self.x.n.saturating_mul(self.y.n),
        }
    }

    /// The point of Table I at grid indices (ix, iy): the base with the two axes' values.
    pub fn point(&self, ix: usize, iy: usize) -> Normalized {
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
}

/// The plants of a map: one family when both axes are wall axes (α, β), one per value of
/// the plant axis when one axis is γ or δ, none (each point builds its own) when both are.
enum Plants {
    Fixed(Box<NormalizedFamily>),
    PerX(Vec<NormalizedFamily>),
    PerY(Vec<NormalizedFamily>),
    PerPoint,
}

impl Plants {
    fn new(spec: &MapSpec) -> Result<Self> {
        let plant_axis = |a: Axis| matches!(a, Axis::Gamma | Axis::Delta);
        let along = |r: AxisRange, y: bool| -> Result<Vec<NormalizedFamily>> {
            (0..r.n)
                .into_par_iter()
                .map(|i| {
                    let p = if y {
                        spec.point(0, i)
                    } else {
                        spec.point(i, 0)
                    };
                    NormalizedFamily::new(p.plant(), p.d)
                })
                .collect()
        };
        Ok(match (plant_axis(spec.x.axis), plant_axis(spec.y.axis)) {
            (false, false) => Self::Fixed(Box::new(NormalizedFamily::new(
                spec.base.plant(),
                spec.base.d,
            )?)),
            (true, false) => Self::PerX(along(spec.x, false)?),
            (false, true) => Self::PerY(along(spec.y, true)?),
            (true, true) => Self::PerPoint,
        })
    }
}

/// Computes a map in parallel over rows (rayon): every point is judged by the one verdict
/// ([`crate::verdict`]) on the exact family of its plant ([`NormalizedFamily`]), built once
/// per plant. `progress` is called with the number of rows finished so far (from any
/// thread).
pub fn compute_map(
    spec: &MapSpec,
    kind: MapKind,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<Map> {
    let deg = spec.base.d + 3;
    let plants = Plants::new(spec)?;
    let failed = std::sync::OnceLock::new();
    let point = |ix: usize, iy: usize, c: &mut [f64]| {
        let p = spec.point(ix, iy);
        let own;
        let fam = match &plants {
            Plants::Fixed(f) => f,
            Plants::PerX(v) => &v[ix],
            Plants::PerY(v) => &v[iy],
            Plants::PerPoint => match NormalizedFamily::new(p.plant(), p.d) {
                Ok(f) => {
                    own = f;
                    &own
                }
                Err(e) => {
                    failed.get_or_init(|| e);
                    return (false, f64::NAN);
                }
            },
        };
        wall_point(fam, p.alpha, p.beta, kind, c)
    };
    let (stable, radius) = grid(spec.x.n, spec.y.n, deg, kind, progress, point);
    if let Some(e) = failed.into_inner() {
        return Err(e);
    }
    Ok(Map {
        spec: *spec,
        stable,
        radius,
    })
}
