//! The margins and the passivity of the clicked wall on any loop (`/api/point`), from the
//! library's own analyses: the same numbers as `hapstab check --json` and
//! `hapstab passivity --json` on the same loop and wall.

use hapstab::Wall;
use hapstab::margins::{Margins, margins_beside_verdict};
use hapstab::passivity::{Passivity, passivity};

use crate::query::{ApiError, PlantSpec, lib_error};

/// The wall (a, b) of a request in the loop's units: K in N/m and B in Ns/m (α and β for a
/// normalized loop, where m = T = 1), [`hapstab::AffineFamily::to_physical`].
pub(crate) fn wall_of(spec: &PlantSpec, a: f64, b: f64) -> Wall {
    let (stiffness, damping) = spec.sys.family().to_physical(a, b);
    Wall { stiffness, damping }
}

/// The margins (withheld beside a verdict that is not stable) and the passivity of the wall
/// (in the loop's units, see [`wall_of`]).
pub(crate) fn wall_analyses(
    spec: &PlantSpec,
    wall: Wall,
    stable: bool,
) -> Result<(Margins, Passivity), ApiError> {
    let lp = spec.sys.lp();
    let margins = margins_beside_verdict(lp, wall, stable).map_err(lib_error)?;
    Ok((margins, passivity(lp, wall).map_err(lib_error)?))
}
