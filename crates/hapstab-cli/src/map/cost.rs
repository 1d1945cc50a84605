//! The command-line budget of `hapstab map`: its cost estimated from the degree of p(z) and
//! the stable share of its window, refused beyond the budget.

use anyhow::Result;
use hapstab::limits::{map_cost_of_degree, plants_cost};

use super::MapArgs;
use super::axes::Grid;
use crate::budget;
use crate::budget::Driver;

/// Refuses a map beyond the command-line budget (a point test is O(n²) in the degree n of
/// p(z), a spectral radius about the cost of its roots, O(n²) per sweep, and the family of
/// each of `plants` plants), naming --x, --y or the flag that sets most of the degree.
pub(super) fn check_budget(
    a: &MapArgs,
    (x, y): (Grid, Grid),
    (degree, plants): (usize, usize),
    stable: f64,
    (what, value): (&str, &str),
) -> Result<()> {
    let points = x.range.n as f64 * y.range.n as f64;
    budget::check(
        map_cost_of_degree(points, degree, a.radius, stable).then(plants_cost(plants as f64)),
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
