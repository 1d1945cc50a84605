//! `/api/passivity`: the device damping one wall requires to be passive (Colgate–Schenkel;
//! eq. 28 for the paper's loop), whether the device has it, the wall's stability and the
//! device's passive region, on any loop: the library's [`passivity_answer`], the object
//! `hapstab passivity --json` prints (`/api/point` carries the same verdict beside the
//! margins).

use hapstab::Wall;
use hapstab::answer::{PassivityAnswer, passivity_answer};
use hapstab::limits::{core_degree, passivity_cost, roots_cost};

use super::loop_budget;
use super::point::{point_names, wall_at};
use crate::query::{ApiError, Params, PlantSpec, lib_error};

/// Query names of `/api/passivity`: those of `/api/point`.
pub(crate) fn passivity_names() -> Vec<&'static str> {
    point_names()
}

/// A parsed `/api/passivity` request.
pub(crate) struct PassivityReq {
    spec: PlantSpec,
    wall: Wall,
}

/// Reads the loop and the wall of `/api/passivity`: K and B in N/m and Ns/m as given
/// (`wall_stiffness`, `wall_damping`), or α and β (of a normalized loop as they are, of a
/// physical one in the page's units).
pub(crate) fn parse_passivity(p: &Params) -> Result<PassivityReq, ApiError> {
    let spec = crate::query::plant_spec(p)?;
    let wall = wall_at(p, &spec)?.wall;
    Ok(PassivityReq { spec, wall })
}

/// Computes `/api/passivity` within the interactive budget.
pub(crate) fn passivity(req: &PassivityReq) -> Result<PassivityAnswer, ApiError> {
    let sys = &req.spec.sys;
    let fam = sys.family();
    let n = fam.degree();
    let cost = passivity_cost(n, core_degree(fam)).then(roots_cost(n));
    loop_budget(&req.spec, cost, "the passive region")?;
    let normalized = req.spec.physical.is_none();
    passivity_answer(sys, normalized, req.wall)
        .map(|(answer, _)| answer)
        .map_err(lib_error)
}
