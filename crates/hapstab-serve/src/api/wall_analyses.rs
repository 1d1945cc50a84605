//! The margins and the passivity of the clicked wall on any loop (`/api/point`), from the
//! library's own analyses: the same numbers as `hapstab check --json` and
//! `hapstab passivity --json` on the same loop and wall.

use hapstab::margins::{Margins, margins_beside_verdict};
use hapstab::passivity::{Passivity, passivity};
use hapstab::{Delay, Effective, Loop, Plant, VelocityEstimator, Wall};

use crate::query::{ApiError, PlantSpec, lib_error};

/// The loop of a request: a general loop as it is; the paper's loop in physical units (the
/// device held by its arm, eq. 1) or in normalized units (m = T = 1, Table I).
pub(crate) fn loop_of(spec: &PlantSpec) -> Result<Loop, ApiError> {
    if let Some(g) = &spec.general {
        return Ok(g.lp().clone());
    }
    let Some(ph) = spec.physical else {
        return Loop::normalized(spec.plant, spec.d).map_err(lib_error);
    };
    let arm = hapstab::Arm {
        mass: ph.arm_mass,
        damping: ph.arm_damping,
        stiffness: ph.arm_stiffness,
    };
    let eff = Effective::new(ph.mass, ph.damping, ph.stiffness).map_err(lib_error)?;
    let mut plant = Plant::mass_spring_damper(eff).map_err(lib_error)?;
    if arm != hapstab::Arm::NONE {
        plant = plant.with_operator(arm).map_err(lib_error)?;
    }
    let delay = Delay::samples(spec.d).map_err(lib_error)?;
    Loop::new(plant, ph.period, delay, VelocityEstimator::Backward).map_err(lib_error)
}

/// The wall (a, b) of a request in the loop's units: K in N/m and B in Ns/m (α and β for a
/// normalized loop, where m = T = 1).
pub(crate) fn wall_of(spec: &PlantSpec, a: f64, b: f64) -> Wall {
    let (stiffness, damping) = match (&spec.general, spec.physical) {
        (Some(g), _) => g.family().to_physical(a, b),
        (None, Some(ph)) => (a * ph.k_per_alpha, b * ph.b_per_beta),
        (None, None) => (a, b),
    };
    Wall { stiffness, damping }
}

/// The margins (withheld beside a verdict that is not stable) and the passivity of the wall
/// (in the loop's units, see [`wall_of`]).
pub(crate) fn wall_analyses(
    spec: &PlantSpec,
    wall: Wall,
    stable: bool,
) -> Result<(Margins, Passivity), ApiError> {
    let lp = loop_of(spec)?;
    let margins = margins_beside_verdict(&lp, wall, stable).map_err(lib_error)?;
    Ok((margins, passivity(&lp, wall).map_err(lib_error)?))
}
