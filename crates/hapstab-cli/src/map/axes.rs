//! The `--x`/`--y` axes of `hapstab map`: what they grid, parsed from NAME:LO:HI:N, and their names.

use anyhow::{Result, anyhow, bail};
use hapstab::map::{Axis, AxisRange};

/// What an axis grids.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Name {
    /// A parameter of the paper's normalized loop.
    Normalized(Axis),
    /// The wall stiffness K in N/m.
    K,
    /// The wall damping B in Ns/m.
    B,
}

/// A parsed axis: its name and n points from lo to hi.
#[derive(Debug, Clone, Copy)]
pub(super) struct Grid {
    pub(super) name: Name,
    pub(super) range: AxisRange,
}

pub(super) fn parse_axis(s: &str, flag: &str) -> Result<Grid> {
    let parts: Vec<&str> = s.split(':').collect();
    if parts.len() != 4 {
        bail!("--{flag} must be NAME:LO:HI:N (got '{s}')");
    }
    let name = match parts[0] {
        "K" => Name::K,
        "B" => Name::B,
        other => Name::Normalized(other.parse().map_err(|_| {
            anyhow!("--{flag}: unknown parameter '{other}' (alpha, beta, gamma, delta, K, B)")
        })?),
    };
    let lo: f64 = parts[1]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad lower end '{}'", parts[1]))?;
    let hi: f64 = parts[2]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad upper end '{}'", parts[2]))?;
    let n: usize = parts[3]
        .parse()
        .map_err(|_| anyhow!("--{flag}: bad point count '{}'", parts[3]))?;
    let axis = match name {
        Name::Normalized(a) => a,
        Name::K => Axis::Alpha,
        Name::B => Axis::Beta,
    };
    let range = AxisRange::new(axis, lo, hi, n).map_err(|e| anyhow!("--{flag}: {e}"))?;
    Ok(Grid { name, range })
}

pub(super) fn axis_label(name: Name) -> &'static str {
    match name {
        Name::Normalized(Axis::Alpha) => "alpha",
        Name::Normalized(Axis::Beta) => "beta",
        Name::Normalized(Axis::Gamma) => "gamma",
        Name::Normalized(Axis::Delta) => "delta",
        Name::K => "K",
        Name::B => "B",
    }
}

/// The axis title of a gridded quantity, with units for the physical wall.
pub(super) fn axis_title(name: Name) -> &'static str {
    match name {
        Name::Normalized(Axis::Alpha) => "α",
        Name::Normalized(Axis::Beta) => "β",
        Name::Normalized(Axis::Gamma) => "γ",
        Name::Normalized(Axis::Delta) => "δ",
        Name::K => "K (N/m)",
        Name::B => "B (Ns/m)",
    }
}
