//! `/api/zwidth`: the Z-width of a physical loop (Colgate & Brown 1994): its stable and
//! passive (K, B) regions, K_max, the linear condition (22) and a K_max-versus-damping table
//! (`table_damping`: dampings in Ns/m, comma-separated; without it 11 from 0 to the largest
//! stable B): the library's [`ZwidthLoop`], in the object `hapstab zwidth --json` prints.

use hapstab::answer::{ZwidthAnswer, ZwidthInput, ZwidthLoop};
use hapstab::limits::zwidth_cost;
use hapstab::zwidth::DEFAULT_TABLE_ROWS;

use super::{loop_budget, physical_loop};
use crate::limits::MAX_TABLE_DAMPINGS;
use crate::query::{ApiError, Params, PlantSpec, clip, lib_error};

/// Query names of `/api/zwidth`.
pub(crate) fn zwidth_names() -> Vec<&'static str> {
    let mut v: Vec<&str> = crate::query::PLANT_PARAMS.to_vec();
    v.push("table_damping");
    v
}

/// A parsed `/api/zwidth` request.
pub(crate) struct ZwidthReq {
    spec: PlantSpec,
    table_damping: Option<Vec<f64>>,
}

/// The table's dampings: finite numbers of Ns/m, comma-separated.
fn table_damping(p: &Params) -> Result<Option<Vec<f64>>, ApiError> {
    let Some(raw) = p.raw("table_damping") else {
        return Ok(None);
    };
    let bad = |why: String| ApiError::param("table_damping", raw, why);
    let values = raw
        .split(',')
        .map(|t| match t.trim().parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            _ => Err(bad(format!(
                "parameter 'table_damping' must be finite numbers of Ns/m, comma-separated (got '{}')",
                clip(t)
            ))),
        })
        .collect::<Result<Vec<f64>, ApiError>>()?;
    if values.len() > MAX_TABLE_DAMPINGS {
        return Err(bad(format!(
            "parameter 'table_damping' has {} dampings; at most {MAX_TABLE_DAMPINGS} for interactive use",
            values.len()
        )));
    }
    Ok(Some(values))
}

/// Reads the loop and the table's dampings of `/api/zwidth`.
pub(crate) fn parse_zwidth(p: &Params) -> Result<ZwidthReq, ApiError> {
    Ok(ZwidthReq {
        spec: crate::query::plant_spec(p)?,
        table_damping: table_damping(p)?,
    })
}

/// Computes `/api/zwidth` within the interactive budget: one loop, labelled by its velocity
/// estimator as `hapstab zwidth` labels its base loop.
pub(crate) fn zwidth(req: &ZwidthReq) -> Result<ZwidthAnswer, ApiError> {
    let sys = physical_loop(&req.spec, "the Z-width")?;
    let (lp, fam) = (sys.lp(), sys.family());
    let rows = req
        .table_damping
        .as_ref()
        .map_or(DEFAULT_TABLE_ROWS, Vec::len);
    loop_budget(&req.spec, zwidth_cost(fam, rows), "the Z-width")?;
    let one = ZwidthLoop::new(lp.velocity.to_string(), lp, req.table_damping.as_deref())
        .map_err(lib_error)?;
    Ok(ZwidthAnswer {
        input: ZwidthInput {
            compare: Vec::new(),
            table_damping: req.table_damping.clone(),
        },
        loops: vec![one],
    })
}
