//! Grid maps — the paper's own method (Section V: "two parameters of p(z) are gridded, and
//! all the others are fixed") — of any loop over its wall (stiffness and damping), computed
//! in parallel with the one verdict, as a fast cross-check of the exact regions; the paper's
//! maps over two of α, β, γ, δ are [`crate::paper::map`].

use rayon::prelude::*;
use serde::{Deserialize, Serialize};

use crate::closed_loop::AffineFamily;
use crate::error::{Error, Result};
use crate::param::Param;
use crate::stability::Analysis;
use crate::verdict::Verdict;

/// A gridded parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Axis {
    /// Normalized virtual stiffness α.
    Alpha,
    /// Normalized virtual damping β.
    Beta,
    /// Normalized physical stiffness γ.
    Gamma,
    /// Normalized physical damping δ.
    Delta,
}

impl std::str::FromStr for Axis {
    type Err = Error;
    fn from_str(s: &str) -> Result<Self> {
        match s {
            "alpha" => Ok(Axis::Alpha),
            "beta" => Ok(Axis::Beta),
            "gamma" => Ok(Axis::Gamma),
            "delta" => Ok(Axis::Delta),
            _ => Err(Error::OutOfRange {
                param: Param::MapAxis,
                value: f64::NAN,
                range: "{alpha, beta, gamma, delta}",
            }),
        }
    }
}

/// One axis of a grid: n points from lo to hi inclusive.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AxisRange {
    /// Which parameter.
    pub axis: Axis,
    /// First value.
    pub lo: f64,
    /// Last value.
    pub hi: f64,
    /// Number of points (>= 2).
    pub n: usize,
}

/// Largest number of grid points in a map (1e8; 800 MB of radius values).
pub const MAX_POINTS: usize = 100_000_000;

impl AxisRange {
    /// Validates a range: finite ends, lo < hi, 2 <= n.
    pub fn new(axis: Axis, lo: f64, hi: f64, n: usize) -> Result<Self> {
        crate::error::finite(Param::MapAxisStart, lo)?;
        crate::error::finite(Param::MapAxisEnd, hi)?;
        if lo >= hi {
            return Err(Error::OutOfRange {
                param: Param::MapAxisEnd,
                value: hi,
                range: "(lo, inf)",
            });
        }
        if n < 2 {
            return Err(Error::OutOfRange {
                param: Param::MapAxisPoints,
                value: n as f64,
                range: "[2, 1e8]",
            });
        }
        Ok(Self { axis, lo, hi, n })
    }

    /// The i-th grid value.
    pub fn value(&self, i: usize) -> f64 {
        crate::grid::evenly_spaced_at(self.lo, self.hi, self.n, i)
    }

    /// Grid spacing.
    pub fn step(&self) -> f64 {
        (self.hi - self.lo) / (self.n - 1) as f64
    }
}

/// Points per axis of the sample that estimates a map's stable share.
pub const SHARE_SAMPLES: usize = 8;

/// The share of stable walls on an 8 × 8 sample of a map's window (a, b ranges in the
/// family's units), which sets the map's cost estimate (the Schur–Cohn test,
/// O(n²) each): a stable point costs a full test, an unstable one a small part of it.
pub fn stable_share(fam: &AffineFamily, (a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> f64 {
    let at = |lo: f64, hi: f64, i: usize| crate::grid::evenly_spaced_at(lo, hi, SHARE_SAMPLES, i);
    let mut stable = 0usize;
    for i in 0..SHARE_SAMPLES {
        for j in 0..SHARE_SAMPLES {
            let c = fam.coefficients(at(a0, a1, i), at(b0, b1, j));
            stable += usize::from(crate::stability::schur_stable(&c));
        }
    }
    // one stable point in the sample stands for at least its share of the grid
    (stable as f64 + 0.5) / (SHARE_SAMPLES * SHARE_SAMPLES) as f64
}

/// What a map holds per point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum MapKind {
    /// Stable (true) or not, by the one verdict ([`crate::verdict::decide`]).
    Stability,
    /// The same verdict and the spectral radius from the polished roots, as `check` reports
    /// it ([`Analysis::of_family`]).
    SpectralRadius,
}

/// A map of any loop over its wall, in wall units (a, b) (see [`AffineFamily`]; multiply by
/// `fam.scale` for K in N/m and B in Ns/m), row-major: value (ix, iy) at index iy·nx + ix.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WallMap {
    /// Stiffness axis (wall units a).
    pub x: AxisRange,
    /// Damping axis (wall units b).
    pub y: AxisRange,
    /// Stable flag per point.
    pub stable: Vec<bool>,
    /// Spectral radius per point (only for `MapKind::SpectralRadius`).
    pub radius: Option<Vec<f64>>,
}

