//! The wall of a request in the loop's units, from the page's (α, β); the clicked wall's
//! verdict, margins and passivity are the library's [`hapstab::answer::WallAnswer`].

use hapstab::Wall;

use crate::query::PlantSpec;

/// The wall (a, b) of a request in the loop's units: K in N/m and B in Ns/m (α and β for a
/// normalized loop, where m = T = 1), [`hapstab::AffineFamily::to_physical`].
pub(crate) fn wall_of(spec: &PlantSpec, a: f64, b: f64) -> Wall {
    let (stiffness, damping) = spec.sys.family().to_physical(a, b);
    Wall { stiffness, damping }
}
