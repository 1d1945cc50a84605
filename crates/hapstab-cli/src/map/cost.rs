//! The command-line budget of `hapstab map`: its cost estimated from the degree of p(z) and
//! the stable share of its window, refused beyond the budget.

use anyhow::Result;
use hapstab::AffineFamily;
use hapstab::limits::map_cost_of_degree;

use super::MapArgs;
use super::axes::Grid;
use crate::budget;
use crate::budget::Driver;

/// Refuses a map beyond the command-line budget (a point test is O(n²) in the degree n of
/// p(z), a spectral radius about the cost of its roots, O(n²) per sweep), naming --x, --y or
/// the flag that sets most of the degree.
pub(super) fn check_budget(
    a: &MapArgs,
    (x, y): (Grid, Grid),
    degree: usize,
    stable: f64,
    (what, value): (&str, &str),
) -> Result<()> {
    let points = x.range.n as f64 * y.range.n as f64;
    budget::check(
        map_cost_of_degree(points, degree, a.radius, stable),
        &format!("the map of {points} points"),
        &[
            Driver {
                flag: "--x",
                value: a.x.clone(),
                factor: x.range.n as f64 / 100.0,
            },
            Driver {
                flag: "--y",
                value: a.y.clone(),
                factor: y.range.n as f64 / 100.0,
            },
            Driver {
                flag: what,
                value: value.to_string(),
                factor: (degree.max(3) as f64 / 3.0).powi(2),
            },
        ],
    )
}

/// Points per axis of the sample that estimates a map's stable share.
pub(super) const SHARE_SAMPLES: usize = 8;

/// The share of stable walls on an 8 × 8 sample of the map's window (the Schur–Cohn test,
/// O(n²) each): a stable point costs a full test, an unstable one a small part of it.
pub(super) fn stable_share(fam: &AffineFamily, (a0, a1): (f64, f64), (b0, b1): (f64, f64)) -> f64 {
    let at = |lo: f64, hi: f64, i: usize| lo + (hi - lo) * i as f64 / (SHARE_SAMPLES - 1) as f64;
    let mut stable = 0usize;
    for i in 0..SHARE_SAMPLES {
        for j in 0..SHARE_SAMPLES {
            let c = fam.coefficients(at(a0, a1, i), at(b0, b1, j));
            stable += usize::from(hapstab::stability::schur_stable(&c));
        }
    }
    // one stable point in the sample stands for at least its share of the grid
    (stable as f64 + 0.5) / (SHARE_SAMPLES * SHARE_SAMPLES) as f64
}
