//! The library's region and interval functions for a resolved loop, in the loop's wall units
//! (a, b) (α, β for the paper's loop); callers convert with `AffineFamily::to_physical`.

use anyhow::Result;
use hapstab::boundary::{Interval, stable_alpha_intervals};
use hapstab::params::{Physical, Sampling, Wall};
use hapstab::region::{StableRegion, stable_region};
use hapstab::stability::Analysis;
use hapstab::{AffineFamily, Loop, PlantModel, PolyFamily};

/// The paper's family of a loop that has the normalized view (eq. 9 in (α, β), as every
/// command has always formed it); its (α, β) are the loop family's wall units (a, b).
fn paper_family(lp: &Loop) -> Result<Option<PolyFamily>> {
    lp.paper_view()
        .map(|pp| PolyFamily::new(pp, lp.delay.samples))
        .transpose()
        .map_err(Into::into)
}

/// Stable intervals lo < a < hi of the wall's stiffness at fixed damping b (Section V).
pub fn stable_intervals(lp: &Loop, fam: &AffineFamily, b: f64) -> Result<Vec<Interval>> {
    Ok(match paper_family(lp)? {
        Some(pf) => stable_alpha_intervals(&pf, b),
        None => stable_alpha_intervals(fam, b),
    })
}

/// The stable region in the wall plane (Section V, Figs. 4–6).
pub fn region(lp: &Loop, fam: &AffineFamily) -> Result<StableRegion> {
    Ok(match paper_family(lp)? {
        Some(pf) => stable_region(&pf)?,
        None => stable_region(fam)?,
    })
}

/// The stable interval that contains a, or else the one reaching furthest.
pub fn pick_interval(ivs: &[Interval], a: f64) -> Option<Interval> {
    ivs.iter()
        .find(|iv| iv.lo < a && a < iv.hi)
        .or_else(|| ivs.iter().max_by(|x, y| x.hi.total_cmp(&y.hi)))
        .copied()
}

/// The linear condition (22) K < (b + B)/(t_d + T/2) in N/m, for the paper's loop in
/// physical units (Section VI); None for other loops.
pub fn linear_k(lp: &Loop, wall_damping: f64) -> Option<f64> {
    lp.paper_view()?;
    let PlantModel::MassSpringDamper(e) = &lp.plant.model else {
        return None;
    };
    let wall = Wall {
        stiffness: 0.0,
        damping: wall_damping,
    };
    let sampling = Sampling::new(lp.period, lp.delay.samples).ok()?;
    let p = Physical::new(*e, wall, sampling).ok()?;
    Some(hapstab::linear::linear_stiffness_limit(&p))
}

/// The wall in the family's units (a, b): for the paper's loop the (α, β) of Table I exactly
/// as [`Physical::normalized`] forms them, so that every command reports the same α and β.
pub fn wall_units(lp: &Loop, fam: &AffineFamily, w: Wall) -> Result<(f64, f64)> {
    if let (Some(_), PlantModel::MassSpringDamper(e)) = (lp.paper_view(), &lp.plant.model) {
        let sampling = Sampling::new(lp.period, lp.delay.samples)?;
        let n = Physical::new(*e, w, sampling)?.normalized()?;
        return Ok((n.alpha, n.beta));
    }
    Ok(fam.to_units(w.stiffness, w.damping))
}

/// The full stability answer (verdict, radius, roots) for a wall in the family's units; for
/// the paper's loop through the paper's family, as every other command forms it.
pub fn analysis(lp: &Loop, fam: &AffineFamily, (a, b): (f64, f64)) -> Result<Analysis> {
    Ok(match paper_family(lp)? {
        Some(pf) => Analysis::of_family(&pf, a, b)?,
        None => Analysis::of_family(fam, a, b)?,
    })
}