impl WallMap {
    /// Stable flag at grid indices.
    pub fn is_stable(&self, ix: usize, iy: usize) -> bool {
        self.stable[iy * self.x.n + ix]
    }
}

/// The grid method of Section V for any loop: the wall's stiffness a along x and damping b
/// along y, one verdict ([`crate::verdict::decide`]) per point, in parallel over rows.
pub fn wall_map(
    fam: &AffineFamily,
    x: AxisRange,
    y: AxisRange,
    kind: MapKind,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<WallMap> {
    if x.n.saturating_mul(y.n) > MAX_POINTS {
        return Err(Error::OutOfRange {
            param: Param::MapPoints,
            value: (x.n as f64) * (y.n as f64),
            range: "[4, 1e8]",
        });
    }
    let (stable, radius) = wall_grid(
        fam,
        (x.n, y.n),
        |ix| x.value(ix),
        |iy| y.value(iy),
        kind,
        progress,
    );
    Ok(WallMap {
        x,
        y,
        stable,
        radius,
    })
}

/// [`wall_map`] over the physical wall: K from `k.0` to `k.1` N/m in `nx` points along x and
/// B from `b.0` to `b.1` Ns/m in `ny` points along y, converted to the family's wall units
/// (the map of `hapstab map --x K:… --y B:…`).
pub fn wall_map_physical(
    fam: &AffineFamily,
    (k, nx): ((f64, f64), usize),
    (b, ny): ((f64, f64), usize),
    kind: MapKind,
    progress: &(dyn Fn(usize) + Sync),
) -> Result<WallMap> {
    let (a_lo, b_lo) = fam.to_units(k.0, b.0);
    let (a_hi, b_hi) = fam.to_units(k.1, b.1);
    let x = AxisRange::new(Axis::Alpha, a_lo, a_hi, nx)?;
    let y = AxisRange::new(Axis::Beta, b_lo, b_hi, ny)?;
    wall_map(fam, x, y, kind, progress)
}

/// Stable flags (and spectral radii) of the walls (a(ix), b(iy)) of a family over an nx × ny
/// grid, one [`wall_point`] per point, in parallel over rows.
fn wall_grid(
    fam: &AffineFamily,
    (nx, ny): (usize, usize),
    a: impl Fn(usize) -> f64 + Sync,
    b: impl Fn(usize) -> f64 + Sync,
    kind: MapKind,
    progress: &(dyn Fn(usize) + Sync),
) -> (Vec<bool>, Option<Vec<f64>>) {
    grid(nx, ny, fam.degree(), kind, progress, |ix, iy, c| {
        wall_point(fam, a(ix), b(iy), kind, c)
    })
}

/// One wall of a map: stable by the one verdict ([`crate::verdict::decide`]) and, for a
/// radius map, the spectral radius of [`Analysis::of_family`] (the same verdict, so the two
/// modes never differ in what they call stable). NaN when the roots cannot be found.
pub(crate) fn wall_point(
    fam: &AffineFamily,
    a: f64,
    b: f64,
    kind: MapKind,
    c: &mut [f64],
) -> (bool, f64) {
    match kind {
        MapKind::Stability => (crate::verdict::stable(fam, a, b, c), f64::NAN),
        MapKind::SpectralRadius => match Analysis::of_family(fam, a, b) {
            Ok(an) => (an.verdict == Verdict::Stable, an.spectral_radius),
            Err(_) => (crate::verdict::stable(fam, a, b, c), f64::NAN),
        },
    }
}

/// Stable flags (and spectral radii) of a map whose points are given by value.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapValues {
    /// Stable flag per point.
    pub stable: Vec<bool>,
    /// Spectral radius per point (only for `MapKind::SpectralRadius`).
    pub radius: Option<Vec<f64>>,
}

fn check_values(param: Param, v: &[f64]) -> Result<()> {
    v.iter()
        .try_for_each(|&x| crate::error::finite(param, x).map(|_| ()))
}

/// The grid method of Section V over axes given by value, not necessarily uniform: the
/// wall's stiffness a[ix] along x and damping b[iy] along y, in wall units, one point test
/// ([`crate::verdict::decide`]) per point, in parallel over rows; row-major, value (ix, iy) at index iy·nx + ix.
/// The same computation as [`wall_map`] at the same values.
pub fn wall_map_values(
    fam: &AffineFamily,
    a: &[f64],
    b: &[f64],
    kind: MapKind,
) -> Result<MapValues> {
    check_values(Param::WallStiffness, a)?;
    check_values(Param::WallDamping, b)?;
    if a.len().saturating_mul(b.len()) > MAX_POINTS {
        return Err(Error::OutOfRange {
            param: Param::MapPoints,
            value: (a.len() as f64) * (b.len() as f64),
            range: "[0, 1e8]",
        });
    }
    let (stable, radius) = wall_grid(
        fam,
        (a.len(), b.len()),
        |ix| a[ix],
        |iy| b[iy],
        kind,
        &|_| {},
    );
    Ok(MapValues { stable, radius })
}

/// Points per parallel task of [`wall_map_points`]: enough Schur–Cohn tests (tens of ns each)
/// to outweigh rayon's task overhead (about a microsecond).
const POINTS_PER_TASK: usize = 1024;

/// Stability (and spectral radius) at the walls (a[i], b[i]), i = 0..n, in wall units, in
/// parallel (Section V's test at scattered points; a and b have the same length).
pub fn wall_map_points(
    fam: &AffineFamily,
    a: &[f64],
    b: &[f64],
    kind: MapKind,
) -> Result<MapValues> {
    if a.len() != b.len() {
        return Err(Error::Invalid {
            param: Param::WallDamping,
            reason: format!(
                "has {} values where the wall stiffness has {}",
                b.len(),
                a.len()
            ),
        });
    }
    check_values(Param::WallStiffness, a)?;
    check_values(Param::WallDamping, b)?;
    let deg = fam.degree();
    let chunks: Vec<(Vec<bool>, Vec<f64>)> = a
        .par_chunks(POINTS_PER_TASK)
        .zip(b.par_chunks(POINTS_PER_TASK))
        .map(|(ac, bc)| {
            let mut c = vec![0.0; deg + 1];
            let mut st = Vec::with_capacity(ac.len());
            let mut rad = Vec::new();
            for (&x, &y) in ac.iter().zip(bc) {
                let (s, r) = wall_point(fam, x, y, kind, &mut c);
                st.push(s);
                if kind == MapKind::SpectralRadius {
                    rad.push(r);
                }
            }
            (st, rad)
        })
        .collect();
    let (stable, radius) = concat(chunks, kind);
    Ok(MapValues { stable, radius })
}

/// Joins per-task results in order.
fn concat(parts: Vec<(Vec<bool>, Vec<f64>)>, kind: MapKind) -> (Vec<bool>, Option<Vec<f64>>) {
    let n = parts.iter().map(|p| p.0.len()).sum();
    let mut stable = Vec::with_capacity(n);
    let mut radius = Vec::with_capacity(if kind == MapKind::SpectralRadius {
        n
    } else {
        0
    });
    for (s, r) in parts {
        stable.extend(s);
        radius.extend(r);
    }
    (stable, (kind == MapKind::SpectralRadius).then_some(radius))
}

/// Stable flags (and spectral radii) over an nx × ny grid, `point` deciding one grid point
/// (given a coefficient buffer), in parallel over rows.
pub(crate) fn grid(
    nx: usize,
    ny: usize,
    deg: usize,
    kind: MapKind,
    progress: &(dyn Fn(usize) + Sync),
    point: impl Fn(usize, usize, &mut [f64]) -> (bool, f64) + Sync,
) -> (Vec<bool>, Option<Vec<f64>>) {
    let done = std::sync::atomic::AtomicUsize::new(0);
    let radius = kind == MapKind::SpectralRadius;
    let rows: Vec<(Vec<bool>, Vec<f64>)> = (0..ny)
        .into_par_iter()
        .map(|iy| {
            let mut c = vec![0.0; deg + 1];
            let mut st = Vec::with_capacity(nx);
            let mut rad = Vec::with_capacity(if radius { nx } else { 0 });
            for ix in 0..nx {
                let (s, r) = point(ix, iy, &mut c);
                st.push(s);
                if radius {
                    rad.push(r);
                }
            }
            let k = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(k);
            (st, rad)
        })
        .collect();
    concat(rows, kind)
}
